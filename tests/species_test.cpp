// Unit tests for gdsmc::species: pair data and the Carnahan-Starling pair correlation (\ref cm_chi "docs/collision-model.md").
#include "model/species.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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
