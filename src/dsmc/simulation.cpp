#include "dsmc/simulation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>

#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/sample.hpp"
#include "io/h5md.hpp"

namespace gdsmc::simulation {

namespace {

using Clock = std::chrono::steady_clock;

particles::InitialDistribution parse_distribution(const std::string& name) {
  if (name == "shell") return particles::InitialDistribution::shell;
  if (name == "cube") return particles::InitialDistribution::cube;
  return particles::InitialDistribution::maxwell;
}

/// One line on stderr, rewritten in place: replica, simulated time, collisions per second, ETA.
class ProgressLine {
 public:
  explicit ProgressLine(bool enabled) : enabled_(enabled), start_(Clock::now()) {}
  void update(double fraction_done, const std::string& where, double time, double events_per_second) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (now - last_ < std::chrono::milliseconds(200) && fraction_done < 1.0) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double eta = fraction_done > 0 ? elapsed * (1.0 - fraction_done) / fraction_done : 0.0;
    const int width = 30;
    const int filled = static_cast<int>(fraction_done * width);
    std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %s  t = %-10.4g  %.3g coll/s  ETA %.0f s  ",
                 filled, "##############################", width - filled, "", 100.0 * fraction_done,
                 where.c_str(), time, events_per_second, eta);
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_) std::fputs("\n", stderr);
  }

 private:
  bool enabled_;
  Clock::time_point start_, last_{};
};

/// What one point (all its replicas) measured.
struct PointResult {
  std::map<std::string, sample::Accumulator> observables;
  double mean_step = 0.0;
  std::uint64_t events = 0;
  double collide_seconds = 0.0;
};

/// Runs every replica of one Config. `point`/`n_points` place it in a sweep for the progress line.
PointResult run_point(const io::config::Config& config, const Options& options, ProgressLine& progress,
                      std::size_t point, std::size_t n_points) {
  const species::Mixture mix = config.mixture();
  const std::size_t s = mix.size();
  const auto counts = particles::species_counts(static_cast<std::size_t>(config.dsmc.n_particles), mix);
  std::size_t n_total = 0;
  for (auto c : counts) n_total += c;
  const auto replicas = static_cast<std::size_t>(config.dsmc.replicas);
  const auto seed = static_cast<std::uint64_t>(config.dsmc.seed);
  const auto scheme = collide::parse_scheme(config.dsmc.scheme);
  const auto bins = static_cast<std::size_t>(config.output.histogram_bins);
  const double range = config.output.histogram_range;
  const bool time_driven = config.dsmc.t_end.has_value();
  const std::vector<double> targets = time_driven ? config.sample_times() : config.sample_collisions();
  const std::size_t n_samples = targets.size();
  const std::size_t n_pairs = s * (s + 1) / 2;

  PointResult result;
  auto column = [&](const std::string& name, std::size_t columns) -> sample::Accumulator& {
    auto& a = result.observables[name];
    a.columns = columns;
    return a;
  };
  // Share of the whole run done: replicas and points so far, and within a replica the simulated
  // time over t_end, or the events over the last target.
  const double final_events = time_driven ? 0.0 : std::ceil(targets.back() * static_cast<double>(n_total) / 2.0);
  auto fraction_done = [&](std::size_t r, const collide::Collider& c) {
    const double f = time_driven ? c.time() / targets.back()
                                 : static_cast<double>(c.counters().events) / std::max(1.0, final_events);
    const double in_point = (static_cast<double>(r) + std::min(f, 1.0)) / static_cast<double>(replicas);
    return (static_cast<double>(point) + in_point) / static_cast<double>(n_points);
  };
  auto where = [&](std::size_t r) {
    std::string w = "replica " + std::to_string(r + 1) + "/" + std::to_string(replicas);
    if (n_points > 1) w = "point " + std::to_string(point + 1) + "/" + std::to_string(n_points) + "  " + w;
    return w;
  };
  double mean_step_sum = 0.0;

  for (std::size_t r = 0; r < replicas; ++r) {
    auto init_stream = rng::make_stream(seed, r, rng::Purpose::initial_state);
    particles::System sys = particles::make_system(mix, counts, config.initial.temperature,
                                                   parse_distribution(config.initial.distribution),
                                                   init_stream);
    collide::Collider collider(scheme, mix, sys, rng::make_stream(seed, r, rng::Purpose::collisions),
                               config.dsmc.step_fraction);
    for (std::size_t i = 0; i < n_samples; ++i) {
      if (options.interrupt && options.interrupt->load()) throw Interrupted();
      const auto t0 = Clock::now();
      // Advance in chunks of events so that the progress line and an interrupt are seen at least
      // every ~1e6 collisions. Stopping at an event does not change the process (collide.hpp).
      const double t_target = time_driven ? targets[i] : std::numeric_limits<double>::infinity();
      // 2 x events / N reaches the target (INTERFACE.md collisions_per_particle)
      const std::uint64_t event_target =
          time_driven ? std::numeric_limits<std::uint64_t>::max()
                      : static_cast<std::uint64_t>(std::ceil(targets[i] * static_cast<double>(n_total) / 2.0));
      constexpr std::uint64_t kChunk = 1u << 20;
      for (;;) {
        const std::uint64_t done = collider.counters().events;
        const std::uint64_t chunk_end = event_target - done > kChunk ? done + kChunk : event_target;
        const bool stopped_by_events = collider.advance(t_target, chunk_end);
        if (!stopped_by_events || collider.counters().events >= event_target) break;
        if (options.interrupt && options.interrupt->load()) throw Interrupted();
        const double elapsed = result.collide_seconds + std::chrono::duration<double>(Clock::now() - t0).count();
        progress.update(std::min(fraction_done(r, collider), 0.999), where(r), collider.time(),
                        static_cast<double>(result.events + collider.counters().events) / elapsed);
      }
      result.collide_seconds += std::chrono::duration<double>(Clock::now() - t0).count();

      const sample::Moments m = sample::measure(mix, sys);
      const auto& counters = collider.counters();
      column("temperature", s).add(r, m.temperature);
      column("total_temperature", 1).add(r, {m.total_temperature});
      column("sonine_c", s).add(r, m.sonine_c);
      column("number", s).add(r, m.number);
      column("collisions", 1).add(r, {static_cast<double>(counters.events)});
      column("collisions_per_particle", 1).add(r, {2.0 * static_cast<double>(counters.events) /
                                                   static_cast<double>(n_total)});
      std::vector<double> pairs;
      pairs.reserve(n_pairs);
      for (std::size_t k = 0; k < s; ++k)
        for (std::size_t j = k; j < s; ++j)
          pairs.push_back(static_cast<double>(counters.pair_events[k * s + j]));
      column("collisions_pair", n_pairs).add(r, pairs);
      column("time", 1).add(r, {collider.time()});
      column("velocity_histogram", s * bins)
          .add(r, sample::velocity_histogram(mix, sys, m, bins, range));

      const double rate = result.collide_seconds > 0
                              ? static_cast<double>(result.events + counters.events) / result.collide_seconds
                              : 0.0;
      progress.update(fraction_done(r, collider), where(r), collider.time(), rate);
    }
    result.events += collider.counters().events;
    mean_step_sum += collider.mean_step();
  }
  result.mean_step = mean_step_sum / static_cast<double>(replicas);
  return result;
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
  std::vector<long long> step(n_samples);
  for (std::size_t i = 0; i < n_samples; ++i) step[i] = static_cast<long long>(i);

  for (const auto& [name, a] : acc) {
    if (name == "velocity_histogram") continue;
    io::h5md::Series series;
    series.time = time_mean;
    series.step = step;
    series.value = a.mean();
    series.columns = a.columns;
    series.error = a.standard_error();
    writer.write_observable(root + "/" + name, series);
  }
  {  // one histogram observable per species: value (Nt x bins)
    const auto mean = acc["velocity_histogram"].mean();
    const auto error = acc["velocity_histogram"].standard_error();
    for (std::size_t k = 0; k < s; ++k) {
      io::h5md::Series series;
      series.time = time_mean;
      series.step = step;
      series.columns = bins;
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
  }
  writer.write_attribute(root + "/temperature", "description",
                         std::string("partial temperatures T_k = m_k <|v-u|^2>/3, columns = species"));
  writer.write_attribute(root + "/sonine_c", "description",
                         std::string("c_k = 2[(3/5)<v^4>/<v^2>^2 - 1] (seed 003 eq 17)"));
  writer.write_attribute(root + "/collisions_pair", "description",
                         std::string("cumulative events per species pair (k <= j, row-major upper triangle)"));
  writer.write_attribute(root + "/velocity_histogram", "description",
                         std::string("pdf of velocity components in units of sqrt(T_k/m_k), per species"));
}

}  // namespace

