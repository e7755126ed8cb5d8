/**
 * \file run_cost.hpp
 * \brief The work of a DSMC run estimated from kinetic theory before it starts, so that an
 *        astronomically long run is refused with the estimate instead of running for ever.
 *
 * With nu_0 the collisions suffered per particle per unit time at the initial temperatures
 * (2 x total_collision_rate / n, \ref cm_mixture_rate "docs/collision-model.md") and zeta_0 the cooling rate of the total temperature
 * (sum_k n_k T_k sum_j xi_kj / sum_k n_k T_k, \ref haff_mixture_odes "docs/haff-and-mixtures.md"; for one species the Haff rate of \ref haff_law "docs/haff-and-mixtures.md"),
 * the Maxwellian cooling dT/dt = -zeta T with zeta/nu = r = zeta_0/nu_0 fixed (both scale with
 * sqrt(T)) gives Haff's law T(t) = T_0/(1 + zeta_0 t/2)^2 (\ref haff_law "docs/haff-and-mixtures.md") and, integrating nu,
 *   C(t) = (2/r) ln(1 + r nu_0 t/2)   collisions per particle,   T(C)/T_0 = exp(-r C).
 * A gas whose temperature is held (thermostat, shear flow) collides at nu_0 throughout: C = nu_0 t.
 * With a viscoelastic restitution alpha -> 1 as the gas cools, so C <= nu_0 t is the estimate (an
 * upper bound: nu falls with T). Mixtures of more than `exact_species` species use O(S) bounds
 * instead of the O(S^2) sums: nu_0 <= n pi sigma_max^2 chi_max sqrt(16 max_k(T_k/m_k)/pi)
 * (<|g_kj|> = sqrt(8 s_kj/pi), \ref cm_mean_speed "docs/collision-model.md") and r = (1 - alpha_max^2)/3, the one-species ratio of the
 * Haff rate to nu (\ref cm_pair_rate "docs/collision-model.md", \ref haff_law "docs/haff-and-mixtures.md") at the largest restitution, which cools slowest.
 * A white noise of strengths chi^2_k heats the gas (dT_k/dt = m_k chi^2_k, \ref wn_forcing "docs/white-noise.md")
 * towards its steady state, where P = max_k m_k chi^2_k balances the least translational loss per collision r
 * (rough.hpp driven_state: (1 - alpha^2)/3 smooth, (4/3)(A - B theta) rough) at nu(T) = nu_0 sqrt(T/T_0):
 *   (T_st/T_0)^(3/2) = P/(r nu_0 T_0),   and never above the noise's energy kept: T <= T_0 + P t_end,
 * with T_0 the mean initial temperature; the estimate of a held gas is then taken at T_0 times that factor
 * (white_noise_heating; more than `exact_species` species: r = (1 - alpha_max^2)/3 if smooth, else r = 0, the
 * energy bound alone).
 * Checked by tests/run_cost_test.cpp.
 */
#pragma once

#include <optional>
#include <vector>

#include "model/species.hpp"

namespace gdsmc::theory {

/// How the temperature of the run evolves, for the estimate.
enum class Cooling {
  haff,          ///< free cooling at constant restitution (Haff's law)
  held,          ///< a thermostat or shear flow keeps T near T_0
  viscoelastic,  ///< free cooling with alpha -> 1 (C <= nu_0 t)
};

/// The estimated length of a run.
struct RunCost {
  double collisions_per_particle = 0.0;  ///< C at the end of the run (2 x events / N)
  double temperature_ratio = 1.0;        ///< T(end)/T(0) of the total temperature
};

/// Mixtures up to this many species get the exact O(S^2) nu_0 and zeta_0; larger ones O(S) bounds.
inline constexpr std::size_t exact_species = 64;

/// The estimate of the header for a run to `t_end` or to `collisions_per_particle` (exactly one
/// given) from the temperatures `initial_temperature` (one per species).
RunCost estimate_run_cost(const species::Mixture& mix, const std::vector<double>& initial_temperature,
                          std::optional<double> t_end, std::optional<double> collisions_per_particle,
                          Cooling cooling);

/// The factor (at least 1) by which a white noise of strengths `strength` (chi^2_k, per species) can raise
/// the temperatures `initial_temperature` in a run to `t_end` (header).
double white_noise_heating(const species::Mixture& mix, const std::vector<double>& initial_temperature,
                           const std::vector<double>& strength, double t_end);

}  // namespace gdsmc::theory
