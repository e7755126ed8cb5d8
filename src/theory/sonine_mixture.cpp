// HCS of an s-species granular mixture in the first Sonine approximation: see sonine_mixture.hpp.
#include "theory/sonine_mixture.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "theory/theory.hpp"

namespace gdsmc::theory {

namespace {

constexpr int newton_max_iterations = 100;
constexpr std::size_t stagnation_window = 10;  // fail if max|F| has not halved in 10 iterations
constexpr double residual_tolerance = 1e-13;
constexpr double step_tolerance = 1e-15;
constexpr double jacobian_step = 1e-7;
constexpr double max_step = 1.0;  // largest change of ln(T_k/T) per Newton step

void require_mixture(const species::Mixture& mix, const char* caller) {
  const std::size_t s = mix.size();
  if (s == 0) throw std::invalid_argument(std::string(caller) + ": the mixture has no species");
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  for (std::size_t k = 0; k < s; ++k)
    if (!positive(mix.mass[k]) || !positive(mix.diameter[k]) || !positive(mix.number_density[k]))
      throw std::invalid_argument(std::string(caller) +
                                  ": masses, diameters and number densities must be positive "
                                  "and finite");
  for (std::size_t k = 0; k < s; ++k)
    for (std::size_t j = 0; j < s; ++j) {
      if (!positive(mix.pair_correlation(k, j)))
        throw std::invalid_argument(std::string(caller) + ": chi must be positive and finite");
      const double a = mix.restitution(k, j);
      if (!(a >= 0.0 && a <= 1.0))
        throw std::invalid_argument(std::string(caller) + ": restitution must lie in [0, 1]");
      if (j > k && a != mix.restitution(j, k))
        throw std::invalid_argument(std::string(caller) +
                                    ": the restitution matrix must be symmetric");
    }
}

/// The mixture in internal units: T = 1, masses in m_u with 1/m_u = (1/s) sum 1/m_k, diameters in
/// sigma_ref, densities in n (x_k). Then v_ref = sqrt(4 T/m_u) = 2 and the reduced rates of
/// sonine_mixture.hpp are the internal ones over 2 (zeta) and 32 (Omega).
struct Reduced {
  std::size_t s = 0;
  std::vector<double> m, sigma, x;
  std::vector<double> chi, alpha;  // s x s, row-major
  /// The white-noise steady state instead of the HCS (white_noise_first_sonine): the kicks' input
  /// m_k chi_k^2, relative to the last species' (`drive`).
  bool driven = false;
  std::vector<double> drive;
  explicit Reduced(const species::Mixture& mix) : s(mix.size()) {
    double inv_m = 0.0, mean_sigma = 0.0;
    for (std::size_t k = 0; k < s; ++k) {
      inv_m += 1.0 / mix.mass[k];
      mean_sigma += mix.diameter[k];
    }
    inv_m /= static_cast<double>(s);
    mean_sigma /= static_cast<double>(s);
    m.resize(s);
    sigma.resize(s);
    x.resize(s);
    chi.resize(s * s);
    alpha.resize(s * s);
    for (std::size_t k = 0; k < s; ++k) {
      m[k] = mix.mass[k] * inv_m;
      sigma[k] = mix.diameter[k] / mean_sigma;
      x[k] = mix.mole_fraction(k);
      for (std::size_t j = 0; j < s; ++j) {
        chi[k * s + j] = mix.pair_correlation(k, j);
        alpha[k * s + j] = mix.restitution(k, j);
      }
    }
  }
};

constexpr double zeta_unit = 2.0;   // v_ref in internal units
constexpr double omega_unit = 32.0;  // v_ref^5

/// Pair terms (sonine_mixture.hpp) in internal units.
SonineTerms pair_terms(const Reduced& r, std::size_t i, std::size_t j, double tau_i, double tau_j) {
  const std::size_t s = r.s;
  SonineTerms t{};
  double scale = 0.0, v0 = 0.0;
  if (i == j) {
    v0 = 2.0 / std::sqrt(r.m[i]);  // sqrt(4 T/m_i)
    t = sonine_self_terms(r.chi[i * s + i], r.alpha[i * s + i], 2.0 / tau_i);
    scale = r.x[i] * r.sigma[i] * r.sigma[i] * v0;
  } else {
    const double mi = r.m[i], mj = r.m[j];
    const double mu_ji = mj / (mi + mj), mu_ij = mi / (mi + mj);
    v0 = std::sqrt(2.0 * (mi + mj) / (mi * mj));
    t = sonine_cross_terms(r.chi[i * s + j], mu_ji, r.alpha[i * s + j], 1.0 / (tau_i * mu_ji),
                           1.0 / (tau_j * mu_ij));
    const double sij = 0.5 * (r.sigma[i] + r.sigma[j]);
    scale = r.x[j] * sij * sij * v0;
  }
  const double v02 = v0 * v0;
  const double omega_scale = scale * v02 * v02;
  t.zeta0 *= scale;
  t.zeta_self *= scale;
  t.zeta_partner *= scale;
  t.omega0 *= omega_scale;
  t.omega_self *= omega_scale;
  t.omega_partner *= omega_scale;
  return t;
}

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Everything at one tau: the pair table, the assembled rows and the c solution.
struct State {
  std::vector<double> tau;
  std::vector<SonineTerms> pairs;  // s x s: [i * s + j] = terms of species i with partner j
  VectorXd zeta0, omega0, W, b, c, zeta;
  MatrixXd Z, O, M;
  Eigen::PartialPivLU<MatrixXd> lu;
  bool ok = false;
};

/// Row i of Z, O and zeta0_i, Omega0_i from pair terms row (terms of species i with each partner).
void assemble_row(const Reduced& r, std::size_t i, const SonineTerms* row, double W_i,
                  double& zeta0, double& omega0, double* Zrow, double* Orow, double* Mrow,
                  double& b) {
  const std::size_t s = r.s;
  zeta0 = omega0 = 0.0;
  double z_ii = 0.0, o_ii = 0.0;
  for (std::size_t j = 0; j < s; ++j) {
    zeta0 += row[j].zeta0;
    omega0 += row[j].omega0;
    z_ii += row[j].zeta_self;
    o_ii += row[j].omega_self;
    Zrow[j] = row[j].zeta_partner;  // 0 for j = i
    Orow[j] = row[j].omega_partner;
  }
  Zrow[i] += z_ii;
  Orow[i] += o_ii;
  for (std::size_t j = 0; j < s; ++j) Mrow[j] = 2.0 * W_i * Zrow[j] + Orow[j];
  if (!r.driven) Mrow[i] += W_i * zeta0;  // the HCS's -2 zeta_i <v^4>_i holds <v^4>_i = W_i (1 + c_i/2)
  b = -2.0 * W_i * zeta0 - omega0;
}

double weight_W(const Reduced& r, std::size_t i, double tau_i) {
  const double t = tau_i / r.m[i];
  return 15.0 * t * t;  // <v^4>_i = W_i (1 + c_i/2)
}

State evaluate(const Reduced& r, const std::vector<double>& tau) {
  const std::size_t s = r.s;
  State st;
  st.tau = tau;
  st.pairs.resize(s * s);
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j) st.pairs[i * s + j] = pair_terms(r, i, j, tau[i], tau[j]);
  st.zeta0.resize(s);
  st.omega0.resize(s);
  st.W.resize(s);
  st.b.resize(s);
  // row-major scratch, copied into the (column-major) Eigen matrices
  std::vector<double> Zr(s), Or(s), Mr(s);
  st.Z.resize(s, s);
  st.O.resize(s, s);
  st.M.resize(s, s);
  for (std::size_t i = 0; i < s; ++i) {
    st.W(i) = weight_W(r, i, tau[i]);
    assemble_row(r, i, &st.pairs[i * s], st.W(i), st.zeta0(i), st.omega0(i), Zr.data(), Or.data(),
                 Mr.data(), st.b(i));
    for (std::size_t j = 0; j < s; ++j) {
      st.Z(i, j) = Zr[j];
      st.O(i, j) = Or[j];
      st.M(i, j) = Mr[j];
    }
  }
  st.lu.compute(st.M);
  st.c = st.lu.solve(st.b);
  st.zeta = st.zeta0 + st.Z * st.c;
  // a singular (or nearly so) c system shows as a large residual of M c = b or non-finite c's
  st.ok = st.c.allFinite() && st.zeta.allFinite();
  if (st.ok) {
    const double res = (st.M * st.c - st.b).cwiseAbs().maxCoeff();
    const double size = st.M.cwiseAbs().maxCoeff() * st.c.cwiseAbs().maxCoeff() +
                        st.b.cwiseAbs().maxCoeff();
    st.ok = res <= 1e-8 * size;
  }
  return st;
}

/// The quantity equal for every species at the solution: zeta_k (HCS), or zeta_k T_k/(m_k chi_k^2)
/// (the white noise: every species' kicks balance its collisions' loss).
double balanced(const Reduced& r, const State& st, std::size_t k) {
  return r.driven ? st.zeta(k) * st.tau[k] / r.drive[k] : st.zeta(k);
}

VectorXd residual(const Reduced& r, const State& st, double nu) {
  const std::size_t s = r.s;
  VectorXd F(s);
  for (std::size_t k = 0; k + 1 < s; ++k) F(k) = (balanced(r, st, k) - balanced(r, st, s - 1)) / nu;
  double norm = -1.0;
  for (std::size_t k = 0; k < s; ++k) norm += r.x[k] * st.tau[k];
  F(s - 1) = norm;
  return F;
}

/// d zeta/d u (u = ln tau), s x s, by the scheme of sonine_mixture.hpp (\ref sonmix_solve).
MatrixXd zeta_jacobian(const Reduced& r, const State& st) {
  const std::size_t s = r.s;
  const double h = jacobian_step;
  MatrixXd R(s, s), Dz(s, s);
  std::vector<SonineTerms> row(s);
  std::vector<double> Zr(s), Or(s), Mr(s);
  for (std::size_t k = 0; k < s; ++k) {
    const double tau_k = st.tau[k] * std::exp(h);
    // row k: all pairs (k, j)
    for (std::size_t j = 0; j < s; ++j)
      row[j] = pair_terms(r, k, j, tau_k, j == k ? tau_k : st.tau[j]);
    double z0 = 0.0, o0 = 0.0, bk = 0.0;
    assemble_row(r, k, row.data(), weight_W(r, k, tau_k), z0, o0, Zr.data(), Or.data(), Mr.data(),
                 bk);
    double rk = bk - st.b(k), dzk = z0 - st.zeta0(k);
    for (std::size_t j = 0; j < s; ++j) {
      rk -= (Mr[j] - st.M(k, j)) * st.c(j);
      dzk += (Zr[j] - st.Z(k, j)) * st.c(j);
    }
    R(k, k) = rk / h;
    Dz(k, k) = dzk / h;
    // rows i != k: only the pair (i, k) changes
    for (std::size_t i = 0; i < s; ++i) {
      if (i == k) continue;
      const SonineTerms& old = st.pairs[i * s + k];
      const SonineTerms nw = pair_terms(r, i, k, st.tau[i], tau_k);
      const double W = st.W(i);
      const double d_z0 = nw.zeta0 - old.zeta0, d_o0 = nw.omega0 - old.omega0;
      const double d_zii = nw.zeta_self - old.zeta_self, d_oii = nw.omega_self - old.omega_self;
      const double d_zik = nw.zeta_partner - old.zeta_partner;
      const double d_oik = nw.omega_partner - old.omega_partner;
      const double d_Mii = 2.0 * W * d_zii + d_oii + (r.driven ? 0.0 : W * d_z0);
      const double d_Mik = 2.0 * W * d_zik + d_oik;
      const double d_b = -2.0 * W * d_z0 - d_o0;
      R(i, k) = (d_b - d_Mii * st.c(i) - d_Mik * st.c(k)) / h;
      Dz(i, k) = (d_z0 + d_zii * st.c(i) + d_zik * st.c(k)) / h;
    }
  }
  const MatrixXd dC = st.lu.solve(R);  // dc/du
  return Dz + st.Z * dC;
}

}  // namespace

