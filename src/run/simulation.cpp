#include "run/simulation.hpp"

#include <cstdlib>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <filesystem>
#include <functional>
#include <sstream>
#include <mutex>
#include <atomic>
#include <cstring>
#include <stdexcept>

#include "dsmc/agg_frag.hpp"
#include "dsmc/collide.hpp"
#include "run/parallel.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/sample.hpp"
#include "dsmc/thermostat.hpp"
#include "io/h5md.hpp"
#include "analysis/sweep_table.hpp"
#include "io/units.hpp"
#include "io/version.hpp"
#include "theory/viscosity.hpp"

namespace gdsmc::simulation {

namespace {

using Clock = std::chrono::steady_clock;

particles::InitialDistribution parse_distribution(const std::string& name) {
  if (name == "shell") return particles::InitialDistribution::shell;
  if (name == "cube") return particles::InitialDistribution::cube;
  return particles::InitialDistribution::maxwell;
}

/// The progress line on stderr: on a terminal one line rewritten in place (at most 5 times a second);
/// otherwise (a log file, a pipe) a full line every 10 s, so that logs are readable, not a stream of
/// carriage returns.
class ProgressLine {
 public:
  ProgressLine(bool enabled, bool terminal) : enabled_(enabled), terminal_(terminal), start_(Clock::now()) {}
  /// Whether a line is due now (so that the caller composes it only then).
  bool due(double fraction_done) const {
    if (!enabled_) return false;
    if (!terminal_ && fraction_done >= 1.0) return false;  // the summary line follows
    if (fraction_done >= 1.0) return true;
    const auto now = Clock::now();
    const auto interval = terminal_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(10000);
    return now - last_ >= interval && (terminal_ || last_ != Clock::time_point{} || now - start_ >= interval);
  }
  void update(double fraction_done, const std::string& what, double events_per_second) {
    if (!due(fraction_done)) return;
    const auto now = Clock::now();
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double eta = fraction_done > 0 ? elapsed * (1.0 - fraction_done) / fraction_done : 0.0;
    if (terminal_) {
      const int width = 30;
      const int filled = static_cast<int>(fraction_done * width);
      std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %s  %.3g coll/s  ETA %.0f s  ", filled,
                   "##############################", width - filled, "", 100.0 * fraction_done, what.c_str(),
                   events_per_second, eta);
    } else {
      std::fprintf(stderr, "granular-dsmc: %5.1f%% done, %s, %.3g coll/s, %.0f s elapsed, ETA %.0f s\n",
                   100.0 * fraction_done, what.c_str(), events_per_second, elapsed, eta);
    }
    std::fflush(stderr);
    printed_ = true;
  }
  void finish() {
    if (enabled_ && terminal_ && printed_) std::fputs("\n", stderr);
  }

 private:
  bool enabled_, terminal_;
  bool printed_ = false;
  Clock::time_point start_, last_{};
};

/// `path` without a trailing ".h5".
std::string without_h5(std::string path) {
  if (path.size() > 3 && path.compare(path.size() - 3, 3, ".h5") == 0) path.resize(path.size() - 3);
  return path;
}

}  // namespace

std::string checkpoint_path(const std::string& output_path, int rank) {
  const std::string stem = without_h5(output_path) + ".checkpoint";
  return rank == 0 ? stem + ".h5" : stem + ".rank" + std::to_string(rank) + ".h5";
}

namespace {

/// Rank k's file of the checkpoint whose rank-0 file is `path`.
std::string rank_file(const std::string& path, int rank) {
  return rank == 0 ? path : without_h5(path) + ".rank" + std::to_string(rank) + ".h5";
}

/// Mixtures with more species than this record neither `collisions_pair` (S(S+1)/2 columns) nor
/// the per-species velocity histograms.
constexpr std::size_t kMaxPairSpecies = collide::pair_event_limit;

/// What one point (all its replicas) measured.
struct PointResult {
  std::map<std::string, sample::Accumulator> observables;
  double mean_step = 0.0;
  std::uint64_t events = 0;
  double collide_seconds = 0.0;
};

/// What one replica of one point measured: per observable, its column count and its rows (one per
/// sample, or one for the reduced_* observables), appended in order.
struct ReplicaResult {
  std::map<std::string, std::pair<std::size_t, std::vector<double>>> rows;
  double mean_step = 0.0;
  std::uint64_t events = 0;
  double collide_seconds = 0.0;

  void add(const std::string& name, std::size_t columns, const std::vector<double>& row) {
    auto& entry = rows[name];
    entry.first = columns;
    entry.second.insert(entry.second.end(), row.begin(), row.end());
  }
};

// Byte serialisation of ReplicaResult, to send it between MPI ranks (same machine type: raw bytes).
template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <class T>
T take(const std::string& in, std::size_t& pos) {
  if (pos + sizeof(T) > in.size()) throw std::runtime_error("corrupt replica result from another rank");
  T value;
  std::memcpy(&value, in.data() + pos, sizeof(T));
  pos += sizeof(T);
  return value;
}

void pack(std::string& out, std::uint64_t unit, const ReplicaResult& r) {
  put(out, unit);
  put(out, r.mean_step);
  put(out, r.events);
  put(out, r.collide_seconds);
  put(out, static_cast<std::uint64_t>(r.rows.size()));
  for (const auto& [name, entry] : r.rows) {
    put(out, static_cast<std::uint64_t>(name.size()));
    out += name;
    put(out, static_cast<std::uint64_t>(entry.first));
    put(out, static_cast<std::uint64_t>(entry.second.size()));
    out.append(reinterpret_cast<const char*>(entry.second.data()), entry.second.size() * sizeof(double));
  }
}

ReplicaResult unpack(const std::string& in, std::size_t& pos, std::uint64_t& unit) {
  ReplicaResult r;
  unit = take<std::uint64_t>(in, pos);
  r.mean_step = take<double>(in, pos);
  r.events = take<std::uint64_t>(in, pos);
  r.collide_seconds = take<double>(in, pos);
  const auto n = take<std::uint64_t>(in, pos);
  for (std::uint64_t k = 0; k < n; ++k) {
    const auto length = take<std::uint64_t>(in, pos);
    if (pos + length > in.size()) throw std::runtime_error("corrupt replica result from another rank");
    std::string name = in.substr(pos, length);
    pos += length;
    auto& entry = r.rows[name];
    entry.first = take<std::uint64_t>(in, pos);
    const auto count = take<std::uint64_t>(in, pos);
    if (pos + count * sizeof(double) > in.size()) throw std::runtime_error("corrupt replica result from another rank");
    entry.second.resize(count);
    std::memcpy(entry.second.data(), in.data() + pos, count * sizeof(double));
    pos += count * sizeof(double);
  }
  return r;
}

/// Progress over all units of this rank (replicas of every sweep point), shared by its threads: one
/// line for the whole run with the fraction of the work done (the mean of the units' fractions), the
/// replicas and sweep points finished, the collision rate since the start and the ETA. A unit's
/// `where` label is not shown (with several threads the line would jump between units); the simulated
/// time is, when the run is a single unit. Every update is O(1) (sums kept, not recomputed), and the
/// line's text is composed only when one is due. Under MPI the line (rank 0's) counts rank 0's units.
class Progress {
 public:
  /// `point_of` gives the sweep point of each unit (slot) of this rank; `points` their number.
  Progress(bool enabled, bool terminal, std::vector<std::size_t> point_of, std::size_t points)
      : line_(enabled, terminal), partial_(point_of.size(), 0.0), point_of_(std::move(point_of)), open_(points, 0) {
    for (std::size_t p : point_of_) ++open_[p];
    for (std::size_t n : open_) points_ += n > 0 ? 1 : 0;
  }
  void update(std::size_t slot, double fraction, const std::string& /*where*/, double time, std::uint64_t new_events) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double before = partial_[slot];
    partial_[slot] = fraction;
    sum_ += fraction - before;
    if (before < 1.0 && fraction >= 1.0) {
      ++units_done_;
      if (--open_[point_of_[slot]] == 0) ++points_done_;
    }
    events_ += new_events;
    const double done = std::min(sum_ / static_cast<double>(partial_.size()), units_done_ == partial_.size() ? 1.0 : 0.999);
    if (!line_.due(done)) return;
    std::string what = std::to_string(units_done_) + "/" + std::to_string(partial_.size()) + " replicas";
    if (points_ > 1) what += ", " + std::to_string(points_done_) + "/" + std::to_string(points_) + " sweep points";
    if (partial_.size() == 1) {
      char t[48];
      std::snprintf(t, sizeof t, ", t = %.4g", time);
      what += t;
    }
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    line_.update(done, what, elapsed > 0 ? static_cast<double>(events_) / elapsed : 0.0);
  }
  void finish() { line_.finish(); }

 private:
  std::mutex mutex_;
  ProgressLine line_;
  std::vector<double> partial_;
  std::vector<std::size_t> point_of_;
  std::vector<std::size_t> open_;  ///< units of each point not finished
  std::size_t points_ = 0, points_done_ = 0, units_done_ = 0;
  double sum_ = 0.0;  ///< sum of partial_
  std::uint64_t events_ = 0;
  Clock::time_point start_ = Clock::now();
};

/// One unit's state in a checkpoint file: named arrays of reals and of exact integers.
struct Snapshot {
  std::map<std::string, std::vector<double>> reals;
  std::map<std::string, std::vector<std::uint64_t>> integers;
};

void store_result(Snapshot& snap, const ReplicaResult& r) {
  for (const auto& [name, entry] : r.rows) {
    snap.reals["result/rows/" + name] = entry.second;
    snap.integers["result/columns/" + name] = {entry.first};
  }
  snap.reals["result/scalars"] = {r.mean_step, r.collide_seconds};
  snap.integers["result/events"] = {r.events};
}

ReplicaResult load_result(const Snapshot& snap) {
  ReplicaResult r;
  const std::string rows = "result/rows/";
  for (const auto& [name, values] : snap.reals)
    if (name.rfind(rows, 0) == 0) {
      const std::string observable = name.substr(rows.size());
      r.rows[observable] = {snap.integers.at("result/columns/" + observable).at(0), values};
    }
  r.mean_step = snap.reals.at("result/scalars").at(0);
  r.collide_seconds = snap.reals.at("result/scalars").at(1);
  r.events = snap.integers.at("result/events").at(0);
  return r;
}

/// Where a replica is between two collision chunks: with the particles and the collider, all a
/// checkpoint needs to continue it exactly.
struct ReplicaProgress {
  std::uint64_t next_sample = 0;
  bool in_sample = false;  ///< the current sample's msd start handling is done, its chunks are running
  bool tracking = false;
  double msd_start = 0.0;
  std::vector<double> speed_counts, c_sum, share_sum;
  double scaling_samples = 0.0, t_first = 0.0, t_last = 0.0, temp_first = 0.0, temp_last = 0.0;
};

/// A sample of the scaling state (past `&output scaling_start` collisions per particle) added to this
/// replica's sums of c_k and T_k/T. A checkpoint of an older version without the sums (their size not
/// s) leaves them alone: the replica then reports no scaling state.
void add_scaling_sample(ReplicaProgress& p, const sample::Moments& m, double time) {
  const std::size_t s = m.sonine_c.size();
  if (p.c_sum.size() != s || p.share_sum.size() != s) return;
  for (std::size_t k = 0; k < s; ++k) {
    p.c_sum[k] += m.sonine_c[k];
    p.share_sum[k] += m.temperature[k] / m.total_temperature;
  }
  if (p.scaling_samples == 0.0) {
    p.t_first = time;
    p.temp_first = m.total_temperature;
  }
  p.t_last = time;
  p.temp_last = m.total_temperature;
  p.scaling_samples += 1.0;
}

