/**
 * \file gmres.hpp
 * \brief Internal: restarted GMRES for a dense non-symmetric system A x = b, right-preconditioned
 *        by a diagonal: O(n^2) per iteration instead of the O(n^3) of an LU factorisation.
 *
 * Y. Saad and M. H. Schultz, SIAM J. Sci. Stat. Comput. 7, 856 (1986); Y. Saad, Iterative Methods
 * for Sparse Linear Systems, 2nd ed. (SIAM 2003), Algorithm 6.9 (GMRES with modified Gram-Schmidt
 * Arnoldi, the least-squares problem reduced by Givens rotations) with the right preconditioning of
 * Algorithm 9.5, M = diag(d): A M^-1 y = b, x = M^-1 y; restarted every `restart` iterations
 * (GMRES(m)). Stops when ||b - A x||_2 <= tolerance ||b||_2 (the Givens residual estimate, exact in
 * exact arithmetic; the true residual is recomputed at every restart and at the end).
 * Documentation: docs/haff-and-mixtures.md "Asymptotic temperature ratios".
 * Checked by tests/theory_test.cpp against Eigen's LU.
 */
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gdsmc::theory::detail {

struct GmresResult {
  int iterations = 0;
  double relative_residual = 0.0;  ///< ||b - A x||/||b|| at the end
  bool converged = false;
};

/// Solves A x = b; x holds the initial guess on entry (e.g. zero) and the solution on exit.
/// `diagonal` (size n, no zero entry) is the right preconditioner; pass A's diagonal for Jacobi.
inline GmresResult gmres(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                         const Eigen::VectorXd& diagonal, Eigen::VectorXd& x, double tolerance,
                         int restart = 50, int max_iterations = 1000) {
  using Eigen::Index;
  using Eigen::VectorXd;
  GmresResult result;
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  const Index n = b.size();
  const int m = std::max(1, std::min<int>(restart, static_cast<int>(n)));
  std::vector<VectorXd> V(static_cast<std::size_t>(m + 1));
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
  VectorXd cs(m), sn(m), g(m + 1);
  while (result.iterations < max_iterations) {
    VectorXd r = b - A * x;
    double beta = r.norm();
    result.relative_residual = beta / b_norm;
    if (result.relative_residual <= tolerance) {
      result.converged = true;
      return result;
    }
    V[0] = r / beta;
    g.setZero();
    g(0) = beta;
    H.setZero();
    int j = 0;
    for (; j < m && result.iterations < max_iterations; ++j) {
      ++result.iterations;
      VectorXd w = A * V[static_cast<std::size_t>(j)].cwiseQuotient(diagonal);  // A M^-1 v_j
      for (int i = 0; i <= j; ++i) {  // modified Gram-Schmidt
        H(i, j) = w.dot(V[static_cast<std::size_t>(i)]);
        w -= H(i, j) * V[static_cast<std::size_t>(i)];
      }
      H(j + 1, j) = w.norm();
      if (H(j + 1, j) > 0.0) V[static_cast<std::size_t>(j + 1)] = w / H(j + 1, j);
      for (int i = 0; i < j; ++i) {  // the earlier rotations on the new column
        const double t = cs(i) * H(i, j) + sn(i) * H(i + 1, j);
        H(i + 1, j) = -sn(i) * H(i, j) + cs(i) * H(i + 1, j);
        H(i, j) = t;
      }
      const double denominator = std::hypot(H(j, j), H(j + 1, j));
      cs(j) = H(j, j) / denominator;
      sn(j) = H(j + 1, j) / denominator;
      H(j, j) = denominator;
      H(j + 1, j) = 0.0;
      g(j + 1) = -sn(j) * g(j);
      g(j) = cs(j) * g(j);
      if (std::abs(g(j + 1)) <= tolerance * b_norm) {  // |g(j + 1)| = ||b - A x_j|| (Saad Prop. 6.9)
        ++j;
        break;
      }
    }
    // x += M^-1 V_j y, H(0:j, 0:j) y = g(0:j) (upper triangular)
    const VectorXd y = H.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    VectorXd update = VectorXd::Zero(n);
    for (int i = 0; i < j; ++i) update += y(i) * V[static_cast<std::size_t>(i)];
    x += update.cwiseQuotient(diagonal);
  }
  result.relative_residual = (b - A * x).norm() / b_norm;
  result.converged = result.relative_residual <= tolerance;
  return result;
}

}  // namespace gdsmc::theory::detail
