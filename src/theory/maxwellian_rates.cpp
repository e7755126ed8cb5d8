// The Maxwellian pair sums of \ref cm_mixture_rate "docs/collision-model.md" and \ref haff_mixture_odes "docs/haff-and-mixtures.md" with their derivatives: see maxwellian_rates.hpp.
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
  offset_.resize(static_cast<std::size_t>(s) + 1);
  offset_[0] = 0;
  for (Eigen::Index k = 0; k < s; ++k)
    offset_[static_cast<std::size_t>(k) + 1] = offset_[static_cast<std::size_t>(k)] + (s - k);
  const Eigen::Index pairs = offset_.back();
  a_row_.resize(pairs);
  b_row_.resize(pairs);
  a_partner_.resize(pairs);
  b_partner_.resize(pairs);
  e_.resize(pairs);
  const double xi_prefactor = (8.0 / 3.0) * std::sqrt(2.0 * pi);  // \ref haff_mixture_odes "docs/haff-and-mixtures.md"
  const double rate_prefactor = 0.5 * pi * std::sqrt(8.0 / pi);   // \ref cm_mixture_rate "docs/collision-model.md", halved (k, j and j, k)
  for (Eigen::Index k = 0; k < s; ++k) inverse_mass_(k) = 1.0 / mix.mass[static_cast<std::size_t>(k)];
  for (Eigen::Index k = 0; k < s; ++k)
    for (Eigen::Index j = k; j < s; ++j) {  // sigma_kj, chi_kj, alpha_kj are symmetric
      const auto kk = static_cast<std::size_t>(k), jj = static_cast<std::size_t>(j);
      const Eigen::Index p = offset_[kk] + (j - k);
      const double sigma = 0.5 * (mix.diameter[kk] + mix.diameter[jj]);  // sigma_kj (species.hpp)
      const double chi = mix.enskog ? mix.pair_correlation(kk, jj) : 1.0;
      const double one_plus_alpha = 1.0 + mix.restitution(kk, jj);
      const double mu_jk = mix.mass[jj] / (mix.mass[kk] + mix.mass[jj]);  // m_j/(m_k + m_j)
      const double mu_kj = 1.0 - mu_jk;
      const double pair = xi_prefactor * sigma * sigma * chi * one_plus_alpha;
      // species k, partner j (\ref haff_mixture_odes "docs/haff-and-mixtures.md", split as in maxwellian_rates.hpp)
      const double common_kj = pair * mix.number_density[jj] * mu_jk;
      a_row_(p) = common_kj * (1.0 - 0.5 * one_plus_alpha * mu_jk);
      b_row_(p) = common_kj * 0.5 * one_plus_alpha * mu_kj;
      // species j, partner k; nothing for j = k (that term is the row's own)
      const double common_jk = pair * mix.number_density[kk] * mu_kj;
      a_partner_(p) = j == k ? 0.0 : common_jk * (1.0 - 0.5 * one_plus_alpha * mu_kj);
      b_partner_(p) = j == k ? 0.0 : common_jk * 0.5 * one_plus_alpha * mu_jk;
      e_(p) = rate_prefactor * mix.number_density[kk] * mix.number_density[jj] * sigma * sigma * chi;
    }
}

double MaxwellianRates::sums(std::span<const double> T, std::span<double> zeta,
                             bool with_collisions) const {
  const auto s = static_cast<Eigen::Index>(size());
  const Eigen::Map<const Eigen::ArrayXd> t(T.data(), s);
  const Eigen::ArrayXd theta = t * inverse_mass_.array();
  // zeta_k = sum_j r_kj a_kj - (1/T_k) sum_j r_kj b_kj T_j: the part j >= k from row k's segment,
  // the part j < k gathered into (partner_a, partner_b) while the rows j < k were swept (complete
  // when row k is reached). One square root per unordered pair, one pass over the pair constants
  // (a vectorised loop: this file is compiled with -fopenmp-simd -fno-math-errno, src/CMakeLists.txt).
  Eigen::ArrayXd partner_a = Eigen::ArrayXd::Zero(s), partner_b = Eigen::ArrayXd::Zero(s);
  const double* th = theta.data();
  const double* temperature = T.data();
  double* gathered_a = partner_a.data();
  double* gathered_b = partner_b.data();
  double rate = 0.0;
  for (Eigen::Index k = 0; k < s; ++k) {
    const Eigen::Index n = s - k, p = offset_[static_cast<std::size_t>(k)];
    const double theta_k = th[k], t_k = temperature[k];
    const double* a_row = a_row_.data() + p;
    const double* b_row = b_row_.data() + p;
    const double* a_partner = a_partner_.data() + p;
    const double* b_partner = b_partner_.data() + p;
    const double* e = e_.data() + p;
    const double* th_j = th + k;
    const double* t_j = temperature + k;
    double* g_a = gathered_a + k;
    double* g_b = gathered_b + k;
    double sum_a = 0.0, sum_b = 0.0, sum_e = 0.0;
#pragma omp simd reduction(+ : sum_a, sum_b, sum_e)
    for (Eigen::Index i = 0; i < n; ++i) {
      const double r = std::sqrt(th_j[i] + theta_k);  // r_kj, j = k + i
      sum_a += a_row[i] * r;
      sum_b += b_row[i] * r * t_j[i];
      sum_e += e[i] * r;
      g_a[i] += a_partner[i] * r;  // 0 for j = k
      g_b[i] += b_partner[i] * r * t_k;
    }
    zeta[static_cast<std::size_t>(k)] = sum_a - sum_b / t_k + gathered_a[k] - gathered_b[k] / t_k;
    // sum over ordered pairs: twice the pairs j > k, once j = k
    if (with_collisions) rate += 2.0 * sum_e - e[0] * std::sqrt(2.0 * theta_k);
  }
  return rate;
}

