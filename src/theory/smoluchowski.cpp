// Smoluchowski rate equations with Maxwellian partial temperatures (smoluchowski.hpp;
// the DSMC notes, eqs. (8)-(14), \ref af_outcome "docs/agg-frag.md").
#include "theory/smoluchowski.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>

#include "theory/cvode_solver.hpp"

namespace gdsmc::theory::smoluchowski {

namespace {

using detail::CvodeMethod;
using detail::CvodeOptions;
using detail::CvodeSolver;

constexpr double pi = std::numbers::pi;
constexpr double infinity = std::numeric_limits<double>::infinity();

// See smoluchowski.hpp, "Numerical integration".
constexpr std::size_t first_max_size = 64;
constexpr std::size_t largest_max_size = 16384;
constexpr double allowed_lost_mass = 1e-8;
// K doubles (and the integration goes on) when this much mass has been lost at the current K: at
// most 8 doublings from 64 to 16384 keep the total below the allowance.
constexpr double grow_lost_mass = 1e-12;
constexpr double relative_tolerance = 1e-9;
constexpr double density_tolerance = 1e-15;  // on n_k/n_1(0)
constexpr double energy_tolerance = 1e-14;   // on E_k/(n_1(0) T0)
constexpr double count_tolerance = 1e-12;    // on events per initial monomer
constexpr double density_floor = 1e-18;      // n_floor/n_1(0) of the regularised T_k
constexpr double reported_density = 1e-300;  // below it Solution::temperature reports 0
// Pairs with a partner below it are skipped: their terms are < 1e-5 of the absolute tolerance per
// collision time (skipping a pair keeps the mass exactly, each pair conserves it on its own).
constexpr double negligible_density = 1e-20;
// ... and pairs whose densities multiply to less than this: at most ~1e-22 n_1(0) events per
// collision time, 1e-7 of the absolute tolerance on any n_k.
constexpr double negligible_product = 1e-22;

void require(bool condition, const char* caller, const std::string& message) {
  if (!condition) throw std::invalid_argument(std::string(caller) + ": " + message);
}

void check_parameters(const Parameters& p, const char* caller) {
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  require(positive(p.monomer_mass), caller, "monomer_mass must be positive and finite");
  require(positive(p.monomer_diameter), caller, "monomer_diameter must be positive and finite");
  require(positive(p.monomer_density), caller, "monomer_density must be positive and finite");
  require(positive(p.initial_temperature), caller,
          "initial_temperature must be positive and finite");
  require(p.restitution >= 0.0 && p.restitution <= 1.0, caller, "restitution must be in [0, 1]");
  require(p.aggregation_energy >= 0.0, caller, "aggregation_energy must be >= 0 (or infinity)");
  require(p.fragmentation_energy >= 0.0, caller,
          "fragmentation_energy must be >= 0 (or infinity)");
  require(p.fragment_restitution >= 0.0 && p.fragment_restitution <= 1.0, caller,
          "fragment_restitution must be in [0, 1]");
}

void check_pair(std::size_t k, std::size_t j, double T_k, double T_j, const char* caller) {
  require(k >= 1 && j >= 1, caller, "cluster sizes start at 1");
  require(T_k > 0.0 && T_j > 0.0 && std::isfinite(T_k) && std::isfinite(T_j), caller,
          "temperatures must be positive and finite");
}

// gamma(2, x) = 1 - (1 + x) e^-x and gamma(3, x) = 2 - (x^2 + 2x + 2) e^-x lose all digits to
// cancellation as x -> 0 (they behave like x^2/2 and x^3/3); below x = 1 use the series
// gamma(a, x) = Gamma(a) x^a e^-x sum_n x^n/Gamma(a + n + 1), whose terms are all positive.
// e = e^-x is passed in: both functions are needed at the same x and share it (one exp per pair).
double lower_gamma_series(int a, double x, double e) {
  double term = 1.0;
  for (int i = 2; i <= a; ++i) term /= i;  // 1/a!
  double sum = term;
  for (int n = 1; n < 40 && term > 1e-18 * sum; ++n) {
    term *= x / (a + n);
    sum += term;
  }
  const double gamma_a = a == 2 ? 1.0 : 2.0;  // Gamma(a) = (a - 1)!, a = 2 or 3
  double x_power_a = x * x;
  if (a == 3) x_power_a *= x;
  return gamma_a * x_power_a * e * sum;
}

double lower_gamma2(double x, double e) {
  if (x < 1.0) return lower_gamma_series(2, x, e);
  return 1.0 - (1.0 + x) * e;
}

double lower_gamma3(double x, double e) {
  if (x < 1.0) return lower_gamma_series(3, x, e);
  return 2.0 - (x * x + 2.0 * x + 2.0) * e;
}

// Integrals over the outcome regions of (x, U) with weight x e^-x dx dU (smoluchowski.hpp):
// probabilities, x-moments and the U-weighted x-moment of bounces.
struct RegionIntegrals {
  double p_agg = 0.0, p_frag = 0.0, p_bounce = 0.0;
  double x_agg = 0.0, x_frag = 0.0;  // I_agg = gamma(3, x_a), I_frag
  double xu_bounce = 0.0;            // J_b
};

// x_f = +infinity: this pair cannot fragment.
RegionIntegrals region_integrals(double x_a, double x_f) {
  RegionIntegrals r;
  if (std::isinf(x_a)) {  // every collision sticks
    r.p_agg = 1.0;
    r.x_agg = 2.0;
    return r;
  }
  const double e_a = std::exp(-x_a);
  r.p_agg = lower_gamma2(x_a, e_a);
  r.x_agg = lower_gamma3(x_a, e_a);
  double xu_frag = 0.0;
  const double x_m = std::max(x_a, x_f);
  // e^-700 ~ 1e-304: beyond it the region is empty in double precision, and the products below
  // could meet infinity * 0.
  if (x_m < 700.0) {
    // Written with d = x_m - x_f >= 0 so that no term cancels:
    // P_frag = Gamma(2, x_m) - x_f Gamma(1, x_m) = (1 + d) e^-x_m,
    // I_frag = Gamma(3, x_m) - x_f Gamma(2, x_m) = (x_m d + x_m + d + 2) e^-x_m,
    // [Gamma(3, x_m) - x_f^2 Gamma(1, x_m)]/2 = (d (x_m + x_f) + 2 x_m + 2) e^-x_m/2.
    const double d = x_m - x_f;
    const double tail = std::exp(-x_m);
    r.p_frag = (1.0 + d) * tail;
    r.x_frag = (x_m * d + x_m + d + 2.0) * tail;
    xu_frag = 0.5 * (d * (x_m + x_f) + 2.0 * x_m + 2.0) * tail;
  }
  r.p_bounce = std::max(0.0, 1.0 - r.p_agg - r.p_frag);
  r.xu_bounce = std::max(0.0, 1.0 - 0.5 * r.x_agg - xu_frag);
  return r;
}

// What a pair (k, j) needs that does not depend on the state.
struct PairConstants {
  double mass_k, mass_j, total_mass, reduced_mass;
  double cross_section;  // pi sigma_kj^2
  bool can_fragment;     // k + j >= 3 (\ref af_outcome "docs/agg-frag.md": two monomers never shatter)
};

// cube_root_k = cbrt(k), cube_root_j = cbrt(j) (sigma_k = k^(1/3) sigma_1), from the caller's table.
PairConstants pair_constants(const Parameters& p, std::size_t k, std::size_t j, double cube_root_k, double cube_root_j) {
  PairConstants c;
  c.mass_k = static_cast<double>(k) * p.monomer_mass;
  c.mass_j = static_cast<double>(j) * p.monomer_mass;
  c.total_mass = c.mass_k + c.mass_j;
  c.reduced_mass = c.mass_k * c.mass_j / c.total_mass;
  const double contact = 0.5 * p.monomer_diameter * (cube_root_k + cube_root_j);
  c.cross_section = pi * contact * contact;
  c.can_fragment = k + j >= 3 && !std::isinf(p.fragmentation_energy);
  return c;
}

PairConstants pair_constants(const Parameters& p, std::size_t k, std::size_t j) {
  return pair_constants(p, k, j, std::cbrt(static_cast<double>(k)), std::cbrt(static_cast<double>(j)));
}

// Region moments of one collision (smoluchowski.hpp, "Outcome of a collision"); s = theta_k +
// theta_j is passed in because the caller needs it for Lambda_kj as well.
PairMoments region_moments(const Parameters& p, const PairConstants& c, double T_k, double T_j,
                           double theta_k, double theta_j, double s) {
  const double impact_scale = c.reduced_mass * s;  // E_imp = m_kj s x
  const double x_a = p.aggregation_energy / impact_scale;
  const double x_f = c.can_fragment ? p.fragmentation_energy / impact_scale : infinity;
  const RegionIntegrals r = region_integrals(x_a, x_f);

  // E[m v^2/2 | x] = slope x + offset for each partner and for the centre of mass.
  const double slope_k = T_k * theta_k / s, offset_k = 1.5 * T_k * theta_j / s;
  const double slope_j = T_j * theta_j / s, offset_j = 1.5 * T_j * theta_k / s;
  const double mu_jk = c.mass_j / c.total_mass, mu_kj = c.mass_k / c.total_mass;
  const double drift = theta_k / s - mu_jk;  // E[V | g] = drift g
  const double slope_cm = c.total_mass * s * drift * drift;
  const double offset_cm = 1.5 * c.total_mass * theta_k * theta_j / s;
  // Bounce (\ref cm_rule "docs/collision-model.md"): E[Delta e_k | x, U] = 2 m_k mu_jk (1 + alpha) [mu_jk (1 + alpha) s/2 -
  // theta_k] x U.
  const double one_plus_alpha = 1.0 + p.restitution;
  const double bounce_k =
      2.0 * c.mass_k * mu_jk * one_plus_alpha * (0.5 * mu_jk * one_plus_alpha * s - theta_k);
  const double bounce_j =
      2.0 * c.mass_j * mu_kj * one_plus_alpha * (0.5 * mu_kj * one_plus_alpha * s - theta_j);

  PairMoments m;
  m.probability = {r.p_agg, r.p_frag, r.p_bounce};
  m.energy_k_agg = slope_k * r.x_agg + offset_k * r.p_agg;
  m.energy_j_agg = slope_j * r.x_agg + offset_j * r.p_agg;
  m.cm_energy_agg = slope_cm * r.x_agg + offset_cm * r.p_agg;
  m.energy_k_frag = slope_k * r.x_frag + offset_k * r.p_frag;
  m.energy_j_frag = slope_j * r.x_frag + offset_j * r.p_frag;
  m.cm_energy_frag = slope_cm * r.x_frag + offset_cm * r.p_frag;
  m.impact_energy_frag = impact_scale * r.x_frag;
  m.bounce_energy_change_k = bounce_k * r.xu_bounce;
  m.bounce_energy_change_j = bounce_j * r.xu_bounce;
  return m;
}

// The right-hand side of the rate equations for sizes 1..K in scaled variables:
// y[k-1] = n_k/n_1(0), y[K+k-1] = E_k/(n_1(0) T0), then lost mass fraction, aggregations,
// fragmentations and collisions per initial monomer. Every term belongs to one unordered pair
// (k, j): the right-hand side is a sum of pair contributions, each conserving mass on its own.
class RateEquations {
 public:
  RateEquations(const Parameters& p, std::size_t max_size, const Stop& stop)
      : p_(p), stop_(stop), max_size_(max_size), cube_root_(max_size), density_(max_size), temperature_(max_size) {
    // O(K) memory: a pair's constants are made when it is visited, not kept in a K x K table.
    for (std::size_t k = 1; k <= max_size; ++k) cube_root_[k - 1] = std::cbrt(static_cast<double>(k));
  }

