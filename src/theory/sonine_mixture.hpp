/**
 * \file sonine_mixture.hpp
 * \brief Homogeneous cooling state (HCS) of a granular mixture of any number s of species in the
 *        first Sonine approximation, dilute or Enskog, any (symmetric) restitution matrix: the
 *        temperature ratios T_k/T, the fourth-moment coefficients c_k and the reduced cooling rate.
 *
 * \section sonmix_model Equations
 * The s-species generalisation (Garzo and Dufty, Phys. Fluids 14, 1476 (2002)) of the binary first
 * Sonine theory of sonine.hpp (Montanero and Garzo 2002, App. A, \ref son_binary "docs/sonine.md"). The collision operator of species i is
 * a sum over partners j, J_i = sum_j J_ij, and J_ij depends only on the pair (i, j): its
 * distributions (Montanero and Garzo 2002, eq. (17), \ref son_scaling "docs/sonine.md", with c_i and c_j) and temperatures T_i, T_j. Hence
 *   zeta_i = sum_j [zeta_ij^(0) + zeta_ij^(1,i) c_i + zeta_ij^(1,j) c_j],
 *   Omega_i = sum_j int v^4 J_ij = sum_j [Omega_ij^(0) + Omega_ij^(1,i) c_i + Omega_ij^(1,j) c_j],
 * where for j != i the pair terms are the cross terms of the binary coefficients of Montanero and Garzo 2002,
 * eqs. (39)-(44) (\ref son_binary_coefficients "docs/sonine.md") for the pair {i, j} (sonine_cross_terms) and for j = i the self terms
 * (sonine_self_terms, i.e. the one-species theory), each converted from the pair's own reduced
 * units (n sigma_ij^2 v0_ij, v0_ij = sqrt(2 T (m_i + m_j)/(m_i m_j))) to common ones: x_j chi_ij is
 * the pair weight, the rate is multiplied by n_j sigma_ij^2 v0_ij (zeta) or n_j sigma_ij^2 v0_ij^5
 * (Omega), lambda_i = T/(T_i mu_ji) with the pair's mu_ji (self pair: mu = 1/2).
 * c_i = 2 [(3/5) <v^4>_i/<v^2>_i^2 - 1] (\ref son_scaling "docs/sonine.md"; one species: c = 2 a2).
 *
 * Unknowns: tau_k = T_k/T (T = sum_k n_k T_k/n, so sum_k x_k tau_k = 1) and c_k. Equations:
 * - equal cooling rates zeta_1 = ... = zeta_s (Montanero and Garzo 2002, eq. (10), \ref son_scaling "docs/sonine.md"; s - 1 equations) and the
 *   normalisation sum_k x_k tau_k = 1;
 * - the fourth-moment equations -2 zeta_i <v^4>_i = Omega_i (Montanero and Garzo 2002, eq. (15), \ref son_binary_cumulants "docs/sonine.md" times v^4, integrated),
 *   <v^4>_i = 15 (T_i/m_i)^2 (1 + c_i/2), linearised in the c's: at fixed tau the s x s linear system
 *   sum_j [2 W_i Z_ij + O_ij + delta_ij W_i zeta_i^(0)] c_j = -2 W_i zeta_i^(0) - Omega_i^(0),
 *   W_i = 15 (T_i/m_i)^2, zeta_i = zeta_i^(0) + sum_j Z_ij c_j, Omega_i = Omega_i^(0) + sum_j O_ij c_j
 *   (for s = 2 this is Montanero and Garzo 2002, eqs. (31)-(38), \ref son_binary_cumulants "docs/sonine.md"), solved with Eigen (partial-pivoting LU).
 *
 * \section sonmix_solve Solution
 * Newton's method on the s equations F_k = (zeta_k - zeta_s)/nu (k < s), F_s = sum_k x_k tau_k - 1
 * in the unknowns u_k = ln tau_k, with the c's eliminated (solved at every tau). nu =
 * sum_ij x_i x_j chi_ij (sigma_ij/sigma_ref)^2 v0_ij/(v_ref/2) (a collision-frequency scale,
 * nonzero also for elastic mixtures). Start: the Maxwellian asymptotic ratios of
 * theory::asymptotic_temperature_ratios (\ref haff_ratios "docs/haff-and-mixtures.md"; their fixed point by Newton's method, theory.hpp),
 * normalised to sum_k x_k tau_k = 1 (equipartition when every alpha = 1, the exact answer then). The
 * Jacobian: a finite difference (step 1e-7 in u_k) of the pair terms, of which only the 2s - 1
 * pairs containing k change, carried through the c system exactly, dc = M^-1 (db - dM c), with the
 * factorisation of M reused for all k (O(s^3) per iteration). Backtracking line search on |F|,
 * steps in u limited to 1; converged when max|F| < 1e-13 (then one more step is taken) or when
 * the step is below 1e-15. Throws std::runtime_error if the c system is singular at the start,
 * when max|F| has not halved over 10 iterations (stagnation: seen for extreme mixtures, e.g. mass
 * ratios near 1000 with alpha near 0.1, maybe without a solution near the Maxwellian ratios), after
 * 100 iterations, or when the line search fails.
 *
 * \section sonmix_units Reduction convention
 * zeta* = zeta/(n sigma_ref^2 v_ref) with sigma_ref = (1/s) sum_k sigma_k and
 * v_ref = sqrt(4 T (1/s) sum_k 1/m_k) (unweighted means over the species). For s = 2 this is
 * sigma_12 and v0 = sqrt(2 T (m1 + m2)/(m1 m2)) of Montanero and Garzo 2002, eq. (15) (\ref son_scaling "docs/sonine.md"), so
 * cooling_rate_reduced equals BinaryHcs::cooling_rate; for one species it is n sigma^2 sqrt(4T/m),
 * the binary value for two identical species. Splitting a species into identical copies changes
 * s and thereby the unit (hcs_rate_unit), not the physical cooling rate.
 * zeta* = sum_k x_k tau_k zeta_k* (Montanero and Garzo 2002, eq. (11), \ref son_binary_gamma "docs/sonine.md"), equal to every zeta_k* at the solution.
 *
 * \section sonmix_driven The white-noise steady state
 * The same moments with the kicks of the white noise (\ref wn_theory "docs/white-noise.md"; one species: van
 * Noije and Ernst 1998; mixtures: the equal-force driving of Barrat and Trizac 2002, any chi_k^2): every
 * species' kicks balance its collisions' loss, m_k chi_k^2 = zeta_k T_k (s - 1 equations zeta_k tau_k/(m_k
 * chi_k^2) equal, with sum_k x_k tau_k = 1), and the kicks' 10 chi_k^2 <v^2>_k = 2 W_k zeta_k in
 * d<v^4>_k/dt (so the c system lacks the HCS's delta_ij W_i zeta_i^(0)): Omega_i + 2 W_i zeta_i = 0. The
 * absolute temperature then follows from m_s chi_s^2 = zeta_s T_s, zeta_s = zeta_s* hcs_rate_unit sqrt(T).
 * The same Newton's method. One species gives van Noije and Ernst's a2 = c/2 and the Sonine balance of
 * theory::rough::sonine_driven_state (smooth spheres). Smooth spheres only (the rates ignore roughness).
 *
 * \section sonmix_limits Limits and cost
 * Pair terms O(s^2) per evaluation, the c system and the Newton Jacobian O(s^3) per iteration;
 * 4 first-Sonine iterations are typical (timings of bench/bench_theory.cpp:
 * \ref perf_theory "docs/performance.md"). Above max_hcs_species = 1200
 * species std::invalid_argument is thrown (the Maxwellian ratios of asymptotic_temperature_ratios
 * are what remains available; granular-theory says so).
 * Input checks as sonine.hpp, for any s >= 1: std::invalid_argument.
 * Checked by tests/sonine_mixture_test.cpp (binary reference, merging identical species,
 * permutations, elastic and one-species limits, Maxwellian zeta_i^(0) against \ref haff_mixture_odes "docs/haff-and-mixtures.md", the
 * equations recomputed from hcs_pair_terms at s = 5 and 100, the ternary example of the docs).
 * Documentation: docs/physics.md "First-Sonine HCS of s species".
 */
