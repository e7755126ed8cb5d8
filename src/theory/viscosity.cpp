// Shear viscosity of granular gases and mixtures: see viscosity.hpp for the equations and sources.
#include "theory/viscosity.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>

#include "theory/input_checks.hpp"
#include "theory/sonine.hpp"
#include "theory/theory.hpp"

namespace gdsmc::theory::viscosity {

namespace {

constexpr double pi = std::numbers::pi;

void require_restitution(double alpha, const char* caller) {
  if (!(alpha >= 0.0 && alpha <= 1.0))
    throw std::invalid_argument(std::string(caller) + ": restitution " + std::to_string(alpha) +
                                " is outside [0, 1]");
}

/// A Navier-Stokes viscosity exists only where the momentum relaxes faster than c zeta: the
/// denominators nu_eta* - c zeta* and the solution of the tau system must be positive.
double require_positive_viscosity(double value, const char* caller) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument(std::string(caller) +
                                ": no positive Navier-Stokes viscosity (nu_eta <= c zeta)");
  return value;
}

/// What the tau system of \ref eta_mixture "docs/shear-viscosity.md" is built for: the state itself, or the dilute elastic
/// reference at equal temperatures (eta_0 of the mixture).
enum class Variant { state, elastic_reference };

/// The tau system of \ref eta_mixture "docs/shear-viscosity.md" for one state: the pair quantities, in GHD 2007's
/// reduced variables (mbar the plain mean mass, v0 = sqrt(2 T/mbar), theta_i = m_i T/(mbar T_i)).
struct TauSystem {
  const species::Mixture& mix;
  const std::vector<double>& temperature;  ///< T_i
  Variant variant;
  bool dense;                  ///< the Enskog gas (chi and the collisional transfer)
  double thermal_speed = 0.0;  ///< v0
  std::vector<double> theta;

  TauSystem(const species::Mixture& m, const std::vector<double>& t, double mixture_temperature, Variant v)
      : mix(m), temperature(t), variant(v), dense(m.enskog && v == Variant::state), theta(m.size()) {
    double mass_mean = 0.0;
    for (double mass : mix.mass) mass_mean += mass;
    mass_mean /= static_cast<double>(mix.size());
    thermal_speed = std::sqrt(2.0 * mixture_temperature / mass_mean);
    for (std::size_t i = 0; i < mix.size(); ++i) theta[i] = mix.mass[i] * mixture_temperature / (mass_mean * temperature[i]);
  }
  double alpha(std::size_t i, std::size_t j) const {
    return variant == Variant::elastic_reference ? 1.0 : mix.restitution(i, j);
  }
  double chi(std::size_t i, std::size_t j) const {
    return dense ? mix.pair_correlation(i, j) : 1.0;  // \ref cm_chi "docs/collision-model.md": chi only in the Enskog gas
  }
  double mu(std::size_t i, std::size_t j) const { return mix.mass_fraction(i, j); }
  double sigma(std::size_t i, std::size_t j) const { return mix.contact_distance(i, j); }
  double beta(std::size_t i, std::size_t j) const { return mu(i, j) * theta[j] - mu(j, i) * theta[i]; }