void MaxwellianRates::cooling_rates(std::span<const double> T, std::span<double> zeta) const {
  sums(T, zeta, false);
}

double MaxwellianRates::cooling_rates_and_collision_rate(std::span<const double> T,
                                                         std::span<double> zeta) const {
  return sums(T, zeta, true);
}

void MaxwellianRates::derivatives(std::span<const double> T, Eigen::MatrixXd* J,
                                  std::span<double> diagonal,
                                  std::span<double> collision_gradient) const {
  const auto s = static_cast<Eigen::Index>(size());
  const Eigen::Map<const Eigen::ArrayXd> t(T.data(), s);
  const Eigen::ArrayXd theta = t * inverse_mass_.array();
  // D_k = sum_j [theta_k g_kj/(2 r_kj) + r_kj b_kj T_j/T_k] (maxwellian_rates.hpp), its part j < k
  // and the collision gradient's gathered as in sums().
  Eigen::ArrayXd d(s), partner_d = Eigen::ArrayXd::Zero(s), partner_g = Eigen::ArrayXd::Zero(s);
  Eigen::ArrayXd r(s), rho(s), g_row(s), g_partner(s), half_over_r(s);
  if (J) J->setZero(s, s);
  for (Eigen::Index k = 0; k < s; ++k) {
    const Eigen::Index n = s - k, p = offset_[static_cast<std::size_t>(k)];
    auto rk = r.head(n), hk = half_over_r.head(n), rhok = rho.head(n);
    auto g1 = g_row.head(n), g2 = g_partner.head(n);
    rk = (theta.tail(n) + theta(k)).sqrt();
    hk = 0.5 / rk;
    rhok = t.tail(n) / t(k);                                       // T_j/T_k
    g1 = a_row_.segment(p, n) - b_row_.segment(p, n) * rhok;       // g_kj
    g2 = a_partner_.segment(p, n) - b_partner_.segment(p, n) / rhok;  // g_jk (0 for j = k)
    const auto rb_row = rk * b_row_.segment(p, n) * rhok;           // r b_kj T_j/T_k
    const auto rb_partner = rk * b_partner_.segment(p, n) / rhok;   // r b_jk T_k/T_j
    d(k) = theta(k) * (g1 * hk).sum() + rb_row.sum() + partner_d(k);
    partner_d.tail(n) += theta.tail(n) * g2 * hk + rb_partner;
    if (J) {
      // P_kj = theta_j g_kj/(2 r) - r b_kj T_j/T_k (row k), P_jk = theta_k g_jk/(2 r) - r b_jk T_k/T_j
      const Eigen::ArrayXd row = theta.tail(n) * g1 * hk - rb_row;
      const Eigen::ArrayXd column = theta(k) * g2 * hk - rb_partner;
      J->row(k).tail(n) += row.matrix().transpose();
      J->col(k).tail(n - 1) += column.tail(n - 1).matrix();
    } else if (!diagonal.empty()) {
      diagonal[static_cast<std::size_t>(k)] = theta(k) * g1(0) * hk(0) - rk(0) * b_row_(p);  // P_kk
    }
    if (!collision_gradient.empty()) {  // dR/d ln T_k = theta_k sum_j e_kj/r_kj
      const auto e_over_r = e_.segment(p, n) / rk;
      collision_gradient[static_cast<std::size_t>(k)] = theta(k) * e_over_r.sum() + partner_g(k);
      partner_g.tail(n - 1) += theta.tail(n - 1) * e_over_r.tail(n - 1);
    }
  }
  if (J) {
    J->diagonal() += d.matrix();
  } else if (!diagonal.empty()) {
    for (Eigen::Index k = 0; k < s; ++k) diagonal[static_cast<std::size_t>(k)] += d(k);
  }
}

void MaxwellianRates::jacobian(std::span<const double> T, Eigen::MatrixXd& J,
                               std::span<double> collision_gradient) const {
  derivatives(T, &J, {}, collision_gradient);
}

void MaxwellianRates::jacobian_diagonal(std::span<const double> T,
                                        std::span<double> diagonal) const {
  derivatives(T, nullptr, diagonal, {});
}

double MaxwellianRates::largest_collision_frequency(std::span<const double> T) const {
  const auto s = static_cast<Eigen::Index>(size());
  const Eigen::Map<const Eigen::ArrayXd> t(T.data(), s);
  const Eigen::ArrayXd theta = t * inverse_mass_.array();
  // nu_k = (2/n_k) sum_j e_kj r_kj (\ref cm_mixture_rate "docs/collision-model.md"), the part j < k gathered as in sums()
  Eigen::ArrayXd partner = Eigen::ArrayXd::Zero(s), r(s);
  double largest = 0.0;
  for (Eigen::Index k = 0; k < s; ++k) {
    const Eigen::Index n = s - k, p = offset_[static_cast<std::size_t>(k)];
    auto rk = r.head(n);
    rk = (theta.tail(n) + theta(k)).sqrt();
    const auto er = e_.segment(p, n) * rk;
    largest = std::max(largest, 2.0 * (er.sum() + partner(k)) / number_density_(k));
    partner.tail(n - 1) += er.tail(n - 1);
  }
  return largest;
}

}  // namespace gdsmc::theory::detail
