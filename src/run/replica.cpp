// One replica of one point, in one loop (replica.hpp).
#include "run/replica.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dsmc/agg_frag.hpp"
#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/sample.hpp"
#include "dsmc/thermostat.hpp"
#include "io/snapshot.hpp"
#include "run/model.hpp"

namespace gdsmc::simulation {

// A physics error that heats a free gas stops the run at once (replica.hpp).
void check_energy_does_not_grow(const ReplicaResult& result, const char* row) {
  const auto it = result.rows.find(row);
  const auto times = result.rows.find("time");
  if (it == result.rows.end() || it->second.first != 1 || it->second.second.size() < 2) return;
  const auto& e = it->second.second;
  const double before = e[e.size() - 2], now = e.back();
  if (!(now > before * (1.0 + 1e-6))) return;
  const std::vector<double> none;
  const auto& t = times == result.rows.end() ? none : times->second.second;
  char text[320];
  std::snprintf(text, sizeof text,
                "the gas's energy (%s) rose from %.10g to %.10g between t = %.6g and t = %.6g, which collisions "
                "of inelastic spheres cannot do: a physics error in the collision rule; the run is stopped",
                row, before, now, t.size() >= 2 ? t[t.size() - 2] : 0.0, t.empty() ? 0.0 : t.back());
  throw std::runtime_error(text);
}

namespace {

/// What steps a replica and what measures it (header): a free gas, a gas with forcings, the clusters.
class Engine {
 public:
  using Between = std::function<void()>;  ///< called between two steps: interrupt, progress, checkpoint
  virtual ~Engine() = default;
  /// The number of samples, t = 0 included.
  virtual std::size_t samples() const = 0;
  /// A replica that starts from the beginning (not from a checkpoint): what precedes the first step.
  virtual void start() {}
  /// Steps up to sample i (its time, or its event target), calling `between` between steps.
  virtual void advance_to_sample(std::size_t i, const Between& between) = 0;
  /// Measures sample i into `result` (an engine whose sampling also collides adds that time to
  /// result.collide_seconds, as the loop adds advance_to_sample's).
  virtual void sample(std::size_t i, ReplicaResult& result) = 0;
  /// The end of the replica: the observables of the whole replica, its events and mean step.
  virtual void finish(ReplicaResult& result) = 0;
  /// The threads the collision loop runs on now: the replica's block threads (at most its blocks) while
  /// it has cache blocks, else 1. Its collide_seconds are thread-seconds, read at the end of each
  /// interval, so that the summary's rate is per thread (approximately: the whole-gas steps near event
  /// targets run on one thread, and a cluster gas can drop its blocks within an interval).
  virtual int loop_threads() const = 0;
  /// The simulated time.
  virtual double time() const = 0;
  /// The collision events so far.
  virtual std::uint64_t events() const = 0;
  /// The share of the replica done: its time over the last sample time, or its events over the last target.
  virtual double fraction_done() const = 0;
  /// The time of sample i: a time-driven run's target (infinity for a collision-driven one).
  virtual double sample_time(std::size_t i) const = 0;
  /// Steps up to time `t` exactly (not beyond the next sample), calling `between` between steps
  /// (&output snapshot_times; time-driven runs of the free gas or the gas with forcings).
  virtual void advance_to_time(double t, const Between& between) = 0;
  /// Adds a snapshot of every particle (io/snapshot.hpp) to `result` as rows snapshot_*.
  virtual void take_snapshot(ReplicaResult& result) const = 0;
  /// The state of the engine's modules (dsmc/state.hpp).
  virtual void save(state::Record& record) const = 0;
  /// Continues from save()'s record.
  virtual void restore(const state::Record& record) = 0;
};

/// Threads given to a replica's cache blocks that this run cannot use: said once, not left idle silently.
void note_idle_threads(const ReplicaContext& ctx, const std::string& why) {
  if (ctx.block_threads > 1 && ctx.slot == 0 && ctx.options.progress)
    std::fprintf(stderr,
                 "granular-dsmc: note: %d of the %d threads per work unit stay idle: %s; threads serve "
                 "replicas and sweep points first, then cache blocks (docs/schemes.md)\n",
                 ctx.block_threads - 1, ctx.block_threads, why.c_str());
}

/// &initial from_file: the velocities (and angular velocities) of replica r's snapshot in `file`
/// (io/snapshot.hpp) replace the drawn ones; the species were checked against the file's (io/config).
void start_from_snapshot(particles::System& sys, const std::string& file, std::size_t r) {
  const io::snapshot::State state = io::snapshot::read(file, r);
  if (state.species.size() != sys.size())
    throw std::runtime_error("'" + file + "': its replica " + std::to_string(r + 1) + " has " +
                             std::to_string(state.species.size()) + " particles, the run " + std::to_string(sys.size()));
  for (std::size_t i = 0; i < sys.size(); ++i) {
    if (state.species[i] != sys.species[i] + 1)
      throw std::runtime_error("'" + file + "': the species of its particles are not those of the run");
    sys.v[i] = {state.velocity[3 * i], state.velocity[3 * i + 1], state.velocity[3 * i + 2]};
  }
  if (auto* spin = sys.find_array(rules::RoughRule::angular_velocity); spin && !state.angular_velocity.empty()) {
    auto& w = std::get<particles::ParticleArray<particles::Vec3>>(spin->values);
    for (std::size_t i = 0; i < sys.size(); ++i)
      w[i] = {state.angular_velocity[3 * i], state.angular_velocity[3 * i + 1], state.angular_velocity[3 * i + 2]};
  }
}

/// Whether the replica must stop: the run's interrupt flag, or another unit's failure (ReplicaContext::abandon).
bool interrupted(const ReplicaContext& ctx) {
  return (ctx.options.interrupt && ctx.options.interrupt->load()) || (ctx.abandon && ctx.abandon->load());
}

/// The set-up's look at the same (particles::SetUpCheck): throws Interrupted, so that a set-up whose time
/// grows with N is left within a second (tests/scale_out/interrupt.sh).
particles::SetUpCheck set_up_check(const ReplicaContext& ctx) {
  return [&ctx] {
    if (interrupted(ctx)) throw Interrupted();
  };
}

/// Replica r's particles, drawn from its stream (seed, r, initial_state).
particles::System initial_system(const io::config::Config& config, const species::Mixture& mix,
                                 const std::vector<std::size_t>& counts, std::size_t r, const ReplicaContext& ctx) {
  auto stream = rng::make_stream(static_cast<std::uint64_t>(config.dsmc.seed), r, rng::Purpose::initial_state);
  particles::System sys = particles::make_system(mix, counts, config.initial.temperature, initial_distribution(config),
                                                 stream, set_up_check(ctx));
  if (mix.rough()) {  // the angular velocities from a stream of their own (the smooth gas's draws unchanged)
    auto spin = rng::make_stream(static_cast<std::uint64_t>(config.dsmc.seed), r, rng::Purpose::rotation);
    particles::add_angular_velocities(sys, mix, config.initial.rotational_temperature, rules::RoughRule::angular_velocity, spin,
                                      set_up_check(ctx));
  }
  if (!config.initial.from_file.empty()) start_from_snapshot(sys, config.initial.from_file, r);
  return sys;
}

/// The particles of a replica and their collider, with the samples of its scaling state: what the free
/// gas and the gas with forcings share.
class Gas : public Engine {
 public:
  std::size_t samples() const override { return targets_.size(); }
  double time() const override { return collider_.time(); }
  int loop_threads() const override {
    return collider_.blocks() > 1 ? static_cast<int>(std::min<std::size_t>(collider_.threads(), collider_.blocks())) : 1;
  }
  std::uint64_t events() const override { return collider_.counters().events; }
  double sample_time(std::size_t i) const override {
    return config_.dsmc.t_end ? targets_[i] : std::numeric_limits<double>::infinity();
  }
  void take_snapshot(ReplicaResult& result) const override;

