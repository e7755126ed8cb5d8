// Unit tests for the first-Sonine HCS of s species (theory/sonine_mixture.hpp; Montanero and Garzo 2002, App. A, \ref son_binary "docs/sonine.md",
// \ref son_binary "docs/sonine.md", Garzo and Dufty 2002). References: the binary solver of theory/sonine.hpp (a
// different root finder on a different formulation: gamma-grid + Brent, Cramer's rule), the
// one-component theory of \ref haff_sonine "docs/haff-and-mixtures.md" (theory::sonine_a2), the Maxwellian cooling rates of \ref haff_mixture_odes "docs/haff-and-mixtures.md"
// (theory::cooling_rate_matrix), exact limits (elastic; mechanically identical species merge) and
// the permutation symmetry.
#include "theory/sonine_mixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "theory/sonine.hpp"
#include "theory/theory.hpp"

using gdsmc::species::make_mixture;
using gdsmc::species::Mixture;
using gdsmc::species::PairMatrix;
namespace theory = gdsmc::theory;

namespace {

constexpr double pi = std::numbers::pi;

/// Binary mixture in Montanero and Garzo 2002's parameters (as tests/sonine_test.cpp): mu = m1/m2, delta = n1/n2,
/// w = sigma_1/sigma_2; Enskog at reduced density n* = n sigma_12^3.
Mixture seed_mixture(double mu, double delta, double w, double a11, double a22, double a12,
                     bool enskog = false, double n_star = 0.0) {
  const double sigma_12 = 0.5 * (w + 1.0);
  const double n = enskog ? n_star / (sigma_12 * sigma_12 * sigma_12) : 1.0;
  PairMatrix alpha(2);
  alpha(0, 0) = a11;
  alpha(1, 1) = a22;
  alpha(0, 1) = alpha(1, 0) = a12;
  return make_mixture({mu, 1.0}, {w, 1.0}, {n * delta / (1.0 + delta), n / (1.0 + delta)}, alpha,
                      enskog);
}

Mixture mixture(std::vector<double> m, std::vector<double> sigma, std::vector<double> n,
                const std::vector<std::vector<double>>& a, bool enskog) {
  PairMatrix alpha(m.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = 0; j < m.size(); ++j) alpha(i, j) = a[i][j];
  return make_mixture(std::move(m), std::move(sigma), std::move(n), alpha, enskog);
}

/// The mixture with species reordered: new species k is old species perm[k].
Mixture permuted(const Mixture& mix, const std::vector<std::size_t>& perm) {
  const std::size_t s = perm.size();
  std::vector<double> m(s), sigma(s), n(s);
  std::vector<std::vector<double>> a(s, std::vector<double>(s));
  for (std::size_t k = 0; k < s; ++k) {
    m[k] = mix.mass[perm[k]];
    sigma[k] = mix.diameter[perm[k]];
    n[k] = mix.number_density[perm[k]];
    for (std::size_t j = 0; j < s; ++j) a[k][j] = mix.restitution(perm[k], perm[j]);
  }
  return mixture(m, sigma, n, a, mix.enskog);
}

}  // namespace

// 1. s = 2 reproduces binary_hcs_first_sonine (gamma, c1, c2, zeta*) to 1e-10, dilute and Enskog,
// including the \ref son_binary_gamma "docs/sonine.md" reference mu = 10, delta = 2, w = 1, alpha = 0.5 (gamma = 3.8005,
// c1 = 0.1091, c2 = 0.0180).
TEST(SonineMixtureHcs, TwoSpeciesReproduceTheBinarySolver) {
  const std::vector<Mixture> cases = {
      seed_mixture(10.0, 2.0, 1.0, 0.5, 0.5, 0.5),
      seed_mixture(2.0, 1.0, 1.0, 0.5, 0.5, 0.5),
      seed_mixture(0.25, 0.5, 2.0, 0.6, 0.9, 0.75),
      seed_mixture(0.25, 0.5, 2.0, 0.6, 0.9, 0.75, true, 0.3),
      seed_mixture(10.0, 2.0, 1.0, 0.5, 0.5, 0.5, true, 0.2),
      seed_mixture(4.0, 0.2, 1.5, 0.9, 0.7, 0.8, true, 0.4),
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    SCOPED_TRACE(::testing::Message() << "case " << k);
    const auto bin = theory::binary_hcs_first_sonine(cases[k]);
    const auto hcs = theory::hcs_first_sonine(cases[k]);
    ASSERT_EQ(hcs.temperature_over_mean.size(), 2u);
    const double gamma = hcs.temperature_over_mean[0] / hcs.temperature_over_mean[1];
    EXPECT_NEAR(gamma, bin.temperature_ratio, 1e-10 * bin.temperature_ratio);
    EXPECT_NEAR(hcs.sonine_c[0], bin.sonine_c[0], 1e-10);
    EXPECT_NEAR(hcs.sonine_c[1], bin.sonine_c[1], 1e-10);
    EXPECT_NEAR(hcs.cooling_rate_reduced, bin.cooling_rate, 1e-10 * bin.cooling_rate);
    const double x1 = cases[k].mole_fraction(0);
    EXPECT_NEAR(x1 * hcs.temperature_over_mean[0] + (1.0 - x1) * hcs.temperature_over_mean[1], 1.0,
                1e-13);
    if (k == 0) {
      EXPECT_NEAR(gamma, 3.8005, 5e-5);
      EXPECT_NEAR(hcs.sonine_c[0], 0.1091, 5e-5);
      EXPECT_NEAR(hcs.sonine_c[1], 0.0180, 5e-5);
    }
  }
}

