// granular-theory: the kinetic-theory predictions for the system of a namelist, as one JSON object
// on stdout (\ref output_theory "docs/output.md").
#include <array>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "io/config.hpp"
#include "io/namelist.hpp"
#include "io/version.hpp"
#include "analysis/json.hpp"
#include "analysis/predictions.hpp"
#include "analysis/run_checks.hpp"
#include "analysis/sweep_table.hpp"
#include "theory/smoluchowski.hpp"
#include "theory/sonine_mixture.hpp"
#include "theory/theory.hpp"
#include "theory/viscosity.hpp"

namespace {

/// The units of the keys (the unit system "namelist" of docs/output.md: time, energy, length, mass;
/// "1" dimensionless); a {time, value} pair has its time in `time`; initial_rates are events per unit volume
/// and time, except its log_monomer_rate (d ln N_1/dt).
const char* kUnitsJson =
    "\"units\": {\"time\": \"time\", \"collision_frequency\": \"time-1\", \"cooling_rate\": \"time-1\", "
    "\"temperature\": \"energy\", \"total_temperature\": \"energy\", \"rotational_temperature\": \"energy\", "
    "\"translational_temperature\": \"energy\", \"kinetic_energy\": \"energy\", \"msd\": \"length+2\", "
    "\"cooling_rate_sonine\": \"time-1\", \"tail_decay_rate\": \"1\", \"initial_rates\": \"length-3 time-1\", "
    "\"log_monomer_rate\": \"time-1\", \"other_keys\": \"1\"}";

const char* kUsage =
    "usage: granular-theory FILE.nml [--set group:variable=value]...   (or --help, --version)\n"
    "Prints the theory for the namelist's system as one JSON object on stdout:\n"
    "  n_species            S, the number of species (&agg_frag: 1, the monomer)\n"
    "  collision_frequency  [nu_k] collisions suffered per particle of species k per unit time at t=0\n"
    "  cooling_rate         [zeta_k] = sum_j xi_kj at t = 0 (docs/haff-and-mixtures.md; one species: Haff's law)\n"
    "  temperature          {time, value[t][k]} the partial-temperature ODEs (CVODE) on the sample times\n"
    "  total_temperature, collisions_per_particle   {time, value} on the same times\n"
    "  asymptotic_temperature_ratio  [T_k/T_1] at long times (mixtures, constant restitution)\n"
    "  sonine_a2, cooling_rate_sonine               one species: van Noije-Ernst a2 and (1+3a2/16) zeta\n"
    "  temperature_ratio, sonine_c, cooling_rate_reduced, tail_beta, tail_decay_rate\n"
    "                       binary mixtures: the HCS in first Sonine approximation (Montanero and Garzo 2002, docs/sonine.md)\n"
    "  hcs                  {first_sonine: {temperature_over_mean, sonine_c, cooling_rate_reduced},\n"
    "                       maxwellian: {temperature_over_mean, cooling_rate_reduced}} HCS for any number of\n"
    "                       species, constant restitution (T = sum_k n_k T_k/n; theory/sonine_mixture.hpp)\n"
    "  approximations       {key: \"maxwellian\" | \"first_sonine\" | ...} behind every key printed\n"
    "  units                {key: unit} in the unit system of the namelist (time, energy, length; other_keys: 1)\n"
    "Temperature ratios: the convention is T_k/T with T = sum_k n_k T_k/n (temperature_over_mean, as --compare);\n"
    "  asymptotic_temperature_ratio (T_k/T_1) and temperature_ratio (T_1/T_2) are kept for existing scripts.\n"
    "A sweep prints {\"sweep\": {variable, values (as written), variables, numbers (values as numbers, null for\n"
    "  a string)}, \"points\": [one object as above per point]}.\n"
    "  shear_viscosity_ratio {hcs, hss} eta/eta_0 in first Sonine (Montanero 2003, docs/shear-viscosity.md): one species\n"
    "                       (dilute or Enskog), binary mixtures (over the elastic mixture value)\n"
    "  shear_viscosity_kinetic_ratio {hcs, hss} its kinetic part, Enskog gases (Montanero 2003, Fig. 10, docs/shear-viscosity.md)\n"
    "  shear_viscosity_reduced {hcs, hss} binary mixtures: eta* = nu eta/(n T), nu = sqrt(pi) n sigma_12^2 v0,\n"
    "                       v0 = sqrt(2 T (m1 + m2)/(m1 m2)), the units of Montanero 2003, Figs. 10-12\n"
    "  shear_viscosity_kinetic_reduced {hcs, hss} its kinetic part eta_k*, Enskog binary mixtures (Fig. 10)\n"
    "  steady_shear         {temperature_over_mean, reduced_shear_rate, pressure_over_p: [xx, yy, zz, xy]} one\n"
    "                       dilute species or a dilute binary: the steady shear flow without thermostat in Grad's\n"
    "                       solution, T_k/T, a* = a eta_0/(n T) (eta_0 of the elastic gas or mixture) and P_ij/p\n"
    "                       (docs/shear-viscosity.md, \"Steady shear flow without thermostat\")\n"
    "  diffusion_coefficient_ratio  [D_k/D_1] (Bodrova and Osinsky 2024, eq. (19), docs/diffusion-msd.md); msd {time, value[t][k]} (eq 17)\n"
    "                       when &output track_displacements = .true. (not with msd_start_temperature)\n"
    "With &system roughness (rough spheres, docs/rough-spheres.md), one species: temperature is T_tr, and\n"
    "  rotational_temperature {time, value} T_rot of the Maxwellian two-temperature equations; rough_hcs\n"
    "                       {maxwellian: {theta, zeta_star}, sonine: {theta, a20, a02, a11, zeta_star} or why\n"
    "                       not} theta = T_rot/T_tr, zeta_tr/nu_M (nu_M = 4 sqrt(pi) n sigma^2 sqrt(T_tr/m)), cumulants\n"
    "                       of the HCS (Sonine: Santos, Kremer and dos Santos 2011); mixtures: rough_hcs {maxwellian:\n"
    "                       {theta: [T_rot,k/T_k], translational_temperature_over_mean: [T_k/T]}, sonine: why not}\n"
    "With &thermostat kind = 'white_noise' (docs/white-noise.md), one species: white_noise {maxwellian:\n"
    "                       {translational_temperature[, theta]}, sonine: {translational_temperature[, theta],\n"
    "                       a20[, a02, a11]} or why not, translational_temperature (Sonine where it exists)};\n"
    "                       mixtures: white_noise {maxwellian: {translational_temperature: [T_k][, theta: [theta_k]]},\n"
    "                       sonine: {translational_temperature: [T_k], sonine_c: [c_k]} (smooth) or why not,\n"
    "                       translational_temperature: [T_k] (Sonine where it exists)}\n"
    "With &agg_frag (docs/agg-frag.md), the Smoluchowski rate equations with Maxwellian kernels instead:\n"
    "  number, temperature  {time, value[t][k]} per cluster size k (number: N_k for the run's n_particles)\n"
    "  total_temperature, kinetic_energy, mean_size, monomer_fraction, collisions, aggregations,\n"
    "  fragmentations, collisions_per_particle   {time, value} (event counts of one replica)\n"
    "  initial_rates        {collisions, aggregations, fragmentations, bounces, log_monomer_rate}: events per\n"
    "                       unit volume and time at t = 0 (exact: Maxwellian monomers)\n"
    "  max_size, lost_mass_fraction   the largest size integrated and the mass beyond it at the last time\n"
    "                       (its cost grows as max_size^2: a sticking gas run long can take hours; Ctrl-C stops it)\n"
    "Exit status: 0 success, 2 bad input, 1 the theory failed, 130 interrupted (nothing printed).\n";

using gdsmc::analysis::json::array;
using gdsmc::analysis::json::number;
/// The text of a JSON string literal, without its quotes (json::quote).
std::string escape(const std::string& text) {
  const std::string quoted = gdsmc::analysis::json::quote(text);
  return quoted.substr(1, quoted.size() - 2);
}

/// The theory of an &agg_frag run (analysis/predictions.hpp) as JSON, in the units of the DSMC observables.
std::string agg_frag_json(const gdsmc::analysis::AggFragPrediction& af, const std::string& indent) {
  const auto& sol = af.solution;
  const auto& rates = af.initial_rates;
  const double n0 = af.initial_monomers;
  const std::size_t nt = sol.time.size(), kt = sol.max_size, width = af.width;
  auto table = [&](const std::vector<double>& values, double scale) {
    std::string out = "{\"time\": " + array(sol.time) + ", \"value\": [";
    for (std::size_t i = 0; i < nt; ++i) {
      std::vector<double> row(values.begin() + static_cast<std::ptrdiff_t>(i * kt),
                              values.begin() + static_cast<std::ptrdiff_t>(i * kt + width));
      for (double& x : row) x *= scale;
      out += (i ? ", " : "") + array(row);
    }
    return out + "]}";
  };
  auto series = [&](const std::vector<double>& values, double scale) {
    std::vector<double> v(values);
    for (double& x : v) x *= scale;
    return "{\"time\": " + array(sol.time) + ", \"value\": " + array(v) + "}";
  };
  const std::string in = indent + "  ";
  std::ostringstream json;
  json << indent << "{\n" << in << "\"n_species\": 1,\n";
  json << in << "\"number\": " << table(sol.number_fraction, n0) << ",\n";
  json << in << "\"temperature\": " << table(sol.temperature, 1.0) << ",\n";
  json << in << "\"total_temperature\": " << series(sol.total_temperature, 1.0) << ",\n";
  json << in << "\"kinetic_energy\": " << series(sol.kinetic_energy, 1.0) << ",\n";
  json << in << "\"mean_size\": " << series(af.mean_size, 1.0) << ",\n";
  json << in << "\"monomer_fraction\": " << series(af.monomer_fraction, 1.0) << ",\n";
  json << in << "\"collisions\": " << series(sol.collisions, n0) << ",\n";
  json << in << "\"aggregations\": " << series(sol.aggregations, n0) << ",\n";
  json << in << "\"fragmentations\": " << series(sol.fragmentations, n0) << ",\n";
  json << in << "\"collisions_per_particle\": " << series(af.collisions_per_particle, 1.0) << ",\n";
  json << in << "\"initial_rates\": {\"collisions\": " << number(rates.collisions)
       << ", \"aggregations\": " << number(rates.aggregations) << ", \"fragmentations\": "
       << number(rates.fragmentations) << ", \"bounces\": " << number(rates.bounces)
       << ", \"log_monomer_rate\": " << number(rates.log_monomer_rate) << "},\n";
  json << in << "\"max_size\": " << kt << ",\n" << in << "\"lost_mass_fraction\": " << number(sol.lost_mass_fraction)
       << ",\n";
  return json.str();
}

/// Many species: says at once what will be computed and about how long it takes (timings of
/// bench/bench_theory.cpp: \ref perf_theory "docs/performance.md"; docs/haff-and-mixtures.md "Numerical integration").
void announce_large_mixture(const gdsmc::io::config::Config& config) {
  const auto s = static_cast<std::size_t>(config.system.n_species);
  if (s <= 1000 || config.has_agg_frag) return;
  // measured (\ref perf_theory "docs/performance.md"): 3000 species in 15-23 s of CPU
  const double seconds = 20.0 * std::pow(static_cast<double>(s) / 3000.0, 2.0);
  std::cerr << "granular-theory: " << s << " species: ";
  if (s > gdsmc::theory::max_hcs_species)
    std::cerr << "the Maxwellian theory only (hcs.first_sonine stops at " << gdsmc::theory::max_hcs_species
              << " species); ";
  std::cerr << "O(S^2) per step of the partial-temperature ODEs, about " << std::lround(seconds)
            << " s of one core (more for stiff mass ratios or long runs)\n";
}

/// The rough-sphere and white-noise keys of one point (rough_hcs, white_noise), each starting with ",\n".
std::string rough_json(const gdsmc::analysis::Predictions& p, const std::string& in) {
  std::ostringstream json;
  if (p.white_noise) {
    const auto& w = *p.white_noise;
    json << ",\n" << in << "\"white_noise\": {\"maxwellian\": {\"translational_temperature\": "
         << number(w.translational_temperature);
    if (w.theta) json << ", \"theta\": " << number(*w.theta);
    json << "}, \"sonine\": ";
    if (const auto& st = w.sonine.state) {
      json << "{\"translational_temperature\": " << number(*w.sonine_temperature);
      if (w.theta) json << ", \"theta\": " << number(st->theta);
      json << ", \"a20\": " << number(st->cumulants.a20);
      if (w.theta) json << ", \"a02\": " << number(st->cumulants.a02) << ", \"a11\": " << number(st->cumulants.a11);
      json << "}";
    } else {
      json << "\"" << escape(w.sonine.why_not) << "\"";
    }
    json << ", \"translational_temperature\": " << number(w.sonine_temperature.value_or(w.translational_temperature)) << "}";
  }
  if (const auto& w = p.white_noise_mixture) {
    json << ",\n" << in << "\"white_noise\": {\"maxwellian\": {\"translational_temperature\": " << array(w->translational);
    if (!w->theta.empty()) json << ", \"theta\": " << array(w->theta);
    json << "}, \"sonine\": ";
    if (const auto& st = p.white_noise_mixture_sonine)
      json << "{\"translational_temperature\": " << array(st->temperature) << ", \"sonine_c\": " << array(st->sonine_c) << "}";
    else
      json << "\"" << escape(p.white_noise_mixture_sonine_why_not) << "\"";
    json << ", \"translational_temperature\": "
         << array(p.white_noise_mixture_sonine ? p.white_noise_mixture_sonine->temperature : w->translational) << "}";
  }
  if (p.rough_hcs_maxwellian) {
    json << ",\n" << in << "\"rough_hcs\": {\"maxwellian\": {\"theta\": " << number(p.rough_hcs_maxwellian->theta)
         << ", \"zeta_star\": " << number(p.rough_zeta_star) << "}, \"sonine\": ";
    if (const auto& st = p.rough_hcs_sonine ? p.rough_hcs_sonine->state : std::nullopt)
      json << "{\"theta\": " << number(st->theta) << ", \"a20\": " << number(st->cumulants.a20) << ", \"a02\": "
           << number(st->cumulants.a02) << ", \"a11\": " << number(st->cumulants.a11) << ", \"zeta_star\": "
           << number(st->cooling_rate_reduced) << "}";
    else
      json << "\"" << escape(p.rough_hcs_sonine ? p.rough_hcs_sonine->why_not : std::string("not computed")) << "\"";
    json << "}";
  }
  if (p.rough_mixture_hcs)
    json << ",\n" << in << "\"rough_hcs\": {\"maxwellian\": {\"theta\": " << array(p.rough_mixture_hcs->theta)
         << ", \"translational_temperature_over_mean\": " << array(p.rough_mixture_hcs->translational_over_mean)
         << "}, \"sonine\": \"not computed: the Sonine theory of rough mixtures is not implemented\"}";
  return json.str();
}

std::atomic<bool> g_interrupted{false};  // written only by the signal handler
extern "C" void on_signal(int) { g_interrupted.store(true); }

/// The theory of one system (analysis::predict) as a JSON object; `indent` prefixes every line. The
/// notes of what was left out go to stderr.
std::string point_json(const gdsmc::io::config::Config& config, const std::string& indent) {
  announce_large_mixture(config);
  const auto p = gdsmc::analysis::predict(config, [] { return g_interrupted.load(); });
  for (const auto& note : p.notes) std::cerr << "granular-theory: " << note << "\n";
  const std::string in = indent + "  ";
  auto approximations = [&] {
    std::string out = in + "\"approximations\": {";
    for (std::size_t k = 0; k < p.approximations.size(); ++k)
      out += (k ? ", \"" : "\"") + p.approximations[k].first + "\": \"" + p.approximations[k].second + "\"";
    return out + "}";
  };
  if (p.agg_frag) return agg_frag_json(*p.agg_frag, indent) + approximations() + ",\n" + in + kUnitsJson + "\n" + indent + "}";
  const std::size_t s = p.n_species;
  std::ostringstream json;
  json << indent << "{\n" << in << "\"n_species\": " << s << ",\n";
  json << in << "\"collision_frequency\": " << array(p.collision_frequency);
  // (keys that do not apply are left out, not written empty: a rough mixture has neither of these two)
  if (!p.cooling_rate.empty()) json << ",\n" << in << "\"cooling_rate\": " << array(p.cooling_rate);
  if (p.has_history) {
    json << ",\n" << in << "\"temperature\": {\"time\": " << array(p.time) << ", \"value\": [";
    for (std::size_t i = 0; i < p.time.size(); ++i) json << (i ? ", " : "") << array(p.temperature[i]);
    json << "]},\n";
    json << in << "\"total_temperature\": {\"time\": " << array(p.time) << ", \"value\": "
         << array(p.total_temperature) << "},\n";
    json << in << "\"collisions_per_particle\": {\"time\": " << array(p.time)
         << ", \"value\": " << array(p.collisions_per_particle) << "}";
    if (!p.rotational_temperature.empty())
      json << ",\n" << in << "\"rotational_temperature\": {\"time\": " << array(p.time) << ", \"value\": "
           << array(p.rotational_temperature) << "}";
  }
  json << rough_json(p, in);
  if (!p.diffusion_coefficient_ratio.empty())
    json << ",\n" << in << "\"diffusion_coefficient_ratio\": " << array(p.diffusion_coefficient_ratio);
  if (p.msd) {
    json << ",\n" << in << "\"msd\": {\"time\": " << array(p.msd->time) << ", \"value\": [";
    for (std::size_t i = 0; i < p.msd->value.size(); ++i) json << (i ? ", " : "") << array(p.msd->value[i]);
    json << "]}";
  }
  if (p.sonine_a2) {
    json << ",\n" << in << "\"sonine_a2\": " << number(*p.sonine_a2) << ",\n" << in << "\"sonine_c\": ["
         << number(2.0 * *p.sonine_a2) << "],\n" << in << "\"cooling_rate_sonine\": ["
         << number(*p.cooling_rate_sonine) << "]";
  }
  if (p.asymptotic_temperature_ratio)
    json << ",\n" << in << "\"asymptotic_temperature_ratio\": " << array(*p.asymptotic_temperature_ratio);
  if (p.hcs_first_sonine || p.hcs_maxwellian_temperature_over_mean) {
    json << ",\n" << in << "\"hcs\": {";
    if (p.hcs_first_sonine) {
      json << "\"first_sonine\": {\"temperature_over_mean\": "
           << array(p.hcs_first_sonine->temperature_over_mean) << ", \"sonine_c\": "
           << array(p.hcs_first_sonine->sonine_c) << ", \"cooling_rate_reduced\": "
           << number(p.hcs_first_sonine->cooling_rate_reduced) << "}";
    }
    if (p.hcs_maxwellian_temperature_over_mean)
      json << (p.hcs_first_sonine ? ", " : "") << "\"maxwellian\": {\"temperature_over_mean\": "
           << array(*p.hcs_maxwellian_temperature_over_mean) << ", \"cooling_rate_reduced\": "
           << number(*p.hcs_maxwellian_cooling_rate_reduced) << "}";
    json << "}";
  }
  if (p.binary_hcs) {  // binary HCS in first Sonine approximation (Montanero and Garzo 2002, App. A, \ref son_binary "docs/sonine.md")
    const auto& hcs = *p.binary_hcs;
    // The same first-Sonine HCS as hcs.first_sonine (the s-species solution), so that both print the
    // same digits; tail_beta is the binary theory's own.
    const auto* fs = p.hcs_first_sonine ? &*p.hcs_first_sonine : nullptr;
    json << ",\n" << in << "\"temperature_ratio\": "
         << number(fs ? fs->temperature_over_mean[0] / fs->temperature_over_mean[1] : hcs.temperature_ratio);
    json << ",\n" << in << "\"sonine_c\": " << array(fs ? fs->sonine_c : std::vector<double>{hcs.sonine_c[0], hcs.sonine_c[1]});
    json << ",\n" << in << "\"cooling_rate_reduced\": " << number(fs ? fs->cooling_rate_reduced : hcs.cooling_rate);
    json << ",\n" << in << "\"tail_beta\": " << array({hcs.tail_beta[0], hcs.tail_beta[1]});
    if (p.binary_tail_decay_rate[0])
      json << ",\n" << in << "\"tail_decay_rate\": "
           << array({*p.binary_tail_decay_rate[0], *p.binary_tail_decay_rate[1]});
  }
  if (p.shear_viscosity_hcs)
    json << ",\n" << in << "\"shear_viscosity_ratio\": {\"hcs\": " << number(*p.shear_viscosity_hcs)
         << ", \"hss\": " << number(*p.shear_viscosity_hss) << "}";
  if (p.shear_viscosity_kinetic_hcs)
    json << ",\n" << in << "\"shear_viscosity_kinetic_ratio\": {\"hcs\": " << number(*p.shear_viscosity_kinetic_hcs)
         << ", \"hss\": " << number(*p.shear_viscosity_kinetic_hss) << "}";
  if (p.shear_viscosity_reduced_factor) {
    const double factor = *p.shear_viscosity_reduced_factor;
    json << ",\n" << in << "\"shear_viscosity_reduced\": {\"hcs\": " << number(factor * *p.shear_viscosity_hcs)
         << ", \"hss\": " << number(factor * *p.shear_viscosity_hss) << "}";
    if (p.shear_viscosity_kinetic_hcs)
      json << ",\n" << in << "\"shear_viscosity_kinetic_reduced\": {\"hcs\": "
           << number(factor * *p.shear_viscosity_kinetic_hcs) << ", \"hss\": "
           << number(factor * *p.shear_viscosity_kinetic_hss) << "}";
  }
  if (p.steady_shear_grad) {
    const auto& u = *p.steady_shear_grad;
    json << ",\n" << in << "\"steady_shear\": {\"temperature_over_mean\": " << array(u.temperature_ratio)
         << ", \"reduced_shear_rate\": " << number(u.reduced_shear_rate) << ", \"pressure_over_p\": "
         << array({u.pressure_xx, u.pressure_yy, u.pressure_zz, u.pressure_xy}) << "}";
  }
  // The approximation behind every key printed (\ref output_theory "docs/output.md"), and the units.
  json << ",\n" << approximations();
  json << ",\n" << in << kUnitsJson;
  json << "\n" << indent << "}";
  return json.str();
}

std::atomic<bool> g_announced{false};  // the interrupt's line is printed once (by the waiting thread or compute)
void announce_interrupt() {
  if (!g_announced.exchange(true)) std::cerr << "granular-theory: interrupted: nothing printed\n";
}

/// The theory of the input (one point, or a sweep's points) as the JSON to print, into `printed`; the
/// exit status (a refusal or failure says why on stderr, and leaves `printed` empty).
int compute(const gdsmc::io::config::Config& config, std::string& printed) {
  try {
    if (!config.is_sweep()) {
      printed = point_json(config, "") + "\n";
    } else {
      // One object per point, in the order of &sweep values (as /sweep/point_K of granular-dsmc).
      std::ostringstream json;
      // "variable": the names joined by ", " (one variable: its name); "values": each point's values
      // joined the same way; "variables" and "points": the same as lists.
      const auto table = config.sweep.table();
      json << "{\n  \"sweep\": {\"variable\": \"" << escape(config.sweep.names()) << "\", \"values\": [";
      for (std::size_t k = 0; k < table.size(); ++k)
        json << (k ? ", " : "") << "\"" << escape(gdsmc::io::config::Sweep::row_text(table[k])) << "\"";
      json << "], \"variables\": [";
      for (std::size_t v = 0; v < config.sweep.variable.size(); ++v)
        json << (v ? ", " : "") << "\"" << escape(config.sweep.variable[v]) << "\"";
      json << "], \"numbers\": [";  // each point's values as numbers (null: a string or an array)
      for (std::size_t k = 0; k < table.size(); ++k) {
        std::vector<double> row;
        for (const auto& text : table[k]) row.push_back(gdsmc::analysis::sweep_table::numeric_value(text));
        json << (k ? ", " : "") << array(row);
      }
      json << "]},\n  \"points\": [\n";
      const auto points = config.sweep_points();
      for (std::size_t k = 0; k < points.size(); ++k)
        json << (k ? ",\n" : "") << point_json(points[k], "    ");
      json << "\n  ]\n}\n";
      printed = json.str();
    }
  } catch (const gdsmc::theory::smoluchowski::Stopped&) {
    announce_interrupt();
    return 130;
  } catch (const gdsmc::io::namelist::Error& e) {  // e.g. an end of the run the ODEs cannot reach
    std::cerr << "granular-theory: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "granular-theory: " << e.what() << "\n";
    return 1;
  } catch (...) {  // (nothing may leave the theory's thread)
    std::cerr << "granular-theory: the theory failed\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string input;
  std::vector<std::string> overrides;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (arg == "--version") {
      std::cout << "granular-theory " << gdsmc::io::build_version() << "\n";
      return 0;
    } else if (arg == "--set") {
      if (i + 1 == argc) {
        std::cerr << "granular-theory: --set needs a value (--set group:variable=value)\n";
        return 2;
      }
      overrides.push_back(argv[++i]);
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "granular-theory: unknown option " << gdsmc::io::namelist::printable(arg) << " (granular-theory --help lists the options)\n";
      return 2;
    } else if (arg.empty()) {
      std::cerr << "granular-theory: an empty argument where the namelist file was expected\n";
      return 2;
    } else if (input.empty()) {
      input = arg;
    } else {
      std::cerr << "granular-theory: one input file only (got '" << gdsmc::io::namelist::printable(input) << "' and '" << gdsmc::io::namelist::printable(arg) << "')\n";
      return 2;
    }
  }
  if (input.empty()) {  // one line, as every refusal (--help prints the usage)
    std::cerr << "granular-theory: no input file: granular-theory FILE.nml [--set group:variable=value]... "
                 "(granular-theory --help lists the options)\n";
    return 2;
  }
  gdsmc::io::config::Config config;
  try {
    config = gdsmc::io::config::read_file(input, overrides, gdsmc::analysis::check_run_cost);
    gdsmc::analysis::check_theory_memory(config, "fewer species (granular-dsmc runs the gas without --compare)");
  } catch (const gdsmc::io::namelist::Error& e) {
    std::cerr << "granular-theory: " << e.what() << "\n";
    return 2;
  }

  // Ctrl-C: the theory runs on a thread of its own while this one looks at the signal every 20 ms; on a
  // signal the process ends at once, status 130, having printed nothing (it writes no file, only stdout),
  // whatever the theory was doing (a dense Newton step of thousands of species' partial temperatures takes
  // seconds and has no place to stop). The Smoluchowski integration also stops at its next right-hand side.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::string printed;
  std::atomic<bool> done{false};
  int status = 0;
  std::thread theory;
  try {
    theory = std::thread([&] {
      status = compute(config, printed);
      done.store(true);
    });
  } catch (const std::system_error&) {  // (no thread to be had: computed here, Ctrl-C as the solvers allow)
    status = compute(config, printed);
    done.store(true);
  }
  while (!done.load()) {
    if (g_interrupted.load()) {
      announce_interrupt();
      std::_Exit(130);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (theory.joinable()) theory.join();
  std::cout << printed;
  return status;
}
