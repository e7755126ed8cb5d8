// granular-theory: the kinetic-theory predictions for the system of a namelist, as one JSON object
// on stdout (INTERFACE.md "granular-theory JSON keys").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/config.hpp"
#include "io/namelist.hpp"
#include "theory/smoluchowski.hpp"
#include "theory/sonine_mixture.hpp"
#include "theory/theory.hpp"
#include "theory/viscosity.hpp"

namespace {

/// Runs `integrate` (an ODE integration over the run's sample points) and turns its failure, e.g.
/// CVODE giving up on t_end = 1e300, into an input error naming the variable that sets the end of
/// the run (t_end or collisions_per_particle), where it was set, as granular-dsmc names refusals.
template <class F>
auto over_the_run(const gdsmc::io::config::Config& config, F&& integrate) {
  try {
    return integrate();
  } catch (const gdsmc::io::namelist::Error&) {
    throw;
  } catch (const std::exception& e) {
    const char* variable = config.dsmc.t_end ? "t_end" : "collisions_per_particle";
    const auto it = config.origin.find(std::string("dsmc:") + variable);
    const std::string file = it == config.origin.end() ? config.source_file : it->second.first;
    const int line = it == config.origin.end() ? 0 : it->second.second;
    char end[32];
    std::snprintf(end, sizeof end, "%.6g", config.dsmc.t_end ? *config.dsmc.t_end : *config.dsmc.collisions_per_particle);
    throw gdsmc::io::namelist::Error(file, line, "dsmc", variable,
                                     std::string("the theory cannot integrate to ") + variable + " = " + end + ": " +
                                         e.what());
  }
}

const char* kUsage =
    "usage: granular-theory FILE.nml [--set group:variable=value]...\n"
    "Prints the theory for the namelist's system as one JSON object on stdout:\n"
    "  collision_frequency  [nu_k] collisions suffered per particle of species k per unit time at t=0\n"
    "  cooling_rate         [zeta_k] = sum_j xi_kj at t = 0 (ERRATA §4; one species: ERRATA §3)\n"
    "  temperature          {time, value[t][k]} the partial-temperature ODEs (CVODE) on the sample times\n"
    "  total_temperature, collisions_per_particle   {time, value} on the same times\n"
    "  asymptotic_temperature_ratio  [T_k/T_1] at long times (mixtures, constant restitution)\n"
    "  sonine_a2, cooling_rate_sonine               one species: van Noije-Ernst a2 and (1+3a2/16) zeta\n"
    "  temperature_ratio, sonine_c, cooling_rate_reduced, tail_beta, tail_decay_rate\n"
    "                       binary mixtures: the HCS in first Sonine approximation (seed 003, ERRATA §6)\n"
    "  hcs                  {first_sonine: {temperature_over_mean, sonine_c, cooling_rate_reduced},\n"
    "                       maxwellian: {temperature_over_mean, cooling_rate_reduced}} HCS for any number of\n"
    "                       species, constant restitution (T = sum_k n_k T_k/n; theory/sonine_mixture.hpp)\n"
    "  approximations       {key: \"maxwellian\" | \"first_sonine\" | ...} behind every key printed\n"
    "  shear_viscosity_ratio {hcs, hss} eta/eta_0 in first Sonine (seed 004, ERRATA §10, §13): one species\n"
    "                       (dilute or Enskog), dilute binary mixtures (over the elastic mixture value)\n"
    "  diffusion_coefficient_ratio  [D_k/D_1] (seed 001 eq 19, ERRATA §8); msd {time, value[t][k]} (eq 17)\n"
    "                       when &output track_displacements = .true. (not with msd_start_temperature)\n"
    "With &agg_frag (ERRATA §12), the Smoluchowski rate equations with Maxwellian kernels instead:\n"
    "  number, temperature  {time, value[t][k]} per cluster size k (number: N_k for the run's n_particles)\n"
    "  total_temperature, kinetic_energy, mean_size, monomer_fraction, collisions, aggregations,\n"
    "  fragmentations, collisions_per_particle   {time, value} (event counts of one replica)\n"
    "  initial_rates        events per unit volume and time at t = 0 (exact: Maxwellian monomers)\n"
    "With &sweep: {\"sweep\": {variable, values}, \"points\": [one object as above per value]}.\n";

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}
std::string array(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + number(v[i]);
  return s + "]";
}

