// Unit tests for the fast Maxwellian pair sums and their Jacobian (theory/maxwellian_rates.hpp,
// \ref cm_mixture_rate "docs/collision-model.md" and \ref haff_mixture_odes "docs/haff-and-mixtures.md"), the dense GMRES (theory/gmres.hpp) and the asymptotic temperature ratios of
// many species (theory.hpp). References: the per-entry functions of theory.hpp
// (cooling_rate_matrix, total_collision_rate: the formulas of docs/haff-and-mixtures.md and docs/collision-model.md written out pair by pair),
// central difference quotients, Eigen's LU, a 2 x 2 system solved by hand, and the stationarity of
// the ratios under the ODEs' own right-hand side.
#include "theory/gmres.hpp"
#include "theory/maxwellian_rates.hpp"
#include "theory/theory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

using gdsmc::species::make_mixture;
using gdsmc::species::Mixture;
using gdsmc::species::PairMatrix;
namespace theory = gdsmc::theory;
using theory::detail::MaxwellianRates;

namespace {

/// s species with unrelated masses, sizes, densities and a non-uniform symmetric restitution.
Mixture scattered_mixture(std::size_t s, bool enskog) {
  std::vector<double> m(s), sigma(s), n(s);
  PairMatrix alpha(s);
  for (std::size_t k = 0; k < s; ++k) {
    const double u = static_cast<double>(k) / static_cast<double>(s > 1 ? s - 1 : 1);
    m[k] = std::pow(30.0, u) * (1.0 + 0.3 * std::sin(5.0 * static_cast<double>(k)));
    sigma[k] = 1.0 + 0.8 * u;
    n[k] = 0.02 * (1.1 + std::cos(2.0 * static_cast<double>(k))) / static_cast<double>(s);
    for (std::size_t j = 0; j <= k; ++j)
      alpha(k, j) = alpha(j, k) = 0.5 + 0.45 * std::abs(std::sin(static_cast<double>(k * 7 + j * 7 + 1)));
  }
  return make_mixture(m, sigma, n, alpha, enskog);
}

/// The polydisperse law of examples/03 (m_k = k, sigma_k = k^(1/3), n_k = n_1 k^-1.5), alpha = 0.8.
Mixture law_mixture(std::size_t s, bool enskog) {
  std::vector<double> m(s), sigma(s), n(s);
  for (std::size_t k = 0; k < s; ++k) {
    const double kk = static_cast<double>(k + 1);
    m[k] = kk;
    sigma[k] = std::cbrt(kk);
    n[k] = 0.05 * std::pow(kk, -1.5);
  }
  return make_mixture(m, sigma, n, PairMatrix::uniform(s, 0.8), enskog);
}

std::vector<double> some_temperatures(std::size_t s) {
  std::vector<double> T(s);
  for (std::size_t k = 0; k < s; ++k) T[k] = 0.3 + 2.0 * std::abs(std::cos(1.3 * static_cast<double>(k)));
  return T;
}

}  // namespace

// The split xi_kj = r_kj (a_kj - b_kj T_j/T_k) reproduces \ref haff_mixture_odes "docs/haff-and-mixtures.md" entry by entry (row sums), and
// sum e_kj r_kj the \ref cm_mixture_rate "docs/collision-model.md" total collision rate, dilute and Enskog (also above the size where
// the mixture computes its pair data on access instead of storing them).
TEST(MaxwellianRates, MatchTheEntryByEntryFormulas) {
  for (std::size_t s : {1u, 2u, 7u, 600u}) {
    for (bool enskog : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "s " << s << " enskog " << enskog);
      const Mixture mix = scattered_mixture(s, enskog);
      const auto T = some_temperatures(s);
      const MaxwellianRates rates(mix);
      std::vector<double> zeta(s), zeta2(s);
      rates.cooling_rates(T, zeta);
      const double total = rates.cooling_rates_and_collision_rate(T, zeta2);
      const auto xi = theory::cooling_rate_matrix(mix, T);
      for (std::size_t k = 0; k < s; k += (s > 20 ? 37 : 1)) {
        double row = 0.0, scale = 0.0;
        for (std::size_t j = 0; j < s; ++j) {
          row += xi(k, j);
          scale += std::abs(xi(k, j));
        }
        EXPECT_NEAR(zeta[k], row, 1e-13 * scale);
        EXPECT_EQ(zeta[k], zeta2[k]);
      }
      const double reference = theory::total_collision_rate(mix, T);
      EXPECT_NEAR(total, reference, 1e-13 * reference);
      // largest collision frequency: max_k sum_j (2 - delta_kj) P_kj / n_k (\ref cm_mixture_rate "docs/collision-model.md")
      const auto pair = theory::pair_collision_rate(mix, T);
      double largest = 0.0;
      for (std::size_t k = 0; k < s; ++k) {
        double suffered = 0.0;
        for (std::size_t j = 0; j < s; ++j) suffered += (j == k ? 2.0 : 1.0) * pair(k, j);
        largest = std::max(largest, suffered / mix.number_density[k]);
      }
      EXPECT_NEAR(rates.largest_collision_frequency(T), largest, 1e-13 * largest);
    }
  }
}