// 2. Three species of which two are mechanically identical (same m, sigma and alpha with every
// species) are the binary mixture with the two merged (densities added): same T_k/T, same c_k, same
// physical cooling rate zeta* x unit (the unit depends on s, sonine_mixture.hpp "Reduction").
TEST(SonineMixtureHcs, IdenticalSpeciesMergeIntoTheBinary) {
  for (bool enskog : {false, true}) {
    SCOPED_TRACE(::testing::Message() << "enskog " << enskog);
    const double nA = enskog ? 0.15 : 0.3, nA2 = enskog ? 0.1 : 0.2, nB = enskog ? 0.05 : 0.5;
    const double aAA = 0.7, aAB = 0.8, aBB = 0.9;
    const Mixture three = mixture({1.0, 4.0, 1.0}, {1.0, 1.5, 1.0}, {nA, nB, nA2},
                                  {{aAA, aAB, aAA}, {aAB, aBB, aAB}, {aAA, aAB, aAA}}, enskog);
    const Mixture two = mixture({1.0, 4.0}, {1.0, 1.5}, {nA + nA2, nB}, {{aAA, aAB}, {aAB, aBB}},
                                enskog);
    const auto h3 = theory::hcs_first_sonine(three);
    const auto h2 = theory::hcs_first_sonine(two);
    const auto bin = theory::binary_hcs_first_sonine(two);
    EXPECT_NEAR(h3.temperature_over_mean[0], h2.temperature_over_mean[0], 1e-10);
    EXPECT_NEAR(h3.temperature_over_mean[2], h2.temperature_over_mean[0], 1e-10);
    EXPECT_NEAR(h3.temperature_over_mean[1], h2.temperature_over_mean[1], 1e-10);
    EXPECT_NEAR(h3.sonine_c[0], h2.sonine_c[0], 1e-10);
    EXPECT_NEAR(h3.sonine_c[2], h2.sonine_c[0], 1e-10);
    EXPECT_NEAR(h3.sonine_c[1], h2.sonine_c[1], 1e-10);
    const double z3 = h3.cooling_rate_reduced * theory::hcs_rate_unit(three);
    const double z2 = bin.cooling_rate * theory::hcs_rate_unit(two);
    EXPECT_NEAR(z3, z2, 1e-10 * z2);
    EXPECT_NEAR(h3.temperature_over_mean[0] / h3.temperature_over_mean[1], bin.temperature_ratio,
                1e-10 * bin.temperature_ratio);
  }
}

