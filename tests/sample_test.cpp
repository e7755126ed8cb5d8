// Unit tests for gdsmc::sample: moments of one replica (T_k, c_k, N_k, T), the velocity histogram and
// the replica statistics (mean, standard error).
#include "dsmc/sample.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "model/species.hpp"

using namespace gdsmc;

namespace {

species::Mixture mixture(std::vector<double> mass) {
  const std::size_t s = mass.size();
  return species::make_mixture(std::move(mass), std::vector<double>(s, 1.0),
                               std::vector<double>(s, 0.1), species::PairMatrix(s, 1.0), false);
}

// A system from explicit per-species velocity lists.
particles::System build(const std::vector<std::vector<std::array<double, 3>>>& velocities) {
  particles::System sys;
  for (std::size_t k = 0; k < velocities.size(); ++k) {
    sys.first.push_back(sys.size());
    sys.count.push_back(velocities[k].size());
    for (const auto& v : velocities[k]) {
      sys.v.push_back({v[0], v[1], v[2]});
      sys.species.push_back(static_cast<std::uint32_t>(k));
    }
  }
  return sys;
}

void shift(particles::System& sys, double ux, double uy, double uz) {
  for (std::size_t i = 0; i < sys.size(); ++i) {
    sys.v[i].x += ux;
    sys.v[i].y += uy;
    sys.v[i].z += uz;
  }
}

}  // namespace