// The analytic Jacobian d zeta_k/d ln T_l and d R/d ln T_l against central difference quotients
// (step 1e-5 in ln T: truncation error ~1e-10 relative), and the diagonal alone against it.
TEST(MaxwellianRates, JacobianMatchesDifferenceQuotients) {
  for (bool enskog : {false, true}) {
    SCOPED_TRACE(::testing::Message() << "enskog " << enskog);
    const std::size_t s = 6;
    const Mixture mix = scattered_mixture(s, enskog);
    const auto T = some_temperatures(s);
    const MaxwellianRates rates(mix);
    Eigen::MatrixXd J;
    std::vector<double> gradient(s), diagonal(s);
    rates.jacobian(T, J, gradient);
    rates.jacobian_diagonal(T, diagonal);
    const double h = 1e-5;
    for (std::size_t l = 0; l < s; ++l) {
      auto up = T, down = T;
      up[l] *= std::exp(h);
      down[l] *= std::exp(-h);
      std::vector<double> zu(s), zd(s);
      const double ru = rates.cooling_rates_and_collision_rate(up, zu);
      const double rd = rates.cooling_rates_and_collision_rate(down, zd);
      for (std::size_t k = 0; k < s; ++k) {
        const double fd = (zu[k] - zd[k]) / (2.0 * h);
        const double an = J(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l));
        EXPECT_NEAR(an, fd, 1e-8 * (std::abs(fd) + 1e-3 * std::abs(zu[k])));
      }
      EXPECT_NEAR(gradient[l], (ru - rd) / (2.0 * h), 1e-8 * ru);
      EXPECT_NEAR(diagonal[l], J(static_cast<Eigen::Index>(l), static_cast<Eigen::Index>(l)),
                  1e-13 * std::abs(diagonal[l]));
    }
    // Homogeneity of degree 1/2 (\ref haff_mixture_odes "docs/haff-and-mixtures.md"): sum_l d zeta_k/d ln T_l = zeta_k/2.
    std::vector<double> zeta(s);
    rates.cooling_rates(T, zeta);
    for (std::size_t k = 0; k < s; ++k)
      EXPECT_NEAR(J.row(static_cast<Eigen::Index>(k)).sum(), 0.5 * zeta[k], 1e-12 * std::abs(zeta[k]));
  }
}