/// Times at which the ODE's collisions per particle (2 x events / n) reach `targets`.
std::vector<double> times_for_collisions(const gdsmc::species::Mixture& mix,
                                         const std::vector<double>& t0,
                                         const std::vector<double>& targets) {
  const double n = mix.total_density();
  // Bracket the last target on a doubling time scale, then tabulate densely and interpolate.
  double horizon = 1.0;
  const double rate0 = gdsmc::theory::total_collision_rate(mix, t0);
  horizon = std::max(horizon, targets.back() * n / (2.0 * rate0));
  for (int guard = 0; guard < 200; ++guard) {
    const auto h = gdsmc::theory::integrate_partial_temperatures(mix, t0, {0.0, horizon});
    if (2.0 * h.collisions.back() / n >= targets.back()) break;
    horizon *= 2.0;
  }
  const std::size_t grid = 20000;
  std::vector<double> t(grid);
  for (std::size_t i = 0; i < grid; ++i) t[i] = horizon * static_cast<double>(i) / (grid - 1);
  const auto h = gdsmc::theory::integrate_partial_temperatures(mix, t0, t);
  std::vector<double> out;
  std::size_t i = 1;
  for (double c : targets) {
    if (c <= 0.0) {
      out.push_back(0.0);
      continue;
    }
    while (i < grid - 1 && 2.0 * h.collisions[i] / n < c) ++i;
    const double c0 = 2.0 * h.collisions[i - 1] / n, c1 = 2.0 * h.collisions[i] / n;
    out.push_back(t[i - 1] + (t[i] - t[i - 1]) * (c - c0) / (c1 - c0));
  }
  return out;
}


std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

