// Kinetic theory of homogeneous granular gases and mixtures: see theory.hpp for the equations.
#include "theory/theory.hpp"

#include "theory/cvode_solver.hpp"
#include "theory/gmres.hpp"
#include "theory/input_checks.hpp"
#include "theory/maxwellian_rates.hpp"

#include <Eigen/Dense>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace gdsmc::theory {

namespace {

using detail::CvodeMethod;
using detail::CvodeOptions;
using detail::CvodeSolver;
using detail::MaxwellianRates;

constexpr double pi = std::numbers::pi;

/// Relative tolerance of the ODE solutions (theory.hpp, "Numerical integration"): rtol of the
/// collision count; the temperatures are integrated as ln T_k, where an absolute error is a relative
/// error of T_k, with a local tolerance 10x tighter so that the global relative error of T_k stays
/// near 1e-10 (measured 3e-10 after Haff cooling to 100 t0, 1e-9 with a local 1e-10).
constexpr double relative_tolerance_of_ode = 1e-10;
constexpr double log_temperature_tolerance = 0.1 * relative_tolerance_of_ode;

static_assert(std::is_same_v<sunrealtype, double>, "SUNDIALS must be built in double precision");

// ---------------------------------------------------------------------------------------------
// Input checks
// ---------------------------------------------------------------------------------------------

using detail::require_temperatures;  // theory/input_checks.hpp
using detail::thermal_speed_sum;     // s_kj, theory/input_checks.hpp

// ---------------------------------------------------------------------------------------------
// Kernels on raw temperature arrays (no checks; the CVODE right-hand sides call these)
// ---------------------------------------------------------------------------------------------

/// \ref cm_mixture_rate "docs/collision-model.md": events per unit volume and time between species k and j (half for k == j).
double pair_rate(const Mixture& mix, std::span<const double> temperature, std::size_t k,
                 std::size_t j) {
  const double sigma_kj = mix.contact_distance(k, j);
  const double rate = mix.number_density[k] * mix.number_density[j] * pi * sigma_kj * sigma_kj *
                      mix.pair_correlation(k, j) *
                      mean_relative_speed(thermal_speed_sum(mix, temperature, k, j));  // \ref cm_pair_rate "docs/collision-model.md"
  return k == j ? 0.5 * rate : rate;  // \ref cm_mixture_rate "docs/collision-model.md": like pairs counted once
}

double total_rate(const Mixture& mix, std::span<const double> temperature) {
  double total = 0.0;
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t j = k; j < mix.size(); ++j) total += pair_rate(mix, temperature, k, j);
  return total;
}

/// \ref haff_mixture_odes "docs/haff-and-mixtures.md": xi_kj = (8/3) sqrt(2 pi) n_j sigma_kj^2 chi_kj sqrt(s_kj) mu_jk (1 + alpha_kj)
///                    [1 - (1/2)(1 + alpha_kj) X_kj],  X_kj = (T_k m_j + T_j m_k)/(T_k (m_j + m_k)).
double cooling_rate_entry(const Mixture& mix, std::span<const double> temperature, std::size_t k,
                          std::size_t j) {
  const double sigma_kj = mix.contact_distance(k, j);
  const double one_plus_alpha = 1.0 + mix.restitution(k, j);
  const double mu_jk = mix.mass_fraction(j, k);  // m_j/(m_k + m_j)
  const double x_kj = (temperature[k] * mix.mass[j] + temperature[j] * mix.mass[k]) /
                      (temperature[k] * (mix.mass[j] + mix.mass[k]));  // \ref haff_mixture_odes "docs/haff-and-mixtures.md" X_kj
  return (8.0 / 3.0) * std::sqrt(2.0 * pi) * mix.number_density[j] * sigma_kj * sigma_kj *
         mix.pair_correlation(k, j) * std::sqrt(thermal_speed_sum(mix, temperature, k, j)) *
         mu_jk * one_plus_alpha * (1.0 - 0.5 * one_plus_alpha * x_kj);  // \ref haff_mixture_odes "docs/haff-and-mixtures.md"
}

/// sum_j xi_kj for every k, so that d ln T_k/dt = -sum_j xi_kj (\ref haff_mixture_odes "docs/haff-and-mixtures.md").
void cooling_rate_row_sums(const Mixture& mix, std::span<const double> temperature,
                           std::span<double> row_sum) {
  for (std::size_t k = 0; k < mix.size(); ++k) {
    double sum = 0.0;
    for (std::size_t j = 0; j < mix.size(); ++j)
      sum += cooling_rate_entry(mix, temperature, k, j);
    row_sum[k] = sum;
  }
}

