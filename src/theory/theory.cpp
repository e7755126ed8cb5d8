// Kinetic theory of homogeneous granular gases and mixtures: see theory.hpp for the equations.
#include "theory/theory.hpp"

#include "theory/cvode_solver.hpp"
#include "theory/input_checks.hpp"

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
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace gdsmc::theory {

namespace {

using detail::CvodeSolver;

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

// ---------------------------------------------------------------------------------------------
// Kernels on raw temperature arrays (no checks; the CVODE right-hand sides call these)
// ---------------------------------------------------------------------------------------------

/// s_kj = T_k/m_k + T_j/m_j (\ref cm_notation "docs/collision-model.md").
double thermal_speed_sum(const Mixture& mix, std::span<const double> temperature, std::size_t k,
                         std::size_t j) {
  return temperature[k] / mix.mass[k] + temperature[j] / mix.mass[j];
}

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

/// Largest collision frequency per particle, max_k sum_j n_j pi sigma_kj^2 chi_kj <|g_kj|>
/// (\ref cm_pair_rate "docs/collision-model.md"): the fastest kinetic time scale, used to size output intervals.
double largest_collision_frequency(const Mixture& mix, std::span<const double> temperature) {
  double largest = 0.0;
  for (std::size_t k = 0; k < mix.size(); ++k) {
    double nu_k = 0.0;
    for (std::size_t j = 0; j < mix.size(); ++j) {
      const double sigma_kj = mix.contact_distance(k, j);
      nu_k += mix.number_density[j] * pi * sigma_kj * sigma_kj * mix.pair_correlation(k, j) *
              mean_relative_speed(thermal_speed_sum(mix, temperature, k, j));  // \ref cm_pair_rate "docs/collision-model.md"
    }
    largest = std::max(largest, nu_k);
  }
  return largest;
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

  std::vector<double> temperature(species_count);
  std::vector<double> row_sum(species_count);
  auto rhs = [&, species_count](double, std::span<const double> y, std::span<double> dydt) {
    for (std::size_t k = 0; k < species_count; ++k)
      temperature[k] = reference_temperature * std::exp(y[k]);
    cooling_rate_row_sums(mix, temperature, row_sum);
    for (std::size_t k = 0; k < species_count; ++k)
      dydt[k] = -row_sum[k];  // \ref haff_mixture_odes "docs/haff-and-mixtures.md": d ln T_k/dt = -sum_j xi_kj
    dydt[species_count] = total_rate(mix, temperature);  // \ref cm_mixture_rate "docs/collision-model.md": d(collisions)/dt
  };
  CvodeSolver solver(rhs, y0, relative_tolerance, absolute_tolerance);

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

std::vector<double> asymptotic_temperature_ratios(const Mixture& mix) {
  const std::size_t species_count = mix.size();
  if (species_count == 0) throw std::invalid_argument("asymptotic_temperature_ratios: no species");
  if (species_count == 1) return {1.0};

  // State y_k = ln(T_k/T_1) with T_1 held at the unit m_1: xi_kj is homogeneous of degree 1/2 in
  // the temperatures, so d ln(T_k/T_1)/dtau = -(sum_j xi_kj - sum_j xi_1j), dtau = sqrt(T_1/m_1) dt.
  const double temperature_unit = mix.mass[0];
  std::vector<double> temperature(species_count, temperature_unit);
  std::vector<double> row_sum(species_count);
  auto rhs = [&, species_count](double, std::span<const double> y, std::span<double> dydt) {
    for (std::size_t k = 0; k < species_count; ++k)
      temperature[k] = temperature_unit * std::exp(y[k]);
    cooling_rate_row_sums(mix, temperature, row_sum);  // \ref haff_mixture_odes "docs/haff-and-mixtures.md"
    for (std::size_t k = 0; k < species_count; ++k) dydt[k] = -(row_sum[k] - row_sum[0]);
  };

  // Start at equal temperatures (the usual initial condition) and follow the ODE.
  const double first_interval = 1.0 / largest_collision_frequency(mix, temperature);
  CvodeSolver solver(rhs, std::vector<double>(species_count, 0.0),
                     std::vector<double>(species_count, 0.0),
                     std::vector<double>(species_count, log_temperature_tolerance));

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

}  // namespace gdsmc::theory
