#include "analysis/run_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include "model/species.hpp"
#include "theory/run_cost.hpp"

namespace gdsmc::analysis {

namespace {

constexpr double kMaxEvents = 1e12, kMinTemperatureRatio = 1e-40;

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

/// Where &dsmc `variable` was set (file, line), or the input file when it was not.
std::pair<std::string, int> origin_of(const io::config::Config& c, const std::string& variable) {
  const auto it = c.origin.find("dsmc:" + variable);
  return it == c.origin.end() ? std::pair<std::string, int>{c.source_file, 0} : it->second;
}

/// Refuses the run for `reason`, naming &dsmc `variable` (t_end or collisions_per_particle).
[[noreturn]] void refuse_run(const io::config::Config& c, const std::string& variable, const std::string& reason) {
  const auto [file, line] = origin_of(c, variable);
  throw io::namelist::Error(file, line, "dsmc", variable,
                            reason + "; shorten the run, or set &dsmc allow_long_run = .true. to run it anyway");
}

/// Refuses passes over all N particles (each `value` majorant mean free times long, at most `value` collisions
/// per particle, so at least C/value of them) beyond 1e13 particle updates, naming &dsmc `variable`.
void check_passes(const io::config::Config& c, const std::string& variable, double value, double collisions_per_particle,
                  const std::string& passes_name, const std::string& estimate, const std::string& larger) {
  const double passes = collisions_per_particle / value, n = static_cast<double>(c.dsmc.n_particles);
  if (passes * n <= 10.0 * kMaxEvents) return;
  const auto [file, line] = origin_of(c, variable);
  throw io::namelist::Error(file, line, "dsmc", variable,
                            variable + " = " + number(value) + " makes at least " + number(passes) + " " + passes_name +
                                " of N = " + number(n) + " particles each (" + estimate +
                                "), beyond 1e13 particle updates (a day or more); " + larger +
                                ", or &dsmc allow_long_run = .true.");
}

}  // namespace

void check_run_cost(const io::config::Config& c) {
  if (c.dsmc.allow_long_run) return;
  const theory::Cooling cooling = c.staged() ? theory::Cooling::held
                                  : c.system.restitution_model == io::config::RestitutionModel::viscoelastic ? theory::Cooling::viscoelastic
                                                                                 : theory::Cooling::haff;
  // A white noise heats the gas (its collisions grow as sqrt(T)): the estimate at the hottest it can be.
  std::vector<double> temperature = c.initial.temperature;
  double heating = 1.0;
  if (c.thermostat.kind == io::config::ThermostatKind::white_noise && c.dsmc.t_end) {
    heating = theory::white_noise_heating(c.mixture(), temperature, c.thermostat.noise_strength, *c.dsmc.t_end);
    for (double& t : temperature) t *= heating;
  }
  const theory::RunCost cost = theory::estimate_run_cost(c.mixture(), temperature, c.dsmc.t_end,
                                                         c.dsmc.collisions_per_particle, cooling);
  const double events = cost.collisions_per_particle * static_cast<double>(c.dsmc.n_particles) / 2.0;
  const char* variable = c.dsmc.t_end ? "t_end" : "collisions_per_particle";
  const std::string estimate = "kinetic theory estimates " + number(events) + " collision events per replica (" +
                               number(cost.collisions_per_particle) + " collisions per particle" +
                               (heating > 1.0 ? ", the white noise heating the gas up to " + number(heating) +
                                                    " times its initial temperature"
                                              : "") +
                               ")";
  std::string reason;
  if (!(cost.temperature_ratio >= kMinTemperatureRatio))
    reason = estimate + ", and a cooling to " + number(cost.temperature_ratio) +
             " of the initial temperature (Haff's law, docs/haff-and-mixtures.md): below 1e-40 the thermal speeds drown in the "
             "round-off of the conserved momentum, almost every candidate is rejected and the run would not end";
  else if (!(events <= kMaxEvents))
    reason = estimate + ", beyond 1e12 (a day or more)";
  if (!reason.empty()) refuse_run(c, variable, reason);
  // Each time step recomputes the speed bounds over all N particles (collide.hpp "Time"), and a step is
  // step_fraction majorant mean free times, at most step_fraction collisions per particle: a tiny
  // step_fraction makes the steps the whole run (1e-9 at N = 2000: years), whatever the events.
  check_passes(c, "step_fraction", c.dsmc.step_fraction, cost.collisions_per_particle, "time steps", estimate,
               "a larger step_fraction (1 is the default)");
  // A thermostat's or shear flow's stage (thermostat.hpp) passes over all N particles once per stage_step
  // majorant mean free times, at most stage_step collisions per particle: the same bound.
  if (c.staged())
    check_passes(c, "stage_step", c.dsmc.stage_step, cost.collisions_per_particle, "stages", estimate,
                 "a larger stage_step (0.125 is the default, 1 with the white noise)");
}

MemoryLimit memory_limit() {
  MemoryLimit limit{static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE)),
                    "this machine's memory"};
  if (struct rlimit as {}; ::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY &&
                           static_cast<double>(as.rlim_cur) < limit.bytes)
    limit = {static_cast<double>(as.rlim_cur), "the address-space limit (ulimit -v)"};
  if (!(limit.bytes > 0.0)) limit.bytes = 0.0;
  return limit;
}

