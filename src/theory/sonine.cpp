// HCS of a binary granular mixture in the first Sonine approximation: see sonine.hpp.
#include "theory/sonine.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace gdsmc::theory {

namespace {

constexpr double pi = std::numbers::pi;

/// Search range and resolution of the root of Montanero and Garzo 2002, eq. (45), \ref son_binary_gamma "docs/sonine.md" (sonine.hpp, step 3).
constexpr int gamma_decade_min = -4;  // gamma >= 1e-4
constexpr int gamma_decade_max = 4;   // gamma <= 1e4
constexpr int grid_points_per_decade = 40;
constexpr double root_relative_width = 1e-14;
constexpr int root_max_iterations = 200;

void require_binary(const species::Mixture& mix, const char* caller) {
  if (mix.size() != 2)
    throw std::invalid_argument(std::string(caller) +
                                ": the first Sonine HCS theory is for 2 species, got " +
                                std::to_string(mix.size()));
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  for (std::size_t k = 0; k < 2; ++k)
    if (!positive(mix.mass[k]) || !positive(mix.diameter[k]) || !positive(mix.number_density[k]) ||
        !positive(mix.pair_correlation(k, k)))
      throw std::invalid_argument(std::string(caller) +
                                  ": masses, diameters, number densities and chi must be positive "
                                  "and finite");
  if (!positive(mix.pair_correlation(0, 1)))
    throw std::invalid_argument(std::string(caller) + ": chi_12 must be positive and finite");
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t j = 0; j < 2; ++j)
      if (!(mix.restitution(k, j) >= 0.0 && mix.restitution(k, j) <= 1.0))
        throw std::invalid_argument(std::string(caller) + ": restitution must lie in [0, 1]");
  if (mix.restitution(0, 1) != mix.restitution(1, 0))
    throw std::invalid_argument(std::string(caller) + ": alpha_12 != alpha_21");
}

void require_gamma(double gamma, const char* caller) {
  if (!(gamma > 0.0) || !std::isfinite(gamma))
    throw std::invalid_argument(std::string(caller) +
                                ": gamma = T1/T2 must be positive and finite");
}

/// Inputs of Montanero and Garzo 2002, eqs. (39)-(44), \ref son_binary_coefficients "docs/sonine.md" written for species i with partner j (i = 1, j = 2 as printed;
/// species 2 by interchanging 1 <-> 2 and eta -> 1/eta, Montanero and Garzo 2002, after eq. (44), \ref son_binary "docs/sonine.md").
struct SpeciesInput {
  double self_weight;   ///< \ref son_binary_coefficients "docs/sonine.md" s = x_i chi_ii (sigma_i/sigma_12)^2
  double cross_weight;  ///< \ref son_binary_coefficients "docs/sonine.md" c = x_j chi_ij
  double mu_ji;         ///< mu_ji = m_j/(m_i + m_j) (mu_21 for species 1)
  double alpha_ii;
  double alpha_ij;
  double lambda_i;
  double lambda_j;
};

struct SpeciesCoefficients {
  double zeta0, zeta_self, zeta_cross;     ///< zeta_i^(0), zeta_ii^(1), zeta_ij^(1)
  double omega0, omega_self, omega_cross;  ///< Omega_i^(0), Omega_ii^(1), Omega_ij^(1)
};

/// \ref son_binary_coefficients "docs/sonine.md" (Montanero and Garzo 2002, eqs. (39)-(44), box glyph = Omega): the sum of the self (i-i) and cross (i-j)
/// collision terms of sonine.hpp's sonine_self_terms and sonine_cross_terms.
SpeciesCoefficients species_coefficients(const SpeciesInput& in) {
  const SonineTerms self = sonine_self_terms(in.self_weight, in.alpha_ii, in.lambda_i);
  const SonineTerms cross =
      sonine_cross_terms(in.cross_weight, in.mu_ji, in.alpha_ij, in.lambda_i, in.lambda_j);
  SpeciesCoefficients out{};
  out.zeta0 = self.zeta0 + cross.zeta0;
  out.zeta_self = self.zeta_self + cross.zeta_self;
  out.zeta_cross = cross.zeta_partner;
  out.omega0 = self.omega0 + cross.omega0;
  out.omega_self = self.omega_self + cross.omega_self;
  out.omega_cross = cross.omega_partner;
  return out;
}

