/**
 * \file rough.hpp
 * \brief Rough spheres of one species in the Maxwellian approximation: the two-temperature cooling
 *        equations, the steady ratio theta = T_rot/T_tr of the homogeneous cooling state and its cooling rate.
 *
 * Normal restitution alpha, tangential restitution beta, reduced moment of inertia kappa = 4 I/(m sigma^2).
 * With translational and rotational velocities Maxwellian at T_tr and T_rot and uncorrelated, the energy
 * each collision moves (dsmc/rules.hpp RoughRule) averaged over the collisions gives
 * (\ref rough_maxwellian "docs/rough-spheres.md"; Huthmann and Zippelius 1997; Luding, Huthmann,
 * McNamara and Zippelius 1998, in 3D; derived in the docs page):
 *   dT_tr/dc = (4/3)(-A T_tr + B T_rot),   dT_rot/dc = (4/3)(B T_tr - C T_rot),
 *   A = (1 - alpha^2)/4 + eta (1 - eta),  B = eta^2/kappa,  C = (eta/kappa)(1 - eta/kappa),
 *   eta = kappa (1 + beta)/(2 (1 + kappa)),
 * with c the collisions per particle, dc/dt = nu = 4 n sigma^2 chi sqrt(pi T_tr/m). Their ratio tends to
 *   theta = [A - C + sqrt((A - C)^2 + 4 B^2)]/(2 B)   (beta > -1; theta = 0 for the smooth limit),
 * and T_tr then cools at zeta_tr = nu (4/3)(A - B theta): zeta* = zeta_tr/nu. beta = -1 gives the smooth
 * gas (A = (1 - alpha^2)/4, zeta* = (1 - alpha^2)/3, \ref haff_law "docs/haff-and-mixtures.md").
 *
 * Sonine theory (\ref rough_sonine "docs/rough-spheres.md"; Santos, Kremer and dos Santos 2011): the
 * distribution f_M(c) f_M(w) [1 + a20 S2(c^2) + a02 S2(w^2) + a11 S1(c^2) S1(w^2)] with the cumulants of
 * the observables (a20 = (3/5)<v^4>/<v^2>^2 - 1, a02 the same for omega, a11 = <v^2 w^2>/(<v^2><w^2>) - 1).
 * The collisional rates of <v^2>, <w^2>, <v^4>, <w^4>, <v^2 w^2> for it, to first order in the
 * cumulants, are polynomials in alpha, h = kappa (1 + beta)/(1 + kappa), 1/kappa and theta, worked out
 * exactly by scripts/derive_rough_moments.py (sympy). Steady states:
 * - cooling (HCS): every reduced moment stationary: d ln<v^4>/dc = 2 d ln T_tr/dc,
 *   d ln<w^4>/dc = 2 d ln T_rot/dc, d ln<v^2 w^2>/dc = d ln T_tr/dc + d ln T_rot/dc (each linearised in
 *   the cumulants), d ln T_rot/dc = d ln T_tr/dc (theta);
 * - white noise on v: the kicks add 3 chi^2 to d<v^2>/dt, 10 chi^2 <v^2> to d<v^4>/dt and
 *   3 chi^2 <w^2> to d<v^2 w^2>/dt; the spins are not kicked (d<w^2>/dt = d<w^4>/dt = 0). Smooth spheres
 *   (beta = -1) keep a20 alone: van Noije and Ernst 1998, a2 = 16(1 - alpha)(1 - 2 alpha^2)/(241 - 177 alpha
 *   + 30 alpha^2 - 30 alpha^3).
 * For fixed theta the cumulant equations are linear; theta is the root of its equation nearest the
 * Maxwellian theta. The solution does not exist where there is no root, and is refused (a reason instead
 * of numbers) where a cumulant exceeds 1 in magnitude: the first Sonine correction is then as large as the
 * Maxwellian it corrects (where that happens: \ref rough_sonine "docs/rough-spheres.md").
 *
 * Units: temperatures in energy, times in the user's time. Checked by tests/rough_test.cpp (by hand,
 * the smooth limit, the elastic perfectly rough gas, the Sonine coefficients against their limits and a
 * Monte Carlo integration) and validation/rough_spheres.
 */
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "model/species.hpp"