double hcs_rate_unit(const species::Mixture& mix) {
  require_mixture(mix, "hcs_rate_unit");
  double inv_m = 0.0, sigma = 0.0;
  for (std::size_t k = 0; k < mix.size(); ++k) {
    inv_m += 1.0 / mix.mass[k];
    sigma += mix.diameter[k];
  }
  const double s = static_cast<double>(mix.size());
  sigma /= s;
  return mix.total_density() * sigma * sigma * std::sqrt(4.0 * inv_m / s);
}

SonineTerms hcs_pair_terms(const species::Mixture& mix, std::size_t i, std::size_t j, double tau_i,
                           double tau_j) {
  require_mixture(mix, "hcs_pair_terms");
  if (i >= mix.size() || j >= mix.size())
    throw std::invalid_argument("hcs_pair_terms: species index out of range");
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(tau_i) || !positive(tau_j))
    throw std::invalid_argument("hcs_pair_terms: T_k/T must be positive and finite");
  SonineTerms t = pair_terms(Reduced(mix), i, j, tau_i, tau_j);
  t.zeta0 /= zeta_unit;
  t.zeta_self /= zeta_unit;
  t.zeta_partner /= zeta_unit;
  t.omega0 /= omega_unit;
  t.omega_self /= omega_unit;
  t.omega_partner /= omega_unit;
  return t;
}

