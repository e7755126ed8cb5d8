// Self-diffusion in a cooling granular mixture: see diffusion.hpp for the equations and numerics.
#include "theory/diffusion.hpp"

#include "theory/cvode_solver.hpp"
#include "theory/input_checks.hpp"

#include <cvode/cvode.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace gdsmc::theory {

namespace {

constexpr double pi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Series coefficients (\ref visco_series "docs/viscoelastic.md", \ref visco_averaged "docs/viscoelastic.md")
// ---------------------------------------------------------------------------------------------

constexpr int square_terms = 2 * restitution_series_terms;  // A_n runs to n = 40 (\ref visco_averaged "docs/viscoelastic.md")

const auto& h_coeff = restitution::h;  // \ref visco_series "docs/viscoelastic.md"

/// \ref visco_averaged "docs/viscoelastic.md": A_n = 4 h_n + sum_{j+l=n, 1<=j,l<=20} h_j h_l (h_n = 0 for n > 20), index n.
constexpr std::array<double, square_terms + 1> square_coefficients() {
  std::array<double, square_terms + 1> a{};
  for (int n = 1; n <= square_terms; ++n) {
    a[n] = n <= restitution_series_terms ? 4.0 * h_coeff[n] : 0.0;
    for (int j = 1; j <= restitution_series_terms; ++j) {
      const int l = n - j;
      if (l >= 1 && l <= restitution_series_terms) a[n] += h_coeff[j] * h_coeff[l];
    }
  }
  return a;
}
constexpr std::array<double, square_terms + 1> a_coeff = square_coefficients();

/// (1/2) Gamma(2 + n/20), so that B_n = half_gamma[n] u_ki^n (\ref visco_averaged "docs/viscoelastic.md").
const std::array<double, square_terms + 1>& half_gamma() {
  static const std::array<double, square_terms + 1> table = [] {
    std::array<double, square_terms + 1> t{};
    for (int n = 0; n <= square_terms; ++n) t[n] = 0.5 * std::tgamma(2.0 + n / 20.0);
    return t;
  }();
  return table;
}

// ---------------------------------------------------------------------------------------------
// Input checks
// ---------------------------------------------------------------------------------------------

using detail::require_temperatures;  // theory/input_checks.hpp
using detail::thermal_speed_sum;     // s_ki = T_k/m_k + T_i/m_i

void require_beta(const Mixture& mix, const PairMatrix& beta, const char* caller) {
  if (beta.size != mix.size() || beta.values.size() != mix.size() * mix.size())
    throw std::invalid_argument(std::string(caller) + ": beta must be S x S for S species");
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t i = 0; i < mix.size(); ++i) {
      const double b = beta(k, i);
      if (!(b >= 0.0) || !std::isfinite(b))
        throw std::invalid_argument(std::string(caller) + ": beta must be finite and >= 0");
      if (std::abs(b - beta(i, k)) > 1e-12 * std::max(b, beta(i, k)))
        throw std::invalid_argument(std::string(caller) + ": beta must be symmetric");
    }
}

void require_times(const std::vector<double>& times, const char* caller) {
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!std::isfinite(times[i]) || times[i] < 0.0 || (i > 0 && !(times[i] > times[i - 1])))
      throw std::invalid_argument(std::string(caller) +
                                  ": times must be finite, non-negative and increasing");
}

// ---------------------------------------------------------------------------------------------
// Pair kernels on raw temperature arrays (no input checks)
// ---------------------------------------------------------------------------------------------

/// \ref haff_mixture_odes "docs/haff-and-mixtures.md", \ref dif_correlation_time "docs/diffusion-msd.md": X_ki = (T_k m_i + T_i m_k)/(T_k (m_i + m_k)).
double x_factor(const Mixture& mix, std::span<const double> T, std::size_t k, std::size_t i) {
  return (T[k] * mix.mass[i] + T[i] * mix.mass[k]) / (T[k] * (mix.mass[i] + mix.mass[k]));
}

/// \ref dif_correlation_time "docs/diffusion-msd.md": base_ki = (8 sqrt(2 pi)/3) n_i sigma_ki^2 chi_ki mu_ik sqrt(s_ki),
/// mu_ik = m_i/(m_i + m_k).
double base_rate(const Mixture& mix, std::span<const double> T, std::size_t k, std::size_t i) {
  const double sigma_ki = mix.contact_distance(k, i);
  return (8.0 / 3.0) * std::sqrt(2.0 * pi) * mix.number_density[i] * sigma_ki * sigma_ki *
         mix.pair_correlation(k, i) * mix.mass_fraction(i, k) *
         std::sqrt(thermal_speed_sum(mix, T, k, i));
}

/// A1 (\ref dif_correlation_time "docs/diffusion-msd.md"): tau_v,ki^-1 = base_ki X_ki (1 + alpha_ki)^2/4.
double inverse_tau_constant(const Mixture& mix, std::span<const double> T, std::size_t k,
                            std::size_t i) {
  const double one_plus_alpha = 1.0 + mix.restitution(k, i);
  return base_rate(mix, T, k, i) * x_factor(mix, T, k, i) * one_plus_alpha * one_plus_alpha / 4.0;
}

