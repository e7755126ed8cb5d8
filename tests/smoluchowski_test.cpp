// Unit tests for gdsmc::theory::smoluchowski (smoluchowski.hpp): aggregation and fragmentation of
// inelastic clusters with Maxwellian partial temperatures (\ref af_smoluchowski "docs/agg-frag.md").
// References are independent of the closed forms under test: Monte Carlo of the collision rule
// itself (\ref cm_rule "docs/collision-model.md", \ref af_smoluchowski "docs/agg-frag.md") over Maxwellian pairs, Haff's law from theory.hpp (\ref haff_law "docs/haff-and-mixtures.md"), exact
// conservation of mass, the energy bookkeeping of each outcome, and numbers computed by hand.
#include "theory/smoluchowski.hpp"

#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "theory/theory.hpp"

namespace smol = gdsmc::theory::smoluchowski;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double infinity = std::numeric_limits<double>::infinity();

// m = sigma = T0 = 1, n = 0.1: the full model of the validation runs.
smol::Parameters full_model() {
  return {.monomer_mass = 1.0,
          .monomer_diameter = 1.0,
          .monomer_density = 0.1,
          .initial_temperature = 1.0,
          .restitution = 0.8,
          .aggregation_energy = 0.5,
          .fragmentation_energy = 1.5,
          .fragment_restitution = 0.5};
}

smol::Parameters sticking_gas() {
  smol::Parameters p = full_model();
  p.aggregation_energy = infinity;
  p.fragmentation_energy = infinity;
  return p;
}

// One species collision frequency nu_0 = 4 sqrt(pi) n sigma^2 sqrt(T0/m) (\ref cm_frequency "docs/collision-model.md").
double monomer_collision_frequency(const smol::Parameters& p) {
  return gdsmc::theory::collision_frequency(p.monomer_density, p.monomer_diameter, 1.0,
                                            p.monomer_mass, p.initial_temperature);
}

// Weighted mean sum(w f)/sum(w) and its standard error (delta method for a ratio estimator).
struct WeightedMean {
  double sw = 0.0, swf = 0.0, sw2 = 0.0, sw2f = 0.0, sw2f2 = 0.0;
  long count = 0;
  void add(double w, double f) {
    sw += w;
    swf += w * f;
    sw2 += w * w;
    sw2f += w * w * f;
    sw2f2 += w * w * f * f;
    ++count;
  }
  double mean() const { return swf / sw; }
  double standard_error() const {
    const double r = mean(), n = static_cast<double>(count), mean_w = sw / n;
    const double variance = (sw2f2 - 2.0 * r * sw2f + r * r * sw2) / n;  // of w (f - r)
    return std::sqrt(variance / n) / mean_w;
  }
};

// Monte Carlo of the collision rule (\ref cm_rule "docs/collision-model.md", \ref af_smoluchowski "docs/agg-frag.md") over Maxwellian pairs at T_k, T_j: e uniform
// on the sphere with weight |g.e| (the rate of \ref cm_pair_rate "docs/collision-model.md"), outcomes classified by the thresholds
// and the energies read off the actual post-collision velocities.
enum Quantity {
  p_agg, p_frag, p_bounce, energy_k_agg, energy_j_agg, cm_energy_agg, energy_k_frag,
  energy_j_frag, cm_energy_frag, impact_energy_frag, bounce_change_k, bounce_change_j, quantity_count
};