  std::size_t state_size() const { return 2 * max_size_ + 4; }
  std::size_t density_index(std::size_t k) const { return k - 1; }
  std::size_t energy_index(std::size_t k) const { return max_size_ + k - 1; }
  std::size_t lost_index() const { return 2 * max_size_; }
  std::size_t aggregation_index() const { return 2 * max_size_ + 1; }
  std::size_t fragmentation_index() const { return 2 * max_size_ + 2; }
  std::size_t collision_index() const { return 2 * max_size_ + 3; }

  void rhs(std::span<const double> y, std::span<double> dydt) {
    if (stop_ && stop_()) throw Stopped();
    read_state(y);
    std::fill(dydt.begin(), dydt.end(), 0.0);
    for (std::size_t k = 1; k <= max_size_; ++k) {
      if (density_[k - 1] < negligible_density) continue;
      for (std::size_t j = k; j <= max_size_; ++j)
        add_pair(k, j, density_[k - 1], temperature_[k - 1], density_[j - 1],
                 temperature_[j - 1], 1.0, dydt.data());
    }
  }

  // T_k from the scaled state, as the right-hand side sees it (see smoluchowski.hpp).
  double regularised_temperature(double density, double energy) const {
    return p_.initial_temperature * (std::max(energy, 0.0) + 1.5 * density_floor * mean_temperature_) /
           (1.5 * (std::max(density, 0.0) + density_floor));
  }

