// One species HCS beyond first Sonine: see theory/sonine.hpp \ref sonine_higher and docs/sonine.md
// "Beyond first Sonine" (Brilliantov and Poeschel, Europhys. Lett. 74, 424 (2006); Noskowicz et al.,
// Europhys. Lett. 79, 60001 (2007); Santos and Montanero, Granular Matter 11, 157 (2009)).
#include <gsl/gsl_integration.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_sf_laguerre.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "theory/sonine.hpp"

namespace gdsmc::theory {
namespace {

constexpr double pi = std::numbers::pi;

struct Rule {
  std::vector<double> x, w;
};

Rule fixed_rule(const gsl_integration_fixed_type* type, int n, double a, double b, double alpha) {
  gsl_integration_fixed_workspace* ws = gsl_integration_fixed_alloc(type, n, a, b, alpha, 0.0);
  if (!ws) throw std::runtime_error("sonine_higher: gsl_integration_fixed_alloc failed");
  Rule r;
  r.x.assign(gsl_integration_fixed_nodes(ws), gsl_integration_fixed_nodes(ws) + n);
  r.w.assign(gsl_integration_fixed_weights(ws), gsl_integration_fixed_weights(ws) + n);
  gsl_integration_fixed_free(ws);
  return r;
}

/// S_k(x) = L_k^(1/2)(x) (3D Sonine polynomials; sonine.hpp \ref sonine_higher).
double sonine_polynomial(int k, double x) { return gsl_sf_laguerre_n(k, 0.5, x); }

/// Collisional moments as quadratic forms: m[((p - 1) * B + i) * B + j], p = 1..K (moment c^(2p)),
/// i, j = 0..K (basis S_i(c1^2) S_j(c2^2), S_0 = 1), B = K + 1, so that
/// mu_2p = sum_ij A_i A_j m[p][i][j] with A = (1, 0, a_2, .., a_K).
/// Exact product Gauss rule: the integrand of basis pair (i, j) and moment 2p is a polynomial of
/// degree <= 2i + 2j + 2p <= 6K in the velocities times exp(-2 C^2 - g^2/2); with c1 = C + g/2,
/// c2 = C - g/2, g along z (isotropy), C = y/sqrt(2): Gauss-Hermite in y (n = 3K + 1 nodes, exact
/// to degree 6K + 1); u = g^2/2 with the weight u e^-u (g^2 dg from the volume element times the
/// g of the flux g.e = g cos(theta)): Gauss-Laguerre, n = 3K + 1; odd powers of g come with odd
/// powers of C_z and vanish on the symmetric Hermite nodes. e on the hemisphere cos(theta) > 0:
/// Gauss-Legendre in cos(theta) (n = 3K + 1) and the trapezoid rule in phi (2K + 2 points, exact
/// for trigonometric degree <= 2K + 1, e enters through c.e to power <= K).
std::vector<double> moment_forms(double alpha, int K) {
  const int B = K + 1, n = 3 * K + 1, nphi = 2 * K + 2;
  const Rule h = fixed_rule(gsl_integration_fixed_hermite, n, 0.0, 1.0, 0.0);
  const Rule l = fixed_rule(gsl_integration_fixed_laguerre, n, 0.0, 1.0, 1.0);
  const Rule t = fixed_rule(gsl_integration_fixed_legendre, n, 0.0, 1.0, 0.0);
  std::vector<double> cphi(nphi), sphi(nphi);
  for (int f = 0; f < nphi; ++f) {
    cphi[f] = std::cos(2.0 * pi * f / nphi);
    sphi[f] = std::sin(2.0 * pi * f / nphi);
  }
  // -(1/2) x pi^-3 (Maxwellians) x 2^(-3/2) (dC = 2^(-3/2) dy) x 4 pi (direction of g)
  // x 2 (g^3 dg = 2 u du) x 2 pi/nphi (trapezoid in phi).
  const double prefactor = -0.5 * std::pow(pi, -3.0) * std::pow(2.0, -1.5) * 4.0 * pi * 2.0 * (2.0 * pi / nphi);
  const double k = 0.5 * (1.0 + alpha);  // \ref cm_rule "docs/collision-model.md", equal masses: v1' = v1 - (1 + alpha)/2 (g.e) e
  std::vector<double> m(static_cast<std::size_t>(K) * B * B, 0.0), E(K + 1), s1(B), s2(B);
  const double r2 = std::sqrt(0.5);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c) {
        const double C[3] = {h.x[a] * r2, h.x[b] * r2, h.x[c] * r2};
        const double wC = h.w[a] * h.w[b] * h.w[c];
        for (int q = 0; q < n; ++q) {
          const double g = std::sqrt(2.0 * l.x[q]);
          const double c1[3] = {C[0], C[1], C[2] + 0.5 * g}, c2[3] = {C[0], C[1], C[2] - 0.5 * g};
          const double x1 = c1[0] * c1[0] + c1[1] * c1[1] + c1[2] * c1[2];
          const double x2 = c2[0] * c2[0] + c2[1] * c2[1] + c2[2] * c2[2];
          std::fill(E.begin(), E.end(), 0.0);
          for (int r = 0; r < n; ++r) {
            const double ct = t.x[r], st = std::sqrt(1.0 - ct * ct), kg = k * g * ct;
            for (int f = 0; f < nphi; ++f) {
              const double e[3] = {st * cphi[f], st * sphi[f], ct};
              double y1 = 0.0, y2 = 0.0;
              for (int d = 0; d < 3; ++d) {
                const double d1 = c1[d] - kg * e[d], d2 = c2[d] + kg * e[d];
                y1 += d1 * d1;
                y2 += d2 * d2;
              }
              const double w = t.w[r] * ct;  // the flux g.e = g cos(theta); g is in the Laguerre weight
              double P1 = 1.0, P2 = 1.0, Q1 = 1.0, Q2 = 1.0;
              for (int p = 1; p <= K; ++p) {
                P1 *= y1;
                P2 *= y2;
                Q1 *= x1;
                Q2 *= x2;
                E[p] += w * (P1 + P2 - Q1 - Q2);
              }
            }
          }
          const double W = wC * l.w[q] * prefactor;
          for (int i = 0; i < B; ++i) {
            s1[i] = sonine_polynomial(i, x1);
            s2[i] = sonine_polynomial(i, x2);
          }
          for (int i = 0; i < B; ++i)
            for (int j = 0; j < B; ++j) {
              const double bb = s1[i] * s2[j] * W;
              for (int p = 1; p <= K; ++p) m[(static_cast<std::size_t>(p - 1) * B + i) * B + j] += bb * E[p];
            }
        }
      }
  return m;
}

/// <|g|> over F(c1) F(c2) as a quadratic form f[i * B + j] in the basis S_i(c1^2) S_j(c2^2), normalised
/// so that f[0] = 1 (the Maxwellian). Exact by the rules of moment_forms (|g| g^2 dg e^(-g^2/2) is the
/// Laguerre weight u e^-u).
std::vector<double> frequency_form(int K) {
  const int B = K + 1, n = 2 * K + 1;
  const Rule h = fixed_rule(gsl_integration_fixed_hermite, n, 0.0, 1.0, 0.0);
  const Rule l = fixed_rule(gsl_integration_fixed_laguerre, n, 0.0, 1.0, 1.0);
  std::vector<double> f(static_cast<std::size_t>(B) * B, 0.0), s1(B), s2(B);
  const double r2 = std::sqrt(0.5);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c)
        for (int q = 0; q < n; ++q) {
          const double C[3] = {h.x[a] * r2, h.x[b] * r2, h.x[c] * r2};
          const double g = std::sqrt(2.0 * l.x[q]);
          const double x1 = C[0] * C[0] + C[1] * C[1] + (C[2] + 0.5 * g) * (C[2] + 0.5 * g);
          const double x2 = C[0] * C[0] + C[1] * C[1] + (C[2] - 0.5 * g) * (C[2] - 0.5 * g);
          const double W = h.w[a] * h.w[b] * h.w[c] * l.w[q];
          for (int i = 0; i < B; ++i) {
            s1[i] = sonine_polynomial(i, x1);
            s2[i] = sonine_polynomial(i, x2);
          }
          for (int i = 0; i < B; ++i)
            for (int j = 0; j < B; ++j) f[i * B + j] += W * s1[i] * s2[j];
        }
  const double norm = f[0];
  for (double& v : f) v /= norm;
  return f;
}