/// This replica's averages of c_k and T_k/T over its scaling-state samples ("scaling_sonine_c",
/// "scaling_temperature_share"): one value per replica, so that their standard error over the replicas
/// is that of the time average itself, whatever the correlation between samples (written as
/// /scaling_state, docs/output.md).
void add_scaling_averages(ReplicaResult& result, const ReplicaProgress& p) {
  if (p.scaling_samples < 1.0) return;
  std::vector<double> c = p.c_sum, share = p.share_sum;
  for (auto& x : c) x /= p.scaling_samples;
  for (auto& x : share) x /= p.scaling_samples;
  result.add("scaling_sonine_c", c.size(), c);
  result.add("scaling_temperature_share", share.size(), share);
}

Snapshot make_snapshot(const particles::System& sys, const collide::Collider& collider, const ReplicaProgress& p,
                       const ReplicaResult& partial) {
  Snapshot snap;
  store_result(snap, partial);
  // Every array a particle carries (particles.hpp System::for_each_array), as its doubles in order.
  sys.for_each_array([&](const char* name, const auto& a) {
    std::string key = "particles/";  // (not "particles/" + name: a false -Warray-bounds of GCC 12)
    key += name;
    auto& out = snap.reals[key];
    out.resize(a.size() * (sizeof(a[0]) / sizeof(double)));
    std::memcpy(out.data(), a.data(), out.size() * sizeof(double));
  });
  snap.integers["particles/species"].assign(sys.species.begin(), sys.species.end());
  const collide::Collider::State c = collider.state();
  snap.reals["collider/clock"] = {c.time, c.credit, c.next_step_time, c.counters.step_sum, c.generator.spare,
                                 c.counters.dissipated};
  snap.reals["collider/max_speed"] = c.max_speed;
  snap.reals["collider/max_speed2"] = c.max_speed2;
  snap.integers["collider/counters"] = {c.counters.events, c.counters.candidates, c.counters.steps,
                                        c.pending_next, c.pending_filled, c.generator.has_spare,
                                        c.counters.overshoots};
  snap.integers["collider/pair_events"] = c.counters.pair_events;
  snap.integers["collider/generator"] = {c.generator.s[0], c.generator.s[1], c.generator.s[2], c.generator.s[3]};
  snap.integers["collider/pending"].assign(c.pending.begin(), c.pending.end());
  snap.reals["collider/block_max_speed2"] = c.block_max_speed2;
  snap.reals["collider/block_credit"] = c.block_credit;
  if (!c.slice_counts.empty()) snap.integers["collider/slice_counts"] = c.slice_counts;
  snap.reals["collider/block_step_start"] = {c.step_start, c.step_acceptance};
  snap.integers["collider/block_mode"] = {c.whole_step, c.step_events_start, c.step_candidates_start,
                                          static_cast<std::uint64_t>(c.block_lowrank)};
  snap.reals["collider/transfer"].assign(c.counters.transfer.begin(), c.counters.transfer.end());
  snap.reals["collider/frame"] = {c.framed ? 1.0 : 0.0, c.frame_scale, c.frame_shear,
                                  c.moments[0],         c.moments[1],  c.moments[2], c.moments[3]};
  snap.integers["progress/flags"] = {p.next_sample, p.in_sample, p.tracking};
  snap.reals["progress/values"] = {p.msd_start, p.scaling_samples, p.t_first, p.t_last, p.temp_first, p.temp_last};
  snap.reals["progress/speed_counts"] = p.speed_counts;
  snap.reals["progress/c_sum"] = p.c_sum;
  snap.reals["progress/share_sum"] = p.share_sum;
  return snap;
}

/// Restores what make_snapshot saved into a System made for the same point (same counts).
/// A checkpoint is read, not trusted: every array it restores must be finite and consistent with the
/// input, or the restart stops with this message (a damaged file must not crash or run on NaN).
void require_intact(bool condition, const std::string& what) {
  if (!condition) throw std::runtime_error("the checkpoint is damaged: " + what);
}
bool all_finite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}

void load_snapshot(const Snapshot& snap, particles::System& sys, collide::Collider& collider, ReplicaProgress& p,
                   ReplicaResult& partial) {
  partial = load_result(snap);
  const auto& v = snap.reals.at("particles/velocity");
  const auto& species = snap.integers.at("particles/species");
  if (v.size() != 3 * sys.size() || species.size() != sys.size())
    throw std::runtime_error("the checkpoint's particle count does not match the input");
  require_intact(all_finite(v), "a velocity is not finite");
  for (std::size_t i = 0; i < sys.size(); ++i)  // the species layout is fixed by the input's counts
    require_intact(species[i] == sys.species[i], "particle " + std::to_string(i) + " has species " +
                                                     std::to_string(species[i]) + ", the input gives " +
                                                     std::to_string(sys.species[i]));
  for (const auto& [name, values] : snap.reals)
    require_intact(all_finite(values), "'" + name + "' holds a value that is not finite");
  {
    const auto& pending = snap.integers.at("collider/pending");
    for (std::size_t q = 0; q < pending.size(); ++q)
      require_intact(pending[q] < (q % 4 < 2 ? sys.size() : sys.n_species()),
                     "a drawn-ahead candidate names a particle or species that does not exist");
  }
  for (std::size_t i = 0; i < sys.size(); ++i) sys.species[i] = static_cast<std::uint32_t>(species[i]);
  // Tracking may have started during the run: the displacements then exist from there on.
  if (snap.reals.count("particles/displacement") && !sys.tracks_displacements()) sys.r.resize(sys.size());
  sys.for_each_array([&](const char* name, auto& a) {
    std::string key = "particles/";
    key += name;
    const auto it = snap.reals.find(key);
    require_intact(it != snap.reals.end(), std::string("the particles' array '") + name + "' is missing");
    require_intact(it->second.size() == a.size() * (sizeof(a[0]) / sizeof(double)),
                   std::string("the particles' array '") + name + "' has the wrong length");
    std::memcpy(a.data(), it->second.data(), it->second.size() * sizeof(double));
  });
  collide::Collider::State c;
  const auto& clock = snap.reals.at("collider/clock");
  const auto& counters = snap.integers.at("collider/counters");
  const auto& generator = snap.integers.at("collider/generator");
  c.time = clock.at(0);
  c.credit = clock.at(1);
  c.next_step_time = clock.at(2);
  c.counters.step_sum = clock.at(3);
  c.generator.spare = clock.at(4);
  c.counters.dissipated = clock.at(5);
  c.max_speed = snap.reals.at("collider/max_speed");
  c.max_speed2 = snap.reals.at("collider/max_speed2");
  c.counters.events = counters.at(0);
  c.counters.candidates = counters.at(1);
  c.counters.steps = counters.at(2);
  c.pending_next = counters.at(3);
  c.pending_filled = counters.at(4) != 0;
  c.generator.has_spare = counters.at(5) != 0;
  if (counters.size() > 6) c.counters.overshoots = counters.at(6);
  c.counters.pair_events = snap.integers.at("collider/pair_events");
  for (int k = 0; k < 4; ++k) c.generator.s[k] = generator.at(k);
  const auto& pending = snap.integers.at("collider/pending");
  c.pending.assign(pending.begin(), pending.end());
  c.block_max_speed2 = snap.reals.at("collider/block_max_speed2");
  c.block_credit = snap.reals.at("collider/block_credit");
  if (const auto it = snap.integers.find("collider/slice_counts"); it != snap.integers.end())
    c.slice_counts.assign(it->second.begin(), it->second.end());
  {
    const auto& start = snap.reals.at("collider/block_step_start");
    c.step_start = start.at(0);
    if (start.size() > 1) c.step_acceptance = start.at(1);
    if (const auto it = snap.integers.find("collider/block_mode"); it != snap.integers.end() && it->second.size() >= 3) {
      c.whole_step = it->second[0] != 0;
      c.step_events_start = it->second[1];
      c.step_candidates_start = it->second[2];
      // (the step's block sampler; a checkpoint of an older version has none: chosen again on restore)
      if (it->second.size() > 3) c.block_lowrank = it->second[3] != 0 ? 1 : 0;
    }
  }
  const auto& transfer = snap.reals.at("collider/transfer");
  for (std::size_t q = 0; q < 6; ++q) c.counters.transfer[q] = transfer.at(q);
  if (const auto it = snap.reals.find("collider/frame"); it != snap.reals.end()) {
    const auto& f = it->second;
    require_intact(f.size() == 7 && f[1] > 0.0, "the velocity frame is damaged");
    c.framed = f[0] != 0.0;
    c.frame_scale = f[1];
    c.frame_shear = f[2];
    for (std::size_t q = 0; q < 4; ++q) c.moments[q] = f[3 + q];
  }
  collider.restore(c);
  const auto& flags = snap.integers.at("progress/flags");
  const auto& values = snap.reals.at("progress/values");
  p.next_sample = flags.at(0);
  p.in_sample = flags.at(1) != 0;
  p.tracking = flags.at(2) != 0;
  p.msd_start = values.at(0);
  p.scaling_samples = values.at(1);
  p.t_first = values.at(2);
  p.t_last = values.at(3);
  p.temp_first = values.at(4);
  p.temp_last = values.at(5);
  p.speed_counts = snap.reals.at("progress/speed_counts");
  p.c_sum = snap.reals.at("progress/c_sum");
  p.share_sum = snap.reals.at("progress/share_sum");
}

/// Called between collision chunks and after each sample with a way to snapshot the replica.
using SafePoint = std::function<void(const std::function<Snapshot()>&)>;

// ---------------------------------------------------------------------------------------------
// Aggregation and fragmentation (&agg_frag): the cluster gas of agg_frag.hpp in a loop of its own
// ---------------------------------------------------------------------------------------------

/// The monomer of &system and the thresholds of &agg_frag (\ref af_outcome "docs/agg-frag.md").
agg_frag::Model agg_frag_model(const io::config::Config& c) {
  agg_frag::Model m;
  m.monomer_mass = c.system.mass[0];
  m.monomer_diameter = c.system.diameter[0];
  m.monomer_density = c.system.number_density[0];
  m.restitution = c.system.restitution(0, 0);
  m.aggregation_energy = c.agg_frag.aggregation_energy.value_or(0.0);
  m.fragmentation_energy = c.agg_frag.fragmentation_energy.value_or(std::numeric_limits<double>::infinity());
  m.fragment_restitution = c.agg_frag.fragment_restitution.value_or(1.0);
  return m;
}

Snapshot make_agg_frag_snapshot(const agg_frag::Gas& gas, std::uint64_t next_sample, const ReplicaResult& partial) {
  Snapshot snap;
  store_result(snap, partial);
  const agg_frag::Gas::State s = gas.state();
  snap.reals["clusters/velocity"] = s.velocity;
  snap.integers["clusters/count"] = s.count;
  snap.reals["clusters/max_speed"] = s.max_speed;
  snap.reals["clusters/clock"] = {s.time, s.credit, s.next_step_time, s.counters.step_sum, s.counters.dissipated,
                                  s.generator.spare};
  snap.integers["clusters/counters"] = {s.counters.events, s.counters.aggregations, s.counters.fragmentations,
                                        s.counters.candidates, s.counters.steps, s.capacity,
                                        s.largest_reached, s.generator.has_spare, next_sample};
  snap.integers["clusters/generator"] = {s.generator.s[0], s.generator.s[1], s.generator.s[2], s.generator.s[3]};
  return snap;
}