 private:
  void read_state(std::span<const double> y) {
    double total_density = 0.0, total_energy = 0.0;
    for (std::size_t k = 1; k <= max_size_; ++k) {
      total_density += std::max(y[density_index(k)], 0.0);
      total_energy += std::max(y[energy_index(k)], 0.0);
    }
    // In units of T0; the mean temperature only serves sizes without clusters.
    mean_temperature_ = total_density > 0.0 ? total_energy / (1.5 * total_density) : 1.0;
    if (!(mean_temperature_ > 1e-300)) mean_temperature_ = 1e-300;
    for (std::size_t k = 1; k <= max_size_; ++k) {
      density_[k - 1] = std::max(y[density_index(k)], 0.0);
      temperature_[k - 1] = regularised_temperature(y[density_index(k)], y[energy_index(k)]);
    }
  }

  // Adds scale times the contributions of the unordered pair (k, j) (k may equal j) to the
  // scaled derivatives `out`, with n_k/n_1(0) = c_k and temperatures T_k.
  void add_pair(std::size_t k, std::size_t j, double c_k, double T_k, double c_j, double T_j,
                double scale, double* out) const {
    if (c_k < negligible_density || c_j < negligible_density || c_k * c_j < negligible_product) return;
    const PairConstants c = pair_constants(p_, k, j, cube_root_[k - 1], cube_root_[j - 1]);
    const double theta_k = T_k / c.mass_k, theta_j = T_j / c.mass_j;
    const double s = theta_k + theta_j;
    // Events per unit volume and time / n_1(0): w_kj for k != j, w_kk/2 (\ref cm_mixture_rate "docs/collision-model.md").
    const double lambda = c.cross_section * std::sqrt(8.0 * s / pi);
    const double events = scale * p_.monomer_density * c_k * c_j * lambda * (k == j ? 0.5 : 1.0);
    const PairMoments m = region_moments(p_, c, T_k, T_j, theta_k, theta_j, s);
    const double p_agg = m.probability.aggregation, p_frag = m.probability.fragmentation;
    const double energy_events = events / p_.initial_temperature;

    out[density_index(k)] -= events * (p_agg + p_frag);
    out[density_index(j)] -= events * (p_agg + p_frag);
    out[energy_index(k)] +=
        energy_events * (m.bounce_energy_change_k - m.energy_k_agg - m.energy_k_frag);
    out[energy_index(j)] +=
        energy_events * (m.bounce_energy_change_j - m.energy_j_agg - m.energy_j_frag);

    const std::size_t merged = k + j;
    if (merged <= max_size_) {
      out[density_index(merged)] += events * p_agg;
      out[energy_index(merged)] += energy_events * m.cm_energy_agg;
    } else {
      out[lost_index()] += events * static_cast<double>(merged) * p_agg;
    }

    // Complete fragmentation into k + j monomers sharing M V^2/2 + eps_f^2 E_imp (\ref af_energy_equation "docs/agg-frag.md").
    const double eps_f = p_.fragment_restitution;
    out[density_index(1)] += events * static_cast<double>(merged) * p_frag;
    out[energy_index(1)] += energy_events * (m.cm_energy_frag + eps_f * eps_f * m.impact_energy_frag);

    out[aggregation_index()] += events * p_agg;
    out[fragmentation_index()] += events * p_frag;
    out[collision_index()] += events;
  }