/// The theory of an &agg_frag run: the Smoluchowski equations of theory/smoluchowski.hpp on the run's
/// sample points, in the units of the DSMC observables (counts for n_particles initial monomers).
std::string agg_frag_json(const gdsmc::io::config::Config& config, const std::string& indent) {
  namespace sm = gdsmc::theory::smoluchowski;
  const sm::Parameters p = sm::parameters_of(config);
  const double n0 = static_cast<double>(config.dsmc.n_particles);
  const auto sol = over_the_run(config, [&] {
    std::vector<double> times = config.sample_times();
    if (times.empty()) {  // collision-driven: the times at which 2 x collisions per monomer reach the targets
      const auto targets = config.sample_collisions();
      double horizon = 1.0;
      for (int guard = 0; guard < 60 && 2.0 * sm::solve(p, {0.0, horizon}).collisions.back() < targets.back(); ++guard)
        horizon *= 2.0;
      const std::size_t grid = 2001;
      std::vector<double> t(grid);
      for (std::size_t i = 0; i < grid; ++i) t[i] = horizon * static_cast<double>(i) / (grid - 1);
      const auto fine = sm::solve(p, t);
      std::size_t i = 1;
      for (double c : targets) {
        if (c <= 0.0) {
          times.push_back(0.0);
          continue;
        }
        while (i < grid - 1 && 2.0 * fine.collisions[i] < c) ++i;
        const double c0 = 2.0 * fine.collisions[i - 1], c1 = 2.0 * fine.collisions[i];
        times.push_back(t[i - 1] + (t[i] - t[i - 1]) * (c - c0) / (c1 - c0));
      }
    }
    return sm::solve(p, times);
  });
  const auto rates = sm::initial_rates(p);
  const std::size_t nt = sol.time.size(), kt = sol.max_size;
  // Columns up to the largest size of which the run would hold 1e-6 clusters or more at some time
  // (the equations integrate sizes far beyond, to keep the lost mass below 1e-8).
  std::size_t width = 1;
  for (std::size_t i = 0; i < nt; ++i)
    for (std::size_t k = 0; k < kt; ++k)
      if (sol.number_fraction[i * kt + k] * n0 >= 1e-6) width = std::max(width, k + 1);
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
  std::vector<double> mean_size(nt), monomer_fraction(nt), per_particle(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    double clusters = 0.0;
    for (std::size_t k = 0; k < kt; ++k) clusters += sol.number_fraction[i * kt + k];
    mean_size[i] = 1.0 / clusters;
    monomer_fraction[i] = sol.number_fraction[i * kt];
    per_particle[i] = 2.0 * sol.collisions[i];
  }
  const std::string in = indent + "  ";
  std::ostringstream json;
  json << indent << "{\n" << in << "\"n_species\": 1,\n";
  json << in << "\"number\": " << table(sol.number_fraction, n0) << ",\n";
  json << in << "\"temperature\": " << table(sol.temperature, 1.0) << ",\n";
  json << in << "\"total_temperature\": " << series(sol.total_temperature, 1.0) << ",\n";
  json << in << "\"kinetic_energy\": " << series(sol.kinetic_energy, 1.0) << ",\n";
  json << in << "\"mean_size\": " << series(mean_size, 1.0) << ",\n";
  json << in << "\"monomer_fraction\": " << series(monomer_fraction, 1.0) << ",\n";
  json << in << "\"collisions\": " << series(sol.collisions, n0) << ",\n";
  json << in << "\"aggregations\": " << series(sol.aggregations, n0) << ",\n";
  json << in << "\"fragmentations\": " << series(sol.fragmentations, n0) << ",\n";
  json << in << "\"collisions_per_particle\": " << series(per_particle, 1.0) << ",\n";
  json << in << "\"initial_rates\": {\"collisions\": " << number(rates.collisions)
       << ", \"aggregations\": " << number(rates.aggregations) << ", \"fragmentations\": "
       << number(rates.fragmentations) << ", \"bounces\": " << number(rates.bounces)
       << ", \"log_monomer_rate\": " << number(rates.log_monomer_rate) << "},\n";
  json << in << "\"max_size\": " << kt << ",\n" << in << "\"lost_mass_fraction\": " << number(sol.lost_mass_fraction)
       << ",\n";
  json << in << "\"approximations\": {\"initial_rates\": \"exact\"";
  for (const char* key : {"number", "temperature", "total_temperature", "kinetic_energy", "mean_size", "monomer_fraction",
                          "collisions", "aggregations", "fragmentations", "collisions_per_particle"})
    json << ", \"" << key << "\": \"maxwellian\"";
  json << "}\n";
  json << indent << "}";
  return json.str();
}