std::uint64_t load_agg_frag_snapshot(const Snapshot& snap, agg_frag::Gas& gas, ReplicaResult& partial) {
  partial = load_result(snap);
  for (const auto& [name, values] : snap.reals)
    require_intact(all_finite(values), "'" + name + "' holds a value that is not finite");
  agg_frag::Gas::State s;
  s.velocity = snap.reals.at("clusters/velocity");
  s.count = snap.integers.at("clusters/count");
  s.max_speed = snap.reals.at("clusters/max_speed");
  const auto& clock = snap.reals.at("clusters/clock");
  const auto& counters = snap.integers.at("clusters/counters");
  const auto& generator = snap.integers.at("clusters/generator");
  s.time = clock.at(0);
  s.credit = clock.at(1);
  s.next_step_time = clock.at(2);
  s.counters.step_sum = clock.at(3);
  s.counters.dissipated = clock.at(4);
  s.generator.spare = clock.at(5);
  s.counters.events = counters.at(0);
  s.counters.aggregations = counters.at(1);
  s.counters.fragmentations = counters.at(2);
  s.counters.candidates = counters.at(3);
  s.counters.steps = counters.at(4);
  s.capacity = counters.at(5);
  s.largest_reached = counters.at(6);
  s.generator.has_spare = counters.at(7) != 0;
  for (int k = 0; k < 4; ++k) s.generator.s[k] = generator.at(k);
  gas.restore(s);
  return counters.at(8);
}

/// The per-size observables of the cluster gas: one row per sample, each as wide as the largest
/// size present then ("name@sample"), until the replica ends and pads them to one width.
constexpr const char* kSizeObservables[] = {"number", "size_energy"};

/// "name@i": the row of sample i of a per-size observable.
std::string sample_row(const char* name, std::size_t i) {
  std::string key(name);
  key += '@';
  key += std::to_string(i);
  return key;
}

void pad_size_rows(ReplicaResult& result, std::size_t n_samples) {
  for (const char* name : kSizeObservables) {
    std::size_t width = 1;
    for (std::size_t i = 0; i < n_samples; ++i) width = std::max(width, result.rows[sample_row(name, i)].first);
    std::vector<double> rows(n_samples * width, 0.0);
    for (std::size_t i = 0; i < n_samples; ++i) {
      const auto key = sample_row(name, i);
      const auto& row = result.rows[key].second;
      std::copy(row.begin(), row.end(), rows.begin() + static_cast<std::ptrdiff_t>(i * width));
      result.rows.erase(key);
    }
    result.rows[name] = {width, std::move(rows)};
  }
}

/// Pads the per-size rows of all replicas of a point to the largest size any of them reached.
void pad_size_columns(std::vector<ReplicaResult>& replicas) {
  for (const char* name : kSizeObservables) {
    std::size_t width = 0;
    for (auto& r : replicas) width = std::max(width, r.rows[name].first);
    for (auto& r : replicas) {
      auto& [columns, values] = r.rows[name];
      if (columns == width) continue;
      const std::size_t n = values.size() / columns;
      std::vector<double> wide(n * width, 0.0);
      for (std::size_t i = 0; i < n; ++i)
        std::copy(values.begin() + static_cast<std::ptrdiff_t>(i * columns),
                  values.begin() + static_cast<std::ptrdiff_t>((i + 1) * columns),
                  wide.begin() + static_cast<std::ptrdiff_t>(i * width));
      columns = width;
      values = std::move(wide);
    }
  }
}

/// Replica r of an &agg_frag run: from N_0 monomers, sampled at the Config's sample points (times,
/// or collisions per initial monomer 2 x events / N_0).
ReplicaResult run_agg_frag_replica(const io::config::Config& config, const Options& options, Progress& progress,
                                   std::size_t slot, const std::string& label, std::size_t r, const Snapshot* resume,
                                   const SafePoint& safe_point, int block_threads) {
  const auto n0 = static_cast<std::size_t>(config.dsmc.n_particles);
  const double initial_monomers = static_cast<double>(n0);
  const auto seed = static_cast<std::uint64_t>(config.dsmc.seed);
  const bool time_driven = config.dsmc.t_end.has_value();
  const std::vector<double> targets = time_driven ? config.sample_times() : config.sample_collisions();
  const std::size_t n_samples = targets.size();
  agg_frag::Gas gas(agg_frag_model(config), n0, config.initial.temperature[0],
                    parse_distribution(config.initial.distribution), rng::make_stream(seed, r, rng::Purpose::initial_state),
                    rng::make_stream(seed, r, rng::Purpose::collisions), config.dsmc.step_fraction);
  // Cache blocks (agg_frag.hpp, "Cache blocks"): while N >= 2 block_size clusters, on block_threads.
  gas.use_blocks(static_cast<std::size_t>(config.dsmc.block_size), block_threads);
  ReplicaResult result;
  std::uint64_t next_sample = 0;
  if (resume) next_sample = load_agg_frag_snapshot(*resume, gas, result);
  const double final_events = time_driven ? 0.0 : std::ceil(targets.back() * initial_monomers / 2.0);
  auto fraction_done = [&] {
    const double f = time_driven ? gas.time() / targets.back()
                                 : static_cast<double>(gas.counters().events) / std::max(1.0, final_events);
    return std::min(f, 0.999);
  };
  std::uint64_t reported_events = gas.counters().events;
  auto report = [&](double fraction) {
    const std::uint64_t events = gas.counters().events;
    progress.update(slot, fraction, label, gas.time(), events - reported_events);
    reported_events = events;
  };
  const std::function<Snapshot()> snapshot = [&] { return make_agg_frag_snapshot(gas, next_sample, result); };

  for (; next_sample < n_samples; ++next_sample, safe_point(snapshot)) {
    const std::size_t i = next_sample;
    if (options.interrupt && options.interrupt->load()) throw Interrupted();
    const auto t0 = Clock::now();
    const double t_target = time_driven ? targets[i] : std::numeric_limits<double>::infinity();
    const std::uint64_t event_target =
        time_driven ? std::numeric_limits<std::uint64_t>::max()
                    : static_cast<std::uint64_t>(std::ceil(targets[i] * initial_monomers / 2.0));
    // Chunks of events, as in run_replica: interrupts, progress and checkpoints at fixed events.
    constexpr std::uint64_t kChunk = 1u << 19;
    for (;;) {
      const std::uint64_t done = gas.counters().events;
      // With blocks a chunk is one blocked step (at most 2^23 candidates, its own event margin).
      const bool blocked = gas.blocks() > 1;
      const std::uint64_t chunk_end = blocked || event_target - done <= kChunk ? event_target : done + kChunk;
      // ... and at most ~1e5 candidates (chunk_end_time); one cluster left or nothing moving: the
      // gas's advance() goes straight to the target.
      const bool still = gas.clusters() < 2 || !(gas.candidate_rate() > 0.0);
      const double t_stop = still     ? t_target
                            : blocked ? std::min(t_target, gas.block_step_end())
                                      : chunk_end_time(gas.time(), gas.counters().candidates, t_target);
      gas.advance(t_stop, chunk_end);
      if (gas.time() >= t_target || gas.counters().events >= event_target) break;
      if (options.interrupt && options.interrupt->load()) throw Interrupted();
      report(fraction_done());
      safe_point(snapshot);
    }
    if (!time_driven && gas.counters().events < event_target)
      throw std::runtime_error("the gas aggregated into one cluster at t = " + std::to_string(gas.time()) +
                               " before collisions_per_particle = " + std::to_string(targets[i]) +
                               " was reached; give t_end instead");
    result.collide_seconds += std::chrono::duration<double>(Clock::now() - t0).count();

    const agg_frag::Measurement m = gas.measure();
    const auto& counters = gas.counters();
    result.add(sample_row("number", i), m.number.size(), m.number);
    result.add(sample_row("size_energy", i), m.energy.size(), m.energy);
    result.add("total_temperature", 1, {2.0 / 3.0 * m.kinetic_energy / m.clusters});  // per cluster, \ref af_observables "docs/agg-frag.md"
    result.add("kinetic_energy", 1, {m.kinetic_energy / initial_monomers});
    result.add("mean_size", 1, {initial_monomers / m.clusters});
    result.add("monomer_fraction", 1, {m.number[0] / initial_monomers});
    result.add("collisions", 1, {static_cast<double>(counters.events)});
    result.add("aggregations", 1, {static_cast<double>(counters.aggregations)});
    result.add("fragmentations", 1, {static_cast<double>(counters.fragmentations)});
    result.add("dissipated_energy", 1, {counters.dissipated / initial_monomers});
    result.add("collisions_per_particle", 1, {2.0 * static_cast<double>(counters.events) / initial_monomers});
    result.add("time", 1, {gas.time()});
    report(i + 1 == n_samples ? 1.0 : fraction_done());
  }
  pad_size_rows(result, n_samples);
  result.events = gas.counters().events;
  result.mean_step = gas.mean_step();
  return result;
}

// ---------------------------------------------------------------------------------------------
// Thermostat and uniform shear flow (&thermostat, &shear): stages of streaming, collisions and
// thermostat (thermostat.hpp, \ref eta_thermostat "docs/shear-viscosity.md")
// ---------------------------------------------------------------------------------------------

/// Whether a staged run uses cache blocks (frames in blocks, collide.hpp "Frame"): `majorant` or
/// `lowrank` (not `pairs`, which the Enskog gas in shear flow needs), N >= 2 block_size.
bool staged_blocks(const io::config::Config& config) {
  return config.dsmc.scheme != "pairs" && config.dsmc.block_size > 0 &&
         config.dsmc.n_particles >= 2 * config.dsmc.block_size;
}

