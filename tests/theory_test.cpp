// Unit tests for gdsmc::theory (theory.hpp): collision rates (\ref cm_pair_rate "docs/collision-model.md"), Haff's law (\ref haff_law "docs/haff-and-mixtures.md"),
// partial temperatures of a mixture (\ref haff_mixture_odes "docs/haff-and-mixtures.md") and the role of chi (\ref cm_chi "docs/collision-model.md").
// Reference values are computed here independently of the code under test: closed forms in a
// different arrangement, the "equivalent form" of \ref haff_ratios "docs/haff-and-mixtures.md", Monte Carlo integration of the
// collision rule (\ref cm_rule "docs/collision-model.md") over Maxwellian pairs, and exact conservation laws.
#include "theory/theory.hpp"
#include "sanitizer_scale.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

using gdsmc::species::make_mixture;
using gdsmc::species::Mixture;
using gdsmc::species::PairMatrix;
namespace theory = gdsmc::theory;

namespace {

constexpr double pi = std::numbers::pi;

Mixture binary_mixture(double m1, double m2, double sigma1, double sigma2, double n1, double n2,
                       double alpha, bool enskog = false) {
  return make_mixture({m1, m2}, {sigma1, sigma2}, {n1, n2}, PairMatrix(2, alpha), enskog);
}

// \ref haff_mixture_odes "docs/haff-and-mixtures.md" "equivalent form" (DSMC notes, eq. (76) corrected), written out independently of xi_kj:
// dT_k/dt = sum_j sqrt(2 pi) chi_kj n_j sigma_kj^2 [ -(4/3)(1 - alpha^2)(m_kj^2/m_k) s_kj^(3/2)
//           + (8/3)(1 + alpha) m_kj s_kj^(1/2) (T_j - T_k)/(m_k + m_j) ].
std::vector<double> equivalent_form_rates(const Mixture& mix, const std::vector<double>& T) {
  const std::size_t s = mix.size();
  std::vector<double> rate(s, 0.0);
  for (std::size_t k = 0; k < s; ++k)
    for (std::size_t j = 0; j < s; ++j) {
      const double mk = mix.mass[k], mj = mix.mass[j];
      const double reduced = mk * mj / (mk + mj);
      const double sigma = 0.5 * (mix.diameter[k] + mix.diameter[j]);
      const double alpha = mix.restitution(k, j);
      const double skj = T[k] / mk + T[j] / mj;
      rate[k] += std::sqrt(2.0 * pi) * mix.pair_correlation(k, j) * mix.number_density[j] * sigma *
                 sigma *
                 (-(4.0 / 3.0) * (1.0 - alpha * alpha) * reduced * reduced / mk * std::pow(skj, 1.5) +
                  (8.0 / 3.0) * (1.0 + alpha) * reduced * std::sqrt(skj) * (T[j] - T[k]) / (mk + mj));
    }
  return rate;
}

struct Accumulator {
  double sum = 0.0, sum_squares = 0.0;
  long count = 0;
  void add(double x) {
    sum += x;
    sum_squares += x * x;
    ++count;
  }
  double mean() const { return sum / count; }
  double standard_error() const {
    const double m = mean();
    return std::sqrt((sum_squares / count - m * m) / (count - 1));
  }
};

// Monte Carlo over Maxwellian pairs (species k with T_k, species j with T_j) and e uniform on the
// full unit sphere. Rate weight of an unordered pair per unit volume / (n_k n_j):
// w = 2 pi sigma_kj^2 chi_kj |g.e| (\ref cm_pair_rate "docs/collision-model.md"). Velocity changes from the collision rule \ref cm_rule "docs/collision-model.md".
struct PairMonteCarlo {
  Accumulator relative_speed;  // |g|
  Accumulator weight;          // w
  Accumulator energy_change;   // w (dE_k + dE_j)
  Accumulator energy_change_k; // w dE_k
  Accumulator energy_change_j; // w dE_j
};

PairMonteCarlo sample_pairs(const Mixture& mix, std::size_t k, std::size_t j, double Tk, double Tj,
                            double alpha, long samples, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double mk = mix.mass[k], mj = mix.mass[j];
  const double sigma = 0.5 * (mix.diameter[k] + mix.diameter[j]);
  const double chi = mix.pair_correlation(k, j);
  const double sk = std::sqrt(Tk / mk), sj = std::sqrt(Tj / mj);
  PairMonteCarlo mc;
  for (long i = 0; i < samples; ++i) {
    double vk[3], vj[3], e[3], g[3];
    double norm = 0.0;
    for (int d = 0; d < 3; ++d) {
      vk[d] = sk * normal(rng);
      vj[d] = sj * normal(rng);
      e[d] = normal(rng);
      norm += e[d] * e[d];
    }
    norm = std::sqrt(norm);
    double ge = 0.0, g2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      e[d] /= norm;
      g[d] = vk[d] - vj[d];
      ge += g[d] * e[d];
      g2 += g[d] * g[d];
    }
    // \ref cm_rule "docs/collision-model.md": v_k' = v_k - mu_jk (1 + alpha)(g.e) e, v_j' = v_j + mu_kj (1 + alpha)(g.e) e.
    const double mu_jk = mj / (mk + mj), mu_kj = mk / (mk + mj);
    double ek = 0.0, ej = 0.0, ek_after = 0.0, ej_after = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double vk_after = vk[d] - mu_jk * (1.0 + alpha) * ge * e[d];
      const double vj_after = vj[d] + mu_kj * (1.0 + alpha) * ge * e[d];
      ek += 0.5 * mk * vk[d] * vk[d];
      ej += 0.5 * mj * vj[d] * vj[d];
      ek_after += 0.5 * mk * vk_after * vk_after;
      ej_after += 0.5 * mj * vj_after * vj_after;
    }
    const double w = 2.0 * pi * sigma * sigma * chi * std::abs(ge);
    mc.relative_speed.add(std::sqrt(g2));
    mc.weight.add(w);
    mc.energy_change.add(w * ((ek_after - ek) + (ej_after - ej)));
    mc.energy_change_k.add(w * (ek_after - ek));
    mc.energy_change_j.add(w * (ej_after - ej));
  }
  return mc;
}

