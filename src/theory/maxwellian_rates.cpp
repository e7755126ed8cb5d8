// The Maxwellian pair sums of ERRATA §2 and §4 with their derivatives: see maxwellian_rates.hpp.
#include "theory/maxwellian_rates.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gdsmc::theory::detail {

namespace {
constexpr double pi = std::numbers::pi;
}  // namespace

MaxwellianRates::MaxwellianRates(const species::Mixture& mix) {
  const auto s = static_cast<Eigen::Index>(mix.size());
  inverse_mass_.resize(s);
  number_density_ = Eigen::Map<const Eigen::VectorXd>(mix.number_density.data(), s);
  a_.resize(s, s);
  b_.resize(s, s);
  e_.resize(s, s);
  const double xi_prefactor = (8.0 / 3.0) * std::sqrt(2.0 * pi);  // ERRATA §4
  const double rate_prefactor = 0.5 * pi * std::sqrt(8.0 / pi);   // ERRATA §2, halved (k, j and j, k)
  for (Eigen::Index k = 0; k < s; ++k) inverse_mass_(k) = 1.0 / mix.mass[static_cast<std::size_t>(k)];
  for (Eigen::Index k = 0; k < s; ++k)
    for (Eigen::Index j = k; j < s; ++j) {  // sigma_kj, chi_kj, alpha_kj are symmetric
      const auto kk = static_cast<std::size_t>(k), jj = static_cast<std::size_t>(j);
      const double sigma = 0.5 * (mix.diameter[kk] + mix.diameter[jj]);  // sigma_kj (species.hpp)
      const double chi = mix.enskog ? mix.pair_correlation(kk, jj) : 1.0;
      const double one_plus_alpha = 1.0 + mix.restitution(kk, jj);
      const double mu_jk = mix.mass[jj] / (mix.mass[kk] + mix.mass[jj]);  // m_j/(m_k + m_j)
      const double mu_kj = 1.0 - mu_jk;
      const double pair = xi_prefactor * sigma * sigma * chi * one_plus_alpha;
      // row k, partner j (ERRATA §4 split as in maxwellian_rates.hpp)
      const double common_kj = pair * mix.number_density[jj] * mu_jk;
      a_(j, k) = common_kj * (1.0 - 0.5 * one_plus_alpha * mu_jk);
      b_(j, k) = common_kj * 0.5 * one_plus_alpha * mu_kj;
      // row j, partner k
      const double common_jk = pair * mix.number_density[kk] * mu_kj;
      a_(k, j) = common_jk * (1.0 - 0.5 * one_plus_alpha * mu_kj);
      b_(k, j) = common_jk * 0.5 * one_plus_alpha * mu_jk;
      e_(j, k) = e_(k, j) = rate_prefactor * mix.number_density[kk] * mix.number_density[jj] *
                            sigma * sigma * chi;
    }
}

void MaxwellianRates::cooling_rates(std::span<const double> T, std::span<double> zeta) const {
  const auto s = static_cast<Eigen::Index>(size());
  const Eigen::Map<const Eigen::ArrayXd> t(T.data(), s);
  const Eigen::ArrayXd theta = t * inverse_mass_.array();
  Eigen::ArrayXd r(s);
  for (Eigen::Index k = 0; k < s; ++k) {
    r = (theta + theta(k)).sqrt();  // r_kj over j
    zeta[static_cast<std::size_t>(k)] =
        (a_.col(k).array() * r).sum() - (b_.col(k).array() * r * t).sum() / t(k);
  }
}

double MaxwellianRates::cooling_rates_and_collision_rate(std::span<const double> T,
                                                         std::span<double> zeta) const {
  const auto s = static_cast<Eigen::Index>(size());
  const Eigen::Map<const Eigen::ArrayXd> t(T.data(), s);
  const Eigen::ArrayXd theta = t * inverse_mass_.array();
  Eigen::ArrayXd r(s);
  double rate = 0.0;
  for (Eigen::Index k = 0; k < s; ++k) {
    r = (theta + theta(k)).sqrt();
    zeta[static_cast<std::size_t>(k)] =
        (a_.col(k).array() * r).sum() - (b_.col(k).array() * r * t).sum() / t(k);
    rate += (e_.col(k).array() * r).sum();
  }
  return rate;
}

void MaxwellianRates::jacobian(std::span<const double> T, Eigen::MatrixXd& J,
                               std::span<double> collision_gradient) const {
  const auto s = static_cast<Eigen::Index>(size());
  const Eigen::Map<const Eigen::ArrayXd> t(T.data(), s);
  const Eigen::ArrayXd theta = t * inverse_mass_.array();
  J.resize(s, s);
  Eigen::ArrayXd r(s), rho(s), g(s);
  // Row k of J is built as column k of J^T (contiguous), then transposed in place.
  for (Eigen::Index k = 0; k < s; ++k) {
    r = (theta + theta(k)).sqrt();
    rho = t / t(k);  // T_j/T_k
    g = a_.col(k).array() - b_.col(k).array() * rho;
    const Eigen::ArrayXd half_over_r = 0.5 / r;
    const Eigen::ArrayXd rb_rho = r * b_.col(k).array() * rho;
    // P_kl = theta_l g_kl/(2 r_kl) - r_kl b_kl T_l/T_k; D_k = sum_j [theta_k g/(2r) + r b T_j/T_k]
    J.col(k) = (theta * g * half_over_r - rb_rho).matrix();
    J(k, k) += theta(k) * (g * half_over_r).sum() + rb_rho.sum();
    if (!collision_gradient.empty())
      collision_gradient[static_cast<std::size_t>(k)] =
          theta(k) * (e_.col(k).array() / r).sum();  // d R/d ln T_k
  }
  J.transposeInPlace();
}

double MaxwellianRates::largest_collision_frequency(std::span<const double> T) const {
  const auto s = static_cast<Eigen::Index>(size());
  const Eigen::Map<const Eigen::ArrayXd> t(T.data(), s);
  const Eigen::ArrayXd theta = t * inverse_mass_.array();
  double largest = 0.0;
  for (Eigen::Index k = 0; k < s; ++k)
    largest = std::max(largest, 2.0 * (e_.col(k).array() * (theta + theta(k)).sqrt()).sum() /
                                    number_density_(k));
  return largest;
}

void MaxwellianRates::jacobian_diagonal(std::span<const double> T,
                                        std::span<double> diagonal) const {
  const auto s = static_cast<Eigen::Index>(size());
  const Eigen::Map<const Eigen::ArrayXd> t(T.data(), s);
  const Eigen::ArrayXd theta = t * inverse_mass_.array();
  Eigen::ArrayXd r(s), rho(s), g(s);
  for (Eigen::Index k = 0; k < s; ++k) {
    r = (theta + theta(k)).sqrt();
    rho = t / t(k);
    g = a_.col(k).array() - b_.col(k).array() * rho;
    // D_k + P_kk (maxwellian_rates.hpp); P_kk = theta_k g_kk/(2 r_kk) - r_kk b_kk
    diagonal[static_cast<std::size_t>(k)] =
        theta(k) * (g / r).sum() * 0.5 + (r * b_.col(k).array() * rho).sum() +
        theta(k) * g(k) * 0.5 / r(k) - r(k) * b_(k, k);
  }
}

}  // namespace gdsmc::theory::detail