// 3. Permuting the species permutes T_k/T and c_k and leaves zeta* unchanged.
TEST(SonineMixtureHcs, PermutingSpeciesPermutesTheAnswer) {
  for (bool enskog : {false, true}) {
    SCOPED_TRACE(::testing::Message() << "enskog " << enskog);
    const double f = enskog ? 0.1 : 1.0;
    const Mixture mix = mixture({1.0, 3.0, 0.5, 8.0}, {1.0, 1.2, 0.8, 2.0},
                                {0.3 * f, 0.2 * f, 0.4 * f, 0.1 * f},
                                {{0.9, 0.8, 0.7, 0.6},
                                 {0.8, 0.75, 0.85, 0.9},
                                 {0.7, 0.85, 0.95, 0.65},
                                 {0.6, 0.9, 0.65, 0.5}},
                                enskog);
    const auto ref = theory::hcs_first_sonine(mix);
    for (const std::vector<std::size_t>& perm :
         {std::vector<std::size_t>{3, 2, 1, 0}, {1, 3, 0, 2}, {2, 0, 3, 1}}) {
      const auto h = theory::hcs_first_sonine(permuted(mix, perm));
      for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_NEAR(h.temperature_over_mean[k], ref.temperature_over_mean[perm[k]], 1e-10);
        EXPECT_NEAR(h.sonine_c[k], ref.sonine_c[perm[k]], 1e-10);
      }
      EXPECT_NEAR(h.cooling_rate_reduced, ref.cooling_rate_reduced,
                  1e-10 * ref.cooling_rate_reduced);
    }
    // and the answer is not trivially symmetric: the species differ
    EXPECT_GT(std::abs(ref.temperature_over_mean[3] - ref.temperature_over_mean[2]), 1e-2);
  }
}

// 4. Elastic limit: equipartition and Maxwellians, no cooling.
TEST(SonineMixtureHcs, ElasticMixtureIsInEquipartition) {
  for (bool enskog : {false, true}) {
    const double f = enskog ? 0.2 : 1.0;
    const Mixture mix = mixture({1.0, 5.0, 0.2}, {1.0, 2.0, 0.7}, {0.5 * f, 0.2 * f, 0.3 * f},
                                {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, enskog);
    const auto h = theory::hcs_first_sonine(mix);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(h.temperature_over_mean[k], 1.0, 1e-12);
      EXPECT_NEAR(h.sonine_c[k], 0.0, 1e-12);
    }
    EXPECT_NEAR(h.cooling_rate_reduced, 0.0, 1e-12);
  }
}

// 5. One species: T_1/T = 1, c = 2 a2 (van Noije-Ernst, theory::sonine_a2) and the one-species
// first-Sonine cooling rate (\ref haff_sonine "docs/haff-and-mixtures.md") zeta = (4/3) sqrt(pi) (1 - alpha^2) n sigma^2 chi sqrt(T/m)
// (1 + 3 a2/16); in the unit n sigma^2 sqrt(4 T/m): zeta* = (2/3) sqrt(pi) (1 - alpha^2) chi
// (1 + 3 a2/16).
TEST(SonineMixtureHcs, OneSpeciesIsTheVanNoijeErnstTheory) {
  for (double alpha : {0.2, 0.5, 0.8, 0.99})
    for (bool enskog : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "alpha " << alpha << " enskog " << enskog);
      const Mixture mix = mixture({2.0}, {1.5}, {enskog ? 0.2 : 1.0}, {{alpha}}, enskog);
      const double chi = mix.pair_correlation(0, 0);
      const double a2 = theory::sonine_a2(alpha);
      const auto h = theory::hcs_first_sonine(mix);
      EXPECT_EQ(h.temperature_over_mean[0], 1.0);
      EXPECT_NEAR(h.sonine_c[0], 2.0 * a2, 1e-12);
      const double zeta = (2.0 / 3.0) * std::sqrt(pi) * (1.0 - alpha * alpha) * chi *
                          (1.0 + 3.0 * a2 / 16.0);
      EXPECT_NEAR(h.cooling_rate_reduced, zeta, 1e-12 * zeta);
    }
}