double hcs_maxwellian_cooling_rate_reduced(const species::Mixture& mix,
                                           const std::vector<double>& tau) {
  require_mixture(mix, "hcs_maxwellian_cooling_rate_reduced");
  if (tau.size() != mix.size())
    throw std::invalid_argument("hcs_maxwellian_cooling_rate_reduced: one T_k/T per species");
  const Reduced r(mix);
  double z = 0.0;
  for (std::size_t i = 0; i < r.s; ++i)
    for (std::size_t j = 0; j < r.s; ++j)
      z += r.x[i] * tau[i] * pair_terms(r, i, j, tau[i], tau[j]).zeta0;
  return z / zeta_unit;
}

std::vector<double> maxwellian_temperature_over_mean(const species::Mixture& mix) {
  if (mix.size() == 1) return {1.0};
  std::vector<double> t = asymptotic_temperature_ratios(mix);
  double mean = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) mean += mix.mole_fraction(k) * t[k];
  for (double& v : t) v /= mean;
  return t;
}

namespace {

/// Newton's method of sonine_mixture.hpp (\ref sonmix_solve) from `start`; `iterations` returns
/// the number of Newton steps taken.
State newton(const Reduced& r, double nu, const std::vector<double>& start, int& iterations) {
  const std::size_t s = r.s;
  const char* what = r.driven ? "white_noise_first_sonine" : "hcs_first_sonine";
  State st = evaluate(r, start);
  if (!st.ok)
    throw std::runtime_error(std::string(what) +
                             ": the linearised fourth-moment system is singular at the starting "
                             "temperature ratios");
  iterations = 0;
  if (s == 1) return st;
  VectorXd F = residual(r, st, nu);
  std::vector<double> history;  // max|F| per iteration
  for (; iterations < newton_max_iterations; ++iterations) {
    const double fnorm = F.cwiseAbs().maxCoeff();
    history.push_back(fnorm);
    if (history.size() > stagnation_window &&
        fnorm > 0.5 * history[history.size() - 1 - stagnation_window])
      throw std::runtime_error(
          std::string(what) + ": Newton's method stagnates at max |F| = " + std::to_string(fnorm) +
          " after " + std::to_string(iterations) +
          " iterations (the first-Sonine equations may have no solution near the Maxwellian ratios)");
    const bool last = fnorm < residual_tolerance;  // one more full step once the tolerance is met
    const MatrixXd Jz = zeta_jacobian(r, st);
    MatrixXd Jb = Jz;  // d balanced(k)/d u_j
    if (r.driven)
      for (std::size_t k = 0; k < s; ++k) {
        Jb.row(k) *= st.tau[k] / r.drive[k];
        Jb(k, k) += st.zeta(k) * st.tau[k] / r.drive[k];
      }
    MatrixXd J(s, s);
    for (std::size_t k = 0; k + 1 < s; ++k) J.row(k) = (Jb.row(k) - Jb.row(s - 1)) / nu;
    for (std::size_t k = 0; k < s; ++k) J(s - 1, k) = r.x[k] * st.tau[k];
    VectorXd du = J.partialPivLu().solve(-F);
    if (!du.allFinite()) throw std::runtime_error(std::string(what) + ": singular Newton matrix");
    const double big = du.cwiseAbs().maxCoeff();
    if (big > max_step) du *= max_step / big;
    if (last) {
      std::vector<double> t(s);
      for (std::size_t k = 0; k < s; ++k) t[k] = st.tau[k] * std::exp(du(k));
      State trial = evaluate(r, t);
      if (trial.ok) {
        const VectorXd Ft = residual(r, trial, nu);
        if (Ft.allFinite() && Ft.cwiseAbs().maxCoeff() <= fnorm) st = std::move(trial);
      }
      ++iterations;
      return st;
    }
    double lambda = 1.0;
    bool accepted = false;
    for (int ls = 0; ls < 40; ++ls, lambda *= 0.5) {
      std::vector<double> t(s);
      for (std::size_t k = 0; k < s; ++k) t[k] = st.tau[k] * std::exp(lambda * du(k));
      State trial = evaluate(r, t);
      if (!trial.ok) continue;
      const VectorXd Ft = residual(r, trial, nu);
      if (Ft.allFinite() && Ft.cwiseAbs().maxCoeff() < (1.0 - 1e-4 * lambda) * fnorm) {
        st = std::move(trial);
        F = Ft;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      if (fnorm < 1e-10) return st;  // round-off level already
      throw std::runtime_error(std::string(what) + ": Newton line search failed (max |F| = " +
                               std::to_string(fnorm) + ")");
    }
    if (lambda * du.cwiseAbs().maxCoeff() < step_tolerance) {
      ++iterations;
      return st;
    }
  }
  throw std::runtime_error(std::string(what) + ": Newton's method did not converge in " +
                           std::to_string(newton_max_iterations) + " iterations");
}



/// The collision-frequency scale of the residual: sum_ij x_i x_j chi_ij (sigma_ij/sigma_ref)^2 v0_ij/(v_ref/2).
double frequency_scale(const Reduced& r) {
  const std::size_t s = r.s;
  double nu = 0.0;
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j) {
      const double mi = r.m[i], mj = r.m[j], sij = 0.5 * (r.sigma[i] + r.sigma[j]);
      nu += r.x[i] * r.x[j] * r.chi[i * s + j] * sij * sij * std::sqrt(2.0 * (mi + mj) / (mi * mj));
    }
  return nu;
}

/// Temperatures in any normalisation as T_k/T (sum_k x_k T_k/T = 1).
std::vector<double> over_mean(const Reduced& r, std::vector<double> tau) {
  double mean = 0.0;
  for (std::size_t k = 0; k < r.s; ++k) mean += r.x[k] * tau[k];
  for (double& t : tau) t /= mean;
  return tau;
}

}  // namespace

