// Unit tests for gdsmc::theory::estimate_run_cost (theory/run_cost.hpp): Haff's law for one species,
// a held temperature, the viscoelastic upper bound and the O(S) bounds of many species.
#include "theory/run_cost.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "theory/rough.hpp"
#include "theory/theory.hpp"

namespace theory = gdsmc::theory;
namespace species = gdsmc::species;

namespace {

species::Mixture one_species(double alpha) {
  return species::make_mixture({1.0}, {1.0}, {0.01}, species::PairMatrix(1, alpha), false);
}

}  // namespace

TEST(RunCost, OneSpeciesFollowsHaffsLaw) {
  const auto mix = one_species(0.9);
  const double nu0 = theory::collision_frequency(0.01, 1.0, 1.0, 1.0, 1.0);
  const double zeta0 = theory::haff_cooling_rate(0.01, 1.0, 1.0, 1.0, 0.9, 1.0);
  const double t0 = 2.0 / zeta0;  // \ref haff_law "docs/haff-and-mixtures.md"
  for (double t : {10.0, 5000.0, 1e30}) {
    const auto cost = theory::estimate_run_cost(mix, {1.0}, t, std::nullopt, theory::Cooling::haff);
    // C = int nu dt = nu0 t0 ln(1 + t/t0) with nu = nu0 sqrt(T/T0), T = T0/(1 + t/t0)^2
    EXPECT_NEAR(cost.collisions_per_particle, nu0 * t0 * std::log1p(t / t0), 1e-9 * cost.collisions_per_particle);
    EXPECT_NEAR(cost.temperature_ratio, theory::haff_temperature(t, 1.0, zeta0), 1e-9 * cost.temperature_ratio);
    // The same run given by its collision count cools by the same factor.
    const auto by_count = theory::estimate_run_cost(mix, {1.0}, std::nullopt, cost.collisions_per_particle,
                                                    theory::Cooling::haff);
    EXPECT_NEAR(std::log(by_count.temperature_ratio), std::log(cost.temperature_ratio), 1e-9 * 140.0);
  }
  // t_end = 1e30 cools by about 55 decades in about 2000 collisions per particle.
  const auto far = theory::estimate_run_cost(mix, {1.0}, 1e30, std::nullopt, theory::Cooling::haff);
  EXPECT_LT(far.temperature_ratio, 1e-50);
  EXPECT_LT(far.collisions_per_particle, 3000.0);
}

TEST(RunCost, HeldOrElasticGasCollidesAtTheInitialRate) {
  const double nu0 = theory::collision_frequency(0.01, 1.0, 1.0, 1.0, 1.0);
  for (auto [alpha, cooling] : {std::pair{0.9, theory::Cooling::held}, std::pair{1.0, theory::Cooling::haff},
                                std::pair{1.0, theory::Cooling::viscoelastic}}) {
    const auto cost = theory::estimate_run_cost(one_species(alpha), {1.0}, 1e4, std::nullopt, cooling);
    EXPECT_NEAR(cost.collisions_per_particle, nu0 * 1e4, 1e-9 * nu0 * 1e4);
    EXPECT_EQ(cost.temperature_ratio, 1.0);
  }
}

TEST(RunCost, ManySpeciesBoundsTheExactEstimate) {
  // 65 species (beyond exact_species): the O(S) bounds give at least the exact collision count of a
  // mixture whose species differ little, and an astronomically long run stays finite.
  const std::size_t s = theory::exact_species + 1;
  std::vector<double> mass(s), diameter(s), density(s, 0.001);
  for (std::size_t k = 0; k < s; ++k) mass[k] = 1.0 + 0.01 * static_cast<double>(k), diameter[k] = 1.0;
  const auto big = species::make_mixture(mass, diameter, density, species::PairMatrix::uniform(s, 0.9), false);
  const std::vector<double> t0(s, 1.0);
  const auto bound = theory::estimate_run_cost(big, t0, 100.0, std::nullopt, theory::Cooling::haff);
  const double exact_nu0 = 2.0 * theory::total_collision_rate(big, t0) / big.total_density();
  EXPECT_GE(bound.collisions_per_particle, 0.5 * exact_nu0 * 100.0 * 0.9);  // cools little by t = 100
  EXPECT_LT(bound.collisions_per_particle, 3.0 * exact_nu0 * 100.0);
  const auto huge = theory::estimate_run_cost(big, t0, 1e300, std::nullopt, theory::Cooling::haff);
  EXPECT_TRUE(std::isfinite(huge.collisions_per_particle));
  EXPECT_EQ(huge.temperature_ratio, 0.0);
}

