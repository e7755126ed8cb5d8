// The checkpoint file of a rank (checkpoint.hpp, \ref output_checkpoint "docs/output.md").
#include "run/checkpoint.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>
#include <stdexcept>

#include "io/h5md.hpp"
#include "io/namelist.hpp"
#include "io/version.hpp"
#include "run/simulation.hpp"

namespace gdsmc::simulation {

std::string rank_file(const std::string& path, int rank) {
  if (rank == 0) return path;
  std::string stem = path;
  if (stem.size() > 3 && stem.compare(stem.size() - 3, 3, ".h5") == 0) stem.resize(stem.size() - 3);
  return stem + ".rank" + std::to_string(rank) + ".h5";
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

}  // namespace

namespace {

/// What a checkpoint file holds, as load() reads it, and the checksum of that content.
struct FileContent {
  std::map<std::size_t, state::Record> done, running;
  std::string fingerprint, stored_checksum, checksum;
  double ranks = 0.0, layout = 0.0;
};

FileContent read_content(const std::string& file) {
  namespace h5 = io::h5md;
  FileContent c;
  ContentHash hash;
  if (std::error_code ec; !std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error("checkpoint '" + file + "': " +
                             (std::filesystem::exists(file, ec) ? "not a file" : "no such file"));
  try {
    c.stored_checksum = h5::read_string_attribute(file, "/checkpoint", "checksum");
    for (const char* kind : {"done", "running"}) {
      const std::string listed = h5::read_string_attribute(file, "/checkpoint", std::string(kind) + "_units");
      hash.add(listed);
      std::istringstream units(listed);
      for (std::size_t u; units >> u;) {
        const std::string group = "/checkpoint/" + std::string(kind) + "/unit_" + std::to_string(u);
        state::Record snap;
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
        (std::string(kind) == "done" ? c.done : c.running)[u] = std::move(snap);
      }
    }
    c.fingerprint = h5::read_string_attribute(file, "/checkpoint", "fingerprint");
    hash.add(c.fingerprint);
    c.ranks = h5::read_double_attribute(file, "/checkpoint", "ranks");
    hash.add(std::vector<double>{c.ranks});
    const auto format = h5::read_dataset(file, "/checkpoint/format").data;
    c.layout = format.size() == 1 ? format[0] : -1.0;
  } catch (const std::exception& e) {
    throw std::runtime_error("checkpoint '" + file + "' is damaged or is not a checkpoint of granular-dsmc: " +
                             e.what());
  }
  c.checksum = hash.hex();
  return c;
}

}  // namespace

std::string content_checksum(const std::string& file) { return read_content(file).checksum; }

std::string override_options(const std::vector<std::string>& overrides) {
  std::string shown;
  for (const std::string& o : overrides) shown += (shown.empty() ? "--set " : " --set ") + io::namelist::shell_word(o);
  return shown;
}

std::string fingerprint_difference(const std::string& stored, const std::string& current) {
  const std::string marker = fingerprint_overrides_marker;
  const auto split = [&](const std::string& f) {
    const std::size_t at = f.rfind(marker);  // (the last: a namelist may hold the marker's text as a line)
    return at == std::string::npos ? std::pair{f, std::string()} : std::pair{f.substr(0, at), f.substr(at + marker.size())};
  };
  const auto [stored_text, stored_overrides] = split(stored);
  const auto [current_text, current_overrides] = split(current);
  const auto options = [](const std::string& lines) {
    std::vector<std::string> overrides;
    std::size_t start = 0;
    for (std::size_t end; (end = lines.find('\n', start)) != std::string::npos; start = end + 1)
      overrides.push_back(lines.substr(start, end - start));
    return overrides.empty() ? std::string("no --set or --output") : override_options(overrides);
  };
  if (stored_text != current_text || stored_overrides == current_overrides)
    return stored_overrides == current_overrides ? "the namelist text differs"
                                                 : "the namelist text differs, and the options: it was written with " +
                                                       options(stored_overrides) + ", this run has " +
                                                       options(current_overrides);
  const bool output = (stored_overrides + current_overrides).find("output:file=") != std::string::npos;
  return "it was written with " + options(stored_overrides) + ", this run has " + options(current_overrides) +
         (output ? " (--output PATH is --set output:file='PATH')" : "");
}

void CheckpointStore::load(const std::string& file) {
  namespace h5 = io::h5md;
  FileContent content = read_content(file);
  auto& done = content.done;
  auto& running = content.running;
  const std::string& fingerprint = content.fingerprint;
  const std::string& stored_checksum = content.stored_checksum;
  const double ranks = content.ranks, layout = content.layout;
  const std::string hash_hex = content.checksum;
  if (hash_hex != stored_checksum)
    throw std::runtime_error("checkpoint '" + file + "' is damaged: its content does not match the checksum "
                             "written with it (a partial copy, or a disk error)");
  if (fingerprint != fingerprint_)
    throw std::runtime_error("checkpoint '" + file + "' was written for a different input: " +
                             fingerprint_difference(fingerprint, fingerprint_));
  if (layout != 1.0 && layout != static_cast<double>(state::layout)) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", layout);
    throw std::runtime_error("checkpoint '" + file + "' has layout " + text + " (/checkpoint/format); this build reads "
                             "layouts 1 and " + std::to_string(state::layout) + ": resume it with the granular-dsmc "
                             "that wrote it, or start the run again");
  }
  if (static_cast<int>(ranks) != ranks_)
    throw std::runtime_error("checkpoint '" + file + "' was written by a run with a different number of MPI ranks");
  // The layout of the records (/checkpoint/format, outside the checksum): 1 is translated as it is read.
  if (layout == 1) {
    for (auto& [u, snap] : done) upgrade_layout_1(snap);
    for (auto& [u, snap] : running) upgrade_layout_1(snap);
  }
  for (auto& [u, snap] : done) done_[u] = load_result(snap);
  running_ = std::move(running);
  resumed_path_ = file;
  try {
    resumed_token_ = h5::read_string_attribute(file, "/checkpoint", "run");
  } catch (const std::exception&) {  // written before the tokens
    resumed_token_.clear();
  }
}

const ReplicaResult* CheckpointStore::finished_result(std::size_t unit) const {
  const auto it = done_.find(unit);
  return it == done_.end() ? nullptr : &it->second;
}

const state::Record* CheckpointStore::resume_point(std::size_t unit) const {
  const auto it = running_.find(unit);
  return it == running_.end() ? nullptr : &it->second;
}

std::uint64_t CheckpointStore::restored_events() const {
  std::uint64_t events = 0;
  for (const auto& [unit, result] : done_) events += result.events;
  // A unit in progress counts its events in its collider's (or cluster gas's) state: result/events is
  // written when it finishes.
  for (const auto& [unit, record] : running_)
    for (const char* name : {"collider/events", "clusters/events"})
      if (record.has_integers(name)) {  // (a damaged record is reported when its unit resumes)
        if (const auto& count = record.integer_array(name); count.size() == 1) events += count[0];
        break;
      }
  return events;
}

void CheckpointStore::finished(std::size_t unit, const ReplicaResult& result) {
  // (after an interrupt no checkpoint is written again: the copy, of a gigabyte with snapshots, is not needed)
  if (every_ <= 0.0 || (stop_ && stop_->load())) return;
  std::lock_guard<std::mutex> lock(mutex_);
  done_[unit] = result;
  running_.erase(unit);
}

void CheckpointStore::safe_point(std::size_t unit, const std::function<state::Record()>& snapshot) {
  // last_saved_[unit] is touched only by the thread running that unit.
  if (every_ <= 0.0 || std::chrono::duration<double>(Clock::now() - last_saved_[unit]).count() < every_) return;
  if (stop_ && stop_->load()) throw Interrupted();  // (not the copy of a gigabyte first)
  state::Record fresh = snapshot();  // outside the lock: other threads keep running
  std::lock_guard<std::mutex> lock(mutex_);
  running_[unit] = std::move(fresh);
  write();
  last_saved_[unit] = Clock::now();
}

std::string new_run_token() {
  std::random_device device;
  const std::uint64_t token = (static_cast<std::uint64_t>(device()) << 32) ^ device() ^
                              static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(token));
  return text;
}