std::array<WeightedMean, quantity_count> monte_carlo_moments(const smol::Parameters& p,
                                                             std::size_t k, std::size_t j,
                                                             double T_k, double T_j, long samples,
                                                             std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double m_k = k * p.monomer_mass, m_j = j * p.monomer_mass, M = m_k + m_j;
  const double m_kj = m_k * m_j / M, alpha = p.restitution;
  const double sd_k = std::sqrt(T_k / m_k), sd_j = std::sqrt(T_j / m_j);
  std::array<WeightedMean, quantity_count> acc;
  for (long n = 0; n < samples; ++n) {
    double vk[3], vj[3], e[3], g[3], norm = 0.0;
    for (int d = 0; d < 3; ++d) {
      vk[d] = sd_k * normal(rng);
      vj[d] = sd_j * normal(rng);
      e[d] = normal(rng);
      norm += e[d] * e[d];
    }
    double ge = 0.0, g2 = 0.0, ek = 0.0, ej = 0.0, cm = 0.0;
    for (int d = 0; d < 3; ++d) {
      e[d] /= std::sqrt(norm);
      g[d] = vk[d] - vj[d];
      ge += g[d] * e[d];
      g2 += g[d] * g[d];
      ek += 0.5 * m_k * vk[d] * vk[d];
      ej += 0.5 * m_j * vj[d] * vj[d];
      const double V = (m_k * vk[d] + m_j * vj[d]) / M;
      cm += 0.5 * M * V * V;
    }
    const double w = std::abs(ge);
    const double impact = 0.5 * m_kj * g2, normal_energy = 0.5 * m_kj * ge * ge;
    std::array<double, quantity_count> f{};
    if (impact < p.aggregation_energy) {
      f[p_agg] = 1.0;
      f[energy_k_agg] = ek;
      f[energy_j_agg] = ej;
      f[cm_energy_agg] = cm;  // the aggregate moves with V
    } else if (normal_energy > p.fragmentation_energy && k + j >= 3) {
      f[p_frag] = 1.0;
      f[energy_k_frag] = ek;
      f[energy_j_frag] = ej;
      f[cm_energy_frag] = cm;
      f[impact_energy_frag] = impact;
    } else {
      f[p_bounce] = 1.0;
      double ek_after = 0.0, ej_after = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double vk_after = vk[d] - (m_j / M) * (1.0 + alpha) * ge * e[d];
        const double vj_after = vj[d] + (m_k / M) * (1.0 + alpha) * ge * e[d];
        ek_after += 0.5 * m_k * vk_after * vk_after;
        ej_after += 0.5 * m_j * vj_after * vj_after;
      }
      f[bounce_change_k] = ek_after - ek;
      f[bounce_change_j] = ej_after - ej;
    }
    for (int q = 0; q < quantity_count; ++q) acc[q].add(w, f[q]);
  }
  return acc;
}

void expect_moments_match_monte_carlo(const smol::Parameters& p, std::size_t k, std::size_t j,
                                      double T_k, double T_j, std::uint64_t seed) {
  const smol::PairMoments m = smol::pair_moments(p, k, j, T_k, T_j);
  const std::array<double, quantity_count> theory = {
      m.probability.aggregation, m.probability.fragmentation, m.probability.bounce,
      m.energy_k_agg, m.energy_j_agg, m.cm_energy_agg, m.energy_k_frag, m.energy_j_frag,
      m.cm_energy_frag, m.impact_energy_frag, m.bounce_energy_change_k,
      m.bounce_energy_change_j};
  const auto mc = monte_carlo_moments(p, k, j, T_k, T_j, 1'000'000, seed);
  const char* names[quantity_count] = {
      "P_agg", "P_frag", "P_bounce", "energy_k_agg", "energy_j_agg", "cm_energy_agg",
      "energy_k_frag", "energy_j_frag", "cm_energy_frag", "impact_energy_frag",
      "bounce_energy_change_k", "bounce_energy_change_j"};
  for (int q = 0; q < quantity_count; ++q) {
    const bool shatters = k + j >= 3;
    if (!shatters && (q == p_frag || (q >= energy_k_frag && q <= impact_energy_frag))) {
      EXPECT_EQ(theory[q], 0.0) << names[q] << " of a monomer pair";
      continue;
    }
    EXPECT_NEAR(theory[q], mc[q].mean(), 5.0 * mc[q].standard_error())
        << names[q] << " for (k, j) = (" << k << ", " << j << ")";
    // The region is populated well enough for the comparison to mean something.
    EXPECT_GT(std::abs(mc[q].mean()), 20.0 * mc[q].standard_error()) << names[q];
  }
}

}  // namespace

// --------------------------------------------------------------------------------------------
// Region moments (\ref af_outcome "docs/agg-frag.md") against Monte Carlo of the collision rule
// --------------------------------------------------------------------------------------------

