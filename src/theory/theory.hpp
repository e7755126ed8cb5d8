/**
 * \file theory.hpp
 * \brief Kinetic theory of a homogeneous granular gas and mixture in the Maxwellian approximation:
 *        collision rates, Haff's law and the partial temperatures T_k(t) of a cooling mixture.
 *
 * \section theory_intro What this module computes
 *
 * The DSMC programs of this project are checked against the predictions collected here. All of them
 * assume that each species k has a Maxwellian velocity distribution with its own partial
 * temperature T_k (molecular chaos; the pair correlation at contact chi_kj multiplies every
 * collision rate, \ref cm_chi "docs/collision-model.md"). Notation is that of \ref cm_notation "docs/collision-model.md" and of species.hpp:
 * s_kj = T_k/m_k + T_j/m_j, sigma_kj = (sigma_k + sigma_j)/2, m_kj = m_k m_j/(m_k + m_j),
 * mu_kj = m_k/(m_k + m_j), alpha_kj the restitution coefficient, n = sum_k n_k, x_k = n_k/n.
 *
 * \subsection theory_rates Collision rates (\ref cm_frequency "docs/collision-model.md"; the DSMC notes, eqs. (29)-(36), (54)-(61) corrected)
 * - Mean relative speed of two Maxwellian species: <|g_kj|> = sqrt(8 s_kj/pi) (DSMC notes, eqs. (34), (60), \ref cm_mean_speed "docs/collision-model.md").
 * - One species, collisions suffered per particle per unit time:
 *   nu = 4 sqrt(pi) n sigma^2 chi sqrt(T/m); events per unit volume and time n nu/2 (DSMC notes, eq. (36), \ref cm_frequency "docs/collision-model.md").
 * - Mixture, events per unit volume and time between species k != j:
 *   R_kj = n_k n_j pi sigma_kj^2 chi_kj <|g_kj|>, and R_kk = (1/2) n_k^2 pi sigma_kk^2 chi_kk <|g_kk|>.
 *   Convention (the one of \ref cm_pair_rate "docs/collision-model.md" and of the DSMC code): an unordered pair collides at the rate
 *   pi sigma_kj^2 chi_kj |g| / V, equivalently 2 pi sigma_kj^2 chi_kj |g.e| / V with e uniform on the
 *   full unit sphere. The DSMC notes, eqs. (58), (61), (63) are a factor 2 too small (\ref cm_mixture_rate "docs/collision-model.md").
 *
 * \subsection theory_haff Haff's law (\ref haff_law "docs/haff-and-mixtures.md"; the DSMC notes, eqs. (37)-(46), eq 45 sign corrected)
 * dT/dt = -zeta T with zeta_0 = (4/3) sqrt(pi) (1 - alpha^2) n sigma^2 chi sqrt(T/m), solved by
 * T(t) = T0/(1 + t/t0)^2, t0 = 2/zeta_0(T0). The first Sonine correction multiplies zeta by
 * (1 + 3 a2/16) with the van Noije-Ernst a2(alpha) (sonine_a2); the functions here return the
 * Maxwellian value, callers apply the correction when they want it.
 *
 * \subsection theory_mixture Partial temperatures of a mixture (\ref haff_mixture_odes "docs/haff-and-mixtures.md"; the DSMC notes, eq. (76))
 * dT_k/dt = -T_k sum_j xi_kj with
 * xi_kj = (8/3) sqrt(2 pi) n_j sigma_kj^2 chi_kj sqrt(s_kj) mu_jk (1 + alpha_kj)
 *         [1 - (1/2)(1 + alpha_kj) X_kj],   X_kj = (T_k m_j + T_j m_k)/(T_k (m_j + m_k)).
 * xi_kj is not symmetric. It equals the "equivalent form" of \ref haff_mixture_odes "docs/haff-and-mixtures.md" (DSMC notes, eq. (76), with its
 * "sigma_kj" read as sigma_kj^2 and mu_kj as the reduced mass); tests/theory_test.cpp checks this,
 * and checks the total energy loss and the energy change of one species against Monte Carlo
 * integrations of the collision rule (\ref cm_rule "docs/collision-model.md") over Maxwellian pairs.
 * With constant alpha the ratios T_k/T_1 tend to constants (asymptotic_temperature_ratios): the
 * fixed point of the ratio ODE, found by Newton's method with a line search, else by
 * pseudo-transient continuation of that ODE, else by its long-time solution (\ref haff_ratios "docs/haff-and-mixtures.md"
 * warns against plain Newton from equal temperatures).
 *
 * \subsection theory_ode Numerical integration
 * integrate_partial_temperatures solves the \ref haff_cvode "docs/haff-and-mixtures.md" ODEs with SUNDIALS CVODE (BDF, Newton with the
 * analytic Jacobian of maxwellian_rates.hpp: dense LU up to 200 species, above matrix-free GMRES
 * left-preconditioned by the diagonal of I - gamma J; the pair sums in O(S^2) vectorised arithmetic,
 * maxwellian_rates.hpp). The state is y_k = ln(T_k/T_ref), T_ref = sum_k x_k T_k(0),
 * not T_k itself: temperatures fall by many decades during cooling, and an absolute error of y_k is
 * a relative error of T_k, which stays meaningful at every T (an atol on T_k that is scaled to T0
 * and then follows T_k down). Tolerances (CVodeWFtolerances): absolute 1e-11 on each y_k and no
 * rtol * |y_k| term (that term would depend on the temperature unit through T_ref), so that the
 * global relative error of T_k is about rtol = 1e-10 (3e-10 measured after Haff cooling to
 * t = 100 t0); one extra component integrates the cumulative collision events per unit volume,
 * dC/dt = total_collision_rate, with rtol 1e-10 and atol 1e-12 n.
 * Every SUNDIALS call is checked; a failure throws std::runtime_error naming the call (and quoting
 * CVODE's own message).
 *
 * \subsection theory_units Units
 * Any consistent set of user units; k_B = 1, so temperature is an energy (T = m <v_x^2>). Rates are
 * per unit time, densities per unit volume, the collision count per unit volume.
 *
 * Checked by tests/theory_test.cpp.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <functional>
#include <vector>

#include "model/species.hpp"
#include "theory/sonine.hpp"

namespace gdsmc::theory {

using species::Mixture;
using species::PairMatrix;

// ---------------------------------------------------------------------------------------------
// One species and single pairs
// ---------------------------------------------------------------------------------------------

/// \ref cm_mean_speed "docs/collision-model.md" (DSMC notes, eq. (60)): Maxwellian mean relative speed <|g_kj|> = sqrt(8 s_kj/pi),
/// s_kj = T_k/m_k + T_j/m_j.
double mean_relative_speed(double s_kj);

/// \ref cm_frequency "docs/collision-model.md", one species: collisions suffered per particle per unit time
/// nu = 4 sqrt(pi) n sigma^2 chi sqrt(T/m).
double collision_frequency(double number_density, double diameter, double chi, double mass,
                           double temperature);

/// \ref haff_law "docs/haff-and-mixtures.md": Maxwellian Haff cooling rate zeta_0 = (4/3) sqrt(pi) (1 - alpha^2) n sigma^2 chi
/// sqrt(T/m) (no Sonine correction).
double haff_cooling_rate(double number_density, double diameter, double chi, double mass,
                         double alpha, double temperature);

/// \ref haff_sonine "docs/haff-and-mixtures.md": van Noije-Ernst second Sonine coefficient
/// a2(alpha) = 16 (1 - alpha)(1 - 2 alpha^2) / (81 - 17 alpha + 30 alpha^2 (1 - alpha)).
double sonine_a2(double alpha);

/// \ref haff_law "docs/haff-and-mixtures.md": T(t) = T0/(1 + t/t0)^2 with t0 = 2/zeta0, zeta0 the cooling rate at T0.
double haff_temperature(double t, double T0, double zeta0);

// ---------------------------------------------------------------------------------------------
// Mixtures (temperature[k] = T_k, one entry per species)
// ---------------------------------------------------------------------------------------------

/// \ref cm_mixture_rate "docs/collision-model.md": collision events per unit volume and unit time between species k and j,
/// k != j: n_k n_j pi sigma_kj^2 chi_kj <|g_kj|>; k == j: half of that. Symmetric S x S matrix.
PairMatrix pair_collision_rate(const Mixture& mix, const std::vector<double>& temperature);

/// \ref cm_mixture_rate "docs/collision-model.md": collisions suffered per particle of species k per unit time,
/// nu_k = (2 P_kk + sum_{j != k} P_kj)/n_k with P = pair_collision_rate, in O(S) memory (any number of species).
std::vector<double> collision_frequencies(const Mixture& mix, const std::vector<double>& temperature);

/// Total events per unit volume and time: sum over unordered pairs k <= j of pair_collision_rate.
/// One species: n nu/2.
double total_collision_rate(const Mixture& mix, const std::vector<double>& temperature);

/// \ref haff_mixture_odes "docs/haff-and-mixtures.md": the S x S matrix xi_kj (not symmetric), such that dT_k/dt = -T_k sum_j xi_kj.
PairMatrix cooling_rate_matrix(const Mixture& mix, const std::vector<double>& temperature);

/// \ref haff_mixture_odes "docs/haff-and-mixtures.md": zeta_k = sum_j xi_kj, the row sums of cooling_rate_matrix
/// in O(S) memory (any number of species).
std::vector<double> cooling_rates(const Mixture& mix, const std::vector<double>& temperature);

/// \ref haff_mixture_odes "docs/haff-and-mixtures.md": dT_k/dt = -T_k sum_j xi_kj for every species k.
std::vector<double> partial_temperature_rates(const Mixture& mix,
                                              const std::vector<double>& temperature);

/// Solution of the \ref haff_mixture_odes "docs/haff-and-mixtures.md" ODEs at the requested times.
struct TemperatureHistory {
  std::vector<double> time;                      ///< the requested output times
  std::vector<std::vector<double>> temperature;  ///< [time index][species] T_k(t)
  std::vector<double> collisions;  ///< cumulative collision events per unit volume since t = 0
};

/**
 * Integrates the \ref haff_ratios "docs/haff-and-mixtures.md" ODEs with CVODE (BDF + dense Newton, rtol 1e-10, state ln(T_k/T_ref),
 * see \ref theory_ode) from T_k(0) = initial_temperature[k] and reports at `times` (non-negative,
 * strictly increasing; times[0] may be 0). Also integrates d(collisions)/dt = total_collision_rate.
 * Throws std::invalid_argument for bad input and std::runtime_error naming the failing SUNDIALS call.
 */