HcsFirstSonine hcs_first_sonine(const species::Mixture& mix,
                                const std::vector<double>& maxwellian_start) {
  require_mixture(mix, "hcs_first_sonine");
  const std::size_t s = mix.size();
  if (s > max_hcs_species)
    throw std::invalid_argument(
        "hcs_first_sonine: " + std::to_string(s) + " species exceed the limit of " +
        std::to_string(max_hcs_species) +
        " for the first-Sonine HCS (O(s^3) per Newton iteration); use the Maxwellian temperature "
        "ratios (asymptotic_temperature_ratios) instead");
  if (!maxwellian_start.empty() && maxwellian_start.size() != s)
    throw std::invalid_argument("hcs_first_sonine: the start needs one T_k/T per species");
  const Reduced r(mix);
  const double nu = frequency_scale(r);

  // Start: the Maxwellian ratios (equipartition for an elastic mixture, where they are exact).
  double alpha_min = 1.0;
  for (double a : r.alpha) alpha_min = std::min(alpha_min, a);
  std::vector<double> tau(s, 1.0);
  if (!maxwellian_start.empty()) {
    tau = over_mean(r, maxwellian_start);
  } else if (s > 1 && alpha_min < 1.0) {
    tau = maxwellian_temperature_over_mean(mix);  // Newton on the fixed point of \ref haff_mixture_odes "docs/haff-and-mixtures.md" (theory.hpp)
  }
  HcsFirstSonine out;
  const State st = newton(r, nu, tau, out.newton_iterations);
  out.temperature_over_mean = st.tau;
  out.sonine_c.assign(st.c.data(), st.c.data() + s);
  double z = 0.0;
  for (std::size_t k = 0; k < s; ++k) z += r.x[k] * st.tau[k] * st.zeta(k);  // Montanero and Garzo 2002, eq. (11), \ref son_binary_gamma "docs/sonine.md"
  out.cooling_rate_reduced = z / zeta_unit;
  return out;
}