/// Above this many species the partial-temperature ODEs are integrated with matrix-free GMRES,
/// left-preconditioned by the diagonal of CVODE's Newton matrix I - gamma J (theory.hpp,
/// "Numerical integration"); below, by a dense LU of the analytic Jacobian (maxwellian_rates.hpp),
/// whose (S + 1)^3 factorisations would dominate above it.
constexpr std::size_t krylov_species = 200;

/// CVODE options for the state y_k = ln(T_k/T_ref) (k < S), y_S = collisions per unit volume, with
/// the Jacobian of maxwellian_rates.hpp: df_k/dy_l = -d zeta_k/d ln T_l, df_S/dy_l = dR/d ln T_l.
CvodeOptions ode_options(const MaxwellianRates& rates, double reference_temperature) {
  const std::size_t s = rates.size();
  CvodeOptions options;
  auto temperatures = [s, reference_temperature](std::span<const double> y) {
    std::vector<double> T(s);
    for (std::size_t k = 0; k < s; ++k) T[k] = reference_temperature * std::exp(y[k]);
    return T;
  };
  if (s > krylov_species) {
    options.method = CvodeMethod::bdf_spgmr;
    options.jacobian_diagonal = [&rates, s, temperatures](double, std::span<const double> y,
                                                          std::span<double> diagonal) {
      rates.jacobian_diagonal(temperatures(y), diagonal.first(s));
      for (std::size_t k = 0; k < s; ++k) diagonal[k] = -diagonal[k];
      diagonal[s] = 0.0;  // the collision count does not enter any rate
    };
  } else {
    options.jacobian = [&rates, s, temperatures](double, std::span<const double> y, double* jac) {
      Eigen::MatrixXd J;
      std::vector<double> gradient(s);
      rates.jacobian(temperatures(y), J, gradient);
      const std::size_t n = s + 1;  // column-major n x n, last row/column the collision count
      for (std::size_t l = 0; l < s; ++l) {
        for (std::size_t k = 0; k < s; ++k)
          jac[l * n + k] = -J(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l));
        jac[l * n + s] = gradient[l];
      }
    };
  }
  return options;
}

}  // namespace

// -------------------------------------------------------------------------------------------------
// One species and single pairs
// -------------------------------------------------------------------------------------------------

double mean_relative_speed(double s_kj) {
  return std::sqrt(8.0 * s_kj / pi);  // \ref cm_mean_speed "docs/collision-model.md" (DSMC notes, eq. (60))
}

double collision_frequency(double number_density, double diameter, double chi, double mass,
                           double temperature) {
  // \ref cm_frequency "docs/collision-model.md": nu = 4 sqrt(pi) n sigma^2 chi sqrt(T/m)
  return 4.0 * std::sqrt(pi) * number_density * diameter * diameter * chi *
         std::sqrt(temperature / mass);
}

double haff_cooling_rate(double number_density, double diameter, double chi, double mass,
                         double alpha, double temperature) {
  // \ref haff_law "docs/haff-and-mixtures.md": zeta_0 = (4/3) sqrt(pi) (1 - alpha^2) n sigma^2 chi sqrt(T/m)
  return (4.0 / 3.0) * std::sqrt(pi) * (1.0 - alpha * alpha) * number_density * diameter *
         diameter * chi * std::sqrt(temperature / mass);
}

double sonine_a2(double alpha) {
  // \ref haff_sonine "docs/haff-and-mixtures.md" (van Noije and Ernst)
  return 16.0 * (1.0 - alpha) * (1.0 - 2.0 * alpha * alpha) /
         (81.0 - 17.0 * alpha + 30.0 * alpha * alpha * (1.0 - alpha));
}

double haff_temperature(double t, double T0, double zeta0) {
  const double t0 = 2.0 / zeta0;  // \ref haff_law "docs/haff-and-mixtures.md"
  const double stretch = 1.0 + t / t0;
  return T0 / (stretch * stretch);  // \ref haff_law "docs/haff-and-mixtures.md" (DSMC notes, eq. (45) with the sign corrected)
}

// -------------------------------------------------------------------------------------------------
// Mixtures
// -------------------------------------------------------------------------------------------------