/// Typical u of a pair, u_ki = beta_ki^(1/2) (2 s_ki)^(1/20): B_n = (1/2) Gamma(2 + n/20) u_ki^n.
double typical_u(double beta_ki, double s_ki) {
  return std::sqrt(beta_ki) * std::pow(2.0 * s_ki, 0.05);
}

struct SeriesSums {
  double ab = 0.0;  ///< sum_{n=1}^{40} A_n B_n
  double hb = 0.0;  ///< sum_{n=1}^{20} h_n B_n
};

/// \ref visco_averaged "docs/viscoelastic.md" sums over the series index n with B_n = (1/2) Gamma(2 + n/20) beta^(n/2) (2 s)^(n/20).
SeriesSums series_sums(double u) {
  const auto& g = half_gamma();
  SeriesSums sums;
  double power = 1.0;
  for (int n = 1; n <= square_terms; ++n) {
    power *= u;
    const double b_n = g[n] * power;
    sums.ab += a_coeff[n] * b_n;
    if (n <= restitution_series_terms) sums.hb += h_coeff[n] * b_n;
  }
  return sums;
}

/// A3 (\ref visco_averaged "docs/viscoelastic.md"): tau_v,ki^-1 = base_ki X_ki (1 + (1/2) sum_n A_n B_n).
double inverse_tau_viscoelastic(const Mixture& mix, const PairMatrix& beta,
                                std::span<const double> T, std::size_t k, std::size_t i) {
  const SeriesSums sums = series_sums(typical_u(beta(k, i), thermal_speed_sum(mix, T, k, i)));
  return base_rate(mix, T, k, i) * x_factor(mix, T, k, i) * (1.0 + 0.5 * sums.ab);
}

/// A4 (\ref visco_averaged "docs/viscoelastic.md"): xi_ki = 2 base_ki [1 - X_ki + sum_n B_n (h_n - (1/2) X_ki A_n)].
double cooling_rate_viscoelastic(const Mixture& mix, const PairMatrix& beta,
                                 std::span<const double> T, std::size_t k, std::size_t i) {
  const SeriesSums sums = series_sums(typical_u(beta(k, i), thermal_speed_sum(mix, T, k, i)));
  const double x = x_factor(mix, T, k, i);
  return 2.0 * base_rate(mix, T, k, i) * (1.0 - x + sums.hb - 0.5 * x * sums.ab);
}

/// Throws std::domain_error if some pair's typical u exceeds the series cut-off (diffusion.hpp).
void require_within_cutoff(const Mixture& mix, const PairMatrix& beta, std::span<const double> T,
                           const char* caller) {
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t i = 0; i < mix.size(); ++i) {
      const double u = typical_u(beta(k, i), thermal_speed_sum(mix, T, k, i));
      if (u > viscoelastic_u_max)
        throw std::domain_error(
            std::string(caller) + ": typical u = beta^(1/2) (2 s)^(1/20) = " + std::to_string(u) +
            " of pair (" + std::to_string(k) + ", " + std::to_string(i) +
            ") exceeds the series cut-off " + std::to_string(viscoelastic_u_max));
    }
}

/// tau_v,k^-1 = sum_i tau_v,ki^-1 (Bodrova and Osinsky 2024, eq. (20), \ref dif_coefficients "docs/diffusion-msd.md"), A1 or (beta) A3.
double inverse_tau_row(const Mixture& mix, const PairMatrix* beta, std::span<const double> T,
                       std::size_t k) {
  double sum = 0.0;
  for (std::size_t i = 0; i < mix.size(); ++i)
    sum +=
        beta ? inverse_tau_viscoelastic(mix, *beta, T, k, i) : inverse_tau_constant(mix, T, k, i);
  return sum;
}

/// unique_ptr to a C object released by Free.
template <class Pointer, auto Free>
struct FreeWith {
  void operator()(Pointer p) const { Free(p); }
};
template <class Pointer, auto Free>
using Owner = std::unique_ptr<std::remove_pointer_t<Pointer>, FreeWith<Pointer, Free>>;

// ---------------------------------------------------------------------------------------------
// GSL quadrature
// ---------------------------------------------------------------------------------------------

/// Switches GSL's abort-on-error handler off for its lifetime (restores the previous one).
struct GslErrorsReturned {
  gsl_error_handler_t* previous = gsl_set_error_handler_off();
  GslErrorsReturned() = default;
  GslErrorsReturned(const GslErrorsReturned&) = delete;
  GslErrorsReturned& operator=(const GslErrorsReturned&) = delete;
  ~GslErrorsReturned() { gsl_set_error_handler(previous); }
};

class Quadrature {
 public:
  Quadrature() : workspace_(gsl_integration_workspace_alloc(limit)) {
    if (!workspace_) throw std::runtime_error("gsl_integration_workspace_alloc failed");
  }
  /// int_a^b f with gsl_integration_qag (rule key GSL_INTEG_GAUSS15..61), relative tolerance rtol.
  template <class F>
  double integrate(F& f, double a, double b, double rtol, int key) {
    gsl_function fn{[](double x, void* p) { return (*static_cast<F*>(p))(x); }, &f};
    double result = 0.0, error = 0.0;
    const int status =
        gsl_integration_qag(&fn, a, b, 0.0, rtol, limit, key, workspace_.get(), &result, &error);
    // A round-off stop is accepted when the error estimate is still small.
    if (status != GSL_SUCCESS && !(status == GSL_EROUND && error <= 1e-8 * std::abs(result)))
      throw std::runtime_error(std::string("gsl_integration_qag failed: ") + gsl_strerror(status));
    return result;
  }