double relative_difference(double a, double b) { return std::abs(a - b) / std::abs(b); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// One species
// ---------------------------------------------------------------------------------------------

TEST(Theory, SonineA2KnownValues) {
  EXPECT_DOUBLE_EQ(theory::sonine_a2(1.0), 0.0);
  EXPECT_NEAR(theory::sonine_a2(1.0 / std::sqrt(2.0)), 0.0, 1e-15);
  // \ref son_scaling "docs/sonine.md" quotes first-Sonine c = 2 a2 = 0.1049 (alpha = 0.5) and 0.2361 (alpha = 0.3).
  EXPECT_NEAR(2.0 * theory::sonine_a2(0.5), 0.1049, 1e-4);
  EXPECT_NEAR(2.0 * theory::sonine_a2(0.3), 0.2361, 1e-4);
}

// the DSMC notes, eq. (46), \ref haff_law "docs/haff-and-mixtures.md" (R = sigma/2): 1/t_c = (8/3)(1 - alpha^2) n R^2 sqrt(pi T0/m), t_c = 2/zeta0.
TEST(Theory, HaffCoolingRateMatchesSeedTimeScale) {
  const double n = 0.02, sigma = 1.3, m = 2.0, alpha = 0.8, T0 = 1.7;
  const double radius = sigma / 2.0;
  const double inverse_tc = (8.0 / 3.0) * (1.0 - alpha * alpha) * n * radius * radius *
                            std::sqrt(pi * T0 / m);
  const double zeta0 = theory::haff_cooling_rate(n, sigma, 1.0, m, alpha, T0);
  EXPECT_NEAR(2.0 / zeta0, 1.0 / inverse_tc, 1e-12 / inverse_tc);
}

// haff_temperature solves dT/dt = -zeta(T) T: compare with the CVODE solution for S = 1 up to
// 100 t0. The cumulative collisions follow from nu(T) = nu0 sqrt(T/T0) = nu0/(1 + t/t0):
// C(t) = (n nu0/2) t0 ln(1 + t/t0).
TEST(Theory, HaffLawAgreesWithOdeSolution) {
  const double n = 0.01, sigma = 1.0, m = 1.0, alpha = 0.8, T0 = 2.0;
  const Mixture mix = make_mixture({m}, {sigma}, {n}, PairMatrix(1, alpha), false);
  const double zeta0 = theory::haff_cooling_rate(n, sigma, 1.0, m, alpha, T0);
  const double t0 = 2.0 / zeta0;
  const double nu0 = theory::collision_frequency(n, sigma, 1.0, m, T0);
  std::vector<double> times = {0.0};
  for (double f : {0.01, 0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0}) times.push_back(f * t0);
  const auto history = theory::integrate_partial_temperatures(mix, {T0}, times);
  ASSERT_EQ(history.temperature.size(), times.size());
  EXPECT_DOUBLE_EQ(history.temperature[0][0], T0);
  EXPECT_EQ(history.collisions[0], 0.0);
  double worst_temperature = 0.0, worst_collisions = 0.0;
  for (std::size_t i = 1; i < times.size(); ++i) {
    const double exact = theory::haff_temperature(times[i], T0, zeta0);
    worst_temperature =
        std::max(worst_temperature, relative_difference(history.temperature[i][0], exact));
    const double collisions = 0.5 * n * nu0 * t0 * std::log1p(times[i] / t0);
    worst_collisions =
        std::max(worst_collisions, relative_difference(history.collisions[i], collisions));
  }
  std::printf("[ Haff ] T(100 t0)/T0 = %.6e, max rel. error T %.2e, collisions %.2e\n",
              history.temperature.back()[0] / T0, worst_temperature, worst_collisions);
  EXPECT_LT(worst_temperature, 1e-8);
  EXPECT_LT(worst_collisions, 1e-8);
  EXPECT_NEAR(history.temperature.back()[0], T0 / (101.0 * 101.0), 1e-8 * T0 / (101.0 * 101.0));
}

// One species, Enskog chi != 1: the ODE right-hand side is -zeta T, and the event rate is n nu/2
// with nu = n pi sigma^2 chi <|g|>, <|g|> = 4 sqrt(T/(pi m)) (DSMC notes, eq. (34), \ref cm_mean_speed "docs/collision-model.md"), i.e. the DSMC notes,
// eq. (36), \ref cm_frequency "docs/collision-model.md", per unit volume: 8 n^2 R^2 chi sqrt(pi T/m).
TEST(Theory, OneSpeciesRatesReduceToHaff) {
  const double n = 0.3, sigma = 1.0, m = 3.0, alpha = 0.6, T = 0.7;
  const Mixture mix = make_mixture({m}, {sigma}, {n}, PairMatrix(1, alpha), true);
  const double chi = mix.pair_correlation(0, 0);
  ASSERT_GT(chi, 1.5);
  const auto rate = theory::partial_temperature_rates(mix, {T});
  const double zeta = theory::haff_cooling_rate(n, sigma, chi, m, alpha, T);
  EXPECT_NEAR(rate[0], -zeta * T, 1e-13 * zeta * T);
  const double nu = theory::collision_frequency(n, sigma, chi, m, T);
  EXPECT_NEAR(nu, n * pi * sigma * sigma * chi * 4.0 * std::sqrt(T / (pi * m)), 1e-13 * nu);
  const double total = theory::total_collision_rate(mix, {T});
  EXPECT_NEAR(total, n * nu / 2.0, 1e-13 * total);
  const double radius = sigma / 2.0;
  EXPECT_NEAR(total, 8.0 * n * n * radius * radius * chi * std::sqrt(pi * T / m), 1e-13 * total);
  EXPECT_NEAR(theory::pair_collision_rate(mix, {T})(0, 0), total, 1e-15 * total);
}

// ---------------------------------------------------------------------------------------------
// Mixtures
// ---------------------------------------------------------------------------------------------

TEST(Theory, XiFormEqualsEquivalentForm) {
  const Mixture mix = make_mixture({1.0, 4.0, 0.3}, {1.0, 2.0, 0.7}, {0.02, 0.01, 0.05},
                                   [] {
                                     PairMatrix a(3);
                                     const double v[3][3] = {
                                         {0.7, 0.8, 0.9}, {0.8, 0.5, 0.95}, {0.9, 0.95, 0.3}};
                                     for (int k = 0; k < 3; ++k)
                                       for (int j = 0; j < 3; ++j) a(k, j) = v[k][j];
                                     return a;
                                   }(),
                                   true);
  const std::vector<double> T = {1.0, 3.0, 0.2};
  const auto rate = theory::partial_temperature_rates(mix, T);
  const auto expected = equivalent_form_rates(mix, T);
  const PairMatrix xi = theory::cooling_rate_matrix(mix, T);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(rate[k], expected[k], 1e-13 * std::abs(expected[k])) << "species " << k;
    EXPECT_NEAR(rate[k], -T[k] * (xi(k, 0) + xi(k, 1) + xi(k, 2)), 1e-14 * std::abs(rate[k]));
    // The row sums without the matrix (analysis::predict's cooling_rate): the same sum in the same order.
    EXPECT_EQ(theory::cooling_rates(mix, T)[k], xi(k, 0) + xi(k, 1) + xi(k, 2));
  }
}

