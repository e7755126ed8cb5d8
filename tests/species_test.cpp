// Unit tests for gdsmc::species: pair data and the Carnahan-Starling pair correlation (\ref cm_chi "docs/collision-model.md").
#include "model/species.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using namespace gdsmc::species;

TEST(Species, PairDataOfBinaryMixture) {
  PairMatrix alpha(2, 0.8);
  const Mixture mix = make_mixture({1.0, 4.0}, {1.0, 3.0}, {0.02, 0.01}, alpha, false);
  EXPECT_DOUBLE_EQ(mix.contact_distance(0, 1), 2.0);
  EXPECT_DOUBLE_EQ(mix.reduced_mass(0, 1), 0.8);
  EXPECT_DOUBLE_EQ(mix.mass_fraction(0, 1) + mix.mass_fraction(1, 0), 1.0);
  EXPECT_DOUBLE_EQ(mix.pair_correlation(0, 1), 1.0);
  EXPECT_NEAR(mix.mole_fraction(0), 2.0 / 3.0, 1e-15);
}

// For one species Carnahan-Starling reduces to chi = (1 - phi/2)/(1 - phi)^3.
TEST(Species, CarnahanStarlingOneSpeciesLimit) {
  const double n = 0.5, sigma = 1.0;
  const double phi = std::numbers::pi / 6.0 * n * sigma * sigma * sigma;
  const PairMatrix chi = carnahan_starling({sigma}, {n});
  EXPECT_NEAR(chi(0, 0), (1.0 - phi / 2.0) / std::pow(1.0 - phi, 3), 1e-14);
}

// Splitting one species into two identical labels must not change chi.
TEST(Species, CarnahanStarlingIdenticalSpecies) {
  const PairMatrix chi1 = carnahan_starling({1.0}, {0.4});
  const PairMatrix chi2 = carnahan_starling({1.0, 1.0}, {0.1, 0.3});
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 2; ++j) EXPECT_NEAR(chi2(i, j), chi1(0, 0), 1e-14);
}

// Unequal diameters, hand-computed (issue 13: chi_ij enters the DSMC rates and the theory through the
// same code, so only an independent number catches an error in it). \ref cm_chi "docs/collision-model.md" / docs/physics.md,
// Carnahan-Starling mixture form: sigma = (1, 2), n = (0.1, 0.05):
// phi = (pi/6)(0.1 * 1 + 0.05 * 8) = pi/12, xi = (pi/6)(0.1 * 1 + 0.05 * 4) = pi/20,
// S_11 = 1, S_22 = 2, S_12 = 2/1.5 = 4/3,
// chi_ij = 1/(1 - phi) + (3/2) xi S/(1 - phi)^2 + (1/2) xi^2 S^2/(1 - phi)^3:
// chi_11 = 1.8176901428193741, chi_12 = 1.9856686759105446, chi_22 = 2.342071127245575.
TEST(Species, CarnahanStarlingUnequalDiametersHandComputed) {
  const PairMatrix chi = carnahan_starling({1.0, 2.0}, {0.1, 0.05});
  EXPECT_NEAR(chi(0, 0), 1.8176901428193741, 1e-13);
  EXPECT_NEAR(chi(0, 1), 1.9856686759105446, 1e-13);
  EXPECT_NEAR(chi(1, 0), 1.9856686759105446, 1e-13);
  EXPECT_NEAR(chi(1, 1), 2.342071127245575, 1e-13);
  // The Mixture built with enskog = true carries the same numbers (what the DSMC rates use).
  PairMatrix alpha(2, 0.9);
  const Mixture mix = make_mixture({1.0, 8.0}, {1.0, 2.0}, {0.1, 0.05}, alpha, true);
  EXPECT_NEAR(mix.pair_correlation(0, 0), 1.8176901428193741, 1e-13);
  EXPECT_NEAR(mix.pair_correlation(0, 1), 1.9856686759105446, 1e-13);
  EXPECT_NEAR(mix.pair_correlation(1, 1), 2.342071127245575, 1e-13);
}

// Above dense_pair_limit species chi is computed on access and its largest entry is known without the S^2
// pairs (a user's 1e5-species Enskog run spent 40 s per replica in max(), deaf to Ctrl-C): max() equals the
// largest of all S^2 entries, checked pair by pair, for 600 species with diameters k^(1/3) (the largest unique),
// with every diameter equal, and with the largest diameter shared by three species and one more 1 ulp below
// it: for some of the 16 largest diameters and densities tried (the diameters found by a search) the round-off
// of S_ij then puts that pair's chi above the largest diameters' own, which max() must still find.
TEST(Species, CarnahanStarlingLargestEntryOfManySpecies) {
  const std::size_t s = 600;
  ASSERT_GT(s, dense_pair_limit);
  const auto largest_by_pairs = [](const PairMatrix& chi) {
    double m = -1.0;
    for (std::size_t i = 0; i < chi.size; ++i)
      for (std::size_t j = 0; j < chi.size; ++j) m = std::max(m, chi(i, j));
    return m;
  };
  const auto expect_largest = [&](const std::vector<double>& diameter, double density) {
    const PairMatrix chi = carnahan_starling(diameter, std::vector<double>(diameter.size(), density));
    EXPECT_FALSE(chi.is_dense());
    EXPECT_TRUE(chi.largest.has_value());
    const double by_pairs = largest_by_pairs(chi);
    EXPECT_EQ(chi.max(), by_pairs) << "density " << density;
    EXPECT_GT(by_pairs, 1.0);
    return by_pairs;
  };
  std::vector<double> rising(s), equal(s, 1.5);
  for (std::size_t k = 0; k < s; ++k) rising[k] = std::cbrt(static_cast<double>(k + 1));
  expect_largest(rising, 1e-6);
  expect_largest(equal, 1e-6);
  int passed_by_round_off = 0;
  for (double top : {25.75890720840042, 25.995683065505144, 29.216452176614776, 48.71498657182489})
    for (double density : {5e-7, 1e-6, 2e-6, 3e-6}) {
      std::vector<double> shared(s);
      for (std::size_t k = 0; k < s; ++k) shared[k] = std::cbrt(static_cast<double>(k % 300 + 1));
      shared[5] = shared[17] = shared[400] = top;
      shared[401] = std::nextafter(top, 0.0);
      if (top * top * top * density * 3.0 > 0.5) continue;  // (a packing fraction the test need not reach)
      const double by_pairs = expect_largest(shared, density);
      const PairMatrix chi = carnahan_starling(shared, std::vector<double>(s, density));
      passed_by_round_off += by_pairs > chi(5, 5);
    }
  EXPECT_GT(passed_by_round_off, 0) << "no case where the round-off of S_ij passes the largest diameters' chi";
  // (a write access drops it: the entry may change)
  PairMatrix written = carnahan_starling(rising, std::vector<double>(s, 1e-6));
  written(0, 0) = 10.0;
  EXPECT_EQ(written.max(), 10.0);
}