DrivenFirstSonine white_noise_first_sonine(const species::Mixture& mix, const std::vector<double>& strength,
                                           const std::vector<double>& maxwellian_start) {
  require_mixture(mix, "white_noise_first_sonine");
  const std::size_t s = mix.size();
  if (s > max_hcs_species)
    throw std::invalid_argument("white_noise_first_sonine: " + std::to_string(s) + " species exceed the limit of " +
                                std::to_string(max_hcs_species));
  if (strength.size() != s) throw std::invalid_argument("white_noise_first_sonine: one noise strength per species");
  for (double c : strength)
    if (!(c > 0.0) || !std::isfinite(c))
      throw std::invalid_argument("white_noise_first_sonine: noise strengths must be positive and finite");
  if (!maxwellian_start.empty() && maxwellian_start.size() != s)
    throw std::invalid_argument("white_noise_first_sonine: the start needs one temperature per species");
  Reduced r(mix);
  if (std::all_of(r.alpha.begin(), r.alpha.end(), [](double a) { return a == 1.0; }))
    throw std::invalid_argument("white_noise_first_sonine: no steady state (the collisions lose no energy)");
  r.driven = true;
  r.drive.resize(s);
  for (std::size_t k = 0; k < s; ++k) r.drive[k] = mix.mass[k] * strength[k] / (mix.mass[s - 1] * strength[s - 1]);
  DrivenFirstSonine out;
  const State st = newton(r, frequency_scale(r), maxwellian_start.empty() ? std::vector<double>(s, 1.0)
                                                                          : over_mean(r, maxwellian_start),
                          out.newton_iterations);
  // m_k chi_k^2 = zeta_k T_k for every k (\ref sonmix_driven): T from the last species'
  const double zeta_last = st.zeta(static_cast<Eigen::Index>(s - 1)) / zeta_unit;
  if (!(zeta_last > 0.0))
    throw std::runtime_error("white_noise_first_sonine: no steady state (a species' Sonine cooling rate is not positive)");
  const double temperature =
      std::pow(mix.mass[s - 1] * strength[s - 1] / (zeta_last * hcs_rate_unit(mix) * st.tau[s - 1]), 2.0 / 3.0);
  out.temperature_over_mean = st.tau;
  for (double t : st.tau) out.temperature.push_back(t * temperature);
  out.sonine_c.assign(st.c.data(), st.c.data() + s);
  return out;
}

}  // namespace gdsmc::theory