// The pair terms: zeta0 summed over partners is the Maxwellian partial cooling rate of \ref haff_mixture_odes "docs/haff-and-mixtures.md"
// (theory::cooling_rate_matrix, an independent formula) at arbitrary temperatures; the cross terms
// of a species with an identical copy of itself equal its self terms.
TEST(SonineMixtureHcs, PairTermsMatchMaxwellianCoolingRatesAndSelfTerms) {
  const Mixture mix = mixture({1.0, 3.0, 0.5}, {1.0, 1.2, 0.8}, {0.1, 0.05, 0.15},
                              {{0.9, 0.8, 0.7}, {0.8, 0.75, 0.85}, {0.7, 0.85, 0.6}}, true);
  const std::vector<double> tau = {0.7, 1.6, 0.9};
  double mean = 0.0;
  for (std::size_t k = 0; k < 3; ++k) mean += mix.mole_fraction(k) * tau[k];
  const double T = 2.5;  // any temperature: zeta = zeta* x unit x sqrt(T)
  std::vector<double> temps(3);
  for (std::size_t k = 0; k < 3; ++k) temps[k] = T * tau[k] / mean;
  const auto xi = theory::cooling_rate_matrix(mix, temps);
  for (std::size_t i = 0; i < 3; ++i) {
    double z = 0.0, ref = 0.0;
    for (std::size_t j = 0; j < 3; ++j) {
      z += theory::hcs_pair_terms(mix, i, j, tau[i] / mean, tau[j] / mean).zeta0;
      ref += xi(i, j);
    }
    EXPECT_NEAR(z * theory::hcs_rate_unit(mix) * std::sqrt(T), ref, 1e-12 * std::abs(ref));
  }
  // a species with its mechanical copy: the cross formula (eta = 1, mu = 1/2) equals the self one
  const Mixture copy = mixture({2.0, 2.0}, {1.0, 1.0}, {0.5, 0.5}, {{0.6, 0.6}, {0.6, 0.6}}, false);
  const auto self = theory::hcs_pair_terms(copy, 0, 0, 1.3, 1.3);
  const auto cross = theory::hcs_pair_terms(copy, 0, 1, 1.3, 1.3);
  EXPECT_NEAR(cross.zeta0, self.zeta0, 1e-12 * self.zeta0);
  EXPECT_NEAR(cross.zeta_self + cross.zeta_partner, self.zeta_self, 1e-12 * self.zeta_self);
  EXPECT_NEAR(cross.omega0, self.omega0, 1e-12 * std::abs(self.omega0));
  EXPECT_NEAR(cross.omega_self + cross.omega_partner, self.omega_self,
              1e-12 * std::abs(self.omega_self));
}

// The solution satisfies its equations, recomputed from the public pair terms: equal cooling rates
// zeta_i* = zeta* and the linearised fourth-moment equations, for five species; and s = 100
// converges (checked against the same equations on a few species).
TEST(SonineMixtureHcs, SolutionSatisfiesTheEquations) {
  for (std::size_t s : {5u, 100u}) {
    SCOPED_TRACE(::testing::Message() << "s " << s);
    std::vector<double> m(s), sigma(s), n(s);
    std::vector<std::vector<double>> a(s, std::vector<double>(s));
    for (std::size_t k = 0; k < s; ++k) {
      const double u = static_cast<double>(k) / static_cast<double>(s - 1);
      m[k] = std::pow(10.0, u);
      sigma[k] = 1.0 + 0.5 * u;
      n[k] = (0.2 * (1.0 + std::sin(3.0 * static_cast<double>(k))) + 0.05) / static_cast<double>(s);
      for (std::size_t j = 0; j < s; ++j)
        a[k][j] = 0.6 + 0.3 * std::abs(std::sin(static_cast<double>(k + j)));
    }
    const Mixture mix = mixture(m, sigma, n, a, true);
    const auto h = theory::hcs_first_sonine(mix);
    const auto& tau = h.temperature_over_mean;
    const auto& c = h.sonine_c;
    double norm = 0.0;
    for (std::size_t k = 0; k < s; ++k) norm += mix.mole_fraction(k) * tau[k];
    EXPECT_NEAR(norm, 1.0, 1e-12);
    const double inv_m_mean = [&] {
      double v = 0.0;
      for (double mk : m) v += 1.0 / mk;
      return v / static_cast<double>(s);
    }();
    for (std::size_t i : {std::size_t{0}, s / 2, s - 1}) {
      double zeta = 0.0, omega = 0.0, zeta0 = 0.0;
      for (std::size_t j = 0; j < s; ++j) {
        const auto t = theory::hcs_pair_terms(mix, i, j, tau[i], tau[j]);
        zeta += t.zeta0 + t.zeta_self * c[i] + t.zeta_partner * c[j];
        zeta0 += t.zeta0;
        omega += t.omega0 + t.omega_self * c[i] + t.omega_partner * c[j];
      }
      EXPECT_NEAR(zeta, h.cooling_rate_reduced, 1e-10 * h.cooling_rate_reduced);
      // <v*^4>_i = W_i (1 + c_i/2) with W_i = 15 (T_i/(m_i v_ref^2))^2, v_ref^2 = 4 T <1/m>
      const double t = tau[i] / (m[i] * 4.0 * inv_m_mean);
      const double W = 15.0 * t * t;
      // linearised: -2 W (zeta + zeta0 c_i/2) = Omega (the product c_i x c-terms of zeta dropped)
      const double lhs = -2.0 * W * (zeta + 0.5 * zeta0 * c[i]);
      EXPECT_NEAR(lhs, omega, 1e-9 * std::abs(omega));
    }
  }
}

