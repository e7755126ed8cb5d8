// Rough spheres of one species: the Maxwellian approximation and the Sonine theory (rough.hpp;
// \ref rough_maxwellian and \ref rough_sonine "docs/rough-spheres.md").
#include "theory/rough.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Dense>

namespace gdsmc::theory::rough {

Coefficients coefficients(double alpha, double beta, double kappa) {
  // Luding, Huthmann, McNamara and Zippelius 1998 (3D); \ref rough_maxwellian "docs/rough-spheres.md"
  const double eta = kappa * (1.0 + beta) / (2.0 * (1.0 + kappa));
  return {0.25 * (1.0 - alpha * alpha) + eta * (1.0 - eta), eta * eta / kappa, eta / kappa * (1.0 - eta / kappa)};
}

double frequency_unit(const species::Mixture& mix) {
  // nu = 4 n sigma^2 chi sqrt(pi T_tr/m) (\ref cm_pair_rate "docs/collision-model.md"), over sqrt(T_tr)
  const double sigma = mix.diameter[0];
  return 4.0 * mix.number_density[0] * sigma * sigma * mix.pair_correlation(0, 0) * std::sqrt(std::numbers::pi / mix.mass[0]);
}

CoolingState cooling_state(double alpha, double beta, double kappa) {
  const Coefficients k = coefficients(alpha, beta, kappa);
  if (k.b == 0.0) return {0.0, 4.0 / 3.0 * k.a};  // beta = -1: smooth, no energy reaches the rotation
  const double d = k.a - k.c;
  const double theta = (d + std::sqrt(d * d + 4.0 * k.b * k.b)) / (2.0 * k.b);
  return {theta, 4.0 / 3.0 * (k.a - k.b * theta)};
}

CoolingState driven_state(double alpha, double beta, double kappa) {
  const Coefficients k = coefficients(alpha, beta, kappa);
  if (k.b == 0.0) return {0.0, 4.0 / 3.0 * k.a};  // smooth: (1 - alpha^2)/3
  const double theta = k.b / k.c;
  return {theta, 4.0 / 3.0 * (k.a - k.b * theta)};
}

CollisionalMoments collisional_moments(double alpha, double beta, double kappa, double theta) {
  // Santos, Kremer and dos Santos 2011 (\ref rough_sonine "docs/rough-spheres.md"): the coefficients as
  // printed by scripts/derive_rough_moments.py, units m = sigma = T_tr = 1, per Maxwellian collision.
  const double h = kappa * (1.0 + beta) / (1.0 + kappa), q = 1.0 / kappa;
  CollisionalMoments m;
  // R_v2
  m.v2.zero = std::pow(alpha, 2) + std::pow(h, 2)*q*theta + std::pow(h, 2) - 2*h - 1;
  m.v2.a20 = -1.0/16.0*(-3*std::pow(alpha, 2) + std::pow(h, 2)*q*theta - 3*std::pow(h, 2) + 6*h + 3);
  m.v2.a02 = 0;
  m.v2.a11 = (1.0/4.0)*std::pow(h, 2)*q*theta;
  // R_w2
  m.w2.zero = 4*h*std::pow(q, 2)*(h*q*theta + h - 2*theta);
  m.w2.a20 = -1.0/4.0*h*std::pow(q, 2)*(h*q*theta - 3*h - 2*theta);
  m.w2.a02 = 0;
  m.w2.a11 = h*std::pow(q, 2)*theta*(h*q - 2);
  // R_v4
  m.v4.zero = 2*std::pow(alpha, 4) + 2*std::pow(alpha, 2)*std::pow(h, 2)*q*theta + 2*std::pow(alpha, 2)*std::pow(h, 2) - 4*std::pow(alpha, 2)*h + 7*std::pow(alpha, 2) + 2*std::pow(h, 4)*std::pow(q, 2)*std::pow(theta, 2) + 4*std::pow(h, 4)*q*theta + 2*std::pow(h, 4) - 8*std::pow(h, 3)*q*theta - 8*std::pow(h, 3) + 9*std::pow(h, 2)*q*theta + 17*std::pow(h, 2) - 18*h - 9;
  m.v4.a20 = -1.0/16.0*(-30*std::pow(alpha, 4) - 6*std::pow(alpha, 2)*std::pow(h, 2)*q*theta - 30*std::pow(alpha, 2)*std::pow(h, 2) + 60*std::pow(alpha, 2)*h - 177*std::pow(alpha, 2) - 64*alpha*h + 64*alpha + 2*std::pow(h, 4)*std::pow(q, 2)*std::pow(theta, 2) - 12*std::pow(h, 4)*q*theta - 30*std::pow(h, 4) + 24*std::pow(h, 3)*q*theta + 120*std::pow(h, 3) - 35*std::pow(h, 2)*q*theta - 327*std::pow(h, 2) + 414*h + 271);
  m.v4.a02 = std::pow(h, 4)*std::pow(q, 2)*std::pow(theta, 2);
  m.v4.a11 = (1.0/4.0)*std::pow(h, 2)*q*theta*(6*std::pow(alpha, 2) + 4*std::pow(h, 2)*q*theta + 12*std::pow(h, 2) - 24*h + 27);
  // R_w4
  m.w4.zero = 32*h*std::pow(q, 3)*(h*q*theta + h - 2*theta)*(std::pow(h, 2)*std::pow(q, 2)*theta + std::pow(h, 2)*q - 2*h*q*theta + 5*theta);
  m.w4.a20 = -2*h*std::pow(q, 3)*(std::pow(h, 3)*std::pow(q, 3)*std::pow(theta, 2) - 6*std::pow(h, 3)*std::pow(q, 2)*theta - 15*std::pow(h, 3)*q - 4*std::pow(h, 2)*std::pow(q, 2)*std::pow(theta, 2) + 12*std::pow(h, 2)*q*theta + 9*h*q*std::pow(theta, 2) - 15*h*theta - 10*std::pow(theta, 2));
  m.w4.a02 = 16*h*std::pow(q, 3)*std::pow(theta, 2)*(std::pow(h, 3)*std::pow(q, 3) - 4*std::pow(h, 2)*std::pow(q, 2) + 13*h*q - 20);
  m.w4.a11 = 8*h*std::pow(q, 3)*theta*(2*std::pow(h, 3)*std::pow(q, 3)*theta + 6*std::pow(h, 3)*std::pow(q, 2) - 8*std::pow(h, 2)*std::pow(q, 2)*theta - 12*std::pow(h, 2)*q + 18*h*q*theta + 15*h - 20*theta);
  // R_v2w2
  m.v2w2.zero = 2*q*(2*std::pow(alpha, 2)*std::pow(h, 2)*std::pow(q, 2)*theta + 2*std::pow(alpha, 2)*std::pow(h, 2)*q - 4*std::pow(alpha, 2)*h*q*theta + 6*std::pow(alpha, 2)*theta + 4*std::pow(h, 4)*std::pow(q, 3)*std::pow(theta, 2) + 8*std::pow(h, 4)*std::pow(q, 2)*theta + 4*std::pow(h, 4)*q - 8*std::pow(h, 3)*std::pow(q, 2)*std::pow(theta, 2) - 8*std::pow(h, 3)*std::pow(q, 2)*theta - 8*std::pow(h, 3)*q*theta - 8*std::pow(h, 3)*q + 5*std::pow(h, 2)*std::pow(q, 2)*theta + 8*std::pow(h, 2)*q*std::pow(theta, 2) + 12*std::pow(h, 2)*q*theta + 7*std::pow(h, 2)*q + 6*std::pow(h, 2)*theta - 10*h*q*theta - 12*h*theta - 6*theta);
  m.v2w2.a20 = -1.0/8.0*q*(-6*std::pow(alpha, 2)*std::pow(h, 2)*std::pow(q, 2)*theta - 30*std::pow(alpha, 2)*std::pow(h, 2)*q + 12*std::pow(alpha, 2)*h*q*theta - 18*std::pow(alpha, 2)*theta + 4*std::pow(h, 4)*std::pow(q, 3)*std::pow(theta, 2) - 24*std::pow(h, 4)*std::pow(q, 2)*theta - 60*std::pow(h, 4)*q - 8*std::pow(h, 3)*std::pow(q, 2)*std::pow(theta, 2) + 24*std::pow(h, 3)*std::pow(q, 2)*theta + 24*std::pow(h, 3)*q*theta + 120*std::pow(h, 3)*q - 23*std::pow(h, 2)*std::pow(q, 2)*theta + 8*std::pow(h, 2)*q*std::pow(theta, 2) - 36*std::pow(h, 2)*q*theta - 129*std::pow(h, 2)*q - 18*std::pow(h, 2)*theta + 46*h*q*theta + 36*h*theta + 18*theta);
  m.v2w2.a02 = 2*std::pow(h, 2)*std::pow(q, 2)*std::pow(theta, 2)*(2*std::pow(h, 2)*std::pow(q, 2) - 4*h*q + 5);
  m.v2w2.a11 = (1.0/2.0)*q*theta*(6*std::pow(alpha, 2)*std::pow(h, 2)*std::pow(q, 2) - 12*std::pow(alpha, 2)*h*q + 18*std::pow(alpha, 2) + 16*alpha*h*q - 24*alpha + 8*std::pow(h, 4)*std::pow(q, 3)*theta + 24*std::pow(h, 4)*std::pow(q, 2) - 16*std::pow(h, 3)*std::pow(q, 2)*theta - 24*std::pow(h, 3)*std::pow(q, 2) - 24*std::pow(h, 3)*q + 15*std::pow(h, 2)*std::pow(q, 2) + 16*std::pow(h, 2)*q*theta + 60*std::pow(h, 2)*q + 18*std::pow(h, 2) - 46*h*q - 60*h - 42);
  return m;
}

namespace {

/// The cumulant equations at a fixed theta (rough.hpp), M x = rhs, rows scaled to order one: the v^4, the
/// omega^4 (over <omega_x^2>^2) and the v^2 omega^2 (over <omega_x^2>) balance.
struct CumulantEquations {
  std::array<std::array<double, 3>, 3> m{};
  std::array<double, 3> rhs{};
};

CumulantEquations cumulant_equations(const CollisionalMoments& r, double theta, double kappa, bool driven) {
  const double r2 = 4.0 * theta / kappa;  // <omega_x^2> = T_rot/I, I = kappa/4
  const auto row = [](const MomentRate& x) { return std::array<double, 4>{x.zero, x.a20, x.a02, x.a11}; };
  const auto v2 = row(r.v2), w2 = row(r.w2), v4 = row(r.v4), w4 = row(r.w4), vw = row(r.v2w2);
  std::array<std::array<double, 4>, 3> e{};  // [constant, a20, a02, a11] of each balance
  for (std::size_t j = 0; j < 4; ++j) {
    if (driven) {  // R + the kicks' share, with 3 chi^2 = -R_v2
      e[0][j] = v4[j] - 10.0 * v2[j];
      e[1][j] = w4[j] / (r2 * r2);
      e[2][j] = vw[j] / r2 - 3.0 * v2[j];
    } else {  // d ln <psi> = the sum of d ln T over its temperatures, linearised in the cumulants
      e[0][j] = v4[j] - 10.0 * v2[j];
      e[1][j] = w4[j] / (r2 * r2) - 10.0 * w2[j] / r2;
      e[2][j] = vw[j] / r2 - 3.0 * v2[j] - 3.0 * w2[j] / r2;
    }
  }
  if (!driven) {  // the (1 + a) of <v^4>, <omega^4>, <v^2 omega^2> times the Maxwellian rates
    e[0][1] -= 10.0 * v2[0];
    e[1][2] -= 10.0 * w2[0] / r2;
    e[2][3] -= 3.0 * (v2[0] + w2[0] / r2);
  }
  CumulantEquations out;
  for (std::size_t i = 0; i < 3; ++i) {
    out.rhs[i] = -e[i][0];
    for (std::size_t j = 0; j < 3; ++j) out.m[i][j] = e[i][j + 1];
  }
  return out;
}

double determinant(const std::array<std::array<double, 3>, 3>& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/// The cumulants at theta, the theta equation's residual (the two temperatures' reduced rates differ by it;
/// white noise: R_w2/<omega_x^2>) and the determinant of the cumulant equations (a pole where it changes sign).
struct AtTheta {
  Cumulants x;
  double residual = 0.0, det = 0.0;
};

AtTheta at_theta(double alpha, double beta, double kappa, double theta, bool driven) {
  const CollisionalMoments r = collisional_moments(alpha, beta, kappa, theta);
  const CumulantEquations eq = cumulant_equations(r, theta, kappa, driven);
  AtTheta out;
  out.det = determinant(eq.m);
  std::array<double, 3> x{};
  for (std::size_t j = 0; j < 3; ++j) {  // Cramer's rule
    auto mj = eq.m;
    for (std::size_t i = 0; i < 3; ++i) mj[i][j] = eq.rhs[i];
    x[j] = determinant(mj) / out.det;
  }
  out.x = {x[0], x[1], x[2]};
  const double r2 = 4.0 * theta / kappa;
  out.residual = driven ? r.w2.at(out.x) / r2 : r.w2.at(out.x) / r2 - r.v2.at(out.x);
  return out;
}

/// theta between lo and hi (a sign change of the residual, no pole), by bisection in log theta.
double bisect(double alpha, double beta, double kappa, bool driven, double lo, double hi) {
  const bool low_positive = at_theta(alpha, beta, kappa, lo, driven).residual > 0.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = std::sqrt(lo * hi);
    if ((at_theta(alpha, beta, kappa, mid, driven).residual > 0.0) == low_positive) lo = mid;
    else hi = mid;
  }
  return std::sqrt(lo * hi);
}

SonineResult sonine_state(double alpha, double beta, double kappa, bool driven) {
  const double guess = driven ? driven_state(alpha, beta, kappa).theta : cooling_state(alpha, beta, kappa).theta;
  constexpr int kGrid = 1200;  // theta from guess/1e3 to guess*1e3, 200 points per decade
  std::optional<double> best;
  AtTheta previous = at_theta(alpha, beta, kappa, guess * 1e-3, driven);
  for (int i = 1; i <= kGrid; ++i) {
    const double lo = guess * std::pow(10.0, -3.0 + 6.0 * (i - 1) / kGrid), hi = guess * std::pow(10.0, -3.0 + 6.0 * i / kGrid);
    const AtTheta next = at_theta(alpha, beta, kappa, hi, driven);
    if ((previous.residual > 0.0) != (next.residual > 0.0) && (previous.det > 0.0) == (next.det > 0.0)) {
      const double theta = bisect(alpha, beta, kappa, driven, lo, hi);
      if (!best || std::abs(std::log(theta / guess)) < std::abs(std::log(*best / guess))) best = theta;
    }
    previous = next;
  }
  if (!best) return {std::nullopt, "no Sonine solution (no theta within 1e3 of the Maxwellian value solves its equation)"};
  const AtTheta s = at_theta(alpha, beta, kappa, *best, driven);
  const double largest = std::max({std::abs(s.x.a20), std::abs(s.x.a02), std::abs(s.x.a11)});
  if (!(largest <= 1.0)) {
    std::ostringstream why;
    why << "the Sonine approximation breaks down here: its cumulants (a20 " << s.x.a20 << ", a02 " << s.x.a02 << ", a11 "
        << s.x.a11 << ") are not small (a cumulant above 1)";
    return {std::nullopt, why.str()};
  }
  const CollisionalMoments r = collisional_moments(alpha, beta, kappa, *best);
  return {SonineState{*best, s.x, -r.v2.at(s.x) / 3.0}, {}};
}

}  // namespace

SonineResult sonine_cooling_state(double alpha, double beta, double kappa) {
  if (!(beta > -1.0)) return {std::nullopt, "smooth spheres (beta = -1): see the smooth-sphere Sonine theory"};
  return sonine_state(alpha, beta, kappa, false);
}

SonineResult sonine_driven_state(double alpha, double beta, double kappa) {
  if (beta > -1.0) return sonine_state(alpha, beta, kappa, true);
  // smooth spheres: the v^4 balance alone (van Noije and Ernst 1998; rough.hpp)
  const CollisionalMoments r = collisional_moments(alpha, -1.0, kappa, 0.0);
  const double a20 = -(r.v4.zero - 10.0 * r.v2.zero) / (r.v4.a20 - 10.0 * r.v2.a20);
  return {SonineState{0.0, {a20, 0.0, 0.0}, -(r.v2.zero + r.v2.a20 * a20) / 3.0}, {}};
}

EnergyRates pair_energy_rates(const species::Mixture& mix, std::size_t a, std::size_t b, const std::vector<double>& t,
                              const std::vector<double>& r) {
  // rough.hpp, \ref rough_mixtures "docs/rough-spheres.md": the Maxwellian average of the rule's energy changes
  const double ma = mix.mass[a], mb = mix.mass[b], ka = mix.moment_of_inertia[a], kb = mix.moment_of_inertia[b];
  const double mab = ma * mb / (ma + mb), mu_ba = mb / (ma + mb);
  const double k = 1.0 / (1.0 + mab / (ka * ma) + mab / (kb * mb));
  const double h = (1.0 + mix.roughness(a, b)) * k, alpha = mix.restitution(a, b);
  const double s2 = t[a] / ma + t[b] / mb, r2 = r[a] / (ka * ma) + r[b] / (kb * mb);
  const double unit = std::sqrt(8.0 * std::numbers::pi * s2);
  const double tr = ma * (-2.0 * mu_ba * t[a] / ma * (1.0 + alpha + h) +
                          mu_ba * mu_ba * ((1.0 + alpha) * (1.0 + alpha) * s2 + h * h * (s2 + r2)));
  const double rot = h * mab / (ka * ma) * (-2.0 * r[a] + mab * h * (s2 + r2));
  return {unit * tr, unit * rot};
}

namespace {

/// d(3 T_k/2)/dt and d(3 R_k/2)/dt of every species (rough.hpp).
std::pair<std::vector<double>, std::vector<double>> mixture_rates(const species::Mixture& mix, const std::vector<double>& t,
                                                                  const std::vector<double>& r) {
  const std::size_t n = mix.size();
  std::vector<double> dt(n, 0.0), dr(n, 0.0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const double sigma = 0.5 * (mix.diameter[a] + mix.diameter[b]);
      const double weight = mix.number_density[b] * sigma * sigma * mix.pair_correlation(a, b);
      const EnergyRates e = pair_energy_rates(mix, a, b, t, r);
      dt[a] += weight * e.translational;
      dr[a] += weight * e.rotational;
    }
  return {dt, dr};
}

/// dc/dt: collisions per particle per unit time of the Maxwellian mixture at T (rough.hpp).
double collision_rate(const species::Mixture& mix, const std::vector<double>& t) {
  double total = 0.0, rate = 0.0;
  for (double x : mix.number_density) total += x;
  for (std::size_t a = 0; a < mix.size(); ++a)
    for (std::size_t b = 0; b < mix.size(); ++b) {
      const double sigma = 0.5 * (mix.diameter[a] + mix.diameter[b]);
      rate += mix.number_density[a] / total * mix.number_density[b] * sigma * sigma * mix.pair_correlation(a, b) *
              std::sqrt(8.0 * std::numbers::pi * (t[a] / mix.mass[a] + t[b] / mix.mass[b]));
    }
  return rate;
}

/// d/dt (or d/dc) of (T_1..T_n, R_1..R_n, c or t).
std::vector<double> mixture_derivative(const species::Mixture& mix, const std::vector<double>& y, bool collision_driven) {
  const std::size_t n = mix.size();
  std::vector<double> t(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<double> r(y.begin() + static_cast<std::ptrdiff_t>(n), y.begin() + static_cast<std::ptrdiff_t>(2 * n));
  for (double& x : t) x = std::max(x, 0.0);
  for (double& x : r) x = std::max(x, 0.0);
  const auto [dt, dr] = mixture_rates(mix, t, r);
  const double nu = collision_rate(mix, t);
  const double scale = collision_driven ? 1.0 / nu : 1.0;
  std::vector<double> out(2 * n + 1);
  for (std::size_t k = 0; k < n; ++k) {
    out[k] = scale * dt[k] / 1.5;
    out[n + k] = scale * dr[k] / 1.5;
  }
  out[2 * n] = collision_driven ? 1.0 / nu : nu;
  return out;
}

}  // namespace

MixtureHistory integrate_mixture(const species::Mixture& mix, const std::vector<double>& translational,
                                 const std::vector<double>& rotational, const std::vector<double>& times, bool collision_driven) {
  if (!mix.rough() || translational.size() != mix.size() || rotational.size() != mix.size())
    throw std::invalid_argument("theory::rough::integrate_mixture: rough spheres, one temperature of each kind per species");
  const std::size_t n = mix.size(), m = 2 * n + 1;
  std::vector<double> y(translational);
  y.insert(y.end(), rotational.begin(), rotational.end());
  y.push_back(0.0);  // c or t
  const auto at = [&](const std::vector<double>& d, double f) {
    std::vector<double> z(y);
    for (std::size_t i = 0; i < m; ++i) z[i] += f * d[i];
    return z;
  };
  MixtureHistory h;
  double x = 0.0;              // t or c
  constexpr double kStep = 0.01;  // collisions per particle per step, as integrate()
  for (double target : times) {
    while (x < target) {
      const double nu = collision_rate(mix, y);
      const double step = std::min(collision_driven ? kStep : kStep / nu, target - x);
      const auto k1 = mixture_derivative(mix, y, collision_driven);
      const auto k2 = mixture_derivative(mix, at(k1, 0.5 * step), collision_driven);
      const auto k3 = mixture_derivative(mix, at(k2, 0.5 * step), collision_driven);
      const auto k4 = mixture_derivative(mix, at(k3, step), collision_driven);
      for (std::size_t i = 0; i < m; ++i) y[i] += step / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
      x = std::min(x + step, target);
    }
    h.time.push_back(collision_driven ? y[2 * n] : x);
    h.collisions_per_particle.push_back(collision_driven ? x : y[2 * n]);
    h.translational.emplace_back(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(n));
    h.rotational.emplace_back(y.begin() + static_cast<std::ptrdiff_t>(n), y.begin() + static_cast<std::ptrdiff_t>(2 * n));
  }
  return h;
}

namespace {

/// The reduced rates g_i = d ln y_i/dt of y = (T_1..T_n, R_1..R_n), each over the mean rate scale, and the
/// residuals g_i - g_1 (i = 2..2n) of the HCS (every temperature cools at one rate).
Eigen::VectorXd hcs_residuals(const species::Mixture& mix, const Eigen::VectorXd& log_y) {
  const std::size_t n = mix.size();
  std::vector<double> t(n), r(n);
  for (std::size_t k = 0; k < n; ++k) {
    t[k] = std::exp(log_y[static_cast<Eigen::Index>(k)]);
    r[k] = std::exp(log_y[static_cast<Eigen::Index>(n + k)]);
  }
  const auto [dt, dr] = mixture_rates(mix, t, r);
  const double scale = collision_rate(mix, t);  // the rates' natural unit
  Eigen::VectorXd g(static_cast<Eigen::Index>(2 * n - 1));
  const double g1 = dt[0] / (1.5 * t[0] * scale);
  for (std::size_t i = 1; i < 2 * n; ++i) {
    const double gi = i < n ? dt[i] / (1.5 * t[i] * scale) : dr[i - n] / (1.5 * r[i - n] * scale);
    g[static_cast<Eigen::Index>(i - 1)] = gi - g1;
  }
  return g;
}

/// Newton's method on `residuals` from u (a step that does not reduce the largest residual is halved): the
/// root, or nothing.
template <class Residuals>
std::optional<Eigen::VectorXd> newton(const Residuals& residuals, Eigen::VectorXd u) {
  const Eigen::Index m = u.size();
  Eigen::VectorXd f = residuals(u);
  for (int iteration = 0; iteration < 50 && f.lpNorm<Eigen::Infinity>() > 1e-13; ++iteration) {
    Eigen::MatrixXd jacobian(m, m);
    for (Eigen::Index j = 0; j < m; ++j) {
      Eigen::VectorXd v = u;
      v[j] += 1e-7;
      jacobian.col(j) = (residuals(v) - f) / 1e-7;
    }
    const Eigen::VectorXd step = jacobian.fullPivLu().solve(-f);
    double length = 1.0;
    Eigen::VectorXd next = u + step, next_f = residuals(next);
    while (!(next_f.lpNorm<Eigen::Infinity>() < f.lpNorm<Eigen::Infinity>()) && length > 1e-4) {
      length *= 0.5;
      next = u + length * step;
      next_f = residuals(next);
    }
    if (!(next_f.lpNorm<Eigen::Infinity>() < f.lpNorm<Eigen::Infinity>())) return std::nullopt;
    u = next;
    f = next_f;
  }
  if (!(f.lpNorm<Eigen::Infinity>() <= 1e-10)) return std::nullopt;
  return u;
}

/// The HCS in the unknowns u = (log T_2..T_n, log R_1..R_n), T_1 = 1.
std::optional<Eigen::VectorXd> hcs_newton(const species::Mixture& mix, const Eigen::VectorXd& u) {
  return newton(
      [&](const Eigen::VectorXd& v) {
        Eigen::VectorXd y(v.size() + 1);
        y << 0.0, v;
        return hcs_residuals(mix, y);
      },
      u);
}

/// Roughness lambda beta of `mix` (the continuation path from beta = 0 of the steady-state solvers).
species::Mixture scaled_roughness(const species::Mixture& mix, double lambda) {
  species::Mixture out = mix;
  for (std::size_t a = 0; a < mix.size(); ++a)
    for (std::size_t b = 0; b < mix.size(); ++b) out.roughness(a, b) = lambda * mix.roughness(a, b);
  return out;
}

/// Continues `solve(mix at lambda, u)` from lambda = 0 (u0) to 1, halving the step where it fails.
template <class Solve>
std::optional<Eigen::VectorXd> continued(const species::Mixture& mix, const Solve& solve, const Eigen::VectorXd& u0) {
  std::optional<Eigen::VectorXd> u = solve(scaled_roughness(mix, 0.0), u0);
  double lambda = 0.0, step = 0.25;
  while (u && lambda < 1.0) {
    const double next = std::min(1.0, lambda + step);
    if (auto v = solve(scaled_roughness(mix, next), *u)) {
      u = std::move(v);
      lambda = next;
      step = std::min(0.5, 1.5 * step);
    } else if ((step *= 0.5) < 1e-6) {
      u.reset();
    }
  }
  return u;
}

}  // namespace

MixtureCoolingState mixture_cooling_state(const species::Mixture& mix) {
  const std::size_t n = mix.size();
  constexpr std::size_t kLargest = 64;  // Newton with a dense Jacobian: O(n^3) pair rates per step
  if (n > kLargest) return {{}, {}, "not computed for more than 64 species"};
  bool lossless = true;  // alpha = beta = 1 everywhere: energy is conserved, equipartition is the state
  for (std::size_t a = 0; a < n; ++a) {
    bool coupled = false;  // some pair of a has beta > -1: its spins exchange energy
    for (std::size_t b = 0; b < n; ++b) {
      coupled = coupled || mix.roughness(a, b) > -1.0;
      lossless = lossless && mix.restitution(a, b) == 1.0 && mix.roughness(a, b) == 1.0;
    }
    if (!coupled)
      return {{}, {}, "species " + std::to_string(a + 1) + " has beta = -1 with every species: its spins keep their "
                      "energy and its T_rot/T_tr grows without bound"};
  }
  if (lossless) return {std::vector<double>(n, 1.0), std::vector<double>(n, 1.0), {}};
  // Newton from T_k = R_k = 1 at beta = 0, then continued along beta(lambda) = lambda beta (lambda 0 -> 1):
  // the quasi-smooth states (theta ~ 1/(1 + beta)^2) are far from any simple first guess
  const auto u = continued(mix, hcs_newton, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * n - 1)));
  if (!u) return {{}, {}, "the Maxwellian HCS equations of this mixture did not converge (Newton)"};
  Eigen::VectorXd y(static_cast<Eigen::Index>(2 * n));
  y << 0.0, *u;
  double total = 0.0, mean = 0.0;
  for (double x : mix.number_density) total += x;
  for (std::size_t k = 0; k < n; ++k) mean += mix.number_density[k] / total * std::exp(y[static_cast<Eigen::Index>(k)]);
  MixtureCoolingState out;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = std::exp(y[static_cast<Eigen::Index>(k)]), r = std::exp(y[static_cast<Eigen::Index>(n + k)]);
    out.translational_over_mean.push_back(t / mean);
    out.theta.push_back(r / t);
  }
  return out;
}