TemperatureHistory integrate_partial_temperatures(const Mixture& mix,
                                                  const std::vector<double>& initial_temperature,
                                                  const std::vector<double>& times);

/// Times at which the Maxwellian ODEs' collisions per particle (2 x events / n) reach `targets`
/// (non-decreasing; a target <= 0 is at t = 0): integrate_partial_temperatures tabulated densely on
/// a horizon doubled until it holds the last target, then interpolated linearly.
std::vector<double> times_for_collisions(const Mixture& mix, const std::vector<double>& initial_temperature,
                                         const std::vector<double>& targets);
/// The same for the history `integrate(times)` gives (the viscoelastic ODEs of diffusion.hpp, say: their
/// cooling, not the constant restitution's, sets when the collisions are reached).
std::vector<double> times_for_collisions(const Mixture& mix, const std::vector<double>& initial_temperature,
                                         const std::vector<double>& targets,
                                         const std::function<TemperatureHistory(const std::vector<double>&)>& integrate);

/**
 * Long-time ratios T_k/T_1 (entry 0 is 1) for constant restitution (\ref haff_ratios "docs/haff-and-mixtures.md"). Because every
 * xi_kj is homogeneous of degree 1/2 in the temperatures, the ratios r_k = T_k/T_1 obey an
 * autonomous ODE, d ln r_k/dtau = -(sum_j xi_kj - sum_j xi_1j) evaluated at T_1 = m_1 (a fixed
 * temperature unit), with dtau = sqrt(T_1(t)/m_1) dt: tau grows like ln t in the Haff regime.
 * Its fixed point F_k = sum_j xi_kj - sum_j xi_1j = 0 is solved in u_k = ln r_k with the analytic
 * Jacobian (maxwellian_rates.hpp) by Newton's method from equal temperatures (steps limited to 1 in
 * u, backtracking until max|F| falls), should that fail by pseudo-transient continuation of the ODE
 * (Kelley and Keyes, SIAM J. Numer. Anal. 35, 508 (1998): implicit Euler steps of growing length from
 * equal temperatures), both to max|F|/zeta_1 < 1e-13 with LU up to 300 species and GMRES above
 * (gmres.hpp); should both fail, the ODE is integrated with CVODE from equal temperatures over
 * output intervals that double in length, until the ratios change by less than 1e-12 relatively
 * over two successive intervals. Throws std::runtime_error if that does not happen either.
 * Documentation: docs/haff-and-mixtures.md "Asymptotic temperature ratios".
 */
std::vector<double> asymptotic_temperature_ratios(const Mixture& mix);

namespace detail {
/// The three methods of asymptotic_temperature_ratios, each alone (tests/maxwellian_rates_test.cpp
/// holds them against each other): empty when that method fails.
enum class RatioMethod { newton, continuation, ode };
std::optional<std::vector<double>> asymptotic_temperature_ratios_by(const Mixture& mix,
                                                                    RatioMethod method);
}  // namespace detail

}  // namespace gdsmc::theory

#include "theory/diffusion.hpp"  // diffusion theory (Bodrova and Osinsky 2024, eqs. (16)-(24), A1-A4; \ref visco_averaged "docs/viscoelastic.md", \ref visco_series "docs/viscoelastic.md")
