/**
 * \file predictions.hpp
 * \brief Everything the theory module predicts for the system of one validated Config, on the run's
 *        own sample points: what `granular-theory` prints (as JSON) and `granular-dsmc --compare`
 *        sets beside the DSMC results (analysis/compare.hpp). One computation, two formats.
 *
 * No formula lives here: each entry calls the module that derives it, which names its sources.
 * - collision_frequency, cooling_rate, temperature, total_temperature, collisions_per_particle:
 *   the Maxwellian rates and partial-temperature ODEs (theory.hpp; \ref cm_pair_rate "docs/collision-model.md", \ref haff_law "docs/haff-and-mixtures.md", \ref haff_mixture_odes "docs/haff-and-mixtures.md"; viscoelastic
 *   restitution: diffusion.hpp, \ref visco_series "docs/viscoelastic.md"). Collision-driven runs: the ODE times at which the
 *   collisions per particle reach the run's sample points.
 * - diffusion_coefficient_ratio, msd: Bodrova and Osinsky 2024, eqs. (17), (19) (diffusion.hpp, \ref dif_msd "docs/diffusion-msd.md").
 * - sonine_a2, cooling_rate_sonine (one species; \ref haff_sonine "docs/haff-and-mixtures.md"), asymptotic_temperature_ratio
 *   (\ref haff_mixture_odes "docs/haff-and-mixtures.md"), hcs.first_sonine / hcs.maxwellian (sonine_mixture.hpp, any number of species),
 *   the binary first-Sonine HCS with tails (sonine.hpp; Montanero and Garzo 2002, \ref son_tails "docs/sonine.md").
 * - shear_viscosity_ratio (viscosity.hpp; Montanero 2003, \ref eta_one_species "docs/shear-viscosity.md", \ref eta_thermostat "docs/shear-viscosity.md");
 *   binary mixtures also in Montanero 2003's units eta* (Figs. 10-12, \ref eta_mixture "docs/shear-viscosity.md").
 * - rough spheres (&system roughness): one species, the Maxwellian two-temperature equations and the
 *   HCS theta, zeta* (theory/rough.hpp, \ref rough_maxwellian "docs/rough-spheres.md"); the smooth-sphere entries
 *   are left out (they do not describe rough spheres), and so is everything for rough mixtures.
 * - &agg_frag runs: the Smoluchowski equations with Maxwellian kernels (smoluchowski.hpp, \ref af_smoluchowski "docs/agg-frag.md").
 * `approximations` names the approximation behind every key, in the order granular-theory prints
 * them; an entry that cannot be evaluated is left out with a note saying why (never an exception).
 * Documentation: docs/physics.md ("Theory", "Comparison with theory").
 */
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/config.hpp"
#include "theory/rough.hpp"
#include "theory/smoluchowski.hpp"
#include "theory/sonine.hpp"
#include "theory/sonine_mixture.hpp"
#include "theory/viscosity.hpp"