TEST(SmoluchowskiMoments, UnequalPairMatchesMonteCarloOfCollisionRule) {
  smol::Parameters p = full_model();
  // Pair (2, 3) at T = 1.3, 0.7: m_kj s = 1.2 * 0.8833 = 1.06, so x_a = 0.75 and x_f = 1.13; all
  // three outcomes are frequent and the thresholds are crossed in both orders over the samples.
  p.aggregation_energy = 0.8;
  p.fragmentation_energy = 1.2;
  expect_moments_match_monte_carlo(p, 2, 3, 1.3, 0.7, 12345);
}

TEST(SmoluchowskiMoments, FragmentationBelowAggregationThresholdMatchesMonteCarlo) {
  // x_f < x_a: every x above x_a with U > x_f/x shatters (x_m = x_a branch).
  smol::Parameters p = full_model();
  p.aggregation_energy = 1.0;
  p.fragmentation_energy = 0.4;
  // T_k = 0.3, T_j = 1.6: m_kj s = 0.8 * 0.7 = 0.56, x_a = 1.79, x_f = 0.71; the monomer's
  // bounce energy change 2 m mu (1 + alpha)[mu (1 + alpha) s/2 - theta_k] J_b is well away from 0.
  expect_moments_match_monte_carlo(p, 1, 4, 0.3, 1.6, 777);
}

TEST(SmoluchowskiMoments, MonomerPairMatchesMonteCarloAndNeverShatters) {
  smol::Parameters p = full_model();
  p.aggregation_energy = 0.8;
  p.fragmentation_energy = 0.1;  // would shatter most collisions if monomers could
  expect_moments_match_monte_carlo(p, 1, 1, 1.3, 1.3, 4242);
}

// --------------------------------------------------------------------------------------------
// Outcome probabilities
// --------------------------------------------------------------------------------------------

TEST(SmoluchowskiOutcomes, ProbabilitiesSumToOneAndKnownLimits) {
  const smol::Parameters p = full_model();
  for (std::size_t k : {1, 2, 7, 40})
    for (std::size_t j : {1, 3, 64})
      for (double T_k : {0.05, 1.0, 9.0}) {
        const smol::Outcomes o = smol::outcome_probabilities(p, k, j, T_k, 0.7);
        EXPECT_NEAR(o.aggregation + o.fragmentation + o.bounce, 1.0, 1e-14);
        EXPECT_GE(o.aggregation, 0.0);
        EXPECT_GE(o.fragmentation, 0.0);
        EXPECT_GE(o.bounce, 0.0);
      }
  // Two monomers never shatter (\ref af_outcome "docs/agg-frag.md"), a monomer and a dimer do.
  EXPECT_EQ(smol::outcome_probabilities(p, 1, 1, 5.0, 5.0).fragmentation, 0.0);
  EXPECT_GT(smol::outcome_probabilities(p, 1, 2, 5.0, 5.0).fragmentation, 0.1);

  smol::Parameters bouncing = p;
  bouncing.aggregation_energy = 0.0;
  bouncing.fragmentation_energy = infinity;
  const smol::Outcomes b = smol::outcome_probabilities(bouncing, 3, 5, 0.4, 2.0);
  EXPECT_EQ(b.aggregation, 0.0);
  EXPECT_EQ(b.fragmentation, 0.0);
  EXPECT_EQ(b.bounce, 1.0);

  const smol::Outcomes sticking = smol::outcome_probabilities(sticking_gas(), 3, 5, 0.4, 2.0);
  EXPECT_EQ(sticking.aggregation, 1.0);
  EXPECT_EQ(sticking.bounce, 0.0);
}

