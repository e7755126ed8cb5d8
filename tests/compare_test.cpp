// Tests of analysis/compare (granular-dsmc --compare): the rows of the table against numbers computed by
// hand here from the formulas compare.hpp cites (Haff's law, \ref haff_law "docs/haff-and-mixtures.md"; the scaling-state average;
// the known errors of docs/physics.md "Comparison with theory"), the marks, and the three outputs.
#include "analysis/compare.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/h5md.hpp"
#include "io/namelist.hpp"
#include "analysis/predictions.hpp"
#include "theory/sonine_mixture.hpp"

namespace {

namespace cmp = gdsmc::analysis::compare;
namespace config = gdsmc::io::config;
namespace h5md = gdsmc::io::h5md;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

config::Config read_text(const std::string& text) {
  return config::read(gdsmc::io::namelist::parse(text, "t.nml"));
}

/// Haff cooling, alpha = 0.9, samples at t = 0, 250, 500, 750, 1000.
config::Config haff_config() {
  return read_text(
      "&system\n n_species = 1\n mass = 1.0\n diameter = 1.0\n number_density = 0.01\n restitution = 0.9\n/\n"
      "&initial\n temperature = 1.0\n/\n&dsmc\n n_particles = 1000\n t_end = 1000.0\n replicas = 64\n/\n"
      "&output\n n_samples = 5\n/\n");
}

/// A binary mixture (masses 1 and 4, equal numbers), alpha = 0.8, five samples.
config::Config binary_config() {
  return read_text(
      "&system\n n_species = 2\n mass = 1.0, 4.0\n diameter = 1.0, 1.0\n number_density = 0.01, 0.01\n"
      " restitution = 0.8\n/\n&initial\n temperature = 1.0\n/\n&dsmc\n n_particles = 1000\n t_end = 400.0\n"
      " replicas = 4\n/\n&output\n n_samples = 5\n/\n");
}

h5md::ObservableData series(const std::vector<double>& time, const std::vector<double>& value,
                            const std::vector<double>& error, std::size_t columns) {
  h5md::ObservableData o;
  o.time = time;
  o.value = value;
  o.error = error;
  o.shape = columns > 1 ? std::vector<std::size_t>{time.size(), columns} : std::vector<std::size_t>{time.size()};
  return o;
}

const cmp::Quantity& find(const cmp::Point& pt, const std::string& name) {
  for (const auto& q : pt.quantities)
    if (q.name == name) return q;
  throw std::runtime_error("no quantity " + name);
}

/// van Noije-Ernst a2 (\ref haff_sonine "docs/haff-and-mixtures.md"), written out again here.
double a2_by_hand(double alpha) {
  return 16.0 * (1.0 - alpha) * (1.0 - 2.0 * alpha * alpha) / (81.0 - 17.0 * alpha + 30.0 * alpha * alpha * (1.0 - alpha));
}

TEST(CompareMarks, StatisticsApproximationBeyond) {
  EXPECT_EQ(cmp::classify(0.3, 0.1, 0.0), cmp::Mark::statistics);       // 3 SE exactly
  EXPECT_EQ(cmp::classify(-0.31, 0.1, 0.02), cmp::Mark::approximation);  // 3 SE + 0.01 < 0.32
  EXPECT_EQ(cmp::classify(0.33, 0.1, 0.02), cmp::Mark::beyond);
  EXPECT_EQ(cmp::classify(0.33, 0.1, kNaN), cmp::Mark::beyond_no_estimate);
  EXPECT_EQ(cmp::classify(0.01, kNaN, 0.02), cmp::Mark::approximation);  // one replica: no SE
  EXPECT_EQ(cmp::classify(0.05, kNaN, 0.02), cmp::Mark::beyond_no_estimate);  // statistics unknown
  EXPECT_EQ(cmp::classify(1e-15, 0.0, 0.0, 1.0), cmp::Mark::statistics);  // round-off of T(0)
  EXPECT_STREQ(cmp::mark_name(cmp::Mark::approximation), "approx");
}

// z_R: Student's t quantile at the two-sided 3-sigma level, R - 1 degrees of freedom (reference values
// from the t distribution's CDF by mpmath at 30 digits, betainc, solved with findroot, outside this code).
TEST(CompareMarks, ThresholdFromTheReplicas) {
  EXPECT_TRUE(std::isnan(cmp::statistical_threshold(1)));
  EXPECT_TRUE(std::isnan(cmp::statistical_threshold(3)));  // fewer than 4: no statistical mark
  EXPECT_NEAR(cmp::statistical_threshold(4), 9.2189404587002563, 1e-9);
  EXPECT_NEAR(cmp::statistical_threshold(5), 6.6202059668158664, 1e-9);
  EXPECT_NEAR(cmp::statistical_threshold(8), 4.5299736787334268, 1e-9);
  EXPECT_NEAR(cmp::statistical_threshold(16), 3.5864232263449525, 1e-9);
  EXPECT_NEAR(cmp::statistical_threshold(64), 3.1235170159668449, 1e-9);
  EXPECT_DOUBLE_EQ(cmp::statistical_threshold(0), 3.0);  // not known: the normal level
  const double z4 = cmp::statistical_threshold(4);
  EXPECT_EQ(cmp::classify(0.9, 0.1, kNaN, 0.0, z4), cmp::Mark::statistics);  // 9 SE < z_4
  EXPECT_EQ(cmp::classify(0.95, 0.1, kNaN, 0.0, z4), cmp::Mark::beyond_no_estimate);
  EXPECT_EQ(cmp::classify(0.95, 0.1, 0.1, 0.0, z4), cmp::Mark::approximation);
  EXPECT_EQ(cmp::classify(1.1, 0.1, 0.1, 0.0, z4), cmp::Mark::beyond);
  // three replicas: the SE is not used; within the known error alone is approx, beyond it ?
  EXPECT_EQ(cmp::classify(0.05, 0.1, 0.1, 0.0, kNaN), cmp::Mark::approximation);
  EXPECT_EQ(cmp::classify(0.15, 0.1, 0.1, 0.0, kNaN), cmp::Mark::beyond_no_estimate);
}

gdsmc::species::Mixture one_species_mixture(double alpha) {
  return gdsmc::species::make_mixture({1.0}, {1.0}, {0.01}, gdsmc::species::PairMatrix(1, alpha), false);
}

// The known error of c_k is the second-Sonine correction |c(K=2) - c(K=3)| of one species: at alpha = 0.5
// and 0.3 the values that theory/sonine.hpp states (nonlinear K = 2: 0.1059, 0.2438; K = 3: 0.0900,
// 0.1760; rounded there to 4 digits), and it does not vanish where c changes sign (alpha = 0.7, where the
// first-Sonine c is about 0.003, the correction is 0.0034, docs/physics.md).
TEST(CompareKnownError, CumulantKeepsTheSecondSonineCorrection) {
  EXPECT_NEAR(cmp::cumulant_known_error(one_species_mixture(0.5)), 0.1059 - 0.0900, 1.5e-4);
  EXPECT_NEAR(cmp::cumulant_known_error(one_species_mixture(0.3)), 0.2438 - 0.1760, 1.5e-4);
  EXPECT_NEAR(cmp::cumulant_known_error(one_species_mixture(0.7)), 0.0034, 1e-4);
  EXPECT_EQ(cmp::cumulant_known_error(one_species_mixture(1.0)), 0.0);  // elastic
  // A binary with alpha_11 = 0.5, alpha_12 = alpha_22 = 0.9: the largest over the pairs, alpha = 0.5's.
  gdsmc::species::PairMatrix alpha(2, 0.9);
  alpha(0, 0) = 0.5;
  const auto mix = gdsmc::species::make_mixture({1.0, 2.0}, {1.0, 1.0}, {0.01, 0.01}, alpha, false);
  EXPECT_DOUBLE_EQ(cmp::cumulant_known_error(mix), cmp::cumulant_known_error(one_species_mixture(0.5)));
}

TEST(CompareAverage, SamplesPastScalingStart) {
  const auto a = cmp::scaling_average({1.0, 2.0, 4.0, 6.0}, {0.1, 0.2, 0.3, 0.5}, {0.0, 9.9, 10.0, 30.0}, 10.0);
  EXPECT_EQ(a.count, 2u);
  EXPECT_DOUBLE_EQ(a.value, 5.0);
  EXPECT_DOUBLE_EQ(a.error, 0.4);
  EXPECT_EQ(cmp::scaling_average({1.0}, {0.1}, {3.0}, 10.0).count, 0u);
}

TEST(CompareKnownError, SonineRateAndViscosity) {
  const auto mix = haff_config().mixture();
  EXPECT_NEAR(cmp::sonine_rate_error(mix), 3.0 / 16.0 * std::abs(a2_by_hand(0.9)), 1e-15);
  EXPECT_NEAR(cmp::sonine_rate_error(mix, {0.1}), 3.0 / 16.0 * 0.05, 1e-15);  // |c|/2 dominates
  EXPECT_NEAR(cmp::shear_viscosity_known_error(mix), 0.016 + 0.0033, 1e-15);
}

// The steady shear flow without thermostat (\ref eta_usf_steady "docs/shear-viscosity.md"): a* and P_ij/p, the time
// averages of /observables/shear_state or, in a file without them, at the last sample (p = tr P/3), against Grad's solution, the known error |Grad - independent| of the table (alpha = 0.7: a* 0.03704,
// between 0.7 and 0.9 the larger of the two: P_yy 0.01970).
TEST(CompareRows, SteadyShearAgainstGrad) {
  auto c = read_text(
      "&system\n n_species = 1\n mass = 1.0\n diameter = 1.0\n number_density = 0.01\n restitution = 0.7\n/\n"
      "&initial\n temperature = 0.28\n/\n&dsmc\n n_particles = 1000\n t_end = 1000.0\n replicas = 16\n/\n"
      "&shear\n rate = 0.02\n/\n&output\n n_samples = 2\n/\n");
  const auto theory = gdsmc::analysis::predict(c);
  ASSERT_TRUE(theory.steady_shear_grad.has_value());
  cmp::Measured m;
  const double t = 0.28, p = 0.01 * t;  // P_xx/p = 1.4, P_xy/p = -0.5 at the last sample, p = tr P/3
  m.observables["total_temperature"] = series({0.0, 1000.0}, {1.0, t}, {0.0, 0.001}, 1);
  m.observables["reduced_shear_rate"] = series({0.0, 1000.0}, {0.35, 0.667}, {0.0, 0.002}, 1);
  m.observables["pressure_tensor"] =
      series({0.0, 1000.0}, {0.01, 0.01, 0.01, 0.0, 0.0, 0.0, 1.4 * p, 0.76 * p, 0.84 * p, -0.5 * p, 0.0, 0.0},
             std::vector<double>(12, 1e-5), 6);
  const auto pt = cmp::compare_point(c, theory, m);
  const auto& rate = find(pt, "steady_shear_rate");
  EXPECT_DOUBLE_EQ(rate.value[0], 0.667);
  EXPECT_NEAR(rate.theory[0], 0.630973536820, 1e-11);
  EXPECT_DOUBLE_EQ(rate.known_error[0], 0.03704);
  const auto& xy = find(pt, "steady_shear_pressure_xy");
  EXPECT_NEAR(xy.value[0], -0.5, 1e-12);
  EXPECT_NEAR(xy.error[0], 0.5 * std::hypot(1e-5 / (0.5 * p), std::sqrt(3.0) * 1e-5 / 3.0 / p), 1e-12);
  EXPECT_NEAR(find(pt, "steady_shear_pressure_zz").value[0], 0.84, 1e-12);
  EXPECT_DOUBLE_EQ(cmp::steady_shear_known_error(0.8, 2), 0.01970);
  EXPECT_DOUBLE_EQ(cmp::steady_shear_known_error(0.95, 0), 0.00548);
  EXPECT_DOUBLE_EQ(cmp::steady_shear_known_error(0.5, 1), 0.00342);  // a table point: its own gap
  EXPECT_TRUE(std::isnan(cmp::steady_shear_known_error(0.4, 0)));
  EXPECT_EQ(rate.at, "last sample");
  // A file with /observables/shear_state (docs/output.md): its time averages and their SE, not the last sample.
  m.arrays["shear_state/value"] = {0.661, 1.43, 0.77, 0.80, -0.503};
  m.arrays["shear_state/error"] = {0.001, 0.002, 0.003, 0.004, 0.005};
  const auto averaged = cmp::compare_point(c, theory, m);
  EXPECT_EQ(find(averaged, "steady_shear_rate").at, "time average");
  EXPECT_DOUBLE_EQ(find(averaged, "steady_shear_rate").value[0], 0.661);
  EXPECT_DOUBLE_EQ(find(averaged, "steady_shear_rate").error[0], 0.001);
  EXPECT_DOUBLE_EQ(find(averaged, "steady_shear_pressure_zz").value[0], 0.80);
  EXPECT_DOUBLE_EQ(find(averaged, "steady_shear_pressure_xy").error[0], 0.005);
  EXPECT_DOUBLE_EQ(find(averaged, "steady_shear_pressure_xy").known_error[0], xy.known_error[0]);
  m.arrays.clear();
  // with the Gaussian thermostat the state is another one: no steady-shear rows
  c.thermostat.kind = gdsmc::io::config::ThermostatKind::gaussian;
  for (const auto& q : cmp::compare_point(c, theory, m).quantities) EXPECT_NE(q.name, "steady_shear_rate");
}

// The Haff row: theory T(t) = T0/(1 + t/t0)^2, t0 = 2/zeta0, zeta0 = (4/3) sqrt(pi) (1 - alpha^2) n sigma^2
// sqrt(T0/m) (\ref haff_law "docs/haff-and-mixtures.md"); collisions per particle nu0 t0 ln(1 + t/t0), nu0 = 4 sqrt(pi) n sigma^2 sqrt(T0/m)
// (\ref cm_pair_rate "docs/collision-model.md"); DSMC 0.4 % above with SE 0.1 %: z = +4, +0.4 %, known error 1.15 eps ln(T0/T) T.
TEST(CompareRows, HaffAgainstHandComputedNumbers) {
  const auto c = haff_config();
  const auto theory = gdsmc::analysis::predict(c);
  const double pi = std::numbers::pi, n = 0.01, alpha = 0.9;
  const double zeta0 = 4.0 / 3.0 * std::sqrt(pi) * (1.0 - alpha * alpha) * n;
  const double t0 = 2.0 / zeta0, nu0 = 4.0 * std::sqrt(pi) * n;
  const std::vector<double> times{0.0, 250.0, 500.0, 750.0, 1000.0};
  std::vector<double> haff, value, error, collisions;
  for (double t : times) {
    haff.push_back(1.0 / ((1.0 + t / t0) * (1.0 + t / t0)));
    value.push_back(haff.back() * (t > 0.0 ? 1.004 : 1.0));
    error.push_back(haff.back() * 0.001);
    collisions.push_back(nu0 * t0 * std::log(1.0 + t / t0));
  }
  cmp::Measured m;
  m.observables["total_temperature"] = series(times, value, error, 1);
  m.observables["collisions_per_particle"] = series(times, collisions, std::vector<double>(5, 0.01), 1);
  const auto pt = cmp::compare_point(c, theory, m);
  const auto& q = find(pt, "total_temperature");
  ASSERT_EQ(q.time, times);
  EXPECT_EQ(q.approximation, "maxwellian");
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_NEAR(q.theory[i], haff[i], 1e-8 * haff[i]) << i;
  const double eps = 3.0 / 16.0 * std::abs(a2_by_hand(alpha));
  const double known = 1.15 * eps * std::log(1.0 / haff[4]) * haff[4];
  EXPECT_NEAR(q.known_error[4], known, 1e-8 * known);
  const auto& col = find(pt, "collisions_per_particle");
  for (std::size_t i = 1; i < times.size(); ++i) EXPECT_NEAR(col.theory[i], collisions[i], 1e-7 * collisions[i]) << i;

  const auto table_rows = cmp::rows(cmp::Comparison{{pt}, false, ""});
  ASSERT_GE(table_rows.size(), 2u);
  const auto& r = table_rows[0];
  EXPECT_EQ(r.quantity, "T");
  EXPECT_TRUE(r.trajectory);
  EXPECT_DOUBLE_EQ(r.time, 1000.0);
  EXPECT_DOUBLE_EQ(r.value, value[4]);
  EXPECT_DOUBLE_EQ(r.error, error[4]);
  EXPECT_NEAR(r.z, 4.0, 1e-6);
  EXPECT_NEAR(r.percent, 0.4, 1e-5);
  EXPECT_EQ(r.mark, cmp::Mark::approximation);  // 4 SE > z_64 = 3.12 SE, but within that + known error (0.74 %)
  EXPECT_EQ(r.counts[0] + r.counts[1] + r.counts[2] + r.counts[3], 5u);
  EXPECT_EQ(r.counts[0], 1u);  // t = 0: within statistics; the later samples need the known error
  EXPECT_EQ(r.counts[1], 4u);
  EXPECT_EQ(table_rows[1].quantity, "collisions/particle");
  EXPECT_EQ(table_rows[1].mark, cmp::Mark::statistics);
}

// Viscoelastic restitution has no constant a2, so no known error: its rows name no source of one ("none
// stated"), as the null known_error and the mark '?' say.
TEST(CompareRows, ViscoelasticRowsStateNoKnownError) {
  const auto c = read_text(
      "&system\n n_species = 1\n mass = 1.0\n diameter = 1.0\n number_density = 0.01\n"
      " restitution_model = 'viscoelastic'\n visco_a_kappa = 0.1\n/\n&initial\n temperature = 1.0\n/\n"
      "&dsmc\n n_particles = 1000\n t_end = 1000.0\n replicas = 8\n/\n&output\n n_samples = 5\n/\n");
  const auto theory = gdsmc::analysis::predict(c);
  const std::vector<double> times{0.0, 250.0, 500.0, 750.0, 1000.0};
  cmp::Measured m;
  m.observables["total_temperature"] = series(times, theory.total_temperature, std::vector<double>(5, 1e-3), 1);
  m.observables["collisions_per_particle"] =
      series(times, theory.collisions_per_particle, std::vector<double>(5, 0.01), 1);
  const auto pt = cmp::compare_point(c, theory, m);
  for (const char* name : {"total_temperature", "collisions_per_particle"}) {
    const auto& q = find(pt, name);
    EXPECT_EQ(q.known_error_source, "none stated") << name;
    for (std::size_t i = 1; i < q.known_error.size(); ++i) EXPECT_TRUE(std::isnan(q.known_error[i])) << name << " " << i;
  }
}

// (D-T)/T % of a theory value that is zero up to round-off (the cooling rate of an elastic, perfectly rough
// gas came out as -3.7e-17 and its percentage as -3e15): not shown (NaN) where |T| <= 1e-12 max(|D|, SE) (the SE
// too: a T of 1.5e-15 beside D = 1e-3 +- 2e-3);
// shown from just above that, and for an ordinary value: 100 (0.101 - 0.1)/0.1 = 1 %.
TEST(CompareRows, APercentageOfARoundOffZeroIsNotShown) {
  cmp::Point pt;
  pt.replicas = 4;
  const auto one = [](double value, double error, double theory) {
    return cmp::Quantity{"zeta_star", "zeta*", "maxwellian", "none stated", {}, 1, {value}, {error}, {theory}, {kNaN}, "scaling state"};
  };
  pt.quantities = {one(1e-3, 2e-3, -3.7e-17), one(1e-3, 2e-3, 2.1e-15), one(0.101, 1e-3, 0.1), one(0.0, 1e-3, 0.0),
                   one(1e-3, 2e-3, 1.5e-15)};
  const auto table_rows = cmp::rows(cmp::Comparison{{pt}, false, ""});
  ASSERT_EQ(table_rows.size(), 5u);
  EXPECT_TRUE(std::isnan(table_rows[4].percent)) << "1.5e-15 <= 1e-12 x SE 2e-3, though above 1e-12 x |D| 1e-3";
  EXPECT_TRUE(std::isnan(table_rows[0].percent)) << table_rows[0].percent;  // 3.7e-17 <= 1e-12 x 2e-3
  EXPECT_NEAR(table_rows[1].percent, 100.0 * (1e-3 - 2.1e-15) / 2.1e-15, 1e3);  // 2.1e-15 > 2e-15: shown
  EXPECT_NEAR(table_rows[2].percent, 1.0, 1e-9);
  EXPECT_TRUE(std::isnan(table_rows[3].percent));  // theory exactly 0, as before
}

// The scaling state of a binary: T_k/T and c_k averaged over the samples past scaling_start = 10
// collisions per particle, against the first-Sonine HCS; error = r hypot(e_k/T_k, e/T), averaged.
TEST(CompareRows, BinaryScalingStateAverages) {
  const auto c = binary_config();
  const auto theory = gdsmc::analysis::predict(c);
  const std::vector<double> times{0.0, 100.0, 200.0, 300.0, 400.0};
  const double t1 = 1.2, t2 = 0.8, total = 0.5 * (t1 + t2);
  std::vector<double> temperature, temperature_error, sonine, sonine_error, total_value, total_error;
  for (std::size_t i = 0; i < 5; ++i) {
    const double f = 1.0 + 0.1 * static_cast<double>(i);  // errors differ from sample to sample
    temperature.insert(temperature.end(), {t1, t2});
    temperature_error.insert(temperature_error.end(), {0.01 * f, 0.02 * f});
    sonine.insert(sonine.end(), {0.05, -0.02});
    sonine_error.insert(sonine_error.end(), {0.003 * f, 0.004 * f});
    total_value.push_back(total);
    total_error.push_back(0.005 * f);
  }
  cmp::Measured m;
  m.observables["temperature"] = series(times, temperature, temperature_error, 2);
  m.observables["total_temperature"] = series(times, total_value, total_error, 1);
  m.observables["sonine_c"] = series(times, sonine, sonine_error, 2);
  m.observables["collisions_per_particle"] = series(times, {0.0, 5.0, 15.0, 20.0, 30.0}, {0, 0, 0, 0, 0}, 1);
  const auto pt = cmp::compare_point(c, theory, m);
  const auto fs = gdsmc::theory::hcs_first_sonine(c.mixture());
  const auto& ratio = find(pt, "temperature_over_mean");
  ASSERT_EQ(ratio.columns, 2u);
  EXPECT_TRUE(ratio.time.empty());
  EXPECT_EQ(ratio.at, "scaling state");
  double e1 = 0.0;
  for (double f : {1.2, 1.3, 1.4}) e1 += t1 / total * std::hypot(0.01 * f / t1, 0.005 * f / total) / 3.0;
  EXPECT_DOUBLE_EQ(ratio.value[0], t1 / total);
  EXPECT_NEAR(ratio.error[0], e1, 1e-15);
  EXPECT_NEAR(ratio.theory[0], fs.temperature_over_mean[0], 1e-12);
  EXPECT_NEAR(ratio.known_error[1], 0.002 * fs.temperature_over_mean[1], 1e-15);  // \ref son_binary "docs/sonine.md", binary
  const auto& cumulant = find(pt, "sonine_c");
  EXPECT_DOUBLE_EQ(cumulant.value[1], -0.02);
  EXPECT_NEAR(cumulant.error[1], 0.004 * 1.3, 1e-15);
  // the larger of 15 % of c_k and the second-Sonine correction of one species at alpha = 0.8
  const double correction = std::abs(gdsmc::theory::one_species_hcs_sonine(0.8, 2).cumulant_c -
                                     gdsmc::theory::one_species_hcs_sonine(0.8, 3).cumulant_c);
  EXPECT_GT(correction, 0.0);
  EXPECT_NEAR(cumulant.known_error[0], std::max(0.15 * std::abs(fs.sonine_c[0]), correction), 1e-15);
  EXPECT_NEAR(cumulant.known_error[1], std::max(0.15 * std::abs(fs.sonine_c[1]), correction), 1e-15);
  // T_1/T_2 (x_1 = x_2 = 1/2): the error of T_1/T carried through x_1 tau_1 + x_2 tau_2 = 1
  const auto& gamma = find(pt, "temperature_ratio");
  const double tau1 = t1 / total, tau2 = t2 / total;
  EXPECT_DOUBLE_EQ(gamma.value[0], t1 / t2);
  EXPECT_NEAR(gamma.error[0], tau1 / tau2 * e1 * (1.0 / tau1 + 1.0 / tau2), 1e-14);
  const double th1 = fs.temperature_over_mean[0], th2 = fs.temperature_over_mean[1];
  EXPECT_NEAR(gamma.theory[0], th1 / th2, 1e-12);
  EXPECT_NEAR(gamma.known_error[0], th1 / th2 * 0.002 * th1 * (1.0 / th1 + 1.0 / th2), 1e-14);
  const auto table_rows = cmp::rows(cmp::Comparison{{pt}, false, ""});
  bool seen = false;
  for (const auto& r : table_rows)
    if (r.quantity == "T_2/T") {
      seen = true;
      EXPECT_NEAR(r.z, (t2 / total - fs.temperature_over_mean[1]) / ratio.error[1], 1e-9);
      EXPECT_NEAR(r.percent, 100.0 * (t2 / total - fs.temperature_over_mean[1]) / fs.temperature_over_mean[1], 1e-9);
    } else if (r.quantity == "c_2") {  // a negative theory: both differences have the sign of D - T
      EXPECT_EQ(r.z > 0.0, r.percent > 0.0) << r.z << " " << r.percent;
    }
  EXPECT_TRUE(seen);
}

/// Every (label, value) of `expected` is a row of `pt`'s table, with that value.
void expect_rows(const cmp::Point& pt, const std::vector<std::pair<std::string, double>>& expected) {
  const auto table_rows = cmp::rows(cmp::Comparison{{pt}, false, ""});
  for (const auto& [label, value] : expected) {
    bool seen = false;
    for (const auto& r : table_rows)
      if (r.quantity == label) {
        seen = true;
        EXPECT_DOUBLE_EQ(r.value, value) << label;
      }
    EXPECT_TRUE(seen) << label << " is not a row of\n" << cmp::table(cmp::Comparison{{pt}, false, ""});
  }
}

TEST(CompareRows, RoughMixtureRowsNameTheirSpecies) {
  // A binary rough mixture: T_k/T and T_rot,k/T_k at the last sample, one row per species, each row named by its
  // species (they were all "T_k/T" and "T_rot,k/T_k"); the values by hand from the last sample.
  const std::string gas =
      "&system\n n_species = 2\n mass = 1.0, 2.0\n diameter = 1.0, 1.2\n number_density = 0.005, 0.005\n"
      " restitution = 0.9\n roughness = 0.5\n moment_of_inertia = 0.4\n/\n&output\n n_samples = 2\n/\n";
  const auto c = read_text(gas + "&dsmc\n n_particles = 1000\n collisions_per_particle = 5.0\n replicas = 4\n/\n");
  cmp::Measured m;
  const std::vector<double> times{0.0, 50.0};
  m.observables["temperature"] = series(times, {1.0, 1.0, 0.6, 0.5}, {0.0, 0.0, 0.01, 0.02}, 2);
  m.observables["rotational_temperature"] = series(times, {1.0, 1.0, 0.45, 0.4}, {0.0, 0.0, 0.01, 0.01}, 2);
  m.observables["total_temperature"] = series(times, {1.0, 0.55}, {0.0, 0.01}, 1);
  expect_rows(cmp::compare_point(c, gdsmc::analysis::predict(c), m),
              {{"T_1/T", 0.6 / 0.55}, {"T_2/T", 0.5 / 0.55}, {"T_rot,1/T_1", 0.45 / 0.6}, {"T_rot,2/T_2", 0.4 / 0.5}});
  // the same gas driven by the white noise: T_k and T_rot,k/T_k at the last sample
  const auto driven = read_text(gas + "&dsmc\n n_particles = 1000\n t_end = 100.0\n replicas = 4\n/\n"
                                      "&thermostat\n kind = 'white_noise'\n noise_strength = 0.001\n/\n");
  expect_rows(cmp::compare_point(driven, gdsmc::analysis::predict(driven), m),
              {{"T_1", 0.6}, {"T_2", 0.5}, {"T_rot,1/T_1", 0.45 / 0.6}, {"T_rot,2/T_2", 0.4 / 0.5}});
}

TEST(CompareRows, NoTheorySaysSoInsteadOfFailing) {
  // A sheared run without thermostat: no free cooling, no HSS, no viscosity theory for its state.
  const auto c = read_text(
      "&system\n n_species = 1\n mass = 1.0\n diameter = 1.0\n number_density = 0.01\n restitution = 0.9\n/\n"
      "&dsmc\n n_particles = 1000\n t_end = 100.0\n/\n&shear\n rate = 0.001\n/\n");
  cmp::Measured m;
  const auto pt = cmp::compare_point(c, gdsmc::analysis::predict(c), m);
  EXPECT_TRUE(pt.quantities.empty());
  const std::string text = cmp::table(cmp::Comparison{{pt}, false, ""});
  EXPECT_NE(text.find("no theory applies to this input"), std::string::npos) << text;
  EXPECT_NE(text.find("no Gaussian thermostat"), std::string::npos) << text;
}

TEST(CompareOutput, TableJsonAndFile) {
  cmp::Point pt;
  pt.quantities.push_back(cmp::Quantity{"temperature", "T_{k}", "maxwellian", "src", {0.0, 1.0}, 2,
                                        {1.0, 1.0, 0.9, 0.8}, {0.0, 0.0, 0.01, 0.01}, {1.0, 1.0, 0.91, 0.8},
                                        {0.0, 0.0, kNaN, 0.001}});
  pt.notes.push_back("a note");
  const cmp::Comparison comparison{{pt}, false, ""};
  const std::string text = cmp::table(comparison);
  EXPECT_NE(text.find("T_1"), std::string::npos) << text;
  EXPECT_NE(text.find("T_2"), std::string::npos) << text;
  EXPECT_NE(text.find("note: a note"), std::string::npos) << text;
  const std::string json = cmp::json(comparison);
  EXPECT_NE(json.find("\"temperature\": {\"label\": \"T_{k}\", \"approximation\": \"maxwellian\""),
            std::string::npos) << json;
  EXPECT_NE(json.find("\"value\": [[1, 1], [0.90000000000000002, 0.80000000000000004]]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"known_error\": [[0, 0], [null, 0.001]]"), std::string::npos) << json;

  const auto path = std::filesystem::temp_directory_path() / ("gdsmc-compare-" + std::to_string(::getpid()) + ".h5");
  {
    h5md::Writer writer(path.string(), "test", "test", "0");
    cmp::write(writer, comparison);
    writer.commit();
  }
  const auto value = h5md::read_dataset(path.string(), "/comparison/temperature/value");
  EXPECT_EQ(value.shape, (std::vector<std::size_t>{2, 2}));
  EXPECT_DOUBLE_EQ(value.data[2], 0.9);
  EXPECT_DOUBLE_EQ(h5md::read_dataset(path.string(), "/comparison/temperature/theory").data[2], 0.91);
  // One entry of four without a known error: NaN there, as the JSON's null (none given at all: left out,
  // FiniteOutputs.EveryDatasetOfEveryKindOfOutputIsFinite).
  EXPECT_TRUE(std::isnan(h5md::read_dataset(path.string(), "/comparison/temperature/known_error").data[2]));
  EXPECT_EQ(h5md::read_string_attribute(path.string(), "/comparison/temperature", "approximation"), "maxwellian");
  const auto time = std::get<std::vector<double>>(h5md::read_attribute(path.string(), "/comparison/temperature", "time"));
  EXPECT_EQ(time, (std::vector<double>{0.0, 1.0}));
  std::filesystem::remove(path);
}

}  // namespace