/// <x^p S_k(x)> over the Maxwellian, x = c^2 (exact Gauss-Laguerre with weight x^(1/2) e^-x).
double maxwell_moment(int p, int k) {
  const Rule r = fixed_rule(gsl_integration_fixed_laguerre, p + k + 2, 0.0, 1.0, 0.5);
  double s = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < r.x.size(); ++i) {
    s += r.w[i] * std::pow(r.x[i], p) * sonine_polynomial(k, r.x[i]);
    norm += r.w[i];
  }
  return s / norm;
}

double quadratic(const std::vector<double>& m, int K, int p, const std::vector<double>& A, bool linear) {
  const int B = K + 1;
  const double* mp = &m[static_cast<std::size_t>(p - 1) * B * B];
  double s = mp[0];
  for (int i = 1; i < B; ++i) s += A[i] * (mp[i * B] + mp[i]);
  if (!linear)
    for (int i = 1; i < B; ++i)
      for (int j = 1; j < B; ++j) s += A[i] * A[j] * mp[i * B + j];
  return s;
}

}  // namespace

double sonine_collision_moment(double alpha, int p, const std::vector<double>& a) {
  const int K = static_cast<int>(a.size()) + 1;
  if (K < 2 || p < 2 || p > 2 * K || p % 2 != 0)
    throw std::invalid_argument("sonine_collision_moment: need 2 <= p <= 2K, p even, K = a.size() + 1 >= 2");
  const auto m = moment_forms(alpha, K);
  std::vector<double> A(K + 1, 0.0);
  A[0] = 1.0;
  for (int k = 2; k <= K; ++k) A[k] = a[k - 2];
  return quadratic(m, K, p / 2, A, false);
}