// Two labels for the same particles behave as one species of the summed density.
TEST(Theory, IdenticalSpeciesBehaveAsOneSpecies) {
  const double m = 1.5, sigma = 0.8, alpha = 0.75, n1 = 0.003, n2 = 0.007, T0 = 1.2;
  const Mixture two = binary_mixture(m, m, sigma, sigma, n1, n2, alpha);
  const double n = n1 + n2;
  const double zeta = theory::haff_cooling_rate(n, sigma, 1.0, m, alpha, T0);
  const auto rate = theory::partial_temperature_rates(two, {T0, T0});
  for (double r : rate) EXPECT_NEAR(r, -zeta * T0, 1e-13 * zeta * T0);
  const double nu = theory::collision_frequency(n, sigma, 1.0, m, T0);
  EXPECT_NEAR(theory::total_collision_rate(two, {T0, T0}), n * nu / 2.0, 1e-13 * n * nu);
  // Per species, in O(S) memory: each label suffers the one species's nu and cools at its zeta.
  for (double f : theory::collision_frequencies(two, {T0, T0})) EXPECT_NEAR(f, nu, 1e-13 * nu);
  for (double z : theory::cooling_rates(two, {T0, T0})) EXPECT_NEAR(z, zeta, 1e-13 * zeta);

  const double t0 = 2.0 / zeta;
  const std::vector<double> times = {0.0, 0.3 * t0, 3.0 * t0, 30.0 * t0};
  const auto history = theory::integrate_partial_temperatures(two, {T0, T0}, times);
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double haff = theory::haff_temperature(times[i], T0, zeta);
    EXPECT_NEAR(history.temperature[i][0], history.temperature[i][1],
                1e-12 * history.temperature[i][1]);
    EXPECT_NEAR(history.temperature[i][0], haff, 1e-8 * haff);
    const double collisions = 0.5 * n * nu * t0 * std::log1p(times[i] / t0);
    EXPECT_NEAR(history.collisions[i], collisions, 1e-8 * collisions + 1e-300);
  }
  // Started unequal, the two labels equalise and then follow Haff together.
  const auto relaxing = theory::integrate_partial_temperatures(two, {0.5 * T0, 2.0 * T0},
                                                               {100.0 * t0});
  EXPECT_NEAR(relaxing.temperature[0][1] / relaxing.temperature[0][0], 1.0, 1e-7);
}