 private:
  static constexpr std::size_t limit = 1000;
  GslErrorsReturned handler_;
  std::unique_ptr<gsl_integration_workspace,
                  FreeWith<gsl_integration_workspace*, gsl_integration_workspace_free>>
      workspace_;
};

// ---------------------------------------------------------------------------------------------
// Dense solution T_k(t), tau_k(t) on a node grid (diffusion.hpp, "Numerics of the MSD")
// ---------------------------------------------------------------------------------------------

constexpr double nodes_per_unit_s = 64.0;
constexpr std::size_t nodes_per_piece = 32;
constexpr double tau_rtol = 1e-12;
constexpr double msd_rtol = 1e-10;

/// Cubic Hermite interpolation on [0, 1] with values y0, y1 and slopes d0, d1 (per unit x) times h.
double hermite(double x, double h, double y0, double d0, double y1, double d1) {
  const double xm = 1.0 - x;
  return (1.0 + 2.0 * x) * xm * xm * y0 + x * xm * xm * h * d0 + x * x * (3.0 - 2.0 * x) * y1 -
         x * x * xm * h * d1;
}

class DenseSolution {
 public:
  DenseSolution(const Mixture& mix, const PairMatrix* beta, const std::vector<double>& T0,
                double t_max)
      : species_(mix.size()), log_T0_(species_) {
    for (std::size_t k = 0; k < species_; ++k) log_T0_[k] = std::log(T0[k]);
    // Node grid uniform in s = ln(1 + t/t_c), t_c = 1/max_k(tau_v,k^-1 + sum_i |xi_ki|) at t = 0.
    const PairMatrix xi0 =
        beta ? cooling_rate_matrix_viscoelastic(mix, *beta, T0) : cooling_rate_matrix(mix, T0);
    double fastest = 0.0;
    for (std::size_t k = 0; k < species_; ++k) {
      double rate = inverse_tau_row(mix, beta, T0, k);
      for (std::size_t i = 0; i < species_; ++i) rate += std::abs(xi0(k, i));
      fastest = std::max(fastest, rate);
    }
    if (!(fastest > 0.0) || !std::isfinite(fastest))
      throw std::invalid_argument("mean_squared_displacement: no collisions (zero rates)");
    const double t_c = 1.0 / fastest;
    const double s_max = std::log1p(t_max / t_c);
    const auto intervals =
        std::max<std::size_t>(16, static_cast<std::size_t>(std::ceil(s_max * nodes_per_unit_s)));
    time_.resize(intervals + 1);
    for (std::size_t i = 0; i <= intervals; ++i)
      time_[i] = t_c * std::expm1(s_max * static_cast<double>(i) / static_cast<double>(intervals));
    time_.front() = 0.0;
    time_.back() = t_max;

    const TemperatureHistory history =
        beta ? integrate_partial_temperatures_viscoelastic(mix, *beta, T0, time_)
             : integrate_partial_temperatures(mix, T0, time_);
    log_T_.resize(time_.size() * species_);
    slope_.resize(time_.size() * species_);
    for (std::size_t i = 0; i < time_.size(); ++i) {
      const std::vector<double>& T = history.temperature[i];
      // d ln T_k/dt = -sum_i xi_ki: \ref haff_mixture_odes "docs/haff-and-mixtures.md" (partial_temperature_rates) or A4.
      std::vector<double> rate;
      if (beta) {
        const PairMatrix xi = cooling_rate_matrix_viscoelastic(mix, *beta, T);
        rate.assign(species_, 0.0);
        for (std::size_t k = 0; k < species_; ++k)
          for (std::size_t j = 0; j < species_; ++j) rate[k] -= xi(k, j);
      } else {
        rate = partial_temperature_rates(mix, T);
        for (std::size_t k = 0; k < species_; ++k) rate[k] /= T[k];
      }
      for (std::size_t k = 0; k < species_; ++k) {
        log_T_[i * species_ + k] = std::log(T[k]);
        slope_[i * species_ + k] = rate[k];
      }
    }

    // tau_k at the nodes: GSL quadrature of sqrt(T_k/T_k(0)) over each interval of the interpolant.
    tau_.assign(time_.size() * species_, 0.0);
    Quadrature quadrature;
    for (std::size_t i = 0; i + 1 < time_.size(); ++i)
      for (std::size_t k = 0; k < species_; ++k) {
        auto speed_ratio = [&](double t) {
          return std::exp(0.5 * (log_T_at(i, k, t) - log_T0_[k]));
        };
        tau_[(i + 1) * species_ + k] =
            tau_[i * species_ + k] +
            quadrature.integrate(speed_ratio, time_[i], time_[i + 1], tau_rtol, GSL_INTEG_GAUSS15);
      }
  }

  const std::vector<double>& nodes() const { return time_; }