PairMatrix pair_collision_rate(const Mixture& mix, const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "pair_collision_rate");
  PairMatrix rate(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t j = 0; j < mix.size(); ++j) rate(k, j) = pair_rate(mix, temperature, k, j);
  return rate;
}

std::vector<double> collision_frequencies(const Mixture& mix, const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "collision_frequencies");
  std::vector<double> frequency(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k) {
    double suffered = 0.0;  // \ref cm_mixture_rate "docs/collision-model.md": 2 P_kk + sum_{j != k} P_kj
    for (std::size_t j = 0; j < mix.size(); ++j) suffered += (j == k ? 2.0 : 1.0) * pair_rate(mix, temperature, k, j);
    frequency[k] = suffered / mix.number_density[k];
  }
  return frequency;
}

double total_collision_rate(const Mixture& mix, const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "total_collision_rate");
  return total_rate(mix, temperature);
}

PairMatrix cooling_rate_matrix(const Mixture& mix, const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "cooling_rate_matrix");
  PairMatrix xi(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t j = 0; j < mix.size(); ++j)
      xi(k, j) = cooling_rate_entry(mix, temperature, k, j);
  return xi;
}

std::vector<double> cooling_rates(const Mixture& mix, const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "cooling_rates");
  std::vector<double> rate(mix.size());
  cooling_rate_row_sums(mix, temperature, rate);
  return rate;
}

std::vector<double> partial_temperature_rates(const Mixture& mix,
                                              const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "partial_temperature_rates");
  std::vector<double> rate(mix.size());
  cooling_rate_row_sums(mix, temperature, rate);
  for (std::size_t k = 0; k < mix.size(); ++k)
    rate[k] *= -temperature[k];  // \ref haff_mixture_odes "docs/haff-and-mixtures.md": dT_k/dt = -T_k sum_j xi_kj
  return rate;
}

TemperatureHistory integrate_partial_temperatures(const Mixture& mix,
                                                  const std::vector<double>& initial_temperature,
                                                  const std::vector<double>& times) {
  require_temperatures(mix, initial_temperature, "integrate_partial_temperatures");
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!std::isfinite(times[i]) || times[i] < 0.0 || (i > 0 && !(times[i] > times[i - 1])))
      throw std::invalid_argument(
          "integrate_partial_temperatures: times must be finite, non-negative and increasing");

  const std::size_t species_count = mix.size();
  // Reference temperature T_ref = sum_k x_k T_k(0); state y_k = ln(T_k/T_ref), y_S = collisions.
  double reference_temperature = 0.0;
  for (std::size_t k = 0; k < species_count; ++k)
    reference_temperature += mix.mole_fraction(k) * initial_temperature[k];

  std::vector<double> y0(species_count + 1, 0.0);
  for (std::size_t k = 0; k < species_count; ++k)
    y0[k] = std::log(initial_temperature[k] / reference_temperature);
  // Tolerances (see theory.hpp): an absolute error on ln T_k is a relative error on T_k, so the
  // ln T_k components get no rtol * |y| term (it would depend on the temperature unit via T_ref).
  std::vector<double> relative_tolerance(species_count + 1, 0.0);
  std::vector<double> absolute_tolerance(species_count + 1, log_temperature_tolerance);
  relative_tolerance[species_count] = relative_tolerance_of_ode;
  absolute_tolerance[species_count] = 1e-12 * mix.total_density();  // events per unit volume

  // The pair sums and their analytic Jacobian (maxwellian_rates.hpp), O(S^2) per evaluation.
  const MaxwellianRates rates(mix);
  std::vector<double> temperature(species_count);
  std::vector<double> row_sum(species_count);
  auto rhs = [&, species_count](double, std::span<const double> y, std::span<double> dydt) {
    for (std::size_t k = 0; k < species_count; ++k)
      temperature[k] = reference_temperature * std::exp(y[k]);
    // \ref haff_mixture_odes "docs/haff-and-mixtures.md": d ln T_k/dt = -sum_j xi_kj; \ref cm_mixture_rate "docs/collision-model.md": d(collisions)/dt
    dydt[species_count] = rates.cooling_rates_and_collision_rate(temperature, row_sum);
    for (std::size_t k = 0; k < species_count; ++k) dydt[k] = -row_sum[k];
  };
  CvodeSolver solver(rhs, y0, relative_tolerance, absolute_tolerance,
                     ode_options(rates, reference_temperature));
  TemperatureHistory history;
  history.time = times;
  for (double t_out : times) {
    if (t_out > 0.0) solver.advance_to(t_out);  // t_out == 0 is the initial state itself
    const auto y = solver.state();
    std::vector<double> temperature_now(species_count);
    for (std::size_t k = 0; k < species_count; ++k)
      temperature_now[k] = reference_temperature * std::exp(y[k]);
    history.temperature.push_back(std::move(temperature_now));
    history.collisions.push_back(y[species_count]);
  }
  return history;
}