// alpha = 1: sum_k n_k T_k is conserved and the temperatures relax to sum_k x_k T_k(0); the
// lighter, colder species heats up (energy flows from hot to cold).
TEST(Theory, ElasticMixtureRelaxesToEquipartition) {
  const Mixture mix = binary_mixture(1.0, 4.0, 1.0, 2.0, 0.02, 0.01, 1.0);
  const std::vector<double> T0 = {1.0, 3.0};
  const double common = (0.02 * T0[0] + 0.01 * T0[1]) / 0.03;
  const double energy0 = 0.02 * T0[0] + 0.01 * T0[1];
  const auto rate0 = theory::partial_temperature_rates(mix, T0);
  EXPECT_GT(rate0[0], 0.0);
  EXPECT_LT(rate0[1], 0.0);
  const double nu = theory::total_collision_rate(mix, T0) / 0.03;  // about one event per particle
  std::vector<double> times;
  for (double f : {0.1, 1.0, 10.0, 100.0, 1000.0, 10000.0}) times.push_back(f / nu);
  const auto history = theory::integrate_partial_temperatures(mix, T0, times);
  double previous_T1 = T0[0];
  for (std::size_t i = 0; i < times.size(); ++i) {
    const auto& T = history.temperature[i];
    EXPECT_NEAR(0.02 * T[0] + 0.01 * T[1], energy0, 1e-9 * energy0) << "t = " << times[i];
    EXPECT_GE(T[0], previous_T1 * (1.0 - 1e-10));
    EXPECT_LE(T[0], common * (1.0 + 1e-10));
    previous_T1 = T[0];
  }
  EXPECT_NEAR(history.temperature.back()[0], common, 1e-8 * common);
  EXPECT_NEAR(history.temperature.back()[1], common, 1e-8 * common);
}