  /// T_k(t) and tau_k(t) for every k, t in [0, t_max].
  void evaluate(double t, std::span<double> T, std::span<double> tau) const {
    const std::size_t i = interval_of(t);
    const double h = time_[i + 1] - time_[i];
    const double x = std::clamp((t - time_[i]) / h, 0.0, 1.0);
    for (std::size_t k = 0; k < species_; ++k) {
      T[k] = std::exp(log_T_at(i, k, t));
      const double r0 = std::exp(0.5 * (log_T_[i * species_ + k] - log_T0_[k]));
      const double r1 = std::exp(0.5 * (log_T_[(i + 1) * species_ + k] - log_T0_[k]));
      tau[k] = hermite(x, h, tau_[i * species_ + k], r0, tau_[(i + 1) * species_ + k], r1);
    }
  }

 private:
  std::size_t interval_of(double t) const {
    const auto after = std::upper_bound(time_.begin(), time_.end(), t);
    const auto index = static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - time_.begin(), 1));
    return std::min(index - 1, time_.size() - 2);
  }
  double log_T_at(std::size_t i, std::size_t k, double t) const {
    const double h = time_[i + 1] - time_[i];
    const double x = std::clamp((t - time_[i]) / h, 0.0, 1.0);
    return hermite(x, h, log_T_[i * species_ + k], slope_[i * species_ + k],
                   log_T_[(i + 1) * species_ + k], slope_[(i + 1) * species_ + k]);
  }

  std::size_t species_;
  std::vector<double> log_T0_;
  std::vector<double> time_;
  std::vector<double> log_T_, slope_, tau_;  // [node * species + k]
};

/// Eq 17 (long_time = false) or eq 21 (long_time = true) with eq 16, see diffusion.hpp.
MsdResult displacement(const Mixture& mix, const std::vector<double>& T0,
                       const std::vector<double>& times, const PairMatrix* beta, bool long_time,
                       const char* caller) {
  if (mix.size() == 0) throw std::invalid_argument(std::string(caller) + ": no species");
  require_temperatures(mix, T0, caller);
  require_times(times, caller);
  if (beta) {
    require_beta(mix, *beta, caller);
    require_within_cutoff(mix, *beta, T0, caller);
  }
  const std::size_t species = mix.size();
  MsdResult result;
  result.time = times;
  result.msd.assign(times.size(), std::vector<double>(species, 0.0));
  result.total.assign(times.size(), 0.0);
  if (times.empty() || times.back() == 0.0) return result;

  const DenseSolution solution(mix, beta, T0, times.back());
  const std::vector<double>& nodes = solution.nodes();
  Quadrature quadrature;
  std::vector<double> T(species), tau(species), tau_now(species);
  for (std::size_t it = 0; it < times.size(); ++it) {
    const double t = times[it];
    if (t == 0.0) continue;
    solution.evaluate(t, T, tau_now);
    for (std::size_t k = 0; k < species; ++k) {
      // Integrand of eq 17: D_k(t1) [1 - exp(-(tau_k(t) - tau_k(t1))/tauhat_v,k(t1))] (eqs 18, 19).
      auto integrand = [&](double t1) {
        solution.evaluate(t1, T, tau);
        const double inverse_tau_v = inverse_tau_row(mix, beta, T, k);   // eq 20
        const double d_k = T[k] / (mix.mass[k] * inverse_tau_v);         // eq 19
        if (long_time) return d_k;                                       // eq 21
        const double tau_hat = std::sqrt(T[k] / T0[k]) / inverse_tau_v;  // eq 18
        const double x = std::max(0.0, (tau_now[k] - tau[k]) / tau_hat);
        return -d_k * std::expm1(-x);
      };
      double integral = 0.0, a = 0.0;
      for (std::size_t node = nodes_per_piece; a < t; node += nodes_per_piece) {
        const double b = node < nodes.size() ? std::min(nodes[node], t) : t;
        integral += quadrature.integrate(integrand, a, b, msd_rtol, GSL_INTEG_GAUSS21);
        a = b;
      }
      result.msd[it][k] = 6.0 * integral;  // eq 17 / eq 21
    }
    double total = 0.0;
    for (std::size_t k = 0; k < species; ++k) total += mix.number_density[k] * result.msd[it][k];
    result.total[it] = total / mix.total_density();  // eq 16
  }
  return result;
}

}  // namespace

// -------------------------------------------------------------------------------------------------
// Viscoelastic restitution (\ref visco_series "docs/viscoelastic.md")
// -------------------------------------------------------------------------------------------------

double restitution_series_coefficient(int j) {
  if (j < 1 || j > restitution_series_terms)
    throw std::out_of_range("restitution_series_coefficient: j must be in 1..20");
  return h_coeff[j];
}

double restitution_series_square_coefficient(int n) {
  if (n < 1 || n > square_terms)
    throw std::out_of_range("restitution_series_square_coefficient: n must be in 1..40");
  return a_coeff[n];
}

// -------------------------------------------------------------------------------------------------
// Velocity correlation times and cooling rates (\ref dif_correlation_time "docs/diffusion-msd.md")
// -------------------------------------------------------------------------------------------------

PairMatrix velocity_correlation_base_rate(const Mixture& mix,
                                          const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "velocity_correlation_base_rate");
  PairMatrix base(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t i = 0; i < mix.size(); ++i) base(k, i) = base_rate(mix, temperature, k, i);
  return base;
}