namespace {

/// The long-time ODE of the ratios (theory.hpp, asymptotic_temperature_ratios): the fallback of
/// ratios_by_newton and ratios_by_continuation, and the method before them.
std::vector<double> asymptotic_ratios_by_ode(const Mixture& mix, const MaxwellianRates& rates) {
  const std::size_t species_count = mix.size();
  // State y_k = ln(T_k/T_1) with T_1 held at the unit m_1: xi_kj is homogeneous of degree 1/2 in
  // the temperatures, so d ln(T_k/T_1)/dtau = -(sum_j xi_kj - sum_j xi_1j), dtau = sqrt(T_1/m_1) dt.
  const double temperature_unit = mix.mass[0];
  std::vector<double> temperature(species_count, temperature_unit);
  std::vector<double> row_sum(species_count);
  auto rhs = [&, species_count](double, std::span<const double> y, std::span<double> dydt) {
    for (std::size_t k = 0; k < species_count; ++k)
      temperature[k] = temperature_unit * std::exp(y[k]);
    rates.cooling_rates(temperature, row_sum);  // \ref haff_mixture_odes "docs/haff-and-mixtures.md"
    for (std::size_t k = 0; k < species_count; ++k) dydt[k] = -(row_sum[k] - row_sum[0]);
  };

  // Start at equal temperatures (the usual initial condition) and follow the ODE.
  const double first_interval = 1.0 / rates.largest_collision_frequency(temperature);
  CvodeOptions options;  // as the partial-temperature ODEs: GMRES for many species
  if (species_count > krylov_species) {
    options.method = CvodeMethod::bdf_spgmr;
    options.jacobian_diagonal = [&](double, std::span<const double> y, std::span<double> diagonal) {
      for (std::size_t k = 0; k < species_count; ++k)
        temperature[k] = temperature_unit * std::exp(y[k]);
      rates.jacobian_diagonal(temperature, diagonal);  // d zeta_k/d ln T_k; the zeta_1 part left out
      for (double& d : diagonal) d = -d;
      diagonal[0] = 0.0;
    };
  }
  CvodeSolver solver(rhs, std::vector<double>(species_count, 0.0),
                     std::vector<double>(species_count, 0.0),
                     std::vector<double>(species_count, log_temperature_tolerance), options);

  constexpr double converged_change = 1e-12;
  constexpr int max_intervals = 400;
  std::vector<double> ratio(species_count, 1.0), previous_ratio = ratio;
  double tau = 0.0, interval = first_interval;
  int quiet_intervals = 0;
  for (int i = 0; i < max_intervals; ++i, interval *= 2.0) {
    tau += interval;
    solver.advance_to(tau);
    const auto y = solver.state();
    double largest_change = 0.0;
    for (std::size_t k = 0; k < species_count; ++k) {
      ratio[k] = std::exp(y[k]);
      largest_change = std::max(largest_change, std::abs(ratio[k] - previous_ratio[k]) / ratio[k]);
    }
    previous_ratio = ratio;
    quiet_intervals = largest_change < converged_change ? quiet_intervals + 1 : 0;
    if (quiet_intervals == 2) return ratio;
  }
  throw std::runtime_error(
      "asymptotic_temperature_ratios: ratios did not settle to 1e-12 within 2^400 collision times");
}

// The fixed point of the ratio ODE (theory.hpp, asymptotic_temperature_ratios): Newton's method
// with a backtracking line search, then, should it fail, pseudo-transient continuation (C. T. Kelley
// and D. E. Keyes, SIAM J. Numer. Anal. 35, 508 (1998), eqs. 1.3-1.4 with the SER step rule 1.5).
constexpr int newton_max_iterations = 60;
constexpr int continuation_max_iterations = 500;
constexpr double ratio_residual = 1e-13;  // max |zeta_k - zeta_1|/zeta_1 at the solution
constexpr double max_log_step = 1.0;      // largest change of ln(T_k/T_1) per Newton step
constexpr std::size_t dense_ratio_species = 300;  // above: GMRES instead of LU per linear solve
constexpr double gmres_tolerance = 1e-10;

/// F_k(u) = zeta_k - zeta_1 (k = 2..s) over the unknowns u_k = ln(T_k/T_1), T_1 = m_1, and their
/// derivatives (maxwellian_rates.hpp), with the linear solves of both methods.
class RatioEquations {
 public:
  RatioEquations(const Mixture& mix, const MaxwellianRates& rates)
      : rates_(rates), s_(mix.size()), n_(static_cast<Eigen::Index>(mix.size() - 1)),
        unit_(mix.mass[0]), T_(mix.size(), mix.mass[0]), zeta_(mix.size()) {}
  Eigen::Index unknowns() const { return n_; }
  /// max_k |F_k|/zeta_1 (infinite when not finite); F and the temperatures are left set at u.
  double evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& F) {
    for (Eigen::Index k = 0; k < n_; ++k) T_[static_cast<std::size_t>(k + 1)] = unit_ * std::exp(u(k));
    rates_.cooling_rates(T_, zeta_);  // \ref haff_mixture_odes "docs/haff-and-mixtures.md"
    F.resize(n_);
    for (Eigen::Index k = 0; k < n_; ++k) F(k) = zeta_[static_cast<std::size_t>(k + 1)] - zeta_[0];
    return F.allFinite() && zeta_[0] > 0.0 ? F.cwiseAbs().maxCoeff() / zeta_[0] : HUGE_VAL;
  }
  /// Solves (shift I + dF/du) delta = -F at the temperatures of the last evaluate().
  Eigen::VectorXd step(const Eigen::VectorXd& F, double shift) {
    rates_.jacobian(T_, J_);  // dF_k/du_l = J_kl - J_1l
    A_ = J_.bottomRightCorner(n_, n_).rowwise() - J_.row(0).tail(n_);
    A_.diagonal().array() += shift;
    if (s_ - 1 <= dense_ratio_species) return A_.partialPivLu().solve(-F);
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(n_);
    const Eigen::VectorXd diagonal = A_.diagonal();
    detail::gmres(A_, -F, diagonal, delta, gmres_tolerance);
    return delta;
  }
  double largest_collision_frequency() const { return rates_.largest_collision_frequency(T_); }