namespace gdsmc::analysis {

/// A time series per species (or per cluster size): value[time index][column].
struct Trajectory {
  std::vector<double> time;                ///< sample times
  std::vector<std::vector<double>> value;  ///< [time][column]
};

/// The Smoluchowski solution of an &agg_frag run in the units of the DSMC observables.
struct AggFragPrediction {
  theory::smoluchowski::Solution solution;     ///< on the run's sample times
  theory::smoluchowski::InitialRates initial_rates;  ///< event rates at t = 0 (exact: Maxwellian monomers)
  double initial_monomers = 0.0;       ///< n_particles: number = number_fraction * this
  std::size_t width = 1;               ///< sizes of which the run would hold >= 1e-6 clusters at some time
  std::vector<double> mean_size;                ///< N_0/N per sample time
  std::vector<double> monomer_fraction;         ///< N_1/N_0 = n_1(t)/n_1(0) per sample time
  std::vector<double> collisions_per_particle;  ///< 2 x collisions / N_0 per sample time
};

/// Everything granular-theory prints for one point (\ref output_theory "docs/output.md").
struct Predictions {
  std::size_t n_species = 1;                ///< S
  std::vector<double> collision_frequency;  ///< nu_k at t = 0
  std::vector<double> cooling_rate;         ///< zeta_k = sum_j xi_kj at t = 0
  /// Free cooling on the sample times (absent for &thermostat / &shear runs, where T is held).
  bool has_history = false;
  std::vector<double> time;                      ///< the sample times
  std::vector<std::vector<double>> temperature;  ///< [time][species]
  std::vector<double> total_temperature;         ///< T on the sample times
  std::vector<double> collisions_per_particle;   ///< 2 x events / N on the sample times
  std::vector<double> final_temperature;  ///< T_k at the last sample time (also for staged runs)
  std::vector<double> diffusion_coefficient_ratio;  ///< D_k/D_1 (\ref dif_coefficients "docs/diffusion-msd.md")
  std::optional<Trajectory> msd;          ///< with &output track_displacements
  std::optional<double> sonine_a2;            ///< one species: van Noije-Ernst a2
  std::optional<double> cooling_rate_sonine;  ///< one species: zeta_0 (1 + 3 a2/16)
  std::optional<std::vector<double>> asymptotic_temperature_ratio;  ///< T_k/T_1, Maxwellian
  std::optional<theory::HcsFirstSonine> hcs_first_sonine;  ///< HCS of any number of species, first Sonine
  std::optional<std::vector<double>> hcs_maxwellian_temperature_over_mean;  ///< HCS T_k/T, Maxwellian
  std::optional<double> hcs_maxwellian_cooling_rate_reduced;  ///< HCS zeta*, Maxwellian
  std::optional<theory::BinaryHcs> binary_hcs;             ///< binary HCS in first Sonine, with tails
  std::optional<double> binary_tail_decay_rate[2]; ///< k_i = 2 beta_i/zeta* of each species
  std::optional<double> shear_viscosity_hcs;          ///< eta/eta_0 in the HCS
  std::optional<double> shear_viscosity_hss;          ///< eta/eta_0 in the HSS
  std::optional<double> shear_viscosity_kinetic_hcs;  ///< its kinetic part (Enskog), HCS
  std::optional<double> shear_viscosity_kinetic_hss;  ///< its kinetic part (Enskog), HSS
  /// Binary mixtures: nu eta_0/(n T), which turns eta/eta_0 into Montanero 2003's eta* = nu eta/(n T)
  /// (Figs. 10-12; nu = sqrt(pi) n sigma_12^2 v0); it does not depend on T.
  std::optional<double> shear_viscosity_reduced_factor;
  /// One dilute species or a dilute binary mixture of smooth spheres: the steady shear flow without thermostat in
  /// Grad's solution (T_k/T, a*, P_ij/p; theory/viscosity.hpp steady_shear_grad, \ref eta_usf_steady "docs/shear-viscosity.md").
  std::optional<theory::viscosity::MixtureSteadyShear> steady_shear_grad;
  std::optional<AggFragPrediction> agg_frag;          ///< &agg_frag runs: the Smoluchowski solution
  /// Rough spheres of one species: the Maxwellian HCS theta = T_rot/T_tr and zeta_tr/nu (theory/rough.hpp).
  std::optional<theory::rough::CoolingState> rough_hcs_maxwellian;
  /// zeta_tr/nu_M of that state, nu_M = 4 sqrt(pi) n sigma^2 sqrt(T_tr/m) without chi (INTERFACE's zeta_star):
  /// chi times its cooling_rate_reduced.
  double rough_zeta_star = 0.0;
  double rough_unit_frequency = 0.0;  ///< nu_M/sqrt(T_tr) = 4 sqrt(pi) n sigma^2/sqrt(m), one rough species
  /// Rough spheres of one species: the Sonine HCS (theta, a20, a02, a11, zeta_tr/nu_M without chi), or why
  /// it does not exist (theory/rough.hpp sonine_cooling_state).
  std::optional<theory::rough::SonineResult> rough_hcs_sonine;
  /// Rough mixtures: the Maxwellian HCS, T_k/T (translational) and theta_k = T_rot,k/T_k
  /// (theory/rough.hpp mixture_cooling_state).
  std::optional<theory::rough::MixtureCoolingState> rough_mixture_hcs;
  std::vector<double> rotational_temperature;  ///< rough, one species: T_rot on the sample times (has_history)
  /// &thermostat kind = 'white_noise', one species: the Maxwellian steady T_tr (and theta for rough spheres).
  struct WhiteNoise {
    double translational_temperature = 0.0;  ///< m chi^2 = nu(T) (4/3)(A - B theta) T
    std::optional<double> theta;             ///< rough spheres: B/C
    /// The Sonine state (theory/rough.hpp sonine_driven_state; smooth spheres: a20 = a2 of van Noije and
    /// Ernst) and its T_tr from m chi^2 = nu(T) zeta* T, or why there is none.
    theory::rough::SonineResult sonine;
    std::optional<double> sonine_temperature;  ///< T_tr of the Sonine state
  };
  std::optional<WhiteNoise> white_noise;     ///< (theory/rough.hpp driven_state)
  /// &thermostat kind = 'white_noise', mixtures: the Maxwellian steady T_k (and theta_k for rough spheres)
  /// (theory/rough.hpp mixture_driven_state).
  std::optional<theory::rough::MixtureDrivenState> white_noise_mixture;
  /// ... and for smooth spheres its first-Sonine state (theory/sonine_mixture.hpp white_noise_first_sonine),
  /// or why there is none.
  std::optional<theory::DrivenFirstSonine> white_noise_mixture_sonine;
  std::string white_noise_mixture_sonine_why_not;  ///< why white_noise_mixture_sonine is empty (when it is)
  /// key -> "maxwellian", "first_sonine", "exact", ... for every key present, in print order.
  std::vector<std::pair<std::string, std::string>> approximations;
  std::vector<std::string> notes;  ///< what was left out and why, in order
};

/// The predictions for one point (not a sweep: call it per Config::sweep_points()). Throws
/// std::runtime_error only when the ODEs themselves fail, and theory::smoluchowski::Stopped when
/// `stop` (asked by the one integration that can take long, the Smoluchowski equations) said so.
Predictions predict(const io::config::Config& config, const theory::smoluchowski::Stop& stop = {});

/// Every trajectory of `p` by the name of the observable it predicts (value[time][column], columns as the
/// observable's: species, or cluster sizes 1..width of &agg_frag), as granular-theory prints them:
/// temperature, total_temperature, collisions_per_particle, rotational_temperature, msd; &agg_frag:
/// number, temperature, total_temperature, kinetic_energy, mean_size, monomer_fraction, collisions,
/// aggregations, fragmentations, collisions_per_particle (`granular-dsmc --table --theory`).
std::map<std::string, Trajectory> trajectories(const Predictions& p);

/// The monomer of &system and the thresholds of &agg_frag of a validated Config, for the Smoluchowski
/// equations (theory/smoluchowski.hpp).
theory::smoluchowski::Parameters smoluchowski_parameters(const io::config::Config& config);

}  // namespace gdsmc::analysis
