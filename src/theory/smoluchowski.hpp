/**
 * \file smoluchowski.hpp
 * \brief Smoluchowski rate equations for aggregating and fragmenting inelastic hard-sphere
 *        clusters, with Maxwellian partial temperatures (DSMC notes, eqs. (8)-(14), \ref af_smoluchowski "docs/agg-frag.md").
 *
 * \section smol_intro What this module computes
 *
 * A homogeneous gas that starts as monomers (mass m_1, diameter sigma_1, density n_1(0),
 * temperature T0) and whose collisions, depending on the impact energy, stick, shatter or bounce.
 * The DSMC aggregation runs are compared with the number densities n_k(t) of clusters of k
 * monomers and their partial temperatures T_k(t) predicted here. The physics is stated for users
 * in docs/physics.md; this header states what the code does.
 *
 * \subsection smol_model Clusters and pairs (\ref af_outcome "docs/agg-frag.md")
 * m_k = k m_1, sigma_k = k^(1/3) sigma_1, sigma_kj = (sigma_k + sigma_j)/2, theta_k = T_k/m_k,
 * s = theta_k + theta_j, m_kj = m_k m_j/M, M = m_k + m_j, mu_jk = m_j/M. Collision measure
 * w_kj = n_k n_j Lambda_kj with Lambda_kj = pi sigma_kj^2 sqrt(8 s/pi) (\ref cm_mean_speed "docs/collision-model.md"): events per unit
 * volume and time are w_kj between k != j and w_kk/2 between two k-clusters.
 *
 * \subsection smol_outcomes Outcome of a collision (\ref af_outcome "docs/agg-frag.md", the DSMC notes, eqs. (9)-(13) corrected)
 * With the collision-weighted Maxwellian pair distribution, x = E_imp/(m_kj s) = g^2/(2 s) has
 * density x e^-x and U = (g.e)^2/g^2 is uniform on (0, 1), independent of x; E_n = m_kj s x U.
 * Thresholds x_a = E_agg/(m_kj s), x_f = E_frag/(m_kj s), x_m = max(x_a, x_f). In this order:
 * aggregation if x < x_a; fragmentation into k + j monomers if x U > x_f and k + j >= 3; else a
 * bounce with restitution alpha (\ref cm_rule "docs/collision-model.md"). Hence
 * - P_agg = gamma(2, x_a) = 1 - (1 + x_a) e^-x_a,
 * - P_frag = Gamma(2, x_m) - x_f Gamma(1, x_m) = (1 + x_m - x_f) e^-x_m (0 for two monomers),
 * - P_bounce = 1 - P_agg - P_frag.
 * Energies need the x-moments of the regions, I_agg = gamma(3, x_a),
 * I_frag = Gamma(3, x_m) - x_f Gamma(2, x_m), and the U-weighted bounce moment
 * J_b = 1 - gamma(3, x_a)/2 - [Gamma(3, x_m) - x_f^2 Gamma(1, x_m)]/2.
 * Given g, v_k is Gaussian with mean (theta_k/s) g and variance theta_k theta_j/s per component,
 * so, with g^2 = 2 s x,
 * - E[m_k v_k^2/2 | x] = (T_k theta_k/s) x + (3/2) T_k theta_j/s,
 * - E[M V^2/2 | x] = M s (theta_k/s - mu_jk)^2 x + (3/2) M theta_k theta_j/s (V: centre of mass),
 * - E_imp = m_kj s x, and for a bounce
 *   E[Delta e_k | x, U] = 2 m_k mu_jk (1 + alpha) x U [mu_jk (1 + alpha) s/2 - theta_k].
 * Integrating these over a region against x e^-x dx dU gives the "region moments" (conditional
 * mean times region probability) that pair_moments returns.
 *
 * \subsection smol_equations Rate equations (\ref af_smoluchowski "docs/agg-frag.md")
 * Sums over j run over ordered pairs, j = 1..K including j = k.
 * dn_k/dt = (1/2) sum_{i+j=k} w_ij P_agg,ij - sum_j w_kj (P_agg + P_frag)_kj
 *           + delta_k1 (1/2) sum_{i,j} (i + j) w_ij P_frag,ij,
 * dE_k/dt = sum_j w_kj [-(agg moment of e_k) - (frag moment of e_k) + (bounce moment of Delta e_k)]
 *           + (1/2) sum_{i+j=k} w_ij (agg moment of M V^2/2)_ij
 *           + delta_k1 (1/2) sum_{i,j} w_ij (frag moment of M V^2/2 + eps_f^2 E_imp)_ij,
 * E_k = (3/2) n_k T_k: fragments share the centre-of-mass energy plus eps_f^2 E_imp (\ref af_energy_equation "docs/agg-frag.md").
 * With E_agg = 0 and E_frag = infinity only bounces remain and the monomer equation is Haff's law
 * dT/dt = -(4/3) sqrt(pi) (1 - alpha^2) n sigma^2 sqrt(T/m) T (\ref haff_law "docs/haff-and-mixtures.md", theory.hpp).
 * The Maxwellian closure is exact at t = 0; later the removal of slow pairs makes the true
 * distributions non-Maxwellian and DSMC drifts from this theory (\ref af_accuracy "docs/agg-frag.md": sticking gas, n_1 about
 * 6 % low by the time the mean cluster size is 8.5).
 *
 * \subsection smol_numerics Numerical integration
 * Sizes 1..K are integrated; clusters that would grow beyond K are removed and their mass is
 * integrated as one extra component ("lost"), so sum_k k n_k/n_1(0) + lost = 1 holds to round-off.
 * solve() starts at K = 64 and doubles K whenever the mass lost at the current K passes 1e-12,
 * going on from the current state (the new sizes start empty, the lost mass is carried), so one
 * integration reaches the last output time with lost < 1e-8 (at most 8 doublings of 1e-12 each, plus
 * what is lost at the final K); should the lost mass still pass 1e-8, integrations from t = 0 with
 * K doubled from that K follow, each abandoned once its lost mass passes 1e-8. The state is
 * scaled, n_k/n_1(0) and E_k/(n_1(0) T0), with rtol 1e-9 and atol 1e-15 (1e-14 for the energies);
 * three more components count aggregations, fragmentations and collisions per initial monomer.
 * The equations are not stiff (rates change on the collision time scale, which the accuracy
 * already resolves), so CVODE integrates them with Adams and fixed-point iteration: no Jacobian,
 * and the cost is O(K^2) per right-hand side. Pairs with a partner below 1e-20 n_1(0), or whose
 * densities multiply to less than 1e-22 n_1(0)^2, are skipped: their terms are far below the
 * absolute tolerance (at most ~1e-20 events per collision time against 1e-15 on any n_k), and each pair
 * conserves mass on its own.
 * BDF with a dense Newton solver, the other theory modules' choice, would cost (2K)^3 per
 * factorisation (bench/bench_smoluchowski.cpp compares them: \ref perf_theory "docs/performance.md").
 * The lost mass is checked 16 times per output interval (interpolated points, no extra steps).
 * Growing K during the integration gives results within 1e-8 relative of a restart from t = 0 for
 * every size the run holds at least one cluster of (1e-9 for the totals), the tolerance of the
 * integration (\ref af_numerics "docs/agg-frag.md"; its cost: \ref perf_theory "docs/performance.md").
 * Partial temperatures for the right-hand side are regularised, T_k = (E_k + (3/2) n_floor T) /
 * ((3/2)(n_k + n_floor)) with T the mean temperature and n_floor = 1e-18 n_1(0) far below the
 * absolute tolerance, so that sizes with no clusters (or integration noise) have a finite T_k near
 * T; their rates carry a factor n_k and vanish with it. Small negative n_k, E_k are read as 0.
 *
 * \subsection smol_units Units
 * Any consistent set; k_B = 1, so temperatures and thresholds are energies. Rates are per unit
 * volume and time; solve() reports densities and event counts per initial monomer.
 *
 * Checked by tests/smoluchowski_test.cpp (region moments against Monte Carlo of the collision rule,
 * the Haff limit, conservation of mass and the sign of the energy balance, rates at t = 0).
 */