/// Replica r of a run with a thermostat or a shear rate. Each stage of length dt: streaming
/// V_x -> V_x - a V_y dt; at a sample time the measurement (after the streaming, before the
/// collisions: \ref eta_thermostat "docs/shear-viscosity.md"); the collisions of [t, t + dt] in continuous time (collide.hpp, no cache
/// blocks: the stages are far shorter than a blocked step); the Gaussian thermostat. The stages end
/// at every sample time.
ReplicaResult run_staged_replica(const io::config::Config& config, const Options& options, Progress& progress,
                                 std::size_t slot, const std::string& label, std::size_t r, const Snapshot* resume,
                                 const SafePoint& safe_point, int block_threads) {
  const species::Mixture mix = config.mixture();
  const std::size_t s = mix.size();
  const auto counts = species::particle_counts(static_cast<std::size_t>(config.dsmc.n_particles), mix);
  const auto seed = static_cast<std::uint64_t>(config.dsmc.seed);
  const std::vector<double> targets = config.sample_times();
  const std::size_t n_samples = targets.size();
  const double t_end = targets.back();
  const double shear = config.shear.rate.value_or(0.0);
  const bool gaussian = config.thermostat.kind == "gaussian";
  const double average_from = config.shear.average_from.value_or(0.5 * t_end);
  const double n = mix.total_density();

  auto init_stream = rng::make_stream(seed, r, rng::Purpose::initial_state);
  particles::System sys = particles::make_system(mix, counts, config.initial.temperature,
                                                 parse_distribution(config.initial.distribution), init_stream);
  thermostat::remove_mean_flow(mix, sys);  // the centre-of-mass velocity sum m V / sum m (\ref eta_thermostat "docs/shear-viscosity.md")
  collide::Collider collider(collide::parse_scheme(config.dsmc.scheme), mix, sys,
                             rng::make_stream(seed, r, rng::Purpose::collisions), config.dsmc.step_fraction);
  ReplicaResult result;
  ReplicaProgress p;
  p.c_sum.assign(s, 0.0);
  p.share_sum.assign(s, 0.0);
  // Enskog in shear flow: the shifted relative velocity and the collisional transfer (collide.hpp).
  const bool enskog_shear = shear > 0.0 && mix.enskog;
  if (enskog_shear) collider.set_shear(shear);
  // Cache blocks with `majorant` (collide.hpp, "Frame": frames in blocks); a pass over the blocks per
  // stage, on block_threads.
  if (staged_blocks(config)) {
    collider.use_blocks(static_cast<std::size_t>(config.dsmc.block_size));
    collider.use_threads(block_threads);
  }
  // Stage accumulators: zeta dt since the last sample, the viscosity's window sums, stage count.
  double zeta_sum = 0.0, zeta_stages = 0.0, window_sum = 0.0, window_samples = 0.0, stages = 0.0;
  double window_kinetic_sum = 0.0, last_sample_time = 0.0;
  std::array<double, 6> last_transfer{};  // Counters::transfer at the previous sample
  thermostat::Rescaling pending;  // decided at the end of a stage, applied at the start of the next
  // The stored velocities are u in a frame, V = G u + b (thermostat.hpp, "Cost: the frame"): the frame
  // (G in the collider, the offset b here), and the momentum sum m u of the stored u and the total mass.
  thermostat::Frame frame;
  particles::Vec3 momentum{0.0, 0.0, 0.0};
  double total_mass = 0.0;
  for (std::size_t k = 0; k < s; ++k) total_mass += mix.mass[k] * static_cast<double>(counts[k]);
  if (resume) {
    load_snapshot(*resume, sys, collider, p, result);
    const auto& v = resume->reals.at("staged/values");
    zeta_sum = v.at(0), zeta_stages = v.at(1), window_sum = v.at(2), window_samples = v.at(3), stages = v.at(4);
    pending.scale = v.at(5);
    pending.mean_flow = {v.at(6), v.at(7), v.at(8)};
    window_kinetic_sum = v.at(9), last_sample_time = v.at(10);
    for (std::size_t q = 0; q < 6; ++q) last_transfer[q] = v.at(11 + q);
    if (v.size() >= 23) {
      frame.offset = {v.at(17), v.at(18), v.at(19)};
      momentum = {v.at(20), v.at(21), v.at(22)};
    }
    frame.scale = collider.frame_scale();
    frame.shear = collider.frame_shear();
  } else {
    collider.velocities_changed();  // the bounds (and the majorant rate that sizes the stages) from the start
  }
  const std::function<Snapshot()> snapshot = [&] {
    Snapshot snap = make_snapshot(sys, collider, p, result);
    snap.reals["staged/values"] = {zeta_sum,        zeta_stages,         window_sum,          window_samples, stages,
                                   pending.scale, pending.mean_flow.x, pending.mean_flow.y, pending.mean_flow.z,
                                   window_kinetic_sum, last_sample_time};
    auto& values = snap.reals["staged/values"];
    values.insert(values.end(), last_transfer.begin(), last_transfer.end());
    values.insert(values.end(), {frame.offset.x, frame.offset.y, frame.offset.z, momentum.x, momentum.y, momentum.z});
    return snap;
  };
  std::uint64_t reported_events = collider.counters().events;

  // The sample of this instant: after the streaming of the stage that starts now.
  auto measure = [&](std::size_t i, double dt) {
    const sample::Moments m = sample::measure(mix, sys);
    const auto& counters = collider.counters();
    result.add("temperature", s, m.temperature);
    result.add("total_temperature", 1, {m.total_temperature});
    result.add("sonine_c", s, m.sonine_c);
    result.add("number", s, m.number);
    result.add("collisions", 1, {static_cast<double>(counters.events)});
    // The kernel's invariant (collide.hpp Counters::overshoots): 0 in a correct run.
    result.add("acceptance_overshoots", 1, {static_cast<double>(counters.overshoots)});
    const double per_particle = 2.0 * static_cast<double>(counters.events) / static_cast<double>(sys.size());
    result.add("collisions_per_particle", 1, {per_particle});
    result.add("time", 1, {collider.time()});
    if (i > 0 && per_particle >= config.output.scaling_start) add_scaling_sample(p, m, collider.time());
    // P at the middle of this stage's streaming jump (thermostat.hpp, "Sampling point"): the value
    // before the jump follows exactly from the one after it (V_x before = V_x + a dt V_y), and the
    // mean of the two is second order in the stage length.
    auto kinetic = sample::kinetic_pressure_tensor(mix, sys, m);
    {
      const double h = shear * dt;  // xx, yy, zz, xy, xz, yz
      const std::array<double, 6> before{kinetic[0] + 2.0 * h * kinetic[3] + h * h * kinetic[1], kinetic[1],
                                         kinetic[2], kinetic[3] + h * kinetic[1], kinetic[4] + h * kinetic[5],
                                         kinetic[5]};
      for (std::size_t c = 0; c < 6; ++c) kinetic[c] = 0.5 * (kinetic[c] + before[c]);
    }
    const std::vector<double> pk(kinetic.begin(), kinetic.end());
    // Collisional transfer since the previous sample (\ref eta_pressure "docs/shear-viscosity.md"): P^c = sum m sigma (1 + alpha)(g.e) e e
    // / (V dt), V = N/n the simulated volume; 0 in the dilute gas.
    std::vector<double> pc(6, 0.0);
    const double now = collider.time();
    if (enskog_shear && now > last_sample_time) {
      const auto& transfer = collider.counters().transfer;
      const double volume = static_cast<double>(sys.size()) / n;
      for (std::size_t q = 0; q < 6; ++q) pc[q] = (transfer[q] - last_transfer[q]) / (volume * (now - last_sample_time));
      last_transfer = transfer;
    }
    last_sample_time = now;
    std::vector<double> total(6);
    for (std::size_t q = 0; q < 6; ++q) total[q] = pk[q] + pc[q];
    result.add("pressure_tensor_kinetic", 6, pk);
    result.add("pressure_tensor_collisional", 6, pc);
    result.add("pressure_tensor", 6, total);
    const double zeta_dt = zeta_stages > 0.0 ? zeta_sum / zeta_stages : 0.0;
    result.add("thermostat_zeta_dt", 1, {zeta_dt});
    zeta_sum = zeta_stages = 0.0;
    if (shear > 0.0) {
      const double viscosity = -total[3] / shear;  // eta = -P_xy/a, P_xy at the middle of the jump
      result.add("shear_viscosity_raw", 1, {viscosity});
      {
        // eta/eta_0(T) with the finite-shear-rate correction of \ref eta_measured "docs/shear-viscosity.md", 1 - (a* eta*)^2,
        // a* = a/nu_0(T), nu_0 = n T/eta_0; eta_0 of one species (\ref eta_one_species "docs/shear-viscosity.md"), or of the elastic
        // mixture at the same T (Chapman and Cowling's first approximation; theory/viscosity.hpp).
        const double eta0 = s == 1 ? theory::viscosity::elastic_viscosity(mix.mass[0], mix.diameter[0],
                                                                           m.total_temperature)
                                   : theory::viscosity::elastic_mixture_viscosity(mix, m.total_temperature);
        const double reduced_rate = shear * eta0 / (n * m.total_temperature);
        const double corrected = viscosity / eta0;
        double eta = corrected;
        for (int it = 0; it < 20; ++it) eta = corrected / (1.0 - reduced_rate * reduced_rate * eta * eta);
        const double kinetic_part = eta * kinetic[3] / total[3];  // the same correction for each part
        result.add("reduced_shear_rate", 1, {reduced_rate});
        result.add("shear_viscosity", 1, {eta});
        if (enskog_shear) result.add("shear_viscosity_kinetic", 1, {kinetic_part});
        if (collider.time() >= average_from * (1.0 - 1e-12) && i > 0) {
          window_sum += eta;
          window_kinetic_sum += kinetic_part;
          window_samples += 1.0;
        }
      }
    }
  };

  const double stage_cap = shear > 0.0 ? 0.01 / shear : std::numeric_limits<double>::infinity();
  // One stage from the collider's time to `end` (or, for the last sample, only its streaming and
  // measurement): streaming, the sample, collisions, thermostat.
  auto stage = [&](double end, bool sample_here, bool last) {
    const double dt = end - collider.time();
    // The previous stage's thermostat rescaling and this stage's streaming, applied to the frame
    // (thermostat.hpp, "Cost: the frame").
    frame = thermostat::advance_frame(frame, pending.scale, pending.mean_flow, shear, dt);
    pending = thermostat::Rescaling{};
    thermostat::Energy start;
    if (sample_here || !collider.framed() || std::abs(frame.shear) > thermostat::frame_shear_limit ||
        frame.scale < 0.5 || frame.scale > 2.0) {
      // One pass: V = G u + b for every particle, the energy, the moments and the largest speeds
      // (the collider's bounds, exact again); the frame is the identity afterwards.
      const thermostat::StageStart pass = thermostat::materialise(mix, sys, frame);
      frame = thermostat::Frame{};
      momentum = {pass.mean_flow.x * total_mass, pass.mean_flow.y * total_mass, pass.mean_flow.z * total_mass};
      collider.reset_frame(pass.moments, pass.max_speed2);
      start = {pass.kinetic, pass.mean_flow};
    } else {
      collider.set_frame(frame.scale, frame.shear);
      start = thermostat::frame_energy(collider.frame_moments(), momentum, total_mass, frame);
    }
    if (sample_here) measure(p.next_sample, dt);
    if (last) return;
    const double dissipated_before = collider.counters().dissipated;
    collider.advance(end);
    if (gaussian) {
      // The dilute collisions change the energy only by their inelastic loss and keep the mean flow,
      // so the thermostat needs no pass over the particles here (thermostat.hpp).
      const double loss = collider.counters().dissipated - dissipated_before;
      if (enskog_shear) {
        // The Enskog collisions in shear flow also do viscous work, which the thermostat must not
        // remove (\ref eta_thermostat "docs/shear-viscosity.md"): only the inelastic loss is restored, s^2 = (E_after + L)/E_after.
        const double after = thermostat::frame_energy(collider.frame_moments(), momentum, total_mass, frame).kinetic;
        pending = {std::sqrt((after + loss) / after), start.mean_flow, loss / start.kinetic};
      } else {
        pending = thermostat::gaussian_rescaling(start.kinetic, loss, start.mean_flow);
      }
      zeta_sum += pending.zeta_dt;
      zeta_stages += 1.0;
    }
    stages += 1.0;
    if (options.interrupt && options.interrupt->load()) throw Interrupted();
    const std::uint64_t events = collider.counters().events;
    progress.update(slot, std::min(collider.time() / t_end, 0.999), label, collider.time(), events - reported_events);
    reported_events = events;
  };
  // The end of a stage of the default length from now, not beyond `limit` (then exactly `limit`).
  auto stage_end = [&](double limit) {
    const double free_time = static_cast<double>(sys.size()) / (2.0 * collider.candidate_rate());
    const double end = collider.time() + std::min(config.dsmc.stage_step * free_time, stage_cap);
    return end < limit ? end : limit;
  };
  for (; p.next_sample < n_samples; ++p.next_sample, safe_point(snapshot)) {
    const std::size_t i = p.next_sample;
    if (options.interrupt && options.interrupt->load()) throw Interrupted();
    const auto t0 = Clock::now();
    while (collider.time() < targets[i]) {  // stages up to the sample time, which the last one hits exactly
      stage(stage_end(targets[i]), false, false);
      safe_point(snapshot);
    }
    const bool last = i + 1 == n_samples;
    // The stage that samples (the last one: only its streaming, of the length the next would have).
    stage(last ? stage_end(std::numeric_limits<double>::infinity()) : stage_end(targets[i + 1]), true, last);
    result.collide_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
  }
  progress.update(slot, 1.0, label, collider.time(), 0);
  result.events = collider.counters().events;
  result.mean_step = collider.time() > 0.0 && stages > 0.0 ? collider.time() / stages : 0.0;
  add_scaling_averages(result, p);
  if (shear > 0.0 && window_samples > 0.0) {
    result.add("shear_viscosity_average", 1, {window_sum / window_samples});
    if (enskog_shear) result.add("shear_viscosity_kinetic_average", 1, {window_kinetic_sum / window_samples});
  }
  return result;
}

}  // namespace

double chunk_end_time(double time, std::uint64_t candidates, double t_target, double chunk) {
  if (candidates == 0 || !(time > 0.0)) return t_target;
  const double end = time + chunk * time / static_cast<double>(candidates);
  return end < t_target ? end : t_target;
}