 protected:
  /// `reduced`: the replica accumulates the reduced speed distributions Phi_i(v*) of its scaling state.
  Gas(const io::config::Config& config, std::size_t r, bool reduced, const ReplicaContext& ctx)
      : reduced_(reduced && config.system.n_species <= 2), config_(config), mix_(config.mixture()), s_(mix_.size()),
        counts_(species::particle_counts(static_cast<std::size_t>(config.dsmc.n_particles), mix_)),
        sys_(initial_system(config, mix_, counts_, r, ctx)),
        collider_(scheme(config), mix_, sys_,
                  rng::make_stream(static_cast<std::uint64_t>(config.dsmc.seed), r, rng::Purpose::collisions),
                  config.dsmc.step_fraction, make_rule(config, mix_)),
        targets_(config.dsmc.t_end ? config.sample_times() : config.sample_collisions()),
        c_sum_(s_, 0.0), share_sum_(s_, 0.0) {}

  /// The rows every gas sample has (temperatures, cumulants, counts, collisions, time); its moments.
  sample::Moments measure_common(ReplicaResult& result) const;
  /// 2 x events / N.
  double collisions_per_particle() const {
    return 2.0 * static_cast<double>(collider_.counters().events) / static_cast<double>(sys_.size());
  }
  /// A sample of the scaling state (past `&output scaling_start` collisions per particle) added to the
  /// sums of c_k and T_k/T. A checkpoint of an older version without the sums (their size not s) leaves
  /// them alone: the replica then reports no scaling state.
  void add_scaling_sample(const sample::Moments& m, double time);
  /// The replica's averages of c_k and T_k/T over its scaling-state samples (scaling_sonine_c,
  /// scaling_temperature_share): one value per replica, so that their standard error over the replicas is
  /// that of the time average itself, whatever the correlation between samples (/scaling_state).
  void add_scaling_averages(ReplicaResult& result) const;
  /// The speeds of sample `m` added to the reduced distributions' counts (a scaling-state sample).
  void add_reduced_speeds(const sample::Moments& m);
  /// Phi_i(v*), c_i, T_i/T of the scaling state and its reduced cooling rate `zeta_star` (Montanero and
  /// Garzo 2002, \ref son_reduced_distributions "docs/sonine.md"), when the replica has two scaling samples.
  void add_reduced(ReplicaResult& result, double zeta_star) const;
  /// Whether add_reduced() has what it needs: two scaling samples at distinct times.
  bool has_reduced() const { return reduced_ && scaling_samples_ >= 2.0 && t_last_ > t_first_; }
  void save_gas(state::Record& r) const;
  void restore_gas(const state::Record& r);

