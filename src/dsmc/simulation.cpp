#include "dsmc/simulation.hpp"

#include <chrono>
#include <cmath>
#include <cstdint>
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
  const auto viscoelastic_beta = config.viscoelastic_beta();
  const bool reduced = s <= 2;  // v0 and Phi_i(v*) are defined for one or two species (seed 003)
  const auto reduced_bins = static_cast<std::size_t>(config.output.reduced_bins);
  const double reduced_range = config.output.reduced_range;

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
                               config.dsmc.step_fraction, viscoelastic_beta ? &*viscoelastic_beta : nullptr);
    // Displacements (seed 001 eq 15) from t = 0, from msd_start_time, or from the first sample
    // with T <= msd_start_temperature.
    const bool track = config.output.track_displacements;
    const bool start_at_zero = track && !config.output.msd_start_time && !config.output.msd_start_temperature;
    bool tracking = false;
    if (start_at_zero) {
      particles::start_tracking(sys, 0.0);
      tracking = true;
    }
    double msd_start = 0.0;
    // The HCS part of this replica: samples past scaling_start collisions per particle.
    std::vector<double> speed_counts, c_sum(s, 0.0), share_sum(s, 0.0);
    double scaling_samples = 0.0, t_first = 0.0, t_last = 0.0, temp_first = 0.0, temp_last = 0.0;
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
      if (track && !tracking && config.output.msd_start_time && *config.output.msd_start_time <= t_target) {
        collider.advance(*config.output.msd_start_time, event_target);  // stop exactly at the start
        if (collider.time() >= *config.output.msd_start_time) {
          particles::start_tracking(sys, collider.time());
          tracking = true;
          msd_start = collider.time();
        }
      }
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
      if (s <= kMaxPairSpecies) {  // S(S+1)/2 columns: only for mixtures of a few species
        std::vector<double> pairs;
        pairs.reserve(n_pairs);
        for (std::size_t k = 0; k < s; ++k)
          for (std::size_t j = k; j < s; ++j)
            pairs.push_back(static_cast<double>(counters.pair_events[k * s + j]));
        column("collisions_pair", n_pairs).add(r, pairs);
      }
      column("time", 1).add(r, {collider.time()});
      if (s <= kMaxPairSpecies)  // one histogram per species: only for a few species
        column("velocity_histogram", s * bins).add(r, sample::velocity_histogram(mix, sys, m, bins, range));
      if (track && !tracking && config.output.msd_start_temperature &&
          m.total_temperature <= *config.output.msd_start_temperature) {
        particles::start_tracking(sys, collider.time());
        tracking = true;
        msd_start = collider.time();
      }
      if (track) {
        column("msd", s).add(r, tracking ? sample::mean_squared_displacement(sys, collider.time())
                                         : std::vector<double>(s, 0.0));
      }
      const double per_particle = 2.0 * static_cast<double>(counters.events) / static_cast<double>(n_total);
      if (reduced && i > 0 && per_particle >= config.output.scaling_start) {
        sample::add_reduced_speeds(mix, sys, m, sample::reduced_velocity_scale(mix, m.total_temperature),
                                   reduced_bins, reduced_range, speed_counts);
        for (std::size_t k = 0; k < s; ++k) {
          c_sum[k] += m.sonine_c[k];
          share_sum[k] += m.temperature[k] / m.total_temperature;
        }
        if (scaling_samples == 0.0) {
          t_first = collider.time();
          temp_first = m.total_temperature;
        }
        t_last = collider.time();
        temp_last = m.total_temperature;
        scaling_samples += 1.0;
      }

      const double rate = result.collide_seconds > 0
                              ? static_cast<double>(result.events + counters.events) / result.collide_seconds
                              : 0.0;
      progress.update(fraction_done(r, collider), where(r), collider.time(), rate);
    }
    result.events += collider.counters().events;
    mean_step_sum += collider.mean_step();
    if (track) column("msd_start", 1).add(r, {tracking ? msd_start : -1.0});
    if (scaling_samples >= 2.0 && t_last > t_first) {
      // Rows are added for the replicas that reached the scaling regime, one after another.
      const std::size_t row = result.observables["reduced_distribution"].values.size();
      column("reduced_distribution", s * reduced_bins)
          .add(row, sample::reduced_distribution(speed_counts, std::vector<double>(counts.begin(), counts.end()),
                                                 scaling_samples, reduced_bins, reduced_range));
      for (auto& c : c_sum) c /= scaling_samples;
      for (auto& x : share_sum) x /= scaling_samples;
      column("reduced_sonine_c", s).add(row, c_sum);
      column("reduced_temperature_share", s).add(row, share_sum);
      // zeta* = zeta/(n sigma_12^2 v0) with zeta = 2 sqrt(T) d(T^-1/2)/dt, constant in the HCS
      // (ERRATA §3, §6): zeta* = 2 slope / (n sigma_12^2 sqrt(2 (m1 + m2)/(m1 m2))).
      const double slope = (1.0 / std::sqrt(temp_last) - 1.0 / std::sqrt(temp_first)) / (t_last - t_first);
      const double sigma12 = mix.contact_distance(0, s - 1);
      const double v0_unit = sample::reduced_velocity_scale(mix, 1.0);
      column("reduced_cooling_rate", 1)
          .add(row, {2.0 * slope / (mix.total_density() * sigma12 * sigma12 * v0_unit)});
    }
  }
  result.mean_step = mean_step_sum / static_cast<double>(replicas);
  return result;
}

/// The HCS distributions of one point (seed 003 sec. 4): Phi_i(v*), the deviation Delta_i(v*) of
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
  const double sigma12 = mix.contact_distance(0, s - 1);
  for (std::size_t k = 0; k < s; ++k) {
    const std::size_t j = s - 1 - k;  // the other species (itself for one species)
    const double mu_jk = mix.mass[j] / (mix.mass[k] + mix.mass[j]);
    const double lambda = 1.0 / (share[k] * mu_jk);  // lambda_i = T/(T_i mu_ji), ERRATA §6
    double beta = 0.0;  // seed 003 eq 20, ERRATA §6
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
                                     "seed 003 eq 27, g = G_i of eq 30 (measured c_i, lambda_i, zeta*)"));
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
    if (name == "velocity_histogram" || name == "msd_start" || name.rfind("reduced_", 0) == 0) continue;
    io::h5md::Series series;
    series.time = time_mean;
    series.step = step;
    series.value = a.mean();
    series.columns = a.columns;
    series.error = a.standard_error();
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
  if (acc.count("reduced_distribution")) write_reduced(writer, root, config, result);
  if (acc.count("msd")) {
    // Each replica's start (-1 if it never started); the mean is the time origin of msd.
    const auto starts = acc["msd_start"].values;
    std::vector<double> start_times;
    for (const auto& row : starts) start_times.push_back(row[0]);
    writer.write_dataset(root + "/msd/start_time", start_times, {start_times.size()});
    writer.write_attribute(root + "/msd", "description",
                           std::string("<|R_k|^2> per species, displacement since start_time (seed 001 eq 15)"));
  }
  writer.write_attribute(root + "/temperature", "description",
                         std::string("partial temperatures T_k = m_k <|v-u|^2>/3, columns = species"));
  writer.write_attribute(root + "/sonine_c", "description",
                         std::string("c_k = 2[(3/5)<v^4>/<v^2>^2 - 1] (seed 003 eq 17)"));
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