// Rough spheres cool by their rotation even at alpha = 1: alpha = 1, beta = 0, kappa = 0.4 has zeta* =
// (4/3)(A - B theta) = 0.1361 per collision per particle (theory/rough.hpp), so 2000 collisions per
// particle end at exp(-272) of T_0 (refused by the run-cost check) where the smooth estimate saw no cooling.
TEST(RunCost, RoughSpheresCoolByTheirRotation) {
  auto mix = gdsmc::species::make_mixture({1.0}, {1.0}, {0.01}, gdsmc::species::PairMatrix(1, 1.0), false);
  mix.roughness = gdsmc::species::PairMatrix(1, 0.0);
  mix.moment_of_inertia = {0.4};
  const double r = gdsmc::theory::rough::cooling_state(1.0, 0.0, 0.4).cooling_rate_reduced;
  EXPECT_NEAR(r, 0.1361, 1e-4);
  const auto cost = gdsmc::theory::estimate_run_cost(mix, {1.0}, std::nullopt, 2000.0, gdsmc::theory::Cooling::haff);
  EXPECT_NEAR(std::log(cost.temperature_ratio), -r * 2000.0, 1e-9 * r * 2000.0);
  EXPECT_LT(cost.temperature_ratio, 1e-40);
}

TEST(RunCost, WhiteNoiseHeatsTowardsTheDrivenStateOrByItsEnergy) {
  // By hand (run_cost.hpp): m = sigma = 1, n = 0.01, T_0 = 1, chi^2 = 1: nu_0 = 4 n sqrt(pi) = 0.0708981540362,
  // r = (1 - 0.81)/3 = 0.0633333; (T_st/T_0)^(3/2) = 1/(r nu_0): T_st = 36.7413534715 T_0.
  const auto inelastic = one_species(0.9);
  EXPECT_NEAR(theory::white_noise_heating(inelastic, {1.0}, {1.0}, 1e6), 36.7413534715, 1e-8);
  // Short runs: the noise's energy kept, T_0 + m chi^2 t_end (11 after t = 10), below the steady state.
  EXPECT_NEAR(theory::white_noise_heating(inelastic, {1.0}, {1.0}, 10.0), 11.0, 1e-12);
  // Elastic: no steady state, the energy bound alone; T_0 = 2 halves the factor's growth.
  EXPECT_NEAR(theory::white_noise_heating(one_species(1.0), {2.0}, {1.0}, 1e6), 1.0 + 1e6 / 2.0, 1e-6);
  // A noise too weak to hold T_0 (the gas cools towards a colder steady state): never below 1.
  EXPECT_EQ(theory::white_noise_heating(inelastic, {1.0}, {1e-6}, 1e6), 1.0);
  // Mixture (m = 1, 4; x = 1/2 each): P = max m_k chi^2_k = 4 x 0.5 = 2, T_0 = (1 + 3)/2 = 2: P t/T_0 = 1 at t = 1.
  const auto binary = species::make_mixture({1.0, 4.0}, {1.0, 1.0}, {0.01, 0.01}, species::PairMatrix::uniform(2, 1.0), false);
  EXPECT_NEAR(theory::white_noise_heating(binary, {1.0, 3.0}, {0.1, 0.5}, 1.0), 2.0, 1e-12);
  // 65 equal smooth species (beyond exact_species: the O(S) bound nu_0 = n pi sigma^2 sqrt(16 T/(pi m)), the
  // same 4 n sqrt(pi) here, and r = (1 - alpha_max^2)/3): the one species' 36.74, not the energy bound 1e6 + 1.
  const std::size_t s = theory::exact_species + 1;
  const auto many = species::make_mixture(std::vector<double>(s, 1.0), std::vector<double>(s, 1.0),
                                          std::vector<double>(s, 0.01 / static_cast<double>(s)),
                                          species::PairMatrix::uniform(s, 0.9), false);
  EXPECT_NEAR(theory::white_noise_heating(many, std::vector<double>(s, 1.0), std::vector<double>(s, 1.0), 1e6),
              36.7413534715, 1e-8);
}