PairMatrix inverse_velocity_correlation_time(const Mixture& mix,
                                             const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "inverse_velocity_correlation_time");
  PairMatrix rate(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t i = 0; i < mix.size(); ++i)
      rate(k, i) = inverse_tau_constant(mix, temperature, k, i);  // A1
  return rate;
}

PairMatrix inverse_velocity_correlation_time_viscoelastic(const Mixture& mix,
                                                          const PairMatrix& beta,
                                                          const std::vector<double>& temperature) {
  constexpr const char* caller = "inverse_velocity_correlation_time_viscoelastic";
  require_temperatures(mix, temperature, caller);
  require_beta(mix, beta, caller);
  require_within_cutoff(mix, beta, temperature, caller);
  PairMatrix rate(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t i = 0; i < mix.size(); ++i)
      rate(k, i) = inverse_tau_viscoelastic(mix, beta, temperature, k, i);  // A3
  return rate;
}

PairMatrix cooling_rate_matrix_viscoelastic(const Mixture& mix, const PairMatrix& beta,
                                            const std::vector<double>& temperature) {
  constexpr const char* caller = "cooling_rate_matrix_viscoelastic";
  require_temperatures(mix, temperature, caller);
  require_beta(mix, beta, caller);
  require_within_cutoff(mix, beta, temperature, caller);
  PairMatrix xi(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k)
    for (std::size_t i = 0; i < mix.size(); ++i)
      xi(k, i) = cooling_rate_viscoelastic(mix, beta, temperature, k, i);  // A4
  return xi;
}

std::vector<double> diffusion_coefficients(const Mixture& mix,
                                           const std::vector<double>& temperature,
                                           const PairMatrix* beta) {
  require_temperatures(mix, temperature, "diffusion_coefficients");
  if (beta) {
    require_beta(mix, *beta, "diffusion_coefficients");
    require_within_cutoff(mix, *beta, temperature, "diffusion_coefficients");
  }
  std::vector<double> d(mix.size());
  for (std::size_t k = 0; k < mix.size(); ++k)  // Bodrova and Osinsky 2024, eqs. (19)-(20), \ref dif_coefficients "docs/diffusion-msd.md"
    d[k] = temperature[k] / (mix.mass[k] * inverse_tau_row(mix, beta, temperature, k));
  return d;
}

std::vector<double> diffusion_coefficient_ratio(const Mixture& mix,
                                                const std::vector<double>& temperature,
                                                const PairMatrix* beta) {
  std::vector<double> d = diffusion_coefficients(mix, temperature, beta);
  if (d.empty()) throw std::invalid_argument("diffusion_coefficient_ratio: no species");
  const double d1 = d[0];
  for (double& value : d) value /= d1;
  return d;
}

std::vector<double> diffusion_coefficient_ratio(const Mixture& mix) {
  std::vector<double> temperature = asymptotic_temperature_ratios(mix);  // \ref haff_ratios "docs/haff-and-mixtures.md", T_1 = 1 unit
  for (double& t : temperature) t *= mix.mass[0];  // any scale: D_k is homogeneous in T
  return diffusion_coefficient_ratio(mix, temperature);
}

// -------------------------------------------------------------------------------------------------
// Second approximation for tracer diffusion (Chapman and Cowling, ch. 9-10;
// \ref dif_second_approximation "docs/diffusion-msd.md")
// -------------------------------------------------------------------------------------------------

TracerSonineMatrix tracer_sonine_matrix(double m_tracer, double m_partner) {
  if (!(m_tracer > 0.0 && std::isfinite(m_tracer) && m_partner > 0.0 && std::isfinite(m_partner)))
    throw std::invalid_argument("tracer_sonine_matrix: masses must be positive and finite");
  // M = partner mass fraction; the closed forms of \ref dif_second_approximation "docs/diffusion-msd.md".
  const double M = m_partner / (m_tracer + m_partner);
  TracerSonineMatrix a;
  a.a00 = M * M / 3.0;
  a.a01 = -M * M * M / 6.0;
  a.a11 = M * M * (27.0 * M * M - 44.0 * M + 30.0) / 12.0;
  return a;
}

std::vector<double> tracer_diffusion_second_approximation_ratio(const Mixture& mix) {
  std::vector<double> ratio(mix.size(), 1.0);
  for (std::size_t k = 0; k < mix.size(); ++k) {
    // A_pq = sum_i n_i sigma_ki^2 chi_ki mu_ki^(-3/2) a_pq(m_k, m_i) (common factors dropped:
    // pi <g^3> mu^(3/2) = 16 sqrt(pi/2) T^(3/2) is the same for every partner at one temperature).
    double a00 = 0.0, a01 = 0.0, a11 = 0.0;
    for (std::size_t i = 0; i < mix.size(); ++i) {
      const double sigma = mix.contact_distance(k, i);
      const double weight = mix.number_density[i] * sigma * sigma * mix.pair_correlation(k, i) *
                            std::pow(mix.reduced_mass(k, i), -1.5);
      const auto a = tracer_sonine_matrix(mix.mass[k], mix.mass[i]);
      a00 += weight * a.a00;
      a01 += weight * a.a01;
      a11 += weight * a.a11;
    }
    if (!(a00 > 0.0 && a11 > 0.0))
      throw std::invalid_argument("tracer_diffusion_second_approximation_ratio: species without partners");
    ratio[k] = 1.0 / (1.0 - a01 * a01 / (a00 * a11));  // [D]_2/[D]_1 = 1/(1 - Delta)
  }
  return ratio;
}