/// The coefficients A, B, D, E, F, G of Montanero and Garzo 2002, eqs. (33)-(38), \ref son_binary_cumulants "docs/sonine.md" and the determinant of the system
/// B c1 + D c2 = A, F c1 + G c2 = E (whose Cramer solution is eqs 31-32).
struct LinearSystem {
  double A, B, D, E, F, G;
  double determinant() const { return B * G - D * F; }
};

LinearSystem linear_system(const SonineCoefficients& k) {
  const double w1 = 15.0 / (2.0 * k.lambda[0] * k.lambda[0]);  // 15/(2 lambda_1^2)
  const double w2 = 15.0 / (2.0 * k.lambda[1] * k.lambda[1]);  // 15/(2 lambda_2^2)
  LinearSystem sys{};
  sys.A = -w1 * k.zeta0[0] - k.omega0[0];                            // Montanero and Garzo 2002, eq. (33), \ref son_binary_cumulants "docs/sonine.md"
  sys.B = w1 * (k.zeta1[0][0] + 0.5 * k.zeta0[0]) + k.omega1[0][0];  // Montanero and Garzo 2002, eq. (34), \ref son_binary_cumulants "docs/sonine.md"
  sys.D = w1 * k.zeta1[0][1] + k.omega1[0][1];                       // Montanero and Garzo 2002, eq. (35), \ref son_binary_cumulants "docs/sonine.md"
  sys.E = -w2 * k.zeta0[1] - k.omega0[1];                            // Montanero and Garzo 2002, eq. (36), \ref son_binary_cumulants "docs/sonine.md"
  sys.F = w2 * k.zeta1[1][0] + k.omega1[1][0];                       // Montanero and Garzo 2002, eq. (37), \ref son_binary_cumulants "docs/sonine.md"
  sys.G = w2 * (k.zeta1[1][1] + 0.5 * k.zeta0[1]) + k.omega1[1][1];  // Montanero and Garzo 2002, eq. (38), \ref son_binary_cumulants "docs/sonine.md"
  return sys;
}

SonineAtGamma solve_at(const SonineCoefficients& k) {
  const LinearSystem sys = linear_system(k);
  const double det = sys.determinant();
  if (det == 0.0 || !std::isfinite(det))
    throw std::runtime_error(
        "binary_sonine_at_gamma: the linearised fourth-moment system (Montanero and Garzo 2002, "
        "eqs. (31)-(38)) is singular");
  SonineAtGamma out{};
  out.c[0] = (sys.A * sys.G - sys.E * sys.D) / det;  // Montanero and Garzo 2002, eq. (31), \ref son_binary_cumulants "docs/sonine.md"
  out.c[1] = (sys.B * sys.E - sys.A * sys.F) / det;  // Montanero and Garzo 2002, eq. (32), \ref son_binary_cumulants "docs/sonine.md"
  // Montanero and Garzo 2002, eq. (45), \ref son_binary_gamma "docs/sonine.md": zeta_1* = zeta1^(0) + zeta11^(1) c1 + zeta12^(1) c2 (left side), zeta_2* =
  // zeta2^(0) + zeta22^(1) c2 + zeta21^(1) c1 (right side)
  for (int i = 0; i < 2; ++i)
    out.zeta[i] = k.zeta0[i] + k.zeta1[i][0] * out.c[0] + k.zeta1[i][1] * out.c[1];
  return out;
}