#pragma once

#include <cstddef>
#include <vector>

#include "model/species.hpp"
#include "theory/sonine.hpp"

namespace gdsmc::theory {

/// HCS of an s-species mixture in first Sonine approximation (see \ref sonmix_model).
struct HcsFirstSonine {
  std::vector<double> temperature_over_mean;  ///< T_k/T, T = sum_k n_k T_k/n
  std::vector<double> sonine_c;               ///< c_k (Montanero and Garzo 2002, eq. (17), \ref son_scaling "docs/sonine.md"; one species: 2 a2)
  double cooling_rate_reduced = 0.0;          ///< zeta/(n sigma_ref^2 v_ref) (\ref sonmix_units)
  int newton_iterations = 0;                  ///< Newton steps the solution took
};

/// The white-noise steady state of an s-species mixture in first Sonine approximation (\ref sonmix_driven).
struct DrivenFirstSonine {
  std::vector<double> temperature;            ///< T_k (the units of the mixture and strengths)
  std::vector<double> temperature_over_mean;  ///< T_k/T, T = sum_k n_k T_k/n
  std::vector<double> sonine_c;               ///< c_k (one species: 2 a2)
  int newton_iterations = 0;                  ///< Newton steps the solution took
};
/// Solves \ref sonmix_driven for the noise strengths chi_k^2 (`strength`, one per species);
/// `maxwellian_start` (optional, any normalisation): the Maxwellian steady temperatures
/// (theory::rough::mixture_driven_state), else equal temperatures. Throws std::invalid_argument for
/// a bad mixture or strength, an elastic mixture (no steady state) or s > max_hcs_species,
/// std::runtime_error if Newton's method fails or a cooling rate is not positive.
DrivenFirstSonine white_noise_first_sonine(const species::Mixture& mix, const std::vector<double>& strength,
                                           const std::vector<double>& maxwellian_start = {});
/// Largest s that hcs_first_sonine accepts (its cost grows like s^3 per Newton iteration).
inline constexpr std::size_t max_hcs_species = 1200;

/// Solves the first-Sonine HCS (see \ref sonmix_solve). `maxwellian_start` (optional): the
/// Maxwellian ratios T_k/T_1 or T_k/T if the caller has them already (any normalisation), else
/// they are computed. Throws std::invalid_argument for a bad mixture or start, or
/// s > max_hcs_species, std::runtime_error if Newton's method fails.
HcsFirstSonine hcs_first_sonine(const species::Mixture& mix,
                                const std::vector<double>& maxwellian_start = {});

/// The unit of cooling_rate_reduced divided by sqrt(T): n sigma_ref^2 sqrt(4 (1/s) sum_k 1/m_k)
/// (\ref sonmix_units); zeta = cooling_rate_reduced * hcs_rate_unit(mix) * sqrt(T).
double hcs_rate_unit(const species::Mixture& mix);

/// The pair terms of species i with partner j (\ref sonmix_model) at T_i/T = tau_i,
/// T_j/T = tau_j (tau_j is not used when j = i), in the units of \ref sonmix_units
/// (zeta terms in n sigma_ref^2 v_ref, Omega terms in n sigma_ref^2 v_ref^5). Throws
/// std::invalid_argument for a bad mixture, index or temperature ratio.
SonineTerms hcs_pair_terms(const species::Mixture& mix, std::size_t i, std::size_t j, double tau_i,
                           double tau_j);

/// Maxwellian reduced cooling rate sum_k x_k tau_k zeta_k^(0) at the given T_k/T (the pair
/// zeta0 terms, equal to the cooling rates of \ref haff_mixture_odes "docs/haff-and-mixtures.md"), in the units of \ref sonmix_units.
double hcs_maxwellian_cooling_rate_reduced(const species::Mixture& mix,
                                           const std::vector<double>& temperature_over_mean);

/// theory::asymptotic_temperature_ratios normalised to T_k/T (sum_k x_k T_k/T = 1); {1} for s = 1.
std::vector<double> maxwellian_temperature_over_mean(const species::Mixture& mix);

}  // namespace gdsmc::theory