namespace {

/// Runs replica r of one Config, from the start or from `resume`. `slot` is its place in this
/// rank's progress; `label` names it. `block_threads`: the threads its cache blocks may use
/// (collide.hpp, "Threads inside one replica"; the results do not depend on it).
ReplicaResult run_replica(const io::config::Config& config, const Options& options, Progress& progress,
                          std::size_t slot, const std::string& label, std::size_t r, const Snapshot* resume,
                          const SafePoint& safe_point, int block_threads) {
  // Threads given to a replica's cache blocks that this run cannot use: said once, not left idle silently.
  const auto note_idle_threads = [&](const std::string& why) {
    if (block_threads > 1 && slot == 0 && options.progress)
      std::fprintf(stderr,
                   "granular-dsmc: note: %d of the %d threads per work unit stay idle: %s; threads serve "
                   "replicas and sweep points first, then cache blocks (docs/schemes.md)\n",
                   block_threads - 1, block_threads, why.c_str());
  };
  if (config.has_agg_frag) {
    if (config.dsmc.block_size == 0 || config.dsmc.n_particles < 2 * config.dsmc.block_size)
      note_idle_threads("this aggregation run has no cache blocks (they need N >= 2 block_size clusters)");
    return run_agg_frag_replica(config, options, progress, slot, label, r, resume, safe_point, block_threads);
  }
  if (config.staged()) {
    if (!staged_blocks(config))
      note_idle_threads("a thermostat or shear flow has cache blocks only with 'majorant' or 'lowrank' (the "
                        "Enskog gas in shear flow needs 'pairs') and N >= 2 block_size");
    return run_staged_replica(config, options, progress, slot, label, r, resume, safe_point, block_threads);
  }
  const species::Mixture mix = config.mixture();
  const std::size_t s = mix.size();
  const auto counts = species::particle_counts(static_cast<std::size_t>(config.dsmc.n_particles), mix);
  std::size_t n_total = 0;
  for (auto c : counts) n_total += c;
  const auto seed = static_cast<std::uint64_t>(config.dsmc.seed);
  const auto scheme = collide::parse_scheme(config.dsmc.scheme);
  const auto bins = static_cast<std::size_t>(config.output.histogram_bins);
  const double range = config.output.histogram_range;
  const bool time_driven = config.dsmc.t_end.has_value();
  const std::vector<double> targets = time_driven ? config.sample_times() : config.sample_collisions();
  const std::size_t n_samples = targets.size();
  const std::size_t n_pairs = s * (s + 1) / 2;
  const auto viscoelastic_beta = config.viscoelastic_beta();
  const bool reduced = s <= 2;  // v0 and Phi_i(v*) are defined for one or two species (Montanero and Garzo 2002, \ref son_reduced_distributions "docs/sonine.md")
  const auto reduced_bins = static_cast<std::size_t>(config.output.reduced_bins);
  const double reduced_range = config.output.reduced_range;

  ReplicaResult result;
  // Share of this replica done: the simulated time over t_end, or the events over the last target.
  const double final_events = time_driven ? 0.0 : std::ceil(targets.back() * static_cast<double>(n_total) / 2.0);
  auto fraction_done = [&](const collide::Collider& c) {
    const double f = time_driven ? c.time() / targets.back()
                                 : static_cast<double>(c.counters().events) / std::max(1.0, final_events);
    return std::min(f, 1.0);
  };

  auto init_stream = rng::make_stream(seed, r, rng::Purpose::initial_state);
  particles::System sys = particles::make_system(mix, counts, config.initial.temperature,
                                                 parse_distribution(config.initial.distribution), init_stream);
  collide::Collider collider(scheme, mix, sys, rng::make_stream(seed, r, rng::Purpose::collisions),
                             config.dsmc.step_fraction, viscoelastic_beta ? &*viscoelastic_beta : nullptr);
  // Displacements (Bodrova and Osinsky 2024, eq. (15), \ref dif_displacements "docs/diffusion-msd.md") from t = 0, from msd_start_time, or from the first sample
  // with T <= msd_start_temperature. The HCS part: samples past scaling_start collisions per particle.
  const bool track = config.output.track_displacements;
  // Cache blocks (collide.hpp "Blocks"; one species, majorant or lowrank): in collision-driven runs
  // the steps near each sample's event target run on the whole gas and stop at it exactly.
  collider.use_blocks(static_cast<std::size_t>(config.dsmc.block_size));
  collider.use_threads(block_threads);
  if (collider.blocks() == 1)
    note_idle_threads("this run has no cache blocks (they need 'majorant' or 'lowrank', at most 128 species and "
                      "N >= 2 block_size)");
  ReplicaProgress p;
  p.c_sum.assign(s, 0.0);
  p.share_sum.assign(s, 0.0);
  if (resume) {
    load_snapshot(*resume, sys, collider, p, result);
  } else if (track && !config.output.msd_start_time && !config.output.msd_start_temperature) {
    particles::start_tracking(sys, 0.0);
    p.tracking = true;
  }
  std::uint64_t reported_events = collider.counters().events;
  auto report = [&](double fraction) {
    const std::uint64_t events = collider.counters().events;
    progress.update(slot, fraction, label, collider.time(), events - reported_events);
    reported_events = events;
  };
  const std::function<Snapshot()> snapshot = [&] { return make_snapshot(sys, collider, p, result); };
  // The end of the next advance() towards `target` (chunk_end_time): ~1e5 candidates, or one time
  // step's candidates when that is more (N/2 step_fraction), at most 2^24 (about a second of work).
  // With cache blocks a chunk also ends at the end of a blocked step (the collider's `to_step_end`), and
  // is at most 2^24 candidates at the rate of the last step (not the run's mean rate, which a cooling
  // gas leaves far behind): a blocked step of up to 3/4 of that (collide.hpp "Blocks", "Step length")
  // is then not split, since a chunk end within a step costs a second visit of every block, and Ctrl-C
  // is noticed within 2^24 candidates (0.25-0.5 s).
  // A gas at rest (no candidates: the collider jumps to its target) goes straight there; with blocks
  // the collider does that itself.
  const bool blocked = collider.blocks() > 1;
  const double step_candidates = 0.5 * static_cast<double>(n_total) * config.dsmc.step_fraction;
  const double chunk = blocked ? 16777216.0 : std::clamp(step_candidates, chunk_candidates, 16777216.0);
  const auto chunk_stop = [&](double target) {
    const bool still =
        collider.blocks() == 1 && collider.counters().steps > 0 && !(collider.candidate_rate() > 0.0);
    if (still) return target;
    if (const double rate = collider.recent_candidate_rate(); blocked && rate > 0.0)
      return std::min(target, collider.time() + chunk / rate);
    return chunk_end_time(collider.time(), collider.counters().candidates, target, chunk);
  };

  for (; p.next_sample < n_samples; ++p.next_sample, p.in_sample = false, safe_point(snapshot)) {
    const std::size_t i = p.next_sample;
    if (options.interrupt && options.interrupt->load()) throw Interrupted();
    const auto t0 = Clock::now();
    // Advance in chunks so that the progress line, an interrupt and checkpoints are seen at least
    // every ~1e6 collisions and every ~1e5 candidates (chunk_end_time). The chunks end at the same
    // events and times in every run, wherever and however often it is stopped and resumed, so the
    // trajectory is the same bit for bit.
    const double t_target = time_driven ? targets[i] : std::numeric_limits<double>::infinity();
    // 2 x events / N reaches the target (\ref output_observables "docs/output.md": collisions_per_particle)
    const std::uint64_t event_target =
        time_driven ? std::numeric_limits<std::uint64_t>::max()
                    : static_cast<std::uint64_t>(std::ceil(targets[i] * static_cast<double>(n_total) / 2.0));
    if (!p.in_sample && track && !p.tracking && config.output.msd_start_time &&
        *config.output.msd_start_time <= t_target) {
      const double start = *config.output.msd_start_time;  // stop exactly at the start
      while (collider.time() < start && collider.counters().events < event_target) {
        collider.advance(chunk_stop(start), event_target, true, UINT64_MAX, blocked);
        if (options.interrupt && options.interrupt->load()) throw Interrupted();
      }
      if (collider.time() >= *config.output.msd_start_time) {
        particles::start_tracking(sys, collider.time());
        p.tracking = true;
        p.msd_start = collider.time();
      }
    }
    p.in_sample = true;
    constexpr std::uint64_t kChunk = 1u << 20;
    for (;;) {
      const std::uint64_t done = collider.counters().events;
      const std::uint64_t chunk_end = event_target - done > kChunk ? done + kChunk : event_target;
      // The sample's own target is exact; a chunk's end is soft (blocks may pass it, collide.hpp).
      // ... and at most ~1e5 candidates; the sample's target is never passed, even by a soft chunk's step.
      collider.advance(chunk_stop(t_target), chunk_end, chunk_end == event_target, event_target, blocked);
      if (collider.time() >= t_target || collider.counters().events >= event_target) break;
      if (options.interrupt && options.interrupt->load()) throw Interrupted();
      report(std::min(fraction_done(collider), 0.999));
      safe_point(snapshot);
    }
    result.collide_seconds += std::chrono::duration<double>(Clock::now() - t0).count();

    const sample::Moments m = sample::measure(mix, sys);
    const auto& counters = collider.counters();
    result.add("temperature", s, m.temperature);
    result.add("total_temperature", 1, {m.total_temperature});
    result.add("sonine_c", s, m.sonine_c);
    result.add("number", s, m.number);
    result.add("collisions", 1, {static_cast<double>(counters.events)});
    // The kernel's invariant (collide.hpp Counters::overshoots): 0 in a correct run.
    result.add("acceptance_overshoots", 1, {static_cast<double>(counters.overshoots)});
    result.add("collisions_per_particle", 1,
               {2.0 * static_cast<double>(counters.events) / static_cast<double>(n_total)});
    if (s <= kMaxPairSpecies) {  // S(S+1)/2 columns: only for mixtures of a few species
      std::vector<double> pairs;
      pairs.reserve(n_pairs);
      for (std::size_t k = 0; k < s; ++k)
        for (std::size_t j = k; j < s; ++j) pairs.push_back(static_cast<double>(counters.pair_events[k * s + j]));
      result.add("collisions_pair", n_pairs, pairs);
    }
    result.add("time", 1, {collider.time()});
    if (s <= kMaxPairSpecies)  // one histogram per species: only for a few species
      result.add("velocity_histogram", s * bins, sample::velocity_histogram(mix, sys, m, bins, range));
    if (track && !p.tracking && config.output.msd_start_temperature &&
        m.total_temperature <= *config.output.msd_start_temperature) {
      particles::start_tracking(sys, collider.time());
      p.tracking = true;
      p.msd_start = collider.time();
    }
    if (track)
      result.add("msd", s,
                 p.tracking ? sample::mean_squared_displacement(sys, collider.time()) : std::vector<double>(s, 0.0));
    const double per_particle = 2.0 * static_cast<double>(counters.events) / static_cast<double>(n_total);
    if (i > 0 && per_particle >= config.output.scaling_start) {
      if (reduced)
        sample::add_reduced_speeds(mix, sys, m, sample::reduced_velocity_scale(mix, m.total_temperature),
                                   reduced_bins, reduced_range, p.speed_counts);
      add_scaling_sample(p, m, collider.time());
    }
    report(i + 1 == n_samples ? 1.0 : std::min(fraction_done(collider), 0.999));
  }
  result.events = collider.counters().events;
  result.mean_step = collider.mean_step();
  if (track) result.add("msd_start", 1, {p.tracking ? p.msd_start : -1.0});
  add_scaling_averages(result, p);
  if (reduced && p.scaling_samples >= 2.0 && p.t_last > p.t_first) {
    result.add("reduced_distribution", s * reduced_bins,
               sample::reduced_distribution(p.speed_counts, std::vector<double>(counts.begin(), counts.end()),
                                            p.scaling_samples, reduced_bins, reduced_range));
    std::vector<double> c = p.c_sum, share = p.share_sum;
    for (auto& x : c) x /= p.scaling_samples;
    for (auto& x : share) x /= p.scaling_samples;
    result.add("reduced_sonine_c", s, c);
    result.add("reduced_temperature_share", s, share);
    // zeta* = zeta/(n sigma_12^2 v0) with zeta = 2 sqrt(T) d(T^-1/2)/dt, constant in the HCS
    // (\ref haff_law "docs/haff-and-mixtures.md", \ref son_scaling "docs/sonine.md"): zeta* = 2 slope / (n sigma_12^2 sqrt(2 (m1 + m2)/(m1 m2))).
    const double slope = (1.0 / std::sqrt(p.temp_last) - 1.0 / std::sqrt(p.temp_first)) / (p.t_last - p.t_first);
    const double sigma12 = mix.contact_distance(0, s - 1);
    const double v0_unit = sample::reduced_velocity_scale(mix, 1.0);
    result.add("reduced_cooling_rate", 1, {2.0 * slope / (mix.total_density() * sigma12 * sigma12 * v0_unit)});
  }
  return result;
}

}  // namespace

