// Rough spheres of one species, Maxwellian approximation (rough.hpp; \ref rough_maxwellian "docs/rough-spheres.md").
#include "theory/rough.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

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

namespace {

/// (T_tr, T_rot, the other variable: c or t) and one RK4 step of length h in t (collision_driven false)
/// or in c.
using State = std::array<double, 3>;

State derivative(const State& y, const Coefficients& k, double nu_unit, bool collision_driven) {
  const double nu = nu_unit * std::sqrt(std::max(y[0], 0.0));
  const double dtr = 4.0 / 3.0 * (-k.a * y[0] + k.b * y[1]), drot = 4.0 / 3.0 * (k.b * y[0] - k.c * y[1]);
  if (collision_driven) return {dtr, drot, 1.0 / nu};  // d/dc; the third variable is t
  return {nu * dtr, nu * drot, nu};                      // d/dt; the third variable is c
}

State rk4(const State& y, double h, const Coefficients& k, double nu_unit, bool collision_driven) {
  const auto at = [&](const State& d, double f) { return State{y[0] + f * d[0], y[1] + f * d[1], y[2] + f * d[2]}; };
  const State k1 = derivative(y, k, nu_unit, collision_driven);
  const State k2 = derivative(at(k1, 0.5 * h), k, nu_unit, collision_driven);
  const State k3 = derivative(at(k2, 0.5 * h), k, nu_unit, collision_driven);
  const State k4 = derivative(at(k3, h), k, nu_unit, collision_driven);
  State out;
  for (std::size_t i = 0; i < 3; ++i) out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  return out;
}

}  // namespace

History integrate(const species::Mixture& mix, double translational, double rotational, const std::vector<double>& times,
                  bool collision_driven) {
  if (mix.size() != 1 || !mix.rough()) throw std::invalid_argument("theory::rough::integrate: one species of rough spheres");
  const Coefficients k = coefficients(mix.restitution(0, 0), mix.roughness(0, 0), mix.moment_of_inertia[0]);
  const double nu_unit = frequency_unit(mix);
  History h;
  State y{translational, rotational, 0.0};  // (T_tr, T_rot, c or t)
  double x = 0.0;                           // t or c
  constexpr double kStep = 0.01;            // collisions per particle per step: RK4 error ~ 1e-10 relative
  for (double target : times) {
    while (x < target) {
      const double nu = nu_unit * std::sqrt(y[0]);
      const double step = std::min(collision_driven ? kStep : kStep / nu, target - x);
      y = rk4(y, step, k, nu_unit, collision_driven);
      x = std::min(x + step, target);
    }
    h.time.push_back(collision_driven ? y[2] : x);
    h.collisions_per_particle.push_back(collision_driven ? x : y[2]);
    h.translational.push_back(y[0]);
    h.rotational.push_back(y[1]);
  }
  return h;
}

}  // namespace gdsmc::theory::rough