OneSpeciesSonine one_species_hcs_sonine(double alpha, int order, bool linear) {
  if (!(alpha >= 0.0 && alpha < 1.0)) throw std::invalid_argument("one_species_hcs_sonine: need 0 <= alpha < 1");
  if (order < 2 || order > 6) throw std::invalid_argument("one_species_hcs_sonine: need 2 <= order <= 6");
  const int K = order, B = K + 1, n = K - 1;
  const auto m = moment_forms(alpha, K);
  // <c^2p> = sum_k A_k <x^p S_k>: the HCS relation mu_2p = (2p/3) mu_2 <c^2p>, p = 2..K.
  std::vector<double> mom(static_cast<std::size_t>(K + 1) * B);
  for (int p = 0; p <= K; ++p)
    for (int k = 0; k < B; ++k) mom[p * B + k] = maxwell_moment(p, k);
  std::vector<double> A(B, 0.0);
  A[0] = 1.0;
  auto residual = [&](const std::vector<double>& Av, bool lin, std::vector<double>& out) {
    const double m2 = quadratic(m, K, 1, Av, lin);
    const double m2_0 = m[0];
    for (int e = 0; e < n; ++e) {
      const int p = e + 2;
      double cp = 0.0, cp_lin = mom[p * B];
      for (int k = 0; k < B; ++k) cp += Av[k] * mom[p * B + k];
      const double rhs = lin ? (2.0 * p / 3.0) * (m2 * cp_lin + m2_0 * (cp - cp_lin))
                             : (2.0 * p / 3.0) * m2 * cp;
      out[e] = quadratic(m, K, p, Av, lin) - rhs;
    }
  };
  // Linear first (one Newton step is exact), then the full quadratic system if asked.
  const int passes = linear ? 1 : 2;
  for (int pass = 0; pass < passes; ++pass) {
    const bool lin = pass == 0;
    for (int it = 0; it < 60; ++it) {
      std::vector<double> f(n), fp(n), J(static_cast<std::size_t>(n) * n);
      residual(A, lin, f);
      for (int v = 0; v < n; ++v) {
        const double step = 1e-6;
        std::vector<double> Ap = A;
        Ap[v + 2] += step;
        residual(Ap, lin, fp);
        for (int e = 0; e < n; ++e) J[e * n + v] = (fp[e] - f[e]) / step;
      }
      gsl_matrix_view Jm = gsl_matrix_view_array(J.data(), n, n);
      gsl_vector_view fv = gsl_vector_view_array(f.data(), n);
      gsl_vector* dx = gsl_vector_alloc(n);
      gsl_permutation* perm = gsl_permutation_alloc(n);
      int sign = 0;
      gsl_linalg_LU_decomp(&Jm.matrix, perm, &sign);
      const int status = gsl_linalg_LU_solve(&Jm.matrix, perm, &fv.vector, dx);
      double change = 0.0;
      for (int v = 0; v < n; ++v) {
        A[v + 2] -= gsl_vector_get(dx, v);
        change = std::max(change, std::abs(gsl_vector_get(dx, v)));
      }
      gsl_vector_free(dx);
      gsl_permutation_free(perm);
      if (status != 0) throw std::runtime_error("one_species_hcs_sonine: singular Jacobian");
      if (change < 1e-13) break;
      if (it == 59) throw std::runtime_error("one_species_hcs_sonine: Newton did not converge");
    }
  }
  for (int k = 2; k < B; ++k)
    if (!std::isfinite(A[k])) throw std::runtime_error("one_species_hcs_sonine: no solution");
  OneSpeciesSonine out;
  out.order = K;
  out.a.assign(A.begin() + 2, A.end());
  out.cumulant_c = 2.0 * A[2];
  out.cooling_factor = quadratic(m, K, 1, A, linear) / m[0];
  const auto f = frequency_form(K);
  double nu = 1.0;
  for (int i = 1; i < B; ++i) nu += A[i] * (f[i * B] + f[i]);
  if (!linear)
    for (int i = 1; i < B; ++i)
      for (int j = 1; j < B; ++j) nu += A[i] * A[j] * f[i * B + j];
  out.collision_factor = nu;
  return out;
}

CumulantBracket sonine_cumulant_bracket(double alpha) {
  const auto s4 = one_species_hcs_sonine(alpha, 4), s5 = one_species_hcs_sonine(alpha, 5);
  return {0.5 * (s4.cumulant_c + s5.cumulant_c), 0.5 * std::abs(s4.cumulant_c - s5.cumulant_c),
          0.5 * (s4.cooling_factor + s5.cooling_factor), 0.5 * std::abs(s4.cooling_factor - s5.cooling_factor)};
}

}  // namespace gdsmc::theory