Summary run(const io::config::Config& config, const std::string& output_path, const Options& options) {
  const auto started = Clock::now();
  const std::vector<io::config::Config> points = config.sweep_points();

  // Open first: an unwritable path fails before any work is done.
  std::optional<io::h5md::Writer> writer_storage;
  try {
    writer_storage.emplace(output_path, "granular-dsmc user", "granular-dsmc", GDSMC_VERSION);
  } catch (const std::runtime_error& e) {
    throw OutputPathError(e.what());
  }
  io::h5md::Writer& writer = *writer_storage;

  ProgressLine progress(options.progress);
  std::vector<PointResult> results;
  for (std::size_t k = 0; k < points.size(); ++k)
    results.push_back(run_point(points[k], options, progress, k, points.size()));
  progress.finish();

  writer.write_parameters(config.resolved(), config.namelist_text);
  writer.write_attribute("/parameters", "source_file", config.source_file);
  std::string joined;
  for (const auto& o : config.overrides) joined += o + "\n";
  writer.write_attribute("/parameters", "overrides", joined);

  Summary summary;
  std::uint64_t events = 0;
  double collide_seconds = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    // A sweep point lives in /sweep/point_K (K from 1) with the value it applies.
    const std::string group = config.is_sweep() ? "/sweep/point_" + std::to_string(k + 1) : "";
    write_point(writer, group + "/observables", points[k], results[k]);
    if (config.is_sweep()) {
      writer.write_attribute(group, "variable", config.sweep.variable);
      writer.write_attribute(group, "value", config.sweep.values[k]);
      writer.write_attribute(group, "mean_time_step", results[k].mean_step);
    } else {
      writer.write_attribute("/parameters", "mean_time_step", results[k].mean_step);
    }
    events += results[k].events;
    collide_seconds += results[k].collide_seconds;
    summary.final_time = results[k].observables["time"].mean().back();
    summary.final_total_temperature = results[k].observables["total_temperature"].mean().back();
    summary.collisions_per_particle = results[k].observables["collisions_per_particle"].mean().back();
  }
  if (config.is_sweep()) {
    writer.write_attribute("/sweep", "variable", config.sweep.variable);
    writer.write_attribute("/sweep", "values", config.sweep.values);
  }
  writer.commit();

  summary.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  summary.events_per_second = collide_seconds > 0 ? static_cast<double>(events) / collide_seconds : 0.0;
  return summary;
}

}  // namespace gdsmc::simulation