/// Temperatures relative to the mixture temperature: T1/T and T2/T (Montanero and Garzo 2002, eqs. (13)-(14), \ref son_binary "docs/sonine.md").
void partial_temperatures(const species::Mixture& mix, double gamma, double t_over_T[2]) {
  const double x1 = mix.mole_fraction(0);
  const double T_over_T2 = 1.0 + x1 * (gamma - 1.0);  // \ref son_binary "docs/sonine.md", Montanero and Garzo 2002, eq. (14)
  t_over_T[0] = gamma / T_over_T2;                    // Montanero and Garzo 2002, eq. (13), \ref son_binary "docs/sonine.md"
  t_over_T[1] = 1.0 / T_over_T2;                      // Montanero and Garzo 2002, eq. (14), \ref son_binary "docs/sonine.md"
}

/// zeta_1* - zeta_2* (Montanero and Garzo 2002, eq. (45), \ref son_binary_gamma "docs/sonine.md") for GSL. No exception may cross the C code of GSL, and a
/// non-finite value would make GSL's default error handler abort: a failure is recorded in the
/// context and reported as 0 (which ends the Brent iteration); the caller then throws.
struct RootContext {
  const species::Mixture* mix;
  bool failed = false;
};

double eq45_residual(double gamma, void* params) noexcept {
  auto* ctx = static_cast<RootContext*>(params);
  try {
    const SonineAtGamma s = solve_at(binary_sonine_coefficients(*ctx->mix, gamma));
    const double f = s.zeta[0] - s.zeta[1];
    if (std::isfinite(f)) return f;
  } catch (...) {
  }
  ctx->failed = true;
  return 0.0;
}

std::string format_gamma(double g) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", g);
  return buf;
}

struct SolverDeleter {
  void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
};

/// Refines a root of eq45_residual in [lo, hi] (signs differ) with Brent's method.
double refine_root(const species::Mixture& mix, double lo, double hi) {
  RootContext ctx{&mix};
  gsl_function fn{&eq45_residual, &ctx};
  const auto check = [&ctx, lo, hi]() {
    if (ctx.failed)
      throw std::runtime_error(
          "binary_hcs_first_sonine: zeta_1* - zeta_2* (Montanero and Garzo 2002, eq. (45), docs/sonine.md) is not finite between "
          "gamma = " + format_gamma(lo) + " and " + format_gamma(hi));
  };
  std::unique_ptr<gsl_root_fsolver, SolverDeleter> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  if (!solver) throw std::runtime_error("binary_hcs_first_sonine: gsl_root_fsolver_alloc failed");
  if (gsl_root_fsolver_set(solver.get(), &fn, lo, hi) != GSL_SUCCESS)
    throw std::runtime_error("binary_hcs_first_sonine: gsl_root_fsolver_set failed");
  for (int iter = 0; iter < root_max_iterations; ++iter) {
    if (gsl_root_fsolver_iterate(solver.get()) != GSL_SUCCESS)
      throw std::runtime_error("binary_hcs_first_sonine: gsl_root_fsolver_iterate failed");
    const double a = gsl_root_fsolver_x_lower(solver.get());
    const double b = gsl_root_fsolver_x_upper(solver.get());
    check();
    if (gsl_root_test_interval(a, b, 0.0, root_relative_width) == GSL_SUCCESS)
      return gsl_root_fsolver_root(solver.get());
  }
  throw std::runtime_error(
      "binary_hcs_first_sonine: Brent iteration for gamma (Montanero and Garzo 2002, eq. (45), docs/sonine.md) did "
      "not converge");
}

}  // namespace

