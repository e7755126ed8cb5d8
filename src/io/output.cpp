// The layout of one point's results (output.hpp, \ref output_h5md "docs/output.md").
#include "io/output.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "io/units.hpp"

namespace gdsmc::io::output {

namespace {

using Accumulators = std::map<std::string, observables::Accumulator>;

/// One series of `acc` under root/name, with the table's unit and description.
void write_series(h5md::Writer& writer, const std::string& root, const std::string& name,
                  const observables::Accumulator& a, const std::vector<long long>& step, const std::vector<double>& time) {
  h5md::Series series;
  series.time = time;
  series.step = step;
  series.value = a.mean();
  series.columns = a.columns;
  series.error = a.standard_error();
  series.time_unit = units::kTime;
  series.value_unit = units::of_observable(name);
  writer.write_observable(root + "/" + name, series);
  writer.write_attribute(root + "/" + name, "description", std::string(observables::find(name).description));
}

/// velocity_histogram: one series per species (value Nt x bins) and the bin edges.
void write_histograms(h5md::Writer& writer, const std::string& root, const config::Config& config,
                      const observables::Accumulator& a, const std::vector<long long>& step, const std::vector<double>& time) {
  const auto s = static_cast<std::size_t>(config.system.n_species);
  const auto bins = static_cast<std::size_t>(config.output.histogram_bins);
  const double range = config.output.histogram_range;
  const auto mean = a.mean();
  const auto error = a.standard_error();
  for (std::size_t k = 0; k < s; ++k) {
    h5md::Series series;
    series.time = time;
    series.step = step;
    series.columns = bins;
    series.time_unit = units::kTime;
    series.value_unit = units::of_observable("velocity_histogram");
    for (std::size_t i = 0; i < time.size(); ++i)
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
  writer.write_unit(root + "/velocity_histogram/bin_edges", units::kDimensionless);  // v/sqrt(T_k/m_k)
  writer.write_attribute(root + "/velocity_histogram", "description",
                         std::string(observables::find("velocity_histogram").description));
}

/// reduced_distribution/ (\ref son_reduced_distributions "docs/sonine.md"): Phi_i, Delta_i, G_i of each species and their errors.
void write_reduced(h5md::Writer& writer, const std::string& root, const config::Config& config, const Accumulators& acc,
                   const observables::ReducedDistributions& r) {
  const std::string group = root + "/reduced_distribution";
  const std::size_t bins = r.edges.size() - 1;
  writer.write_dataset(group + "/bin_edges", r.edges, {bins + 1});
  writer.write_unit(group + "/bin_edges", units::kDimensionless);  // v* = |v - u|/v0
  for (std::size_t k = 0; k < r.species.size(); ++k) {
    const auto& s = r.species[k];
    const std::string sp = group + "/species_" + std::to_string(k + 1);
    // Distributions of the reduced speed v* and their errors: dimensionless.
    for (const auto& [name, values] : std::vector<std::pair<const char*, const std::vector<double>*>>{
             {"value", &s.value}, {"error", &s.error}, {"delta", &s.delta}, {"delta_error", &s.delta_error},
             {"g", &s.g}, {"g_error", &s.g_error}}) {
      if (values->empty()) continue;  // (the errors, with one replica)
      writer.write_dataset(sp + "/" + name, *values, {bins});
      writer.write_unit(sp + "/" + name, units::kDimensionless);
    }
    writer.write_attribute(sp, "sonine_c", s.sonine_c);
    writer.write_attribute(sp, "lambda", s.lambda);
    writer.write_attribute(sp, "tail_beta", s.tail_beta);
  }
  const auto& zeta = acc.at("reduced_cooling_rate");
  writer.write_attribute(group, "cooling_rate_reduced", zeta.mean()[0]);
  if (const auto e = zeta.standard_error(); !e.empty()) writer.write_attribute(group, "cooling_rate_reduced_error", e[0]);
  writer.write_attribute(group, "replicas", static_cast<long long>(acc.at("reduced_distribution").values.size()));
  writer.write_attribute(group, "scaling_start", config.output.scaling_start);
  writer.write_attribute(group, "description",
                         std::string("Phi_i(v*), v* = |v - u|/v0, v0 = sqrt(2T(m1+m2)/(m1 m2)), averaged over the "
                                     "samples past scaling_start collisions per particle; delta = Delta_i of "
                                     "Montanero and Garzo 2002 eq 27, g = G_i of eq 30 (measured c_i, lambda_i, zeta*); docs/sonine.md"));
}

/// scaling_state/ (docs/output.md): c_k and T_k/T averaged over each replica's samples past
/// scaling_start, then over the replicas, with the standard error over the replicas. Written when every
/// replica has such samples.
void write_scaling_state(h5md::Writer& writer, const std::string& root, const config::Config& config,
                         const Accumulators& acc) {
  if (!acc.count("scaling_sonine_c") || !acc.count("scaling_temperature_share") || !acc.count("time")) return;
  const std::size_t replicas = acc.at("time").values.size();
  for (const char* name : {"scaling_sonine_c", "scaling_temperature_share"}) {
    const auto& a = acc.at(name);
    if (a.values.size() != replicas) return;
    for (const auto& v : a.values)
      if (v.size() != a.columns) return;
  }
  const std::string group = root + "/scaling_state";
  const std::size_t s = acc.at("scaling_sonine_c").columns;
  for (const auto& [name, dataset] : std::vector<std::pair<std::string, std::string>>{
           {"scaling_sonine_c", "sonine_c"}, {"scaling_temperature_share", "temperature_over_mean"}}) {
    writer.write_dataset(group + "/" + dataset, acc.at(name).mean(), {s});
    writer.write_unit(group + "/" + dataset, units::kDimensionless);
    const auto error = acc.at(name).standard_error();
    if (!error.empty()) {
      writer.write_dataset(group + "/" + dataset + "_error", error, {s});
      writer.write_unit(group + "/" + dataset + "_error", units::kDimensionless);
    }
  }
  writer.write_attribute(group, "replicas", static_cast<long long>(replicas));
  writer.write_attribute(group, "scaling_start", config.output.scaling_start);
  writer.write_attribute(group, "description",
                         std::string("c_k and T_k/T of each replica averaged over its samples past scaling_start "
                                     "collisions per particle, then over the replicas; *_error: standard error "
                                     "over the replicas (docs/output.md)"));
}

/// The per-replica values beside the series: the viscosity's time averages, the displacements' starts.
void write_per_replica(h5md::Writer& writer, const std::string& root, const config::Config& config, const Accumulators& acc) {
  if (acc.count("shear_viscosity_average")) {
    // One value per replica: the mean of eta/eta_0 over its samples from average_from on.
    const auto& a = acc.at("shear_viscosity_average");
    const std::string g = root + "/shear_viscosity";
    writer.write_attribute(g, "time_average", a.mean().at(0));
    if (const auto e = a.standard_error(); !e.empty()) writer.write_attribute(g, "time_average_error", e.at(0));
    writer.write_attribute(g, "average_from", config.shear.average_from.value_or(0.5 * *config.dsmc.t_end));
    writer.write_attribute(g, "replicas_averaged", static_cast<long long>(a.values.size()));
    if (acc.count("shear_viscosity_kinetic_average")) {
      const auto& k = acc.at("shear_viscosity_kinetic_average");
      writer.write_attribute(g, "time_average_kinetic", k.mean().at(0));
      if (const auto e = k.standard_error(); !e.empty()) writer.write_attribute(g, "time_average_kinetic_error", e.at(0));
    }
  }
  if (acc.count("shear_state_average")) {
    // Each replica's time average of a* and P_ij/(n T) (the steady shear flow), its mean and SE over replicas.
    const auto& a = acc.at("shear_state_average");
    const std::string g = root + "/shear_state";
    writer.write_dataset(g + "/value", a.mean(), {a.columns});
    writer.write_unit(g + "/value", units::kDimensionless);
    if (const auto e = a.standard_error(); !e.empty()) {
      writer.write_dataset(g + "/error", e, {a.columns});
      writer.write_unit(g + "/error", units::kDimensionless);
    }
    writer.write_attribute(g, "columns", std::string("reduced_shear_rate pxx pyy pzz pxy"));
    writer.write_attribute(g, "average_from", config.shear.average_from.value_or(0.5 * *config.dsmc.t_end));
    writer.write_attribute(g, "replicas", static_cast<long long>(a.values.size()));
    writer.write_attribute(g, "description",
                           std::string("each replica's time average from average_from on of a* = a eta_0(T)/(n T) and "
                                       "P_ij/(n T), T = tr P^k/(3 n), at the middle of the streaming jump; error: "
                                       "standard error over the replicas (docs/output.md)"));
  }
  if (acc.count("msd_start")) {
    // Each replica's start (-1 if it never started); the mean is the time origin of msd.
    std::vector<double> start_times;
    for (const auto& row : acc.at("msd_start").values) start_times.push_back(row[0]);
    writer.write_dataset(root + "/msd/start_time", start_times, {start_times.size()});
    writer.write_unit(root + "/msd/start_time", units::kTime);
  }
}

}  // namespace

void write_point(h5md::Writer& writer, const std::string& root, const config::Config& config, const Point& point) {
  const Accumulators& acc = point.observables;
  const std::vector<double> time_mean = acc.at("time").mean();
  const std::size_t n_samples = time_mean.size();
  // H5MD `step` (docs/output.md "The H5MD file"): an integer step of the simulation itself, the
  // cumulative collision events of a replica up to the sample (the observable `collisions`), its mean
  // over the replicas rounded to the nearest integer; `time` is the simulation time.
  const std::vector<double> events = acc.at("collisions").mean();
  std::vector<long long> step(n_samples);
  for (std::size_t i = 0; i < n_samples; ++i) step[i] = i < events.size() ? std::llround(events[i]) : 0;
  for (const auto& [name, a] : acc) {
    if (name == "velocity_histogram") {
      write_histograms(writer, root, config, a, step, time_mean);
    } else if (observables::find(name).reduction == observables::Reduction::series) {
      write_series(writer, root, name, a, step, time_mean);
    }
  }
  if (point.cluster_temperature) {  // &agg_frag: T_k of each size, a ratio of the replicas' sums
    h5md::Series temperature;
    temperature.time = time_mean;
    temperature.step = step;
    temperature.columns = acc.at("number").columns;
    temperature.time_unit = units::kTime;
    temperature.value_unit = units::of_observable("temperature");
    temperature.value = point.cluster_temperature->value;
    temperature.error = point.cluster_temperature->error;
    writer.write_observable(root + "/temperature", temperature);
    writer.write_attribute(root + "/temperature", "description", std::string(observables::find("temperature").description));
  }
  if (point.reduced) write_reduced(writer, root, config, acc, *point.reduced);
  write_scaling_state(writer, root, config, acc);
  write_per_replica(writer, root, config, acc);
}

}  // namespace gdsmc::io::output