// -------------------------------------------------------------------------------------------------
// Second Sonine approximation for inelastic tracer diffusion in the homogeneous cooling state
// (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md")
// -------------------------------------------------------------------------------------------------

namespace {

/// Nodes and weights of an n-point GSL fixed rule (Legendre on [a, b], or Hermite with weight e^(-x^2)).
struct FixedRule {
  std::vector<double> node, weight;
};

FixedRule fixed_rule(const gsl_integration_fixed_type* type, std::size_t n, double a, double b) {
  std::unique_ptr<gsl_integration_fixed_workspace, decltype(&gsl_integration_fixed_free)> w(
      gsl_integration_fixed_alloc(type, n, a, b, 0.0, 0.0), &gsl_integration_fixed_free);
  if (!w) throw std::runtime_error("inelastic_tracer_sonine_matrix: GSL fixed quadrature rule not available");
  FixedRule rule;
  rule.node.assign(gsl_integration_fixed_nodes(w.get()), gsl_integration_fixed_nodes(w.get()) + n);
  rule.weight.assign(gsl_integration_fixed_weights(w.get()), gsl_integration_fixed_weights(w.get()) + n);
  return rule;
}

}  // namespace

namespace {

/// S_p(x) = L_p^(3/2)(x), p = 0, 1, 2 (x = c^2): the Sonine polynomials of the vector functions v S_p.
inline double sonine_vector(int p, double x) {
  switch (p) {
    case 0: return 1.0;
    case 1: return 2.5 - x;
    default: return 0.5 * x * x - 3.5 * x + 35.0 / 8.0;
  }
}

}  // namespace

InelasticTracerSonine inelastic_tracer_sonine_matrix(double m_tracer, double t_tracer, double m_partner,
                                                     double t_partner, double alpha) {
  if (!(m_tracer > 0.0 && std::isfinite(m_tracer) && m_partner > 0.0 && std::isfinite(m_partner) &&
        t_tracer > 0.0 && std::isfinite(t_tracer) && t_partner > 0.0 && std::isfinite(t_partner)))
    throw std::invalid_argument("inelastic_tracer_sonine_matrix: masses and temperatures must be positive and finite");
  if (!(alpha >= 0.0 && alpha <= 1.0))
    throw std::invalid_argument("inelastic_tracer_sonine_matrix: restitution must lie in [0, 1]");
  // Velocities: v ~ N(0, a2) per component (tracer), v_p ~ N(0, b2) (partner); g = v - v_p ~ N(0, s2).
  // Given g, v = beta g + w with w ~ N(0, a2 b2/s2) independent of g (Gaussian conditioning), so the
  // pair average is an integral over |g| (g along z: the whole average is rotation invariant), over
  // the collision direction e on the hemisphere e.g > 0 and over w. The integrands are polynomials in
  // w of degree <= 10 and in the components of e of degree <= 9 (times the weight e.g), so the
  // 6-point Hermite rule (exact to degree 11), the 10-point Legendre rule in cos(theta) and the
  // 20-point trapezoidal rule in phi are exact; the |g| integral, a polynomial times
  // g^2 exp(-g^2/(2 s2)), uses 72 Legendre nodes on [0, 13 s], converged to round-off (1e-13).
  const double a2 = t_tracer / m_tracer, b2 = t_partner / m_partner, s2 = a2 + b2, s = std::sqrt(s2);
  const double beta = a2 / s2, w_scale = std::sqrt(2.0 * a2 * b2 / s2);
  const double impulse = m_partner / (m_tracer + m_partner) * (1.0 + alpha);  // mu_pt (1 + alpha)
  const double v02 = 2.0 * a2;                                                 // c^2 = v^2/v02
  static const FixedRule hermite = fixed_rule(gsl_integration_fixed_hermite, 6, 0.0, 1.0);
  static const FixedRule cosine = fixed_rule(gsl_integration_fixed_legendre, 10, 0.0, 1.0);
  const FixedRule speed = fixed_rule(gsl_integration_fixed_legendre, 72, 0.0, 13.0 * s);
  constexpr int azimuths = 20;
  constexpr int n = InelasticTracerSonine::terms;
  const double pi = std::numbers::pi;
  const double hermite_norm = std::pow(pi, -1.5);                      // E over w
  const double speed_norm = 4.0 * pi * std::pow(2.0 * pi * s2, -1.5);  // density of |g|
  // The collision directions relative to g (along z): (e_x, e_y, e_z = u) and the weight du dphi.
  struct Direction {
    double x, y, u, weight;
  };
  std::vector<Direction> directions;
  for (std::size_t iu = 0; iu < cosine.node.size(); ++iu) {
    const double u = cosine.node[iu], sin_t = std::sqrt(1.0 - u * u);
    for (int iphi = 0; iphi < azimuths; ++iphi) {
      const double phi = 2.0 * pi * (iphi + 0.5) / azimuths;
      directions.push_back({sin_t * std::cos(phi), sin_t * std::sin(phi), u, cosine.weight[iu] * 2.0 * pi / azimuths});
    }
  }
  std::array<std::array<double, n>, n> e{};  // e[p][q] = E[S_q(c^2) int de (g.e) v.(v' S_p(c'^2) - v S_p(c^2))]
  double energy = 0.0;                       // E[int de (g.e) (v'^2 - v^2)]
  for (std::size_t ig = 0; ig < speed.node.size(); ++ig) {
    const double g = speed.node[ig];
    const double g_weight = speed.weight[ig] * speed_norm * g * g * std::exp(-g * g / (2.0 * s2));
    std::array<std::array<double, n>, n> f{};
    double fe = 0.0;
    for (std::size_t ia = 0; ia < hermite.node.size(); ++ia)
      for (std::size_t ib = 0; ib < hermite.node.size(); ++ib)
        for (std::size_t ic = 0; ic < hermite.node.size(); ++ic) {
          const double w_weight = hermite.weight[ia] * hermite.weight[ib] * hermite.weight[ic] * hermite_norm;
          const double vx = w_scale * hermite.node[ia], vy = w_scale * hermite.node[ib];
          const double vz = beta * g + w_scale * hermite.node[ic];
          const double v2 = vx * vx + vy * vy + vz * vz, c2 = v2 / v02;
          std::array<double, n> sq{}, h{};
          for (int p = 0; p < n; ++p) sq[p] = sonine_vector(p, c2);
          double he = 0.0;
          for (const Direction& d : directions) {
            const double ge = g * d.u;
            const double kick = impulse * ge;  // v' = v - mu (1 + alpha)(g.e) e
            const double px = vx - kick * d.x, py = vy - kick * d.y, pz = vz - kick * d.u;
            const double vp2 = px * px + py * py + pz * pz, cp2 = vp2 / v02;
            const double vdotvp = vx * px + vy * py + vz * pz;
            const double weight = d.weight * ge;
            for (int p = 0; p < n; ++p) h[p] += weight * (vdotvp * sonine_vector(p, cp2) - v2 * sq[p]);
            he += weight * (vp2 - v2);
          }
          for (int p = 0; p < n; ++p)
            for (int q = 0; q < n; ++q) f[p][q] += w_weight * sq[q] * h[p];
          fe += w_weight * he;
        }
    for (int p = 0; p < n; ++p)
      for (int q = 0; q < n; ++q) e[p][q] += g_weight * f[p][q];
    energy += g_weight * fe;
  }
  InelasticTracerSonine r;
  for (int p = 0; p < n; ++p)
    for (int q = 0; q < n; ++q) r.l[p][q] = -e[p][q] / v02;
  r.cooling = -(2.0 / (3.0 * t_tracer)) * 0.5 * m_tracer * energy;  // xi: dT/dt = -xi T
  return r;
}