  /// Phi_i(v*) is defined for one or two species (Montanero and Garzo 2002, \ref son_reduced_distributions "docs/sonine.md").
  bool reduced_;
  const io::config::Config& config_;
  species::Mixture mix_;
  std::size_t s_;
  std::vector<std::size_t> counts_;
  particles::System sys_;
  collide::Collider collider_;
  std::vector<double> targets_;  ///< sample points: times, or collisions per particle
  double scaling_samples_ = 0.0, t_first_ = 0.0, t_last_ = 0.0, temp_first_ = 0.0, temp_last_ = 0.0;
  std::vector<double> speed_counts_, c_sum_, share_sum_;
};

sample::Moments Gas::measure_common(ReplicaResult& result) const {
  const sample::Moments m = sample::measure(mix_, sys_);
  const auto& counters = collider_.counters();
  result.add("temperature", s_, m.temperature);
  result.add("total_temperature", 1, {m.total_temperature});
  result.add("sonine_c", s_, m.sonine_c);
  result.add("number", s_, m.number);
  result.add("collisions", 1, {static_cast<double>(counters.events)});
  // The kernel's invariant (collide.hpp Counters::overshoots): 0 in a correct run.
  result.add("acceptance_overshoots", 1, {static_cast<double>(counters.overshoots)});
  result.add("collisions_per_particle", 1, {collisions_per_particle()});
  result.add("time", 1, {collider_.time()});
  collider_.measure_rule(result);  // (the rule's own observables: none for smooth or viscoelastic spheres)
  return m;
}

void Gas::add_scaling_sample(const sample::Moments& m, double time) {
  if (c_sum_.size() != s_ || share_sum_.size() != s_) return;
  for (std::size_t k = 0; k < s_; ++k) {
    c_sum_[k] += m.sonine_c[k];
    share_sum_[k] += m.temperature[k] / m.total_temperature;
  }
  if (scaling_samples_ == 0.0) {
    t_first_ = time;
    temp_first_ = m.total_temperature;
  }
  t_last_ = time;
  temp_last_ = m.total_temperature;
  scaling_samples_ += 1.0;
}

void Gas::add_scaling_averages(ReplicaResult& result) const {
  if (scaling_samples_ < 1.0) return;
  std::vector<double> c = c_sum_, share = share_sum_;
  for (auto& x : c) x /= scaling_samples_;
  for (auto& x : share) x /= scaling_samples_;
  result.add("scaling_sonine_c", c.size(), c);
  result.add("scaling_temperature_share", share.size(), share);
}

void Gas::add_reduced_speeds(const sample::Moments& m) {
  if (!reduced_) return;
  sample::add_reduced_speeds(mix_, sys_, m, sample::reduced_velocity_scale(mix_, m.total_temperature),
                             static_cast<std::size_t>(config_.output.reduced_bins), config_.output.reduced_range,
                             speed_counts_);
}

void Gas::add_reduced(ReplicaResult& result, double zeta_star) const {
  const auto bins = static_cast<std::size_t>(config_.output.reduced_bins);
  result.add("reduced_distribution", s_ * bins,
             sample::reduced_distribution(speed_counts_, std::vector<double>(counts_.begin(), counts_.end()),
                                          scaling_samples_, bins, config_.output.reduced_range));
  std::vector<double> c = c_sum_, share = share_sum_;
  for (auto& x : c) x /= scaling_samples_;
  for (auto& x : share) x /= scaling_samples_;
  result.add("reduced_sonine_c", s_, c);
  result.add("reduced_temperature_share", s_, share);
  result.add("reduced_cooling_rate", 1, {zeta_star});
}

void Gas::take_snapshot(ReplicaResult& result) const {
  const std::size_t n = sys_.size();
  const auto flat = [n](const auto& vectors) {  // [N][3], row-major
    std::vector<double> out;
    out.reserve(3 * n);
    for (const auto& v : vectors) out.insert(out.end(), {v.x, v.y, v.z});
    return out;
  };
  if (!result.rows.count("snapshot_species")) {  // the species never move (particles.hpp): once
    std::vector<double> species(n);
    for (std::size_t i = 0; i < n; ++i) species[i] = static_cast<double>(sys_.species[i]) + 1.0;
    result.add("snapshot_species", n, species);
  }
  result.add("snapshot_time", 2, {time(), static_cast<double>(events())});
  result.add("snapshot_velocity", 3 * n, flat(sys_.v));
  for (const auto& e : sys_.extra)
    if (e.name == rules::RoughRule::angular_velocity)
      result.add("snapshot_angular_velocity", 3 * n, flat(std::get<particles::ParticleArray<particles::Vec3>>(e.values)));
  if (config_.output.track_displacements) {  // R + v (t - t_last) since the start of tracking; 0 before it
    std::vector<double> r(3 * n, 0.0);
    if (sys_.tracks_displacements())
      for (std::size_t i = 0; i < n; ++i) {
        const auto& d = sys_.r[i];
        const auto& v = sys_.v[i];
        const double dt = time() - d.t_last;
        r[3 * i] = d.x + v.x * dt;
        r[3 * i + 1] = d.y + v.y * dt;
        r[3 * i + 2] = d.z + v.z * dt;
      }
    result.add("snapshot_displacement", 3 * n, r);
  }
}

void Gas::save_gas(state::Record& r) const {
  particles::save(sys_, r);
  collider_.save(r);
  r.put("gas/scaling_samples", scaling_samples_);
  r.put("gas/t_first", t_first_);
  r.put("gas/t_last", t_last_);
  r.put("gas/temp_first", temp_first_);
  r.put("gas/temp_last", temp_last_);
  r.put("gas/speed_counts", speed_counts_);
  r.put("gas/c_sum", c_sum_);
  r.put("gas/share_sum", share_sum_);
}

/// No run reaches a kinetic energy per particle of kinetic_energy_limit times the largest initial
/// temperature (free cooling and agg/frag only lose energy; the thermostats hold T near its start or a
/// steady value): a checkpoint beyond it was forged or damaged, and its moments would overflow (T/m <=
/// 1e100 by the input checks, so v^2 <= 1e130 and v^4 <= 1e260 within double range).
constexpr double kinetic_energy_limit = 1e30;

double largest_initial_temperature(const io::config::Config& config) {
  return *std::max_element(config.initial.temperature.begin(), config.initial.temperature.end());
}

void Gas::restore_gas(const state::Record& r) {
  particles::restore(sys_, r);
  const double limit = kinetic_energy_limit * largest_initial_temperature(config_);
  for (std::size_t k = 0; k < s_; ++k)
    for (std::size_t i = sys_.first[k]; i < sys_.first[k] + sys_.count[k]; ++i) {
      const particles::Vec3& v = sys_.v[i];
      if (!(mix_.mass[k] * (v.x * v.x + v.y * v.y + v.z * v.z) <= limit))
        throw state::StateError("particle " + std::to_string(i) + " has m v^2 beyond 1e30 times the largest initial "
                                "temperature, which no run reaches");
    }
  collider_.restore(r);
  scaling_samples_ = r.real("gas/scaling_samples");
  t_first_ = r.real("gas/t_first");
  t_last_ = r.real("gas/t_last");
  temp_first_ = r.real("gas/temp_first");
  temp_last_ = r.real("gas/temp_last");
  speed_counts_ = r.array("gas/speed_counts");
  // Empty before the first scaling-state sample, S x reduced_bins after (a record is read, not trusted).
  const std::size_t bins = s_ * static_cast<std::size_t>(config_.output.reduced_bins);
  if (!speed_counts_.empty() && speed_counts_.size() != bins)
    throw state::StateError("'gas/speed_counts' holds " + std::to_string(speed_counts_.size()) + " values, not " +
                            std::to_string(bins));
  c_sum_ = r.array("gas/c_sum");
  share_sum_ = r.array("gas/share_sum");
}

// ---------------------------------------------------------------------------------------------
// The free gas: collision chunks between samples
// ---------------------------------------------------------------------------------------------

class FreeGas final : public Gas {
 public:
  FreeGas(const io::config::Config& config, std::size_t r, const ReplicaContext& ctx);
  void start() override;
  void advance_to_sample(std::size_t i, const Between& between) override;
  void advance_to_time(double t, const Between& between) override;
  void sample(std::size_t i, ReplicaResult& result) override;
  void finish(ReplicaResult& result) override;
  double fraction_done() const override {
    const double f = time_driven_ ? collider_.time() / targets_.back()
                                  : static_cast<double>(collider_.counters().events) / std::max(1.0, final_events_);
    return std::min(f, 1.0);
  }
  void save(state::Record& r) const override;
  void restore(const state::Record& r) override;