namespace gdsmc::theory::rough {

/// A, B, C of the two-temperature equations (header) for alpha, beta, kappa.
struct Coefficients {
  double a;  ///< A = (1 - alpha^2)/4 + eta (1 - eta)
  double b;  ///< B = eta^2/kappa
  double c;  ///< C = (eta/kappa)(1 - eta/kappa)
};
/// The coefficients of one species (header).
Coefficients coefficients(double alpha, double beta, double kappa);

/// nu_1 = 4 n sigma^2 chi sqrt(pi/m) of one species: the Maxwellian collision frequency is nu_1 sqrt(T_tr)
/// (\ref cm_pair_rate "docs/collision-model.md").
double frequency_unit(const species::Mixture& mix);

/// The homogeneous cooling state, Maxwellian approximation (header).
struct CoolingState {
  double theta;                 ///< T_rot/T_tr
  double cooling_rate_reduced;  ///< zeta_tr/nu = (4/3)(A - B theta)
};
/// theta and zeta_tr/nu of one species (header).
CoolingState cooling_state(double alpha, double beta, double kappa);

/// The steady state under white noise on the translational velocities (\ref wn_theory "docs/white-noise.md"):
/// the spins are not kicked, so dT_rot/dc = 0 gives theta = B/C (0 for smooth spheres), and the
/// translational loss per collision per particle is (4/3)(A - B theta) T_tr, which the noise's
/// m chi^2 per unit time balances: m chi^2 = nu (4/3)(A - B theta) T_tr. `cooling_rate_reduced` is that
/// (4/3)(A - B theta).
CoolingState driven_state(double alpha, double beta, double kappa);

/// The cumulants a20, a02, a11 (header).
struct Cumulants {
  double a20 = 0.0;  ///< (3/5)<v^4>/<v^2>^2 - 1
  double a02 = 0.0;  ///< the same of the angular velocities
  double a11 = 0.0;  ///< <v^2 w^2>/(<v^2><w^2>) - 1
};

/// The rate of change of one moment per Maxwellian collision, R = zero + a20 * a20 + a02 * a02 + a11 * a11,
/// in units m = sigma = T_tr = 1 (header; nu_M = 4 sqrt(pi) n sigma^2 chi sqrt(T_tr/m)).
struct MomentRate {
  double zero = 0.0;  ///< the Maxwellian rate
  double a20 = 0.0;   ///< the coefficient of a20
  double a02 = 0.0;   ///< the coefficient of a02
  double a11 = 0.0;   ///< the coefficient of a11
  /// R at the cumulants x.
  [[nodiscard]] double at(const Cumulants& x) const { return zero + a20 * x.a20 + a02 * x.a02 + a11 * x.a11; }
};
/// R of <v1^2 + v2^2>-type sums over a colliding pair: v2 = <v^2>, w2 = <omega^2>, v4 = <v^4>, w4 = <omega^4>,
/// v2w2 = <v^2 omega^2>, I = kappa/4, T_rot = theta.
struct CollisionalMoments {
  MomentRate v2;    ///< <v^2>
  MomentRate w2;    ///< <omega^2>
  MomentRate v4;    ///< <v^4>
  MomentRate w4;    ///< <omega^4>
  MomentRate v2w2;  ///< <v^2 omega^2>
};
/// The rates (header) for alpha, beta, kappa and theta = T_rot/T_tr.
CollisionalMoments collisional_moments(double alpha, double beta, double kappa, double theta);

/// A steady state in the Sonine approximation (header): theta, the cumulants and zeta_tr/nu_M (for the
/// white noise: the translational loss per collision, which m chi^2 balances as in driven_state).
struct SonineState {
  double theta = 0.0;                 ///< T_rot/T_tr (0 for smooth spheres)
  Cumulants cumulants;                ///< a20, a02, a11
  double cooling_rate_reduced = 0.0;  ///< zeta_tr/nu_M = -R_v2/3
};
/// The state, or why there is none (header).
struct SonineResult {
  std::optional<SonineState> state;  ///< the state, if it exists
  std::string why_not;  ///< set when state is empty
};
/// The homogeneous cooling state (beta > -1).
SonineResult sonine_cooling_state(double alpha, double beta, double kappa);
/// The white-noise steady state (beta = -1: smooth, a20 = a2 of van Noije and Ernst, theta = 0).
SonineResult sonine_driven_state(double alpha, double beta, double kappa);

/// Mixtures, Maxwellian approximation (\ref rough_mixtures "docs/rough-spheres.md"; Santos, Kremer and
/// Garzo 2010, here derived from the rule): the energy that collisions with species b bring per unit time
/// to one particle of species a, over n_b sigma_ab^2 chi_ab, with s^2 = T_a/m_a + T_b/m_b,
/// r^2 = R_a/(kappa_a m_a) + R_b/(kappa_b m_b) (R: rotational temperatures), h = (1 + beta) K,
/// K = 1/(1 + m_ab/(kappa_a m_a) + m_ab/(kappa_b m_b)), mu_ba = m_b/(m_a + m_b):
///   d(3 T_a/2)/dt = sqrt(8 pi) s m_a [-2 mu_ba (T_a/m_a)(1 + alpha + h) + mu_ba^2 ((1 + alpha)^2 s^2 + h^2 (s^2 + r^2))],
///   d(3 R_a/2)/dt = sqrt(8 pi) s h (m_ab/(kappa_a m_a)) [-2 R_a + m_ab h (s^2 + r^2)].
struct EnergyRates {
  double translational = 0.0;  ///< d(3 T_a/2)/dt over n_b sigma_ab^2 chi_ab
  double rotational = 0.0;     ///< d(3 R_a/2)/dt over n_b sigma_ab^2 chi_ab
};
/// The rates (above) of species a in collisions with b of `mix` at the temperatures T (translational) and
/// R (rotational) of every species.
EnergyRates pair_energy_rates(const species::Mixture& mix, std::size_t a, std::size_t b, const std::vector<double>& t,
                              const std::vector<double>& r);

/// The homogeneous cooling state of a rough mixture, Maxwellian approximation: every T_k and R_k cools at one
/// rate. Newton's method on those 2s - 1 conditions (log temperatures, T_1 = 1), from T_k = 1 and the
/// one-species theta of each species; at most 64 species.
struct MixtureCoolingState {
  std::vector<double> translational_over_mean;  ///< T_k/T, T = sum_k x_k T_k (translational)
  std::vector<double> theta;                    ///< R_k/T_k
  std::string why_not;                          ///< set (and the vectors empty) when there is no state
};
/// The state of `mix` (rough), or why not: more than 64 species, a species whose spins are coupled to
/// nothing (beta = -1 with every species: its theta grows without bound), no convergence.
MixtureCoolingState mixture_cooling_state(const species::Mixture& mix);

/// The Maxwellian equations of a rough mixture from T_k(0), R_k(0) (rough.hpp: the rates above summed over
/// b, times n_b sigma_kb^2 chi_kb): at the times `times`, or with `collision_driven` at the collisions per
/// particle `times` (dc/dt = sum_a x_a sum_b n_b sigma_ab^2 chi_ab sqrt(8 pi) s_ab). RK4.
struct MixtureHistory {
  std::vector<double> time;                          ///< sample times
  std::vector<double> collisions_per_particle;       ///< c
  std::vector<std::vector<double>> translational;    ///< [sample][species] T_k
  std::vector<std::vector<double>> rotational;       ///< [sample][species] T_rot,k
};
/// (above)
MixtureHistory integrate_mixture(const species::Mixture& mix, const std::vector<double>& translational,
                                 const std::vector<double>& rotational, const std::vector<double>& times, bool collision_driven);

/// The white-noise steady state of a mixture, Maxwellian approximation (\ref wn_theory "docs/white-noise.md"):
/// the kicks bring (3/2) m_k chi^2_k per particle and unit time to species k (strength = chi^2_k, the
/// resolved &thermostat noise_strength), the collisions take what the rates above say; the spins are not
/// kicked. Smooth mixtures (not mix.rough()) have no rotation (theta empty). Newton in the log
/// temperatures (rough: continued from beta = 0); at most 64 species.
struct MixtureDrivenState {
  std::vector<double> translational;  ///< T_k
  std::vector<double> theta;          ///< T_rot,k/T_k (rough spheres)
  std::string why_not;                ///< set (and the vectors empty) when there is no state
};
/// (above)
MixtureDrivenState mixture_driven_state(const species::Mixture& mix, const std::vector<double>& strength);

/// T_tr and T_rot at a run's sample points, with the collisions per particle and the times.
struct History {
  std::vector<double> time;                     ///< sample times
  std::vector<double> translational;            ///< T_tr
  std::vector<double> rotational;               ///< T_rot
  std::vector<double> collisions_per_particle;  ///< c
};
/// The two-temperature equations of the one-species rough gas `mix` from T_tr(0), T_rot(0), at the
/// times `times` (increasing), or, with `collision_driven`, at the collisions per particle `times`.
History integrate(const species::Mixture& mix, double translational, double rotational, const std::vector<double>& times,
                  bool collision_driven);

}  // namespace gdsmc::theory::rough