  Parameters p_;
  const Stop& stop_;
  std::size_t max_size_;
  std::vector<double> cube_root_;     // k^(1/3), k = 1..K
  std::vector<double> density_;       // clamped n_k/n_1(0)
  std::vector<double> temperature_;   // regularised T_k
  double mean_temperature_ = 1.0;     // in units of T0
};

void check_times(const std::vector<double>& times) {
  require(!times.empty(), "solve", "no output times");
  for (std::size_t i = 0; i < times.size(); ++i)
    require(std::isfinite(times[i]) && times[i] >= 0.0 && (i == 0 || times[i] > times[i - 1]),
            "solve", "times must be finite, non-negative and strictly increasing");
}

/// The state of RateEquations(max_size) for monomers at T0.
std::vector<double> initial_state(const RateEquations& equations) {
  std::vector<double> y0(equations.state_size(), 0.0);
  y0[equations.density_index(1)] = 1.0;
  y0[equations.energy_index(1)] = 1.5;  // (3/2) n_1 T0 in units of n_1(0) T0
  return y0;
}

/// `y` of RateEquations(from) as a state of RateEquations(to), to > from: sizes from + 1..to start
/// empty; lost mass and event counts are carried over.
std::vector<double> widened_state(const RateEquations& from, const RateEquations& to,
                                  std::span<const double> y) {
  std::vector<double> out(to.state_size(), 0.0);
  const std::size_t K = (from.state_size() - 4) / 2;
  for (std::size_t k = 1; k <= K; ++k) {
    out[to.density_index(k)] = y[from.density_index(k)];
    out[to.energy_index(k)] = y[from.energy_index(k)];
  }
  out[to.lost_index()] = y[from.lost_index()];
  out[to.aggregation_index()] = y[from.aggregation_index()];
  out[to.fragmentation_index()] = y[from.fragmentation_index()];
  out[to.collision_index()] = y[from.collision_index()];
  return out;
}

/// CVODE for RateEquations, from state y0 at time t0 (see smoluchowski.hpp, "Numerical integration").
std::unique_ptr<CvodeSolver> make_solver(RateEquations& equations, const std::vector<double>& y0,
                                         double t0) {
  const std::size_t n = equations.state_size();
  const std::size_t max_size = (n - 4) / 2;
  std::vector<double> rtol(n, relative_tolerance), atol(n, density_tolerance);
  for (std::size_t k = 1; k <= max_size; ++k) atol[equations.energy_index(k)] = energy_tolerance;
  atol[equations.aggregation_index()] = count_tolerance;
  atol[equations.fragmentation_index()] = count_tolerance;
  atol[equations.collision_index()] = count_tolerance;

  // Measured (bench_smoluchowski, sticking gas to <k> = 10, K up to 512): the system is not stiff,
  // CVODE takes 500-900 right-hand sides with any method, and Adams without linear algebra wins:
  // 1.9 s, against 4.1 s for BDF + matrix-free GMRES and 33 s for BDF + dense LU (2K + 4)^3.
  CvodeOptions options;
  options.method = CvodeMethod::adams_fixed_point;
  options.start_time = t0;
  return std::make_unique<CvodeSolver>(
      [&equations](double, std::span<const double> y, std::span<double> dydt) {
        equations.rhs(y, dydt);
      },
      y0, rtol, atol, options);
}

/// Integrates from monomers at t = 0 with `max_size` sizes. With `grow`, whenever the lost mass
/// passes grow_lost_mass the number of sizes is doubled and the integration goes on from the
/// current state (smoluchowski.hpp, "Numerical integration"); without, an integration whose lost mass
/// passes allowed_lost_mass is abandoned.
Solution integrate(const Parameters& p, std::size_t max_size, const std::vector<double>& times,
                   bool grow, const Stop& stop) {
  auto equations = std::make_unique<RateEquations>(p, max_size, stop);
  auto solver = make_solver(*equations, initial_state(*equations), 0.0);

  // Rows of the tables as they were written, each with the number of sizes integrated then.
  std::vector<std::vector<double>> density_rows, temperature_rows;
  Solution solution;
  solution.time = times;
  // Lost mass only grows: once it passes the allowance this K is doomed, and finishing the run
  // would be wasted time. It is checked at interpolated points inside each output interval (CVODE
  // steps past them and interpolates, so they cost no extra steps).
  constexpr int checks_per_interval = 16;
  const auto lost = [&] { return solver->state()[equations->lost_index()]; };
  const auto doomed = [&] { return lost() >= allowed_lost_mass; };
  // Advances to t; with `grow`, doubles K once the mass lost at this K has passed grow_lost_mass.
  double lost_before = 0.0;  // lost mass carried in from smaller K
  const auto advance = [&](double t) {
    try {
      solver->advance_to(t);
    } catch (const std::runtime_error&) {  // CVODE reports the right-hand side's Stopped as its failure
      if (stop && stop()) throw Stopped();
      throw;
    }
    if (grow && lost() - lost_before >= grow_lost_mass && max_size < largest_max_size) {
      lost_before = lost();
      const std::vector<double> y(solver->state().begin(), solver->state().end());
      auto wider = std::make_unique<RateEquations>(p, 2 * max_size, stop);
      std::vector<double> y_wide = widened_state(*equations, *wider, y);
      solver.reset();
      equations = std::move(wider);
      max_size *= 2;
      solver = make_solver(*equations, y_wide, t);
    }
  };
  double t_previous = 0.0;
  for (double t_out : times) {
    for (int i = 1; i < checks_per_interval && t_out > 0.0 && !doomed(); ++i)
      advance(t_previous + (t_out - t_previous) * i / checks_per_interval);
    if (t_out > 0.0 && !doomed()) advance(t_out);  // t_out == 0: the initial state
    t_previous = t_out;
    const auto y = solver->state();
    std::vector<double> density_row, temperature_row;
    double total_density = 0.0, total_energy = 0.0;
    for (std::size_t k = 1; k <= max_size; ++k) {
      const double density = y[equations->density_index(k)];
      const double energy = y[equations->energy_index(k)];
      density_row.push_back(density);
      temperature_row.push_back(
          density < reported_density ? 0.0
                                     : p.initial_temperature * std::max(energy, 0.0) / (1.5 * density));
      total_density += std::max(density, 0.0);
      total_energy += std::max(energy, 0.0);
    }
    density_rows.push_back(std::move(density_row));
    temperature_rows.push_back(std::move(temperature_row));
    solution.total_temperature.push_back(p.initial_temperature * total_energy /
                                         (1.5 * total_density));
    solution.kinetic_energy.push_back(p.initial_temperature * total_energy);
    solution.aggregations.push_back(y[equations->aggregation_index()]);
    solution.fragmentations.push_back(y[equations->fragmentation_index()]);
    solution.collisions.push_back(y[equations->collision_index()]);
    solution.lost_mass_fraction = y[equations->lost_index()];
    if (doomed()) break;
  }
  // The tables with the final K columns: sizes not integrated yet at an earlier time held nothing.
  solution.max_size = max_size;
  for (std::size_t i = 0; i < density_rows.size(); ++i) {
    density_rows[i].resize(max_size, 0.0);
    temperature_rows[i].resize(max_size, 0.0);
    solution.number_fraction.insert(solution.number_fraction.end(), density_rows[i].begin(),
                                    density_rows[i].end());
    solution.temperature.insert(solution.temperature.end(), temperature_rows[i].begin(),
                                temperature_rows[i].end());
  }
  return solution;
}

}  // namespace

Outcomes outcome_probabilities(const Parameters& parameters, std::size_t k, std::size_t j,
                               double T_k, double T_j) {
  return pair_moments(parameters, k, j, T_k, T_j).probability;
}

PairMoments pair_moments(const Parameters& parameters, std::size_t k, std::size_t j, double T_k,
                         double T_j) {
  check_parameters(parameters, "pair_moments");
  check_pair(k, j, T_k, T_j, "pair_moments");
  const PairConstants c = pair_constants(parameters, k, j);
  const double theta_k = T_k / c.mass_k, theta_j = T_j / c.mass_j;
  return region_moments(parameters, c, T_k, T_j, theta_k, theta_j, theta_k + theta_j);
}

InitialRates initial_rates(const Parameters& parameters) {
  check_parameters(parameters, "initial_rates");
  const double n = parameters.monomer_density;
  const double T0 = parameters.initial_temperature;
  const PairConstants c = pair_constants(parameters, 1, 1);
  const double s = 2.0 * T0 / parameters.monomer_mass;
  // \ref cm_mixture_rate "docs/collision-model.md": w_11/2 events per unit volume and time between monomers.
  const double collisions = 0.5 * n * n * c.cross_section * std::sqrt(8.0 * s / pi);
  const Outcomes p = outcome_probabilities(parameters, 1, 1, T0, T0);
  InitialRates rates;
  rates.collisions = collisions;
  rates.aggregations = collisions * p.aggregation;
  rates.fragmentations = collisions * p.fragmentation;  // 0: two monomers never shatter
  rates.bounces = collisions * p.bounce;
  rates.log_monomer_rate = -2.0 * rates.aggregations / n;  // each aggregation takes two monomers
  return rates;
}

Solution solve(const Parameters& parameters, const std::vector<double>& times) { return solve(parameters, times, {}); }

Solution solve(const Parameters& parameters, const std::vector<double>& times, const Stop& stop) {
  check_parameters(parameters, "solve");
  check_times(times);
  // One integration whose K grows as the clusters do; should the mass lost on the way exceed the
  // allowance, integrations from t = 0 with K doubled from that last K.
  Solution grown = integrate(parameters, first_max_size, times, true, stop);
  if (grown.lost_mass_fraction < allowed_lost_mass) return grown;
  for (std::size_t max_size = grown.max_size; max_size <= largest_max_size; max_size *= 2) {
    Solution solution = integrate(parameters, max_size, times, false, stop);
    if (solution.lost_mass_fraction < allowed_lost_mass) return solution;
  }
  throw std::runtime_error("smoluchowski::solve: more than 1e-8 of the mass grows beyond size " +
                           std::to_string(largest_max_size));
}


}  // namespace gdsmc::theory::smoluchowski