 private:
  /// The end of the next advance() towards `target` (header): ~1e5 candidates (chunk_end_time), or one
  /// time step's candidates when that is more, at most 2^24; with cache blocks 2^24 at the last step's
  /// rate, ending at blocked steps' ends (collide.hpp "Blocks", "Step length"). A gas at rest (no
  /// candidates: the collider jumps to its target) goes straight there.
  double chunk_stop(double target) const;
  /// Displacements from msd_start_time: stop there exactly, then start tracking.
  void start_displacements(double t_target, std::uint64_t event_target, const Between& between);

  bool time_driven_, track_, blocked_;
  double final_events_, chunk_;
  bool in_sample_ = false;  ///< the current sample's msd start handling is done, its chunks are running
  bool tracking_ = false;
  double msd_start_ = 0.0;
};

FreeGas::FreeGas(const io::config::Config& config, std::size_t r, const ReplicaContext& ctx)
    : Gas(config, r, true, ctx), time_driven_(config.dsmc.t_end.has_value()),
      track_(config.output.track_displacements) {
  final_events_ = time_driven_ ? 0.0 : std::ceil(targets_.back() * static_cast<double>(sys_.size()) / 2.0);
  // Cache blocks (collide.hpp "Blocks"): in collision-driven runs the steps near each sample's event
  // target run on the whole gas and stop at it exactly.
  collider_.use_blocks(static_cast<std::size_t>(config.dsmc.block_size), set_up_check(ctx));
  collider_.use_threads(ctx.block_threads);
  collider_.set_stop_flag(ctx.options.interrupt);  // a step start notices it (collide.hpp)
  if (collider_.blocks() == 1)
    note_idle_threads(ctx, "this run has no cache blocks (they need 'majorant' or 'lowrank' with at most 256 species, "
                           "or 'lowrank' with at most N/2 species, beyond 65535 at most about 125000, and N >= 2 block_size)");
  blocked_ = collider_.blocks() > 1;
  const double step_candidates = 0.5 * static_cast<double>(sys_.size()) * config.dsmc.step_fraction;
  chunk_ = blocked_ ? 16777216.0 : std::clamp(step_candidates, chunk_candidates, 16777216.0);
}

void FreeGas::start() {
  // Displacements (Bodrova and Osinsky 2024, eq. (15), \ref dif_displacements "docs/diffusion-msd.md") from t = 0, from msd_start_time, or
  // from the first sample with T <= msd_start_temperature.
  if (track_ && !config_.output.msd_start_time && !config_.output.msd_start_temperature) {
    particles::start_tracking(sys_, 0.0);
    tracking_ = true;
  }
}

double FreeGas::chunk_stop(double target) const {
  const bool still = collider_.blocks() == 1 && collider_.counters().steps > 0 && !(collider_.candidate_rate() > 0.0);
  if (still) return target;
  if (const double rate = collider_.recent_candidate_rate(); blocked_ && rate > 0.0)
    return std::min(target, collider_.time() + chunk_ / rate);
  return chunk_end_time(collider_.time(), collider_.counters().candidates, target, chunk_);
}

void FreeGas::start_displacements(double t_target, std::uint64_t event_target, const Between& between) {
  if (in_sample_ || !track_ || tracking_ || !config_.output.msd_start_time || *config_.output.msd_start_time > t_target)
    return;
  const double start = *config_.output.msd_start_time;  // stop exactly at the start
  while (collider_.time() < start && collider_.counters().events < event_target) {
    collider_.advance(chunk_stop(start), event_target, true, UINT64_MAX, blocked_);
    between();
  }
  if (collider_.time() >= start) {
    particles::start_tracking(sys_, collider_.time());
    tracking_ = true;
    msd_start_ = collider_.time();
  }
}

void FreeGas::advance_to_sample(std::size_t i, const Between& between) {
  // Chunks, so that the progress line, an interrupt and checkpoints are seen at least every ~1e6
  // collisions and every ~1e5 candidates (chunk_end_time). The chunks end at the same events and times
  // in every run, wherever and however often it is stopped and resumed: the same trajectory bit for bit.
  const double t_target = time_driven_ ? targets_[i] : std::numeric_limits<double>::infinity();
  // 2 x events / N reaches the target (\ref output_observables "docs/output.md": collisions_per_particle)
  const std::uint64_t event_target =
      time_driven_ ? std::numeric_limits<std::uint64_t>::max()
                   : static_cast<std::uint64_t>(std::ceil(targets_[i] * static_cast<double>(sys_.size()) / 2.0));
  start_displacements(t_target, event_target, between);
  in_sample_ = true;
  constexpr std::uint64_t kChunk = 1u << 20;
  for (;;) {
    const std::uint64_t done = collider_.counters().events;
    const std::uint64_t chunk_end = event_target - done > kChunk ? done + kChunk : event_target;
    // The sample's own target is exact; a chunk's end is soft (blocks may pass it, collide.hpp), and
    // the sample's target is never passed, even by a soft chunk's step.
    collider_.advance(chunk_stop(t_target), chunk_end, chunk_end == event_target, event_target, blocked_);
    if (collider_.time() >= t_target || collider_.counters().events >= event_target) break;
    between();
  }
}

void FreeGas::advance_to_time(double t, const Between& between) {
  start_displacements(t, std::numeric_limits<std::uint64_t>::max(), between);
  constexpr std::uint64_t kChunk = 1u << 20;  // as advance_to_sample: chunks of events, soft
  while (collider_.time() < t) {
    const std::uint64_t chunk_end = collider_.counters().events + kChunk;
    collider_.advance(chunk_stop(t), chunk_end, false, std::numeric_limits<std::uint64_t>::max(), blocked_);
    if (collider_.time() >= t) break;
    between();
  }
}

void FreeGas::sample(std::size_t i, ReplicaResult& result) {
  // A blocked step whose collisions outran the bound its length was given passes the sample's exact
  // target (collide.hpp "Event targets": a gas far from equilibrium, whose bounds rise many times within
  // a step): the sample is taken at the collisions it reports, and the run's summary says so.
  if (!time_driven_) {
    const auto target = static_cast<std::uint64_t>(std::ceil(targets_[i] * static_cast<double>(sys_.size()) / 2.0));
    if (const std::uint64_t events = collider_.counters().events; events > target) {
      ++result.samples_past_target;
      result.most_past_target = std::max(result.most_past_target, events - target);
    }
  }
  const sample::Moments m = measure_common(result);
  check_energy_does_not_grow(result, config_.rough() ? "total_energy" : "total_temperature");
  const auto& counters = collider_.counters();
  if (s_ <= collide::pair_event_limit) {  // S(S+1)/2 columns, and a histogram per species: a few species only
    std::vector<double> pairs;
    for (std::size_t k = 0; k < s_; ++k)
      for (std::size_t j = k; j < s_; ++j) pairs.push_back(static_cast<double>(counters.pair_events[k * s_ + j]));
    result.add("collisions_pair", s_ * (s_ + 1) / 2, pairs);
    const auto bins = static_cast<std::size_t>(config_.output.histogram_bins);
    result.add("velocity_histogram", s_ * bins,
               sample::velocity_histogram(mix_, sys_, m, bins, config_.output.histogram_range));
  }
  if (track_ && !tracking_ && config_.output.msd_start_temperature &&
      m.total_temperature <= *config_.output.msd_start_temperature) {
    particles::start_tracking(sys_, collider_.time());
    tracking_ = true;
    msd_start_ = collider_.time();
  }
  if (track_)
    result.add("msd", s_, tracking_ ? sample::mean_squared_displacement(sys_, collider_.time()) : std::vector<double>(s_, 0.0));
  if (i > 0 && collisions_per_particle() >= config_.output.scaling_start) {
    add_reduced_speeds(m);
    add_scaling_sample(m, collider_.time());
  }
  in_sample_ = false;
}

void FreeGas::finish(ReplicaResult& result) {
  result.events = collider_.counters().events;
  result.mean_step = collider_.mean_step();
  result.cache_blocks = collider_.blocks();
  result.block_draw = static_cast<std::uint64_t>(collider_.block_draw());
  if (track_) result.add("msd_start", 1, {tracking_ ? msd_start_ : -1.0});
  add_scaling_averages(result);
  if (!has_reduced()) return;
  // zeta* = zeta/(n sigma_12^2 v0) with zeta = 2 sqrt(T) d(T^-1/2)/dt, constant in the HCS
  // (\ref haff_law "docs/haff-and-mixtures.md", \ref son_scaling "docs/sonine.md"): zeta* = 2 slope / (n sigma_12^2 sqrt(2 (m1 + m2)/(m1 m2))).
  const double slope = (1.0 / std::sqrt(temp_last_) - 1.0 / std::sqrt(temp_first_)) / (t_last_ - t_first_);
  const double sigma12 = mix_.contact_distance(0, s_ - 1);
  const double v0_unit = sample::reduced_velocity_scale(mix_, 1.0);
  add_reduced(result, 2.0 * slope / (mix_.total_density() * sigma12 * sigma12 * v0_unit));
}

void FreeGas::save(state::Record& r) const {
  save_gas(r);
  r.put_integer("gas/in_sample", in_sample_);
  r.put_integer("gas/tracking", tracking_);
  r.put("gas/msd_start", msd_start_);
}

void FreeGas::restore(const state::Record& r) {
  restore_gas(r);
  in_sample_ = r.flag("gas/in_sample");
  tracking_ = r.flag("gas/tracking");
  msd_start_ = r.real("gas/msd_start");
}

// ---------------------------------------------------------------------------------------------
// The gas with forcings (&thermostat, &shear): stages of the forcings' maps, collisions and ends
// (dsmc/thermostat.hpp, \ref eta_thermostat "docs/shear-viscosity.md")
// ---------------------------------------------------------------------------------------------

class ForcedGas final : public Gas {
 public:
  ForcedGas(const io::config::Config& config, std::size_t r, const ReplicaContext& ctx);
  void start() override { collider_.velocities_changed(); }  // the bounds (and the rate that sizes the stages)
  void advance_to_sample(std::size_t i, const Between& between) override;
  void advance_to_time(double t, const Between& between) override;
  void sample(std::size_t i, ReplicaResult& result) override;
  void finish(ReplicaResult& result) override;
  double fraction_done() const override { return std::min(collider_.time() / targets_.back(), 1.0); }
  void save(state::Record& r) const override {
    save_gas(r);
    stages_.save(r);
    r.put("gas/dissipated_first", dissipated_first_);
    r.put("gas/dissipated_last", dissipated_last_);
  }
  void restore(const state::Record& r) override;