double tracer_sonine_cooling_matrix(int p, int q) {
  // Z_pq = <c^2 S_p [(2 - c^2) S_q + c^2 S_q']> over the Maxwellian, by hand with <c^(2j)> =
  // Gamma(j + 3/2)/Gamma(3/2) (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md").
  static constexpr double z[3][3] = {{-0.75, 0.0, 0.0}, {3.75, -5.625, 0.0}, {0.0, 13.125, -16.40625}};
  if (p < 0 || p > 2 || q < 0 || q > 2) throw std::out_of_range("tracer_sonine_cooling_matrix: p, q in 0..2");
  return z[p][q];
}

std::array<std::vector<double>, 3> tracer_diffusion_sonine_ratios(const Mixture& mix,
                                                                  const std::vector<double>& temperature) {
  require_temperatures(mix, temperature, "tracer_diffusion_sonine_ratio");
  constexpr int n = InelasticTracerSonine::terms;
  std::array<std::vector<double>, 3> ratio;
  for (auto& r : ratio) r.assign(mix.size(), 1.0);
  for (std::size_t k = 0; k < mix.size(); ++k) {
    std::array<std::array<double, n>, n> l{};
    double zeta = 0.0;
    for (std::size_t i = 0; i < mix.size(); ++i) {
      const double sigma = mix.contact_distance(k, i);
      const double weight = mix.number_density[i] * sigma * sigma * mix.pair_correlation(k, i);
      if (weight == 0.0) continue;
      const auto e = inelastic_tracer_sonine_matrix(mix.mass[k], temperature[k], mix.mass[i], temperature[i],
                                                    mix.restitution(k, i));
      for (int p = 0; p < n; ++p)
        for (int q = 0; q < n; ++q) l[p][q] += weight * e.l[p][q];
      zeta += weight * e.cooling;
    }
    const double first = 1.0 / (l[0][0] + zeta * tracer_sonine_cooling_matrix(0, 0));
    if (!(first > 0.0))
      throw std::invalid_argument("tracer_diffusion_sonine_ratio: no positive first Sonine diffusion coefficient "
                                  "(species without partners?)");
    for (int terms = 2; terms <= n; ++terms) {
      // Solve (L + zeta Z) a = -(3/2, 0, 0) in the first `terms` functions; D is proportional to -a_0
      // (the common factor 3/2 cancels in the ratio).
      double m[3][4] = {};
      for (int p = 0; p < terms; ++p) {
        for (int q = 0; q < terms; ++q) m[p][q] = l[p][q] + zeta * tracer_sonine_cooling_matrix(p, q);
        m[p][terms] = p == 0 ? 1.0 : 0.0;
      }
      bool singular = false;
      for (int c = 0; c < terms && !singular; ++c) {  // Gauss-Jordan elimination with partial pivoting (at most 3 x 3)
        int pivot = c;
        for (int r = c + 1; r < terms; ++r)
          if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
        for (int q = 0; q <= terms; ++q) std::swap(m[c][q], m[pivot][q]);
        if (!(std::abs(m[c][c]) > 0.0)) {
          singular = true;
          break;
        }
        for (int r = 0; r < terms; ++r) {
          if (r == c) continue;
          const double factor = m[r][c] / m[c][c];
          for (int q = c; q <= terms; ++q) m[r][q] -= factor * m[c][q];
        }
      }
      const double a0 = singular ? 0.0 : m[0][terms] / m[0][0];
      // A heavy, dilute tracer can relax its higher Sonine modes more slowly than the gas cools: the
      // truncated normal solution then has no positive D (the diagonal l_pp + zeta Z_pp < 0). No estimate
      // exists there: NaN, which callers must test (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md").
      ratio[terms - 1][k] = a0 > 0.0 ? a0 / first : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return ratio;
}

std::vector<double> tracer_diffusion_sonine_ratio(const Mixture& mix, const std::vector<double>& temperature,
                                                  int terms) {
  if (terms < 1 || terms > InelasticTracerSonine::terms)
    throw std::invalid_argument("tracer_diffusion_sonine_ratio: terms must be 1, 2 or 3");
  return tracer_diffusion_sonine_ratios(mix, temperature)[terms - 1];
}

// -------------------------------------------------------------------------------------------------
// Partial temperatures with viscoelastic restitution
// -------------------------------------------------------------------------------------------------

TemperatureHistory integrate_partial_temperatures_viscoelastic(
    const Mixture& mix, const PairMatrix& beta, const std::vector<double>& initial_temperature,
    const std::vector<double>& times) {
  constexpr const char* caller = "integrate_partial_temperatures_viscoelastic";
  require_temperatures(mix, initial_temperature, caller);
  require_beta(mix, beta, caller);
  require_times(times, caller);
  require_within_cutoff(mix, beta, initial_temperature, caller);

  // State y_k = ln(T_k/T_ref), T_ref = sum_k x_k T_k(0); y_S = collisions per unit volume. The same
  // tolerances as integrate_partial_temperatures (theory.hpp, "Numerical integration").
  const std::size_t species = mix.size();
  double reference = 0.0;
  for (std::size_t k = 0; k < species; ++k)
    reference += mix.mole_fraction(k) * initial_temperature[k];
  std::vector<double> y0(species + 1, 0.0);
  for (std::size_t k = 0; k < species; ++k) y0[k] = std::log(initial_temperature[k] / reference);
  std::vector<double> rtol(species + 1, 0.0), atol(species + 1, 1e-11);
  rtol[species] = 1e-10;
  atol[species] = 1e-12 * mix.total_density();

  std::vector<double> T(species);
  auto rhs = [&](std::span<const double> y, std::span<double> dydt) {
    for (std::size_t k = 0; k < species; ++k) T[k] = reference * std::exp(y[k]);
    require_within_cutoff(mix, beta, T, caller);
    for (std::size_t k = 0; k < species; ++k) {
      double sum = 0.0;
      for (std::size_t i = 0; i < species; ++i)
        sum += cooling_rate_viscoelastic(mix, beta, T, k, i);
      dydt[k] = -sum;  // Bodrova and Osinsky 2024, eqs. (22)-(23), \ref visco_averaged "docs/viscoelastic.md" with A4: d ln T_k/dt = -sum_i xi_ki
    }
    dydt[species] = total_collision_rate(mix, T);  // \ref cm_mixture_rate "docs/collision-model.md"
  };
  detail::CvodeSolver solver([&rhs](double, std::span<const double> y, std::span<double> dy) { rhs(y, dy); },
                             y0, rtol, atol);

  TemperatureHistory history;
  history.time = times;
  for (double t : times) {
    if (t > 0.0) solver.advance_to(t);
    const auto y = solver.state();
    std::vector<double> now(species);
    for (std::size_t k = 0; k < species; ++k) now[k] = reference * std::exp(y[k]);
    history.temperature.push_back(std::move(now));
    history.collisions.push_back(y[species]);
  }
  return history;
}

// -------------------------------------------------------------------------------------------------
// Mean squared displacement
// -------------------------------------------------------------------------------------------------

MsdResult mean_squared_displacement(const Mixture& mix,
                                    const std::vector<double>& initial_temperature,
                                    const std::vector<double>& times, const PairMatrix* beta) {
  return displacement(mix, initial_temperature, times, beta, false, "mean_squared_displacement");
}

MsdResult long_time_msd(const Mixture& mix, const std::vector<double>& initial_temperature,
                        const std::vector<double>& times, const PairMatrix* beta) {
  return displacement(mix, initial_temperature, times, beta, true, "long_time_msd");
}

}  // namespace gdsmc::theory
