/**
 * \file maxwellian_rates.hpp
 * \brief Internal: the Maxwellian pair sums of a mixture of many species in O(S^2) vectorised
 *        arithmetic, with their analytic derivatives (the Jacobian of the partial-temperature ODEs).
 *
 * Not part of the public API (namespace gdsmc::theory::detail); used by theory.cpp for the
 * partial-temperature ODEs, their CVODE Jacobian and the asymptotic temperature ratios.
 *
 * \section mrates_split The pair sums
 * \ref haff_mixture_odes "docs/haff-and-mixtures.md" (DSMC notes, eq. (76)):
 *   xi_kj = (8/3) sqrt(2 pi) n_j sigma_kj^2 chi_kj sqrt(s_kj) mu_jk (1 + alpha_kj)
 *           [1 - (1/2)(1 + alpha_kj) X_kj],   X_kj = mu_jk + mu_kj T_j/T_k
 * (X_kj = (T_k m_j + T_j m_k)/(T_k (m_j + m_k)) split over its two terms), s_kj = theta_k + theta_j,
 * theta_k = T_k/m_k. Everything but sqrt(s_kj) and T_j/T_k is a constant of the pair, so
 *   xi_kj = r_kj (a_kj - b_kj T_j/T_k),   r_kj = sqrt(theta_k + theta_j),
 *   a_kj = (8/3) sqrt(2 pi) n_j sigma_kj^2 chi_kj mu_jk (1 + alpha_kj) [1 - (1/2)(1 + alpha_kj) mu_jk],
 *   b_kj = (8/3) sqrt(2 pi) n_j sigma_kj^2 chi_kj mu_jk (1 + alpha_kj) (1/2)(1 + alpha_kj) mu_kj,
 * and the collision events per unit volume and time (\ref cm_mixture_rate "docs/collision-model.md", "mixture
 * rates"; like pairs counted once) are
 *   R = sum_{k <= j} R_kj = sum_{k, j} e_kj r_kj,   e_kj = (1/2) n_k n_j pi sigma_kj^2 chi_kj sqrt(8/pi).
 * r_kj and e_kj are symmetric: the constants are stored per unordered pair k <= j, row by row
 * (a_kj, b_kj, a_jk, b_jk, e_kj: 2.5 S^2 doubles), computed once; each evaluation sweeps the pairs
 * once, one square root and a few multiply-adds per unordered pair, which Eigen vectorises, adding
 * row k's terms to zeta_k and the partner's to zeta_j.
 *
 * \section mrates_jacobian Derivatives
 * With u_l = ln T_l, d r_kj/d u_k = theta_k/(2 r_kj), d r_kj/d u_j = theta_j/(2 r_kj) and
 * d(T_j/T_k) = (T_j/T_k)(du_j - du_k), so with g_kj = a_kj - b_kj T_j/T_k:
 *   d zeta_k/d u_l = delta_kl D_k + P_kl,   zeta_k = sum_j xi_kj,
 *   D_k = sum_j [theta_k g_kj/(2 r_kj) + r_kj b_kj T_j/T_k],
 *   P_kl = theta_l g_kl/(2 r_kl) - r_kl b_kl T_l/T_k
 * (for l = k the two parts add up to xi_kk/2, as they must: xi_kk is homogeneous of degree 1/2), and
 *   d R/d u_l = theta_l sum_j e_lj/r_lj   (e is symmetric).
 * Checked against difference quotients and the per-entry functions of theory.hpp by
 * tests/theory_test.cpp.
 */
#pragma once

#include <Eigen/Dense>

#include <cstddef>
#include <span>
#include <vector>

#include "model/species.hpp"

namespace gdsmc::theory::detail {

class MaxwellianRates {
 public:
  /// The pair constants a, b, e of \ref mrates_split (O(S^2), reads every pair of `mix` once).
  explicit MaxwellianRates(const species::Mixture& mix);

  std::size_t size() const { return static_cast<std::size_t>(inverse_mass_.size()); }

  /// zeta_k = sum_j xi_kj for every k (\ref haff_mixture_odes "docs/haff-and-mixtures.md": d ln T_k/dt = -zeta_k) at temperatures T.
  void cooling_rates(std::span<const double> T, std::span<double> zeta) const;

  /// Cooling rates and the total collision events per unit volume and time (\ref cm_mixture_rate "docs/collision-model.md") in one pass.
  double cooling_rates_and_collision_rate(std::span<const double> T, std::span<double> zeta) const;

  /// d zeta_k/d ln T_l into J (S x S; \ref mrates_jacobian) and, if `collision_gradient` is not
  /// empty, d R/d ln T_l into it.
  void jacobian(std::span<const double> T, Eigen::MatrixXd& J,
                std::span<double> collision_gradient = {}) const;

  /// Largest collision frequency per particle, max_k (2/n_k) sum_j e_kj r_kj (\ref cm_mixture_rate "docs/collision-model.md"): the
  /// fastest kinetic time scale.
  double largest_collision_frequency(std::span<const double> T) const;

  /// The diagonal d zeta_k/d ln T_k = D_k + P_kk alone (O(S^2) time, O(S) memory).
  void jacobian_diagonal(std::span<const double> T, std::span<double> diagonal) const;

 private:
  double sums(std::span<const double> T, std::span<double> zeta, bool with_collisions) const;
  void derivatives(std::span<const double> T, Eigen::MatrixXd* J, std::span<double> diagonal,
                   std::span<double> collision_gradient) const;

  Eigen::VectorXd inverse_mass_, number_density_;
  // Unordered pairs k <= j, row k at offset_[k] + (j - k): a_row_ = a_kj, b_row_ = b_kj,
  // a_partner_ = a_jk, b_partner_ = b_jk (0 for j = k), e_ = e_kj.
  std::vector<Eigen::Index> offset_;
  Eigen::ArrayXd a_row_, b_row_, a_partner_, b_partner_, e_;
};

}  // namespace gdsmc::theory::detail