bool CheckpointStore::remove() const {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path_, ec)) return false;
  std::string token;
  try {
    token = io::h5md::read_string_attribute(path_, "/checkpoint", "run");
  } catch (const std::exception&) {  // not a checkpoint, or one written before the tokens
  }
  const bool own = written_ && token == run_token_;
  const bool resumed = !resumed_path_.empty() && (token.empty() ? resumed_token_.empty() &&
                                                                      std::filesystem::equivalent(path_, resumed_path_, ec)
                                                                : token == resumed_token_);
  return (own || resumed) && std::filesystem::remove(path_, ec);
}

void CheckpointStore::write() const {
  io::h5md::Writer w(path_, "granular-dsmc", "granular-dsmc checkpoint", io::build_version());
  if (replace_any_) w.replace_any_file();
  std::string done_units, running_units;
  for (const auto& [u, result] : done_) done_units += std::to_string(u) + " ";
  for (const auto& [u, snap] : running_) running_units += std::to_string(u) + " ";
  // The checksum covers the content in the order load() reads it (ContentHash).
  ContentHash hash;
  const auto stop_if_interrupted = [this] {
    if (stop_ && stop_->load()) throw Interrupted();  // (w's destructor removes the temporary file)
  };
  auto put_unit = [&](const std::string& group, const state::Record& snap) {
    std::string reals, integers;
    for (const auto& [name, values] : snap.reals) reals += name + "\n";
    for (const auto& [name, values] : snap.integers) integers += name + "\n";
    hash.add(reals);
    hash.add(integers);
    for (const auto& [name, values] : snap.reals) {
      stop_if_interrupted();
      w.write_dataset(group + "/" + name, values, {});
      hash.add(values);
    }
    for (const auto& [name, values] : snap.integers) {
      stop_if_interrupted();
      w.write_integers(group + "/" + name, values);
      hash.add(values);
    }
    w.write_attribute(group, "reals", reals);
    w.write_attribute(group, "integers", integers);
  };
  hash.add(done_units);
  for (const auto& [u, result] : done_) {
    stop_if_interrupted();
    state::Record snap;
    save(result, snap);
    put_unit("/checkpoint/done/unit_" + std::to_string(u), snap);
  }
  hash.add(running_units);
  for (const auto& [u, snap] : running_) put_unit("/checkpoint/running/unit_" + std::to_string(u), snap);
  hash.add(fingerprint_);
  hash.add(std::vector<double>{static_cast<double>(ranks_)});
  w.write_attribute("/checkpoint", "checksum", hash.hex());
  w.write_dataset("/checkpoint/format", {static_cast<double>(state::layout)}, {});
  w.write_attribute("/checkpoint", "fingerprint", fingerprint_);
  w.write_attribute("/checkpoint", "ranks", static_cast<double>(ranks_));
  w.write_attribute("/checkpoint", "run", run_token_);
  w.write_attribute("/checkpoint", "done_units", done_units);
  w.write_attribute("/checkpoint", "running_units", running_units);
  w.write_attribute("/checkpoint", "description",
                    std::string("granular-dsmc checkpoint: finished work units (point-major replica index) "
                                "and the state of those in progress; resume with granular-dsmc FILE.nml "
                                "--restart THIS_FILE"));
  stop_if_interrupted();
  w.commit();
  written_ = true;
}