 private:
  const MaxwellianRates& rates_;
  std::size_t s_;
  Eigen::Index n_;
  double unit_;
  std::vector<double> T_, zeta_;
  Eigen::MatrixXd J_, A_;
};

std::vector<double> ratios_of(const Eigen::VectorXd& u) {
  std::vector<double> ratio(static_cast<std::size_t>(u.size() + 1), 1.0);
  for (Eigen::Index k = 0; k < u.size(); ++k) ratio[static_cast<std::size_t>(k + 1)] = std::exp(u(k));
  return ratio;
}

/// Newton's method from equal temperatures: steps in u limited to max_log_step, halved until
/// max|F| decreases; empty if that fails or takes more than newton_max_iterations.
std::optional<std::vector<double>> ratios_by_newton(RatioEquations& eq) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(eq.unknowns()), F, trial_F;
  double residual = eq.evaluate(u, F);
  for (int iteration = 0; iteration < newton_max_iterations; ++iteration) {
    if (residual <= ratio_residual) return ratios_of(u);
    if (!std::isfinite(residual)) return std::nullopt;
    Eigen::VectorXd delta = eq.step(F, 0.0);
    if (!delta.allFinite()) return std::nullopt;
    const double largest = delta.cwiseAbs().maxCoeff();
    if (largest > max_log_step) delta *= max_log_step / largest;
    bool accepted = false;
    for (double lambda = 1.0; lambda > 1e-4; lambda *= 0.5) {
      const Eigen::VectorXd trial = u + lambda * delta;
      const double trial_residual = eq.evaluate(trial, trial_F);
      if (trial_residual < (1.0 - 1e-4 * lambda) * residual) {
        u = trial;
        F = trial_F;
        residual = trial_residual;
        accepted = true;
        break;
      }
    }
    if (!accepted) return std::nullopt;
  }
  return std::nullopt;
}