TEST(SmoluchowskiOutcomes, SmallAggregationThresholdKeepsRelativeAccuracy) {
  // P_agg = 1 - (1 + x) e^-x = x^2/2 - x^3/3 + x^4/8 - ...: evaluated naively at x = 1e-6 it
  // would keep only about 4 digits (1e-12 out of 1).
  smol::Parameters p = full_model();
  const double x = 1e-6;  // monomers at T = 1: m_11 s = 1/2 * 2 = 1
  p.aggregation_energy = x;
  const double expected = x * x / 2.0 - x * x * x / 3.0 + x * x * x * x / 8.0;
  EXPECT_NEAR(smol::outcome_probabilities(p, 1, 1, 1.0, 1.0).aggregation / expected, 1.0, 1e-12);
  // The aggregated pairs' energy: m_k v_k^2/2 over x < x_a is (T theta/s) I_agg + (3/2) T theta/s
  // P_agg = x^3/6 + 3 x^2/8 to leading order.
  const smol::PairMoments m = smol::pair_moments(p, 1, 1, 1.0, 1.0);
  EXPECT_NEAR(m.energy_k_agg / (x * x * x / 6.0 + 0.75 * x * x / 2.0), 1.0, 1e-5);
}

// --------------------------------------------------------------------------------------------
// The rate equations
// --------------------------------------------------------------------------------------------

TEST(SmoluchowskiSolve, ElasticOnlyBouncesReduceToHaffLaw) {
  smol::Parameters p = full_model();
  p.restitution = 0.7;
  p.aggregation_energy = 0.0;
  p.fragmentation_energy = infinity;
  const double zeta0 = gdsmc::theory::haff_cooling_rate(p.monomer_density, p.monomer_diameter, 1.0,
                                                        p.monomer_mass, p.restitution,
                                                        p.initial_temperature);
  const double t0 = 2.0 / zeta0;
  const std::vector<double> times = {0.0, 0.1 * t0, t0, 3.0 * t0, 10.0 * t0, 30.0 * t0};
  const smol::Solution s = smol::solve(p, times);
  ASSERT_EQ(s.time.size(), times.size());
  const std::size_t K = s.max_size;
  const double nu0 = monomer_collision_frequency(p);
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double haff = gdsmc::theory::haff_temperature(times[i], p.initial_temperature, zeta0);
    EXPECT_NEAR(s.temperature[i * K] / haff, 1.0, 1e-6) << "t/t0 = " << times[i] / t0;
    EXPECT_NEAR(s.number_fraction[i * K], 1.0, 1e-12);
    EXPECT_EQ(s.number_fraction[i * K + 1], 0.0);
    EXPECT_EQ(s.aggregations[i], 0.0);
    // Events per monomer: integral of nu(t)/2 = (nu0 t0/2) ln(1 + t/t0), nu ~ sqrt(T).
    EXPECT_NEAR(s.collisions[i], 0.5 * nu0 * t0 * std::log1p(times[i] / t0),
                1e-6 * (1.0 + s.collisions[i]));
  }
}

TEST(SmoluchowskiSolve, MassIsConservedInStickingAndFullModel) {
  for (const smol::Parameters& p : {sticking_gas(), full_model()}) {
    const double nu0 = monomer_collision_frequency(p);
    std::vector<double> times;
    for (double t = 0.0; t <= 12.0; t += 1.0) times.push_back(t / nu0);  // to <k> ~ 2.5-7
    const smol::Solution s = smol::solve(p, times);
    const std::size_t K = s.max_size;
    EXPECT_LT(s.lost_mass_fraction, 1e-8);
    for (std::size_t i = 0; i < times.size(); ++i) {
      double mass = 0.0;
      for (std::size_t k = 1; k <= K; ++k) mass += k * s.number_fraction[i * K + k - 1];
      EXPECT_NEAR(mass, 1.0, 1e-8 + s.lost_mass_fraction) << "t nu0 = " << times[i] * nu0;
      if (i > 0) {
        // Inelastic bounces, sticking and eps_f < 1: kinetic energy can only decrease.
        EXPECT_LE(s.kinetic_energy[i], s.kinetic_energy[i - 1] * (1.0 + 1e-9));
        EXPECT_GE(s.aggregations[i], s.aggregations[i - 1]);
      }
    }
    EXPECT_LT(s.number_fraction[(times.size() - 1) * K], 0.9) << "the gas has aggregated";
  }
}