// Mean relative speed and pair event rates against Monte Carlo over Maxwellian pairs, T1 != T2.
TEST(Theory, PairCollisionRateAgreesWithMonteCarlo) {
  const Mixture mix = binary_mixture(1.0, 4.0, 1.0, 2.0, 0.02, 0.01, 0.7);
  const std::vector<double> T = {1.0, 3.0};
  const PairMatrix rate = theory::pair_collision_rate(mix, T);
  EXPECT_DOUBLE_EQ(rate(0, 1), rate(1, 0));
  const long samples = gdsmc::test::samples(2'000'000);  // 250000 under the sanitizers
  const std::size_t pairs[3][2] = {{0, 0}, {1, 1}, {0, 1}};
  for (int p = 0; p < 3; ++p) {
    const std::size_t k = pairs[p][0], j = pairs[p][1];
    const auto mc = sample_pairs(mix, k, j, T[k], T[j], 0.7, samples, 1234 + p);
    const double sigma = 0.5 * (mix.diameter[k] + mix.diameter[j]);
    const double like = k == j ? 0.5 : 1.0;
    const double nn = mix.number_density[k] * mix.number_density[j] * like;
    // <|g|>: rate = n_k n_j pi sigma^2 chi <|g|> (x 1/2 for like species)
    const double g_theory = rate(k, j) / (nn * pi * sigma * sigma);
    std::printf("[ MC ] <|g_%zu%zu|>: MC %.6f +- %.6f, theory %.6f\n", k + 1, j + 1,
                mc.relative_speed.mean(), mc.relative_speed.standard_error(), g_theory);
    EXPECT_NEAR(mc.relative_speed.mean(), g_theory, 4.0 * mc.relative_speed.standard_error());
    // Rate convention of \ref cm_pair_rate "docs/collision-model.md": 2 pi sigma^2 chi |g.e|, e uniform on the full sphere.
    const double rate_mc = nn * mc.weight.mean(), rate_se = nn * mc.weight.standard_error();
    std::printf("[ MC ] R_%zu%zu: MC %.6e +- %.1e, theory %.6e\n", k + 1, j + 1, rate_mc, rate_se,
                rate(k, j));
    EXPECT_NEAR(rate_mc, rate(k, j), 4.0 * rate_se);
    EXPECT_LT(rate_se, gdsmc::test::precision_bound(2e-3) * rate_mc);  // precise enough to see a factor 2 or a wrong s_kj
  }
}

// Total energy balance: sum_k (3/2) n_k dT_k/dt equals the energy lost per unit volume and time,
// sum over unordered pairs of (event rate x energy change), by Monte Carlo with the collision rule.
TEST(Theory, EnergyLossAgreesWithMonteCarlo) {
  const double alpha = 0.7;
  const Mixture mix = binary_mixture(1.0, 4.0, 1.0, 2.0, 0.02, 0.01, alpha);
  const std::vector<double> T = {1.0, 3.0};
  const auto rate = theory::partial_temperature_rates(mix, T);
  const double theory_loss = 1.5 * (0.02 * rate[0] + 0.01 * rate[1]);
  const long samples = gdsmc::test::samples(2'000'000);  // 250000 under the sanitizers
  const std::size_t pairs[3][2] = {{0, 0}, {1, 1}, {0, 1}};
  double mc = 0.0, variance = 0.0;
  for (int p = 0; p < 3; ++p) {
    const std::size_t k = pairs[p][0], j = pairs[p][1];
    const auto sample = sample_pairs(mix, k, j, T[k], T[j], alpha, samples, 99 + p);
    const double nn =
        mix.number_density[k] * mix.number_density[j] * (k == j ? 0.5 : 1.0);  // \ref cm_pair_rate "docs/collision-model.md"
    mc += nn * sample.energy_change.mean();
    variance += std::pow(nn * sample.energy_change.standard_error(), 2);
  }
  const double se = std::sqrt(variance);
  std::printf("[ MC ] energy change per unit volume and time: MC %.6e +- %.1e, theory %.6e\n", mc,
              se, theory_loss);
  EXPECT_LT(theory_loss, 0.0);
  EXPECT_NEAR(theory_loss, mc, 4.0 * se);
  EXPECT_LT(se, gdsmc::test::precision_bound(2e-3) * std::abs(mc));
}

