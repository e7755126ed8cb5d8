#include <cerrno>  // program_invocation_short_name (glibc)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/config_detail.hpp"
#include "io/file_guard.hpp"
#include "io/snapshot.hpp"
#include "model/restitution.hpp"

namespace gdsmc::io::config {
namespace detail {

// ---------------------------------------------------------------------------------------------
// Checking and deriving, group by group
// ---------------------------------------------------------------------------------------------
namespace {
/// The symmetric S x S matrix `name` (restitution, roughness) from its assignments: one value for all
/// pairs, the whole matrix, or elements (i,j); `symbol` names its entries in the messages (alpha, beta).
species::PairMatrix resolve_pair_matrix(const std::string& name, const std::string& symbol, std::size_t s,
                                        const Provenance& prov, const std::string& group) {
  {  // one value for all pairs: a uniform matrix, stored densely only for a few species
    const auto& only = prov.pair_assignments.at(name);
    if (only.size() == 1 && only[0].first->index.empty() && only[0].first->values.size() == 1) {
      auto uniform = species::PairMatrix::uniform(s, only[0].first->values[0].real);
      if (s <= species::dense_pair_limit) uniform.densify();
      return uniform;
    }
  }
  species::PairMatrix m(s, std::numeric_limits<double>::quiet_NaN());
  const auto& list = prov.pair_assignments.at(name);
  // (i <= j) -> value and line of its element assignment in the current source (the namelist, or
  // one --set): within one source (i,j) and (j,i) must agree; a later --set may replace the value.
  std::map<std::pair<std::size_t, std::size_t>, std::pair<double, int>> element_values;
  std::string element_source;
  for (const auto& [a, file] : list) {
    if (a->index.empty()) {
      if (a->values.size() == 1) {
        std::fill(m.values.begin(), m.values.end(), a->values[0].real);
      } else if (a->values.size() == s * s) {
        for (std::size_t c = 0; c < s * s; ++c) m(c % s, c / s) = a->values[c].real;  // column-major
        for (std::size_t i = 0; i < s; ++i)  // alpha_ij = alpha_ji: one event, whichever is "first"
          for (std::size_t j = i + 1; j < s; ++j)
            if (m(i, j) != m(j, i))
              throw Error(file, a->line, group, name,
                          "the matrix is not symmetric: " + name + "(" + std::to_string(i + 1) + "," +
                              std::to_string(j + 1) + ") = " + a->values[i + j * s].text +
                              " but " + name + "(" + std::to_string(j + 1) + "," +
                              std::to_string(i + 1) + ") = " + a->values[j + i * s].text);
      } else {
        throw Error(file, a->line, group, name,
                    "expected 1 or n_species^2 = " + std::to_string(s * s) + " values, got " +
                        std::to_string(a->values.size()));
      }
      continue;
    }
    std::size_t i = static_cast<std::size_t>(a->index[0] - 1);
    std::size_t j = static_cast<std::size_t>(a->index[1] - 1);
    if (file != element_source) {
      element_values.clear();
      element_source = file;
    }
    for (const auto& v : a->values) {  // consecutive elements in column-major order
      if (i >= s || j >= s)
        throw Error(file, v.line, group, name,
                    "element (" + std::to_string(i + 1) + "," + std::to_string(j + 1) +
                        ") is outside the " + std::to_string(s) + " x " + std::to_string(s) +
                        " matrix");
      // alpha_ij = alpha_ji is one pair's value: (i,j) and (j,i) given differently is a conflict.
      const auto key = std::make_pair(std::min(i, j), std::max(i, j));
      if (const auto it = element_values.find(key); it != element_values.end() && it->second.first != v.real)
        throw Error(file, v.line, group, name,
                    name + "(" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ") = " + v.text +
                        " conflicts with line " + std::to_string(it->second.second) + ": the matrix is symmetric, " +
                        symbol + "_ij = " + symbol + "_ji");
      element_values[key] = {v.real, v.line};
      m(i, j) = v.real;
      m(j, i) = v.real;
      if (++i == s) {
        i = 0;
        ++j;
      }
    }
  }
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j)
      if (std::isnan(m(i, j)))
        throw Error(prov.file_of(name), prov.line.at(name), group, name,
                    name + "(" + std::to_string(i + 1) + "," + std::to_string(j + 1) +
                        ") is not given");
  return m;
}

void check_species_list(std::vector<double>& values, const std::string& name, const std::string& law,
                        std::size_t s, const Provenance& prov, const std::string& group) {
  const int line = prov.line.count(name) ? prov.line.at(name) : 0;
  const std::size_t expected = law == "list" ? s : 1;
  if (values.size() != expected)
    throw Error(prov.file_of(name), line, group, name,
                "expected " + std::to_string(expected) + " value(s) (" +
                    (law == "list" ? "n_species = " + std::to_string(s)
                                   : "species 1 only, with the law '" + law + "'") +
                    "), got " + std::to_string(values.size()));
  for (std::size_t k = 0; k < values.size(); ++k)
    if (std::isnan(values[k]))
      throw Error(prov.file_of(name), line, group, name,
                  name + "(" + std::to_string(k + 1) + ") is not given");
}

}  // namespace

void check_system(System& sys, const Provenance& prov) {
  const std::string group = "system";
  const auto s = static_cast<std::size_t>(sys.n_species);
  if (sys.restitution_model == RestitutionModel::viscoelastic) {
    if (!sys.visco_a_kappa)
      throw Error(prov.file_of("restitution_model"), prov.line.at("restitution_model"), group, "visco_a_kappa",
                  "required with restitution_model = 'viscoelastic'");
    if (prov.line.count("restitution"))
      throw Error(prov.file_of("restitution"), prov.line.at("restitution"), group, "restitution",
                  "not used with restitution_model = 'viscoelastic' (alpha follows from visco_a_kappa)");
  } else {
    if (!prov.line.count("restitution"))
      throw Error(prov.file, prov.group_line, group, "restitution", "required variable is missing");
    if (prov.line.count("visco_a_kappa"))
      throw Error(prov.file_of("visco_a_kappa"), prov.line.at("visco_a_kappa"), group, "visco_a_kappa",
                  "only used with restitution_model = 'viscoelastic'");
  }
  check_species_list(sys.mass, "mass", name(sys.mass_law), s, prov, group);
  check_species_list(sys.diameter, "diameter", name(sys.diameter_law), s, prov, group);
  check_species_list(sys.number_density, "number_density", name(sys.density_law), s, prov, group);
  // The default value is accepted, so that the --print-defaults template reads back.
  if (sys.density_law != DensityLaw::power && prov.line.count("density_exponent") &&
      sys.density_exponent != System{}.density_exponent)
    throw Error(prov.file_of("density_exponent"), prov.line.at("density_exponent"), group,
                "density_exponent",
                "only used with density_law = 'power'");
  // derive: the species laws (Bodrova and Osinsky 2024, sec. II, \ref sch_lowrank "docs/schemes.md": m_k = k m_1, sigma_k = k^(1/3) sigma_1, n_k = n_1 k^-theta)
  for (std::size_t k = 2; k <= s; ++k) {
    const double kk = static_cast<double>(k);
    if (sys.mass_law == MassLaw::linear) sys.mass.push_back(kk * sys.mass[0]);
    if (sys.diameter_law == DiameterLaw::cube_root) sys.diameter.push_back(std::cbrt(kk) * sys.diameter[0]);
    if (sys.density_law == DensityLaw::power)
      sys.number_density.push_back(sys.number_density[0] * std::pow(kk, -sys.density_exponent));
  }
  if (sys.restitution_model == RestitutionModel::constant) sys.restitution = resolve_pair_matrix("restitution", "alpha", s, prov, group);
  else {  // placeholder: alpha comes from the impact speed
    sys.restitution = species::PairMatrix::uniform(s, 1.0);
    if (s <= species::dense_pair_limit) sys.restitution.densify();
  }
  if (sys.enskog) {
    double phi = 0.0;
    for (std::size_t k = 0; k < s; ++k) phi += sys.number_density[k] * std::pow(sys.diameter[k], 3);
    phi *= std::acos(-1.0) / 6.0;
    if (phi >= species::carnahan_starling_fluid_limit)
      throw Error(prov.file_of("number_density"),
                  prov.line.count("number_density") ? prov.line.at("number_density") : 0,
                  group, "number_density",
                  "packing fraction " + std::to_string(phi) +
                      " is beyond the Carnahan-Starling fluid range (phi < 0.5)");
  }
}

void check_initial(Initial& ini, std::size_t s, const Provenance& prov) {
  const int line = prov.line.count("temperature") ? prov.line.at("temperature") : 0;
  for (std::size_t k = 0; k < ini.temperature.size(); ++k)
    if (std::isnan(ini.temperature[k]))
      throw Error(prov.file_of("temperature"), line, "initial", "temperature",
                  "temperature(" + std::to_string(k + 1) + ") is not given");
  if (ini.temperature.size() == 1 && s > 1) ini.temperature.assign(s, ini.temperature[0]);
  if (ini.temperature.size() != s)
    throw Error(prov.file_of("temperature"), line, "initial", "temperature",
                "expected 1 or n_species = " + std::to_string(s) + " values, got " +
                    std::to_string(ini.temperature.size()));
}

void check_dsmc(const Dsmc& d, const species::Mixture& mix, const Provenance& prov, int group_line) {
  const std::string group = "dsmc";
  if (d.t_end.has_value() == d.collisions_per_particle.has_value())
    throw Error(d.t_end ? prov.file_of("collisions_per_particle") : prov.file,
                d.t_end ? prov.line.at("collisions_per_particle") : group_line, group,
                d.t_end ? "collisions_per_particle" : "t_end",
                "give exactly one of t_end and collisions_per_particle");
  // The event targets are integers: 2 x events / N = collisions_per_particle must stay far inside
  // 64 bits (1e30 would wrap round to a run of no collisions and a file of zeros).
  if (d.collisions_per_particle && *d.collisions_per_particle * static_cast<double>(d.n_particles) / 2.0 > 1e18)
    throw Error(prov.file_of("collisions_per_particle"), prov.line.at("collisions_per_particle"), group,
                "collisions_per_particle",
                "collisions_per_particle x n_particles / 2 = " +
                    std::to_string(*d.collisions_per_particle * static_cast<double>(d.n_particles) / 2.0) +
                    " collision events: beyond 1e18, far more than any run can do");
  // 'majorant' and 'pairs' recompute their bounds over all S^2 species pairs at every time step
  // (collide.cpp rebuild_bounds), which has about N/2 candidates: with thousands of species the
  // rebuilds are the whole run (3000 species: minutes per collision per particle). 'lowrank' updates
  // its rank-3 majorant in O(S log S) (collide.hpp).
  constexpr std::size_t kMaxPairSchemeSpecies = 256;
  if (d.scheme != Scheme::lowrank && mix.size() > kMaxPairSchemeSpecies)
    throw Error(prov.file_of("scheme"), prov.line.count("scheme") ? prov.line.at("scheme") : group_line, group,
                "scheme",
                "scheme = '" + name(d.scheme) + "' recomputes its bounds over all n_species^2 = " +
                    std::to_string(mix.size() * mix.size()) +
                    " species pairs at every time step: with more than 256 species use scheme = 'lowrank' "
                    "(O(S log S), Bodrova and Osinsky 2024, docs/schemes.md)");
  // A block is a gas of its own for a step: it needs partners (and a block of a few particles gains
  // nothing from the cache); 64 is the mixtures' smallest slice (collide.hpp, "Mixtures in blocks").
  if (d.block_size > 0 && d.block_size < 64)
    throw Error(prov.file_of("block_size"), prov.line.count("block_size") ? prov.line.at("block_size") : group_line,
                group, "block_size",
                "a cache block needs at least 64 particles (got " + std::to_string(d.block_size) +
                    "); 0 turns the blocks off");
  const auto counts = species::particle_counts(static_cast<std::size_t>(d.n_particles), mix);
  for (std::size_t k = 0; k < counts.size(); ++k)
    if (counts[k] < 2)
      throw Error(prov.file_of("n_particles"),
                  prov.line.count("n_particles") ? prov.line.at("n_particles") : group_line,
                  group, "n_particles",
                  "n_particles = " + std::to_string(d.n_particles) + " gives " +
                      std::to_string(counts[k]) + " particle(s) of species " + std::to_string(k + 1) +
                      "; at least 2 per species are needed");
}

void check_output(Output& out, const Dsmc& d, const Provenance& prov) {
  for (const char* v : {"msd_start_time", "msd_start_temperature"})
    if (prov.line.count(v) && !out.track_displacements)
      throw Error(prov.file, prov.line.at(v), "output", v, "only used with track_displacements = .true.");
  if (out.msd_start_time && out.msd_start_temperature)
    throw Error(prov.file, prov.line.at("msd_start_temperature"), "output", "msd_start_temperature",
                "give at most one of msd_start_time and msd_start_temperature");
  if (out.msd_start_time && d.t_end && *out.msd_start_time >= *d.t_end)
    throw Error(prov.file, prov.line.at("msd_start_time"), "output", "msd_start_time",
                "msd_start_time must be below t_end");
  const double end = d.t_end ? *d.t_end : *d.collisions_per_particle;
  if (!out.sample_times.empty()) {
    const std::string file = prov.file_of("sample_times");
    const int line = prov.line.at("sample_times");
    for (const char* v : {"n_samples", "spacing", "first_sample"})
      if (prov.line.count(v))
        throw Error(prov.file_of(v), prov.line.at(v), "output", v,
                    "not used with sample_times (the explicit list sets every sample point)");
    for (std::size_t k = 0; k < out.sample_times.size(); ++k) {
      if (std::isnan(out.sample_times[k]))
        throw Error(file, line, "output", "sample_times", "sample_times(" + std::to_string(k + 1) + ") is not given");
      if (k > 0 && !(out.sample_times[k] > out.sample_times[k - 1]))
        throw Error(file, line, "output", "sample_times",
                    "sample_times must increase: element " + std::to_string(k + 1) + " is not above element " +
                        std::to_string(k));
    }
    if (out.sample_times.back() > end)
      throw Error(file, line, "output", "sample_times",
                  "the last sample point is beyond the end of the run (" + std::to_string(end) + ")");
    return;
  }
  if (out.spacing == Spacing::log) {
    if (!out.first_sample) out.first_sample = end / 1000.0;  // derive
    if (*out.first_sample >= end)
      throw Error(prov.file_of("first_sample"), prov.line.at("first_sample"), "output", "first_sample",
                  "first_sample must be below the end of the run (" + std::to_string(end) + ")");
  } else if (prov.line.count("first_sample")) {
    throw Error(prov.file_of("first_sample"), prov.line.at("first_sample"), "output", "first_sample",
                "only used with spacing = 'log'");
  }
}

/// Throws the input Error for `variable` of `group` where it was set (the group's line if it was not).
[[noreturn]] static void refuse_variable(const Provenance& p, const std::string& group, const std::string& variable,
                                         const std::string& message) {
  throw Error(p.file_of(variable), p.line.count(variable) ? p.line.at(variable) : p.group_line, group, variable, message);
}

void check_scales(const Config& c, std::map<std::string, Provenance>& prov) {
  constexpr double low = 1e-100, high = 1e100;
  const auto inside = [](double x) { return x >= low && x <= high; };
  // The temperatures a snapshot gave (&initial from_file, check_from_file) are refused as from_file's.
  const bool from_file = !c.initial.from_file.empty();
  const auto refuse = [&](const std::string& group, const std::string& variable, std::size_t k, double value,
                          const std::string& what) {
    const bool of_file = from_file && group == "initial" && !prov[group].line.count(variable);
    char text[200];
    std::snprintf(text, sizeof text, "%s%s(%zu) = %.6g is outside [1e-100, 1e100]",
                  of_file ? "its snapshot's velocities give " : "", what.c_str(), k + 1, value);
    refuse_variable(prov[group], group, of_file ? "from_file" : variable,
                    std::string(text) + ": the code computes in the input's units, where the velocities' fourth moments "
                    "(T/m)^2 and the collision rates must stay far inside double range; choose units in which these "
                    "are nearer 1 (docs/output.md \"Units\")");
  };
  const auto& sys = c.system;
  const std::size_t s = static_cast<std::size_t>(sys.n_species);
  for (std::size_t k = 0; k < s && k < sys.mass.size() && k < c.initial.temperature.size(); ++k) {
    if (!inside(sys.mass[k])) refuse("system", "mass", k, sys.mass[k], "mass");
    if (!inside(sys.diameter[k])) refuse("system", "diameter", k, sys.diameter[k], "diameter");
    if (!inside(sys.number_density[k])) refuse("system", "number_density", k, sys.number_density[k], "number_density");
    const double t = c.initial.temperature[k];
    if (!inside(t)) refuse("initial", "temperature", k, t, "temperature");
    if (!inside(t / sys.mass[k])) refuse("initial", "temperature", k, t / sys.mass[k], "temperature/mass");
    const double rate = sys.number_density[k] * sys.diameter[k] * sys.diameter[k] * std::sqrt(t / sys.mass[k]);
    if (!inside(rate)) refuse("system", "number_density", k, rate, "number_density x diameter^2 x sqrt(temperature/mass)");
    // Rough spheres: a spin far hotter than the translation makes the first collisions take ~sqrt(T_rot/T)
    // times longer than the later ones, whose time steps then vanish in the round-off of the clock.
    const auto& spin = c.initial.rotational_temperature;
    if (k < spin.size() && c.rough()) {
      // (0 exactly: no rotation at the start, docs/rough-spheres.md)
      if (spin[k] != 0.0 && !inside(spin[k])) refuse("initial", "rotational_temperature", k, spin[k], "rotational_temperature");
      if (!(spin[k] / t <= 1e20)) {
        const bool of_file = from_file && !prov["initial"].line.count("rotational_temperature");
        char text[360];
        std::snprintf(text, sizeof text,
                      "%srotational_temperature(%zu)/temperature(%zu) = %.3g is beyond 1e20: the first collisions would "
                      "take %.3g times as long as the later ones, whose time steps vanish in the clock's round-off (the "
                      "run would not end)%s",
                      of_file ? "its snapshot's velocities give " : "", k + 1, k + 1, spin[k] / t, std::sqrt(spin[k] / t),
                      of_file ? "" : "; start the translation warmer");
        refuse_variable(prov["initial"], "initial", of_file ? "from_file" : "rotational_temperature", text);
      }
    }
  }
}

void check_viscoelastic_range(const Config& c, std::map<std::string, Provenance>& prov) {
  const auto beta = c.viscoelastic_beta();
  if (!beta) return;
  const auto& sys = c.system;
  const std::size_t s = static_cast<std::size_t>(sys.n_species);
  double worst = 0.0, worst_speed = 0.0;
  for (std::size_t k = 0; k < s; ++k)
    for (std::size_t i = k; i < s; ++i) {
      const double speed = 7.0 * std::sqrt(c.initial.temperature[k] / sys.mass[k] + c.initial.temperature[i] / sys.mass[i]);
      const double u = std::sqrt((*beta)(k, i)) * std::pow(speed, 0.1);  // \ref visco_one_material "docs/viscoelastic.md"
      if (u > worst) {
        worst = u;
        worst_speed = speed;
      }
    }
  if (worst <= restitution::u_max) return;
  char text[512];
  std::snprintf(text, sizeof text,
                "u = beta^(1/2) |g.e|^(1/10) reaches %.3g at impact speed %.3g (7 thermal relative speeds at the initial "
                "temperature, about 1 in 1e11 collisions), beyond the series' cut-off %.2g: a smaller visco_a_kappa or a "
                "lower temperature (docs/viscoelastic.md \"Range of validity\")",
                worst, worst_speed, restitution::u_max);
  refuse_variable(prov["system"], "system", "visco_a_kappa", text);
}

/// Rough spheres (\ref rough_rule "docs/rough-spheres.md"): beta_kj resolved as restitution is, kappa_k and
/// T_rot,k(0) filled per species; refused where the loops have no rough rule (clusters, frames,
/// viscoelastic restitution), naming the variable that asks for it.
void check_rough(Config& c, std::map<std::string, Provenance>& prov) {
  Provenance& p = prov["system"];
  Provenance& q = prov["initial"];
  const auto s = static_cast<std::size_t>(c.system.n_species);
  const bool given = p.pair_assignments.count("roughness") != 0;
  const auto refuse = [&](Provenance& where, const std::string& group, const char* v, const std::string& message) {
    throw Error(where.file_of(v), where.line.count(v) ? where.line.at(v) : where.group_line, group, v, message);
  };
  if (!given) {
    if (p.line.count("moment_of_inertia"))
      refuse(p, "system", "moment_of_inertia", "only used with roughness (rough spheres)");
    if (q.line.count("rotational_temperature"))
      refuse(q, "initial", "rotational_temperature", "only used with &system roughness (rough spheres)");
    return;
  }
  c.system.roughness = resolve_pair_matrix("roughness", "beta", s, p, "system");
  // One value for all species; or per species, the species an element assignment left out (NaN) taking
  // the default.
  auto per_species = [&](std::vector<double>& values, Provenance& where, const std::string& group, const char* v,
                         const std::vector<double>& fill) {
    if (values.empty()) values = fill;
    if (values.size() == 1 && s > 1) values.assign(s, values[0]);
    for (std::size_t k = 0; k < values.size() && k < fill.size(); ++k)
      if (std::isnan(values[k])) values[k] = fill.size() == 1 ? fill[0] : fill[k];
    if (values.size() != s)
      refuse(where, group, v,
             "expected 1 or n_species = " + std::to_string(s) + " values, got " + std::to_string(values.size()));
  };
  per_species(c.system.moment_of_inertia, p, "system", "moment_of_inertia", {0.4});
  per_species(c.initial.rotational_temperature, q, "initial", "rotational_temperature", c.initial.temperature);
  if (!c.rough()) return;  // every beta_kj = -1: the smooth gas
  if (c.system.restitution_model != RestitutionModel::constant)
    refuse(p, "system", "roughness", "rough spheres run with restitution_model = 'constant' only");
  if (c.has_agg_frag)
    refuse(p, "system", "roughness", "rough spheres cannot run with &agg_frag (clusters have no moment of inertia here)");
  if (c.shear.rate || c.thermostat.kind == ThermostatKind::gaussian)
    refuse(p, "system", "roughness",
           "rough spheres cannot run with the Gaussian thermostat or &shear yet (the frame holds no angular velocity)");
}

/// &thermostat kind = 'white_noise' (\ref wn_forcing "docs/white-noise.md"): noise_strength chi^2_k filled per
/// species (one value: species 1, the others by equal forces chi^2_k = chi^2_1 (m_1/m_k)^2), finite; not
/// with &shear; noise_strength only with this kind.
void check_white_noise(Config& c, std::map<std::string, Provenance>& prov) {
  Provenance& p = prov["thermostat"];
  const auto refuse = [&](const char* v, const std::string& message) {
    throw Error(p.file_of(v), p.line.count(v) ? p.line.at(v) : p.group_line, "thermostat", v, message);
  };
  auto& chi2 = c.thermostat.noise_strength;
  if (c.thermostat.kind != ThermostatKind::white_noise) {
    if (!chi2.empty()) refuse("noise_strength", "only used with kind = 'white_noise'");
    return;
  }
  if (chi2.empty()) refuse("kind", "noise_strength is required with kind = 'white_noise'");
  if (c.shear.rate) refuse("kind", "white noise cannot run with &shear (the steady state of either alone is the one described)");
  const auto s = static_cast<std::size_t>(c.system.n_species);
  for (std::size_t k = 0; k < chi2.size(); ++k)
    if (!std::isfinite(chi2[k])) refuse("noise_strength", "noise_strength(" + std::to_string(k + 1) + ") is not finite");
  if (chi2.size() == 1)  // equal forces: m_k^2 chi^2_k the same for every species
    for (std::size_t k = 1; k < s; ++k)
      chi2.push_back(chi2[0] * (c.system.mass[0] / c.system.mass[k]) * (c.system.mass[0] / c.system.mass[k]));
  if (chi2.size() != s)
    refuse("noise_strength", "expected 1 or n_species = " + std::to_string(s) + " values, got " + std::to_string(chi2.size()));
}

/// &agg_frag (\ref af_outcome "docs/agg-frag.md"): the run starts from monomers of one constant-restitution, dilute
/// species, and the model runs in dsmc/agg_frag.hpp's own loop; every combination it cannot run is
/// refused here, naming the variable that asks for it.
void check_agg_frag(const Config& c, std::map<std::string, Provenance>& prov) {
  const std::string group = "agg_frag";
  Provenance& p = prov[group];
  const AggFrag& a = c.agg_frag;
  const auto where = [&](const std::string& g, const char* v) {
    const Provenance& q = prov[g];
    return std::make_pair(q.file_of(v), q.line.count(v) ? q.line.at(v) : q.group_line);
  };
  const auto refuse = [&](const std::string& g, const char* v, const std::string& message) {
    const auto [file, line] = where(g, v);
    throw Error(file, line, g, v, message);
  };
  if (!a.aggregation_energy && !a.fragmentation_energy)
    throw Error(p.file, p.group_line, group, "aggregation_energy",
                "&agg_frag needs aggregation_energy, fragmentation_energy or both");
  if (a.fragmentation_energy && !a.fragment_restitution)
    throw Error(p.file_of("fragmentation_energy"), p.line.at("fragmentation_energy"), group, "fragment_restitution",
                "required with fragmentation_energy");
  if (!a.fragmentation_energy && a.fragment_restitution)
    refuse(group, "fragment_restitution", "only used with fragmentation_energy");
  if (c.system.n_species != 1)
    refuse("system", "n_species",
           "&agg_frag starts from monomers: n_species must be 1 (cluster sizes become the species)");
  if (c.system.restitution_model != RestitutionModel::constant)
    refuse("system", "restitution_model", "&agg_frag runs with restitution_model = 'constant' only");
  if (c.system.enskog) refuse("system", "enskog", "&agg_frag runs in the dilute gas only (enskog = .false.)");
  if (c.dsmc.scheme != Scheme::lowrank)
    refuse("dsmc", "scheme",
           "&agg_frag runs with scheme = 'lowrank' only (cluster sizes as species, Bodrova and Osinsky 2024, docs/schemes.md); set scheme = "
           "'lowrank'");
  if (c.output.track_displacements)
    refuse("output", "track_displacements", "displacements are not tracked with &agg_frag");
}

/// &thermostat and &shear (\ref eta_thermostat "docs/shear-viscosity.md"): what the staged loop of simulation.cpp can run, and a shear
/// rate that keeps the finite-shear correction small. Refusals name the variable that asks for the
/// combination.
void check_staged(const Config& c, std::map<std::string, Provenance>& prov) {
  const auto refuse = [&](const std::string& g, const char* v, const std::string& message) {
    const Provenance& q = prov[g];
    throw Error(q.file_of(v), q.line.count(v) ? q.line.at(v) : q.group_line, g, v, message);
  };
  if (!c.staged()) {
    if (prov["shear"].line.count("average_from"))
      refuse("shear", "average_from", "only used with a shear rate");
    return;
  }
  const std::string what = c.shear.rate ? "&shear" : "&thermostat";
  if (c.has_agg_frag)
    refuse(c.shear.rate ? "shear" : "thermostat", c.shear.rate ? "rate" : "kind",
           what + " cannot run with &agg_frag: no forcing acts on the clusters' gas, which cools freely");
  if (c.system.enskog && c.shear.rate && c.dsmc.scheme != Scheme::pairs)
    refuse("dsmc", "scheme",
           "shear flow in the Enskog gas runs with scheme = 'pairs' only: its relative velocity "
           "g - a sigma e_y x depends on the direction e, which 'majorant' and 'lowrank' draw from g "
           "(docs/physics.md, shear flow)");
  if (c.system.restitution_model != RestitutionModel::constant)
    refuse("system", "restitution_model", what + " runs with restitution_model = 'constant' only");
  if (c.dsmc.scheme == Scheme::lowrank && c.system.n_species > 64)
    refuse("dsmc", "scheme", what + " runs with at most 64 species");
  if (!c.dsmc.t_end)
    refuse("dsmc", "collisions_per_particle", what + " runs are driven by t_end (stages end at times)");
  if (c.output.track_displacements)
    refuse("output", "track_displacements", "displacements are not tracked with " + what);
  if (c.shear.rate) {
    // a* = a / nu_0(T_0) with nu_0 = n T / eta_0, eta_0 = (5/(16 sigma^2)) sqrt(m T/pi) (\ref eta_thermostat "docs/shear-viscosity.md"),
    // species 1's size and mass for a mixture. Above a* = 1 at T_0 the start is far from the
    // Navier-Stokes regime the viscosity protocol measures.
    const double m = c.system.mass[0], sigma = c.system.diameter[0], t0 = c.initial.temperature[0];
    double n = 0.0;
    for (double x : c.system.number_density) n += x;
    const double eta0 = 5.0 / (16.0 * sigma * sigma) * std::sqrt(m * t0 / std::acos(-1.0));
    const double reduced = *c.shear.rate * eta0 / (n * t0);
    if (reduced > 1.0)
      refuse("shear", "rate",
             "a* = a/nu_0(T_0) = " + std::to_string(reduced) +
                 " > 1: far from the Navier-Stokes regime; lower rate or raise T_0 (a* <= 0.1 for the viscosity)");
    if (*c.shear.rate == 0.0) refuse("shear", "rate", "rate = 0: leave &shear out for no shear");
    if (c.shear.average_from && *c.shear.average_from >= *c.dsmc.t_end)
      refuse("shear", "average_from", "average_from must be below t_end");
  } else if (prov["shear"].line.count("average_from")) {
    refuse("shear", "average_from", "only used with a shear rate");
  }
}

std::vector<double> spaced(const Output& out, double end) {
  if (!out.sample_times.empty()) {  // 0, the list, and the end of the run
    std::vector<double> t{0.0};
    t.insert(t.end(), out.sample_times.begin(), out.sample_times.end());
    if (t.back() < end) t.push_back(end);
    return t;
  }
  const auto n = static_cast<std::size_t>(out.n_samples);
  std::vector<double> t(n, 0.0);
  if (out.spacing == Spacing::linear) {
    for (std::size_t i = 1; i < n; ++i) t[i] = end * static_cast<double>(i) / static_cast<double>(n - 1);
  } else {
    const double first = *out.first_sample;
    for (std::size_t i = 1; i < n; ++i)
      t[i] = n == 2 ? end
                    : first * std::pow(end / first, static_cast<double>(i - 1) / static_cast<double>(n - 2));
  }
  t.back() = end;
  return t;
}

/// A number as messages print it (%g: 1e-07, not 0.000000).
std::string shown(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

/// &output snapshot_times (io/snapshot.hpp): a time-driven free gas (the gas with forcings keeps its
/// velocities in a moving frame and samples a stage ahead: refused, not written wrong), increasing times
/// within [0, t_end], at most kSnapshotBytes in all (the run holds them in memory and gathers them).
void check_snapshot_times(const Config& c, Provenance& out) {
  const auto& times = c.output.snapshot_times;
  if (times.empty()) return;
  const auto refuse = [&](const std::string& message) {
    throw Error(out.file_of("snapshot_times"), out.line.at("snapshot_times"), "output", "snapshot_times", message);
  };
  if (!c.dsmc.t_end) refuse("snapshot_times needs t_end: the times of a collision-driven run are not known before it runs");
  if (c.has_agg_frag) refuse("not with &agg_frag: clusters change their species as they merge and break");
  if (c.staged()) refuse("not with &thermostat or &shear yet: snapshots are written for the free gas only");
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (std::isnan(times[k])) refuse("snapshot_times(" + std::to_string(k + 1) + ") is not given");
    if (k > 0 && !(times[k] > times[k - 1]))
      refuse("snapshot_times must increase: element " + std::to_string(k + 1) + " is not above element " + std::to_string(k));
  }
  if (times.back() > *c.dsmc.t_end) refuse("the last snapshot time is beyond t_end = " + shown(*c.dsmc.t_end));
  const double arrays = 1.0 + (c.rough() ? 1.0 : 0.0) + (c.output.track_displacements ? 1.0 : 0.0);
  const double bytes = static_cast<double>(c.dsmc.replicas) * static_cast<double>(times.size()) *
                       static_cast<double>(c.dsmc.n_particles) * 24.0 * arrays;
  if (bytes > kSnapshotBytes)
    refuse(shown(bytes / 1e9) + " GB of snapshots (replicas x snapshots x particles x 24 bytes per array): above " +
           shown(kSnapshotBytes / 1e9) + " GB, which the run would hold in memory; write fewer, or use fewer replicas");
}

/// &initial from_file: every replica of the file's /particles valid, with the run's species counts and
/// masses; the run's initial temperatures become those of the snapshots its replicas start from.
void check_from_file(Config& c, Provenance& ini) {
  const auto refuse = [&](const char* v, const std::string& message) {
    throw Error(ini.file_of(v), ini.line.count(v) ? ini.line.at(v) : ini.group_line, "initial", v, message);
  };
  if (c.has_agg_frag) refuse("from_file", "not with &agg_frag (its particles are monomers)");
  for (const char* v : {"temperature", "distribution"})
    if (ini.line.count(v)) refuse(v, "not used with from_file (the velocities come from the file)");
  const auto mix = c.mixture();
  const auto counts = species::particle_counts(static_cast<std::size_t>(c.dsmc.n_particles), mix);
  std::vector<snapshot::State> states;
  try {
    // (a damaged file can loop inside HDF5: the guard ends the process then, io/file_guard.hpp)
    const double limit = FileGuard::limit_seconds(c.initial.from_file);
    char after[200];
    std::snprintf(after, sizeof after,
                  "cannot start from it: the HDF5 library had not finished reading it after %.0f s: the file is "
                  "damaged, or on a very slow disk (GDSMC_READ_LIMIT=SECONDS allows longer)", limit);
    const std::string v = "from_file";
    const FileGuard guard(limit, nullptr,
                          {std::string(program_invocation_short_name) + ": " + Error(ini.file_of(v), ini.line.count(v) ? ini.line.at(v) : ini.group_line,
                                                             "initial", v, after).what(),
                           "", {}});
    // (replica 0 always: a file without snapshots is refused by read(), saying why)
    const std::size_t available = std::max<std::size_t>(1, snapshot::replicas(c.initial.from_file));
    for (std::size_t j = 0; j < std::min(static_cast<std::size_t>(c.dsmc.replicas), available); ++j)
      states.push_back(snapshot::read(c.initial.from_file, j, counts));
    snapshot::check_masses(c.initial.from_file, mix.mass);
  } catch (const std::runtime_error& e) {
    refuse("from_file", std::string("cannot start from it: ") + e.what());
  }
  const bool spins = !states.front().angular_velocity.empty();
  if (spins && ini.line.count("rotational_temperature"))
    refuse("rotational_temperature", "not used with from_file (its snapshot has the angular velocities)");
  // Replica r starts from the file's replica r mod R': the mean over the run's replicas, each about its
  // mean flow (as dsmc/sample.cpp measures).
  const auto replicas = static_cast<std::size_t>(c.dsmc.replicas);
  std::vector<double> translational(mix.size(), 0.0), rotational(mix.size(), 0.0);
  for (std::size_t j = 0; j < states.size(); ++j) {
    const double weight = static_cast<double>((replicas - 1 - j) / states.size() + 1) / static_cast<double>(replicas);
    const auto t = snapshot::temperatures(states[j], mix);
    for (std::size_t k = 0; k < mix.size(); ++k) {
      translational[k] += weight * t.translational[k];
      if (!t.rotational.empty()) rotational[k] += weight * t.rotational[k];
    }
  }
  c.initial.temperature = translational;
  if (!mix.rough()) return;
  if (spins) c.initial.rotational_temperature = rotational;
  else if (!ini.line.count("rotational_temperature")) c.initial.rotational_temperature = translational;  // its default
}

/// Particle snapshots and the start from one (io/snapshot.hpp).
void check_snapshots(Config& c, std::map<std::string, Provenance>& prov) {
  check_snapshot_times(c, prov["output"]);
  if (!c.initial.from_file.empty()) check_from_file(c, prov["initial"]);
}

}  // namespace detail