 private:
  /// One stage from the collider's time to `end` (thermostat.hpp Stages): with `result`, sample `i` is
  /// taken at its start; the last sample's stage stops there (only its streaming).
  void stage(double end, std::size_t i, ReplicaResult* result, bool last);

  thermostat::Stages stages_;
  /// The collisions' loss (collide.hpp Counters::dissipated) at the first and the last scaling sample: the
  /// cooling rate of the HSS, which the thermostat restores.
  double dissipated_first_ = 0.0, dissipated_last_ = 0.0;
};

/// The HSS of the Gaussian thermostat alone, smooth spheres: its scaled distribution is the HCS's (the
/// thermostat term (zeta/2) d/dv . (v f) is the HCS's scaling term; \ref eta_thermostat "docs/shear-viscosity.md"),
/// so it has the reduced distributions. Shear flow, white noise and rough spheres have other states.
bool hss_of_gaussian_thermostat(const io::config::Config& config) {
  return config.thermostat.kind == io::config::ThermostatKind::gaussian && !config.shear.rate && !config.rough();
}

void ForcedGas::restore(const state::Record& r) {
  restore_gas(r);
  stages_.restore(r);
  if (r.has("gas/dissipated_first") && r.has("gas/dissipated_last")) {
    dissipated_first_ = r.real("gas/dissipated_first");
    dissipated_last_ = r.real("gas/dissipated_last");
  } else if (reduced_ && scaling_samples_ > 0.0) {
    throw state::StateError("'gas/dissipated_first' is missing: the checkpoint of an earlier build, whose steady-state "
                            "distributions cannot be completed; run the input again without --restart");
  }
}

/// The stages of a replica with forcings: the forcings of the input (run/model.cpp), the Enskog gas in
/// shear flow's shifted relative velocity set on the collider (collide.hpp set_shear) first.
thermostat::Stages make_stages(const io::config::Config& config, const species::Mixture& mix, particles::System& sys,
                               collide::Collider& collider, std::size_t r) {
  const double shear = config.shear.rate.value_or(0.0);
  const bool collisional = shear > 0.0 && mix.enskog;
  if (collisional) collider.set_shear(shear);
  return thermostat::Stages(mix, sys, collider, make_forcings(config, mix), config.dsmc.stage_step, shear, collisional,
                            rng::make_stream(static_cast<std::uint64_t>(config.dsmc.seed), r, rng::Purpose::forcing));
}

ForcedGas::ForcedGas(const io::config::Config& config, std::size_t r, const ReplicaContext& ctx)
    : Gas(config, r, hss_of_gaussian_thermostat(config), ctx),
      // (the centre-of-mass velocity sum m V / sum m removed first: \ref eta_thermostat "docs/shear-viscosity.md")
      stages_((thermostat::remove_mean_flow(mix_, sys_), make_stages(config, mix_, sys_, collider_, r))) {
  // Cache blocks with `majorant` or `lowrank` (collide.hpp, "Frame": frames in blocks): a pass over the
  // blocks per stage, on the block threads.
  if (staged_blocks(config)) {
    collider_.use_blocks(static_cast<std::size_t>(config.dsmc.block_size), set_up_check(ctx));
    collider_.use_threads(ctx.block_threads);
  } else {
    note_idle_threads(ctx, "a thermostat or shear flow has cache blocks only with 'majorant' or 'lowrank' (the "
                           "Enskog gas in shear flow needs 'pairs') and N >= 2 block_size");
  }
  collider_.set_stop_flag(ctx.options.interrupt);
}

void ForcedGas::stage(double end, std::size_t i, ReplicaResult* result, bool last) {
  const double dt = end - collider_.time();
  stages_.begin(dt, result != nullptr);
  if (result) {  // the sample of this instant: after the streaming of the stage that starts now
    const sample::Moments m = measure_common(*result);
    if (i > 0 && collisions_per_particle() >= config_.output.scaling_start) {
      add_reduced_speeds(m);
      if (scaling_samples_ == 0.0) dissipated_first_ = collider_.counters().dissipated;
      dissipated_last_ = collider_.counters().dissipated;
      add_scaling_sample(m, collider_.time());
    }
    stages_.measure(m, dt, i > 0, *result);
  }
  if (last) return;
  stages_.end(end);
}

void ForcedGas::advance_to_sample(std::size_t i, const Between& between) {
  while (collider_.time() < targets_[i]) {  // stages up to the sample time, which the last one hits exactly
    stage(stages_.stage_end(targets_[i]), i, nullptr, false);
    between();
  }
}

void ForcedGas::advance_to_time(double t, const Between& between) {
  while (collider_.time() < t) {  // whole stages, the last one ending at t exactly
    stage(stages_.stage_end(t), 0, nullptr, false);
    between();
  }
}

void ForcedGas::sample(std::size_t i, ReplicaResult& result) {
  // The stage that samples (the last one: only its streaming, of the length the next would have).
  const bool last = i + 1 == targets_.size();
  const auto t0 = Clock::now();
  stage(last ? stages_.stage_end(std::numeric_limits<double>::infinity()) : stages_.stage_end(targets_[i + 1]), i,
        &result, last);
  result.collide_seconds += std::chrono::duration<double>(Clock::now() - t0).count() * loop_threads();  // its collisions count
}

void ForcedGas::finish(ReplicaResult& result) {
  result.events = collider_.counters().events;
  result.cache_blocks = collider_.blocks();
  result.block_draw = static_cast<std::uint64_t>(collider_.block_draw());
  result.mean_step = collider_.time() > 0.0 && stages_.count() > 0.0 ? collider_.time() / stages_.count() : 0.0;
  add_scaling_averages(result);
  if (has_reduced() && stages_.count() > 0.0) {
    // The collisions' loss over the kinetic energy (3/2) N T, which the thermostat restores after each
    // stage (\ref eta_thermostat "docs/shear-viscosity.md"): the fraction `lost` of it per stage of length
    // `step`. Within a stage the gas cools freely, E_after/E_before = (1 + zeta dt/2)^-2 (Haff's law,
    // \ref haff_law "docs/haff-and-mixtures.md"): zeta at the HSS temperature, the stage's start, is
    // 2 ((1 - lost)^-1/2 - 1)/step (lost/step alone is 3 lost/4 low); zeta* = zeta/(n sigma_12^2 v0(T)).
    const double n_particles = static_cast<double>(sys_.size());
    const double step = collider_.time() / stages_.count();  // the stages' length, constant in the HSS
    const double lost = (dissipated_last_ - dissipated_first_) / (t_last_ - t_first_) * step / (1.5 * n_particles * temp_last_);
    const double zeta = 2.0 * (1.0 / std::sqrt(1.0 - lost) - 1.0) / step;
    const double sigma12 = mix_.contact_distance(0, s_ - 1);
    add_reduced(result, zeta / (mix_.total_density() * sigma12 * sigma12 *
                                sample::reduced_velocity_scale(mix_, temp_last_)));
  }
  stages_.finish(result);
}

// ---------------------------------------------------------------------------------------------
// The cluster gas of &agg_frag (agg_frag.hpp): chunks of events between samples
// ---------------------------------------------------------------------------------------------

class Clusters final : public Engine {
 public:
  Clusters(const io::config::Config& config, std::size_t r, const ReplicaContext& ctx);
  std::size_t samples() const override { return targets_.size(); }
  void advance_to_sample(std::size_t i, const Between& between) override;
  void sample(std::size_t i, ReplicaResult& result) override;
  void finish(ReplicaResult& result) override;
  double time() const override { return gas_.time(); }
  int loop_threads() const override {
    return gas_.blocks() > 1 ? static_cast<int>(std::min<std::size_t>(gas_.threads(), gas_.blocks())) : 1;
  }
  std::uint64_t events() const override { return gas_.counters().events; }
  double fraction_done() const override {
    const double f = time_driven_ ? gas_.time() / targets_.back()
                                  : static_cast<double>(gas_.counters().events) / std::max(1.0, final_events_);
    return std::min(f, 0.999);
  }
  void save(state::Record& r) const override { gas_.save(r); }
  void restore(const state::Record& r) override {
    gas_.restore(r);
    // As Gas::restore_gas: the clusters' kinetic energy per initial monomer is bounded too.
    const double energy = gas_.measure().kinetic_energy / initial_monomers_;
    if (!(energy <= energy_limit_))
      throw state::StateError("the clusters' kinetic energy is beyond 1e30 times the initial temperature per monomer, "
                              "which no run reaches");
  }
  // No snapshots of clusters (io/config refuses snapshot_times with &agg_frag).
  double sample_time(std::size_t) const override { return std::numeric_limits<double>::infinity(); }
  void advance_to_time(double, const Between&) override { throw std::logic_error("no snapshots of &agg_frag"); }
  void take_snapshot(ReplicaResult&) const override { throw std::logic_error("no snapshots of &agg_frag"); }