// Energy change of each species alone, (3/2) n_k dT_k/dt: tests the exchange term and its sign.
// Like pairs lose (1 - alpha^2) m_kk (g.e)^2/2 per event; unlike pairs also transfer energy.
// The elastic case isolates the exchange term: energy flows from the hotter species.
TEST(Theory, PartialEnergyChangeAgreesWithMonteCarlo) {
  const std::vector<double> T = {1.0, 3.0};
  const long samples = gdsmc::test::samples(2'000'000);  // 250000 under the sanitizers
  for (double alpha : {0.7, 1.0}) {
    const Mixture mix = binary_mixture(1.0, 4.0, 1.0, 2.0, 0.02, 0.01, alpha);
    const auto rate = theory::partial_temperature_rates(mix, T);
    const auto like1 = sample_pairs(mix, 0, 0, T[0], T[0], alpha, samples, 7);
    const auto like2 = sample_pairs(mix, 1, 1, T[1], T[1], alpha, samples, 8);
    const auto unlike = sample_pairs(mix, 0, 1, T[0], T[1], alpha, samples, 9);
    const double n1 = 0.02, n2 = 0.01;
    const double mc[2] = {0.5 * n1 * n1 * like1.energy_change.mean() +
                              n1 * n2 * unlike.energy_change_k.mean(),
                          0.5 * n2 * n2 * like2.energy_change.mean() +
                              n1 * n2 * unlike.energy_change_j.mean()};
    const double se[2] = {
        std::hypot(0.5 * n1 * n1 * like1.energy_change.standard_error(),
                   n1 * n2 * unlike.energy_change_k.standard_error()),
        std::hypot(0.5 * n2 * n2 * like2.energy_change.standard_error(),
                   n1 * n2 * unlike.energy_change_j.standard_error())};
    const double density[2] = {n1, n2};
    for (int k = 0; k < 2; ++k) {
      const double theory_value = 1.5 * density[k] * rate[k];
      std::printf("[ MC ] alpha %.1f, (3/2) n_%d dT_%d/dt: MC %.6e +- %.1e, theory %.6e\n", alpha,
                  k + 1, k + 1, mc[k], se[k], theory_value);
      EXPECT_NEAR(theory_value, mc[k], 4.0 * se[k]) << "alpha " << alpha << " species " << k + 1;
      EXPECT_LT(se[k], gdsmc::test::precision_bound(0.02) * std::abs(mc[k]));
    }
    if (alpha == 1.0) {  // species 2 is hotter: it loses what species 1 gains
      EXPECT_GT(rate[0], 0.0);
      EXPECT_NEAR(n1 * rate[0], -n2 * rate[1], 1e-14 * n1 * rate[0]);
    }
  }
}

// \ref haff_ratios "docs/haff-and-mixtures.md" example: alpha = 0.3, m2/m1 = 100, equal diameters and number densities: T2/T1 = 60.6.
TEST(Theory, AsymptoticTemperatureRatio) {
  const Mixture mix = binary_mixture(1.0, 100.0, 1.0, 1.0, 0.01, 0.01, 0.3);
  const auto ratio = theory::asymptotic_temperature_ratios(mix);
  ASSERT_EQ(ratio.size(), 2u);
  EXPECT_EQ(ratio[0], 1.0);
  // Independent root of d ln T_1/dt = d ln T_2/dt from the equivalent form, by bisection in
  // log gamma on [1, 1e4] (one sign change there).
  auto mismatch = [&](double gamma) {
    const auto r = equivalent_form_rates(mix, {1.0, gamma});
    return r[0] / 1.0 - r[1] / gamma;
  };
  double lo = 1.0, hi = 1e4;
  ASSERT_LT(mismatch(lo) * mismatch(hi), 0.0);
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (mismatch(lo) * mismatch(mid) <= 0.0 ? hi : lo) = mid;
  }
  const double gamma = std::sqrt(lo * hi);
  std::printf("[ ratio ] T2/T1: ODE %.12f, bisection %.12f\n", ratio[1], gamma);
  EXPECT_NEAR(ratio[1], 60.6, 0.05);
  EXPECT_NEAR(ratio[1], gamma, 1e-9 * gamma);

  // Stationary under the time ODE: both species cool at the same relative rate ...
  const auto rate = theory::partial_temperature_rates(mix, {1.0, ratio[1]});
  EXPECT_NEAR(rate[1] / ratio[1], rate[0], 1e-9 * std::abs(rate[0]));
  // ... and T2/T1 stays put while T falls by decades.
  const double zeta1 = -rate[0];
  const auto history = theory::integrate_partial_temperatures(
      mix, {1.0, ratio[1]}, {1.0 / zeta1, 10.0 / zeta1, 1000.0 / zeta1});
  for (const auto& T : history.temperature)
    EXPECT_NEAR(T[1] / T[0], ratio[1], 1e-8 * ratio[1]);
  EXPECT_LT(history.temperature.back()[0], 1e-4);
}

// The asymptotic ratio is approached from equal temperatures by the time-domain solution.
TEST(Theory, AsymptoticRatioIsReachedFromEqualTemperatures) {
  const Mixture mix = binary_mixture(1.0, 2.0, 1.0, 1.5, 0.02, 0.01, 0.5);
  const auto ratio = theory::asymptotic_temperature_ratios(mix);
  const double zeta0 = -theory::partial_temperature_rates(mix, {1.0, 1.0})[0];
  const auto history =
      theory::integrate_partial_temperatures(mix, {1.0, 1.0}, {1e3 / zeta0, 1e6 / zeta0});
  const auto& T = history.temperature.back();
  std::printf("[ ratio ] m2/m1 = 2: asymptotic %.10f, ODE at 1e6/zeta0 %.10f\n", ratio[1],
              T[1] / T[0]);
  EXPECT_NEAR(T[1] / T[0], ratio[1], 1e-6 * ratio[1]);
}

