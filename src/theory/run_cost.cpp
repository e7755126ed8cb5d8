#include "theory/run_cost.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "theory/rough.hpp"
#include "theory/theory.hpp"

namespace gdsmc::theory {

namespace {

/// (1 - alpha_max^2)/3: the one-species ratio of the Haff rate to nu at the largest restitution, which cools
/// slowest (the O(S) bound of the header).
double slowest_cooling_ratio(const species::Mixture& mix) {
  const auto& a = mix.restitution;
  const double alpha = a.is_dense() ? *std::max_element(a.values.begin(), a.values.end()) : a(0, 0);
  return (1.0 - alpha * alpha) / 3.0;
}

/// nu_0 and r = zeta_0/nu_0 of the header: exact sums for a few species, O(S) bounds for many.
std::pair<double, double> rates(const species::Mixture& mix, const std::vector<double>& t0, Cooling cooling) {
  const std::size_t s = mix.size();
  const double n = mix.total_density();
  if (mix.rough() && cooling == Cooling::haff && s <= exact_species) {
    // Rough spheres cool their translation at zeta* = (4/3)(A - B theta) per collision per particle in
    // the HCS (rough.hpp; \ref rough_maxwellian "docs/rough-spheres.md"), the least over the pairs.
    double r = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < s; ++k)
      for (std::size_t j = 0; j < s; ++j)
        r = std::min(r, rough::cooling_state(mix.restitution(k, j), mix.roughness(k, j), mix.moment_of_inertia[k])
                            .cooling_rate_reduced);
    return {2.0 * total_collision_rate(mix, t0) / n, std::max(0.0, r)};
  }
  if (s <= exact_species) {
    const double nu0 = 2.0 * total_collision_rate(mix, t0) / n;  // \ref cm_mixture_rate "docs/collision-model.md"
    if (cooling != Cooling::haff) return {nu0, 0.0};
    const PairMatrix xi = cooling_rate_matrix(mix, t0);        // \ref haff_mixture_odes "docs/haff-and-mixtures.md"
    double loss = 0.0, energy = 0.0;
    for (std::size_t k = 0; k < s; ++k) {
      double row = 0.0;
      for (std::size_t j = 0; j < s; ++j) row += xi(k, j);
      loss += mix.number_density[k] * t0[k] * row;
      energy += mix.number_density[k] * t0[k];
    }
    return {nu0, std::max(0.0, loss / energy) / nu0};
  }
  std::size_t largest = 0;
  double speed2 = 0.0;  // max_k T_k/m_k
  for (std::size_t k = 0; k < s; ++k) {
    if (mix.diameter[k] > mix.diameter[largest]) largest = k;
    speed2 = std::max(speed2, t0[k] / mix.mass[k]);
  }
  // chi_kj grows with sigma_k sigma_j/sigma_kj (\ref cm_chi "docs/collision-model.md"): its largest value is at the largest pair.
  const double sigma = mix.diameter[largest], chi = mix.pair_correlation(largest, largest);
  const double nu0 = n * std::numbers::pi * sigma * sigma * chi * std::sqrt(16.0 * speed2 / std::numbers::pi);
  if (cooling != Cooling::haff) return {nu0, 0.0};
  return {nu0, slowest_cooling_ratio(mix)};
}

}  // namespace

RunCost estimate_run_cost(const species::Mixture& mix, const std::vector<double>& initial_temperature,
                          std::optional<double> t_end, std::optional<double> collisions_per_particle,
                          Cooling cooling) {
  RunCost cost;
  if (collisions_per_particle) {
    cost.collisions_per_particle = *collisions_per_particle;
    if (cooling == Cooling::haff) {
      const double r = rates(mix, initial_temperature, cooling).second;
      cost.temperature_ratio = std::exp(-r * cost.collisions_per_particle);  // T(C)/T_0 = exp(-r C)
    }
    return cost;
  }
  const auto [nu0, r] = rates(mix, initial_temperature, cooling);
  const double elastic = nu0 * *t_end;  // C = nu_0 t at constant T
  const double x = 0.5 * r * elastic;   // zeta_0 t/2
  // C = (2/r) ln(1 + zeta_0 t/2), which tends to nu_0 t as r -> 0.
  cost.collisions_per_particle = x > 1e-12 ? 2.0 / r * std::log1p(x) : elastic;
  if (cooling == Cooling::haff) cost.temperature_ratio = 1.0 / ((1.0 + x) * (1.0 + x));  // Haff's law
  return cost;
}

double white_noise_heating(const species::Mixture& mix, const std::vector<double>& initial_temperature,
                           const std::vector<double>& strength, double t_end) {
  const std::size_t s = mix.size();
  const double n = mix.total_density();
  double power = 0.0, temperature = 0.0;  // P = max_k m_k chi^2_k, T_0 = sum_k x_k T_k
  for (std::size_t k = 0; k < s; ++k) {
    power = std::max(power, mix.mass[k] * (k < strength.size() ? strength[k] : 0.0));
    temperature += mix.number_density[k] / n * initial_temperature[k];
  }
  if (!(power > 0.0) || !(temperature > 0.0)) return 1.0;
  double r = 0.0;  // the least loss per collision over the pairs (rough.hpp driven_state)
  if (s > exact_species && !mix.rough()) {  // as rates() bounds a smooth gas
    r = slowest_cooling_ratio(mix);
  } else if (s <= exact_species) {
    r = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < s; ++k)
      for (std::size_t j = 0; j < s; ++j)
        r = std::min(r, rough::driven_state(mix.restitution(k, j), mix.rough() ? mix.roughness(k, j) : -1.0,
                                            mix.rough() ? mix.moment_of_inertia[k] : 0.4)
                            .cooling_rate_reduced);
  }
  const double nu0 = rates(mix, initial_temperature, Cooling::held).first;
  const double kept = 1.0 + power * t_end / temperature;  // no loss at all
  const double steady = r > 0.0 && nu0 > 0.0 ? std::pow(power / (r * nu0 * temperature), 2.0 / 3.0)
                                             : std::numeric_limits<double>::infinity();
  return std::max(1.0, std::min(kept, steady));
}

}  // namespace gdsmc::theory