 private:
  bool time_driven_;
  std::vector<double> targets_;  ///< sample points: times, or collisions per initial monomer 2 x events / N_0
  double initial_monomers_, final_events_;
  double energy_limit_;  ///< of a restored gas, per initial monomer (restore())
  agg_frag::Gas gas_;
  std::size_t initial_blocks_ = 1;  ///< the blocks of the first step (their number falls as clusters stick)
};

Clusters::Clusters(const io::config::Config& config, std::size_t r, const ReplicaContext& ctx)
    : time_driven_(config.dsmc.t_end.has_value()),
      targets_(time_driven_ ? config.sample_times() : config.sample_collisions()),
      initial_monomers_(static_cast<double>(config.dsmc.n_particles)),
      final_events_(time_driven_ ? 0.0 : std::ceil(targets_.back() * initial_monomers_ / 2.0)),
      energy_limit_(kinetic_energy_limit * largest_initial_temperature(config)),
      gas_(agg_frag_model(config), static_cast<std::size_t>(config.dsmc.n_particles), config.initial.temperature[0],
           initial_distribution(config),
           rng::make_stream(static_cast<std::uint64_t>(config.dsmc.seed), r, rng::Purpose::initial_state),
           rng::make_stream(static_cast<std::uint64_t>(config.dsmc.seed), r, rng::Purpose::collisions),
           config.dsmc.step_fraction, set_up_check(ctx)) {
  if (config.dsmc.block_size == 0 || config.dsmc.n_particles < 2 * config.dsmc.block_size)
    note_idle_threads(ctx, "this aggregation run has no cache blocks (they need N >= 2 block_size clusters)");
  // Cache blocks (agg_frag.hpp, "Cache blocks"): while N >= 2 block_size clusters, on the block threads.
  gas_.use_blocks(static_cast<std::size_t>(config.dsmc.block_size), ctx.block_threads);
  initial_blocks_ = gas_.blocks();
  gas_.set_stop_flag(ctx.options.interrupt);
}

void Clusters::advance_to_sample(std::size_t i, const Between& between) {
  const double t_target = time_driven_ ? targets_[i] : std::numeric_limits<double>::infinity();
  const std::uint64_t event_target =
      time_driven_ ? std::numeric_limits<std::uint64_t>::max()
                   : static_cast<std::uint64_t>(std::ceil(targets_[i] * initial_monomers_ / 2.0));
  // Chunks of events, as the free gas's: interrupts, progress and checkpoints at fixed events.
  constexpr std::uint64_t kChunk = 1u << 19;
  for (;;) {
    const std::uint64_t done = gas_.counters().events;
    // With blocks a chunk is one blocked step (at most 2^24 candidates, its own event margin).
    const bool blocked = gas_.blocks() > 1;
    const std::uint64_t chunk_end = blocked || event_target - done <= kChunk ? event_target : done + kChunk;
    // ... and at most ~1e5 candidates (chunk_end_time); one cluster left or nothing moving: the
    // gas's advance() goes straight to the target.
    const bool still = gas_.clusters() < 2 || !(gas_.candidate_rate() > 0.0);
    const double t_stop = still     ? t_target
                          : blocked ? std::min(t_target, gas_.block_step_end())
                                    : chunk_end_time(gas_.time(), gas_.counters().candidates, t_target);
    gas_.advance(t_stop, chunk_end);
    if (gas_.time() >= t_target || gas_.counters().events >= event_target) break;
    between();
  }
  if (!time_driven_ && gas_.counters().events < event_target)
  {
    char text[320];  // (the clock of a gas with nothing left to collide stands at infinity: not shown)
    std::snprintf(text, sizeof text,
                  "the gas aggregated into one cluster after %.6g collisions per monomer, before "
                  "collisions_per_particle = %.6g was reached (its sample at %.6g); give t_end instead",
                  2.0 * static_cast<double>(gas_.counters().events) / initial_monomers_, targets_.back(), targets_[i]);
    throw UnreachableTarget(text);
  }
}

void Clusters::sample(std::size_t i, ReplicaResult& result) {
  const agg_frag::Measurement m = gas_.measure();
  const auto& counters = gas_.counters();
  result.add(sample_row("number", i), m.number.size(), m.number);
  result.add(sample_row("size_energy", i), m.energy.size(), m.energy);
  result.add("total_temperature", 1, {2.0 / 3.0 * m.kinetic_energy / m.clusters});  // per cluster, \ref af_observables "docs/agg-frag.md"
  result.add("kinetic_energy", 1, {m.kinetic_energy / initial_monomers_});
  check_energy_does_not_grow(result, "kinetic_energy");
  result.add("mean_size", 1, {initial_monomers_ / m.clusters});
  result.add("monomer_fraction", 1, {m.number[0] / initial_monomers_});
  result.add("collisions", 1, {static_cast<double>(counters.events)});
  result.add("aggregations", 1, {static_cast<double>(counters.aggregations)});
  result.add("fragmentations", 1, {static_cast<double>(counters.fragmentations)});
  result.add("dissipated_energy", 1, {counters.dissipated / initial_monomers_});
  result.add("collisions_per_particle", 1, {2.0 * static_cast<double>(counters.events) / initial_monomers_});
  result.add("time", 1, {gas_.time()});
}

void Clusters::finish(ReplicaResult& result) {
  pad_size_rows(result, targets_.size());
  result.events = gas_.counters().events;
  result.mean_step = gas_.mean_step();
  result.cache_blocks = initial_blocks_;
  result.block_draw = static_cast<std::uint64_t>(initial_blocks_ > 1 ? collide::Collider::BlockDraw::clusters
                                                                     : collide::Collider::BlockDraw::unblocked);
}

std::unique_ptr<Engine> make_engine(const io::config::Config& config, std::size_t r, const ReplicaContext& ctx) {
  if (config.has_agg_frag) return std::make_unique<Clusters>(config, r, ctx);
  if (config.staged()) return std::make_unique<ForcedGas>(config, r, ctx);
  return std::make_unique<FreeGas>(config, r, ctx);
}

/// A checkpoint is read, not trusted: every real it holds must be finite (a damaged file must not run on NaN).
void require_finite(const state::Record& record) {
  for (const auto& [name, values] : record.reals)
    for (double x : values)
      if (!std::isfinite(x)) throw state::StateError("'" + name + "' holds a value that is not finite");
}

}  // namespace

ReplicaResult run_replica(const io::config::Config& config, std::size_t replica, const state::Record* resume,
                          ReplicaContext& ctx) {
  const std::unique_ptr<Engine> engine = make_engine(config, replica, ctx);
  ReplicaResult result;
  std::uint64_t next_sample = 0;
  if (resume) {
    try {
      require_finite(*resume);
      result = load_result(*resume);
      next_sample = resume->integer("replica/next_sample");
      // Every sample adds one row of "time": a next_sample that disagrees with them was forged.
      const auto times = result.rows.find("time");
      const std::size_t taken = times == result.rows.end() ? 0 : times->second.second.size();
      if (next_sample > engine->samples() || next_sample != taken)
        throw state::StateError("'replica/next_sample' is " + std::to_string(next_sample) + " but the record holds " +
                                std::to_string(taken) + " samples of " + std::to_string(engine->samples()));
      check_rows(result, taken, false);
      engine->restore(*resume);
    } catch (const state::StateMismatch& e) {  // exit status 2 with --restart's name (simulation.hpp)
      throw RestartError(std::string("the checkpoint does not fit this build: ") + e.what());
    } catch (const state::StateError& e) {
      throw RestartError(std::string("the checkpoint is damaged: ") + e.what());
    } catch (const std::invalid_argument& e) {  // (a state the modules refuse: a zero stream, a bound out of range)
      throw RestartError(std::string("the checkpoint is damaged: ") + e.what());
    }
  } else {
    engine->start();
  }
  std::uint64_t reported = engine->events();
  const auto report = [&](double fraction) {
    const std::uint64_t events = engine->events();
    const auto it = result.rows.find("total_temperature");  // T at the last sample, for the progress line
    const double temperature = it == result.rows.end() || it->second.second.empty() ? std::nan("") : it->second.second.back();
    ctx.progress.update(ctx.slot, fraction, engine->time(), events - reported, temperature);
    reported = events;
  };
  const std::function<state::Record()> snapshot = [&] {
    state::Record record;
    save(result, record);
    record.put_integer("replica/next_sample", next_sample);
    engine->save(record);
    return record;
  };
  // A stop flag ends an advance early (collide.hpp set_stop_flag), so every safe point looks at the
  // flag first: an unfinished advance or stage is never checkpointed, and never written.
  const auto safe_point = [&] {
    if (interrupted(ctx)) throw Interrupted();
    ctx.safe_point(snapshot);
  };
  const Engine::Between between = [&] {
    if (interrupted(ctx)) throw Interrupted();
    report(std::min(engine->fraction_done(), 0.999));
    safe_point();
  };
  const std::size_t n_samples = engine->samples();
  const std::uint64_t resumed_at = next_sample;
  const auto& snapshot_times = config.output.snapshot_times;
  // Snapshots taken so far: the rows the result holds (also after a restart from a checkpoint).
  const auto taken = result.rows.find("snapshot_time");
  std::size_t next_snapshot = taken == result.rows.end() ? 0 : taken->second.second.size() / 2;
  for (; next_sample < n_samples; ++next_sample, safe_point()) {
    if (interrupted(ctx)) throw Interrupted();
    const auto t0 = Clock::now();
    for (; next_snapshot < snapshot_times.size() && snapshot_times[next_snapshot] <= engine->sample_time(next_sample);
         ++next_snapshot) {  // the snapshots up to this sample's time (io/snapshot.hpp)
      engine->advance_to_time(snapshot_times[next_snapshot], between);
      engine->take_snapshot(result);
      safe_point();
    }
    engine->advance_to_sample(next_sample, between);
    result.collide_seconds += std::chrono::duration<double>(Clock::now() - t0).count() * engine->loop_threads();
    engine->sample(next_sample, result);
    if (resume && next_sample == resumed_at) {
      // Which rows a replica writes depends on the input: a row missing from the record shows in the
      // first sample after it (one row where the others have all), not only at the end of the run.
      try {
        check_rows(result, next_sample + 1, false);
      } catch (const state::StateError& e) {
        throw RestartError(std::string("the checkpoint is damaged: ") + e.what());
      }
    }
    report(next_sample + 1 == n_samples ? 1.0 : std::min(engine->fraction_done(), 0.999));
  }
  engine->finish(result);
  return result;
}

}  // namespace gdsmc::simulation