/// Pseudo-transient continuation: implicit Euler steps (I/h + dF/du) delta = -F of the ratio ODE
/// du/dtau = -F(u) from equal temperatures, h_0 = 1/nu_max, h growing as max|F| falls (SER);
/// empty if it does not converge.
std::optional<std::vector<double>> ratios_by_continuation(RatioEquations& eq) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(eq.unknowns()), F, trial_F;
  double residual = eq.evaluate(u, F);
  double h = 1.0 / eq.largest_collision_frequency();
  for (int iteration = 0; iteration < continuation_max_iterations; ++iteration) {
    if (residual <= ratio_residual) return ratios_of(u);
    if (!std::isfinite(residual)) return std::nullopt;
    const Eigen::VectorXd delta = eq.step(F, 1.0 / h);
    if (!delta.allFinite()) return std::nullopt;
    const Eigen::VectorXd trial = u + delta;
    const double trial_residual = eq.evaluate(trial, trial_F);
    if (!(trial_residual < 10.0 * residual)) {  // a step too long for the trajectory: shorten it
      h *= 0.1;
      eq.evaluate(u, F);  // the temperatures of u again, for the next Jacobian
      continue;
    }
    h *= residual / trial_residual;  // switched evolution relaxation (SER)
    u = trial;
    F = trial_F;
    residual = trial_residual;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::vector<double>> detail::asymptotic_temperature_ratios_by(const Mixture& mix,
                                                                           RatioMethod method) {
  if (mix.size() < 2) throw std::invalid_argument("asymptotic_temperature_ratios_by: two species or more");
  const MaxwellianRates rates(mix);
  RatioEquations equations(mix, rates);
  switch (method) {
    case RatioMethod::newton:
      return ratios_by_newton(equations);
    case RatioMethod::continuation:
      return ratios_by_continuation(equations);
    case RatioMethod::ode:
      try {
        return asymptotic_ratios_by_ode(mix, rates);
      } catch (const std::runtime_error&) {
        return std::nullopt;
      }
  }
  return std::nullopt;
}

std::vector<double> asymptotic_temperature_ratios(const Mixture& mix) {
  const std::size_t species_count = mix.size();
  if (species_count == 0) throw std::invalid_argument("asymptotic_temperature_ratios: no species");
  if (species_count == 1) return {1.0};
  const MaxwellianRates rates(mix);
  RatioEquations equations(mix, rates);
  if (auto ratio = ratios_by_newton(equations)) return *ratio;
  if (auto ratio = ratios_by_continuation(equations)) return *ratio;
  return asymptotic_ratios_by_ode(mix, rates);
}

std::vector<double> times_for_collisions(const Mixture& mix, const std::vector<double>& t0,
                                         const std::vector<double>& targets) {
  return times_for_collisions(mix, t0, targets,
                              [&](const std::vector<double>& times) { return integrate_partial_temperatures(mix, t0, times); });
}

std::vector<double> times_for_collisions(const Mixture& mix, const std::vector<double>& t0,
                                         const std::vector<double>& targets,
                                         const std::function<TemperatureHistory(const std::vector<double>&)>& integrate) {
  const double n = mix.total_density();
  // Bracket the last target on a doubling time scale, then tabulate densely and interpolate.
  double horizon = 1.0;
  const double rate0 = total_collision_rate(mix, t0);
  horizon = std::max(horizon, targets.back() * n / (2.0 * rate0));
  for (int guard = 0; guard < 200; ++guard) {
    const auto h = integrate({0.0, horizon});
    if (2.0 * h.collisions.back() / n >= targets.back()) break;
    horizon *= 2.0;
  }
  const std::size_t grid = 20000;
  std::vector<double> t(grid);
  for (std::size_t i = 0; i < grid; ++i) t[i] = horizon * static_cast<double>(i) / (grid - 1);
  const auto h = integrate(t);
  std::vector<double> out;
  std::size_t i = 1;
  for (double c : targets) {
    if (c <= 0.0) {
      out.push_back(0.0);
      continue;
    }
    while (i < grid - 1 && 2.0 * h.collisions[i] / n < c) ++i;
    const double c0 = 2.0 * h.collisions[i - 1] / n, c1 = 2.0 * h.collisions[i] / n;
    out.push_back(t[i - 1] + (t[i] - t[i - 1]) * (c - c0) / (c1 - c0));
  }
  return out;
}

}  // namespace gdsmc::theory