MixtureDrivenState mixture_driven_state(const species::Mixture& mix, const std::vector<double>& strength) {
  const std::size_t n = mix.size();
  if (n > 64) return {{}, {}, "not computed for more than 64 species"};
  if (strength.size() != n) throw std::invalid_argument("theory::rough::mixture_driven_state: one strength per species");
  const bool rough_gas = mix.rough();
  species::Mixture work = mix;  // smooth spheres: beta = -1 everywhere, no rotation enters the rates
  if (!rough_gas) {
    work.roughness = species::PairMatrix(n, -1.0);
    work.moment_of_inertia.assign(n, 0.4);
  }
  bool lossless = true;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b)
      lossless = lossless && work.restitution(a, b) == 1.0 && std::abs(work.roughness(a, b)) == 1.0;
  if (lossless) return {{}, {}, "no steady state (the collisions lose no energy)"};
  const std::size_t unknowns = rough_gas ? 2 * n : n;
  const auto residuals = [&](const species::Mixture& at, const Eigen::VectorXd& u) {
    std::vector<double> t(n), r(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      t[k] = std::exp(u[static_cast<Eigen::Index>(k)]);
      if (rough_gas) r[k] = std::exp(u[static_cast<Eigen::Index>(n + k)]);
    }
    const auto [dt, dr] = mixture_rates(at, t, r);
    const double scale = collision_rate(at, t);
    Eigen::VectorXd f(static_cast<Eigen::Index>(unknowns));
    for (std::size_t k = 0; k < n; ++k) {
      const double input = 1.5 * mix.mass[k] * strength[k];  // d(3 T_k/2)/dt of the kicks
      f[static_cast<Eigen::Index>(k)] = dt[k] / input + 1.0;
      if (rough_gas) f[static_cast<Eigen::Index>(n + k)] = dr[k] / (1.5 * r[k] * scale);
    }
    return f;
  };
  Eigen::VectorXd u0(static_cast<Eigen::Index>(unknowns));
  double density = 0.0;
  for (double x : mix.number_density) density += x;
  for (std::size_t k = 0; k < n; ++k) {  // one species' balance with its own alpha, the whole density
    const double alpha = mix.restitution(k, k), sigma = mix.diameter[k];
    const double nu_unit = 4.0 * density * sigma * sigma * std::sqrt(std::numbers::pi / mix.mass[k]);
    const double zeta = std::max((1.0 - alpha * alpha) / 3.0, 0.01);
    u0[static_cast<Eigen::Index>(k)] = 2.0 / 3.0 * std::log(mix.mass[k] * strength[k] / (zeta * nu_unit));
    if (rough_gas) u0[static_cast<Eigen::Index>(n + k)] = u0[static_cast<Eigen::Index>(k)] + std::log(0.2);
  }
  const auto solve = [&](const species::Mixture& at, const Eigen::VectorXd& u) {
    return newton([&](const Eigen::VectorXd& v) { return residuals(at, v); }, u);
  };
  const auto u = rough_gas ? continued(work, solve, u0) : solve(work, u0);
  if (!u) return {{}, {}, "the Maxwellian white-noise equations of this mixture did not converge (Newton)"};
  MixtureDrivenState out;
  for (std::size_t k = 0; k < n; ++k) {
    out.translational.push_back(std::exp((*u)[static_cast<Eigen::Index>(k)]));
    if (rough_gas) out.theta.push_back(std::exp((*u)[static_cast<Eigen::Index>(n + k)]) / out.translational.back());
  }
  return out;
}

History integrate(const species::Mixture& mix, double translational, double rotational, const std::vector<double>& times,
                  bool collision_driven) {
  if (mix.size() != 1 || !mix.rough()) throw std::invalid_argument("theory::rough::integrate: one species of rough spheres");
  // the mixture equations for one species are the A, B, C equations (Rough.TwoTemperatureEquationsAgreeWithTheClosedForm)
  const MixtureHistory m = integrate_mixture(mix, {translational}, {rotational}, times, collision_driven);
  History h{m.time, {}, {}, m.collisions_per_particle};
  for (std::size_t i = 0; i < m.time.size(); ++i) {
    h.translational.push_back(m.translational[i][0]);
    h.rotational.push_back(m.rotational[i][0]);
  }
  return h;
}

}  // namespace gdsmc::theory::rough