std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t bytes) {
  // FNV-1a, 64 bits (Fowler, Noll and Vo; offset basis 14695981039346656037, prime 1099511628211).
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
  return hash;
}

namespace {

/// The checksum of a checkpoint: FNV-1a over every attribute and dataset name and content, in the
/// order written (written last, checked first on restore, so that any damage is reported as such).
class ContentHash {
 public:
  void add(const std::string& text) {
    const std::uint64_t size = text.size();
    hash_ = fnv1a(fnv1a(hash_, &size, sizeof size), text.data(), text.size());
  }
  template <class T>
  void add(const std::vector<T>& values) {
    const std::uint64_t size = values.size();
    hash_ = fnv1a(fnv1a(hash_, &size, sizeof size), values.data(), values.size() * sizeof(T));
  }
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash_));
    return text;
  }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;
};

/// The checkpoint file of this rank (\ref output_checkpoint "docs/output.md"): the results of its finished units and the
/// latest snapshot of each unit in progress, rewritten whole (temporary file + rename, io::h5md).
/// Each unit in progress refreshes its own snapshot (and rewrites the file) when that snapshot is
/// `every` seconds old, so every thread's unit is saved, not only the first to reach a safe point.
class CheckpointStore {
 public:
  CheckpointStore(std::string path, double every, std::string fingerprint, int ranks, std::size_t units)
      : path_(std::move(path)), every_(every), fingerprint_(std::move(fingerprint)), ranks_(ranks),
        last_saved_(units, Clock::now()) {}

  /// Reads a checkpoint written by this store's write(); checks that it is intact (its checksum)
  /// and that it belongs to this input.
  void load(const std::string& file) {
    namespace h5 = io::h5md;
    std::map<std::size_t, Snapshot> done, running;
    ContentHash hash;
    std::string fingerprint, stored_checksum;
    double ranks = 0.0;
    try {
      stored_checksum = h5::read_string_attribute(file, "/checkpoint", "checksum");
      for (const char* kind : {"done", "running"}) {
        const std::string listed = h5::read_string_attribute(file, "/checkpoint", std::string(kind) + "_units");
        hash.add(listed);
        std::istringstream units(listed);
        for (std::size_t u; units >> u;) {
          const std::string group = "/checkpoint/" + std::string(kind) + "/unit_" + std::to_string(u);
          Snapshot snap;
          const std::string real_names = h5::read_string_attribute(file, group, "reals");
          const std::string integer_names = h5::read_string_attribute(file, group, "integers");
          hash.add(real_names);
          hash.add(integer_names);
          std::istringstream reals(real_names);
          for (std::string name; std::getline(reals, name);)
            if (!name.empty()) hash.add(snap.reals[name] = h5::read_dataset(file, group + "/" + name).data);
          std::istringstream integers(integer_names);
          for (std::string name; std::getline(integers, name);)
            if (!name.empty()) hash.add(snap.integers[name] = h5::read_integers(file, group + "/" + name));
          (std::string(kind) == "done" ? done : running)[u] = std::move(snap);
        }
      }
      fingerprint = h5::read_string_attribute(file, "/checkpoint", "fingerprint");
      hash.add(fingerprint);
      ranks = h5::read_double_attribute(file, "/checkpoint", "ranks");
      hash.add(std::vector<double>{ranks});
    } catch (const std::exception& e) {
      throw std::runtime_error("checkpoint '" + file + "' is damaged or is not a checkpoint of granular-dsmc: " +
                               e.what());
    }
    if (hash.hex() != stored_checksum)
      throw std::runtime_error("checkpoint '" + file + "' is damaged: its content does not match the checksum "
                               "written with it (a partial copy, or a disk error)");
    if (fingerprint != fingerprint_)
      throw std::runtime_error("checkpoint '" + file +
                               "' was written for a different input (namelist text, --set or --output differ)");
    if (static_cast<int>(ranks) != ranks_)
      throw std::runtime_error("checkpoint '" + file + "' was written by a run with a different number of MPI ranks");
    for (auto& [u, snap] : done) done_[u] = load_result(snap);
    running_ = std::move(running);
  }
  const ReplicaResult* finished_result(std::size_t unit) const {
    const auto it = done_.find(unit);
    return it == done_.end() ? nullptr : &it->second;
  }
  const Snapshot* resume_point(std::size_t unit) const {
    const auto it = running_.find(unit);
    return it == running_.end() ? nullptr : &it->second;
  }

  void finished(std::size_t unit, const ReplicaResult& result) {
    if (every_ <= 0.0) return;
    std::lock_guard<std::mutex> lock(mutex_);
    done_[unit] = result;
    running_.erase(unit);
  }
  void safe_point(std::size_t unit, const std::function<Snapshot()>& snapshot) {
    // last_saved_[unit] is touched only by the thread running that unit.
    if (every_ <= 0.0 || std::chrono::duration<double>(Clock::now() - last_saved_[unit]).count() < every_) return;
    Snapshot fresh = snapshot();  // outside the lock: other threads keep running
    std::lock_guard<std::mutex> lock(mutex_);
    running_[unit] = std::move(fresh);
    write();
    last_saved_[unit] = Clock::now();
  }
  void remove() const {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }

 private:
  void write() const {
    io::h5md::Writer w(path_, "granular-dsmc", "granular-dsmc checkpoint", io::build_version());
    std::string done_units, running_units;
    for (const auto& [u, result] : done_) done_units += std::to_string(u) + " ";
    for (const auto& [u, snap] : running_) running_units += std::to_string(u) + " ";
    // The checksum covers the content in the order load() reads it (ContentHash).
    ContentHash hash;
    auto put_unit = [&](const std::string& group, const Snapshot& snap) {
      std::string reals, integers;
      for (const auto& [name, values] : snap.reals) reals += name + "\n";
      for (const auto& [name, values] : snap.integers) integers += name + "\n";
      hash.add(reals);
      hash.add(integers);
      for (const auto& [name, values] : snap.reals) {
        w.write_dataset(group + "/" + name, values, {});
        hash.add(values);
      }
      for (const auto& [name, values] : snap.integers) {
        w.write_integers(group + "/" + name, values);
        hash.add(values);
      }
      w.write_attribute(group, "reals", reals);
      w.write_attribute(group, "integers", integers);
    };
    hash.add(done_units);
    for (const auto& [u, result] : done_) {
      Snapshot snap;
      store_result(snap, result);
      put_unit("/checkpoint/done/unit_" + std::to_string(u), snap);
    }
    hash.add(running_units);
    for (const auto& [u, snap] : running_) put_unit("/checkpoint/running/unit_" + std::to_string(u), snap);
    hash.add(fingerprint_);
    hash.add(std::vector<double>{static_cast<double>(ranks_)});
    w.write_attribute("/checkpoint", "checksum", hash.hex());
    w.write_dataset("/checkpoint/format", {1.0}, {});
    w.write_attribute("/checkpoint", "fingerprint", fingerprint_);
    w.write_attribute("/checkpoint", "ranks", static_cast<double>(ranks_));
    w.write_attribute("/checkpoint", "done_units", done_units);
    w.write_attribute("/checkpoint", "running_units", running_units);
    w.write_attribute("/checkpoint", "description",
                      std::string("granular-dsmc checkpoint: finished work units (point-major replica index) "
                                  "and the state of those in progress; resume with granular-dsmc FILE.nml "
                                  "--restart THIS_FILE"));
    w.commit();
  }

  std::string path_;
  double every_;
  std::string fingerprint_;
  int ranks_;
  std::mutex mutex_;
  std::map<std::size_t, ReplicaResult> done_;
  std::map<std::size_t, Snapshot> running_;
  std::vector<Clock::time_point> last_saved_;  ///< per unit
};

/// The replica results of one point, reduced in replica order (the same order in every run).
PointResult reduce_point(std::vector<ReplicaResult>& replicas) {
  PointResult point;
  double mean_step_sum = 0.0;
  for (std::size_t r = 0; r < replicas.size(); ++r) {
    for (auto& [name, entry] : replicas[r].rows) {
      auto& a = point.observables[name];
      a.columns = entry.first;
      // Rows of the reduced_* observables exist only for the replicas that reached the scaling
      // regime: each such replica adds one row, in replica order.
      a.values.push_back(std::move(entry.second));
    }
    mean_step_sum += replicas[r].mean_step;
    point.events += replicas[r].events;
    point.collide_seconds += replicas[r].collide_seconds;
  }
  point.mean_step = mean_step_sum / static_cast<double>(replicas.size());
  return point;
}

