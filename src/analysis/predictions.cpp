// Everything the theory predicts for one Config (predictions.hpp): the computations granular-theory
// made in place before, moved here unchanged so that granular-dsmc --compare uses the same numbers.
#include "analysis/predictions.hpp"

#include <array>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <numbers>
#include <string>

#include "io/namelist.hpp"
#include "theory/theory.hpp"
#include "theory/viscosity.hpp"

namespace gdsmc::analysis {

// Every formula is the theory module's (this file only evaluates it for one Config).
using namespace gdsmc::theory;


namespace {

/// Runs `integrate` (an ODE integration over the run's sample points) and turns its failure, e.g.
/// CVODE giving up on t_end = 1e300, into an input error naming the variable that sets the end of
/// the run (t_end or collisions_per_particle), where it was set, as granular-dsmc names refusals.
template <class F>
auto over_the_run(const io::config::Config& config, F&& integrate) {
  try {
    return integrate();
  } catch (const io::namelist::Error&) {
    throw;
  } catch (const smoluchowski::Stopped&) {
    throw;
  } catch (const std::exception& e) {
    const char* variable = config.dsmc.t_end ? "t_end" : "collisions_per_particle";
    const auto it = config.origin.find(std::string("dsmc:") + variable);
    const std::string file = it == config.origin.end() ? config.source_file : it->second.first;
    const int line = it == config.origin.end() ? 0 : it->second.second;
    char end[32];
    std::snprintf(end, sizeof end, "%.6g", config.dsmc.t_end ? *config.dsmc.t_end : *config.dsmc.collisions_per_particle);
    throw io::namelist::Error(file, line, "dsmc", variable,
                              std::string("the theory cannot integrate to ") + variable + " = " + end + ": " + e.what());
  }
}

/// The Smoluchowski equations of smoluchowski.hpp on the run's sample points, in the units of the
/// DSMC observables (counts for n_particles initial monomers).
AggFragPrediction agg_frag_prediction(const io::config::Config& config, const smoluchowski::Stop& stop) {
  namespace sm = smoluchowski;
  const sm::Parameters p = smoluchowski_parameters(config);
  AggFragPrediction out;
  out.initial_monomers = static_cast<double>(config.dsmc.n_particles);
  out.solution = over_the_run(config, [&] {
    std::vector<double> times = config.sample_times();
    if (times.empty()) {  // collision-driven: the times at which 2 x collisions per monomer reach the targets
      const auto targets = config.sample_collisions();
      double horizon = 1.0;
      for (int guard = 0; guard < 60 && 2.0 * sm::solve(p, {0.0, horizon}, stop).collisions.back() < targets.back(); ++guard)
        horizon *= 2.0;
      const std::size_t grid = 2001;
      std::vector<double> t(grid);
      for (std::size_t i = 0; i < grid; ++i) t[i] = horizon * static_cast<double>(i) / (grid - 1);
      const auto fine = sm::solve(p, t, stop);
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
    return sm::solve(p, times, stop);
  });
  out.initial_rates = sm::initial_rates(p);
  const auto& sol = out.solution;
  const std::size_t nt = sol.time.size(), kt = sol.max_size;
  // Columns up to the largest size of which the run would hold 1e-6 clusters or more at some time
  // (the equations integrate sizes far beyond, to keep the lost mass below 1e-8).
  for (std::size_t i = 0; i < nt; ++i)
    for (std::size_t k = 0; k < kt; ++k)
      if (sol.number_fraction[i * kt + k] * out.initial_monomers >= 1e-6) out.width = std::max(out.width, k + 1);
  out.mean_size.resize(nt);
  out.monomer_fraction.resize(nt);
  out.collisions_per_particle.resize(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    double clusters = 0.0;
    for (std::size_t k = 0; k < kt; ++k) clusters += sol.number_fraction[i * kt + k];
    out.mean_size[i] = 1.0 / clusters;
    out.monomer_fraction[i] = sol.number_fraction[i * kt];
    out.collisions_per_particle[i] = 2.0 * sol.collisions[i];
  }
  return out;
}

}  // namespace

theory::smoluchowski::Parameters smoluchowski_parameters(const io::config::Config& config) {
  theory::smoluchowski::Parameters p;
  p.monomer_mass = config.system.mass[0];
  p.monomer_diameter = config.system.diameter[0];
  p.monomer_density = config.system.number_density[0];
  p.initial_temperature = config.initial.temperature[0];
  p.restitution = config.system.restitution(0, 0);
  p.aggregation_energy = config.agg_frag.aggregation_energy.value_or(0.0);
  p.fragmentation_energy = config.agg_frag.fragmentation_energy.value_or(std::numeric_limits<double>::infinity());
  p.fragment_restitution = config.agg_frag.fragment_restitution.value_or(1.0);
  return p;
}

namespace {

/// The Maxwellian collision frequencies and cooling rates at t = 0 (\ref cm_mixture_rate "docs/collision-model.md", \ref haff_mixture_odes "docs/haff-and-mixtures.md").
void add_rates(Predictions& out, const species::Mixture& mix, const std::vector<double>& t0,
               const std::optional<species::PairMatrix>& beta) {
  // Collisions suffered by species k per unit volume: 2 P_kk + sum_{j != k} P_kj (\ref cm_mixture_rate
  // "docs/collision-model.md"), and zeta_k = sum_j xi_kj, in O(S) memory for constant restitution
  // (viscoelastic restitution keeps its S x S matrix).
  out.collision_frequency = collision_frequencies(mix, t0);
  if (beta) {
    const auto xi = cooling_rate_matrix_viscoelastic(mix, *beta, t0);
    out.cooling_rate.assign(mix.size(), 0.0);
    for (std::size_t k = 0; k < mix.size(); ++k)
      for (std::size_t j = 0; j < mix.size(); ++j) out.cooling_rate[k] += xi(k, j);
  } else {
    out.cooling_rate = cooling_rates(mix, t0);
  }
  out.approximations = {{"collision_frequency", "maxwellian"}, {"cooling_rate", "maxwellian"}};

}

/// The free-cooling history on the run's sample points (the partial-temperature ODEs); returned for the
/// diffusion's end temperatures.
theory::TemperatureHistory add_history(Predictions& out, const io::config::Config& config, const species::Mixture& mix,
                                       const std::optional<species::PairMatrix>& beta) {
  const std::size_t s = mix.size();
  const auto& t0 = config.initial.temperature;
  const double n = mix.total_density();
  std::vector<double> times = config.sample_times();
  if (times.empty())
    times = over_the_run(config, [&] {
      // (the history's own cooling maps collisions to times: viscoelastic spheres cool more slowly)
      if (beta)
        return times_for_collisions(mix, t0, config.sample_collisions(), [&](const std::vector<double>& grid) {
          return integrate_partial_temperatures_viscoelastic(mix, *beta, t0, grid);
        });
      return times_for_collisions(mix, t0, config.sample_collisions());
    });
  const auto history = over_the_run(config, [&] {
    return beta ? integrate_partial_temperatures_viscoelastic(mix, *beta, t0, times)
                : integrate_partial_temperatures(mix, t0, times);
  });
  out.final_temperature = history.temperature.back();
  if (config.staged()) {
    // The free-cooling history does not describe a run with a thermostat or a shear flow.
    // (a copy of a named string: GCC 12 warns falsely (-Warray-bounds) on the move of a temporary here)
    static const std::string staged_note =
        "temperature, total_temperature, collisions_per_particle left out: the run has &thermostat "
        "or &shear (T is held or heated; see shear_viscosity_ratio, temperature_ratio)";
    out.notes.push_back(staged_note);
  } else {
    out.has_history = true;
    out.time = history.time;
    out.temperature = history.temperature;
    for (std::size_t i = 0; i < history.time.size(); ++i) {
      double tt = 0.0;
      for (std::size_t k = 0; k < s; ++k) tt += mix.number_density[k] * history.temperature[i][k];
      out.total_temperature.push_back(tt / n);
      out.collisions_per_particle.push_back(2.0 * history.collisions[i] / n);
    }
    for (const char* key : {"temperature", "total_temperature", "collisions_per_particle"})
      out.approximations.emplace_back(key, "maxwellian");
  }
  return history;
}

/// D_k/D_1 and the MSD (Bodrova and Osinsky 2024, eqs. (16)-(21), \ref dif_coefficients "docs/diffusion-msd.md").
void add_diffusion(Predictions& out, const io::config::Config& config, const species::Mixture& mix,
                   const std::optional<species::PairMatrix>& beta, const theory::TemperatureHistory& history) {
  const auto& t0 = config.initial.temperature;
  // D_k/D_1 at long times (constant alpha) or at the end
  // of the run (viscoelastic, where the ratios drift), and eq 17's MSD when displacements are tracked.
  try {
    out.diffusion_coefficient_ratio = beta ? diffusion_coefficient_ratio(mix, history.temperature.back(), &*beta)
                                           : diffusion_coefficient_ratio(mix);
    out.approximations.emplace_back("diffusion_coefficient_ratio", "maxwellian");
  } catch (const std::exception& e) {  // e.g. the HCS ratios' ODE at a mass ratio of 1e20: left out, with a word why
    out.diffusion_coefficient_ratio.clear();
    out.notes.push_back(std::string("diffusion_coefficient_ratio left out: ") + e.what());
  }
  if (config.output.track_displacements) {
    // The MSD counts from msd_start_time (or t = 0), starting from the theory's temperatures then.
    const double start = config.output.msd_start_time.value_or(0.0);
    std::vector<double> start_temperature = t0;
    if (start > 0.0) {
      const auto at = over_the_run(config, [&] {
        return beta ? integrate_partial_temperatures_viscoelastic(mix, *beta, t0, {0.0, start})
                    : integrate_partial_temperatures(mix, t0, {0.0, start});
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
      const auto msd = mean_squared_displacement(mix, start_temperature, since, beta ? &*beta : nullptr);
      out.msd = Trajectory{shifted_times, msd.msd};
      out.approximations.emplace_back("msd", "maxwellian");
    }
  }
}

/// The Sonine theory of the HCS: a2 of one species, the asymptotic ratios, first Sonine of any number
/// of species, the binary HCS with tails (\ref son_binary "docs/sonine.md", \ref haff_sonine "docs/haff-and-mixtures.md").
void add_sonine(Predictions& out, const species::Mixture& mix, const std::optional<species::PairMatrix>& beta) {
  const std::size_t s = mix.size();
  std::optional<std::vector<double>> maxwellian_ratios;  // asymptotic T_k/T_1 (constant alpha)
  if (beta) {
    // Constant-alpha keys (Sonine HCS, asymptotic ratios) do not apply to viscoelastic spheres.
  } else if (s == 1) {
    const double a2 = sonine_a2(mix.restitution(0, 0));
    out.sonine_a2 = a2;
    out.cooling_rate_sonine = out.cooling_rate[0] * (1.0 + 3.0 * a2 / 16.0);  // \ref haff_sonine "docs/haff-and-mixtures.md"
    out.approximations.emplace_back("sonine_a2", "first_sonine");
    out.approximations.emplace_back("sonine_c", "first_sonine");
    out.approximations.emplace_back("cooling_rate_sonine", "first_sonine");
  } else {
    const bool inelastic = mix.restitution.max() < 1.0;
    if (inelastic) {
      try {
        out.asymptotic_temperature_ratio = asymptotic_temperature_ratios(mix);
        out.approximations.emplace_back("asymptotic_temperature_ratio", "maxwellian");
        maxwellian_ratios = out.asymptotic_temperature_ratio;
      } catch (const std::exception& e) {  // a key that cannot be evaluated is left out, with a word why
        out.notes.push_back(std::string("asymptotic_temperature_ratio left out: ") + e.what());
      }
    } else {
      maxwellian_ratios = std::vector<double>(s, 1.0);  // elastic: equipartition
    }
  }
  // HCS of any number of species, constant restitution (theory/sonine_mixture.hpp): first Sonine,
  // and the Maxwellian ratios in the same normalisation (T_k/T, T = sum_k n_k T_k/n).
  if (!beta) {
    if (s == 1) maxwellian_ratios = std::vector<double>{1.0};
    try {
      out.hcs_first_sonine = hcs_first_sonine(mix, maxwellian_ratios.value_or(std::vector<double>{}));
    } catch (const std::exception& e) {
      out.notes.push_back(std::string("hcs.first_sonine left out: ") + e.what());
    }
    if (maxwellian_ratios) {
      try {
        std::vector<double> t = *maxwellian_ratios;
        double mean = 0.0;
        for (std::size_t k = 0; k < s; ++k) mean += mix.mole_fraction(k) * t[k];
        for (double& v : t) v /= mean;
        out.hcs_maxwellian_cooling_rate_reduced = hcs_maxwellian_cooling_rate_reduced(mix, t);
        out.hcs_maxwellian_temperature_over_mean = t;
      } catch (const std::exception& e) {
        out.notes.push_back(std::string("hcs.maxwellian left out: ") + e.what());
      }
    }
    if (out.hcs_first_sonine) out.approximations.emplace_back("hcs.first_sonine", "first_sonine");
    if (out.hcs_maxwellian_temperature_over_mean) out.approximations.emplace_back("hcs.maxwellian", "maxwellian");
  }
  if (s == 2 && !beta) {
    try {
      out.binary_hcs = binary_hcs_first_sonine(mix);
    } catch (const std::exception& e) {  // e.g. gamma outside the root finder's range
      out.notes.push_back(std::string("binary HCS keys (temperature_ratio, sonine_c, ...) left out: ") + e.what());
    }
  }
  if (out.binary_hcs) {  // binary HCS in first Sonine approximation (Montanero and Garzo 2002, App. A, \ref son_binary "docs/sonine.md")
    const auto& hcs = *out.binary_hcs;
    if (hcs.cooling_rate > 0.0)
      for (int k = 0; k < 2; ++k) out.binary_tail_decay_rate[k] = tail_decay_rate(hcs, k);
    out.approximations.emplace_back("temperature_ratio", "first_sonine");
    out.approximations.emplace_back("sonine_c", "first_sonine");
    out.approximations.emplace_back("cooling_rate_reduced", "first_sonine");
    out.approximations.emplace_back("tail_beta", "high_velocity_asymptotics");
    if (hcs.cooling_rate > 0.0)
      out.approximations.emplace_back("tail_decay_rate", "high_velocity_asymptotics_first_sonine");
  }
}

/// The steady shear flow without thermostat in Grad's solution (\ref eta_usf_steady "docs/shear-viscosity.md"): one
/// dilute species or a dilute binary of smooth spheres.
void add_steady_shear(Predictions& out, const species::Mixture& mix, bool rough, bool sheared) {  // sheared: &shear, no thermostat
  namespace vt = viscosity;
  if (rough || mix.enskog || mix.size() > 2) {
    if (sheared)
      out.notes.push_back("steady_shear left out: Grad's steady shear flow is implemented for one dilute species or a "
                          "dilute binary of smooth spheres (docs/shear-viscosity.md)");
    return;
  }
  bool elastic = true;  // no steady shear flow: the elastic gas heats
  for (double alpha : mix.restitution.values) elastic = elastic && alpha == 1.0;
  if (elastic) return;
  try {
    if (mix.size() == 1) {
      const auto one = vt::steady_shear_grad(mix.restitution(0, 0));
      out.steady_shear_grad = vt::MixtureSteadyShear{{1.0}, one.reduced_shear_rate, one.pressure_xx, one.pressure_yy,
                                                     one.pressure_zz, one.pressure_xy};
    } else {
      out.steady_shear_grad = vt::steady_shear_grad(mix);
    }
    out.approximations.emplace_back("steady_shear", "grad");
  } catch (const std::exception& e) {
    if (sheared) out.notes.push_back(std::string("steady_shear left out: ") + e.what());  // (else no one asked)
  }
}

/// The shear viscosity (below).
void add_viscosity(Predictions& out, const species::Mixture& mix, const std::optional<species::PairMatrix>& beta) {
  const std::size_t s = mix.size();
  // Shear viscosity eta/eta_0 in first Sonine (Montanero 2003, \ref eta_one_species "docs/shear-viscosity.md", \ref eta_measured "docs/shear-viscosity.md"; theory/viscosity.hpp): one
  // species, dilute or Enskog; binary mixtures, dilute or Enskog, over the elastic mixture value. In
  // the Enskog gas also the kinetic part alone (Montanero 2003, Fig. 10, \ref eta_mixture "docs/shear-viscosity.md").
  if (!beta && (s == 1 || (s == 2 && out.binary_hcs))) {
    namespace vt = viscosity;
    try {
      // {total, kinetic} of eta/eta_0
      auto reduced = [&](vt::State state) -> std::array<double, 2> {
        if (s == 2) {
          const auto v = vt::binary_viscosity(mix, 1.0, state);
          return {v.reduced, v.kinetic / v.elastic};
        }
        const double alpha = mix.restitution(0, 0);
        if (!mix.enskog) {
          const double eta = vt::dilute_reduced_viscosity(alpha, state);
          return {eta, eta};
        }
        const auto v = vt::enskog_reduced_viscosity(alpha, mix.packing_fraction(), state);
        return {v.total, v.kinetic};
      };
      const auto hcs = reduced(vt::State::homogeneous_cooling);
      const auto hss = reduced(vt::State::gaussian_thermostat);
      out.shear_viscosity_hcs = hcs[0];
      out.shear_viscosity_hss = hss[0];
      out.approximations.emplace_back("shear_viscosity_ratio", "first_sonine");
      if (mix.enskog) {
        out.shear_viscosity_kinetic_hcs = hcs[1];
        out.shear_viscosity_kinetic_hss = hss[1];
        out.approximations.emplace_back("shear_viscosity_kinetic_ratio", "first_sonine");
      }
      if (s == 2) {  // eta* = nu eta/(n T) = (nu eta_0/(n T)) eta/eta_0, at T = 1 (the factor is T-free)
        out.shear_viscosity_reduced_factor = vt::binary_reduced_viscosity_frequency(mix, 1.0) *
                                             vt::elastic_mixture_viscosity(mix, 1.0) / mix.total_density();
        out.approximations.emplace_back("shear_viscosity_reduced", "first_sonine");
        if (mix.enskog) out.approximations.emplace_back("shear_viscosity_kinetic_reduced", "first_sonine");
      }
    } catch (const std::exception& e) {
      out.notes.push_back(std::string("shear_viscosity_ratio left out: ") + e.what());
    }
  }
}

}  // namespace

namespace {

/// Rough spheres (\ref rough_maxwellian "docs/rough-spheres.md"): the collision frequency (the centres'
/// relative velocities only: as for smooth spheres) and, for one species, the Maxwellian two-temperature
/// history and HCS; nothing of the smooth-sphere theory.
Predictions predict_rough(const io::config::Config& config) {
  Predictions out;
  const auto mix = config.mixture();
  const std::size_t s = mix.size();
  out.n_species = s;
  add_rates(out, mix, config.initial.temperature, std::nullopt);
  out.cooling_rate.clear();
  out.approximations = {{"collision_frequency", "maxwellian"}};
  out.notes.push_back("rough spheres: the smooth-sphere theory (Sonine a2, temperature ratios, diffusion, viscosity) "
                      "is left out");
  if (s != 1) {
    out.notes.push_back("rough mixtures: the Maxwellian HCS only (T_k/T, theta_k); no history, no Sonine theory");
    auto hcs = rough::mixture_cooling_state(mix);
    if (hcs.theta.empty()) out.notes.push_back("rough mixtures: no Maxwellian HCS: " + hcs.why_not);
    else {
      out.rough_mixture_hcs = std::move(hcs);
      out.approximations.emplace_back("rough_hcs.maxwellian", "maxwellian");
    }
    return out;
  }
  const double t_tr = config.initial.temperature[0], t_rot = config.initial.rotational_temperature[0];
  const auto k = rough::coefficients(mix.restitution(0, 0), mix.roughness(0, 0), mix.moment_of_inertia[0]);
  out.cooling_rate = {out.collision_frequency[0] * 4.0 / 3.0 * (k.a - k.b * t_rot / t_tr)};  // zeta_tr at t = 0
  out.approximations.emplace_back("cooling_rate", "maxwellian");
  const bool by_collisions = !config.dsmc.t_end;
  const auto h = over_the_run(config, [&] {
    return rough::integrate(mix, t_tr, t_rot, by_collisions ? config.sample_collisions() : config.sample_times(), by_collisions);
  });
  out.final_temperature = {h.translational.back()};
  out.rough_hcs_maxwellian = rough::cooling_state(mix.restitution(0, 0), mix.roughness(0, 0), mix.moment_of_inertia[0]);
  out.rough_zeta_star = mix.pair_correlation(0, 0) * out.rough_hcs_maxwellian->cooling_rate_reduced;
  out.rough_unit_frequency = rough::frequency_unit(mix) / mix.pair_correlation(0, 0);
  out.rough_hcs_sonine = rough::sonine_cooling_state(mix.restitution(0, 0), mix.roughness(0, 0), mix.moment_of_inertia[0]);
  if (auto& st = out.rough_hcs_sonine->state) st->cooling_rate_reduced *= mix.pair_correlation(0, 0);
  out.has_history = true;
  out.time = h.time;
  for (std::size_t i = 0; i < h.time.size(); ++i) out.temperature.push_back({h.translational[i]});
  out.total_temperature = h.translational;
  out.collisions_per_particle = h.collisions_per_particle;
  out.rotational_temperature = h.rotational;
  for (const char* key : {"temperature", "total_temperature", "collisions_per_particle", "rotational_temperature",
                          "rough_hcs.maxwellian"})
    out.approximations.emplace_back(key, "maxwellian");
  if (out.rough_hcs_sonine->state) out.approximations.emplace_back("rough_hcs.sonine", "first_sonine");
  return out;
}

/// The white-noise steady state of one species (\ref wn_theory "docs/white-noise.md"): T_tr^(3/2) =
/// m chi^2 / (zeta* nu_1), nu = nu_1 sqrt(T_tr), nu_1 = 4 n sigma^2 chi sqrt(pi/m), zeta* = (4/3)(A - B theta)
/// (Maxwellian) or the Sonine state's (theory/rough.hpp).
void add_white_noise(Predictions& out, const io::config::Config& config, const species::Mixture& mix) {
  if (mix.size() != 1) {
    auto state = rough::mixture_driven_state(mix, config.thermostat.noise_strength);
    if (state.translational.empty()) return out.notes.push_back("white noise: " + state.why_not);
    out.approximations.emplace_back("white_noise.maxwellian", "maxwellian");
    if (mix.rough()) {  // (more than 64 species have no Maxwellian state above, which starts the Sonine one)
      out.white_noise_mixture_sonine_why_not = "not computed: the Sonine theory of driven rough mixtures is not implemented";
    } else {
      try {
        out.white_noise_mixture_sonine = white_noise_first_sonine(mix, config.thermostat.noise_strength, state.translational);
        out.approximations.emplace_back("white_noise.sonine", "first_sonine");
      } catch (const std::exception& e) {
        out.white_noise_mixture_sonine_why_not = e.what();
      }
    }
    out.approximations.emplace_back("white_noise.translational_temperature",
                                    out.white_noise_mixture_sonine ? "first_sonine" : "maxwellian");
    if (!out.white_noise_mixture_sonine)
      out.notes.push_back("white noise, mixtures: the Maxwellian steady state only (first Sonine: " +
                          out.white_noise_mixture_sonine_why_not + ")");
    if (out.hcs_first_sonine)
      out.notes.push_back("white noise: the hcs keys describe the free cooling of the same gas, not this driven state");
    out.white_noise_mixture = std::move(state);
    return;
  }
  const bool rough_gas = mix.rough();
  const auto state = rough::driven_state(mix.restitution(0, 0), rough_gas ? mix.roughness(0, 0) : -1.0,
                                         rough_gas ? mix.moment_of_inertia[0] : 0.4);
  const double alpha = mix.restitution(0, 0), beta = rough_gas ? mix.roughness(0, 0) : -1.0;
  if ((alpha == 1.0 && std::abs(beta) == 1.0) || !(state.cooling_rate_reduced > 1e-12)) {  // nothing balances the kicks
    out.notes.push_back("white noise: no steady state (the collisions lose no energy: T_tr grows as T(0) + m chi^2 t)");
    return;
  }
  const double m = mix.mass[0];
  const auto steady_temperature = [&](double cooling_rate_reduced) {
    return std::pow(m * config.thermostat.noise_strength[0] / (cooling_rate_reduced * rough::frequency_unit(mix)), 2.0 / 3.0);
  };
  Predictions::WhiteNoise w;
  w.translational_temperature = steady_temperature(state.cooling_rate_reduced);
  if (rough_gas) w.theta = state.theta;
  w.sonine = rough::sonine_driven_state(mix.restitution(0, 0), rough_gas ? mix.roughness(0, 0) : -1.0,
                                        rough_gas ? mix.moment_of_inertia[0] : 0.4);
  if (w.sonine.state && w.sonine.state->cooling_rate_reduced > 1e-12)
    w.sonine_temperature = steady_temperature(w.sonine.state->cooling_rate_reduced);
  else if (w.sonine.state)
    w.sonine = {std::nullopt, "no Sonine steady state (the Sonine cooling rate is not positive)"};
  out.white_noise = w;
  out.approximations.emplace_back("white_noise.maxwellian", "maxwellian");
  if (w.sonine.state) out.approximations.emplace_back("white_noise.sonine", "first_sonine");
  out.approximations.emplace_back("white_noise.translational_temperature", w.sonine_temperature ? "first_sonine" : "maxwellian");
  if (out.sonine_a2 || out.hcs_first_sonine)
    out.notes.push_back("white noise: the hcs and sonine keys describe the free cooling of the same gas, not this driven state");
}

}  // namespace

Predictions predict(const io::config::Config& config, const smoluchowski::Stop& stop) {
  if (config.rough()) {
    Predictions out = predict_rough(config);
    if (config.thermostat.kind == io::config::ThermostatKind::white_noise) {
      out.has_history = false;  // the free-cooling history does not describe a driven run
      out.notes.push_back("temperature, rotational_temperature left out: the run is driven by white noise");
      add_white_noise(out, config, config.mixture());
    }
    return out;
  }
  Predictions out;
  if (config.has_agg_frag) {
    out.agg_frag = agg_frag_prediction(config, stop);
    out.approximations.emplace_back("initial_rates", "exact");
    for (const char* key : {"number", "temperature", "total_temperature", "kinetic_energy", "mean_size",
                            "monomer_fraction", "collisions", "aggregations", "fragmentations", "collisions_per_particle"})
      out.approximations.emplace_back(key, "maxwellian");
    return out;
  }
  const auto mix = config.mixture();
  const std::size_t s = mix.size();
  out.n_species = s;
  const auto beta = config.viscoelastic_beta();  // viscoelastic restitution: A3, A4 (\ref visco_averaged "docs/viscoelastic.md")
  add_rates(out, mix, config.initial.temperature, beta);
  const auto history = add_history(out, config, mix, beta);
  add_diffusion(out, config, mix, beta, history);
  add_sonine(out, mix, beta);
  add_viscosity(out, mix, beta);
  add_steady_shear(out, mix, config.rough() || beta.has_value(),
                   config.shear.rate.has_value() && config.thermostat.kind == io::config::ThermostatKind::none);
  if (config.thermostat.kind == io::config::ThermostatKind::white_noise) add_white_noise(out, config, mix);
  return out;
}


std::map<std::string, Trajectory> trajectories(const Predictions& p) {
  std::map<std::string, Trajectory> out;
  const auto scalar = [](const std::vector<double>& time, const std::vector<double>& values, double scale) {
    Trajectory t{time, {}};
    for (double v : values) t.value.push_back({v * scale});
    return t;
  };
  if (p.agg_frag) {
    const auto& af = *p.agg_frag;
    const auto& sol = af.solution;
    const double n0 = af.initial_monomers;
    const auto sizes = [&](const std::vector<double>& values, double scale) {  // [time][size] of [time * max_size + size]
      Trajectory t{sol.time, {}};
      for (std::size_t i = 0; i < sol.time.size(); ++i) {
        std::vector<double> row;
        for (std::size_t k = 0; k < af.width; ++k) row.push_back(values[i * sol.max_size + k] * scale);
        t.value.push_back(std::move(row));
      }
      return t;
    };
    out["number"] = sizes(sol.number_fraction, n0);
    out["temperature"] = sizes(sol.temperature, 1.0);
    out["total_temperature"] = scalar(sol.time, sol.total_temperature, 1.0);
    out["kinetic_energy"] = scalar(sol.time, sol.kinetic_energy, 1.0);
    out["mean_size"] = scalar(sol.time, af.mean_size, 1.0);
    out["monomer_fraction"] = scalar(sol.time, af.monomer_fraction, 1.0);
    out["collisions"] = scalar(sol.time, sol.collisions, n0);
    out["aggregations"] = scalar(sol.time, sol.aggregations, n0);
    out["fragmentations"] = scalar(sol.time, sol.fragmentations, n0);
    out["collisions_per_particle"] = scalar(sol.time, af.collisions_per_particle, 1.0);
    return out;
  }
  if (p.has_history) {
    out["temperature"] = Trajectory{p.time, p.temperature};
    out["total_temperature"] = scalar(p.time, p.total_temperature, 1.0);
    out["collisions_per_particle"] = scalar(p.time, p.collisions_per_particle, 1.0);
    if (!p.rotational_temperature.empty()) out["rotational_temperature"] = scalar(p.time, p.rotational_temperature, 1.0);
  }
  if (p.msd) out["msd"] = *p.msd;
  return out;
}

}  // namespace gdsmc::analysis