using namespace detail;  // the tables and steps of config_detail.hpp

std::optional<species::PairMatrix> Config::viscoelastic_beta() const {
  if (system.restitution_model != RestitutionModel::viscoelastic) return std::nullopt;
  return restitution::one_material_beta(mixture(), *system.visco_a_kappa);
}

species::Mixture Config::mixture() const {
  species::Mixture mix = species::make_mixture(system.mass, system.diameter, system.number_density,
                                               system.restitution, system.enskog);
  if (rough()) {
    mix.roughness = system.roughness;
    mix.moment_of_inertia = system.moment_of_inertia;
  }
  return mix;
}

bool Config::rough() const {
  if (system.roughness.size == 0) return false;
  const std::size_t s = system.roughness.size;
  if (!system.roughness.is_dense()) return system.roughness(0, 0) != -1.0;  // uniform
  for (std::size_t k = 0; k < s; ++k)
    for (std::size_t j = 0; j < s; ++j)
      if (system.roughness(k, j) != -1.0) return true;
  return false;
}

std::vector<double> Config::sample_times() const {
  return dsmc.t_end ? spaced(output, *dsmc.t_end) : std::vector<double>{};
}

std::vector<double> Config::sample_collisions() const {
  return dsmc.collisions_per_particle ? spaced(output, *dsmc.collisions_per_particle)
                                      : std::vector<double>{};
}

}  // namespace gdsmc::io::config