/// The HCS distributions of one point (Montanero and Garzo 2002, sec. 4, \ref son_reduced_distributions "docs/sonine.md"): Phi_i(v*), the deviation Delta_i(v*) of
/// eq 27 with the measured c_i and lambda_i = T/(T_i mu_ji), and G_i(v*) = exp(2 beta_i v*/zeta*) Phi_i
/// of eq 30 with beta_i of eq 20 and the measured reduced cooling rate zeta*.
void write_reduced(io::h5md::Writer& writer, const std::string& root, const io::config::Config& config,
                   PointResult& result) {
  auto& acc = result.observables;
  const auto mix = config.mixture();
  const std::size_t s = mix.size();
  const auto bins = static_cast<std::size_t>(config.output.reduced_bins);
  const double range = config.output.reduced_range, width = range / static_cast<double>(bins);
  const auto phi = acc["reduced_distribution"].mean();
  const auto phi_error = acc["reduced_distribution"].standard_error();
  const auto c = acc["reduced_sonine_c"].mean();
  const auto share = acc["reduced_temperature_share"].mean();
  const double zeta = acc["reduced_cooling_rate"].mean()[0];
  const auto zeta_error = acc["reduced_cooling_rate"].standard_error();
  const std::string group = root + "/reduced_distribution";
  std::vector<double> edges(bins + 1);
  for (std::size_t b = 0; b <= bins; ++b) edges[b] = width * static_cast<double>(b);
  writer.write_dataset(group + "/bin_edges", edges, {bins + 1});
  writer.write_unit(group + "/bin_edges", io::units::kDimensionless);  // v* = |v - u|/v0
  const double sigma12 = mix.contact_distance(0, s - 1);
  for (std::size_t k = 0; k < s; ++k) {
    const std::size_t j = s - 1 - k;  // the other species (itself for one species)
    const double mu_jk = mix.mass[j] / (mix.mass[k] + mix.mass[j]);
    const double lambda = 1.0 / (share[k] * mu_jk);  // lambda_i = T/(T_i mu_ji), \ref son_binary "docs/sonine.md"
    double beta = 0.0;  // Montanero and Garzo 2002, eq. (20), \ref son_tails "docs/sonine.md"
    for (std::size_t l = 0; l < s; ++l) {
      const double ratio = mix.contact_distance(k, l) / sigma12;
      beta += M_PI * mix.mole_fraction(l) * mix.pair_correlation(k, l) * ratio * ratio;
    }
    std::vector<double> value(bins), error(bins), delta(bins), delta_error(bins), g(bins), g_error(bins);
    for (std::size_t b = 0; b < bins; ++b) {
      value[b] = phi[k * bins + b];
      error[b] = phi_error.empty() ? 0.0 : phi_error[k * bins + b];
      const double maxwell = sample::maxwellian_shell_average(lambda, edges[b], edges[b + 1]);
      // eq 27; far out the Maxwellian underflows to 0 and Delta is undefined: written as 0 there
      // (never NaN), and Phi itself, always finite, is the quantity to read in the far tail.
      const bool defined = maxwell > 0.0 && c[k] != 0.0;
      delta[b] = defined ? 2.0 / c[k] * (value[b] / maxwell - 1.0) : 0.0;
      delta_error[b] = defined ? 2.0 / std::abs(c[k]) * error[b] / maxwell : 0.0;
      const double weight = std::exp(2.0 * beta * 0.5 * (edges[b] + edges[b + 1]) / zeta);  // eq 30
      g[b] = weight * value[b];
      g_error[b] = weight * error[b];
    }
    const std::string sp = group + "/species_" + std::to_string(k + 1);
    writer.write_dataset(sp + "/value", value, {bins});
    if (!phi_error.empty()) writer.write_dataset(sp + "/error", error, {bins});
    writer.write_dataset(sp + "/delta", delta, {bins});
    if (!phi_error.empty()) writer.write_dataset(sp + "/delta_error", delta_error, {bins});
    writer.write_dataset(sp + "/g", g, {bins});
    if (!phi_error.empty()) writer.write_dataset(sp + "/g_error", g_error, {bins});
    // Distributions of the reduced speed v* and their errors: dimensionless.
    for (const char* dataset : {"value", "delta", "g"})
      writer.write_unit(sp + "/" + dataset, io::units::kDimensionless);
    if (!phi_error.empty())
      for (const char* dataset : {"error", "delta_error", "g_error"})
        writer.write_unit(sp + "/" + dataset, io::units::kDimensionless);
    writer.write_attribute(sp, "sonine_c", c[k]);
    writer.write_attribute(sp, "lambda", lambda);
    writer.write_attribute(sp, "tail_beta", beta);
  }
  writer.write_attribute(group, "cooling_rate_reduced", zeta);
  if (!zeta_error.empty()) writer.write_attribute(group, "cooling_rate_reduced_error", zeta_error[0]);
  writer.write_attribute(group, "replicas", static_cast<long long>(acc["reduced_distribution"].values.size()));
  writer.write_attribute(group, "scaling_start", config.output.scaling_start);
  writer.write_attribute(group, "description",
                         std::string("Phi_i(v*), v* = |v - u|/v0, v0 = sqrt(2T(m1+m2)/(m1 m2)), averaged over the "
                                     "samples past scaling_start collisions per particle; delta = Delta_i of "
                                     "Montanero and Garzo 2002 eq 27, g = G_i of eq 30 (measured c_i, lambda_i, zeta*); docs/sonine.md"));
}

/// /scaling_state (docs/output.md): c_k and T_k/T averaged over each replica's samples past
/// scaling_start, then over the replicas, with the standard error over the replicas (that of the time
/// average itself, whatever the correlation between its samples). Written when every replica has such
/// samples.
void write_scaling_state(io::h5md::Writer& writer, const std::string& root, const io::config::Config& config,
                         PointResult& result) {
  auto& acc = result.observables;
  if (!acc.count("scaling_sonine_c") || !acc.count("scaling_temperature_share") || !acc.count("time")) return;
  const std::size_t replicas = acc["time"].values.size();
  for (const char* name : {"scaling_sonine_c", "scaling_temperature_share"}) {
    const auto& values = acc[name].values;
    if (values.size() != replicas) return;
    for (const auto& v : values)
      if (v.size() != acc[name].columns) return;
  }
  const std::string group = root + "/scaling_state";
  const std::size_t s = acc["scaling_sonine_c"].columns;
  for (const auto& [name, dataset] : std::vector<std::pair<std::string, std::string>>{
           {"scaling_sonine_c", "sonine_c"}, {"scaling_temperature_share", "temperature_over_mean"}}) {
    writer.write_dataset(group + "/" + dataset, acc[name].mean(), {s});
    writer.write_unit(group + "/" + dataset, io::units::kDimensionless);
    const auto error = acc[name].standard_error();
    if (!error.empty()) {
      writer.write_dataset(group + "/" + dataset + "_error", error, {s});
      writer.write_unit(group + "/" + dataset + "_error", io::units::kDimensionless);
    }
  }
  writer.write_attribute(group, "replicas", static_cast<long long>(replicas));
  writer.write_attribute(group, "scaling_start", config.output.scaling_start);
  writer.write_attribute(group, "description",
                         std::string("c_k and T_k/T of each replica averaged over its samples past scaling_start "
                                     "collisions per particle, then over the replicas; *_error: standard error "
                                     "over the replicas (docs/output.md)"));
}

/// The observables of an &agg_frag point. T_k of a size that most replicas lack is not the mean of
/// per-replica temperatures: it is the ratio estimator T_k = (2/3) sum_r E_kr / sum_r N_kr (E_kr the
/// kinetic energy of size k in replica r), with the delta-method standard error
/// sqrt(sum_r (E_kr - rho N_kr)^2 / (R (R - 1))) / mean_r N_kr times 2/3, rho = sum E/sum N; 0 where
/// no replica has a cluster of that size (never NaN).
void write_agg_frag_point(io::h5md::Writer& writer, const std::string& root, PointResult& result,
                          const std::vector<long long>& step, const std::vector<double>& time_mean) {
  auto& acc = result.observables;
  for (const auto& [name, a] : acc) {
    if (name == "size_energy") continue;
    io::h5md::Series series;
    series.time = time_mean;
    series.step = step;
    series.value = a.mean();
    series.columns = a.columns;
    series.error = a.standard_error();
    series.time_unit = io::units::kTime;
    series.value_unit = io::units::of_observable(name);
    writer.write_observable(root + "/" + name, series);
  }
  const auto& number = acc["number"];
  const auto& energy = acc["size_energy"];
  const std::size_t width = number.columns, replicas = number.values.size();
  io::h5md::Series temperature;
  temperature.time = time_mean;
  temperature.step = step;
  temperature.columns = width;
  temperature.time_unit = io::units::kTime;
  temperature.value_unit = io::units::of_observable("temperature");
  for (std::size_t c = 0; c < time_mean.size() * width; ++c) {
    double sum_n = 0.0, sum_e = 0.0;
    for (std::size_t r = 0; r < replicas; ++r) {
      sum_n += number.values[r][c];
      sum_e += energy.values[r][c];
    }
    const double rho = sum_n > 0.0 ? sum_e / sum_n : 0.0;
    temperature.value.push_back(2.0 / 3.0 * rho);
    if (replicas > 1) {
      double residual2 = 0.0;
      for (std::size_t r = 0; r < replicas; ++r) {
        const double d = energy.values[r][c] - rho * number.values[r][c];
        residual2 += d * d;
      }
      const double mean_n = sum_n / static_cast<double>(replicas);
      const double rr = static_cast<double>(replicas);
      temperature.error.push_back(mean_n > 0.0 ? 2.0 / 3.0 * std::sqrt(residual2 / (rr * (rr - 1.0))) / mean_n : 0.0);
    }
  }
  writer.write_observable(root + "/temperature", temperature);
  writer.write_attribute(root + "/number", "description",
                         std::string("clusters of size k = column + 1 (k monomers), per replica"));
  writer.write_attribute(root + "/temperature", "description",
                         std::string("T_k = m_k <|v-u|^2>/3 of clusters of size k = column + 1: ratio of the replica "
                                     "sums (2/3) sum E_k / sum N_k; 0 where no replica has such a cluster"));
  writer.write_attribute(root + "/total_temperature", "description",
                         std::string("per cluster: sum_k N_k T_k / N (docs/agg-frag.md)"));
  writer.write_attribute(root + "/kinetic_energy", "description",
                         std::string("kinetic energy relative to the mean flow per initial monomer"));
  writer.write_attribute(root + "/dissipated_energy", "description",
                         std::string("energy lost in collisions so far per initial monomer, added event by event"));
}

/// Writes one point's observables under `root` ("/observables" or "/sweep/point_K/observables").
void write_point(io::h5md::Writer& writer, const std::string& root, const io::config::Config& config,
                 PointResult& result) {
  auto& acc = result.observables;
  const std::size_t s = static_cast<std::size_t>(config.system.n_species);
  const auto bins = static_cast<std::size_t>(config.output.histogram_bins);
  const double range = config.output.histogram_range;
  const std::vector<double> time_mean = acc["time"].mean();
  const std::size_t n_samples = time_mean.size();
  // H5MD `step` (docs/output.md "The H5MD file"): an integer step of the simulation itself, the
  // cumulative collision events of a replica up to the sample (the observable `collisions`), its mean
  // over the replicas rounded to the nearest integer; `time` is the simulation time.
  const std::vector<double> events = acc["collisions"].mean();
  std::vector<long long> step(n_samples);
  for (std::size_t i = 0; i < n_samples; ++i) step[i] = i < events.size() ? std::llround(events[i]) : 0;
  if (config.has_agg_frag) {
    write_agg_frag_point(writer, root, result, step, time_mean);
    return;
  }

  for (const auto& [name, a] : acc) {
    if (name == "velocity_histogram" || name == "msd_start" ||
        (name.rfind("reduced_", 0) == 0 && name != "reduced_shear_rate") || name.rfind("scaling_", 0) == 0 ||
        name == "shear_viscosity_average" ||
        name == "shear_viscosity_kinetic_average")
      continue;
    io::h5md::Series series;
    series.time = time_mean;
    series.step = step;
    series.value = a.mean();
    series.columns = a.columns;
    series.error = a.standard_error();
    series.time_unit = io::units::kTime;
    series.value_unit = io::units::of_observable(name);
    writer.write_observable(root + "/" + name, series);
  }
  if (acc.count("velocity_histogram")) {  // one histogram observable per species: value (Nt x bins)
    const auto mean = acc["velocity_histogram"].mean();
    const auto error = acc["velocity_histogram"].standard_error();
    for (std::size_t k = 0; k < s; ++k) {
      io::h5md::Series series;
      series.time = time_mean;
      series.step = step;
      series.columns = bins;
      series.time_unit = io::units::kTime;
      series.value_unit = io::units::of_observable("velocity_histogram");
      for (std::size_t i = 0; i < n_samples; ++i)
        for (std::size_t b = 0; b < bins; ++b) {
          series.value.push_back(mean[i * s * bins + k * bins + b]);
          if (!error.empty()) series.error.push_back(error[i * s * bins + k * bins + b]);
        }
      writer.write_observable(root + "/velocity_histogram/species_" + std::to_string(k + 1), series);
    }
    std::vector<double> edges(bins + 1);
    for (std::size_t b = 0; b <= bins; ++b)
      edges[b] = -range + 2.0 * range * static_cast<double>(b) / static_cast<double>(bins);
    writer.write_dataset(root + "/velocity_histogram/bin_edges", edges, {bins + 1});
    writer.write_unit(root + "/velocity_histogram/bin_edges", io::units::kDimensionless);  // v/sqrt(T_k/m_k)
  }
  if (acc.count("reduced_distribution")) write_reduced(writer, root, config, result);
  write_scaling_state(writer, root, config, result);
  if (acc.count("shear_viscosity_average")) {
    // One value per replica: the mean of eta/eta_0 over its samples from average_from on.
    const auto mean = acc["shear_viscosity_average"].mean();
    const auto error = acc["shear_viscosity_average"].standard_error();
    const std::string g = root + "/shear_viscosity";
    writer.write_attribute(g, "time_average", mean.at(0));
    if (!error.empty()) writer.write_attribute(g, "time_average_error", error.at(0));
    writer.write_attribute(g, "average_from", config.shear.average_from.value_or(0.5 * *config.dsmc.t_end));
    writer.write_attribute(g, "replicas_averaged", static_cast<long long>(acc["shear_viscosity_average"].values.size()));
    if (acc.count("shear_viscosity_kinetic_average")) {
      writer.write_attribute(g, "time_average_kinetic", acc["shear_viscosity_kinetic_average"].mean().at(0));
      const auto e = acc["shear_viscosity_kinetic_average"].standard_error();
      if (!e.empty()) writer.write_attribute(g, "time_average_kinetic_error", e.at(0));
    }
  }
  if (acc.count("shear_viscosity"))
    writer.write_attribute(root + "/shear_viscosity", "description",
                           std::string("eta/eta_0(T) = -P_xy/(a eta_0) with P_xy at the middle of the streaming jump "
                                       "(thermostat.hpp), divided by 1 - (a* eta*)^2 (finite shear rate, docs/shear-viscosity.md)"));
  if (acc.count("pressure_tensor"))
    writer.write_attribute(root + "/pressure_tensor", "description",
                           std::string("P = P^k + P^c, columns xx, yy, zz, xy, xz, yz; sampled at a stage's start, the mean of "
                                       "the values before and after its streaming (thermostat.hpp); dilute gas: P^c = 0"));
  if (acc.count("msd")) {
    // Each replica's start (-1 if it never started); the mean is the time origin of msd.
    const auto starts = acc["msd_start"].values;
    std::vector<double> start_times;
    for (const auto& row : starts) start_times.push_back(row[0]);
    writer.write_dataset(root + "/msd/start_time", start_times, {start_times.size()});
    writer.write_unit(root + "/msd/start_time", io::units::kTime);
    writer.write_attribute(root + "/msd", "description",
                           std::string("<|R_k|^2> per species, displacement since start_time (Bodrova and Osinsky 2024 eq 15; docs/diffusion-msd.md)"));
  }
  writer.write_attribute(root + "/temperature", "description",
                         std::string("partial temperatures T_k = m_k <|v-u|^2>/3, columns = species"));
  writer.write_attribute(root + "/sonine_c", "description",
                         std::string("c_k = 2[(3/5)<v^4>/<v^2>^2 - 1] (Montanero and Garzo 2002 eq 17; docs/sonine.md)"));
  if (acc.count("collisions_pair"))
    writer.write_attribute(root + "/collisions_pair", "description",
                           std::string("cumulative events per species pair (k <= j, row-major upper triangle)"));
  if (acc.count("velocity_histogram"))
    writer.write_attribute(root + "/velocity_histogram", "description",
                           std::string("pdf of velocity components in units of sqrt(T_k/m_k), per species"));
}

}  // namespace