SonineTerms sonine_self_terms(double weight, double alpha_ii, double lambda_i) {
  const double sw = weight;
  const double inelastic_ii = 1.0 - alpha_ii * alpha_ii;
  const double li_half = 1.0 / std::sqrt(lambda_i);              // lambda_i^(-1/2)
  const double li_5half = li_half * li_half * li_half * li_half * li_half;  // lambda_i^(-5/2)
  SonineTerms out{};
  // Montanero and Garzo 2002, eqs. (39), (40), (42), (43) (\ref son_binary_coefficients "docs/sonine.md"): the terms proportional to s
  out.zeta0 = (2.0 / 3.0) * std::sqrt(2.0 * pi) * sw * li_half * inelastic_ii;
  out.zeta_self = (1.0 / 8.0) * std::sqrt(pi / 2.0) * sw * li_half * inelastic_ii;
  out.zeta_partner = 0.0;
  out.omega0 = -std::sqrt(2.0 * pi) * li_5half * sw * (9.0 + 2.0 * alpha_ii * alpha_ii) *
               inelastic_ii / 2.0;
  out.omega_self = -std::sqrt(2.0 * pi) * li_5half * sw *
                   (1.0 + alpha_ii + (3.0 / 64.0) * (69.0 + 10.0 * alpha_ii * alpha_ii) * inelastic_ii);
  out.omega_partner = 0.0;
  return out;
}

SonineTerms sonine_cross_terms(double weight, double mu_ji, double alpha_ij, double lambda_i,
                               double lambda_j) {
  const double c = weight;
  const double mu = mu_ji;
  const double e = lambda_i / lambda_j;  // eta
  const double p = 1.0 + e;              // 1 + eta
  const double A = mu * (1.0 + alpha_ij);  // \ref son_binary_coefficients "docs/sonine.md": A = mu_21 (1 + alpha_12)
  const double Ap = A * p, Ap2 = Ap * Ap, Ap3 = Ap2 * Ap;
  const double lj_half = 1.0 / std::sqrt(lambda_j);  // lambda_j^(-1/2)
  const double li_half = 1.0 / std::sqrt(lambda_i);
  const double li_5half = li_half * li_half * li_half * li_half * li_half;  // lambda_i^(-5/2)
  const double cross = c * mu * (1.0 + alpha_ij);  // x_j chi_ij mu_ji (1 + alpha_ij)
  const double sqrt_pi = std::sqrt(pi);
  const double sqrt_p = std::sqrt(p), sqrt_e = std::sqrt(e);
  const double p_m15 = 1.0 / (p * sqrt_p), p_m25 = p_m15 / p, p_m05 = 1.0 / sqrt_p;

  SonineTerms out{};
  // Montanero and Garzo 2002, eq. (39), \ref son_binary_coefficients "docs/sonine.md" zeta1_0 (cross part)
  out.zeta0 = (4.0 / 3.0) * sqrt_pi * cross * (sqrt_p / sqrt_e) * lj_half * (2.0 - Ap);
  // Montanero and Garzo 2002, eq. (40), \ref son_binary_coefficients "docs/sonine.md" zeta11_1 (cross part)
  out.zeta_self = (1.0 / 12.0) * sqrt_pi * cross * p_m15 / sqrt_e * lj_half *
                  (2.0 * (3.0 + 4.0 * e) - 3.0 * Ap);
  // Montanero and Garzo 2002, eq. (41), \ref son_binary_coefficients "docs/sonine.md" zeta12_1; (p/e)^(-3/2) = e^(3/2) p^(-3/2)
  out.zeta_partner =
      -(1.0 / 12.0) * sqrt_pi * cross * (e * sqrt_e * p_m15) * lj_half * (2.0 + 3.0 * Ap);
  // Montanero and Garzo 2002, eq. (42), \ref son_binary_coefficients "docs/sonine.md" Omega1_0 (cross part)
  out.omega0 = std::sqrt(2.0 * pi) * li_5half * std::sqrt(2.0) * cross * p_m05 *
               (-2.0 * (6.0 + 5.0 * e) + Ap * (14.0 + 5.0 * e) - 8.0 * Ap2 + 2.0 * Ap3);
  // Montanero and Garzo 2002, eq. (43), \ref son_binary_coefficients "docs/sonine.md" Omega11_1 (cross part)
  out.omega_self = std::sqrt(2.0 * pi) * li_5half * (std::sqrt(2.0) / 16.0) * cross * p_m25 *
                   (-2.0 * (90.0 + 231.0 * e + 184.0 * e * e + 40.0 * e * e * e) +
                    3.0 * Ap * (70.0 + 117.0 * e + 44.0 * e * e) - 24.0 * Ap2 * (5.0 + 4.0 * e) +
                    30.0 * Ap3);
  // Montanero and Garzo 2002, eq. (44), \ref son_binary_coefficients "docs/sonine.md" Omega12_1
  out.omega_partner = (sqrt_pi / 8.0) * cross * li_5half * e * e * p_m25 *
                      (2.0 * (2.0 + 5.0 * e) + 3.0 * Ap * (2.0 + 5.0 * e) - 24.0 * Ap2 + 30.0 * Ap3);
  return out;
}