  /// zeta_0 = (1/T) sum_i x_i T_i zeta_i, zeta_i = sum_j xi_ij (\ref haff_mixture_odes "docs/haff-and-mixtures.md"); the
  /// elastic reference does not cool.
  double cooling_rate(double mixture_temperature) const {
    if (variant != Variant::state) return 0.0;
    double rate = 0.0;
    const species::PairMatrix xi = cooling_rate_matrix(mix, temperature);
    for (std::size_t i = 0; i < mix.size(); ++i) {
      double zeta_i = 0.0;
      for (std::size_t j = 0; j < mix.size(); ++j) zeta_i += xi(i, j);
      rate += mix.mole_fraction(i) * temperature[i] * zeta_i;
    }
    return rate / mixture_temperature;
  }
  /// tau_ij without the cooling term (\ref eta_mixture "docs/shear-viscosity.md").
  double tau(std::size_t i, std::size_t j) const {
    if (j == i) {
      // S_i: the unlike-pair part of tau_ii.
      double unlike_sum = 0.0;
      for (std::size_t l = 0; l < mix.size(); ++l) {
        if (l == i) continue;
        const double r_il = std::sqrt(theta[i] + theta[l]);
        unlike_sum += mix.number_density[l] * chi(i, l) * sigma(i, l) * sigma(i, l) * mu(l, i) * (1.0 + alpha(i, l)) *
                      std::pow(theta[i], 1.5) / std::sqrt(theta[l]) *
                      (6.0 * beta(i, l) / (theta[i] * theta[i] * r_il) +
                       0.5 * (9.0 - 3.0 * alpha(i, l)) * mu(l, i) * r_il / (theta[i] * theta[i]) + 5.0 / (theta[i] * r_il));
      }
      const double sigma_i = mix.diameter[i];
      return 4.0 * std::sqrt(pi) / 15.0 * thermal_speed *
             (mix.number_density[i] * chi(i, i) * sigma_i * sigma_i / std::sqrt(2.0 * theta[i]) *
                  (9.0 - 3.0 * alpha(i, i)) * (1.0 + alpha(i, i)) +
              2.0 * unlike_sum);
    }
    const double r_ij = std::sqrt(theta[i] + theta[j]);
    return 8.0 * std::sqrt(pi) / 15.0 * thermal_speed * mix.number_density[i] * chi(i, j) * sigma(i, j) * sigma(i, j) *
           mu(i, j) * std::pow(theta[j], 1.5) / std::sqrt(theta[i]) * (1.0 + alpha(i, j)) *
           (6.0 * beta(i, j) / (theta[j] * theta[j] * r_ij) +
            0.5 * (9.0 - 3.0 * alpha(i, j)) * mu(j, i) * r_ij / (theta[j] * theta[j]) - 5.0 / (theta[j] * r_ij));
  }
  /// Source n_i T_i, plus in the Enskog gas the collisional transfer b_i (GHD 2007 II).
  double source(std::size_t i) const {
    double source_i = mix.number_density[i] * temperature[i];
    if (!dense) return source_i;
    for (std::size_t j = 0; j < mix.size(); ++j) {
      const double sigma_ij = sigma(i, j);
      source_i += 2.0 * pi / 15.0 * mix.mass[i] * mix.number_density[i] * mix.number_density[j] * mu(j, i) * sigma_ij *
                  sigma_ij * sigma_ij * chi(i, j) * (1.0 + alpha(i, j)) *
                  (mu(j, i) * (3.0 * alpha(i, j) - 1.0) * (temperature[i] / mix.mass[i] + temperature[j] / mix.mass[j]) -
                   4.0 * (temperature[i] - temperature[j]) / (mix.mass[i] + mix.mass[j]));
    }
    return source_i;
  }
  /// The Enskog gas's bulk viscosity and collisional part of eta from the partial eta_i (GHD 2007 II).
  void add_collisional(MixtureViscosity& result) const {
    for (std::size_t i = 0; i < mix.size(); ++i)
      for (std::size_t j = 0; j < mix.size(); ++j) {
        const double sigma_ij = sigma(i, j);
        // bulk viscosity kappa (GHD 2007 II)
        result.bulk += 2.0 * std::sqrt(pi) / 9.0 * thermal_speed * mu(i, j) * mix.mass[j] * mix.number_density[i] *
                       mix.number_density[j] * std::pow(sigma_ij, 4) * chi(i, j) * (1.0 + alpha(i, j)) *
                       std::sqrt((theta[i] + theta[j]) / (theta[i] * theta[j]));
        result.collisional += 4.0 * pi / 15.0 * mix.number_density[j] * sigma_ij * sigma_ij * sigma_ij * chi(i, j) *
                              mu(j, i) * (1.0 + alpha(i, j)) * result.partial[i];
      }
    result.collisional += 0.6 * result.bulk;
  }
};

/// Solution of sum_j (tau_ij - c zeta_0 delta_ij) eta_j = n_i T_i + b_i and the collisional parts
/// (viscosity.hpp, "Mixture"). `temperature` holds T_i, `mixture_temperature` T.
MixtureViscosity solve_mixture(const species::Mixture& mix, const std::vector<double>& temperature,
                               double mixture_temperature, double cooling_coefficient_c,
                               Variant variant) {
  const std::size_t species_count = mix.size();
  const TauSystem tau(mix, temperature, mixture_temperature, variant);
  const double cooling_rate = tau.cooling_rate(mixture_temperature);
  Eigen::MatrixXd system(species_count, species_count);
  Eigen::VectorXd source(species_count);
  for (std::size_t i = 0; i < species_count; ++i) {
    for (std::size_t j = 0; j < species_count; ++j)
      system(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          j == i ? tau.tau(i, j) - cooling_coefficient_c * cooling_rate : tau.tau(i, j);
    source(static_cast<Eigen::Index>(i)) = tau.source(i);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> solver(system);
  if (!solver.isInvertible())
    throw std::runtime_error("viscosity::mixture_viscosity: the tau system is singular");
  const Eigen::VectorXd partial = solver.solve(source);

  MixtureViscosity result;
  result.cooling_rate = cooling_rate;
  result.partial.assign(partial.data(), partial.data() + partial.size());
  for (double eta_i : result.partial) result.kinetic += eta_i;
  if (tau.dense) tau.add_collisional(result);
  result.total = result.kinetic + result.collisional;
  return result;
}

/// The steady shear flow's two conditions for the mixture at partial temperatures T_i (mixture T = 1):
/// A_i = a^2 = (3/2) [tau (zeta p)]_i / (p_i + Pi_i,yy), Pi_yy = -tau^-1 (zeta p), one value per species
/// (\ref eta_usf_steady "docs/shear-viscosity.md"), and the partial stresses of that state.
struct ShearBalance {
  std::vector<double> shear_rate2;            ///< A_i: the a^2 species i's balance asks for
  std::vector<double> pressure_yy, pressure_xy_times_a;  ///< P_i,yy and a P_i,xy = -(3/2) zeta_i p_i
};

ShearBalance shear_balance(const species::Mixture& mix, const std::vector<double>& temperature) {
  const std::size_t s = mix.size();
  const TauSystem system(mix, temperature, 1.0, Variant::state);
  const species::PairMatrix xi = cooling_rate_matrix(mix, temperature);
  Eigen::MatrixXd tau(s, s);
  Eigen::VectorXd loss(s), pressure(s);  // zeta_i p_i, p_i
  for (std::size_t i = 0; i < s; ++i) {
    double zeta_i = 0.0;
    for (std::size_t j = 0; j < s; ++j) {
      tau(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = system.tau(i, j);
      zeta_i += xi(i, j);
    }
    pressure(static_cast<Eigen::Index>(i)) = mix.number_density[i] * temperature[i];
    loss(static_cast<Eigen::Index>(i)) = zeta_i * pressure(static_cast<Eigen::Index>(i));
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> solver(tau);
  if (!solver.isInvertible()) throw std::runtime_error("viscosity::steady_shear_grad: the tau system is singular");
  const Eigen::VectorXd traceless_yy = -solver.solve(loss);  // tau Pi_yy = (2/3) a P_xy = -zeta p
  const Eigen::VectorXd heating = 1.5 * (tau * loss);        // a^2 (p + Pi_yy) = (3/2) tau (zeta p)
  ShearBalance b;
  for (std::size_t i = 0; i < s; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    b.pressure_yy.push_back(pressure(k) + traceless_yy(k));
    b.shear_rate2.push_back(heating(k) / b.pressure_yy.back());
    b.pressure_xy_times_a.push_back(-1.5 * loss(k));
  }
  return b;
}

}  // namespace

double cooling_coefficient(State state) {
  return state == State::homogeneous_cooling ? 0.5 : 1.0;
}

// ---------------------------------------------------------------------------------------------
// One component
// ---------------------------------------------------------------------------------------------

double elastic_viscosity(double mass, double diameter, double temperature) {
  if (!(mass > 0.0) || !(diameter > 0.0) || !(temperature > 0.0))
    throw std::invalid_argument("viscosity::elastic_viscosity: mass, diameter and temperature "
                                "must be positive");
  return 5.0 / (16.0 * diameter * diameter) * std::sqrt(mass * temperature / pi);  // \ref eta_one_species "docs/shear-viscosity.md"
}

double reduced_momentum_collision_frequency(double alpha, double a2) {
  require_restitution(alpha, "viscosity::reduced_momentum_collision_frequency");
  return (1.0 + alpha) * (3.0 - alpha) / 4.0 * (1.0 - a2 / 32.0);  // \ref eta_one_species "docs/shear-viscosity.md"
}

double reduced_cooling_rate(double alpha, double a2) {
  require_restitution(alpha, "viscosity::reduced_cooling_rate");
  return 5.0 / 12.0 * (1.0 - alpha * alpha) * (1.0 + 3.0 * a2 / 16.0);  // \ref eta_one_species "docs/shear-viscosity.md", \ref haff_sonine "docs/haff-and-mixtures.md"
}

double dilute_reduced_viscosity(double alpha, State state, double a2) {
  return require_positive_viscosity(
      1.0 / (reduced_momentum_collision_frequency(alpha, a2) -
             cooling_coefficient(state) * reduced_cooling_rate(alpha, a2)),  // \ref eta_one_species "docs/shear-viscosity.md"
      "viscosity::dilute_reduced_viscosity");
}

SteadyShear steady_shear_grad(double alpha) {
  require_restitution(alpha, "viscosity::steady_shear_grad");
  // \ref eta_usf_steady "docs/shear-viscosity.md": the moment equations of P_ij in the steady state,
  // a (delta_ix P_yj + delta_jx P_yi) = -nu (P_ij - p delta_ij) - zeta p delta_ij, at a2 = 0
  const double nu = reduced_momentum_collision_frequency(alpha, 0.0), zeta = reduced_cooling_rate(alpha, 0.0);
  const double normal = 1.0 - zeta / nu;  // P_yy/p = P_zz/p
  SteadyShear steady;
  steady.reduced_shear_rate = std::sqrt(1.5 * zeta * nu * nu / (nu - zeta));  // the trace: -a P_xy = (3/2) zeta p
  steady.pressure_yy = steady.pressure_zz = normal;
  steady.pressure_xx = 1.0 + 2.0 * zeta / nu;
  steady.pressure_xy = -steady.reduced_shear_rate * normal / nu;
  steady.viscosity = normal / nu;
  return steady;
}

MixtureSteadyShear steady_shear_grad(const species::Mixture& mix) {
  if (mix.size() != 2 || mix.enskog)
    throw std::invalid_argument("viscosity::steady_shear_grad: a dilute binary mixture only");
  bool elastic = true;
  for (double alpha : mix.restitution.values) {
    require_restitution(alpha, "viscosity::steady_shear_grad");
    elastic = elastic && alpha == 1.0;
  }
  if (elastic) throw std::invalid_argument("viscosity::steady_shear_grad: an elastic gas has no steady shear flow (it heats)");
  // T_1/T_2 = gamma such that both species' balances ask for the same a^2 (bisection in ln gamma), T = 1
  const auto temperatures = [&](double gamma) {
    const double x1 = mix.mole_fraction(0), t2 = 1.0 / (1.0 + x1 * (gamma - 1.0));
    return std::vector<double>{gamma * t2, t2};
  };
  const auto mismatch = [&](double log_gamma) {
    const auto b = shear_balance(mix, temperatures(std::exp(log_gamma)));
    return b.shear_rate2[0] - b.shear_rate2[1];
  };
  double lo = std::log(1e-6), hi = std::log(1e6);
  const double f_lo = mismatch(lo);
  if (!(f_lo * mismatch(hi) < 0.0))
    throw std::runtime_error("viscosity::steady_shear_grad: no temperature ratio in [1e-6, 1e6] balances both species");
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    ((mismatch(mid) < 0.0) == (f_lo < 0.0) ? lo : hi) = mid;
  }
  const auto t = temperatures(std::exp(0.5 * (lo + hi)));
  const auto b = shear_balance(mix, t);
  for (std::size_t i = 0; i < 2; ++i)
    if (!(b.shear_rate2[i] > 0.0) || !(b.pressure_yy[i] > 0.0))
      throw std::runtime_error("viscosity::steady_shear_grad: Grad's solution has no positive a^2 and P_yy here");
  const double a = std::sqrt(0.5 * (b.shear_rate2[0] + b.shear_rate2[1]));
  const double p = mix.total_density();  // n T at T = 1
  MixtureSteadyShear steady;
  steady.temperature_ratio = t;
  steady.reduced_shear_rate = a * elastic_mixture_viscosity(mix, 1.0) / p;
  double yy = 0.0, xy = 0.0;
  for (std::size_t i = 0; i < 2; ++i) {
    yy += b.pressure_yy[i];
    xy += b.pressure_xy_times_a[i] / a;
  }
  steady.pressure_yy = steady.pressure_zz = yy / p;
  steady.pressure_xx = 3.0 - 2.0 * steady.pressure_yy;
  steady.pressure_xy = xy / p;
  return steady;
}

double dilute_reduced_viscosity(double alpha, State state) {
  require_restitution(alpha, "viscosity::dilute_reduced_viscosity");
  return dilute_reduced_viscosity(alpha, state, sonine_a2(alpha));
}

EnskogReducedViscosity enskog_reduced_viscosity(double alpha, double packing_fraction, double chi,
                                                State state, double a2) {
  require_restitution(alpha, "viscosity::enskog_reduced_viscosity");
  if (!(packing_fraction >= 0.0 && packing_fraction < 1.0))
    throw std::invalid_argument("viscosity::enskog_reduced_viscosity: packing fraction " +
                                std::to_string(packing_fraction) + " is outside [0, 1)");
  if (!(chi > 0.0) || !std::isfinite(chi))
    throw std::invalid_argument("viscosity::enskog_reduced_viscosity: chi must be positive");
  const double phi_chi = packing_fraction * chi;
  // Garzo and Dufty 1999: every collision rate carries chi (\ref cm_chi "docs/collision-model.md").
  const double relaxation = chi * (reduced_momentum_collision_frequency(alpha, a2) -
                                   cooling_coefficient(state) * reduced_cooling_rate(alpha, a2));
  EnskogReducedViscosity eta;
  eta.kinetic = require_positive_viscosity(
      (1.0 - 0.4 * (1.0 + alpha) * (1.0 - 3.0 * alpha) * phi_chi) / relaxation,
      "viscosity::enskog_reduced_viscosity");
  eta.bulk = 128.0 / (5.0 * pi) * packing_fraction * phi_chi * (1.0 + alpha) * (1.0 - a2 / 16.0);
  eta.collisional = 0.8 * phi_chi * (1.0 + alpha) * eta.kinetic + 0.6 * eta.bulk;
  eta.total = eta.kinetic + eta.collisional;
  return eta;
}

EnskogReducedViscosity enskog_reduced_viscosity(double alpha, double packing_fraction,
                                                State state) {
  require_restitution(alpha, "viscosity::enskog_reduced_viscosity");
  const double chi = (1.0 - 0.5 * packing_fraction) /
                     std::pow(1.0 - packing_fraction, 3);  // Carnahan-Starling (\ref cm_chi "docs/collision-model.md")
  return enskog_reduced_viscosity(alpha, packing_fraction, chi, state, sonine_a2(alpha));
}

// ---------------------------------------------------------------------------------------------
// Mixtures
// ---------------------------------------------------------------------------------------------

MixtureViscosity mixture_viscosity(const species::Mixture& mix,
                                   const std::vector<double>& temperature_ratio, double temperature,
                                   State state) {
  constexpr const char* caller = "viscosity::mixture_viscosity";
  if (mix.size() == 0) throw std::invalid_argument(std::string(caller) + ": no species");
  detail::require_temperatures(mix, temperature_ratio, caller);
  if (!(temperature > 0.0) || !std::isfinite(temperature))
    throw std::invalid_argument(std::string(caller) + ": temperature must be positive and finite");
  for (std::size_t i = 0; i < mix.size(); ++i)
    for (std::size_t j = 0; j < mix.size(); ++j) require_restitution(mix.restitution(i, j), caller);

  // T = sum_i x_i T_i fixes the scale of the ratios.
  double weighted = 0.0;
  for (std::size_t i = 0; i < mix.size(); ++i)
    weighted += mix.mole_fraction(i) * temperature_ratio[i];
  std::vector<double> partial_temperature(mix.size());
  for (std::size_t i = 0; i < mix.size(); ++i)
    partial_temperature[i] = temperature * temperature_ratio[i] / weighted;

  MixtureViscosity result = solve_mixture(mix, partial_temperature, temperature,
                                          cooling_coefficient(state), Variant::state);
  require_positive_viscosity(result.kinetic, caller);
  result.elastic = elastic_mixture_viscosity(mix, temperature);
  result.reduced = result.total / result.elastic;
  return result;
}

double elastic_mixture_viscosity(const species::Mixture& mix, double temperature) {
  if (mix.size() == 0)
    throw std::invalid_argument("viscosity::elastic_mixture_viscosity: no species");
  if (!(temperature > 0.0) || !std::isfinite(temperature))
    throw std::invalid_argument(
        "viscosity::elastic_mixture_viscosity: temperature must be positive and finite");
  const std::vector<double> equal(mix.size(), temperature);
  return solve_mixture(mix, equal, temperature, 0.0, Variant::elastic_reference).kinetic;
}

std::vector<double> binary_state_temperature_ratios(const species::Mixture& mix) {
  const double gamma = binary_hcs_first_sonine(mix).temperature_ratio;  // \ref son_binary_gamma "docs/sonine.md"
  const double x1 = mix.mole_fraction(0);
  const double t2 = 1.0 / (1.0 + x1 * (gamma - 1.0));  // Montanero and Garzo 2002, eqs. (13)-(14), \ref son_binary "docs/sonine.md"
  return {gamma * t2, t2};
}

MixtureViscosity binary_viscosity(const species::Mixture& mix, double temperature, State state) {
  return mixture_viscosity(mix, binary_state_temperature_ratios(mix), temperature, state);
}

double binary_reduced_viscosity_frequency(const species::Mixture& mix, double temperature) {
  if (mix.size() != 2)
    throw std::invalid_argument("viscosity::binary_reduced_viscosity_frequency: needs 2 species");
  const double sigma_12 = mix.contact_distance(0, 1);
  const double v0 = std::sqrt(2.0 * temperature * (mix.mass[0] + mix.mass[1]) /
                              (mix.mass[0] * mix.mass[1]));  // Montanero 2003, Sec. 2, \ref eta_stages "docs/shear-viscosity.md"
  return std::sqrt(pi) * mix.total_density() * sigma_12 * sigma_12 * v0;
}

}  // namespace gdsmc::theory::viscosity