Summary run(const io::config::Config& config, const std::string& output_path, const Options& options) {
  const auto started = Clock::now();
  const std::vector<io::config::Config> points = config.sweep_points();
  const int rank = parallel::rank(), ranks = parallel::size();

  // Open first (rank 0, which writes): an unwritable path fails before any work is done.
  std::optional<io::h5md::Writer> writer_storage;
  std::string open_error;
  if (rank == 0) {
    try {
      writer_storage.emplace(output_path, io::config::author_name(config.output), "granular-dsmc",
                             io::build_version());
    } catch (const std::runtime_error& e) {
      open_error = e.what();
      if (open_error.empty()) open_error = "cannot create the output file";
    }
  }
  open_error = parallel::broadcast_from_root(open_error);
  if (!open_error.empty()) throw OutputPathError(rank == 0 ? open_error : "");

  // Work units u = point * R_p + replica, point-major; unit u runs on rank u mod K (parallel.hpp).
  struct Unit {
    std::size_t point, replica;
  };
  std::vector<Unit> units;
  for (std::size_t p = 0; p < points.size(); ++p)
    for (std::size_t r = 0; r < static_cast<std::size_t>(points[p].dsmc.replicas); ++r) units.push_back({p, r});
  std::vector<std::size_t> mine;
  for (std::size_t u = 0; u < units.size(); ++u)
    if (u % static_cast<std::size_t>(ranks) == static_cast<std::size_t>(rank)) mine.push_back(u);

  // Checkpoints: one file per rank (rank 0's is the one \ref output_checkpoint "docs/output.md" names).
  const std::string fingerprint = config.namelist_text + "\n--overrides--\n" + [&] {
    std::string joined;
    for (const auto& o : config.overrides) joined += o + "\n";
    return joined;
  }();
  CheckpointStore checkpoints(checkpoint_path(output_path, rank), config.output.checkpoint_every.value_or(0.0),
                              fingerprint, ranks, units.size());
  std::string restart_error;
  if (!options.restart_path.empty()) {
    try {
      checkpoints.load(rank_file(options.restart_path, rank));
    } catch (const std::exception& e) {
      restart_error = e.what();
    }
  }
  {
    std::vector<std::string> errors = parallel::gather_to_root(restart_error);
    std::string first;
    for (const auto& e : errors)
      if (!e.empty() && first.empty()) first = e;
    first = parallel::broadcast_from_root(first);
    if (!first.empty()) throw RestartError(first);
  }

  std::vector<std::size_t> point_of;
  for (std::size_t u : mine) point_of.push_back(units[u].point);
  Progress progress(options.progress && rank == 0, options.progress_terminal, point_of, points.size());
  std::vector<ReplicaResult> done(mine.size());
  std::string failure;  // first error of a thread (exceptions must not leave an OpenMP region)
  std::atomic<bool> interrupted{false}, failed{false};
  const auto n_mine = static_cast<std::ptrdiff_t>(mine.size());
  // Threads serve the units first; when this rank has fewer units than threads, each unit's cache
  // blocks share the rest (collide.hpp, "Threads inside one replica"), and the output is the same.
  const parallel::ThreadSplit split = parallel::split_threads(mine.size());
  const auto run_unit = [&](std::ptrdiff_t k) {
    if (interrupted.load() || failed.load()) return;
    const Unit& unit = units[mine[static_cast<std::size_t>(k)]];
    const auto& point = points[unit.point];
    std::string label = "replica " + std::to_string(unit.replica + 1) + "/" + std::to_string(point.dsmc.replicas);
    if (points.size() > 1)
      label = "point " + std::to_string(unit.point + 1) + "/" + std::to_string(points.size()) + "  " + label;
    const std::size_t u = mine[static_cast<std::size_t>(k)];
    try {
      if (const ReplicaResult* finished = checkpoints.finished_result(u)) {
        done[static_cast<std::size_t>(k)] = *finished;
        progress.update(static_cast<std::size_t>(k), 1.0, label, 0.0, 0);
      } else {
        const SafePoint safe_point = [&](const std::function<Snapshot()>& snapshot) {
          checkpoints.safe_point(u, snapshot);
        };
        done[static_cast<std::size_t>(k)] = run_replica(point, options, progress, static_cast<std::size_t>(k), label,
                                                        unit.replica, checkpoints.resume_point(u), safe_point,
                                                        split.per_unit);
        checkpoints.finished(u, done[static_cast<std::size_t>(k)]);
      }
    } catch (const Interrupted&) {
      interrupted.store(true);
    } catch (const std::exception& e) {
#pragma omp critical(gdsmc_failure)
      if (!failed.exchange(true)) failure = e.what();
    }
  };
  if (split.units > 1) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(split.units)
    for (std::ptrdiff_t k = 0; k < n_mine; ++k) run_unit(k);
  } else {
    // One unit at a time: no enclosing parallel region, so the blocks' parallel regions are not nested
    // (libgomp starts new threads for every nested region instead of reusing its pool: 144 threads
    // for a run of 40 steps).
    for (std::ptrdiff_t k = 0; k < n_mine; ++k) run_unit(k);
  }
  progress.finish();

  // Every rank sends its status and results to rank 0, which decides for all.
  std::string packed(1, interrupted.load() ? 'I' : failed.load() ? 'F' : 'K');
  if (failed.load()) packed += failure;
  else if (!interrupted.load())
    for (std::size_t k = 0; k < mine.size(); ++k) pack(packed, mine[k], done[k]);
  done.clear();
  const std::vector<std::string> gathered = parallel::gather_to_root(packed);
  std::string verdict;
  if (rank == 0)
    for (const auto& g : gathered)
      if (g[0] != 'K' && verdict.empty()) verdict = g;
  verdict = parallel::broadcast_from_root(verdict);
  if (!verdict.empty() && verdict[0] == 'I') throw Interrupted();
  if (!verdict.empty()) throw std::runtime_error(verdict.substr(1));
  if (rank != 0) {
    checkpoints.remove();
    Summary summary;
    summary.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
    return summary;
  }

  std::vector<std::vector<ReplicaResult>> by_point(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) by_point[p].resize(static_cast<std::size_t>(points[p].dsmc.replicas));
  for (const auto& g : gathered) {
    std::size_t pos = 1;
    while (pos < g.size()) {
      std::uint64_t u = 0;
      ReplicaResult r = unpack(g, pos, u);
      by_point[units[u].point][units[u].replica] = std::move(r);
    }
  }
  std::vector<PointResult> results;
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (points[p].has_agg_frag) pad_size_columns(by_point[p]);
    results.push_back(reduce_point(by_point[p]));
  }
  io::h5md::Writer& writer = *writer_storage;

  writer.write_parameters(config.resolved(), config.namelist_text);
  writer.write_attribute("/parameters", "source_file", config.source_file);
  std::string joined;
  for (const auto& o : config.overrides) joined += o + "\n";
  writer.write_attribute("/parameters", "overrides", joined);
  // H5MD's units module: every time and observable carries its unit, in the units of the namelist
  // (\ref output_units "docs/output.md").
  io::units::declare(writer);

  Summary summary;
  std::uint64_t events = 0;
  double collide_seconds = 0.0;
  const auto sweep_rows = config.sweep.table();
  for (std::size_t k = 0; k < points.size(); ++k) {
    // A sweep point lives in /sweep/point_K (K from 1) with the value it applies.
    const std::string group = config.is_sweep() ? "/sweep/point_" + std::to_string(k + 1) : "";
    write_point(writer, group + "/observables", points[k], results[k]);
    if (config.is_sweep()) {
      // One variable: its name and the value as written (as before tables); several: joined by ", ".
      writer.write_attribute(group, "variable", config.sweep.names());
      writer.write_attribute(group, "value", io::config::Sweep::row_text(sweep_rows[k]));
      writer.write_attribute(group, "mean_time_step", results[k].mean_step);
      // Each point is an H5MD root of its own (h5md + observables): a reader opened at the group
      // reads it as a file (docs/output.md "Sweeps").
      writer.write_hard_link("/h5md", group + "/h5md");
    } else {
      writer.write_attribute("/parameters", "mean_time_step", results[k].mean_step);
    }
    events += results[k].events;
    collide_seconds += results[k].collide_seconds;
    summary.final_time = results[k].observables["time"].mean().back();
    summary.final_total_temperature = results[k].observables["total_temperature"].mean().back();
    summary.collisions_per_particle = results[k].observables["collisions_per_particle"].mean().back();
    if (results[k].observables.count("acceptance_overshoots"))
      summary.acceptance_overshoots += results[k].observables["acceptance_overshoots"].mean().back() *
                                       static_cast<double>(points[k].dsmc.replicas);
  }
  if (config.is_sweep()) {
    writer.write_attribute("/sweep", "variable", config.sweep.names());
    std::vector<std::string> texts;
    for (const auto& row : sweep_rows) texts.push_back(io::config::Sweep::row_text(row));
    writer.write_attribute("/sweep", "values", texts);
    // The table (analysis/sweep_table.hpp): the swept values and the headline results, read back from the
    // points just written.
    analysis::sweep_table::write(writer, analysis::sweep_table::build(config, writer.temporary_path()));
  }
  if (options.before_commit) options.before_commit(writer);
  writer.commit();
  checkpoints.remove();  // the run is complete: its checkpoint is stale

  summary.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  summary.events_per_second = collide_seconds > 0 ? static_cast<double>(events) / collide_seconds : 0.0;
  return summary;
}

}  // namespace gdsmc::simulation