/// The theory of one system as a JSON object; `indent` prefixes every line.
std::string point_json(const gdsmc::io::config::Config& config, const std::string& indent) {
  if (config.has_agg_frag) return agg_frag_json(config, indent);
  namespace th = gdsmc::theory;
  const auto mix = config.mixture();
  const std::size_t s = mix.size();
  const auto& t0 = config.initial.temperature;
  const double n = mix.total_density();

  // Collisions suffered by species k per unit volume: 2 P_kk + sum_{j != k} P_kj (ERRATA §2).
  const auto pair = th::pair_collision_rate(mix, t0);
  std::vector<double> frequency(s), cooling(s);
  const auto beta = config.viscoelastic_beta();  // viscoelastic restitution: A3, A4 (ERRATA §8)
  const auto xi = beta ? th::cooling_rate_matrix_viscoelastic(mix, *beta, t0) : th::cooling_rate_matrix(mix, t0);
  for (std::size_t k = 0; k < s; ++k) {
    double suffered = 0.0, z = 0.0;
    for (std::size_t j = 0; j < s; ++j) {
      suffered += (j == k ? 2.0 : 1.0) * pair(k, j);
      z += xi(k, j);
    }
    frequency[k] = suffered / mix.number_density[k];
    cooling[k] = z;
  }

  std::vector<double> times = config.sample_times();
  if (times.empty())
    times = over_the_run(config, [&] { return times_for_collisions(mix, t0, config.sample_collisions()); });
  const auto history = over_the_run(config, [&] {
    return beta ? th::integrate_partial_temperatures_viscoelastic(mix, *beta, t0, times)
                : th::integrate_partial_temperatures(mix, t0, times);
  });

  const std::string in = indent + "  ";
  std::vector<std::pair<std::string, std::string>> approximations = {{"collision_frequency", "maxwellian"},
                                                                     {"cooling_rate", "maxwellian"}};
  if (!config.staged())
    for (const char* key : {"temperature", "total_temperature", "collisions_per_particle"})
      approximations.emplace_back(key, "maxwellian");
  std::ostringstream json;
  json << indent << "{\n" << in << "\"n_species\": " << s << ",\n";
  json << in << "\"collision_frequency\": " << array(frequency) << ",\n";
  json << in << "\"cooling_rate\": " << array(cooling);
  if (config.staged()) {
    // The free-cooling history does not describe a run with a thermostat or a shear flow.
    std::cerr << "granular-theory: temperature, total_temperature, collisions_per_particle left out: the run has "
                 "&thermostat or &shear (T is held or heated; see shear_viscosity_ratio, temperature_ratio)\n";
  } else {
    json << ",\n" << in << "\"temperature\": {\"time\": " << array(history.time) << ", \"value\": [";
    std::vector<double> total, collisions;
    for (std::size_t i = 0; i < history.time.size(); ++i) {
      json << (i ? ", " : "") << array(history.temperature[i]);
      double tt = 0.0;
      for (std::size_t k = 0; k < s; ++k) tt += mix.number_density[k] * history.temperature[i][k];
      total.push_back(tt / n);
      collisions.push_back(2.0 * history.collisions[i] / n);
    }
    json << "]},\n";
    json << in << "\"total_temperature\": {\"time\": " << array(history.time) << ", \"value\": "
         << array(total) << "},\n";
    json << in << "\"collisions_per_particle\": {\"time\": " << array(history.time)
         << ", \"value\": " << array(collisions) << "}";
  }
  // Diffusion (seed 001 eqs 16-21, ERRATA §8): D_k/D_1 at long times (constant alpha) or at the end
  // of the run (viscoelastic, where the ratios drift), and eq 17's MSD when displacements are tracked.
  {
    const auto ratio = beta ? th::diffusion_coefficient_ratio(mix, history.temperature.back(), &*beta)
                            : th::diffusion_coefficient_ratio(mix);
    json << ",\n" << in << "\"diffusion_coefficient_ratio\": " << array(ratio);
    approximations.emplace_back("diffusion_coefficient_ratio", "maxwellian");
  }
  if (config.output.track_displacements) {
    // The MSD counts from msd_start_time (or t = 0), starting from the theory's temperatures then.
    const double start = config.output.msd_start_time.value_or(0.0);
    std::vector<double> start_temperature = t0;
    if (start > 0.0) {
      const auto at = over_the_run(config, [&] {
        return beta ? th::integrate_partial_temperatures_viscoelastic(mix, *beta, t0, {0.0, start})
                    : th::integrate_partial_temperatures(mix, t0, {0.0, start});
      });
      start_temperature = at.temperature.back();
    }
    std::vector<double> since, shifted_times;
    for (double t : history.time)
      if (t >= start) {
        since.push_back(t - start);
        shifted_times.push_back(t);
      }
    if (!config.output.msd_start_temperature && !since.empty()) {
      const auto msd = th::mean_squared_displacement(mix, start_temperature, since, beta ? &*beta : nullptr);
      json << ",\n" << in << "\"msd\": {\"time\": " << array(shifted_times) << ", \"value\": [";
      for (std::size_t i = 0; i < msd.msd.size(); ++i) json << (i ? ", " : "") << array(msd.msd[i]);
      json << "]}";
      approximations.emplace_back("msd", "maxwellian");
    }
  }
  std::optional<std::vector<double>> maxwellian_ratios;  // asymptotic T_k/T_1 (constant alpha)
  if (beta) {
    // Constant-alpha keys (Sonine HCS, asymptotic ratios) do not apply to viscoelastic spheres.
  } else if (s == 1) {
    const double alpha = mix.restitution(0, 0);
    const double a2 = th::sonine_a2(alpha);
    json << ",\n" << in << "\"sonine_a2\": " << number(a2) << ",\n" << in << "\"sonine_c\": ["
         << number(2.0 * a2) << "],\n" << in << "\"cooling_rate_sonine\": ["
         << number(cooling[0] * (1.0 + 3.0 * a2 / 16.0)) << "]";
    approximations.emplace_back("sonine_a2", "first_sonine");
    approximations.emplace_back("sonine_c", "first_sonine");
    approximations.emplace_back("cooling_rate_sonine", "first_sonine");
  } else {
    const bool inelastic = mix.restitution.max() < 1.0;
    if (inelastic) {
      try {
        const auto ratios = th::asymptotic_temperature_ratios(mix);
        json << ",\n" << in << "\"asymptotic_temperature_ratio\": " << array(ratios);
        approximations.emplace_back("asymptotic_temperature_ratio", "maxwellian");
        maxwellian_ratios = ratios;
      } catch (const std::exception& e) {  // a key that cannot be evaluated is left out, with a word why
        std::cerr << "granular-theory: asymptotic_temperature_ratio left out: " << e.what() << "\n";
      }
    } else {
      maxwellian_ratios = std::vector<double>(s, 1.0);  // elastic: equipartition
    }
  }
  // HCS of any number of species, constant restitution (theory/sonine_mixture.hpp): first Sonine,
  // and the Maxwellian ratios in the same normalisation (T_k/T, T = sum_k n_k T_k/n).
  if (!beta) {
    if (s == 1) maxwellian_ratios = std::vector<double>{1.0};
    std::optional<th::HcsFirstSonine> first_sonine;
    try {
      first_sonine = th::hcs_first_sonine(mix, maxwellian_ratios.value_or(std::vector<double>{}));
    } catch (const std::exception& e) {
      std::cerr << "granular-theory: hcs.first_sonine left out: " << e.what() << "\n";
    }
    std::string maxwellian;
    if (maxwellian_ratios) {
      try {
        std::vector<double> t = *maxwellian_ratios;
        double mean = 0.0;
        for (std::size_t k = 0; k < s; ++k) mean += mix.mole_fraction(k) * t[k];
        for (double& v : t) v /= mean;
        maxwellian = "{\"temperature_over_mean\": " + array(t) + ", \"cooling_rate_reduced\": " +
                     number(th::hcs_maxwellian_cooling_rate_reduced(mix, t)) + "}";
      } catch (const std::exception& e) {
        std::cerr << "granular-theory: hcs.maxwellian left out: " << e.what() << "\n";
      }
    }
    if (first_sonine || !maxwellian.empty()) {
      json << ",\n" << in << "\"hcs\": {";
      if (first_sonine) {
        json << "\"first_sonine\": {\"temperature_over_mean\": "
             << array(first_sonine->temperature_over_mean) << ", \"sonine_c\": "
             << array(first_sonine->sonine_c) << ", \"cooling_rate_reduced\": "
             << number(first_sonine->cooling_rate_reduced) << "}";
        approximations.emplace_back("hcs.first_sonine", "first_sonine");
      }
      if (!maxwellian.empty()) {
        json << (first_sonine ? ", " : "") << "\"maxwellian\": " << maxwellian;
        approximations.emplace_back("hcs.maxwellian", "maxwellian");
      }
      json << "}";
    }
  }
  std::optional<th::BinaryHcs> hcs_result;
  if (s == 2 && !beta) {
    try {
      hcs_result = th::binary_hcs_first_sonine(mix);
    } catch (const std::exception& e) {  // e.g. gamma outside the root finder's range
      std::cerr << "granular-theory: binary HCS keys (temperature_ratio, sonine_c, ...) left out: " << e.what()
                << "\n";
    }
  }
  if (hcs_result) {  // binary HCS in first Sonine approximation (seed 003 App. A, ERRATA §6)
    const auto& hcs = *hcs_result;
    json << ",\n" << in << "\"temperature_ratio\": " << number(hcs.temperature_ratio);
    json << ",\n" << in << "\"sonine_c\": " << array({hcs.sonine_c[0], hcs.sonine_c[1]});
    json << ",\n" << in << "\"cooling_rate_reduced\": " << number(hcs.cooling_rate);
    json << ",\n" << in << "\"tail_beta\": " << array({hcs.tail_beta[0], hcs.tail_beta[1]});
    if (hcs.cooling_rate > 0.0)
      json << ",\n" << in << "\"tail_decay_rate\": "
           << array({th::tail_decay_rate(hcs, 0), th::tail_decay_rate(hcs, 1)});
    approximations.emplace_back("temperature_ratio", "first_sonine");
    approximations.emplace_back("sonine_c", "first_sonine");
    approximations.emplace_back("cooling_rate_reduced", "first_sonine");
    approximations.emplace_back("tail_beta", "high_velocity_asymptotics");
    if (hcs.cooling_rate > 0.0)
      approximations.emplace_back("tail_decay_rate", "high_velocity_asymptotics_first_sonine");
  }
  // Shear viscosity eta/eta_0 in first Sonine (seed 004, ERRATA §10, §13; theory/viscosity.hpp): one
  // species, dilute or Enskog; dilute binary mixtures over the elastic mixture value.
  if (!beta && (s == 1 || (s == 2 && hcs_result && !mix.enskog))) {
    namespace vt = th::viscosity;
    try {
      auto reduced = [&](vt::State state) {
        if (s == 2) return vt::binary_viscosity(mix, 1.0, state).reduced;
        const double alpha = mix.restitution(0, 0);
        return mix.enskog ? vt::enskog_reduced_viscosity(alpha, mix.packing_fraction(), state).total
                          : vt::dilute_reduced_viscosity(alpha, state);
      };
      json << ",\n" << in << "\"shear_viscosity_ratio\": {\"hcs\": "
           << number(reduced(vt::State::homogeneous_cooling)) << ", \"hss\": "
           << number(reduced(vt::State::gaussian_thermostat)) << "}";
      approximations.emplace_back("shear_viscosity_ratio", "first_sonine");
    } catch (const std::exception& e) {
      std::cerr << "granular-theory: shear_viscosity_ratio left out: " << e.what() << "\n";
    }
  }
  // The approximation behind every key printed (INTERFACE.md "granular-theory JSON keys").
  json << ",\n" << in << "\"approximations\": {";
  for (std::size_t k = 0; k < approximations.size(); ++k)
    json << (k ? ", " : "") << "\"" << approximations[k].first << "\": \"" << approximations[k].second
         << "\"";
  json << "}";
  json << "\n" << indent << "}";
  return json.str();
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
    } else if (arg == "--set" && i + 1 < argc) {
      overrides.push_back(argv[++i]);
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "granular-theory: unknown option " << arg << "\n" << kUsage;
      return 2;
    } else {
      input = arg;
    }
  }
  if (input.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  gdsmc::io::config::Config config;
  try {
    config = gdsmc::io::config::read_file(input, overrides);
  } catch (const gdsmc::io::namelist::Error& e) {
    std::cerr << "granular-theory: " << e.what() << "\n";
    return 2;
  }

  try {
    if (!config.is_sweep()) {
      std::cout << point_json(config, "") << "\n";
    } else {
      // One object per point, in the order of &sweep values (as /sweep/point_K of granular-dsmc).
      std::ostringstream json;
      json << "{\n  \"sweep\": {\"variable\": \"" << config.sweep.variable << "\", \"values\": [";
      for (std::size_t k = 0; k < config.sweep.values.size(); ++k)
        json << (k ? ", " : "") << "\"" << escape(config.sweep.values[k]) << "\"";
      json << "]},\n  \"points\": [\n";
      const auto points = config.sweep_points();
      for (std::size_t k = 0; k < points.size(); ++k)
        json << (k ? ",\n" : "") << point_json(points[k], "    ");
      json << "\n  ]\n}\n";
      std::cout << json.str();
    }
  } catch (const gdsmc::io::namelist::Error& e) {  // e.g. an end of the run the ODEs cannot reach
    std::cerr << "granular-theory: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "granular-theory: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