TEST(SonineMixtureHcs, RejectsBadInput) {
  EXPECT_THROW(theory::hcs_first_sonine(
                   mixture({1.0, -1.0}, {1.0, 1.0}, {1.0, 1.0}, {{0.5, 0.5}, {0.5, 0.5}}, false)),
               std::invalid_argument);
  EXPECT_THROW(theory::hcs_first_sonine(
                   mixture({1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}, {{0.5, 0.4}, {0.6, 0.5}}, false)),
               std::invalid_argument);
  const std::size_t s = theory::max_hcs_species + 1;
  const auto big = make_mixture(std::vector<double>(s, 1.0), std::vector<double>(s, 1.0),
                                std::vector<double>(s, 1.0), PairMatrix::uniform(s, 0.8), false);
  EXPECT_THROW(theory::hcs_first_sonine(big), std::invalid_argument);
}

// The ternary example quoted in docs/physics.md ("First-Sonine HCS of s species"): m = 1 : 3 : 10,
// equal diameters and densities, alpha = 0.7, dilute. A regression check of the quoted numbers.
TEST(SonineMixtureHcs, TernaryExample) {
  PairMatrix alpha(3, 0.7);
  const Mixture mix = make_mixture({1.0, 3.0, 10.0}, {1.0, 1.0, 1.0}, {0.01, 0.01, 0.01}, alpha,
                                   false);
  const auto h = theory::hcs_first_sonine(mix);
  const auto maxwellian = theory::maxwellian_temperature_over_mean(mix);
  const double fs[3] = {0.618447, 0.896304, 1.485249}, mw[3] = {0.614133, 0.896577, 1.489290},
               c[3] = {-0.018645, 0.033403, 0.079726};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(h.temperature_over_mean[k], fs[k], 5e-7);
    EXPECT_NEAR(maxwellian[k], mw[k], 5e-7);
    EXPECT_NEAR(h.sonine_c[k], c[k], 5e-7);
  }
  EXPECT_NEAR(h.cooling_rate_reduced, 0.419184, 5e-7);
  EXPECT_NEAR(theory::hcs_maxwellian_cooling_rate_reduced(mix, maxwellian), 0.417162, 5e-7);
}

// The white-noise steady state (sonine_mixture.hpp \ref sonmix_driven). One species, alpha = 0.9, m = sigma = 1,
// n = 0.01, chi^2 = 0.001, by hand: van Noije and Ernst's a2 = 16 (1 - a)(1 - 2a^2)/(241 - 177a + 30a^2 - 30a^3)
// = -0.0117913, zeta* = (1 - a^2)(1 + 3 a2/16)/3 = 0.0631933 in units of 4 n sigma^2 sqrt(pi T/m), so
// T^(3/2) = m chi^2/(zeta* 4 n sigma^2 sqrt(pi/m)): T = 0.3679561 (docs/white-noise.md, "The steady state").
// At alpha = 0.5 a2 = 0.0256 exactly.
TEST(SonineMixtureWhiteNoise, OneSpeciesIsVanNoijeAndErnst) {
  const auto one = theory::white_noise_first_sonine(make_mixture({1.0}, {1.0}, {0.01}, PairMatrix(1, 0.9), false), {0.001});
  ASSERT_EQ(one.temperature.size(), 1u);
  EXPECT_NEAR(one.sonine_c[0] / 2.0, -0.011791275407108, 1e-12);
  EXPECT_NEAR(one.temperature[0], 0.367956068667187, 1e-12);
  EXPECT_EQ(one.temperature_over_mean[0], 1.0);
  const auto half = theory::white_noise_first_sonine(make_mixture({1.0}, {1.0}, {0.01}, PairMatrix(1, 0.5), false), {0.001});
  EXPECT_NEAR(half.sonine_c[0] / 2.0, 0.0256, 1e-12);
}

// Two identical species are the one species: the same T and c for both (the second started away from it).
TEST(SonineMixtureWhiteNoise, IdenticalSpeciesAreTheOneSpecies) {
  const auto one = theory::white_noise_first_sonine(make_mixture({2.0}, {1.5}, {0.03}, PairMatrix(1, 0.7), false), {0.002});
  const auto two = theory::white_noise_first_sonine(make_mixture({2.0, 2.0}, {1.5, 1.5}, {0.01, 0.02}, PairMatrix(2, 0.7), false),
                                                    {0.002, 0.002}, {1.0, 1.3});
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(two.temperature[k], one.temperature[0], 1e-10 * one.temperature[0]) << "species " << k + 1;
    EXPECT_NEAR(two.sonine_c[k], one.sonine_c[0], 1e-10) << "species " << k + 1;
  }
}