// Every entry xi_kj of the rate matrix of \ref haff_mixture_odes "docs/haff-and-mixtures.md" (the energy species k loses to, or exchanges with,
// species j) against a direct Monte Carlo integral over Maxwellian pairs, written independently of
// sample_pairs above: velocities from the Maxwellians of T_k and T_j, e uniform on the unit sphere, and the
// collision rule (\ref cm_rule "docs/collision-model.md") weighted with the pair rate in its hemisphere form (\ref cm_hemisphere "docs/collision-model.md"),
// 4 pi sigma_kj^2 chi_kj (g.e) theta(g.e) (its mean over e is pi sigma_kj^2 chi_kj |g|). With dE_k the
// energy change of the species-k partner,
//   k != j:  -(3/2) n_k T_k xi_kj = n_k n_j <w dE_k>        (n_k n_j unordered unlike pairs per volume^2)
//   k == j:  -(3/2) n_k T_k xi_kk = (n_k^2/2) <w (dE_a + dE_b)>,
// at unequal masses, sizes, temperatures and three different restitution coefficients (alpha_11,
// alpha_22, alpha_12), dilute and Enskog; 2e6 pairs per entry (SE 0.2-0.5 % of the entry: a 1-2 % error
// in one entry fails), fixed seeds, 4 SE (issue 13).
TEST(Theory, CoolingRateEntriesAgreeWithMaxwellianPairMonteCarlo) {
  PairMatrix alpha(2);
  alpha(0, 0) = 0.6;
  alpha(1, 1) = 0.85;
  alpha(0, 1) = alpha(1, 0) = 0.75;
  const std::vector<double> T = {1.0, 2.5};
  const long samples = gdsmc::test::samples(2'000'000);  // 250000 under the sanitizers
  for (bool enskog : {false, true}) {
    const double scale = enskog ? 10.0 : 1.0;  // Enskog: solid fraction ~0.2, chi_kj 1.5-2.4
    const Mixture mix = make_mixture({1.0, 3.0}, {1.0, 1.6}, {0.02 * scale, 0.008 * scale}, alpha, enskog);
    const PairMatrix xi = theory::cooling_rate_matrix(mix, T);
    for (std::size_t k = 0; k < 2; ++k)
      for (std::size_t j = 0; j < 2; ++j) {
        std::mt19937_64 rng(4242 + 10 * k + j + (enskog ? 100 : 0));
        std::normal_distribution<double> normal(0.0, 1.0);
        const double mk = mix.mass[k], mj = mix.mass[j], a = mix.restitution(k, j);
        const double sigma = 0.5 * (mix.diameter[k] + mix.diameter[j]), chi = mix.pair_correlation(k, j);
        const double sk = std::sqrt(T[k] / mk), sj = std::sqrt(T[j] / mj);
        Accumulator loss;  // w dE (species k's share, or the pair's for k == j)
        for (long i = 0; i < samples; ++i) {
          double vk[3], vj[3], e[3], norm = 0.0;
          for (int d = 0; d < 3; ++d) {
            vk[d] = sk * normal(rng);
            vj[d] = sj * normal(rng);
            e[d] = normal(rng);
            norm += e[d] * e[d];
          }
          double ge = 0.0;
          for (int d = 0; d < 3; ++d) ge += (vk[d] - vj[d]) * e[d] / std::sqrt(norm);
          if (ge <= 0.0) {  // theta(g.e): the pair separates along e, no collision
            loss.add(0.0);
            continue;
          }
          const double w = 4.0 * pi * sigma * sigma * chi * ge;
          // \ref cm_rule "docs/collision-model.md": v_k' = v_k - (m_j/(m_k + m_j))(1 + alpha)(g.e) e, v_j' = v_j + (m_k/(m_k + m_j))(...) e
          double dek = 0.0, dej = 0.0;
          for (int d = 0; d < 3; ++d) {
            const double ed = e[d] / std::sqrt(norm);
            const double vk_after = vk[d] - mj / (mk + mj) * (1.0 + a) * ge * ed;
            const double vj_after = vj[d] + mk / (mk + mj) * (1.0 + a) * ge * ed;
            dek += 0.5 * mk * (vk_after * vk_after - vk[d] * vk[d]);
            dej += 0.5 * mj * (vj_after * vj_after - vj[d] * vj[d]);
          }
          loss.add(w * (k == j ? dek + dej : dek));
        }
        const double nk = mix.number_density[k], nj = mix.number_density[j];
        const double factor = k == j ? -nk / (3.0 * T[k]) : -2.0 * nj / (3.0 * T[k]);
        const double mc = factor * loss.mean(), se = std::abs(factor) * loss.standard_error();
        std::printf("[ MC ] %s xi_%zu%zu (alpha %.2f, chi %.4f, %ld pairs): MC %.6e +- %.1e, theory %.6e "
                    "(%+.2f SE)\n",
                    enskog ? "Enskog" : "dilute", k + 1, j + 1, a, chi, samples, mc, se, xi(k, j),
                    (xi(k, j) - mc) / se);
        EXPECT_NEAR(xi(k, j), mc, 4.0 * se) << (enskog ? "Enskog" : "dilute") << " k " << k << " j " << j;
        EXPECT_LT(se, gdsmc::test::precision_bound(0.01) * std::abs(mc));  // precise enough to see a few per cent in one entry
      }
  }
}