// The number of sizes K grows during the integration (smoluchowski.hpp, "Numerical integration"):
// two output schedules make it grow at different times (its lost mass is checked 16 times per output
// interval), and to a different last K; the answer at the common last time must not depend on that
// beyond the integration's tolerance: every size with n_k/n_1(0) >= 1e-9 to 1e-7 relative plus
// 1e-13 (100 times the absolute tolerance on n_k/n_1(0)), the totals to 1e-8.
TEST(SmoluchowskiSolve, GrowingTheSizesDoesNotChangeTheAnswer) {
  for (const smol::Parameters& p : {sticking_gas(), full_model()}) {
    const double nu0 = monomer_collision_frequency(p);
    std::vector<double> many;
    for (double t = 0.0; t <= 20.0; t += 0.5) many.push_back(t / nu0);  // to <k> ~ 5-12
    const smol::Solution a = smol::solve(p, many);
    const smol::Solution b = smol::solve(p, {0.0, 3.0 / nu0, 20.0 / nu0});
    ASSERT_GT(a.max_size, 64u) << "K has grown";
    const std::size_t ia = many.size() - 1, ib = 2;
    for (std::size_t k = 0; k < std::min(a.max_size, b.max_size); ++k) {
      const double na = a.number_fraction[ia * a.max_size + k], nb = b.number_fraction[ib * b.max_size + k];
      if (na >= 1e-9) {
        EXPECT_NEAR(nb, na, 1e-7 * na + 1e-13) << "size " << k + 1;
      }
    }
    EXPECT_NEAR(b.kinetic_energy[ib], a.kinetic_energy[ia], 1e-8 * a.kinetic_energy[ia]);
    EXPECT_NEAR(b.collisions[ib], a.collisions[ia], 1e-8 * a.collisions[ia]);
    EXPECT_LT(a.lost_mass_fraction, 1e-8);
    EXPECT_LT(b.lost_mass_fraction, 1e-8);
  }
}

// A Stop is asked at every right-hand side: the integration ends with Stopped soon after the first call
// that says so (here the 50th; CVODE may try a few more right-hand sides before it gives up), not at
// the end (over 150 calls); a Stop that never says so leaves the answer unchanged, bit for bit.
TEST(SmoluchowskiSolve, AStopEndsTheIntegrationAtTheNextRightHandSide) {
  const smol::Parameters p = sticking_gas();
  const double nu0 = monomer_collision_frequency(p);
  const std::vector<double> times{0.0, 5.0 / nu0, 20.0 / nu0};
  int asked = 0;
  EXPECT_THROW(smol::solve(p, times, [&] { return ++asked >= 50; }), smol::Stopped);
  EXPECT_GE(asked, 50);
  EXPECT_LE(asked, 70);
  int never = 0;
  const smol::Solution a = smol::solve(p, times, [&] { return ++never < 0; });
  const smol::Solution b = smol::solve(p, times);
  EXPECT_GT(never, 150);
  EXPECT_EQ(a.number_fraction, b.number_fraction);
  EXPECT_EQ(a.kinetic_energy, b.kinetic_energy);
}