// GMRES: a 2 x 2 system by hand, [[4, 1], [2, 3]] x = [1, 2] -> x = (0.1, 0.6); random
// non-symmetric systems against Eigen's LU, with restarts (m = 5) and without.
TEST(Gmres, SolvesDenseSystems) {
  Eigen::MatrixXd A(2, 2);
  A << 4.0, 1.0, 2.0, 3.0;
  Eigen::VectorXd b(2), x = Eigen::VectorXd::Zero(2);
  b << 1.0, 2.0;
  auto result = theory::detail::gmres(A, b, A.diagonal(), x, 1e-14);
  EXPECT_TRUE(result.converged);
  EXPECT_NEAR(x(0), 0.1, 1e-14);
  EXPECT_NEAR(x(1), 0.6, 1e-14);

  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const int n = 80;
  Eigen::MatrixXd M(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) M(i, j) = uniform(rng) / n;
  for (int i = 0; i < n; ++i) M(i, i) += 1.0 + 10.0 * std::abs(uniform(rng));  // scattered diagonal
  Eigen::VectorXd rhs(n);
  for (int i = 0; i < n; ++i) rhs(i) = uniform(rng);
  const Eigen::VectorXd exact = M.partialPivLu().solve(rhs);
  for (int restart : {5, 50}) {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
    result = theory::detail::gmres(M, rhs, M.diagonal(), y, 1e-12, restart, 2000);
    EXPECT_TRUE(result.converged) << "restart " << restart;
    EXPECT_LT((y - exact).norm(), 1e-10 * exact.norm()) << "restart " << restart;
    EXPECT_LT((rhs - M * y).norm(), 1e-12 * rhs.norm() * 1.01) << "restart " << restart;
  }
  // zero right-hand side: x = 0 at once
  Eigen::VectorXd z = Eigen::VectorXd::Ones(n);
  result = theory::detail::gmres(M, Eigen::VectorXd::Zero(n), M.diagonal(), z, 1e-12);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(z.norm(), 0.0);
}

// The asymptotic ratios of many species (found by continuation, theory.hpp) are stationary under
// the ODEs' right-hand side as the entry-by-entry formulas evaluate it: every species cools at the
// same relative rate. Dilute and Enskog, 3 and 120 species (the latter in the GMRES-free range but
// with S^2 pair work).
TEST(AsymptoticRatios, AreStationaryForManySpecies) {
  for (std::size_t s : {3u, 120u}) {
    for (bool enskog : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "s " << s << " enskog " << enskog);
      const Mixture mix = law_mixture(s, enskog);
      const auto ratio = theory::asymptotic_temperature_ratios(mix);
      ASSERT_EQ(ratio.size(), s);
      EXPECT_EQ(ratio[0], 1.0);
      const auto rate = theory::partial_temperature_rates(mix, ratio);
      const double zeta0 = -rate[0] / ratio[0];
      for (std::size_t k = 0; k < s; ++k) EXPECT_NEAR(-rate[k] / ratio[k], zeta0, 1e-11 * zeta0);
      // heavier species hotter in a cooling gas of these laws (DSMC notes, Fig. 6)
      EXPECT_GT(ratio[s - 1], ratio[0]);
    }
  }
}

// The three methods of asymptotic_temperature_ratios (theory.hpp) find the same ratios: Newton's
// method with line search, pseudo-transient continuation and the long-time ODE (the method before
// issue 17), for the example of \ref haff_mixture_odes "docs/haff-and-mixtures.md" (alpha = 0.3, m2/m1 = 100: T2/T1 = 60.6, where plain Newton
// from equal temperatures is said to fail), a scattered 6-species Enskog mixture with a non-uniform
// restitution matrix, and 250 species of the polydisperse laws (GMRES in the fixed-point methods).
TEST(AsymptoticRatios, NewtonContinuationAndOdeAgree) {
  using theory::detail::RatioMethod;
  std::vector<Mixture> mixtures;
  PairMatrix alpha(2, 0.3);
  mixtures.push_back(make_mixture({1.0, 100.0}, {1.0, 1.0}, {0.01, 0.01}, alpha, false));
  mixtures.push_back(scattered_mixture(6, true));
  mixtures.push_back(law_mixture(250, false));
  for (const Mixture& mix : mixtures) {
    SCOPED_TRACE(::testing::Message() << "s " << mix.size());
    const auto newton = theory::detail::asymptotic_temperature_ratios_by(mix, RatioMethod::newton);
    const auto continuation =
        theory::detail::asymptotic_temperature_ratios_by(mix, RatioMethod::continuation);
    const auto ode = theory::detail::asymptotic_temperature_ratios_by(mix, RatioMethod::ode);
    ASSERT_TRUE(newton && continuation && ode);
    for (std::size_t k = 0; k < mix.size(); ++k) {
      EXPECT_NEAR((*continuation)[k], (*newton)[k], 1e-12 * (*newton)[k]);
      EXPECT_NEAR((*ode)[k], (*newton)[k], 1e-10 * (*newton)[k]);
    }
    if (mix.size() == 2) {
      EXPECT_NEAR((*newton)[1], 60.6, 0.05);
    }
  }
}