SonineCoefficients binary_sonine_coefficients(const species::Mixture& mix, double gamma) {
  require_binary(mix, "binary_sonine_coefficients");
  require_gamma(gamma, "binary_sonine_coefficients");
  const double x[2] = {mix.mole_fraction(0), mix.mole_fraction(1)};
  double t_over_T[2];
  partial_temperatures(mix, gamma, t_over_T);
  const double sigma_12 = mix.contact_distance(0, 1);
  const double alpha_12 = mix.restitution(0, 1);

  SonineCoefficients k{};
  // \ref son_binary "docs/sonine.md": lambda_1 = T/(T1 mu_21), lambda_2 = T/(T2 mu_12) (Montanero and Garzo 2002, after eq. (17))
  k.lambda[0] = 1.0 / (t_over_T[0] * mix.mass_fraction(1, 0));
  k.lambda[1] = 1.0 / (t_over_T[1] * mix.mass_fraction(0, 1));
  k.eta = k.lambda[0] / k.lambda[1];  // \ref son_binary "docs/sonine.md", = mu_12/(mu_21 gamma) (Montanero and Garzo 2002, after eq. (44))

  for (int i = 0; i < 2; ++i) {
    const int j = 1 - i;
    const double ratio = mix.diameter[i] / sigma_12;  // sigma_ii/sigma_12 (sigma_ii = sigma_i)
    SpeciesInput in{};
    in.self_weight = x[i] * mix.pair_correlation(i, i) * ratio * ratio;  // \ref son_binary_coefficients "docs/sonine.md" s
    in.cross_weight = x[j] * mix.pair_correlation(i, j);                 // \ref son_binary_coefficients "docs/sonine.md" c
    in.mu_ji = mix.mass_fraction(j, i);
    in.alpha_ii = mix.restitution(i, i);
    in.alpha_ij = alpha_12;
    in.lambda_i = k.lambda[i];
    in.lambda_j = k.lambda[j];
    // Montanero and Garzo 2002, after eq. (44), \ref son_binary "docs/sonine.md": species 2 by interchanging 1 <-> 2 and eta -> 1/eta (sonine_cross_terms
    // takes eta = lambda_i/lambda_j from its arguments)
    const SpeciesCoefficients sc = species_coefficients(in);
    k.zeta0[i] = sc.zeta0;
    k.zeta1[i][i] = sc.zeta_self;
    k.zeta1[i][j] = sc.zeta_cross;
    k.omega0[i] = sc.omega0;
    k.omega1[i][i] = sc.omega_self;
    k.omega1[i][j] = sc.omega_cross;
  }
  return k;
}

SonineAtGamma binary_sonine_at_gamma(const species::Mixture& mix, double gamma) {
  return solve_at(binary_sonine_coefficients(mix, gamma));
}