#pragma once


#include <cstddef>
#include <functional>
#include <stdexcept>
#include <vector>

namespace gdsmc::theory::smoluchowski {

/// Monomers and collision model. Energies are thresholds on E_imp = m_kj g^2/2 (aggregation) and
/// on E_n = m_kj (g.e)^2/2 (fragmentation); +infinity disables fragmentation (aggregation_energy
/// = +infinity: every collision sticks).
struct Parameters {
  double monomer_mass;          ///< m_1 > 0
  double monomer_diameter;      ///< sigma_1 > 0
  double monomer_density;       ///< n_1(0) > 0
  double initial_temperature;   ///< T0 > 0 of the monomers (k_B = 1)
  double restitution;           ///< alpha in [0, 1] of bounces
  double aggregation_energy;    ///< E_agg >= 0 or +infinity
  double fragmentation_energy;  ///< E_frag >= 0 or +infinity
  double fragment_restitution;  ///< eps_f in [0, 1]: fragments carry eps_f^2 E_imp in the CM frame
};

/// Probabilities of the three outcomes of one collision of a pair (sum 1).
struct Outcomes {
  double aggregation;    ///< the pair sticks
  double fragmentation;  ///< the pair shatters
  double bounce;         ///< the pair bounces
};

/// \ref af_smoluchowski "docs/agg-frag.md": outcome probabilities of a collision of sizes k, j (>= 1) with Maxwellian T_k, T_j.
Outcomes outcome_probabilities(const Parameters& parameters, std::size_t k, std::size_t j,
                               double T_k, double T_j);

/// Region moments per collision of the pair (k, j): mean over collisions of the quantity times the
/// indicator of the outcome (conditional mean times outcome probability). energy_*: m v^2/2 of the
/// partner before the collision; cm_energy: M V^2/2; impact_energy_frag: E_imp;
/// bounce_energy_change_*: m v'^2/2 - m v^2/2 over bounces.
struct PairMoments {
  Outcomes probability;      ///< the outcome probabilities
  double energy_k_agg;       ///< m_k v_k^2/2, aggregations
  double energy_j_agg;       ///< m_j v_j^2/2, aggregations
  double cm_energy_agg;      ///< M V^2/2, aggregations
  double energy_k_frag;      ///< m_k v_k^2/2, fragmentations
  double energy_j_frag;      ///< m_j v_j^2/2, fragmentations
  double cm_energy_frag;     ///< M V^2/2, fragmentations
  double impact_energy_frag; ///< E_imp, fragmentations
  double bounce_energy_change_k;  ///< m_k v_k'^2/2 - m_k v_k^2/2, bounces
  double bounce_energy_change_j;  ///< m_j v_j'^2/2 - m_j v_j^2/2, bounces
};

/// The PairMoments of sizes k, j (>= 1) at Maxwellian temperatures T_k, T_j.
PairMoments pair_moments(const Parameters& parameters, std::size_t k, std::size_t j, double T_k,
                         double T_j);

/// Rates per unit volume and time at t = 0 (monomers only, at T0); log_monomer_rate = d ln n_1/dt.
struct InitialRates {
  double collisions;        ///< all collisions
  double aggregations;      ///< those that stick
  double fragmentations;    ///< those that shatter
  double bounces;           ///< those that bounce
  double log_monomer_rate;  ///< d ln n_1/dt
};

/// The InitialRates of the Parameters' monomer gas.
InitialRates initial_rates(const Parameters& parameters);

/// Solution at the requested times. Tables are row-major, time index x size index (k - 1).
struct Solution {
  std::vector<double> time;                ///< the requested times
  std::size_t max_size = 0;                ///< K, the largest size integrated
  std::vector<double> number_fraction;     ///< n_k(t)/n_1(0)
  std::vector<double> temperature;         ///< T_k(t); 0 where n_k/n_1(0) < 1e-300
  std::vector<double> total_temperature;   ///< sum_k n_k T_k / sum_k n_k
  std::vector<double> kinetic_energy;      ///< sum_k (3/2) n_k T_k / n_1(0)
  std::vector<double> aggregations;        ///< cumulative events per initial monomer
  std::vector<double> fragmentations;      ///< cumulative events per initial monomer
  std::vector<double> collisions;          ///< cumulative events per initial monomer
  double lost_mass_fraction = 0.0;         ///< mass in sizes > K at the last time (< 1e-8)
};

/**
 * Integrates the rate equations from monomers at T0 and reports at `times` (finite, non-negative,
 * strictly increasing; times[0] may be 0), doubling K from 64 until the lost mass fraction at the
 * last time is below 1e-8 (std::runtime_error if K would exceed 16384). std::invalid_argument for
 * bad parameters or times, std::runtime_error naming a failing SUNDIALS call.
 */
Solution solve(const Parameters& parameters, const std::vector<double>& times);

/// Asked at every right-hand side (O(K^2) work, so within a fraction of a second at any K): true
/// stops the integration with Stopped (an interrupt, or the time --compare allows the theory).
using Stop = std::function<bool()>;
/// What solve() throws when its Stop said so.
struct Stopped : std::runtime_error {
  Stopped() : std::runtime_error("the Smoluchowski integration was stopped") {}
};
/// solve() that asks `stop` (which may be empty: never) at every right-hand side.
Solution solve(const Parameters& parameters, const std::vector<double>& times, const Stop& stop);

}  // namespace gdsmc::theory::smoluchowski