namespace {

/// Layout 1 kept related values in one positional array; `take` moves its values to names of their
/// own (values beyond the array's end, written only by later versions of layout 1, get `fallback`).
class Layout1 {
 public:
  explicit Layout1(state::Record& r) : r_(r) {}
  /// Moves the reals of `from` to the names `to` (one value each; "" skips one), removing `from`.
  void reals(const std::string& from, const std::vector<std::string>& to, std::size_t required) {
    const auto it = r_.reals.find(from);
    if (it == r_.reals.end()) return;
    const std::vector<double> v = it->second;
    r_.reals.erase(it);
    if (v.size() < required) throw state::StateError("'" + from + "' is too short for layout 1");
    for (std::size_t q = 0; q < to.size(); ++q)
      if (!to[q].empty() && q < v.size()) r_.put(to[q], v[q]);
  }
  /// The same for integers.
  void integers(const std::string& from, const std::vector<std::string>& to, std::size_t required) {
    const auto it = r_.integers.find(from);
    if (it == r_.integers.end()) return;
    const std::vector<std::uint64_t> v = it->second;
    r_.integers.erase(it);
    if (v.size() < required) throw state::StateError("'" + from + "' is too short for layout 1");
    for (std::size_t q = 0; q < to.size(); ++q)
      if (!to[q].empty() && q < v.size()) r_.put_integer(to[q], v[q]);
  }
  /// Moves the whole array `from` to `to`.
  void rename(const std::string& from, const std::string& to) {
    if (auto it = r_.reals.find(from); it != r_.reals.end()) {
      auto v = std::move(it->second);
      r_.reals.erase(it);
      r_.put(to, std::move(v));
    }
    if (auto it = r_.integers.find(from); it != r_.integers.end()) {
      auto v = std::move(it->second);
      r_.integers.erase(it);
      r_.put(to, std::move(v));
    }
  }
  /// Moves `count` reals of `from` from `first` on to the array `to` (left as they are when too short).
  void slice(const std::string& from, std::size_t first, std::size_t count, const std::string& to) {
    const auto it = r_.reals.find(from);
    if (it == r_.reals.end() || it->second.size() < first + count) return;
    r_.put(to, std::vector<double>(it->second.begin() + static_cast<std::ptrdiff_t>(first),
                                   it->second.begin() + static_cast<std::ptrdiff_t>(first + count)));
  }
  /// Sets `name` to `value` when absent.
  void default_real(const std::string& name, double value) {
    if (!r_.has(name)) r_.put(name, value);
  }
  void default_integer(const std::string& name, std::uint64_t value) {
    if (!r_.has_integers(name)) r_.put_integer(name, value);
  }

