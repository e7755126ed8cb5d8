#include "model/restitution.hpp"

#include <stdexcept>
#include <string>

namespace gdsmc::restitution {

double viscoelastic(double beta_ki, double normal_speed) {
  if (!(beta_ki >= 0.0) || !std::isfinite(beta_ki) || !std::isfinite(normal_speed))
    throw std::domain_error("viscoelastic restitution: beta must be finite and >= 0, g.e finite");
  const double u = std::sqrt(beta_ki) * std::pow(std::abs(normal_speed), 0.1);  // \ref visco_one_material "docs/viscoelastic.md"
  if (u > u_max)
    throw std::domain_error("viscoelastic restitution: u = beta^(1/2) |g.e|^(1/10) = " + std::to_string(u) +
                            " exceeds the series cut-off " + std::to_string(u_max) +
                            " (impact speed " + std::to_string(std::abs(normal_speed)) +
                            "): &system visco_a_kappa is too large for this run's impact speeds (docs/viscoelastic.md "
                            "\"Range of validity\")");
  return series(u);
}

species::PairMatrix one_material_beta(const species::Mixture& mix, double beta_11) {
  if (!(beta_11 >= 0.0) || !std::isfinite(beta_11))
    throw std::invalid_argument("viscoelastic beta: beta_11 must be finite and >= 0");
  if (mix.size() == 0) return species::PairMatrix(0);
  // Bodrova and Osinsky 2024, eq. (8): sigma_eff = sigma_i sigma_k/(sigma_i + sigma_k); \ref visco_one_material "docs/viscoelastic.md" scaling.
  auto beta = [beta_11, d = mix.diameter, m = mix.mass](std::size_t k, std::size_t i) {
    const auto sigma_eff = [&d](std::size_t a, std::size_t b) { return d[a] * d[b] / (d[a] + d[b]); };
    const auto reduced = [&m](std::size_t a, std::size_t b) { return m[a] * m[b] / (m[a] + m[b]); };
    const double ratio = std::sqrt(sigma_eff(k, i) / sigma_eff(0, 0)) * reduced(0, 0) / reduced(k, i);
    return beta_11 * std::pow(ratio, 0.4);  // \ref visco_one_material "docs/viscoelastic.md"
  };
  species::PairMatrix matrix = species::PairMatrix::computed(mix.size(), beta);
  if (mix.size() <= species::dense_pair_limit) matrix.densify();
  return matrix;
}

}  // namespace gdsmc::restitution