TEST(SmoluchowskiSolve, ElasticGasLosesEnergyOnlyByAggregation) {
  // alpha = eps_f = 1: bounces and fragmentations conserve kinetic energy and each aggregation
  // loses E_imp, so dE_kin/dt = -sum over pairs of (events) x (aggregated E_imp), which is
  // sum w_kj (energy_k_agg + energy_j_agg - cm_energy_agg) from pair_moments at the solution state.
  smol::Parameters p = full_model();
  p.restitution = 1.0;
  p.fragment_restitution = 1.0;
  const double nu0 = monomer_collision_frequency(p);
  const double h = 1e-3 / nu0;
  std::vector<double> times;
  for (double t : {5.0, 50.0}) {
    times.push_back(t / nu0 - h);
    times.push_back(t / nu0);
    times.push_back(t / nu0 + h);
  }
  const smol::Solution s = smol::solve(p, times);
  const std::size_t K = s.max_size;
  const double n0 = p.monomer_density;
  for (std::size_t i : {1, 4}) {
    const double rate = (s.kinetic_energy[i + 1] - s.kinetic_energy[i - 1]) / (2.0 * h);
    double loss = 0.0;  // per initial monomer and unit time
    for (std::size_t k = 1; k <= K; ++k)
      for (std::size_t j = k; j <= K; ++j) {
        const double c_k = s.number_fraction[i * K + k - 1], c_j = s.number_fraction[i * K + j - 1];
        if (c_k < 1e-14 || c_j < 1e-14) continue;
        const double T_k = s.temperature[i * K + k - 1], T_j = s.temperature[i * K + j - 1];
        const double sigma = 0.5 * (std::cbrt(k) + std::cbrt(j)) * p.monomer_diameter;
        const double speed = std::sqrt(8.0 * (T_k / k + T_j / j) / p.monomer_mass / pi);
        const double events = n0 * c_k * c_j * pi * sigma * sigma * speed * (k == j ? 0.5 : 1.0);
        const smol::PairMoments m = smol::pair_moments(p, k, j, T_k, T_j);
        loss += events * (m.energy_k_agg + m.energy_j_agg - m.cm_energy_agg);
      }
    EXPECT_LT(rate, 0.0);
    EXPECT_NEAR(rate / -loss, 1.0, 1e-4) << "t nu0 = " << s.time[i] * nu0;
  }
}

// --------------------------------------------------------------------------------------------
// Rates at t = 0
// --------------------------------------------------------------------------------------------

TEST(SmoluchowskiInitialRates, MatchHandComputedValues) {
  const smol::Parameters p = full_model();  // E_agg = 0.5, T0 = m = sigma = 1, n = 0.1
  const smol::InitialRates r = smol::initial_rates(p);
  // Events per unit volume (1/2) n^2 pi sigma^2 sqrt(16 T/(pi m)) = 0.005 sqrt(16 pi)
  // = 0.005 * 7.0898154 = 0.035449077.
  EXPECT_NEAR(r.collisions, 0.035449077, 1e-9);
  // m_11 = 1/2, s = 2, x_a = 0.5/(1/2 * 2) = 0.5: P_agg = 1 - 1.5 e^-0.5 = 1 - 1.5 * 0.60653066
  // = 0.09020401; aggregations = 0.035449077 * 0.09020401 = 0.0031976489.
  EXPECT_NEAR(r.aggregations, 0.0031976489, 1e-10);
  EXPECT_EQ(r.fragmentations, 0.0);  // monomer pairs never shatter
  EXPECT_NEAR(r.bounces, 0.035449077 - 0.0031976489, 1e-9);
  // Each aggregation takes two monomers: d ln n_1/dt = -2 * 0.0031976489/0.1 = -0.063952978.
  EXPECT_NEAR(r.log_monomer_rate, -0.063952978, 1e-8);

  // The integrated equations start with the same rates: over dt = 1e-4 (1.4e-5 collision times)
  // the rates drift by |d ln(rate)/dt| dt/2 ~ 0.13 * 5e-5 = 7e-6 relative, hence 2e-5.
  const double dt = 1e-4;
  const smol::Solution s = smol::solve(p, {0.0, dt});
  EXPECT_NEAR(std::log(s.number_fraction[s.max_size]) / dt / r.log_monomer_rate, 1.0, 2e-5);
  EXPECT_NEAR(s.aggregations[1] / dt / (r.aggregations / p.monomer_density), 1.0, 2e-5);
  EXPECT_NEAR(s.collisions[1] / dt / (r.collisions / p.monomer_density), 1.0, 2e-5);
}

TEST(SmoluchowskiInitialRates, RejectsBadParameters) {
  smol::Parameters p = full_model();
  p.restitution = 1.5;
  EXPECT_THROW(smol::initial_rates(p), std::invalid_argument);
  p = full_model();
  p.aggregation_energy = -1.0;
  EXPECT_THROW(smol::pair_moments(p, 1, 2, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(smol::pair_moments(full_model(), 0, 2, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(smol::solve(full_model(), {1.0, 0.5}), std::invalid_argument);
}