 private:
  state::Record& r_;
};

void upgrade_collider(Layout1& l) {
  l.reals("collider/clock", {"collider/time", "collider/credit", "collider/next_step_time", "collider/step_sum",
                             "collider/generator_spare", "collider/dissipated"}, 6);
  l.integers("collider/counters", {"collider/events", "collider/candidates", "collider/steps", "collider/pending_next",
                                   "collider/pending_filled", "collider/generator_has_spare", "collider/overshoots"}, 6);
  l.default_integer("collider/overshoots", 0);
  l.reals("collider/block_step_start", {"collider/step_start", "collider/step_acceptance"}, 1);
  l.default_real("collider/step_acceptance", 0.0);
  l.integers("collider/block_mode", {"collider/whole_step", "collider/step_events_start", "collider/step_candidates_start",
                                     "collider/block_sampler"}, 3);
  l.default_integer("collider/whole_step", 0);
  l.default_integer("collider/step_events_start", 0);
  l.default_integer("collider/step_candidates_start", 0);
  l.default_integer("collider/block_sampler", 2);  // unknown: the scheme's (collide.hpp State::block_lowrank)
}

void upgrade_frame(state::Record& r) {
  // collider/frame = {framed, scale, shear, Q_xx, Q_yy, Q_zz, Q_xy}; absent: no frame
  Layout1 l(r);
  const auto it = r.reals.find("collider/frame");
  if (it == r.reals.end()) {
    r.put_integer("collider/framed", 0);
    r.put("collider/frame_scale", 1.0);
    r.put("collider/frame_shear", 0.0);
    r.put("collider/moments", std::vector<double>(4, 0.0));
    return;
  }
  if (it->second.size() != 7) throw state::StateError("the velocity frame is damaged");
  const std::vector<double> f = it->second;
  r.reals.erase(it);
  r.put_integer("collider/framed", f[0] != 0.0);
  r.put("collider/frame_scale", f[1]);
  r.put("collider/frame_shear", f[2]);
  r.put("collider/moments", std::vector<double>(f.begin() + 3, f.end()));
}

void upgrade_staged(state::Record& r) {
  // staged/values = {zeta_sum, zeta_stages, window_sum, window_samples, stages, pending scale,
  // pending mean flow (3), window_kinetic_sum, last_sample_time, last_transfer (6)[, frame offset (3), momentum (3)]}
  Layout1 l(r);
  l.slice("staged/values", 6, 3, "thermostat/pending_mean_flow");
  l.slice("staged/values", 11, 6, "stages/last_transfer");
  l.slice("staged/values", 17, 3, "stages/frame_offset");
  l.slice("staged/values", 20, 3, "stages/momentum");
  l.reals("staged/values", {"thermostat/zeta_sum", "thermostat/zeta_stages", "shear/window_sum", "shear/window_samples",
                            "stages/count", "thermostat/pending_scale", "", "", "", "shear/window_kinetic_sum",
                            "stages/last_sample_time"}, 17);
  if (!r.has("stages/frame_offset")) r.put("stages/frame_offset", std::vector<double>(3, 0.0));
  if (!r.has("stages/momentum")) r.put("stages/momentum", std::vector<double>(3, 0.0));
}

}  // namespace

void upgrade_layout_1(state::Record& r) {
  Layout1 l(r);
  l.reals("result/scalars", {"result/mean_step", "result/collide_seconds"}, 2);
  if (r.has_integers("clusters/counters")) {  // an &agg_frag unit
    l.reals("clusters/clock", {"clusters/time", "clusters/credit", "clusters/next_step_time", "clusters/step_sum",
                               "clusters/dissipated", "clusters/generator_spare"}, 6);
    l.integers("clusters/counters", {"clusters/events", "clusters/aggregations", "clusters/fragmentations",
                                     "clusters/candidates", "clusters/steps", "clusters/capacity",
                                     "clusters/largest_reached", "clusters/generator_has_spare", "replica/next_sample"}, 9);
    return;
  }
  if (!r.has_integers("collider/counters")) return;  // a finished unit: its result only
  upgrade_collider(l);
  upgrade_frame(r);
  l.integers("progress/flags", {"replica/next_sample", "gas/in_sample", "gas/tracking"}, 3);
  l.reals("progress/values", {"gas/msd_start", "gas/scaling_samples", "gas/t_first", "gas/t_last", "gas/temp_first",
                              "gas/temp_last"}, 6);
  l.rename("progress/speed_counts", "gas/speed_counts");
  l.rename("progress/c_sum", "gas/c_sum");
  l.rename("progress/share_sum", "gas/share_sum");
  if (r.has("staged/values")) upgrade_staged(r);
}

}  // namespace gdsmc::simulation