// chi only multiplies rates (\ref cm_chi "docs/collision-model.md"): chi = 2 doubles every rate; Carnahan-Starling chi_kj
// multiplies pair k-j.
TEST(Theory, PairCorrelationIsARateMultiplier) {
  const Mixture dilute = binary_mixture(1.0, 4.0, 1.0, 2.0, 0.02, 0.01, 0.7);
  Mixture doubled = dilute;
  doubled.pair_correlation = PairMatrix(2, 2.0);
  const std::vector<double> T = {1.0, 3.0};
  const PairMatrix r1 = theory::pair_collision_rate(dilute, T);
  const PairMatrix r2 = theory::pair_collision_rate(doubled, T);
  const PairMatrix x1 = theory::cooling_rate_matrix(dilute, T);
  const PairMatrix x2 = theory::cooling_rate_matrix(doubled, T);
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t j = 0; j < 2; ++j) {
      EXPECT_NEAR(r2(k, j), 2.0 * r1(k, j), 1e-14 * r1(k, j));
      EXPECT_NEAR(x2(k, j), 2.0 * x1(k, j), 1e-14 * std::abs(x1(k, j)));
    }
  const auto d1 = theory::partial_temperature_rates(dilute, T);
  const auto d2 = theory::partial_temperature_rates(doubled, T);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(d2[k], 2.0 * d1[k], 1e-14 * std::abs(d1[k]));
  EXPECT_NEAR(theory::total_collision_rate(doubled, T), 2.0 * theory::total_collision_rate(dilute, T),
              1e-14 * theory::total_collision_rate(dilute, T));

  const Mixture dense = binary_mixture(1.0, 4.0, 1.0, 2.0, 0.2, 0.05, 0.7, true);
  const Mixture dense_dilute = binary_mixture(1.0, 4.0, 1.0, 2.0, 0.2, 0.05, 0.7, false);
  const PairMatrix rd = theory::pair_collision_rate(dense, T);
  const PairMatrix rb = theory::pair_collision_rate(dense_dilute, T);
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t j = 0; j < 2; ++j) {
      EXPECT_GT(dense.pair_correlation(k, j), 1.0);
      EXPECT_NEAR(rd(k, j), dense.pair_correlation(k, j) * rb(k, j), 1e-14 * rd(k, j));
    }
}

// ---------------------------------------------------------------------------------------------
// Errors
// ---------------------------------------------------------------------------------------------

TEST(Theory, RejectsBadInput) {
  const Mixture mix = binary_mixture(1.0, 4.0, 1.0, 2.0, 0.02, 0.01, 0.7);
  EXPECT_THROW(theory::partial_temperature_rates(mix, {1.0}), std::invalid_argument);
  EXPECT_THROW(theory::pair_collision_rate(mix, {1.0, -1.0}), std::invalid_argument);
  EXPECT_THROW(theory::integrate_partial_temperatures(mix, {1.0, 1.0}, {1.0, 0.5}),
               std::invalid_argument);
  EXPECT_THROW(theory::integrate_partial_temperatures(mix, {1.0, 1.0}, {-1.0}),
               std::invalid_argument);
}

// alpha > 1 heats: T = T0/(1 - t/t_b)^2 blows up at t_b = 2/|zeta0|. Asking for 2 t_b must make
// CVODE fail, reported as a runtime_error that names the call.
TEST(Theory, SolverFailureNamesTheSundialsCall) {
  const Mixture mix = make_mixture({1.0}, {1.0}, {0.01}, PairMatrix(1, 2.0), false);
  const double blow_up = 2.0 / std::abs(theory::haff_cooling_rate(0.01, 1.0, 1.0, 1.0, 2.0, 1.0));
  try {
    theory::integrate_partial_temperatures(mix, {1.0}, {2.0 * blow_up});
    FAIL() << "expected a SUNDIALS failure";
  } catch (const std::runtime_error& error) {
    std::printf("[ error ] %s\n", error.what());
    EXPECT_NE(std::string(error.what()).find("SUNDIALS call CVode"), std::string::npos);
  }
}