BinaryHcs binary_hcs_first_sonine(const species::Mixture& mix) {
  require_binary(mix, "binary_hcs_first_sonine");

  // Step 3 of sonine.hpp: tabulate f = zeta_1* - zeta_2* and det(BG - DF) on a log grid.
  const int points = (gamma_decade_max - gamma_decade_min) * grid_points_per_decade + 1;
  std::vector<double> grid(points), f(points), det(points);
  for (int p = 0; p < points; ++p) {
    // the exponent is exactly 0 at p = -gamma_decade_min * grid_points_per_decade: gamma = 1 is a
    // grid point (the root for elastic or mechanically equivalent species)
    grid[p] = std::pow(10.0, gamma_decade_min + static_cast<double>(p) / grid_points_per_decade);
    const SonineCoefficients k = binary_sonine_coefficients(mix, grid[p]);
    det[p] = linear_system(k).determinant();
    const SonineAtGamma s = solve_at(k);
    f[p] = s.zeta[0] - s.zeta[1];
    if (!std::isfinite(f[p]))
      throw std::runtime_error(
          "binary_hcs_first_sonine: zeta_1* - zeta_2* (Montanero and Garzo 2002, eq. (45), docs/sonine.md) is not finite at gamma = " +
          format_gamma(grid[p]));
  }

  // Roots: exact zeros on the grid, and sign changes of f not accompanied by a sign change of the
  // determinant (those are poles of c_i, not roots).
  std::vector<double> roots;
  for (int p = 0; p < points; ++p) {
    if (f[p] == 0.0) {
      roots.push_back(grid[p]);
      continue;
    }
    if (p + 1 < points && f[p + 1] != 0.0 && (f[p] < 0.0) != (f[p + 1] < 0.0) &&
        (det[p] < 0.0) == (det[p + 1] < 0.0))
      roots.push_back(refine_root(mix, grid[p], grid[p + 1]));
  }
  if (roots.size() != 1) {
    std::string msg =
        "binary_hcs_first_sonine: expected exactly one root of zeta_1* = zeta_2* (Montanero and Garzo 2002, eq. (45), docs/sonine.md) "
        "for " + format_gamma(std::pow(10.0, gamma_decade_min)) + " <= gamma <= " +
        format_gamma(std::pow(10.0, gamma_decade_max)) + ", found " + std::to_string(roots.size());
    for (double r : roots) msg += (r == roots.front() ? ": gamma = " : ", ") + format_gamma(r);
    throw std::runtime_error(msg);
  }

  const double gamma = roots.front();
  const SonineAtGamma s = binary_sonine_at_gamma(mix, gamma);
  double t_over_T[2];
  partial_temperatures(mix, gamma, t_over_T);
  const double x[2] = {mix.mole_fraction(0), mix.mole_fraction(1)};
  const double sigma_12 = mix.contact_distance(0, 1);

  BinaryHcs hcs{};
  hcs.temperature_ratio = gamma;
  hcs.sonine_c[0] = s.c[0];
  hcs.sonine_c[1] = s.c[1];
  // Montanero and Garzo 2002, eq. (11), \ref son_binary_gamma "docs/sonine.md": zeta = sum_i x_i (T_i/T) zeta_i (= zeta_1* = zeta_2* at the root of eq 45)
  hcs.cooling_rate = x[0] * t_over_T[0] * s.zeta[0] + x[1] * t_over_T[1] * s.zeta[1];
  for (int i = 0; i < 2; ++i) {
    double beta = 0.0;
    for (int j = 0; j < 2; ++j) {
      const double ratio = mix.contact_distance(i, j) / sigma_12;
      beta += x[j] * mix.pair_correlation(i, j) * ratio * ratio;
    }
    hcs.tail_beta[i] = pi * beta;  // Montanero and Garzo 2002, eq. (20), \ref son_tails "docs/sonine.md"
  }
  return hcs;
}

double tail_decay_rate(const BinaryHcs& hcs, int species) {
  if (species != 0 && species != 1)
    throw std::invalid_argument("tail_decay_rate: species must be 0 or 1, got " +
                                std::to_string(species));
  if (hcs.cooling_rate == 0.0) return std::numeric_limits<double>::infinity();  // elastic: no tail
  return 2.0 * hcs.tail_beta[species] / hcs.cooling_rate;  // Montanero and Garzo 2002, eqs. (21), (30); \ref son_tails "docs/sonine.md"
}

}  // namespace gdsmc::theory