// Hand-built two-species system with zero total momentum.
// Species 0 (m = 2): the six velocities +-e_x, +-e_y, +-e_z: <v^2> = 1, <v^4> = 1, so T_0 = 2/3 and
//   c_0 = 2 [(3/5) 1 - 1] = -0.8 (all speeds equal).
// Species 1 (m = 3): (+-2, 0, 0), (0, +-1, 0): <v^2> = 5/2, <v^4> = 17/2, T_1 = 5/2,
//   c_1 = 2 [(3/5)(17/2)/(25/4) - 1] = -0.368.
// T = (6 T_0 + 4 T_1) / 10 = 1.4.
TEST(Sample, MeasureHandBuiltSystem) {
  const auto mix = mixture({2.0, 3.0});
  auto sys = build({{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                    {{2, 0, 0}, {-2, 0, 0}, {0, 1, 0}, {0, -1, 0}}});
  const auto m = sample::measure(mix, sys);
  ASSERT_EQ(m.temperature.size(), 2u);
  EXPECT_NEAR(m.temperature[0], 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(m.temperature[1], 2.5, 1e-15);
  EXPECT_NEAR(m.sonine_c[0], -0.8, 1e-15);
  EXPECT_NEAR(m.sonine_c[1], -0.368, 1e-15);
  EXPECT_EQ(m.number, (std::vector<double>{6.0, 4.0}));
  EXPECT_NEAR(m.total_temperature, 1.4, 1e-15);
}

// The velocities are taken relative to the mass-weighted mean flow of the whole system, not per
// species: species 0 (m = 1) drifting at +e_x and species 1 (m = 2) at -e_x/2 with zero total momentum
// have T_0 = 1/3, T_1 = 2 (1/4)/3 = 1/6 (the relative drift counts as temperature), c = -0.8 both.
TEST(Sample, MeasureUsesTotalMeanFlow) {
  const auto mix = mixture({1.0, 2.0});
  auto sys = build({{{1, 0, 0}, {1, 0, 0}}, {{-0.5, 0, 0}, {-0.5, 0, 0}}});
  const auto m = sample::measure(mix, sys);
  EXPECT_NEAR(m.temperature[0], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(m.temperature[1], 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(m.sonine_c[0], -0.8, 1e-14);
  EXPECT_NEAR(m.sonine_c[1], -0.8, 1e-14);
  EXPECT_NEAR(m.total_temperature, 0.25, 1e-15);
}

// Adding a uniform velocity to every particle changes neither T_k nor c_k (nor T): hand-built system
// (exact to 1e-13) and a random 3-species system with unequal masses (1e-12 relative).
TEST(Sample, MeasureIsGalileanInvariant) {
  {
    const auto mix = mixture({2.0, 3.0});
    auto sys = build({{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                      {{2, 0, 0}, {-2, 0, 0}, {0, 1, 0}, {0, -1, 0}}});
    shift(sys, 0.3, -1.7, 2.2);
    const auto m = sample::measure(mix, sys);
    EXPECT_NEAR(m.temperature[0], 2.0 / 3.0, 1e-13);
    EXPECT_NEAR(m.temperature[1], 2.5, 1e-13);
    EXPECT_NEAR(m.sonine_c[0], -0.8, 1e-13);
    EXPECT_NEAR(m.sonine_c[1], -0.368, 1e-13);
    EXPECT_NEAR(m.total_temperature, 1.4, 1e-13);
  }
  const auto mix = mixture({1.0, 5.0, 0.5});
  auto gen = rng::make_stream(4, 0, rng::Purpose::sampling);
  particles::System sys;
  const std::size_t counts[3] = {300, 200, 100};
  for (std::uint32_t k = 0; k < 3; ++k) {
    sys.first.push_back(sys.size());
    sys.count.push_back(counts[k]);
    for (std::size_t i = 0; i < counts[k]; ++i) {  // per-species drifts, non-Gaussian shapes
      sys.v.push_back({gen.normal() + 0.2 * k, gen.uniform() - 0.1 * k, gen.normal() * gen.normal()});
      sys.species.push_back(k);
    }
  }
  const auto before = sample::measure(mix, sys);
  shift(sys, 3.0, -2.0, 0.5);
  const auto after = sample::measure(mix, sys);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(after.temperature[k] / before.temperature[k], 1.0, 1e-12);
    EXPECT_NEAR(after.sonine_c[k], before.sonine_c[k], 1e-12);
  }
  EXPECT_NEAR(after.total_temperature / before.total_temperature, 1.0, 1e-12);
}

// Moments with the given temperatures and no mean flow, for histograms built by hand.
sample::Moments at_rest(std::vector<double> temperature) {
  sample::Moments m;
  m.temperature = std::move(temperature);
  return m;
}

// The histogram is of velocities relative to the mean flow: a drift of the whole gas changes nothing.
TEST(Sample, VelocityHistogramIgnoresMeanFlow) {
  const auto mix = mixture({1.0});
  auto gen = rng::make_stream(5, 0, rng::Purpose::initial_state);
  auto sys = particles::make_system(mix, {1000}, {1.0}, particles::InitialDistribution::maxwell, gen);
  const auto still = sample::velocity_histogram(mix, sys, sample::measure(mix, sys), 10, 3.0);
  for (std::size_t i = 0; i < sys.size(); ++i) sys.v[i].x += 0.7;
  const auto moving = sample::velocity_histogram(mix, sys, sample::measure(mix, sys), 10, 3.0);
  for (std::size_t b = 0; b < 10; ++b) EXPECT_NEAR(moving[b], still[b], 1e-12) << "bin " << b;
}

// Bins by hand. Species 0: m = 4, T = 1, so c = 2 v; species 1: m = 1, T = 4, so c = v / 2.
// bins = 4 on [-2, 2): [-2,-1), [-1,0), [0,1), [1,2), width 1; density = count / (3 N_k width).
TEST(Sample, VelocityHistogramBinsAndNormalisation) {
  const auto mix = mixture({4.0, 1.0});
  // Species 0 components c: (0.5, -0.5, 1.5), (-2, 0, 0.9998) -> bins 2,1,3 and 0,2,2.
  // Species 1 components c: (0.5, 1.0, -1.0), (-0.25, 1.999, -2.0) -> bins 2,3,1 and 1,3,0.
  auto sys = build({{{0.25, -0.25, 0.75}, {-1.0, 0.0, 0.4999}},
                    {{1.0, 2.0, -2.0}, {-0.5, 3.998, -4.0}}});
  const auto h = sample::velocity_histogram(mix, sys, at_rest({1.0, 4.0}), 4, 2.0);
  ASSERT_EQ(h.size(), 8u);
  const double u = 1.0 / 6.0;  // one count of 3 * 2 components, width 1
  const std::vector<double> expected{u, u, 3 * u, u, u, 2 * u, u, 2 * u};
  for (std::size_t b = 0; b < 8; ++b) EXPECT_NEAR(h[b], expected[b], 1e-15) << "bin " << b;
  for (std::size_t k = 0; k < 2; ++k) {
    double integral = 0.0;
    for (std::size_t b = 0; b < 4; ++b) integral += h[k * 4 + b] * 1.0;
    EXPECT_NEAR(integral, 1.0, 1e-15);
  }
  // Components at or beyond the range are dropped ([-range, range) is kept): c = 2 and c = -2.02.
  auto out = build({{{1.0, -1.01, 0.0}}});
  const auto mix1 = mixture({4.0});
  const auto ho = sample::velocity_histogram(mix1, out, at_rest({1.0}), 4, 2.0);
  EXPECT_NEAR(ho[0] + ho[1] + ho[2] + ho[3], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(ho[2], 1.0 / 3.0, 1e-15);
}

// A Maxwellian (make_system, N = 1e5, T = 2, m = 3) gives a histogram that integrates to 1 (range 12
// holds every component) and, on 20 bins over [-4, 4), matches the standard normal density
// averaged over each bin: expected p_b / width with p_b from erfc; SE = sqrt(p_b (1 - p_b) / 3N) /
// width (3N = 3e5 pooled components, independent for a Gaussian); tolerance 5 SE per bin.
TEST(Sample, VelocityHistogramOfMaxwellian) {
  const auto mix = mixture({3.0});
  auto gen = rng::make_stream(31, 0, rng::Purpose::initial_state);
  const std::size_t n = 100000;
  const auto sys = particles::make_system(mix, {n}, {2.0}, particles::InitialDistribution::maxwell, gen);
  const auto wide = sample::velocity_histogram(mix, sys, at_rest({2.0}), 60, 12.0);
  double integral = 0.0;
  for (double x : wide) integral += x * (24.0 / 60.0);
  EXPECT_NEAR(integral, 1.0, 1e-12);

  const std::size_t bins = 20;
  const double range = 4.0, width = 2.0 * range / bins, samples = 3.0 * n;
  const auto h = sample::velocity_histogram(mix, sys, at_rest({2.0}), bins, range);
  double worst = 0.0;
  for (std::size_t b = 0; b < bins; ++b) {
    const double lo = -range + b * width, hi = lo + width;
    const double p = 0.5 * (std::erfc(-hi / std::sqrt(2.0)) - std::erfc(-lo / std::sqrt(2.0)));
    const double se = std::sqrt(p * (1.0 - p) / samples) / width;
    worst = std::max(worst, std::abs(h[b] - p / width) / se);
    EXPECT_NEAR(h[b], p / width, 5.0 * se) << "bin " << b;
  }
  std::printf("[ Sample.Histogram ] worst bin deviation %.2f SE over %zu bins\n", worst, bins);
}

// Accumulator: 3 replicas, 2 sample rows of 2 columns each; mean and SE = s / sqrt(R) element-wise
// with the unbiased s. Per element the replica values are (1,2,3), (2,4,6), (3,5,4), (4,6,8):
// means 2, 4, 4, 6; s = 1, 2, 1, 2; SE = s / sqrt(3).
TEST(Sample, AccumulatorMeanAndStandardError) {
  observables::Accumulator acc;
  acc.columns = 2;
  acc.add(2, {3.0, 6.0});  // replicas may arrive in any order
  acc.add(0, {1.0, 2.0});
  acc.add(0, {3.0, 4.0});
  acc.add(1, {2.0, 4.0});
  acc.add(1, {5.0, 6.0});
  acc.add(2, {4.0, 8.0});
  ASSERT_EQ(acc.values.size(), 3u);
  EXPECT_EQ(acc.values[0], (std::vector<double>{1.0, 2.0, 3.0, 4.0}));
  const auto mean = acc.mean();
  const auto se = acc.standard_error();
  const std::vector<double> mean_expected{2.0, 4.0, 4.0, 6.0};
  const std::vector<double> se_expected{1.0 / std::sqrt(3.0), 2.0 / std::sqrt(3.0),
                                        1.0 / std::sqrt(3.0), 2.0 / std::sqrt(3.0)};
  ASSERT_EQ(mean.size(), 4u);
  ASSERT_EQ(se.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(mean[i], mean_expected[i], 1e-15);
    EXPECT_NEAR(se[i], se_expected[i], 1e-15);
  }
}

TEST(Sample, AccumulatorOneReplica) {
  observables::Accumulator acc;
  acc.add(0, {1.5});
  acc.add(0, {-2.0});
  EXPECT_EQ(acc.mean(), (std::vector<double>{1.5, -2.0}));
  EXPECT_TRUE(acc.standard_error().empty());
}

// G_i = exp(2 beta v*/zeta*) Phi_i (Montanero and Garzo 2002, eq. (30)) has no meaning without cooling:
// an elastic run (zeta* = 0) wrote +Inf in every bin (or NaN where Phi = 0). It is written as 0 there,
// as Delta is where it is undefined; with cooling it is the weight times Phi, by hand at one bin.
TEST(Sample, ReducedDistributionsAreFiniteWithoutCooling) {
  const species::Mixture mix = mixture({1.0});
  const std::size_t bins = 4;
  const double range = 4.0;
  const std::vector<double> phi{0.1, 0.2, 0.0, 0.05}, phi_error{0.01, 0.01, 0.0, 0.01};
  for (double zeta : {0.0, -1.0, 1e-300}) {
    const auto d = sample::reduced_distributions(mix, phi, phi_error, {0.0}, {1.0}, zeta, bins, range);
    for (std::size_t b = 0; b < bins; ++b) {
      EXPECT_EQ(d.species[0].g[b], 0.0) << "zeta* = " << zeta << ", bin " << b;
      EXPECT_EQ(d.species[0].g_error[b], 0.0);
      EXPECT_TRUE(std::isfinite(d.species[0].delta[b]));
    }
  }
  const auto d = sample::reduced_distributions(mix, phi, phi_error, {0.1}, {1.0}, 2.0, bins, range);
  const double beta = M_PI * mix.pair_correlation(0, 0);  // one species: pi chi (sigma/sigma)^2
  EXPECT_NEAR(d.species[0].g[1], std::exp(2.0 * beta * 1.5 / 2.0) * 0.2, 1e-12);
}