double theory_memory_bytes(const io::config::Config& config) {
  // Up to 1000 species the tables are at most 60 MB: not counted.
  if (config.has_agg_frag || config.system.n_species <= 1000) return 0.0;
  // Measured peaks of granular-theory (docs/performance.md#perf_theory): 1300 species 0.25 GB, 2000
  // 0.41 GB, 3000 0.66 GB, 4000 0.95 GB: 42-67 bytes per added pair of species, above a base of 0.15 GB
  // (0.2 GB and 60 bytes here, upper estimates).
  const double s = static_cast<double>(config.system.n_species);
  return 2e8 + 60.0 * s * s;
}

void check_theory_memory(const io::config::Config& config, const std::string& remedy) {
  const double need = theory_memory_bytes(config);
  const MemoryLimit have = memory_limit();
  if (!(have.bytes > 0.0) || need <= have.bytes) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "the theory of %ld species needs about %.3g GB (its O(S^2) tables of pairs of species), more than %s "
                "(%.3g GB); %s",
                static_cast<long>(config.system.n_species), need / 1e9, have.what.c_str(), have.bytes / 1e9,
                remedy.c_str());
  const auto it = config.origin.find("system:n_species");
  const std::string file = it == config.origin.end() ? config.source_file : it->second.first;
  const int line = it == config.origin.end() ? 0 : it->second.second;
  throw io::namelist::Error(file, line, "system", "n_species", text);
}

std::vector<std::string> input_warnings(const io::config::Config& config) {
  std::vector<std::string> out;
  double densest = 0.0;
  std::size_t densest_point = 0;  // (of a sweep: the point named in the warning)
  const auto points = config.sweep_points();
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto mix = points[k].mixture();
    // (&agg_frag is the dilute cluster gas by definition, docs/agg-frag.md: enskog cannot be set there)
    if (!mix.enskog && !points[k].has_agg_frag && mix.packing_fraction() > densest) {
      densest = mix.packing_fraction();
      densest_point = k;
    }
  }
  if (densest > kDenseWarning) {
    char text[400];
    if (densest < species::carnahan_starling_fluid_limit) {
      const double chi = (1.0 - densest / 2.0) / std::pow(1.0 - densest, 3);  // Carnahan-Starling, docs/collision-model.md
      std::snprintf(text, sizeof text,
                    "packing fraction %.3g without enskog: this runs a dilute (Boltzmann) gas, whose collision rate "
                    "ignores the density (the Enskog gas collides %.3g times as often); set &system enskog = .true. "
                    "for a dense gas (warned above %g)", densest, chi, kDenseWarning);
    } else {
      // Carnahan-Starling's chi is a fluid's (phi < 0.5; it diverges at phi = 1 and is negative beyond) and enskog refuses
      // such a gas: quote neither.
      std::snprintf(text, sizeof text,
                    "packing fraction %.3g without enskog: this runs a dilute (Boltzmann) gas, whose collision rate "
                    "ignores the density; no Enskog gas is that dense (the Carnahan-Starling fluid ends at %g, where "
                    "enskog stops): check the number densities and diameters (warned above %g)",
                    densest, species::carnahan_starling_fluid_limit, kDenseWarning);
    }
    // The gas as &system writes it, or else the densest point of the sweep that made it dense, named as the
    // sweep's own errors name a point (io/config_sweep.cpp).
    const auto base = config.mixture();
    const bool by_sweep = config.is_sweep() && !(base.packing_fraction() > kDenseWarning && !base.enskog);
    const std::string key = by_sweep ? "sweep:values" : "system:number_density";
    const std::string message =
        by_sweep ? "point " + std::to_string(densest_point + 1) + " (" +
                       config.sweep.row_label(config.sweep.table()[densest_point]) + "): " + text
                 : std::string(text);
    const auto it = config.origin.find(key);
    const std::string file = it == config.origin.end() ? config.source_file : it->second.first;
    const int line = it == config.origin.end() ? 0 : it->second.second;
    out.emplace_back(io::namelist::Error(file, line, by_sweep ? "sweep" : "system", by_sweep ? "values" : "number_density",
                                         message).what());
  }
  // Variables given that no point of the run uses (a warning, not a refusal: an output of an older build that
  // wrote them must still read, and a sweep may stage some points only).
  const auto warn_unused = [&](const std::string& group, const std::string& variable, const std::string& text) {
    const auto it = config.origin.find(group + ":" + variable);
    if (it == config.origin.end()) return;
    out.emplace_back(io::namelist::Error(it->second.first, it->second.second, group, variable, text).what());
  };
  if (config.dsmc.stage_step != io::config::Dsmc{}.stage_step &&
      std::none_of(points.begin(), points.end(), [](const io::config::Config& p) { return p.staged(); }))
    warn_unused("dsmc", "stage_step", "only used with &thermostat or &shear (the length of their stages): no effect here");
  if (config.sweep.grid && !config.is_sweep())
    warn_unused("sweep", "grid", "only used with variable and values (a sweep): no sweep is run");
  return out;
}

}  // namespace gdsmc::analysis