// A binary and a 5-species mixture (Enskog, equal forces): the solution satisfies its equations, recomputed from
// hcs_pair_terms: m_k chi_k^2 = zeta_k T_k with zeta_k = zeta_k* hcs_rate_unit sqrt(T), and the fourth moments
// Omega_i + 2 W_i zeta_i = 0 (the kicks' 10 chi_i^2 <v^2>_i), W_i = 15 (T_i/(m_i v_ref^2))^2.
TEST(SonineMixtureWhiteNoise, SolutionSatisfiesTheEquations) {
  for (std::size_t s : {2u, 5u}) {
    SCOPED_TRACE(::testing::Message() << "s " << s);
    std::vector<double> m(s), sigma(s), n(s), chi2(s);
    std::vector<std::vector<double>> a(s, std::vector<double>(s));
    for (std::size_t k = 0; k < s; ++k) {
      const double u = static_cast<double>(k) / static_cast<double>(s - 1);
      m[k] = std::pow(4.0, u);
      sigma[k] = 1.0 + 0.5 * u;
      n[k] = 0.03 * (1.0 + 0.5 * std::sin(3.0 * static_cast<double>(k))) / static_cast<double>(s);
      chi2[k] = 0.001 / (m[k] * m[k]);  // equal forces
      for (std::size_t j = 0; j < s; ++j) a[k][j] = 0.6 + 0.3 * std::abs(std::sin(static_cast<double>(k + j)));
    }
    const Mixture mix = mixture(m, sigma, n, a, true);
    const auto w = theory::white_noise_first_sonine(mix, chi2);
    double inv_m_mean = 0.0, mean_t = 0.0;
    for (std::size_t k = 0; k < s; ++k) {
      inv_m_mean += 1.0 / m[k] / static_cast<double>(s);
      mean_t += mix.mole_fraction(k) * w.temperature[k];
    }
    const double unit = theory::hcs_rate_unit(mix) * std::sqrt(mean_t);
    for (std::size_t i = 0; i < s; ++i) {
      EXPECT_NEAR(w.temperature_over_mean[i], w.temperature[i] / mean_t, 1e-12);
      double zeta = 0.0, omega = 0.0;
      for (std::size_t j = 0; j < s; ++j) {
        const auto t = theory::hcs_pair_terms(mix, i, j, w.temperature_over_mean[i], w.temperature_over_mean[j]);
        zeta += t.zeta0 + t.zeta_self * w.sonine_c[i] + t.zeta_partner * w.sonine_c[j];
        omega += t.omega0 + t.omega_self * w.sonine_c[i] + t.omega_partner * w.sonine_c[j];
      }
      EXPECT_NEAR(zeta * unit * w.temperature[i], m[i] * chi2[i], 1e-9 * m[i] * chi2[i]) << "species " << i + 1;
      const double t = w.temperature_over_mean[i] / (m[i] * 4.0 * inv_m_mean);
      EXPECT_NEAR(omega + 2.0 * 15.0 * t * t * zeta, 0.0, 1e-9 * std::abs(omega)) << "species " << i + 1;
    }
  }
}

TEST(SonineMixtureWhiteNoise, RefusesAnElasticMixtureAndBadStrengths) {
  const Mixture elastic = make_mixture({1.0, 2.0}, {1.0, 1.0}, {0.01, 0.01}, PairMatrix(2, 1.0), false);
  EXPECT_THROW(theory::white_noise_first_sonine(elastic, {0.001, 0.001}), std::invalid_argument);
  const Mixture mix = make_mixture({1.0, 2.0}, {1.0, 1.0}, {0.01, 0.01}, PairMatrix(2, 0.8), false);
  EXPECT_THROW(theory::white_noise_first_sonine(mix, {0.001}), std::invalid_argument);
  EXPECT_THROW(theory::white_noise_first_sonine(mix, {0.001, 0.0}), std::invalid_argument);
  EXPECT_THROW(theory::white_noise_first_sonine(mix, {0.001, std::nan("")}), std::invalid_argument);
}
