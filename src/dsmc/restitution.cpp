#include "dsmc/restitution.hpp"

#include <stdexcept>
#include <string>

namespace gdsmc::restitution {

double viscoelastic(double beta_ki, double normal_speed) {
  if (!(beta_ki >= 0.0) || !std::isfinite(beta_ki) || !std::isfinite(normal_speed))
    throw std::domain_error("viscoelastic restitution: beta must be finite and >= 0, g.e finite");
  const double u = std::sqrt(beta_ki) * std::pow(std::abs(normal_speed), 0.1);  // ERRATA §11
  if (u > u_max)
    throw std::domain_error("viscoelastic restitution: u = beta^(1/2) |g.e|^(1/10) = " + std::to_string(u) +
                            " exceeds the series cut-off " + std::to_string(u_max) +
                            " (impact speed " + std::to_string(std::abs(normal_speed)) + ")");
  return series(u);
}

species::PairMatrix one_material_beta(const species::Mixture& mix, double beta_11) {
  if (!(beta_11 >= 0.0) || !std::isfinite(beta_11))
    throw std::invalid_argument("viscoelastic beta: beta_11 must be finite and >= 0");
  if (mix.size() == 0) return species::PairMatrix(0);
  // seed 001 eq 8: sigma_eff = sigma_i sigma_k/(sigma_i + sigma_k); ERRATA §11 scaling.
  auto sigma_eff = [&](std::size_t k, std::size_t i) {
    return mix.diameter[k] * mix.diameter[i] / (mix.diameter[k] + mix.diameter[i]);
  };
  species::PairMatrix beta(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t i = k; i < mix.size(); ++i) {
      const double ratio = std::sqrt(sigma_eff(k, i) / sigma_eff(0, 0)) * mix.reduced_mass(0, 0) /
                           mix.reduced_mass(k, i);
      beta(k, i) = beta(i, k) = beta_11 * std::pow(ratio, 0.4);  // ERRATA §11
    }
  return beta;
}

}  // namespace gdsmc::restitution
