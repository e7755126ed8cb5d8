// Unit tests for gdsmc::collide: the binary collision rule (\ref cm_rule "docs/collision-model.md") and the two DSMC schemes
// (conservation laws, collision rates of \ref cm_pair_rate "docs/collision-model.md", stopping and reproducibility, Haff cooling, \ref haff_law "docs/haff-and-mixtures.md").
//
// Statistical tests use fixed seeds; each tolerance is set as for a random seed (5 Poisson sigma or
// 5 standard errors, as stated above each test), and the measured numbers are printed.
#include "dsmc/collide.hpp"
#include "dsmc/event_margin.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "dsmc/deal.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/rules.hpp"
#include "dsmc/state.hpp"
#include "model/restitution.hpp"
#include "run/model.hpp"
#include "model/species.hpp"
#include "sanitizer_scale.hpp"

using namespace gdsmc;
using collide::Collider;
using collide::Scheme;
using particles::InitialDistribution;

namespace {

const double kPi = std::numbers::pi;

const char* name(Scheme s) {
  return s == Scheme::majorant ? "majorant" : s == Scheme::pairs ? "pairs" : "lowrank";
}

// The kernel tests below compare a scheme's own block sampler with its unblocked loops: the blocks then
// run that sampler rather than the cheaper of the two (Collider::BlockSampler; the choice itself is
// tested in Collide.BlocksRunTheCheaperSampler).
void follow_scheme(Collider& c, Scheme s) {
  c.set_block_sampler(s == Scheme::lowrank ? Collider::BlockSampler::lowrank : Collider::BlockSampler::majorant);
}

species::Mixture one_species(double alpha, double n = 0.01) {
  return species::make_mixture({1.0}, {1.0}, {n}, species::PairMatrix(1, alpha), false);
}

species::Mixture binary(double a11, double a12, double a22) {
  species::PairMatrix alpha(2);
  alpha(0, 0) = a11;
  alpha(0, 1) = alpha(1, 0) = a12;
  alpha(1, 1) = a22;
  return species::make_mixture({1.0, 4.0}, {1.0, 2.0}, {0.01, 0.005}, alpha, false);
}

particles::System initial(const species::Mixture& mix, const std::vector<std::size_t>& counts,
                          const std::vector<double>& temperature, std::uint64_t seed) {
  auto gen = rng::make_stream(seed, 0, rng::Purpose::initial_state);
  return particles::make_system(mix, counts, temperature, InitialDistribution::maxwell, gen);
}

double kinetic_energy(const species::Mixture& mix, const particles::System& sys) {
  double e = 0.0;
  for (std::size_t i = 0; i < sys.size(); ++i)
    e += 0.5 * mix.mass[sys.species[i]] *
         (sys.v[i].x * sys.v[i].x + sys.v[i].y * sys.v[i].y + sys.v[i].z * sys.v[i].z);
  return e;
}

void momentum(const species::Mixture& mix, const particles::System& sys, double p[3],
              double* scale = nullptr) {
  p[0] = p[1] = p[2] = 0.0;
  double s = 0.0;
  for (std::size_t i = 0; i < sys.size(); ++i) {
    const double m = mix.mass[sys.species[i]];
    p[0] += m * sys.v[i].x;
    p[1] += m * sys.v[i].y;
    p[2] += m * sys.v[i].z;
    s += m * std::sqrt(sys.v[i].x * sys.v[i].x + sys.v[i].y * sys.v[i].y + sys.v[i].z * sys.v[i].z);
  }
  if (scale) *scale = s;
}

/// The frame's moments kept by the collider equal sum m u u^T of the stored velocities (xx, yy, zz, xy).
void expect_frame_moments(const Collider& collider, const species::Mixture& mix, const particles::System& u) {
  std::array<double, 4> q{};
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double m = mix.mass[u.species[i]];
    q[0] += m * u.v[i].x * u.v[i].x, q[1] += m * u.v[i].y * u.v[i].y, q[2] += m * u.v[i].z * u.v[i].z;
    q[3] += m * u.v[i].x * u.v[i].y;
  }
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(collider.frame_moments()[c], q[c], 1e-11 * (q[0] + q[1] + q[2]));
}

/// Mean and standard error of the mean of replica values.
std::pair<double, double> mean_se(const std::vector<double>& x) {
  double m = 0.0, v = 0.0;
  for (double a : x) m += a;
  m /= static_cast<double>(x.size());
  for (double a : x) v += (a - m) * (a - m);
  return {m, std::sqrt(v / static_cast<double>(x.size() - 1) / static_cast<double>(x.size()))};
}

// Per replica of a binary gas of 8000 + 4000 particles: T_1, T_2, the share of 1-2 events and the time.
struct BinaryRuns {
  std::vector<double> t1, t2, cross, time;
  void add(const particles::System& sys, const species::Mixture& mix, const Collider& c) {
    double e[2] = {0.0, 0.0};
    for (std::size_t i = 0; i < sys.size(); ++i) {
      const auto& v = sys.v[i];
      e[sys.species[i]] += mix.mass[sys.species[i]] * (v.x * v.x + v.y * v.y + v.z * v.z);
    }
    t1.push_back(e[0] / (3.0 * 8000.0));
    t2.push_back(e[1] / (3.0 * 4000.0));
    cross.push_back(static_cast<double>(c.counters().pair_events[1]) / static_cast<double>(c.counters().events));
    time.push_back(c.time());
  }
};

// Masses 1 and 4, diameters 1 and 1.5 at equal densities: its blocks run the `majorant` sampler.
species::Mixture near_binary() {
  return species::make_mixture({1.0, 4.0}, {1.0, 1.5}, {0.01, 0.01}, species::PairMatrix(2, 0.9), false);
}

// 20 species of the Fig 8 law (m_k = k, sigma_k = k^(1/3), n_k = 0.01 k^-3, alpha = 0.8), N_k =
// 12000 k^-3 + 1 (N = 14441: 13 species scattered over blocks of 3000): its blocks run `lowrank`.
std::pair<species::Mixture, std::vector<std::size_t>> fig8_gas() {
  std::vector<double> mass(20), diameter(20), density(20);
  std::vector<std::size_t> counts(20);
  for (std::size_t k = 0; k < 20; ++k) {
    const double kk = static_cast<double>(k + 1);
    mass[k] = kk;
    diameter[k] = std::cbrt(kk);
    density[k] = 0.01 * std::pow(kk, -3.0);
    counts[k] = static_cast<std::size_t>(std::llround(12000.0 * std::pow(kk, -3.0))) + 1;
  }
  return {species::make_mixture(mass, diameter, density, species::PairMatrix(20, 0.8), false), counts};
}

// runs[1] (blocked) against runs[0] (unblocked): each observable within 4 combined SE, printed.
void expect_binary_runs_agree(const BinaryRuns (&runs)[2], const std::string& label) {
  const char* names[] = {"T1", "T2", "share of 1-2 events", "time at the target"};
  const std::vector<double> BinaryRuns::*fields[] = {&BinaryRuns::t1, &BinaryRuns::t2, &BinaryRuns::cross,
                                                     &BinaryRuns::time};
  for (int q = 0; q < 4; ++q) {
    const auto [m0, s0] = mean_se(runs[0].*fields[q]);
    const auto [m1, s1] = mean_se(runs[1].*fields[q]);
    std::printf("%s %s: unblocked %.6g +- %.2g, blocked %.6g +- %.2g (%.2f SE)\n", label.c_str(), names[q], m0, s0,
                m1, s1, (m1 - m0) / std::hypot(s0, s1));
    EXPECT_LT(std::abs(m1 - m0), 4.0 * std::hypot(s0, s1)) << names[q];
  }
}

}  // namespace

// hemisphere_projection (\ref cm_hemisphere "docs/collision-model.md"): p = (g.e) e for e of density
// (g_hat.e)/pi on the hemisphere. Over 1e6 draws for one g: |p|^2 equals the returned (g.e)^2 and p.g
// equals it too (to round-off), and U = (g.e)^2/g^2 is uniform on (0, 1): <U> = 1/2 (SE sqrt(1/(12 N))),
// <U^2> = 1/3 (Var U^2 = 1/5 - 1/9, SE sqrt(4/(45 N))); the component of e across g averages to 0
// (e_perp.x, SE <= sqrt(1/N)); tolerance 5 SE.
TEST(Collide, HemisphereProjectionIsTheHemisphereImpulse) {
  rng::Xoshiro256pp gen(99);
  const double gx = 0.3, gy = -1.2, gz = 0.7, g2 = gx * gx + gy * gy + gz * gz, g = std::sqrt(g2);
  const int n = 1000000;
  double su = 0.0, su2 = 0.0, sperp = 0.0, worst = 0.0;
  for (int i = 0; i < n; ++i) {
    double px, py, pz;
    const double q = rules::hemisphere_projection(gen, gx, gy, gz, g, px, py, pz);
    worst = std::max({worst, std::abs(px * px + py * py + pz * pz - q) / g2, std::abs(px * gx + py * gy + pz * gz - q) / g2});
    const double u = q / g2;
    su += u;
    su2 += u * u;
    // e's component along x after removing its part along g_hat (p / |p| = e)
    const double norm = std::sqrt(q);
    if (norm > 0.0) sperp += (px - (px * gx + py * gy + pz * gz) / g2 * gx) / norm;
  }
  const double se_u = std::sqrt(1.0 / 12.0 / n), se_u2 = std::sqrt(4.0 / 45.0 / n), se_perp = std::sqrt(1.0 / n);
  std::printf("[ Collide.HemisphereProjection ] <U> = %.5f (SE %.5f, exp 0.5), <U^2> = %.5f (SE %.5f, exp 0.33333), "
              "<e_perp,x> = %.5f, worst round-off %.2e\n",
              su / n, se_u, su2 / n, se_u2, sperp / n, worst);
  EXPECT_LT(worst, 1e-14);
  EXPECT_NEAR(su / n, 0.5, 5.0 * se_u);
  EXPECT_NEAR(su2 / n, 1.0 / 3.0, 5.0 * se_u2);
  EXPECT_NEAR(sperp / n, 0.0, 5.0 * se_perp);
}

// &dsmc scheme of the Config as the Collider's scheme (run/model.cpp).
TEST(Collide, SchemeOfTheConfig) {
  namespace config = gdsmc::io::config;
  config::Config c;
  c.dsmc.scheme = config::Scheme::majorant;
  EXPECT_EQ(gdsmc::simulation::scheme(c), Scheme::majorant);
  c.dsmc.scheme = config::Scheme::pairs;
  EXPECT_EQ(gdsmc::simulation::scheme(c), Scheme::pairs);
  c.dsmc.scheme = config::Scheme::lowrank;
  EXPECT_EQ(gdsmc::simulation::scheme(c), Scheme::lowrank);
}

// \ref cm_rule "docs/collision-model.md" for random velocities, unequal masses (m_b/m_a in {1, 3, 1/7}), random e and several
// alpha: momentum conserved to 1e-14 of sum m|v|; (g'.e) = -alpha (g.e); energy loss
// (1 - alpha^2) m_ab (g.e)^2 / 2 to 1e-13 relative. (The stored post-collision velocities carry
// round-off eps |v|, so the computed loss has an error ~ eps E; the relative check is therefore made
// for draws whose loss is at least 1 % of E, and every draw is checked to 1e-13 of E.)
TEST(Rules, SmoothRuleConservesMomentumAndLosesRightEnergy) {
  auto gen = rng::make_stream(99, 0, rng::Purpose::sampling);
  particles::System sys;
  sys.v.assign(2, {});
  sys.species = {0, 1};
  sys.first = {0, 1};
  sys.count = {1, 1};
  int relative_checks = 0;
  double worst_rel = 0.0;
  for (double ma : {1.0, 2.0}) {
    for (double ratio : {1.0, 3.0, 1.0 / 7.0}) {
      const double mb = ma * ratio;
      const double mfb = mb / (ma + mb), mab = ma * mb / (ma + mb);
      for (double alpha : {0.0, 0.3, 0.5, 0.8, 0.95, 1.0}) {
        for (int trial = 0; trial < 200; ++trial) {
          for (std::size_t i = 0; i < 2; ++i) {
            sys.v[i].x = 3.0 * gen.normal();
            sys.v[i].y = 3.0 * gen.normal();
            sys.v[i].z = 3.0 * gen.normal();
          }
          double ex, ey, ez;
          rng::unit_vector(gen, ex, ey, ez);
          const double va[3] = {sys.v[0].x, sys.v[0].y, sys.v[0].z};
          const double vb[3] = {sys.v[1].x, sys.v[1].y, sys.v[1].z};
          const double g_e = (va[0] - vb[0]) * ex + (va[1] - vb[1]) * ey + (va[2] - vb[2]) * ez;
          const double e_before = 0.5 * ma * (va[0] * va[0] + va[1] * va[1] + va[2] * va[2]) +
                                  0.5 * mb * (vb[0] * vb[0] + vb[1] * vb[1] + vb[2] * vb[2]);
          const double p_scale = ma * std::sqrt(va[0] * va[0] + va[1] * va[1] + va[2] * va[2]) +
                                  mb * std::sqrt(vb[0] * vb[0] + vb[1] * vb[1] + vb[2] * vb[2]);
          const double g_norm = std::sqrt((va[0] - vb[0]) * (va[0] - vb[0]) +
                                          (va[1] - vb[1]) * (va[1] - vb[1]) +
                                          (va[2] - vb[2]) * (va[2] - vb[2]));

          const auto pair = rules::SmoothRule::make_pair(alpha, ma, mb);
          ASSERT_EQ(pair.mass_fraction, mfb);
          const rules::Outcome out = rules::SmoothRule::collide(sys.v[0], sys.v[1], pair, {ex, ey, ez, g_e, ex, ey, ez});
          // The loss it reports and the momentum it gives b along e, m_ab (1 + alpha)(g.e).
          ASSERT_NEAR(out.loss, (1.0 - alpha * alpha) * mab * g_e * g_e / 2.0, 1e-13 * e_before);
          ASSERT_NEAR(out.impulse, mab * (1.0 + alpha) * g_e, 1e-13 * p_scale);

          const double pa[3] = {ma * va[0] + mb * vb[0], ma * va[1] + mb * vb[1], ma * va[2] + mb * vb[2]};
          const double pb[3] = {ma * sys.v[0].x + mb * sys.v[1].x, ma * sys.v[0].y + mb * sys.v[1].y,
                                ma * sys.v[0].z + mb * sys.v[1].z};
          for (int d = 0; d < 3; ++d) ASSERT_LE(std::abs(pb[d] - pa[d]), 1e-14 * p_scale);

          const double g_e_after = (sys.v[0].x - sys.v[1].x) * ex + (sys.v[0].y - sys.v[1].y) * ey +
                                   (sys.v[0].z - sys.v[1].z) * ez;
          ASSERT_NEAR(g_e_after, -alpha * g_e, 1e-14 * g_norm);

          const double e_after =
              0.5 * ma * (sys.v[0].x * sys.v[0].x + sys.v[0].y * sys.v[0].y + sys.v[0].z * sys.v[0].z) +
              0.5 * mb * (sys.v[1].x * sys.v[1].x + sys.v[1].y * sys.v[1].y + sys.v[1].z * sys.v[1].z);
          const double loss = e_before - e_after;
          const double expected = (1.0 - alpha * alpha) * mab * g_e * g_e / 2.0;
          ASSERT_NEAR(loss, expected, 1e-13 * e_before) << "alpha " << alpha;
          if (alpha == 1.0) {
            ASSERT_NEAR(e_after, e_before, 1e-14 * e_before);
          }
          if (expected >= 0.01 * e_before) {
            ++relative_checks;
            worst_rel = std::max(worst_rel, std::abs(loss / expected - 1.0));
            ASSERT_NEAR(loss / expected, 1.0, 1e-13) << "alpha " << alpha << " ratio " << ratio;
          }
        }
      }
    }
  }
  std::printf("[ Rules.SmoothRule ] %d relative energy-loss checks, worst relative error %.2e\n",
              relative_checks, worst_rel);
  EXPECT_GT(relative_checks, 1000);
}

// The sign of e does not matter (\ref cm_rule "docs/collision-model.md").
TEST(Rules, SmoothRuleIndependentOfSignOfE) {
  std::vector<particles::Vec3> a = {{1.0, 0.3, -0.7}, {-0.5, 0.2, 0.9}}, b = a;
  const double e[3] = {0.48, 0.6, 0.64};  // unit
  const auto pair = rules::SmoothRule::make_pair(0.7, 3.0, 1.0);  // mass fraction 1/4
  const auto along = [](std::vector<particles::Vec3>& v, double s, const double* e) {
    return rules::Contact{s * e[0], s * e[1], s * e[2],
                          (v[0].x - v[1].x) * s * e[0] + (v[0].y - v[1].y) * s * e[1] + (v[0].z - v[1].z) * s * e[2],
                          s * e[0], s * e[1], s * e[2]};
  };
  rules::SmoothRule::collide(a[0], a[1], pair, along(a, 1.0, e));
  rules::SmoothRule::collide(b[0], b[1], pair, along(b, -1.0, e));
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(a[i].x, b[i].x, 1e-15);
    EXPECT_NEAR(a[i].y, b[i].y, 1e-15);
    EXPECT_NEAR(a[i].z, b[i].z, 1e-15);
  }
}

// The rule by hand (\ref cm_rule "docs/collision-model.md"): m_a = 1, m_b = 3, alpha = 1/2, v_a = (1, 0, 0),
// v_b = 0, e = x: g.e = 1, mu_ba = 3/4, (1 + alpha)(g.e) = 3/2, so v_a' = 1 - (3/4)(3/2) = -1/8 and
// v_b' = (1/4)(3/2) = 3/8 (momentum 1 before and after; g'.e = -1/2); the energy 1/2 before and
// (1/2)(1/64) + (3/2)(9/64) = 7/32 after: 9/32 lost = (1 - 1/4)(3/4)(1)/2; b receives m_ab (3/2) = 9/8.
// Every number is a binary fraction: the results are exact.
TEST(Rules, SmoothRuleByHand) {
  particles::Vec3 va{1.0, 0.0, 0.0}, vb{0.0, 0.0, 0.0};
  const auto pair = rules::SmoothRule::make_pair(0.5, 1.0, 3.0);
  const rules::Outcome out = rules::SmoothRule::collide(va, vb, pair, {1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0});
  EXPECT_EQ(va.x, -0.125);
  EXPECT_EQ(vb.x, 0.375);
  EXPECT_EQ(va.y + va.z + vb.y + vb.z, 0.0);
  EXPECT_EQ(out.loss, 9.0 / 32.0);
  EXPECT_EQ(out.impulse, 9.0 / 8.0);
  // The projected form with p = (g.e) e: the same collision.
  particles::Vec3 pa{1.0, 0.0, 0.0}, pb{0.0, 0.0, 0.0};
  EXPECT_EQ(rules::SmoothRule::collide_projected(pa, pb, pair, 1.0, {1.0, 0.0, 0.0}), 9.0 / 32.0);
  EXPECT_EQ(pa, va);
  EXPECT_EQ(pb, vb);
}

// The projected form (the block kernels) and the general form give the same collision for p = (g.e) e,
// random velocities, masses, e and alpha, to round-off; and a direction d other than e (a frame's
// G^-1 e) moves the stored velocities along d by the same amounts.
TEST(Rules, SmoothRuleProjectedIsTheGeneralRule) {
  auto gen = rng::make_stream(7, 0, rng::Purpose::sampling);
  for (int trial = 0; trial < 1000; ++trial) {
    const double ma = 0.5 + gen.uniform(), mb = 0.5 + 3.0 * gen.uniform(), alpha = gen.uniform();
    const auto pair = rules::SmoothRule::make_pair(alpha, ma, mb);
    particles::Vec3 va{gen.normal(), gen.normal(), gen.normal()}, vb{gen.normal(), gen.normal(), gen.normal()};
    double ex, ey, ez;
    rng::unit_vector(gen, ex, ey, ez);
    const double g_e = (va.x - vb.x) * ex + (va.y - vb.y) * ey + (va.z - vb.z) * ez;
    particles::Vec3 ga = va, gb = vb, qa = va, qb = vb;
    const double loss = rules::SmoothRule::collide(ga, gb, pair, {ex, ey, ez, g_e, ex, ey, ez}).loss;
    const double projected = rules::SmoothRule::collide_projected(qa, qb, pair, g_e * g_e, {g_e * ex, g_e * ey, g_e * ez});
    ASSERT_NEAR(projected, loss, 1e-14 * (1.0 + loss));
    for (const auto& [x, y] : {std::pair{ga.x, qa.x}, {ga.y, qa.y}, {ga.z, qa.z}, {gb.x, qb.x}, {gb.y, qb.y}, {gb.z, qb.z}})
      ASSERT_NEAR(x, y, 1e-14 * (1.0 + std::abs(x)));
    // Along d = (0, 0, 1) instead of e: each velocity moves by (its share) (1 + alpha)(g.e) along z only.
    particles::Vec3 da = va, db = vb;
    rules::SmoothRule::collide(da, db, pair, {ex, ey, ez, g_e, 0.0, 0.0, 1.0});
    EXPECT_EQ(da.x, va.x);
    EXPECT_EQ(db.y, vb.y);
    EXPECT_NEAR(da.z - va.z, -pair.mass_fraction * (1.0 + alpha) * g_e, 1e-14);
    EXPECT_NEAR(db.z - vb.z, (1.0 - pair.mass_fraction) * (1.0 + alpha) * g_e, 1e-14);
  }
}

// The viscoelastic rule is the smooth rule with alpha(|g.e|) of restitution.hpp: the same collision as
// SmoothRule with that alpha, for slow and fast impacts (series and exact law), and no energy is created.
TEST(Rules, ViscoelasticRuleIsTheSmoothRuleAtItsAlpha) {
  species::Mixture mix = species::make_mixture({1.0, 2.0}, {1.0, 1.26}, {0.01, 0.01}, species::PairMatrix::uniform(2, 1.0), false);
  const auto beta = restitution::one_material_beta(mix, 0.05);
  const rules::ViscoelasticRule rule(mix, beta);
  for (double g_e : {1e-3, 0.3, 2.0, 40.0}) {
    const auto pair = rule.pair(0, 1);
    const double alpha = rules::ViscoelasticRule::restitution(pair, g_e);
    EXPECT_GT(alpha, 0.0);
    EXPECT_LE(alpha, 1.0);
    // (the series, used up to u = 0.8, is within 1.1e-4 of the contact model: \ref visco_series "docs/viscoelastic.md")
    EXPECT_NEAR(alpha, restitution::viscoelastic(beta(0, 1), g_e), 1.1e-4) << "g.e = " << g_e;
    particles::Vec3 va{g_e, 0.1, 0.0}, vb{0.0, -0.2, 0.3}, sa = va, sb = vb;
    const auto out = rules::ViscoelasticRule::collide(va, vb, pair, {1.0, 0.0, 0.0, g_e, 1.0, 0.0, 0.0});
    const auto smooth = rules::SmoothRule::collide(sa, sb, rules::SmoothRule::make_pair(alpha, 1.0, 2.0),
                                                   {1.0, 0.0, 0.0, g_e, 1.0, 0.0, 0.0});
    EXPECT_EQ(va, sa);
    EXPECT_EQ(vb, sb);
    EXPECT_EQ(out.impulse, smooth.impulse);
    EXPECT_NEAR(out.loss, smooth.loss, 1e-15 * (1.0 + smooth.loss));
    EXPECT_GE(out.loss, 0.0);
  }
}

// (a) Total momentum of an inelastic binary mixture (m = 1, 4) is conserved over 1e5 collisions, both
// schemes: the drift stays below 1e-12 of sum m|v| (round-off, ~sqrt(1e5) eps per particle scale).
TEST(Collide, ColliderConservesMomentum) {
  const auto mix = binary(0.9, 0.8, 0.7);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    auto sys = initial(mix, {2000, 1000}, {1.0, 1.0}, 5);
    double p0[3], scale;
    momentum(mix, sys, p0, &scale);
    Collider collider(scheme, mix, sys, rng::make_stream(5, 0, rng::Purpose::collisions), 1.0);
    EXPECT_TRUE(collider.advance(1e12, 100000));
    EXPECT_EQ(collider.counters().events, 100000u);
    double p1[3];
    momentum(mix, sys, p1);
    for (int d = 0; d < 3; ++d) EXPECT_LT(std::abs(p1[d] - p0[d]), 1e-12 * scale);
    EXPECT_LT(kinetic_energy(mix, sys), 0.5 * 1.5 * 3000.0);  // it did cool
  }
}

// (b) An elastic one-species gas conserves the total kinetic energy to 1e-10 relative over 2e5
// collisions (100 per particle), both schemes.
TEST(Collide, ColliderElasticConservesEnergy) {
  const auto mix = one_species(1.0);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    auto sys = initial(mix, {4000}, {1.0}, 6);
    const double e0 = kinetic_energy(mix, sys);
    Collider collider(scheme, mix, sys, rng::make_stream(6, 0, rng::Purpose::collisions), 1.0);
    collider.advance(1e12, 200000);
    EXPECT_EQ(collider.counters().events, 200000u);
    const double e1 = kinetic_energy(mix, sys);
    std::printf("[ Collide.Elastic ] %s: relative energy change %.2e over 2e5 collisions\n",
                name(scheme), e1 / e0 - 1.0);
    EXPECT_NEAR(e1 / e0, 1.0, 1e-10);
  }
}

// (c) Collision rate, elastic one-species Maxwellian gas, T = m = sigma = 1, n = 0.01, N = 20000.
// Expected events E = N nu t / 2, nu = 4 sqrt(pi) n sigma^2 sqrt(T/m) (\ref cm_frequency "docs/collision-model.md"); t is chosen for
// E = 2e5. Tolerance 5 sqrt(E) (Poisson; the scheme's count is binomial given the deterministic
// candidate count, so its true variance is smaller). The finite-N factor N/(N-1) of the candidate
// selection (5e-5) is far below the tolerance (1.1 %).
TEST(Collide, CollisionRateOneSpecies) {
  const double n = 0.01, sigma = 1.0, temperature = 1.0, mass = 1.0;
  const std::size_t n_particles = 20000;
  const auto mix = one_species(1.0, n);
  const double nu = 4.0 * std::sqrt(kPi) * n * sigma * sigma * std::sqrt(temperature / mass);
  const double expected = 2e5;
  const double t = 2.0 * expected / (n_particles * nu);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    auto sys = initial(mix, {n_particles}, {temperature}, 7);
    Collider collider(scheme, mix, sys, rng::make_stream(7, 0, rng::Purpose::collisions), 1.0);
    EXPECT_FALSE(collider.advance(t));
    EXPECT_DOUBLE_EQ(collider.time(), t);
    const double events = static_cast<double>(collider.counters().events);
    std::printf("[ Collide.Rate1 ] %s: events %.0f, expected %.1f, sigma %.1f, (E-exp)/sigma = %.2f\n",
                name(scheme), events, expected, std::sqrt(expected),
                (events - expected) / std::sqrt(expected));
    EXPECT_NEAR(events, expected, 5.0 * std::sqrt(expected)) << name(scheme);
    EXPECT_EQ(collider.counters().pair_events[0], collider.counters().events);
  }
}

// (d) Binary elastic mixture, m = (1, 4), sigma = (1, 2), n = (0.01, 0.005), T = 1 both, N = 30000
// (N_k = 20000, 10000, exactly N x_k). Expected events per species pair in time t:
// n_k n_j pi sigma_kj^2 <|g_kj|> V t for k != j, half that for k == j, V = N / n,
// <|g|> = sqrt(8 s_kj / pi), s_kj = T_k/m_k + T_j/m_j (\ref cm_mean_speed "docs/collision-model.md"). t = 150 gives about 1.06e5 (11),
// 1.89e5 (12) and 5.3e4 (22) events. Tolerance 5 sqrt(expected) per pair (Poisson); both schemes,
// with step_fraction 0.25 (more bound rebuilds than the other tests).
TEST(Collide, CollisionRateBinaryMixture) {
  const auto mix = binary(1.0, 1.0, 1.0);
  const std::vector<std::size_t> counts{20000, 10000};
  const double n_total = mix.total_density();
  const double volume = 30000.0 / n_total;
  const double t = 150.0;
  const std::vector<double> temperature{1.0, 1.0};
  double expected[2][2];
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t j = 0; j < 2; ++j) {
      const double s = temperature[k] / mix.mass[k] + temperature[j] / mix.mass[j];
      const double sigma = 0.5 * (mix.diameter[k] + mix.diameter[j]);
      const double mean_g = std::sqrt(8.0 * s / kPi);
      expected[k][j] = mix.number_density[k] * mix.number_density[j] * kPi * sigma * sigma * mean_g *
                       volume * t * (k == j ? 0.5 : 1.0);
    }
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    auto sys = initial(mix, counts, temperature, 8);
    Collider collider(scheme, mix, sys, rng::make_stream(8, 0, rng::Purpose::collisions), 0.25);
    collider.advance(t);
    const auto& c = collider.counters();
    EXPECT_EQ(c.pair_events[1 * 2 + 0], 0u);  // counted at (min, max) only
    EXPECT_EQ(c.pair_events[0] + c.pair_events[1] + c.pair_events[3], c.events);
    for (std::size_t k = 0; k < 2; ++k)
      for (std::size_t j = k; j < 2; ++j) {
        const double events = static_cast<double>(c.pair_events[k * 2 + j]);
        const double e = expected[k][j], sd = std::sqrt(e);
        std::printf("[ Collide.Rate2 ] %s pair %zu%zu: events %.0f, expected %.1f, sigma %.1f, "
                    "(E-exp)/sigma = %.2f\n", name(scheme), k + 1, j + 1, events, e, sd,
                    (events - e) / sd);
        EXPECT_NEAR(events, e, 5.0 * sd) << name(scheme) << " pair " << k << j;
      }
  }
}

// (e) advance(t, event_target) stops exactly at the event target; time() is monotone and never
// passes the target time.
TEST(Collide, AdvanceStopsAtEventTargetAndTimeIsMonotone) {
  const auto mix = binary(0.8, 0.8, 0.8);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    auto sys = initial(mix, {600, 400}, {1.0, 2.0}, 9);
    Collider collider(scheme, mix, sys, rng::make_stream(9, 0, rng::Purpose::collisions), 0.5);
    double last = collider.time();
    EXPECT_EQ(last, 0.0);
    for (std::uint64_t target : {1u, 2u, 17u, 500u, 501u, 3000u}) {
      EXPECT_TRUE(collider.advance(1e12, target));
      EXPECT_EQ(collider.counters().events, target);
      EXPECT_GE(collider.time(), last);
      EXPECT_LT(collider.time(), 1e12);
      last = collider.time();
    }
    // Already at the target: returns at once without moving the clock.
    EXPECT_TRUE(collider.advance(1e12, 3000));
    EXPECT_EQ(collider.time(), last);
    EXPECT_EQ(collider.counters().events, 3000u);
    // Time targets: reached exactly, monotone, event count never decreases.
    std::uint64_t events = collider.counters().events;
    for (int step = 1; step <= 50; ++step) {
      const double t = last + 0.37 * step;
      EXPECT_FALSE(collider.advance(t));
      EXPECT_EQ(collider.time(), t);
      EXPECT_GE(collider.counters().events, events);
      events = collider.counters().events;
    }
    EXPECT_GT(events, 3000u);
    // A target time in the past does nothing.
    const double now = collider.time();
    EXPECT_FALSE(collider.advance(now - 1.0));
    EXPECT_EQ(collider.time(), now);
    EXPECT_EQ(collider.counters().events, events);
    // Interleaved one-event and short-time targets (sub-steps cut by events, bound raises and
    // step boundaries in every order): the clock never goes back.
    for (int i = 0; i < 3000; ++i) {
      double before = collider.time();
      collider.advance(1e12, collider.counters().events + 1);
      ASSERT_GE(collider.time(), before) << "event stop " << i;
      before = collider.time();
      collider.advance(before + 0.003);
      ASSERT_GE(collider.time(), before) << "time stop " << i;
    }
  }
}

// A gas at rest has no candidates: the clock jumps to the target and nothing collides.
TEST(Collide, GasAtRestNeverCollides) {
  const auto mix = one_species(0.5);
  particles::System sys;
  sys.v.assign(10, {});
  sys.species.assign(10, 0);
  sys.first = {0};
  sys.count = {10};
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    auto copy = sys;
    Collider collider(scheme, mix, copy, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
    EXPECT_FALSE(collider.advance(3.5, 10));
    EXPECT_EQ(collider.time(), 3.5);
    EXPECT_EQ(collider.counters().events, 0u);
  }
}

// (e) Reproducibility: two colliders from the same seed stream and the same initial system give
// bitwise identical velocities after the same advance calls; another seed gives other velocities.
TEST(Collide, ReproducibleFromSameSeed) {
  const auto mix = binary(0.7, 0.9, 0.5);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    const auto start = initial(mix, {700, 300}, {1.0, 1.0}, 10);
    auto sys_a = start, sys_b = start, sys_c = start;
    Collider a(scheme, mix, sys_a, rng::make_stream(10, 2, rng::Purpose::collisions), 1.0);
    Collider b(scheme, mix, sys_b, rng::make_stream(10, 2, rng::Purpose::collisions), 1.0);
    Collider c(scheme, mix, sys_c, rng::make_stream(10, 3, rng::Purpose::collisions), 1.0);
    for (Collider* col : {&a, &b, &c}) {
      col->advance(5.0);
      col->advance(12.5, 4000);
      col->advance(40.0);
    }
    EXPECT_EQ(sys_a.v, sys_b.v);
    EXPECT_EQ(a.time(), b.time());
    EXPECT_EQ(a.counters().events, b.counters().events);
    EXPECT_EQ(a.counters().candidates, b.counters().candidates);
    EXPECT_NE(sys_a.v, sys_c.v);
  }
}

// Checkpoints (issue 5): a collider restored from state() into a copy of the particles continues
// bitwise as the original does, for every scheme, after stops by time and by events, from a stop
// at an event (mid sub-step) and from one at a sample time; a collider restored with a wrong saved
// state (other generator) does not.
TEST(Collide, RestoredStateContinuesBitwise) {
  const auto mix = binary(0.7, 0.9, 0.5);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    for (bool stop_at_event : {true, false}) {
      auto sys_a = initial(mix, {700, 300}, {1.0, 1.0}, 10);
      Collider a(scheme, mix, sys_a, rng::make_stream(10, 2, rng::Purpose::collisions), 1.0);
      a.advance(5.0);
      if (stop_at_event) {
        EXPECT_TRUE(a.advance(30.0, a.counters().events + 1234));
      }
      const Collider::State saved = a.state();
      auto sys_b = sys_a, sys_c = sys_a;
      // Different streams on purpose: restore() must replace them.
      Collider b(scheme, mix, sys_b, rng::make_stream(99, 0, rng::Purpose::collisions), 1.0);
      b.restore(saved);
      Collider c(scheme, mix, sys_c, rng::make_stream(99, 0, rng::Purpose::collisions), 1.0);
      Collider::State wrong = saved;
      wrong.generator = rng::make_stream(98, 0, rng::Purpose::collisions).state();
      c.restore(wrong);
      for (Collider* col : {&a, &b, &c}) {
        col->advance(20.0, col->counters().events + 2000);
        col->advance(45.0);
      }
      EXPECT_EQ(sys_a.v, sys_b.v);
      EXPECT_EQ(a.time(), b.time());
      EXPECT_EQ(a.counters().events, b.counters().events);
      EXPECT_EQ(a.counters().candidates, b.counters().candidates);
      EXPECT_EQ(a.counters().pair_events, b.counters().pair_events);
      EXPECT_EQ(a.mean_step(), b.mean_step());
      EXPECT_NE(sys_a.v, sys_c.v);
    }
  }
}

// Blocks (issue 5): only for one species with majorant or lowrank and N >= 2 block_size; a blocked
// collider restored mid-step (stopped at a time inside a step) continues bitwise; an exact event target
// is met exactly (the steps near it run on the whole gas), a soft one at a step end, never before it.
TEST(Collide, BlocksRestoreAndStopAtStepEnds) {
  const auto mix1 = one_species(0.9);
  const auto mix2 = binary(0.7, 0.9, 0.5);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    auto sys = initial(mix2, {2000, 2000}, {1.0, 1.0}, 3);
    Collider c(scheme, mix2, sys, rng::make_stream(3, 0, rng::Purpose::collisions), 1.0);
    c.use_blocks(1000);
    follow_scheme(c, scheme);
    // mixtures are blocked with majorant and lowrank, not pairs (species slices, header "Blocks")
    EXPECT_EQ(c.blocks(), scheme != Scheme::pairs ? 4u : 1u) << name(scheme);
  }
  {
    auto sys = initial(mix2, {3900, 100}, {1.0, 1.0}, 3);  // 100 < 64 K: the rare species is scattered
    Collider c(Scheme::majorant, mix2, sys, rng::make_stream(3, 0, rng::Purpose::collisions), 1.0);
    c.use_blocks(1000);
    EXPECT_EQ(c.blocks(), 4u);
  }
  for (Scheme scheme : {Scheme::majorant, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    auto sys_a = initial(mix1, {4000}, {1.0}, 4);
    Collider a(scheme, mix1, sys_a, rng::make_stream(4, 0, rng::Purpose::collisions), 1.0);
    a.use_blocks(1000);
    EXPECT_EQ(a.blocks(), 4u);
    EXPECT_TRUE(a.advance(1e9, 3000));
    EXPECT_EQ(a.counters().events, 3000u);  // exact (a whole-gas step near the target)
    EXPECT_TRUE(a.advance(1e9, 40000));
    EXPECT_EQ(a.counters().events, 40000u);
    EXPECT_TRUE(a.advance(1e9, 41000, false));  // a soft target: met at a step end
    EXPECT_GE(a.counters().events, 41000u);
    // A soft target with a hard limit beyond it (a progress chunk inside a sample; a step far from
    // an exact target brings ~11000 events here, 5.6 collisions per particle, header "Step length"):
    // the soft one is met at a step end, the limit never passed, then met exactly.
    const std::uint64_t limit = a.counters().events + 30000;
    for (int chunk = 0; chunk < 12; ++chunk) {
      const std::uint64_t before = a.counters().events;
      if (before >= limit) break;
      EXPECT_TRUE(a.advance(1e9, std::min<std::uint64_t>(before + 10, limit), false, limit));
      EXPECT_LE(a.counters().events, limit);
    }
    EXPECT_TRUE(a.advance(1e9, limit, false, limit));
    EXPECT_EQ(a.counters().events, limit);
    EXPECT_TRUE(a.advance(1e9, 1000000, false, limit + 3000));  // a soft target far beyond the limit
    EXPECT_EQ(a.counters().events, limit + 3000);
    // An exact target given inside a step (sized without it) that its rest would pass: met exactly.
    a.advance(a.time() + 1e9, UINT64_MAX, true, UINT64_MAX, true);  // to the end of a (long) step
    a.advance(a.time() + 0.2 * (a.mean_step()));  // inside the next
    const std::uint64_t inside = a.counters().events;
    EXPECT_TRUE(a.advance(1e9, inside + 4000));
    EXPECT_EQ(a.counters().events, inside + 4000);
    // ... and given a few candidates into a step (its rate so far known from a handful of events),
    // then two close targets after the step it ended (its acceptance from those few candidates).
    for (int round = 0; round < 20; ++round) {
      a.advance(a.time() + 1e9, UINT64_MAX, true, UINT64_MAX, true);  // to a step end
      a.advance(a.time() + 2e-4 * a.mean_step());  // a few candidates into the next step
      const std::uint64_t early = a.counters().events;
      EXPECT_TRUE(a.advance(1e9, early + 2500));
      EXPECT_EQ(a.counters().events, early + 2500);
      EXPECT_TRUE(a.advance(1e9, early + 2700));
      EXPECT_EQ(a.counters().events, early + 2700);
    }
    a.advance(a.time() + 0.37 * a.mean_step());  // inside a step
    const Collider::State saved = a.state();
    auto sys_b = sys_a;
    Collider b(scheme, mix1, sys_b, rng::make_stream(77, 0, rng::Purpose::collisions), 1.0);
    b.use_blocks(1000);
    b.restore(saved);
    const double t_end = a.time() + 40.0;
    for (Collider* col : {&a, &b}) col->advance(t_end);
    EXPECT_EQ(sys_a.v, sys_b.v);
    EXPECT_EQ(a.counters().events, b.counters().events);
    EXPECT_EQ(a.time(), b.time());
  }
  // Remixing moves particles and loses none: an elastic blocked gas keeps its energy and momentum.
  const auto elastic = one_species(1.0);
  auto sys = initial(elastic, {4000}, {1.0}, 5);
  auto totals = [&] {
    std::vector<double> t(4, 0.0);
    for (const auto& v : sys.v) {
      t[0] += v.x * v.x + v.y * v.y + v.z * v.z;
      t[1] += v.x;
      t[2] += v.y;
      t[3] += v.z;
    }
    return t;
  };
  const auto before = totals();
  Collider c(Scheme::majorant, elastic, sys, rng::make_stream(5, 0, rng::Purpose::collisions), 1.0);
  c.use_blocks(1000);
  c.advance(300.0);
  EXPECT_GT(c.counters().steps, 3u);  // several remixes
  const auto after = totals();
  EXPECT_NEAR(after[0], before[0], 1e-10 * before[0]);
  for (int k = 1; k < 4; ++k) EXPECT_NEAR(after[k], before[k], 1e-9);
}

// The remix in place (deal.hpp) is the dealing into a second array that it replaced, bit for bit: for
// one species and a binary mixture (each species dealt round its own slices), velocities and tracked
// displacements, with K = Collider::blocks() not dividing N (nor N_k), on 1, 2 and 3 threads, compared
// with that dealing written out here (old index (offset + i) mod N_k to slice i mod K, slot i div K); and the remix's
// scratch memory stays within its bound, below the second array it replaced.
TEST(Collide, DealInPlaceIsTheDealing) {
  const auto mix1 = one_species(0.9);
  const auto mix2 = binary(0.9, 0.8, 0.7);
  struct Case {
    const species::Mixture* mix;
    std::vector<std::size_t> counts;
    std::size_t block_size;
  };
  for (const Case& c : {Case{&mix1, {10007}, 1000}, Case{&mix1, {4099}, 130}, Case{&mix2, {7001, 2999}, 1000},
                        Case{&mix2, {5003, 1301}, 150}}) {
    auto sys = initial(*c.mix, c.counts, std::vector<double>(c.counts.size(), 1.0), 11);
    particles::start_tracking(sys, 0.0);
    for (std::size_t i = 0; i < sys.size(); ++i) sys.r[i] = {0.5 * i, -1.0 * i, 2.0 * i, 0.25 * i};
    Collider collider(Scheme::majorant, *c.mix, sys, rng::make_stream(11, 0, rng::Purpose::collisions), 1.0);
    collider.use_blocks(c.block_size);
    const std::size_t blocks = collider.blocks(), s = c.counts.size();
    ASSERT_GT(blocks, 2u);
    bool divides = true;
    for (std::size_t n_k : c.counts) divides = divides && n_k % blocks == 0;
    EXPECT_FALSE(divides) << "K = " << blocks;
    // The slices of use_blocks(): ceil((N_k - j)/K) particles of species k in block j.
    std::vector<std::size_t> slice_first(blocks * s);
    for (std::size_t k = 0; k < s; ++k)
      for (std::size_t j = 0, first = sys.first[k]; j < blocks; ++j) {
        slice_first[j * s + k] = first;
        first += (c.counts[k] - j + blocks - 1) / blocks;
      }
    auto rgen = rng::make_stream(12, 0, rng::Purpose::collisions);
    deal::Workspace workspace;
    for (int remix = 0; remix < 3; ++remix) {
      std::vector<std::size_t> offset(s);
      for (std::size_t k = 0; k < s; ++k) offset[k] = rgen.below(c.counts[k]);
      auto dealt = [&](const auto& data) {  // the out-of-place dealing of each species round its slices
        auto out = data;
        for (std::size_t k = 0; k < s; ++k)
          for (std::size_t i = 0; i < c.counts[k]; ++i)
            out[slice_first[(i % blocks) * s + k] + i / blocks] =
                data[sys.first[k] + (offset[k] + i) % c.counts[k]];
        return out;
      };
      const auto v = dealt(sys.v);
      const auto r = dealt(sys.r);
      for (std::size_t k = 0; k < s; ++k) {  // on 1, 2 and 3 threads
        deal::deal_in_place(sys.v.data() + sys.first[k], c.counts[k], blocks, offset[k], workspace, 1 + remix);
        deal::deal_in_place(sys.r.data() + sys.first[k], c.counts[k], blocks, offset[k], workspace, 1 + remix);
      }
      EXPECT_TRUE(sys.v == v) << "N = " << sys.size() << ", K = " << blocks << ", remix " << remix;
      EXPECT_TRUE(sys.r == r) << "N = " << sys.size() << ", K = " << blocks << ", remix " << remix;
    }
    // The elements aside (fewer than seg K + K) and at most 9 tiles of seg K a thread, seg <= N_k/(128 K),
    // and 2 bits a grid place (deal.hpp): on 3 threads below a quarter of the second array it replaced,
    // on one thread (the collider here) below an eighth.
    EXPECT_LE(workspace.bytes(), sys.size() * sizeof(particles::Displacement) / 4 + 256);
    EXPECT_LE(collider.workspace_bytes(), sys.size() * sizeof(particles::Displacement) / 8 + 256);
  }
  // Edge cases of the permutation itself: n < k, k = 1, k = n, segments of one row.
  deal::Workspace workspace;
  for (std::size_t n : {1u, 2u, 5u, 33u, 64u, 65u, 1000u})
    for (std::size_t k : {1u, 2u, 3u, 31u, 64u, 200u})
      for (std::size_t offset : {std::size_t{0}, n / 3, n - 1}) {
        std::vector<double> data(n), out(n);
        for (std::size_t i = 0; i < n; ++i) data[i] = static_cast<double>(i);
        const std::size_t q = n / k, r = n % k;
        for (std::size_t i = 0; i < n; ++i)
          out[(i % k) * q + std::min(i % k, r) + i / k] = data[(offset + i) % n];
        deal::deal_in_place(data.data(), n, k, offset, workspace, static_cast<int>(1 + n % 3));
        EXPECT_EQ(data, out) << "n = " << n << ", k = " << k << ", offset = " << offset;
      }
  // The long cycles of stage 3 cut into pieces on 2 and 3 threads (deal.hpp, "Threads"): at n = 200003
  // in 30 blocks a random offset usually leaves one cycle holding most of the grid.
  std::size_t cut = 0;
  for (std::size_t offset : {std::size_t{0}, std::size_t{12345}, std::size_t{99991}, std::size_t{200002}})
    for (int threads : {2, 3}) {
      const std::size_t n = 200003, k = 30, q = n / k, r = n % k;
      std::vector<std::uint64_t> data(n), out(n);
      for (std::size_t i = 0; i < n; ++i) data[i] = i;
      for (std::size_t i = 0; i < n; ++i) out[(i % k) * q + std::min(i % k, r) + i / k] = data[(offset + i) % n];
      deal::deal_in_place(data.data(), n, k, offset, workspace, threads);
      EXPECT_TRUE(data == out) << "n = " << n << ", offset = " << offset << ", threads = " << threads;
      cut += workspace.pieces.size();
    }
  EXPECT_GT(cut, 0u);
}

// The order in which the threads take up the blocks (collide.hpp, "Threads inside one replica"): written
// out by hand for 7 blocks on 2 and 3 threads, the identity on one thread, and for K = 1..40 blocks on
// 1 to 4 threads a permutation of 0..K-1 whose consecutive entries are never neighbouring blocks when
// K > 2 T (h = ceil(K/T) apart within a row, at least h - 1 from one row to the next; at K = 4, T = 2 the
// order 0, 2, 1, 3 has 2 then 1).
TEST(Collide, BlockVisitOrderKeepsNeighboursApart) {
  using V = std::vector<std::size_t>;
  EXPECT_EQ(Collider::visit_order(7, 2), (V{0, 4, 1, 5, 2, 6, 3}));
  EXPECT_EQ(Collider::visit_order(7, 3), (V{0, 3, 6, 1, 4, 2, 5}));
  EXPECT_EQ(Collider::visit_order(5, 1), (V{0, 1, 2, 3, 4}));
  for (int threads = 1; threads <= 4; ++threads)
    for (std::size_t k = 1; k <= 40; ++k) {
      SCOPED_TRACE(std::to_string(k) + " blocks, " + std::to_string(threads) + " threads");
      const V order = Collider::visit_order(k, threads);
      V sorted = order;
      std::sort(sorted.begin(), sorted.end());
      V identity(k);
      for (std::size_t j = 0; j < k; ++j) identity[j] = j;
      ASSERT_EQ(sorted, identity);
      if (threads > 1 && k > 2 * static_cast<std::size_t>(threads))
        for (std::size_t q = 0; q + 1 < k; ++q) {
          const std::size_t a = order[q], b = order[q + 1];
          EXPECT_GT(a > b ? a - b : b - a, 1u) << "at " << q;
        }
    }
}

// Threads inside one replica (collide.hpp): the blocks of a step on 1, 2 or 3 threads give the same
// velocities, displacements, counts and dissipated energy, bit for bit, for one species (time-driven,
// with displacements) and a binary mixture with `majorant` and `lowrank` (up to an exact event target,
// through whole-gas steps); a
// restored collider with another thread count continues bitwise.
TEST(Collide, BlockThreadsAreBitwiseTheSame) {
  const auto mix1 = one_species(0.9);
  const auto mix2 = binary(0.7, 0.9, 0.5);
  struct Run {
    std::vector<particles::Vec3> v;
    std::vector<double> r;
    collide::Counters counters;
    double time;
  };
  auto run = [&](const species::Mixture& mix, std::vector<std::size_t> counts, int threads, bool track,
                 Scheme scheme) {
    auto sys = initial(mix, counts, std::vector<double>(counts.size(), 1.0), 8);
    if (track) particles::start_tracking(sys, 0.0);
    Collider c(scheme, mix, sys, rng::make_stream(8, 0, rng::Purpose::collisions), 1.0);
    c.use_blocks(1000);
    follow_scheme(c, scheme);
    c.use_threads(threads);
    EXPECT_GT(c.blocks(), 2u);
    if (track) {
      c.advance(60.0);
      c.advance(60.0 + 0.5 * c.mean_step());  // ends inside a step
      c.advance(150.0);
    } else {
      c.advance(1e9, 30000);
    }
    Run out{{sys.v.begin(), sys.v.end()}, {}, c.counters(), c.time()};
    if (track)
      for (const auto& d : sys.r) out.r.insert(out.r.end(), {d.x, d.y, d.z, d.t_last});
    return out;
  };
  for (int path = 0; path < 3; ++path) {
    SCOPED_TRACE(path == 0 ? "one species" : path == 1 ? "binary mixture, majorant" : "binary mixture, lowrank");
    const Scheme scheme = path == 2 ? Scheme::lowrank : Scheme::majorant;
    auto one_run = [&](int threads) {
      return path == 0 ? run(mix1, {6000}, threads, true, scheme) : run(mix2, {3000, 3000}, threads, false, scheme);
    };
    const Run serial = one_run(1);
    EXPECT_GT(serial.counters.events, 10000u);
    for (int threads : {2, 3}) {
      const Run threaded = one_run(threads);
      EXPECT_EQ(threaded.v, serial.v) << threads << " threads";
      EXPECT_EQ(threaded.r, serial.r);
      EXPECT_EQ(threaded.counters.events, serial.counters.events);
      EXPECT_EQ(threaded.counters.candidates, serial.counters.candidates);
      EXPECT_EQ(threaded.counters.pair_events, serial.counters.pair_events);
      EXPECT_EQ(threaded.counters.dissipated, serial.counters.dissipated);
      EXPECT_EQ(threaded.time, serial.time);
    }
  }
  // Checkpointed with 1 thread mid-step, continued with 2: the same as 1 thread throughout.
  auto sys_a = initial(mix1, {6000}, {1.0}, 9);
  Collider a(Scheme::majorant, mix1, sys_a, rng::make_stream(9, 0, rng::Purpose::collisions), 1.0);
  a.use_blocks(1000);
  a.advance(50.0);
  a.advance(50.0 + 0.3 * a.mean_step());
  auto sys_b = sys_a;
  Collider b(Scheme::majorant, mix1, sys_b, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  b.use_blocks(1000);
  b.use_threads(2);
  b.restore(a.state());
  a.advance(120.0);
  b.advance(120.0);
  EXPECT_EQ(sys_a.v, sys_b.v);
  EXPECT_EQ(a.counters().events, b.counters().events);
  EXPECT_EQ(a.counters().dissipated, b.counters().dissipated);
}

// (e) Advancing in 200 small increments instead of one call is not bitwise identical (the candidate
// clock is carried across calls), but it samples the same process: with the same seeds, elastic
// one-species gas (N = 5000, n = 0.01) over t = 40 (expected N nu t / 2 = 7090 events), the two
// event counts agree within 5 sqrt(E1 + E2) (as if independent Poisson counts; conservative).
TEST(Collide, SmallIncrementsSampleTheSameProcess) {
  const auto mix = one_species(1.0);
  const double t_end = 40.0;
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    auto sys_a = initial(mix, {5000}, {1.0}, 12), sys_b = sys_a;
    Collider a(scheme, mix, sys_a, rng::make_stream(12, 0, rng::Purpose::collisions), 1.0);
    Collider b(scheme, mix, sys_b, rng::make_stream(12, 0, rng::Purpose::collisions), 1.0);
    a.advance(t_end);
    for (int i = 1; i <= 200; ++i) b.advance(t_end * i / 200.0);
    EXPECT_EQ(a.time(), b.time());
    const double ea = static_cast<double>(a.counters().events);
    const double eb = static_cast<double>(b.counters().events);
    std::printf("[ Collide.Increments ] %s: one call %.0f events, 200 calls %.0f events\n",
                name(scheme), ea, eb);
    EXPECT_NEAR(ea, eb, 5.0 * std::sqrt(ea + eb)) << name(scheme);
  }
}

// (f) Haff cooling, one species, alpha = 0.5, n = 0.01, sigma = m = T0 = 1, N = 1e5 Maxwellian.
// Over dt = 0.05 collision times (1/nu) the measured rate r = (T0 - T(dt)) / (T0 dt) is compared
// with Haff's law T(dt) = T0 / (1 + zeta0 dt / 2)^2 (\ref haff_law "docs/haff-and-mixtures.md"), zeta0 = (4/3) sqrt(pi)
// (1 - alpha^2) n sigma^2 sqrt(T0/m), i.e. r_exp = [1 - (1 + zeta0 dt/2)^-2] / dt = zeta0 (1 - 0.94 %).
// (The initial state is Maxwellian, so the Sonine correction of the cooling rate is zero at t = 0 and
// O(1e-4) after 0.05 collisions per particle.) Ensemble: 20 independent seeds per scheme (about
// 2500 collisions each); SE = sample std / sqrt(20); tolerance 5 SE.
TEST(Collide, HaffCoolingRate) {
  const double alpha = 0.5, n = 0.01, sigma = 1.0, mass = 1.0, t0 = 1.0;
  const auto mix = one_species(alpha, n);
  const double nu = 4.0 * std::sqrt(kPi) * n * sigma * sigma * std::sqrt(t0 / mass);
  const double zeta0 = 4.0 / 3.0 * std::sqrt(kPi) * (1.0 - alpha * alpha) * n * sigma * sigma *
                       std::sqrt(t0 / mass);
  const double dt = 0.05 / nu;
  const double expected = (1.0 - 1.0 / std::pow(1.0 + zeta0 * dt / 2.0, 2)) / dt;
  const int replicas = 20;
  const std::size_t n_particles = 100000;
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    std::vector<double> rate(replicas);
    for (int r = 0; r < replicas; ++r) {
      auto sys = initial(mix, {n_particles}, {t0}, 100 + r);
      Collider collider(scheme, mix, sys, rng::make_stream(100 + r, 0, rng::Purpose::collisions), 1.0);
      collider.advance(dt);
      const double t_end = 2.0 * kinetic_energy(mix, sys) / (3.0 * n_particles);  // momentum is 0
      rate[r] = (t0 - t_end) / (t0 * dt);
    }
    double mean = 0.0;
    for (double x : rate) mean += x;
    mean /= replicas;
    double var = 0.0;
    for (double x : rate) var += (x - mean) * (x - mean);
    const double se = std::sqrt(var / (replicas - 1) / replicas);
    std::printf("[ Collide.Haff ] %s: rate %.6f, SE %.6f, expected %.6f (zeta0 %.6f), "
                "(r-exp)/SE = %.2f\n", name(scheme), mean, se, expected, zeta0,
                (mean - expected) / se);
    EXPECT_NEAR(mean, expected, 5.0 * se) << name(scheme);
    EXPECT_LT(se, 0.01 * expected);  // the test has resolving power
  }
}

// The frame (collide.hpp, "Frame"). With S = 2, c = 0 the frame is an exact power-of-two scaling, so a
// framed collider on u and a plain one on V = 2 u make the same decisions bit for bit: same events,
// same candidates, V = 2 u at the end, the same dissipated energy; and the moments kept collision by
// collision equal sum m u u^T recomputed (binary mixture, every scheme).
TEST(Collide, FrameOfScaleTwoIsTheUnframedGasBitwise) {
  const auto mix = binary(0.9, 0.8, 0.7);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    auto u = initial(mix, {600, 400}, {0.25, 0.25}, 21);
    auto v = u;
    for (auto& x : v.v) x = {2.0 * x.x, 2.0 * x.y, 2.0 * x.z};
    Collider framed(scheme, mix, u, rng::make_stream(21, 0, rng::Purpose::collisions), 0.5);
    Collider plain(scheme, mix, v, rng::make_stream(21, 0, rng::Purpose::collisions), 0.5);
    framed.set_frame(2.0, 0.0);
    framed.advance(1e12, 20000);
    plain.advance(1e12, 20000);
    EXPECT_EQ(framed.counters().events, plain.counters().events);
    EXPECT_EQ(framed.counters().candidates, plain.counters().candidates);
    EXPECT_EQ(framed.time(), plain.time());
    EXPECT_EQ(framed.counters().dissipated, plain.counters().dissipated);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < u.size(); ++i)
      differ += u.v[i].x * 2.0 != v.v[i].x || u.v[i].y * 2.0 != v.v[i].y || u.v[i].z * 2.0 != v.v[i].z;
    EXPECT_EQ(differ, 0u);
    expect_frame_moments(framed, mix, u);
  }
}

// A sheared frame (c = 0.3, S = 0.7): the collisions act on the actual velocities V = G u. Checked on
// V recomputed from u: momentum conserved, the energy of V lost is exactly the dissipated sum
// (1 - alpha^2) m_kj (g.e)^2 / 2 of the actual g (a wrong G^-1 in the update breaks both), and the
// moments kept equal the recomputed ones. An elastic run keeps the energy of V to 1e-10.
TEST(Collide, ShearedFrameCollidesTheActualVelocities) {
  for (double alpha : {0.8, 1.0}) {
    const auto mix = binary(alpha, alpha, alpha);
    for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
      SCOPED_TRACE(std::string(name(scheme)) + " alpha " + std::to_string(alpha));
      auto u = initial(mix, {1200, 800}, {1.0, 1.0}, 22);
      const double s = 0.7, c = 0.3;
      auto actual = [&] {
        particles::System w = u;
        for (auto& x : w.v) x = {s * (x.x + c * x.y), s * x.y, s * x.z};
        return w;
      };
      const auto v0 = actual();
      double p0[3], scale;
      momentum(mix, v0, p0, &scale);
      const double e0 = kinetic_energy(mix, v0);
      Collider collider(scheme, mix, u, rng::make_stream(22, 0, rng::Purpose::collisions), 0.5);
      collider.set_frame(s, c);
      collider.advance(1e12, 50000);
      EXPECT_EQ(collider.counters().events, 50000u);
      const auto v1 = actual();
      double p1[3];
      momentum(mix, v1, p1);
      for (int d = 0; d < 3; ++d) EXPECT_LT(std::abs(p1[d] - p0[d]), 1e-12 * scale);
      const double e1 = kinetic_energy(mix, v1);
      EXPECT_NEAR(e0 - e1, collider.counters().dissipated, 1e-10 * e0);
      if (alpha == 1.0) {
        EXPECT_NEAR(e1 / e0, 1.0, 1e-10);
      } else {
        EXPECT_GT(collider.counters().dissipated, 0.05 * e0);
      }
      expect_frame_moments(collider, mix, u);
    }
  }
}

// Frames in blocks (header, "Frame"; `majorant` and `lowrank`, one species and a binary mixture, 4
// blocks; the binary `lowrank` also with the factored draw forced, whose rows and acceptance take ||G||):
// in a
// sheared frame (S = 1.3, c = 0.3) the blocked collider never overshoots, conserves the momentum of V = G u, loses exactly the dissipated
// energy, keeps the moments Q equal to the recomputed ones (each block's change added in block order),
// meets an event target exactly, and gives the same u, counts and Q bit for bit on 1 and 2 threads.
TEST(Collide, ShearedFrameInBlocks) {
  const auto binary_mix = binary(0.8, 0.8, 0.8);
  const auto one = one_species(0.8);
  for (int sampler = 0; sampler < 3; ++sampler)  // majorant, lowrank, lowrank by the factored draw
  for (const species::Mixture* mix : {&one, &binary_mix}) {
    const Scheme scheme = sampler == 0 ? Scheme::majorant : Scheme::lowrank;
    const bool factored = sampler == 2;
    if (factored && mix->size() == 1) continue;  // (one species runs the one-species kernel)
    SCOPED_TRACE(std::string(name(scheme)) + (factored ? " factored" : "") +
                 (mix->size() == 1 ? ", one species" : ", binary"));
    const std::vector<std::size_t> counts = mix->size() == 1 ? std::vector<std::size_t>{8000}
                                                              : std::vector<std::size_t>{4800, 3200};
    const std::vector<double> temperatures(mix->size(), 1.0);
    const double s = 1.3, c = 0.3;  // ||G|| = 1.51: a bound without it overshoots
    auto run = [&](int threads, particles::System& u) {
      Collider collider(scheme, *mix, u, rng::make_stream(31, 0, rng::Purpose::collisions), 0.5);
      collider.use_blocks(2000);
      follow_scheme(collider, scheme);
      if (factored) collider.set_lowrank_factor_above(0);
      collider.use_threads(threads);
      EXPECT_EQ(collider.blocks(), 4u);
      collider.set_frame(s, c);
      EXPECT_TRUE(collider.advance(1e12, 30000));
      EXPECT_EQ(collider.counters().events, 30000u);
      // (event caps far above a correct run's ~10^4 events: a wrong update that heats the gas
      // without bound then fails here instead of running on)
      collider.advance(collider.time() + 40.0, 200000);
      collider.set_frame(s * 0.9, c - 0.01);  // the next stage's frame
      collider.advance(collider.time() + 40.0, 400000);
      return collider;
    };
    auto u1 = initial(*mix, counts, temperatures, 31);
    auto u2 = u1;
    auto actual = [&](const particles::System& u, double scale, double shear) {
      particles::System w = u;
      for (auto& x : w.v) x = {scale * (x.x + shear * x.y), scale * x.y, scale * x.z};
      return w;
    };
    const auto v0 = actual(u1, s, c);
    double p0[3], scale;
    momentum(*mix, v0, p0, &scale);
    const double e0 = kinetic_energy(*mix, v0);
    // the energy of the first frame's V up to the frame change, then of the second's: compare the
    // invariants after a run in one frame only
    particles::System u_one = u1;
    {
      Collider collider(scheme, *mix, u_one, rng::make_stream(32, 0, rng::Purpose::collisions), 0.5);
      collider.use_blocks(2000);
      follow_scheme(collider, scheme);
      if (factored) collider.set_lowrank_factor_above(0);
      collider.set_frame(s, c);
      collider.advance(150.0, 200000);
      EXPECT_GT(collider.counters().events, 20000u);
      EXPECT_LT(collider.counters().events, 200000u);
      EXPECT_GT(collider.counters().steps, 2u);  // remixes between the blocked steps
      const auto v1 = actual(u_one, s, c);
      double p1[3];
      momentum(*mix, v1, p1);
      for (int d = 0; d < 3; ++d) EXPECT_LT(std::abs(p1[d] - p0[d]), 1e-12 * scale);
      EXPECT_NEAR(e0 - kinetic_energy(*mix, v1), collider.counters().dissipated, 1e-10 * e0);
      expect_frame_moments(collider, *mix, u_one);
      EXPECT_EQ(collider.counters().overshoots, 0u);
    }
    const Collider c1 = run(1, u1);
    const Collider c2 = run(2, u2);
    expect_frame_moments(c1, *mix, u1);
    EXPECT_EQ(c1.counters().events, c2.counters().events);
    EXPECT_EQ(c1.counters().candidates, c2.counters().candidates);
    EXPECT_EQ(c1.counters().dissipated, c2.counters().dissipated);
    EXPECT_EQ(c1.frame_moments(), c2.frame_moments());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < u1.size(); ++i)
      differ += u1.v[i].x != u2.v[i].x || u1.v[i].y != u2.v[i].y || u1.v[i].z != u2.v[i].z;
    EXPECT_EQ(differ, 0u);
  }
}

// The bound of a frame is ||G|| times that of u: the largest singular value of S [[1, c], [0, 1]],
// S (|c|/2 + sqrt(1 + c^2/4)); by hand, c = 0.04: 1.0202; c = 2: 1 + sqrt(2) (the silver ratio).
TEST(Collide, FrameNormIsTheLargestSingularValue) {
  EXPECT_DOUBLE_EQ(Collider::frame_norm(1.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(Collider::frame_norm(3.0, 0.0), 3.0);
  EXPECT_NEAR(Collider::frame_norm(1.0, 2.0), 1.0 + std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(Collider::frame_norm(2.0, -2.0), 2.0 * (1.0 + std::sqrt(2.0)), 1e-14);
  EXPECT_NEAR(Collider::frame_norm(1.0, 0.04), 0.02 + std::sqrt(1.0004), 1e-15);
  // No vector is stretched more: G (1, t, 0)/|(1, t, 0)| over a fine grid of directions in the xy plane.
  for (double c : {0.04, 0.5, 2.0}) {
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
      const double phi = i * kPi / 20000.0, x = std::cos(phi), y = std::sin(phi);
      worst = std::max(worst, std::hypot(x + c * y, y));
    }
    EXPECT_LE(worst, Collider::frame_norm(1.0, c) * (1.0 + 1e-15));
    EXPECT_GT(worst, Collider::frame_norm(1.0, c) * (1.0 - 1e-7));
  }
}

// The stage loop's pass in cache blocks (Collider::map_blocks; thermostat.hpp, "Cost: the frame"): three species
// of 4800, 3200 and 40 particles (the third scattered) in 4 blocks, after collisions in a sheared frame. The map
// V = (s u_x + sc u_y, s u_y, s u_z) + b with s = 1.3, sc = 1.3 x 0.03, b = (0.2, -0.1, 0.05) gives every
// velocity bit for bit as computed here; the mass, momentum and moments agree with sums over the particles to
// 1e-12 of their scale; each block's bound is bit for bit what reset_frame's own pass over the block finds, and
// the largest speed of each species the largest |V|^2 over the particles; on 2 threads every bit is as on 1.
TEST(Collide, BlockPassMapsSumsAndBoundsAsSeparatePasses) {
  const auto mix = species::make_mixture({1.0, 2.0, 4.0}, {1.0, 1.3, 1.6}, {0.006, 0.004, 0.00005},
                                         species::PairMatrix(3, 0.8), false);
  const double s = 1.3, sc = 1.3 * 0.03;
  const particles::Vec3 b{0.2, -0.1, 0.05};
  struct Result {
    particles::System sys;
    Collider::BlockPass pass;
    std::vector<double> bounds;
  };
  auto run = [&](int threads, bool by_blocks) {
    Result r{initial(mix, {4800, 3200, 40}, {1.0, 1.0, 1.0}, 41), {}, {}};
    Collider collider(Scheme::majorant, mix, r.sys, rng::make_stream(41, 0, rng::Purpose::collisions), 0.5);
    collider.use_blocks(2000);
    collider.use_threads(threads);
    EXPECT_EQ(collider.blocks(), 4u);
    collider.set_frame(1.3, 0.03);
    collider.advance(1e12, 20000);
    if (by_blocks) {
      r.pass = collider.map_blocks(s, sc, b);
      collider.reset_frame(r.pass.moments, r.pass.max_speed2, true);
    } else {  // the map here, then reset_frame's own pass over each block
      for (auto& v : r.sys.v) v = {s * v.x + sc * v.y + b.x, s * v.y + b.y, s * v.z + b.z};
      std::vector<double> max2(3, 0.0);
      for (std::size_t i = 0; i < r.sys.size(); ++i) {
        const auto& v = r.sys.v[i];
        max2[r.sys.species[i]] = std::max(max2[r.sys.species[i]], v.x * v.x + v.y * v.y + v.z * v.z);
      }
      r.pass.max_speed2 = max2;
      collider.reset_frame({0.0, 0.0, 0.0, 0.0}, max2);
    }
    r.bounds = collider.state().block_max_speed2;
    return r;
  };
  const Result reference = run(1, false), one = run(1, true), two = run(2, true);
  ASSERT_EQ(one.sys.size(), reference.sys.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < one.sys.size(); ++i)
    differ += one.sys.v[i].x != reference.sys.v[i].x || one.sys.v[i].y != reference.sys.v[i].y ||
              one.sys.v[i].z != reference.sys.v[i].z || two.sys.v[i].x != one.sys.v[i].x ||
              two.sys.v[i].y != one.sys.v[i].y || two.sys.v[i].z != one.sys.v[i].z;
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(one.bounds, reference.bounds);
  EXPECT_EQ(two.bounds, one.bounds);
  EXPECT_EQ(one.pass.max_speed2, reference.pass.max_speed2);
  double mass = 0.0, p[3] = {0.0, 0.0, 0.0}, q[4] = {0.0, 0.0, 0.0, 0.0}, scale = 0.0;
  for (std::size_t i = 0; i < reference.sys.size(); ++i) {
    const double m = mix.mass[reference.sys.species[i]];
    const auto& v = reference.sys.v[i];
    mass += m, p[0] += m * v.x, p[1] += m * v.y, p[2] += m * v.z;
    q[0] += m * v.x * v.x, q[1] += m * v.y * v.y, q[2] += m * v.z * v.z, q[3] += m * v.x * v.y;
    scale += m * (v.x * v.x + v.y * v.y + v.z * v.z);
  }
  EXPECT_NEAR(one.pass.mass, mass, 1e-12 * mass);
  EXPECT_NEAR(one.pass.momentum.x, p[0], 1e-12 * scale);
  EXPECT_NEAR(one.pass.momentum.y, p[1], 1e-12 * scale);
  EXPECT_NEAR(one.pass.momentum.z, p[2], 1e-12 * scale);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(one.pass.moments[k], q[k], 1e-12 * scale);
  EXPECT_EQ(two.pass.mass, one.pass.mass);
  EXPECT_EQ(two.pass.momentum.x, one.pass.momentum.x);
  EXPECT_EQ(two.pass.momentum.y, one.pass.momentum.y);
  EXPECT_EQ(two.pass.momentum.z, one.pass.momentum.z);
  EXPECT_EQ(two.pass.moments, one.pass.moments);
}

// The kernel's invariant (Counters::overshoots): with the bounds of the schemes an acceptance
// probability never exceeds 1, also when the bounds are refreshed rarely (step_fraction 50, so only
// the raise-when-exceeded keeps them) and in a sheared frame; and a bound set too low on purpose is
// noticed (the count and the largest probability are reported, not silently capped at 1).
TEST(Collide, AcceptanceNeverExceedsOneAndAnOvershootIsCounted) {
  const auto mix = binary(0.8, 0.8, 0.8);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    {
      auto sys = initial(mix, {1500, 1000}, {1.0, 3.0}, 23);
      Collider collider(scheme, mix, sys, rng::make_stream(23, 0, rng::Purpose::collisions), 50.0);
      collider.advance(1e12, 100000);
      EXPECT_EQ(collider.counters().overshoots, 0u);
      collider.set_frame(1.3, 0.04);
      collider.advance(1e12, 200000);
      EXPECT_EQ(collider.counters().overshoots, 0u);
    }
    auto sys = initial(mix, {1500, 1000}, {1.0, 3.0}, 24);
    Collider collider(scheme, mix, sys, rng::make_stream(24, 0, rng::Purpose::collisions), 50.0);
    collider.advance(1e12, 10);  // the first step: exact bounds, a long step ahead
    collider.set_max_speeds({0.01, 0.01});  // far below the real speeds
    collider.advance(1e12, 20);
    EXPECT_GT(collider.counters().overshoots, 0u);
    EXPECT_GT(collider.counters().largest_acceptance, 1.0);
  }
}

// Collision-driven runs with blocks (header "Blocks"): the steps near an exact event target run on the
// whole gas. Over 16 replicas (N = 6000, 4 blocks, alpha = 0.8, 10 collisions per particle in 5
// targets) the temperature and the time at each target agree with the unblocked collider within
// 4 combined standard errors (a wrong rate in the mixed steps, e.g. the block density used on the
// whole gas, shifts the time by far more), and every target is met exactly.
TEST(Collide, BlockedCollisionDrivenRunsMatchUnblocked) {
  const auto mix = one_species(0.8);
  const std::size_t n = 6000, replicas = 16;
  std::vector<std::vector<double>> temperature(2), time(2);
  for (int blocked = 0; blocked < 2; ++blocked)
    for (std::size_t r = 0; r < replicas; ++r) {
      auto sys = initial(mix, {n}, {1.0}, 100 + r);
      Collider c(Scheme::majorant, mix, sys, rng::make_stream(100 + r, 0, rng::Purpose::collisions), 1.0);
      if (blocked) c.use_blocks(1500);
      EXPECT_EQ(c.blocks(), blocked ? 4u : 1u);
      for (std::uint64_t target : {3000u, 6000u, 15000u, 24000u, 30000u}) {
        c.advance(1e12, target);
        ASSERT_EQ(c.counters().events, target);
      }
      temperature[blocked].push_back(2.0 * kinetic_energy(mix, sys) / (3.0 * static_cast<double>(n)));
      time[blocked].push_back(c.time());
    }
  for (auto* q : {&temperature, &time}) {
    const auto [m0, s0] = mean_se((*q)[0]);
    const auto [m1, s1] = mean_se((*q)[1]);
    std::printf("[ Blocks.CollisionDriven ] unblocked %.6g +- %.2g, blocked %.6g +- %.2g (%.2f SE)\n", m0, s0, m1, s1,
                (m1 - m0) / std::hypot(s0, s1));
    EXPECT_LT(std::abs(m1 - m0), 4.0 * std::hypot(s0, s1));
  }
}

namespace {
// One species in blocks driven by events only: every target met exactly, no acceptance overshoot.
void expect_event_targets_met(double alpha, std::size_t n, std::size_t block_size, std::size_t blocks,
                              std::uint64_t seed, const std::vector<std::uint64_t>& targets) {
  const auto mix = one_species(alpha);
  auto sys = initial(mix, {n}, {1.0}, seed);
  Collider c(Scheme::majorant, mix, sys, rng::make_stream(seed, 0, rng::Purpose::collisions), 1.0);
  c.use_blocks(block_size);
  ASSERT_EQ(c.blocks(), blocks);
  for (std::uint64_t target : targets) {
    EXPECT_TRUE(c.advance(1e12, target));
    ASSERT_EQ(c.counters().events, target);
  }
  EXPECT_EQ(c.counters().overshoots, 0u);
}
}  // namespace

// With many blocks (K = 60 > 32) a whole-gas step near an event target is capped at 4 blocks' events
// instead of N/8 (header "Blocks"): the blocked steps are shortened further, and every target is still
// met exactly, with no acceptance overshoot.
TEST(Collide, ManyBlocksMeetEventTargetsExactly) {
  expect_event_targets_met(0.8, 24000, 400, 60, 7, {5000, 12000, 30000, 48000, 120000});
}

// Long blocked steps near exact targets (header "Blocks", "Step length", "Event targets"): a strongly
// inelastic gas (alpha = 0.3: steps of sqrt(2/gamma) = 2.5 collisions per particle, over which the
// acceptance falls by about a fifth) large enough that the margins of 10 % and 8 standard deviations are
// small: each target is met exactly. (The step after a long one takes the acceptance of the long one's
// first 5 mean free times, its probe, and long steps are shortened to fit a target.)
TEST(Collide, LongBlockedStepsMeetEventTargetsExactly) {
  expect_event_targets_met(0.3, 200000, 10000, 20, 8, {1000000, 2000000, 2500000});
}

namespace {
// A `majorant` collider in blocks of `block_size` on `threads` threads that takes over `from`'s run through
// a checkpoint's Record (its own stream seeded otherwise: what follows must come from the record alone).
std::unique_ptr<Collider> restored_majorant_blocks(const Collider& from, const species::Mixture& mix,
                                                   particles::System& sys, std::size_t block_size, int threads) {
  state::Record record;
  from.save(record);
  auto fresh = std::make_unique<Collider>(Scheme::majorant, mix, sys, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  fresh->use_blocks(block_size);
  fresh->use_threads(threads);
  fresh->restore(record);
  return fresh;
}
}  // namespace

// A step begun short is judged by its plan (header "Event targets"): one species, alpha = 0.9, N = 1e5 in 20
// blocks, every speed sqrt(3) at the start (no tail: the first step's exact bound rises as collisions make
// one), to an exact target of 18 collisions per particle. The first step is begun at block_steps mean free
// times (250000 candidates) and brings about 1.9 times as many as its bound rises; its acceptance, times
// that ratio, then sizes the second step, which is long (5.6 collisions per particle at the first step's
// acceptance: about 3.4 times block_steps; the target stays out of its reach). Judged by its candidates the
// first step would count as long without a probe, acceptance 1, whose long step might reach the target,
// and the second step would be cut to block_steps (tests/mutation 101). The target is met exactly, bit for bit on 2 threads and restored
// after the first step.
TEST(Collide, AStepBegunShortIsJudgedByItsPlan) {
  const auto mix = one_species(0.9);
  const std::uint64_t target = 900000;
  const double short_candidates = 5.0 * 100000 / 2.0;  // block_steps N step_fraction / 2
  struct Run {
    std::vector<particles::Vec3> v;
    std::vector<collide::Collider::State> steps;  // the state at each step's end
  };
  auto run = [&](int threads, bool restart) {
    auto sys = initial(mix, {100000}, {1.0}, 23);
    for (auto& v : sys.v) {  // each speed sqrt(3) (the same temperature, no tail)
      const double scale = std::sqrt(3.0 / (v.x * v.x + v.y * v.y + v.z * v.z));
      v = {v.x * scale, v.y * scale, v.z * scale};
    }
    auto c = std::make_unique<Collider>(Scheme::majorant, mix, sys, rng::make_stream(23, 0, rng::Purpose::collisions), 1.0);
    c->use_blocks(5000);
    c->use_threads(threads);
    Run out;
    while (c->counters().events < target) {
      c->advance(1e12, target, true, target, true);
      out.steps.push_back(c->state());
      if (restart && c->counters().steps == 1) c = restored_majorant_blocks(*c, mix, sys, 5000, threads);
    }
    EXPECT_EQ(c->counters().events, target);
    EXPECT_EQ(c->counters().overshoots, 0u);
    out.v.assign(sys.v.begin(), sys.v.end());
    return out;
  };
  const Run serial = run(1, false);
  ASSERT_GE(serial.steps.size(), 2u);
  const auto& first = serial.steps[0];
  const double first_candidates = static_cast<double>(first.counters.candidates - first.step_candidates_start);
  std::printf("[ measured ] first step begun at %.0f candidates, ran %.0f (%llu events); second begun at %.0f; %zu steps\n",
              first.step_planned_candidates, first_candidates, static_cast<unsigned long long>(first.counters.events),
              serial.steps[1].step_planned_candidates, serial.steps.size());
  EXPECT_NEAR(first.step_planned_candidates, short_candidates, 1e-6 * short_candidates);
  EXPECT_GT(first_candidates, 1.05 * short_candidates);  // the case: the bound rose within the first step
  EXPECT_GT(serial.steps[1].step_planned_candidates, 2.0 * short_candidates);
  for (const auto& [threads, restart] : {std::pair{2, false}, {1, true}}) {
    SCOPED_TRACE(std::to_string(threads) + " threads" + (restart ? ", restored after the first step" : ""));
    const Run other = run(threads, restart);
    EXPECT_EQ(other.v, serial.v);
    EXPECT_EQ(other.steps.size(), serial.steps.size());
  }
}

// A checkpoint's collider holds its blocks, whose count N, S and block_size fix: a record another rule wrote
// (20 blocks restored where the gas makes 10, as from a build whose separable block count differs) is refused as
// a mismatch (replica.cpp: "does not fit this build"), not read as damage nor run. Its step's planned candidates
// (collider/step_planned_candidates, approach_acceptance) must be a count: negative, NaN or infinite is refused
// as damage; absent (an older build's record) they are 0, the step then judged by its candidates alone.
TEST(Collide, ARecordOfOtherBlocksIsRefused) {
  const auto mix = one_species(0.9);
  auto sys = initial(mix, {100000}, {1.0}, 21);
  Collider c(Scheme::majorant, mix, sys, rng::make_stream(21, 0, rng::Purpose::collisions), 1.0);
  c.use_blocks(5000);
  c.advance(1e12, 50000, true, 50000, true);
  state::Record record;
  c.save(record);
  Collider other(Scheme::majorant, mix, sys, rng::make_stream(21, 0, rng::Purpose::collisions), 1.0);
  other.use_blocks(10000);
  ASSERT_EQ(other.blocks(), 10u);
  EXPECT_THROW(other.restore(record), state::StateMismatch);
  Collider same(Scheme::majorant, mix, sys, rng::make_stream(21, 0, rng::Purpose::collisions), 1.0);
  same.use_blocks(5000);
  EXPECT_NO_THROW(same.restore(record));
  ASSERT_GT(record.real("collider/step_planned_candidates"), 0.0);
  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    state::Record damaged = record;
    damaged.put("collider/step_planned_candidates", bad);
    Collider again(Scheme::majorant, mix, sys, rng::make_stream(21, 0, rng::Purpose::collisions), 1.0);
    again.use_blocks(5000);
    EXPECT_THROW(again.restore(damaged), std::invalid_argument) << bad;
  }
  state::Record older = record;
  older.reals.erase("collider/step_planned_candidates");
  Collider again(Scheme::majorant, mix, sys, rng::make_stream(21, 0, rng::Purpose::collisions), 1.0);
  again.use_blocks(5000);
  ASSERT_NO_THROW(again.restore(older));
  EXPECT_EQ(again.state().step_planned_candidates, 0.0);
}

// The probe of a long step (header "Event targets"; docs/schemes.md, "Event targets"): one species,
// alpha = 0.9 (steps of 5.6 collisions per particle), N = 1e5 in 20 blocks, to an exact target of 10
// collisions per particle. With the probe the step after a long one starts from the acceptance of the
// long one's first 5 mean free times, and a long step is shortened to fit: 8 steps (10 when the step after
// a long one takes acceptance 1 instead, tests/mutation 86). The target is met
// exactly, the same on 2 threads, and a collider restored (through a checkpoint's Record) after each of
// the first four steps, whose probes it must keep, continues bitwise as the uninterrupted one.
TEST(Collide, LongStepsProbeTheirAcceptance) {
  const auto mix = one_species(0.9);
  const std::uint64_t target = 500000;
  struct Run {
    std::vector<particles::Vec3> v;
    collide::Counters counters;
    double time;
  };
  // Step by step (advance's to_step_end), restored after step `restart` (0: never).
  auto run = [&](int threads, std::uint64_t restart) {
    auto sys = initial(mix, {100000}, {1.0}, 21);
    auto c = std::make_unique<Collider>(Scheme::majorant, mix, sys, rng::make_stream(21, 0, rng::Purpose::collisions), 1.0);
    c->use_blocks(5000);
    c->use_threads(threads);
    EXPECT_EQ(c->blocks(), 20u);
    while (c->counters().events < target) {
      c->advance(1e12, target, true, target, true);
      if (c->counters().steps == restart) c = restored_majorant_blocks(*c, mix, sys, 5000, threads);
    }
    return Run{{sys.v.begin(), sys.v.end()}, c->counters(), c->time()};
  };
  const Run serial = run(1, 0);
  std::printf("[ measured ] %llu steps to %llu events, t = %.6g\n", static_cast<unsigned long long>(serial.counters.steps),
              static_cast<unsigned long long>(serial.counters.events), serial.time);
  EXPECT_EQ(serial.counters.events, target);
  EXPECT_EQ(serial.counters.overshoots, 0u);
  EXPECT_LE(serial.counters.steps, 8u);
  for (const auto& [threads, restart] : {std::pair{2, 0}, {1, 1}, {1, 2}, {1, 3}, {2, 4}}) {
    SCOPED_TRACE(std::to_string(threads) + " threads, restored after step " + std::to_string(restart));
    const Run other = run(threads, static_cast<std::uint64_t>(restart));
    EXPECT_EQ(other.v, serial.v);
    EXPECT_EQ(other.counters.events, serial.counters.events);
    EXPECT_EQ(other.counters.candidates, serial.counters.candidates);
    EXPECT_EQ(other.counters.steps, serial.counters.steps);
    EXPECT_EQ(other.time, serial.time);
  }
}

// The probe when a step spans several passes (the simulation's chunks end passes at any time): chunks of
// 3.7 time units (about a twentieth of a long step), or ending exactly at the probe, or restored from a
// checkpoint while the probe is pending. The probe's counts lie between the step's counts at the start
// and the end of the pass that held it, equal the latter when the pass ends at the probe, and the target
// of 10 collisions per particle (N = 1e5, 20 blocks) is met exactly.
TEST(Collide, ProbeOverSeveralPasses) {
  const auto mix = one_species(0.9);
  const std::uint64_t target = 500000;
  for (int mode = 0; mode < 3; ++mode) {
    SCOPED_TRACE(mode == 0 ? "chunks" : mode == 1 ? "a chunk ends at the probe" : "restored while the probe is pending");
    auto sys = initial(mix, {100000}, {1.0}, 21);
    auto c = std::make_unique<Collider>(Scheme::majorant, mix, sys, rng::make_stream(21, 0, rng::Purpose::collisions), 1.0);
    c->use_blocks(5000);
    int measured = 0, restored = 0;
    while (c->counters().events < target) {
      const Collider::State before = c->state();
      const bool pending = before.probe == 1;
      const double t = mode == 1 && pending ? before.probe_time : c->time() + 3.7;
      c->advance(t, target, true, target, false);
      const Collider::State after = c->state();
      if (pending && after.probe == 2) {
        ++measured;
        ASSERT_EQ(after.step_events_start, before.step_events_start);
        EXPECT_GE(after.probe_events, before.counters.events - before.step_events_start);
        EXPECT_LE(after.probe_events, after.counters.events - after.step_events_start);
        EXPECT_GE(after.probe_candidates, before.counters.candidates - before.step_candidates_start);
        EXPECT_LE(after.probe_candidates, after.counters.candidates - after.step_candidates_start);
        if (mode == 1) {
          EXPECT_EQ(after.probe_events, after.counters.events - after.step_events_start);
        }
      }
      if (mode == 2 && after.probe == 1) {  // a checkpoint inside the step, its probe pending
        state::Record record;
        c->save(record);
        auto fresh = std::make_unique<Collider>(Scheme::majorant, mix, sys, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
        fresh->use_blocks(5000);
        fresh->restore(record);
        EXPECT_EQ(fresh->state().probe, 1);
        EXPECT_EQ(fresh->state().probe_time, after.probe_time);
        c = std::move(fresh);
        ++restored;
      }
    }
    std::printf("[ measured ] %d probes measured, %d restores, %llu steps\n", measured, restored,
                static_cast<unsigned long long>(c->counters().steps));
    EXPECT_GE(measured, 2);
    if (mode == 2) {
      EXPECT_GE(restored, 2);
    }
    EXPECT_EQ(c->counters().events, target);
  }
}

// Mixtures in blocks (header "Blocks": a slice of each species per block). Binary mixture (masses 1
// and 4, diameters 1 and 2, alpha 0.9/0.8/0.7), N = 12000 in 4 blocks, 16 replicas (8 under the sanitizers: sanitizer_scale.hpp), time-driven to
// about 8 collisions per particle and then collision-driven to an exact target: T_1, T_2, the pair
// events 1-2 and the time at the target agree with the unblocked collider within 4 combined standard
// errors, the target is met exactly and the species layout is unchanged (each particle keeps its
// species' range); for `majorant` and for `lowrank` (each block its own A_ik), dilute and, with
// `lowrank` (whose blocks use chi_ik itself, not chi_max), Enskog at packing fraction 0.2.
TEST(Collide, BlockedThreeSpeciesLowrankMatchesUnblocked) {
  // Three species: the block kernel's one-word draw then uses an alias table of 16 cells for the 9
  // pairs (7 of zero weight) and 12 coin bits (collide.cpp, set_block_lowrank). The share of each
  // species pair's events and each T_k, blocked against unblocked, over 16 replicas (8 under the sanitizers).
  species::PairMatrix alpha(3, 0.9);
  alpha(0, 2) = alpha(2, 0) = 0.7;
  const auto mix = species::make_mixture({1.0, 2.0, 4.0}, {1.0, 1.3, 1.6}, {0.006, 0.004, 0.003}, alpha, false);
  const std::vector<std::size_t> counts = {6000, 4000, 3000};
  const std::size_t replicas = gdsmc::test::replicas(16);  // 8 under the sanitizers
  std::vector<std::vector<double>> observed[2];
  for (int blocked = 0; blocked < 2; ++blocked) {
    observed[blocked].assign(9, {});
    for (std::size_t r = 0; r < replicas; ++r) {
      auto sys = initial(mix, counts, {1.0, 1.0, 1.0}, 300 + r);
      Collider c(Scheme::lowrank, mix, sys, rng::make_stream(300 + r, 0, rng::Purpose::collisions), 1.0);
      if (blocked) c.use_blocks(3000);
      follow_scheme(c, Scheme::lowrank);
      ASSERT_EQ(c.blocks(), blocked ? 4u : 1u);
      c.advance(60.0);
      EXPECT_EQ(c.counters().overshoots, 0u);
      double e[3] = {0.0, 0.0, 0.0};
      for (std::size_t i = 0; i < sys.size(); ++i) {
        const auto& v = sys.v[i];
        e[sys.species[i]] += mix.mass[sys.species[i]] * (v.x * v.x + v.y * v.y + v.z * v.z);
      }
      for (std::size_t k = 0; k < 3; ++k) observed[blocked][k].push_back(e[k] / (3.0 * static_cast<double>(counts[k])));
      const auto events = static_cast<double>(c.counters().events);
      std::size_t q = 3;
      for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t j = k; j < 3; ++j)
          observed[blocked][q++].push_back(static_cast<double>(c.counters().pair_events[k * 3 + j]) / events);
    }
  }
  const char* names[] = {"T1", "T2", "T3", "share 1-1", "share 1-2", "share 1-3", "share 2-2", "share 2-3", "share 3-3"};
  for (std::size_t q = 0; q < 9; ++q) {
    const auto [m0, s0] = mean_se(observed[0][q]);
    const auto [m1, s1] = mean_se(observed[1][q]);
    std::printf("[ Blocks.Three ] lowrank %s: unblocked %.6g +- %.2g, blocked %.6g +- %.2g (%.2f SE)\n", names[q], m0,
                s0, m1, s1, (m1 - m0) / std::hypot(s0, s1));
    EXPECT_LT(std::abs(m1 - m0), 4.0 * std::hypot(s0, s1)) << names[q];
  }
}

TEST(Collide, BlockedMixtureMatchesUnblocked) {
  const auto dilute = binary(0.9, 0.8, 0.7);
  species::PairMatrix alpha(2, 0.9);
  alpha(0, 1) = alpha(1, 0) = 0.8;
  alpha(1, 1) = 0.7;
  // pi/6 (0.1 + 0.05 x 8) = 0.26: chi_11, chi_12, chi_22 well apart
  const auto dense = species::make_mixture({1.0, 4.0}, {1.0, 2.0}, {0.1, 0.05}, alpha, true);
  const std::size_t replicas = gdsmc::test::replicas(16);  // 8 under the sanitizers
  // Path 3: viscoelastic restitution, whose blocks run the general lowrank loop (not the mixture kernel):
  // its per-pair bounds with chi_ik (mutant 21).
  const species::PairMatrix beta(2, 0.2);
  for (int path = 0; path < 4; ++path) {
  const Scheme scheme = path == 0 ? Scheme::majorant : Scheme::lowrank;
  const auto& mix = path >= 2 ? dense : dilute;
  const double t_mid = path >= 2 ? 6.0 : 60.0;
  SCOPED_TRACE(path == 3 ? "lowrank, Enskog, viscoelastic" : path == 2 ? "lowrank, Enskog" : name(scheme));
  BinaryRuns runs[2];
  for (int blocked = 0; blocked < 2; ++blocked)
    for (std::size_t r = 0; r < replicas; ++r) {
      auto sys = initial(mix, {8000, 4000}, {1.0, 1.0}, 200 + r);
      const auto species_before = sys.species;
      Collider c(scheme, mix, sys, rng::make_stream(200 + r, 0, rng::Purpose::collisions), 1.0,
                 path == 3 ? &beta : nullptr);
      if (blocked) c.use_blocks(3000);
      follow_scheme(c, scheme);
      ASSERT_EQ(c.blocks(), blocked ? 4u : 1u);
      c.advance(t_mid);
      c.advance(1e12, c.counters().events + 20000);
      EXPECT_EQ(sys.species, species_before);
      EXPECT_EQ(c.counters().overshoots, 0u);
      runs[blocked].add(sys, mix, c);
    }
  expect_binary_runs_agree(runs, std::string("[ Blocks.Mixture ] ") + name(scheme) +
                                     (path == 3 ? " Enskog viscoelastic" : path == 2 ? " Enskog" : ""));
  }
}

// The blocks of a mixture run the cheaper of their two exact samplers, whatever the scheme (collide.hpp,
// "Mixtures in blocks", "The cheaper sampler"; docs/schemes.md). (a) The two candidate rates against
// numbers computed by hand. (b) The choice: `lowrank` for diameters 1 and 2 and for 20 species (the
// Fig 8 law), `majorant` for diameters 1 and 1.5 at equal densities, none for one species, the same for
// either scheme; a forced sampler is taken at the next step, and the blocks run it: the candidates per
// event of three steps with it over three with the chosen one are the ratio of the two rates (measured
// within 1-4 %; 1 if the blocks ignored the choice, against 0.76-1.88 here). (c) Samplers forced in turn, changed 8 times in a run, sample the
// unblocked process: T_1, T_2, the share of 1-2 events and the time at an event target over 16 replicas
// (8 under the sanitizers) within 4 combined SE, the event target met exactly. (d) A checkpoint taken
// inside a step continues bitwise with the sampler saved; one without it (an older checkpoint) ends the
// step with the scheme's sampler and chooses at the next.
TEST(Collide, BlocksRunTheCheaperSampler) {
  using Sampler = Collider::BlockSampler;
  const auto mix = binary(0.9, 0.8, 0.7);  // masses 1, 4; diameters 1, 2; n = 0.01, 0.005
  {  // (a) N = 8000 + 4000, n = 0.015, vmax = 3 and 1.5; pi sigma_kj^2 = pi, 2.25 pi, 4 pi
    auto sys = initial(mix, {8000, 4000}, {1.0, 1.0}, 1);
    Collider c(Scheme::majorant, mix, sys, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
    c.use_blocks(3000);
    c.set_max_speeds({9.0, 2.25});
    // B = max(pi (3 + 3), 2.25 pi (3 + 1.5), 4 pi (1.5 + 1.5)) = 12 pi; N n B/2 = 12000 0.015 6 pi = 1080 pi
    EXPECT_NEAR(c.block_candidate_rate(false), 1080.0 * kPi, 1e-9);
    // pi n/(N - 1) (3 8000^2 + 2.25 3 8000 4000 + 2.25 1.5 4000 8000 + 4 1.5 4000^2) = 6.12e8 pi 0.015/11999
    EXPECT_NEAR(c.block_candidate_rate(true), 6.12e8 * kPi * 0.015 / 11999.0, 1e-9);
  }
  {  // (b)
    const auto near = near_binary();
    const auto [many, counts] = fig8_gas();
    const std::vector<double> temperature(20, 1.0);
    struct Case {
      const species::Mixture* mix;
      std::vector<std::size_t> counts;
      std::vector<double> temperature;
      bool lowrank;
    };
    const Case cases[] = {{&mix, {8000, 4000}, {1.0, 1.0}, true},
                          {&near, {6000, 6000}, {1.0, 1.0}, false},
                          {&many, counts, temperature, true},
                          {nullptr, {12000}, {1.0}, false}};
    const auto one = one_species(0.9);
    for (const Case& k : cases) {
      const species::Mixture& m = k.mix ? *k.mix : one;
      for (Scheme scheme : {Scheme::majorant, Scheme::lowrank}) {
        SCOPED_TRACE(std::string(name(scheme)) + ", " + std::to_string(m.size()) + " species");
        auto sys = initial(m, k.counts, k.temperature, 2);
        Collider c(scheme, m, sys, rng::make_stream(2, 0, rng::Purpose::collisions), 1.0);
        c.use_blocks(3000);
        c.advance(5.0);
        c.advance(1e12, UINT64_MAX, true, UINT64_MAX, true);  // to the end of the step
        EXPECT_EQ(c.block_lowrank(), k.lowrank);
        if (m.size() == 1) continue;
        const double lowrank_rate = c.block_candidate_rate(true), majorant_rate = c.block_candidate_rate(false);
        // Three steps with the chosen sampler, then three with the other one forced: the blocks run it,
        // so that the candidates per event change by the ratio of the two rates, taken at the first
        // segment's bounds. Allowance 15 %: within a step a block's bounds loosen by about gamma c / 4 of
        // the cooling (docs/schemes.md "Step length": 12 % at alpha = 0.8, gamma = 0.12, c = sqrt(2/gamma) = 4.1),
        // and the two samplers' bounds (vmax_k per species against the pair maximum) need not loosen
        // alike. Blocks that ignored the choice would give 1 against 0.76-1.88 here.
        const auto per_event = [&c](const collide::Counters from) {  // (a copy: counters() changes)
          for (int step = 0; step < 3; ++step) c.advance(1e12, UINT64_MAX, true, UINT64_MAX, true);
          return static_cast<double>(c.counters().candidates - from.candidates) /
                 static_cast<double>(c.counters().events - from.events);
        };
        const double chosen = per_event(c.counters());
        c.set_block_sampler(k.lowrank ? Sampler::majorant : Sampler::lowrank);
        const double other = per_event(c.counters());
        EXPECT_EQ(c.block_lowrank(), !k.lowrank);
        const double predicted = k.lowrank ? majorant_rate / lowrank_rate : lowrank_rate / majorant_rate;
        std::printf("[ Blocks.Samplers ] %zu species, %s: candidates per event %.3f chosen, %.3f other (%.3f predicted)\n",
                    m.size(), name(scheme), chosen, other, chosen * predicted);
        EXPECT_NEAR(other / chosen, predicted, 0.15 * predicted);
      }
    }
  }
  {  // (c)
    const std::size_t replicas = gdsmc::test::replicas(16);  // 8 under the sanitizers
    BinaryRuns runs[2];
    for (int blocked = 0; blocked < 2; ++blocked)
      for (std::size_t r = 0; r < replicas; ++r) {
        auto sys = initial(mix, {8000, 4000}, {1.0, 1.0}, 600 + r);
        // (steps of a quarter of the usual length, so that 8 of them end before t = 60)
        Collider c(Scheme::majorant, mix, sys, rng::make_stream(600 + r, 0, rng::Purpose::collisions), 0.25);
        if (blocked) c.use_blocks(3000);
        int changes = 0;
        bool last = false;
        for (int piece = 1; piece <= 8; ++piece) {  // one step each (unblocked: to t = 60 in 8 pieces)
          c.set_block_sampler(piece % 2 ? Sampler::lowrank : Sampler::majorant);
          c.advance(blocked ? 1e12 : 7.5 * piece, UINT64_MAX, true, UINT64_MAX, true);
          changes += c.block_lowrank() != last;
          last = c.block_lowrank();
        }
        EXPECT_EQ(changes, blocked ? 8 : 0);
        if (blocked) {
          EXPECT_LT(c.time(), 60.0);  // (about 40)
        }
        c.advance(60.0);
        // (a change of sampler at the target's approach: that step takes acceptance 1, a bound)
        c.set_block_sampler(Sampler::lowrank);
        const std::uint64_t target = c.counters().events + 20000;
        c.advance(1e12, target);
        EXPECT_EQ(c.counters().events, target);
        EXPECT_EQ(c.counters().overshoots, 0u);
        runs[blocked].add(sys, mix, c);
      }
    expect_binary_runs_agree(runs, "[ Blocks.Samplers ] samplers in turn,");
  }
  {  // (d)
    auto sys_a = initial(mix, {8000, 4000}, {1.0, 1.0}, 7);
    Collider a(Scheme::majorant, mix, sys_a, rng::make_stream(7, 0, rng::Purpose::collisions), 1.0);
    a.use_blocks(3000);
    a.advance(20.0);
    a.advance(20.0 + 0.4 * a.mean_step());  // inside a step
    ASSERT_TRUE(a.block_lowrank());  // (so that a restore that took `majorant` would differ)
    const Collider::State saved = a.state();
    Collider::State older = saved;
    older.block_lowrank = -1;
    auto sys_b = sys_a, sys_c = sys_a;
    Collider b(Scheme::majorant, mix, sys_b, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
    Collider c(Scheme::majorant, mix, sys_c, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
    b.use_blocks(3000);
    c.use_blocks(3000);
    b.restore(saved);
    c.restore(older);
    a.advance(40.0);
    b.advance(40.0);
    EXPECT_EQ(sys_b.v, sys_a.v);
    EXPECT_EQ(b.counters().events, a.counters().events);
    // An older checkpoint: the rest of its step with the scheme's sampler (which the code that wrote
    // it ran), then chosen again.
    EXPECT_FALSE(c.block_lowrank());
    c.advance(1e12, UINT64_MAX, true, UINT64_MAX, true);
    EXPECT_FALSE(c.block_lowrank());
    c.advance(1e12, UINT64_MAX, true, UINT64_MAX, true);
    EXPECT_TRUE(c.block_lowrank());
  }
}

// Exact event targets one after another with the cheaper sampler unforced, where it differs from the
// scheme (collide.hpp "Mixtures in blocks", "The cheaper sampler"): `majorant` runs whose blocks take
// `lowrank` (diameters 1 and 2; 20 species of the Fig 8 law, 13 of them scattered) and `lowrank` runs whose
// blocks take `majorant` (diameters 1 and 1.5), on 2 threads and with displacements tracked. The
// whole-gas steps before each target run the scheme's own sampler, so that the step after one has its
// acceptance from the other majorant (its events are judged from the events per unit time then): every
// target met exactly, no overshoot.
TEST(Collide, CheaperSamplerMeetsEventTargetsExactly) {
  const auto wide = binary(0.9, 0.8, 0.7);  // diameters 1 and 2
  const auto near = near_binary();
  const auto [many, counts] = fig8_gas();
  struct Case {
    const species::Mixture* mix;
    Scheme scheme;
    std::vector<std::size_t> counts;
    bool lowrank;  // the blocks' sampler
  };
  const Case cases[] = {{&wide, Scheme::majorant, {8000, 4000}, true},
                        {&many, Scheme::majorant, counts, true},
                        {&near, Scheme::lowrank, {6000, 6000}, false}};
  for (const Case& k : cases) {
    SCOPED_TRACE(std::string(name(k.scheme)) + ", " + std::to_string(k.mix->size()) + " species");
    auto sys = initial(*k.mix, k.counts, std::vector<double>(k.mix->size(), 1.0), 11);
    particles::start_tracking(sys, 0.0);
    Collider c(k.scheme, *k.mix, sys, rng::make_stream(11, 0, rng::Purpose::collisions), 1.0);
    c.use_blocks(3000);
    c.use_threads(2);
    for (std::uint64_t target : {3000, 6000, 9000, 15000, 24000, 30000, 45000, 60000, 66000, 90000}) {
      EXPECT_TRUE(c.advance(1e12, target));
      ASSERT_EQ(c.counters().events, target);
      EXPECT_EQ(c.block_lowrank(), k.lowrank);
    }
    EXPECT_EQ(c.counters().overshoots, 0u);
  }
}

// A species with fewer than 64 K particles is scattered (collide.hpp, "Mixtures in blocks"): each
// particle to a uniformly random block at every remix, so that every pair, rare-rare ones of one
// species included, shares a block with probability 1/K. (a) Blocked runs with a scattered species
// (N = 12000 + 200, K = 4; the rare species large, sigma 6, so that its own pairs are 0.5 % of the
// events) agree with unblocked ones, `majorant` and `lowrank`, 16 replicas each (8 under the sanitizers): T_1, T_2, the shares
// of 1-2 and 2-2 events and the time at an event target within 4 combined SE. (b) Bitwise the same on
// 1, 2 and 3 threads, with displacements, and after a restore in the middle of a step. (c) Nothing is
// lost in the shuffles: an elastic run keeps energy and momentum. A species with 3 particles (fewer
// than K) is blocked too.
TEST(Collide, ScatteredRareSpeciesMatchUnblocked) {
  species::PairMatrix alpha(2, 0.8);
  const auto mix = species::make_mixture({1.0, 4.0}, {1.0, 6.0}, {0.01, 0.01 * 200.0 / 12000.0}, alpha, false);
  const std::size_t replicas = gdsmc::test::replicas(16);  // 8 under the sanitizers
  for (Scheme scheme : {Scheme::majorant, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    std::vector<std::vector<double>> t1(2), t2(2), cross(2), rare(2), time(2);
    for (int blocked = 0; blocked < 2; ++blocked)
      for (std::size_t r = 0; r < replicas; ++r) {
        auto sys = initial(mix, {12000, 200}, {1.0, 1.0}, 300 + r);
        Collider c(scheme, mix, sys, rng::make_stream(300 + r, 0, rng::Purpose::collisions), 1.0);
        if (blocked) c.use_blocks(3000);
        follow_scheme(c, scheme);
        ASSERT_EQ(c.blocks(), blocked ? 4u : 1u);
        c.advance(20.0);
        c.advance(1e12, c.counters().events + 20000);
        double e[2] = {0.0, 0.0};
        for (std::size_t i = 0; i < sys.size(); ++i) {
          const auto& v = sys.v[i];
          e[sys.species[i]] += mix.mass[sys.species[i]] * (v.x * v.x + v.y * v.y + v.z * v.z);
        }
        EXPECT_EQ(c.counters().overshoots, 0u);
        t1[blocked].push_back(e[0] / (3.0 * 12000.0));
        t2[blocked].push_back(e[1] / (3.0 * 200.0));
        const auto events = static_cast<double>(c.counters().events);
        cross[blocked].push_back(static_cast<double>(c.counters().pair_events[1]) / events);
        rare[blocked].push_back(static_cast<double>(c.counters().pair_events[3]) / events);
        time[blocked].push_back(c.time());
      }
    const char* names[] = {"T1", "T2", "share of 1-2 events", "share of 2-2 events", "time at the target"};
    int q = 0;
    for (auto* x : {&t1, &t2, &cross, &rare, &time}) {
      const auto [m0, s0] = mean_se((*x)[0]);
      const auto [m1, s1] = mean_se((*x)[1]);
      std::printf("[ Blocks.Scattered ] %s %s: unblocked %.6g +- %.2g, blocked %.6g +- %.2g (%.2f SE)\n", name(scheme),
                  names[q++], m0, s0, m1, s1, (m1 - m0) / std::hypot(s0, s1));
      EXPECT_LT(std::abs(m1 - m0), 4.0 * std::hypot(s0, s1));
    }
  }
  // (b) threads and restore, with displacements; 3 particles of the rare species (fewer than K).
  for (Scheme scheme : {Scheme::majorant, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    auto run = [&](int threads, bool restore) {
      auto sys = initial(mix, {5997, 3}, {1.0, 1.0}, 21);
      particles::start_tracking(sys, 0.0);
      Collider c(scheme, mix, sys, rng::make_stream(21, 0, rng::Purpose::collisions), 1.0);
      c.use_blocks(1000);
      follow_scheme(c, scheme);
      c.use_threads(threads);
      EXPECT_EQ(c.blocks(), 6u);
      c.advance(40.0);
      c.advance(40.0 + 0.4 * c.mean_step());  // ends inside a step
      auto sys_b = sys;
      Collider b(scheme, mix, sys_b, rng::make_stream(99, 0, rng::Purpose::collisions), 1.0);
      b.use_blocks(1000);
      follow_scheme(b, scheme);
      b.use_threads(threads == 1 ? 2 : 1);
      if (restore) b.restore(c.state());
      Collider& go = restore ? b : c;
      particles::System& out = restore ? sys_b : sys;
      go.advance(120.0);
      std::vector<double> flat;
      for (const auto& v : out.v) flat.insert(flat.end(), {v.x, v.y, v.z});
      for (const auto& d : out.r) flat.insert(flat.end(), {d.x, d.y, d.z, d.t_last});
      flat.push_back(static_cast<double>(go.counters().events));
      flat.push_back(static_cast<double>(go.counters().pair_events[3] + 7 * go.counters().pair_events[1]));
      flat.push_back(go.counters().dissipated);
      return flat;
    };
    const auto serial = run(1, false);
    EXPECT_EQ(run(2, false), serial);
    EXPECT_EQ(run(3, false), serial);
    EXPECT_EQ(run(1, true), serial);
    EXPECT_EQ(run(2, true), serial);
  }
  // (d) A species of 5 particles in K = 6 blocks, so large (sigma 100, mass 1) that its own pairs make
  // 0.1 % of the events: dealt, its particles would never share a block; scattered without the
  // shuffle, the same ones would share it too often. The count of its own events over 24 replicas of
  // 12000 events agrees with the unblocked collider within 4 combined Poisson SE.
  {
    const auto huge = species::make_mixture({1.0, 1.0}, {1.0, 100.0}, {0.01, 0.01 * 5.0 / 5995.0}, alpha, false);
    std::uint64_t rare_events[2] = {0, 0};
    for (int blocked = 0; blocked < 2; ++blocked)
      for (std::size_t r = 0; r < 24; ++r) {
        auto sys = initial(huge, {5995, 5}, {1.0, 1.0}, 500 + r);
        Collider c(Scheme::lowrank, huge, sys, rng::make_stream(500 + r, 0, rng::Purpose::collisions), 1.0);
        if (blocked) c.use_blocks(1000);
        follow_scheme(c, Scheme::lowrank);
        ASSERT_EQ(c.blocks(), blocked ? 6u : 1u);
        c.advance(1e12, 12000);
        rare_events[blocked] += c.counters().pair_events[3];
      }
    const auto e0 = static_cast<double>(rare_events[0]), e1 = static_cast<double>(rare_events[1]);
    std::printf("[ Blocks.Scattered ] 5 particles of sigma 100, their own events: unblocked %g, blocked %g (%.2f SE)\n",
                e0, e1, (e1 - e0) / std::sqrt(e0 + e1));
    EXPECT_GT(e0, 100.0);
    EXPECT_LT(std::abs(e1 - e0), 4.0 * std::sqrt(e0 + e1));
  }
  // (c) an elastic run with a scattered species keeps energy and momentum through the remixes.
  const auto elastic = species::make_mixture({1.0, 4.0}, {1.0, 6.0}, {0.01, 0.0005}, species::PairMatrix(2, 1.0), false);
  auto sys = initial(elastic, {3950, 50}, {1.0, 1.0}, 22);
  auto totals = [&] {
    std::vector<double> t(4, 0.0);
    for (std::size_t i = 0; i < sys.size(); ++i) {
      const auto& v = sys.v[i];
      const double m = elastic.mass[sys.species[i]];
      t[0] += m * (v.x * v.x + v.y * v.y + v.z * v.z);
      t[1] += m * v.x;
      t[2] += m * v.y;
      t[3] += m * v.z;
    }
    return t;
  };
  const auto before = totals();
  Collider c(Scheme::lowrank, elastic, sys, rng::make_stream(22, 0, rng::Purpose::collisions), 1.0);
  c.use_blocks(1000);
  follow_scheme(c, Scheme::lowrank);
  EXPECT_EQ(c.blocks(), 4u);
  c.advance(300.0);
  EXPECT_GT(c.counters().steps, 3u);
  EXPECT_GT(c.counters().pair_events[1], 0u);
  const auto after = totals();
  EXPECT_NEAR(after[0], before[0], 1e-10 * before[0]);
  for (int k = 1; k < 4; ++k) EXPECT_NEAR(after[k], before[k], 1e-9);
}

namespace {
// The temperatures m <v^2>/3 of species 1, of species 2-10 and of the rest (the many-species tests).
std::array<double, 3> group_temperatures(const species::Mixture& mix, const particles::System& sys) {
  double e[3] = {0.0, 0.0, 0.0}, n[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < sys.size(); ++i) {
    const auto& v = sys.v[i];
    const std::uint32_t k = sys.species[i];
    const int group = k == 0 ? 0 : k < 10 ? 1 : 2;
    e[group] += mix.mass[k] * (v.x * v.x + v.y * v.y + v.z * v.z);
    n[group] += 3.0;
  }
  return {e[0] / n[0], e[1] / n[1], e[2] / n[2]};
}
}  // namespace

// A call whose event target is already met returns at once, also inside a whole-gas step near the target
// (collide.hpp "Blocks", "Event targets"): two samples' targets can be equal (logarithmic spacing, small N).
// 30 targets 400-548 events apart in a gas of 4096 particles in 4 blocks (the last 64 or fewer events of
// each on the whole gas, whose step outlasts its target), each asked for twice.
namespace {
/// One species (alpha = 0.9, T = 1) of `n` particles with `majorant` in blocks of `block_size`, seeded `seed`.
struct BlockedOneSpecies {
  BlockedOneSpecies(std::size_t n, std::size_t block_size, std::uint64_t seed)
      : mix(one_species(0.9)), sys(initial(mix, {n}, {1.0}, seed)),
        collider(Scheme::majorant, mix, sys, rng::make_stream(seed, 0, rng::Purpose::collisions), 1.0) {
    collider.use_blocks(block_size);
  }
  species::Mixture mix;
  particles::System sys;
  Collider collider;
};
}  // namespace

TEST(Collide, BlocksMeetARepeatedEventTargetWithoutAnotherEvent) {
  BlockedOneSpecies gas(4096, 1024, 31);
  Collider& c = gas.collider;
  ASSERT_EQ(c.blocks(), 4u);
  std::uint64_t target = 0;
  for (std::uint64_t i = 0; i < 30; ++i) {
    target += 400 + 37 * (i % 5);
    for (int again = 0; again < 2; ++again) {
      EXPECT_TRUE(c.advance(1e12, target));
      EXPECT_EQ(c.counters().events, target) << "target " << i << (again ? ", asked again" : "");
    }
  }
}

// Samples closer than a step make every step a shortened one, which keeps the blocks of the step before:
// the blocks must still be dealt again, at the latest when a kept step would end beyond two full steps'
// time of the last remix (collide.hpp "Event targets"); else each block would become a gas of its own.
// 65536 particles in 4 blocks, targets 3000 events apart (more than N/64 = 1024, so that blocked steps
// approach them; a full step brings about 5 collisions per particle, 160000 events), 600 targets, about
// 27 collisions per particle: the blocks were dealt again at least 4 times (without the limit: never after t = 0).
TEST(Collide, ShortenedStepsStillRemixTheBlocks) {
  BlockedOneSpecies gas(65536, 16384, 37);
  Collider& c = gas.collider;
  ASSERT_EQ(c.blocks(), 4u);
  std::vector<double> remix_times;
  for (std::uint64_t target = 3000; target <= 1800000; target += 3000) {
    ASSERT_TRUE(c.advance(1e12, target));
    ASSERT_EQ(c.counters().events, target);
    if (remix_times.empty() || c.last_remix_time() != remix_times.back()) remix_times.push_back(c.last_remix_time());
  }
  std::printf("[ measured ] %zu distinct remix times over %llu steps, t = %.4g\n", remix_times.size(),
              static_cast<unsigned long long>(c.counters().steps), c.time());
  EXPECT_GE(remix_times.size(), 4u);
}

namespace {

// The many-species gases of the block tests: S species, m_k = k, sigma_k = k^(1/3), N_k = max(least,
// round(scale k^-1.5)), alpha = 0.8, total density 0.01, all at T = 1.
struct PowerLawGas {
  species::Mixture mix;
  std::vector<std::size_t> counts;
  std::size_t total = 0;
};

PowerLawGas power_law_gas(std::size_t s, double scale, std::size_t least) {
  std::vector<double> mass(s), diameter(s), density(s);
  PowerLawGas gas;
  gas.counts.resize(s);
  for (std::size_t k = 0; k < s; ++k) {
    const double kk = static_cast<double>(k + 1);
    mass[k] = kk;
    diameter[k] = std::cbrt(kk);
    gas.counts[k] = std::max(least, static_cast<std::size_t>(std::llround(scale * std::pow(kk, -1.5))));
    gas.total += gas.counts[k];
  }
  for (std::size_t k = 0; k < s; ++k)
    density[k] = 0.01 * static_cast<double>(gas.counts[k]) / static_cast<double>(gas.total);
  gas.mix = species::make_mixture(mass, diameter, density, species::PairMatrix(s, 0.8), false);
  return gas;
}

// Blocked (blocks of `block_size`, expected `blocks` of them) against unblocked, 16 replicas each (8 under
// the sanitizers) from seeds seed + r: T_1, the temperature of species 2-10 and of 11-S together and the time
// at an event target 12000 events on from t = 15 (5 under the sanitizers) agree within 4 combined SE
// (printed); the target is met exactly and the blocked runs make no acceptance overshoot.
void expect_blocks_match_unblocked(const PowerLawGas& gas, Scheme scheme, std::size_t block_size, std::size_t blocks,
                                   std::uint64_t seed, const char* label) {
  const std::size_t s = gas.counts.size();
  const std::vector<double> temperature(s, 1.0);
  const std::size_t replicas = gdsmc::test::replicas(16);
  std::vector<std::vector<double>> observed[2];
  for (int blocked = 0; blocked < 2; ++blocked) {
    observed[blocked].assign(4, {});
    for (std::size_t r = 0; r < replicas; ++r) {
      auto sys = initial(gas.mix, gas.counts, temperature, seed + r);
      Collider c(scheme, gas.mix, sys, rng::make_stream(seed + r, 0, rng::Purpose::collisions), 1.0);
      if (blocked) c.use_blocks(block_size);
      follow_scheme(c, scheme);
      ASSERT_EQ(c.blocks(), blocked ? blocks : 1u);
      c.advance(gdsmc::test::sanitized ? 5.0 : 15.0);
      const std::uint64_t target = c.counters().events + 12000;
      c.advance(1e12, target);
      // met exactly (collide.hpp "Blocks", "Event targets")
      EXPECT_EQ(c.counters().events, target) << "blocked " << blocked << ", replica " << r;
      EXPECT_EQ(c.counters().overshoots, 0u);
      const auto t = group_temperatures(gas.mix, sys);
      for (int g = 0; g < 3; ++g) observed[blocked][g].push_back(t[g]);
      observed[blocked][3].push_back(c.time());
    }
  }
  const std::string names[] = {"T_1", "T of species 2-10", "T of species 11-" + std::to_string(s), "time at the target"};
  for (int q = 0; q < 4; ++q) {
    const auto [m0, s0] = mean_se(observed[0][q]);
    const auto [m1, s1] = mean_se(observed[1][q]);
    std::printf("[ %s ] %s %s: unblocked %.6g +- %.2g, blocked %.6g +- %.2g (%.2f SE)\n", label, name(scheme),
                names[q].c_str(), m0, s0, m1, s1, (m1 - m0) / std::hypot(s0, s1));
    EXPECT_LT(std::abs(m1 - m0), 4.0 * std::hypot(s0, s1));
  }
}

// The velocities and the time after 5 collisions per particle of `gas` in blocks of `block_size` on
// `threads` threads (seed 777), the separable draw in three stages beyond `deep_above` present species.
std::vector<double> blocked_run(const PowerLawGas& gas, std::size_t block_size, int threads,
                                std::size_t deep_above = Collider::separable_deep_above) {
  auto sys = initial(gas.mix, gas.counts, std::vector<double>(gas.counts.size(), 1.0), 777);
  Collider c(Scheme::lowrank, gas.mix, sys, rng::make_stream(777, 0, rng::Purpose::collisions), 1.0);
  c.use_blocks(block_size);
  c.set_separable_deep_above(deep_above);
  c.use_threads(threads);
  c.advance(1e12, 5 * gas.total);
  std::vector<double> flat;
  for (const auto& v : sys.v) flat.insert(flat.end(), {v.x, v.y, v.z});
  flat.push_back(c.time());
  return flat;
}

}  // namespace

// Blocks for more than pair_event_limit species (up to block_species_limit; collide.hpp, "Mixtures in
// blocks"): 200 species, N_k = round(7000 k^-1.5) (N = 17301, N_200 = 2), blocks of 3000 (K = 5: species 1-7
// dealt, 193 scattered, most blocks missing some of them, so that the alias table covers the species present
// only), `majorant` and `lowrank` (expect_blocks_match_unblocked).
TEST(Collide, ManySpeciesBlocksMatchUnblocked) {
  const PowerLawGas gas = power_law_gas(200, 7000.0, 0);
  for (Scheme scheme : {Scheme::majorant, Scheme::lowrank})
    expect_blocks_match_unblocked(gas, scheme, 3000, gas.total / 3000, 400, "Blocks.ManySpecies");
}

// Blocks beyond block_species_limit (collide.hpp, "Mixtures in blocks": `lowrank`, the separable draw):
// 300 species, N_k = max(2, round(9000 k^-1.5)) (N = 22473), blocks of 3000 (K = 7: species 1-7 dealt, 293
// scattered; expect_blocks_match_unblocked); 2 threads give the same velocities bit for bit as one.
TEST(Collide, SeparableBlocksBeyondTheSpeciesLimitMatchUnblocked) {
  const PowerLawGas gas = power_law_gas(300, 9000.0, 2);
  ASSERT_GT(gas.counts.size(), collide::block_species_limit);
  expect_blocks_match_unblocked(gas, Scheme::lowrank, 3000, gas.total / 3000, 700, "Blocks.Separable300");
  EXPECT_EQ(blocked_run(gas, 3000, 1), blocked_run(gas, 3000, 2));
  // in three stages (as beyond separable_deep_above present species): another stream, the same on 2 threads
  const std::vector<double> deep = blocked_run(gas, 3000, 1, 0);
  EXPECT_EQ(deep, blocked_run(gas, 3000, 2, 0));
  EXPECT_NE(deep, blocked_run(gas, 3000, 1));
}

// The set-up of the blocks looks at the interrupt (particles::SetUpCheck) every 1024 species: 3000 species
// (N = 29,000 in 9 blocks) call it at species 0, 1024 and 2048; the run is the same as without the check,
// and a check that throws abandons the set-up.
TEST(Collide, BlocksSetUpLooksAtTheInterrupt) {
  const PowerLawGas gas = power_law_gas(3000, 9000.0, 2);
  const auto run = [&gas](const particles::SetUpCheck& check) {
    auto sys = initial(gas.mix, gas.counts, std::vector<double>(gas.counts.size(), 1.0), 778);
    Collider c(Scheme::lowrank, gas.mix, sys, rng::make_stream(778, 0, rng::Purpose::collisions), 1.0);
    c.use_blocks(200, check);
    EXPECT_EQ(c.blocks(), 9u);
    c.advance(1e12, gas.total);
    return sys.v;
  };
  int calls = 0;
  const auto checked = run([&calls] { ++calls; });
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(checked, run({}));
  auto sys = initial(gas.mix, gas.counts, std::vector<double>(gas.counts.size(), 1.0), 778);
  Collider c(Scheme::lowrank, gas.mix, sys, rng::make_stream(778, 0, rng::Purpose::collisions), 1.0);
  EXPECT_THROW(c.use_blocks(200, [] { throw std::runtime_error("interrupted"); }), std::runtime_error);
}

// The separable draw's larger blocks (Collider::separable_block_count): blocks of 200 would each rebuild six
// tables of about S = 300 cells per visit for 200 particles (and hold S K = 33600 > N table entries), so
// the 300-species gas above runs in 16 blocks of about 1400 instead (N div (8 S) = 9, at least 16), with the
// unblocked process (expect_blocks_match_unblocked) and bit for bit on any thread count. K = N div S where
// 16 blocks would hold S K > N; beyond separable_species_limit species the blocks hold at
// most separable_block_limit particles on average, while S K <= 2 N.
TEST(Collide, SeparableBlocksGrowWhenTheTablesWouldOutgrowTheGas) {
  const PowerLawGas gas = power_law_gas(300, 9000.0, 2);
  ASSERT_GT(300 * (gas.total / 200), gas.total);
  expect_blocks_match_unblocked(gas, Scheme::lowrank, 200, 16, 900, "Blocks.SeparableLarger");
  EXPECT_EQ(blocked_run(gas, 200, 1), blocked_run(gas, 200, 2));
  EXPECT_EQ(Collider::separable_block_count(1000, 1000000, 32768), 30u);     // S K <= N: N div block_size
  EXPECT_EQ(Collider::separable_block_count(100000, 1000000, 32768), 16u);   // ceil(1e6 / 62500)
  EXPECT_EQ(Collider::separable_block_count(50000, 1000000, 32768), 16u);    // N div 8 S = 2: at least 16
  EXPECT_EQ(Collider::separable_block_count(10000, 1000000, 32768), 16u);    // N div 8 S = 12: at least 16
  EXPECT_EQ(Collider::separable_block_count(5000, 1000000, 32768), 25u);     // N div 8 S
  EXPECT_EQ(Collider::separable_block_count(4000, 1000000, 32768), 30u);     // N div block_size < N div 8 S
  EXPECT_EQ(Collider::separable_block_count(60000, 200000, 32768), 3u);      // 6 blocks: S K > N, N div S
  EXPECT_EQ(Collider::separable_block_count(100000, 1100000, 32768), 18u);   // ceil(1.1e6 / 62500)
  EXPECT_EQ(Collider::separable_block_count(100000, 10000000, 32768), 160u); // ceil(1e7 / 62500), S K <= 2 N
  EXPECT_EQ(Collider::separable_block_count(200000, 1000000, 32768), 0u);    // S K = 3.4 N: none
  EXPECT_LT(Collider::separable_block_count(60000, 100000, 64), 2u);         // N div S = 1: none
}

// The separable draw reads a block's exact bounds at its first visit in the same pass that gathers its
// species (set_block_separable): the 300-species gas above in 16 blocks, at 1e-3 time units into each of four
// steps (its remix done, each block visited once, few collisions yet) every particle's speed^2 is within its
// block's bound for its species (exact at the first visit, then raised by every collision), read through the
// checkpoint's slices (species k's particles in block order). Bounds kept from the last step's blocks miss
// the particles the remix brought (tests/mutation 102; at a step's end the collisions have mostly raised
// them again).
TEST(Collide, SeparableFirstVisitBoundsHoldEveryParticle) {
  const PowerLawGas gas = power_law_gas(300, 9000.0, 2);
  auto sys = initial(gas.mix, gas.counts, std::vector<double>(gas.counts.size(), 1.0), 31);
  Collider c(Scheme::lowrank, gas.mix, sys, rng::make_stream(31, 0, rng::Purpose::collisions), 1.0);
  c.use_blocks(200);
  ASSERT_EQ(c.blocks(), 16u);
  const std::size_t s = gas.counts.size();
  std::size_t checked = 0;
  for (int step = 0; step < 4; ++step) {
    if (step > 0) c.advance(1e12, 100 * gas.total, true, 100 * gas.total, true);  // (the step before, to its end)
    c.advance(c.time() + 1e-3);
    const Collider::State st = c.state();
    ASSERT_EQ(st.slice_counts.size(), 16 * s);
    for (std::size_t k = 0; k < s; ++k) {
      std::size_t at = sys.first[k];
      for (std::size_t j = 0; j < 16; ++j) {
        const auto count = static_cast<std::size_t>(st.slice_counts[j * s + k]);
        for (std::size_t i = at; i < at + count; ++i, ++checked) {
          const particles::Vec3& v = sys.v[i];
          ASSERT_LE(v.x * v.x + v.y * v.y + v.z * v.z, st.block_max_speed2[j * s + k])
              << "step " << step << ", block " << j << ", species " << k;
        }
        at += count;
      }
      ASSERT_EQ(at, sys.first[k] + sys.count[k]);
    }
  }
  EXPECT_EQ(checked, 4 * gas.total);
  EXPECT_EQ(c.counters().overshoots, 0u);
}

// The scattered species' shuffles (collide.hpp scatter_species: the draws in one stream, the transpositions on
// the block threads, species by species) give the same particles, displacements and counters, bit for bit,
// on 1, 2 and 3 threads: 300 species of the power law in 16 blocks, all but the four commonest scattered
// (about 7100 transpositions a remix, so the threads share them), displacements tracked, to an exact event
// target of 20 collisions per particle (several remixes).
TEST(Collide, ScatteredSpeciesAreShuffledAlikeOnAnyThreadCount) {
  const PowerLawGas gas = power_law_gas(300, 9000.0, 2);
  struct Run {
    std::vector<particles::Vec3> v;
    std::vector<double> r;
    collide::Counters counters;
  };
  auto run = [&](int threads) {
    auto sys = initial(gas.mix, gas.counts, std::vector<double>(gas.counts.size(), 1.0), 41);
    particles::start_tracking(sys, 0.0);
    Collider c(Scheme::lowrank, gas.mix, sys, rng::make_stream(41, 0, rng::Purpose::collisions), 1.0);
    c.use_blocks(200);
    c.use_threads(threads);
    EXPECT_EQ(c.blocks(), 16u);
    EXPECT_TRUE(c.advance(1e12, 10 * gas.total));
    Run out{{sys.v.begin(), sys.v.end()}, {}, c.counters()};
    for (const auto& d : sys.r) out.r.insert(out.r.end(), {d.x, d.y, d.z, d.t_last});
    return out;
  };
  const Run serial = run(1);
  EXPECT_EQ(serial.counters.events, 10 * gas.total);
  EXPECT_GT(serial.counters.steps, 3u);
  for (int threads : {2, 3}) {
    const Run threaded = run(threads);
    EXPECT_EQ(threaded.v, serial.v) << threads << " threads";
    EXPECT_EQ(threaded.r, serial.r) << threads << " threads";
    EXPECT_EQ(threaded.counters.candidates, serial.counters.candidates) << threads << " threads";
    EXPECT_EQ(threaded.counters.dissipated, serial.counters.dissipated) << threads << " threads";
  }
}

// The factored `lowrank` draw (collide.hpp, "Mixtures in blocks"; \ref sch_factored "docs/schemes.md"),
// which blocks with more than 24 species present take, forced at P = 2, 3 and 20 by the test hook
// Collider::set_lowrank_factor_above(0): it samples the process of the one-word draw and of the
// unblocked `lowrank` loop.
namespace {

// A gas of the factored-draw tests: every species dealt into every block (N_k >= 64 K), so that each
// block holds all P = S species.
struct FactoredCase {
  std::string label;
  species::Mixture mix;
  std::vector<std::size_t> counts;
  double t_mid;  // the time-driven part of a run: about 6-10 collisions per particle
  double frame_scale = 1.0, frame_shear = 0.0;  // a sheared frame (set_frame) when not 1 and 0
};

// S species of equal counts (600 each) with m_k = k, sigma_k = k^(1/3), alpha = 0.8, total density n.
species::Mixture equal_count_mixture(std::size_t s, double n, bool enskog) {
  std::vector<double> mass(s), diameter(s), density(s, n / static_cast<double>(s));
  for (std::size_t k = 0; k < s; ++k) mass[k] = static_cast<double>(k + 1), diameter[k] = std::cbrt(mass[k]);
  return species::make_mixture(mass, diameter, density, species::PairMatrix(s, 0.8), enskog);
}

std::vector<FactoredCase> factored_cases() {
  species::PairMatrix binary_alpha(2, 0.9), three_alpha(3, 0.9);
  binary_alpha(0, 1) = binary_alpha(1, 0) = 0.8;
  binary_alpha(1, 1) = 0.7;
  three_alpha(0, 2) = three_alpha(2, 0) = 0.7;
  const auto three = [&](double scale, bool enskog) {
    return species::make_mixture({1.0, 2.0, 4.0}, {1.0, 1.3, 1.6}, {0.006 * scale, 0.004 * scale, 0.003 * scale},
                                 three_alpha, enskog);
  };
  return {
      {"P = 2, dilute", binary(0.9, 0.8, 0.7), {8000, 4000}, 60.0},
      // in the frame S = 1.3, c = 0.3 of Collide.ShearedFrameInBlocks: rows and acceptance take ||G|| = 1.51
      {"P = 2, dilute, sheared frame", binary(0.9, 0.8, 0.7), {8000, 4000}, 60.0, 1.3, 0.3},
      // packing fraction pi/6 (0.1 + 0.05 x 8) = 0.26: chi_11, chi_12, chi_22 well apart
      {"P = 2, Enskog", species::make_mixture({1.0, 4.0}, {1.0, 2.0}, {0.1, 0.05}, binary_alpha, true), {8000, 4000},
       6.0},
      {"P = 3, dilute", three(1.0, false), {6000, 4000, 3000}, 60.0},
      {"P = 3, Enskog", three(10.0, true), {6000, 4000, 3000}, 6.0},  // packing fraction 0.14
      {"P = 20, dilute", equal_count_mixture(20, 0.01, false), std::vector<std::size_t>(20, 600), 60.0},
      // packing fraction pi/6 x 0.0025 x 210 = 0.27
      {"P = 20, Enskog", equal_count_mixture(20, 0.05, true), std::vector<std::size_t>(20, 600), 8.0},
  };
}

// Species groups of the observables: each species for S <= 3; species 1, 2-10 and 11-20 for S = 20.
std::size_t group_of(std::size_t k, std::size_t s) { return s <= 3 ? k : k == 0 ? 0 : k < 10 ? 1 : 2; }

// Observables of one run: each group's temperature, each pair of groups' share of the events, the time
// at the event target; their names in `names`.
std::vector<double> factored_observables(const species::Mixture& mix, const particles::System& sys, const Collider& c,
                                         std::vector<std::string>& names) {
  const std::size_t s = mix.size(), groups = group_of(s - 1, s) + 1;
  std::vector<double> energy(groups, 0.0), count(groups, 0.0), events(groups * groups, 0.0);
  for (std::size_t i = 0; i < sys.size(); ++i) {
    const auto& v = sys.v[i];
    const std::size_t g = group_of(sys.species[i], s);
    energy[g] += mix.mass[sys.species[i]] * (v.x * v.x + v.y * v.y + v.z * v.z);
    count[g] += 3.0;
  }
  for (std::size_t k = 0; k < s; ++k)
    for (std::size_t j = k; j < s; ++j)
      events[group_of(k, s) * groups + group_of(j, s)] += static_cast<double>(c.counters().pair_events[k * s + j]);
  std::vector<double> out;
  names.clear();
  for (std::size_t g = 0; g < groups; ++g) {
    out.push_back(energy[g] / count[g]);
    names.push_back("T of group " + std::to_string(g + 1));
  }
  for (std::size_t g = 0; g < groups; ++g)
    for (std::size_t h = g; h < groups; ++h) {
      out.push_back(events[g * groups + h] / static_cast<double>(c.counters().events));
      names.push_back("share " + std::to_string(g + 1) + "-" + std::to_string(h + 1));
    }
  out.push_back(c.time());
  names.push_back("time at the target");
  return out;
}

// One replica of `gas` with `lowrank`: unblocked (draw 0), in 4 blocks by the one-word draw (1), by
// the factored draw forced (2), by the separable draw forced (3) or by it in three stages (4: the species'
// entries read a stage after the cells, as beyond separable_deep_above present species); time-driven to t_mid, then 20000
// events to an exact target.
std::vector<double> run_factored_case(const FactoredCase& gas, int draw, std::uint64_t seed,
                                      std::vector<std::string>& names) {
  auto sys = initial(gas.mix, gas.counts, std::vector<double>(gas.mix.size(), 1.0), seed);
  Collider c(Scheme::lowrank, gas.mix, sys, rng::make_stream(seed, 0, rng::Purpose::collisions), 1.0);
  if (draw > 0) c.use_blocks(3000);
  follow_scheme(c, Scheme::lowrank);
  if (draw == 2) c.set_lowrank_factor_above(0);
  if (draw >= 3) c.set_separable_blocks();
  if (draw == 4) c.set_separable_deep_above(0);
  EXPECT_EQ(c.blocks(), draw > 0 ? 4u : 1u);
  if (gas.frame_scale != 1.0 || gas.frame_shear != 0.0) c.set_frame(gas.frame_scale, gas.frame_shear);
  c.advance(gas.t_mid);
  const std::uint64_t target = c.counters().events + 20000;
  c.advance(1e12, target);
  EXPECT_EQ(c.counters().events, target);
  EXPECT_EQ(c.counters().overshoots, 0u);
  return factored_observables(gas.mix, sys, c, names);
}

}  // namespace

// Seven gases (P = 2, 3 and 20 species, dilute and Enskog at packing fractions 0.14-0.27, and the binary
// one in a sheared frame, where the temperatures are those of the stored u; masses and diameters
// unlike, so that the pair law matters), each run unblocked, in 4 blocks with the one-word
// draw and in 4 blocks with the factored draw forced, 16 replicas each (8 under the sanitizers, which
// compare with the unblocked loop only: the one-word reference runs in full in the optimised build),
// `lowrank`, time-driven to about 6-10 collisions per particle and then to an exact event target. Each
// group's temperature, each pair of groups' share of the events and the time at the target, factored
// against unblocked and factored against one-word, agree within 4 combined standard errors (printed),
// with no acceptance overshoot. A row weight without w_i (the candidate rate kept right) moves the
// binary gas's shares of 1-1 and 2-2 events by about 80 SE (mutant 64); rows without ||G|| move the
// sheared frame's time at the target by about 90 SE (mutant 66).
TEST(Collide, FactoredDrawMatchesOneWordDrawAndUnblocked) {
  const std::size_t replicas = gdsmc::test::replicas(16);  // 8 under the sanitizers
  const char* draw_name[] = {"unblocked", "one-word", "factored"};
  for (const FactoredCase& gas : factored_cases()) {
    SCOPED_TRACE(gas.label);
    std::vector<std::string> names;
    std::vector<std::vector<double>> observed[3];  // [draw][observable][replica]
    for (int draw = 0; draw < 3; ++draw)
      for (std::size_t r = 0; r < (draw == 1 && gdsmc::test::sanitized ? 0 : replicas); ++r) {
        const auto x = run_factored_case(gas, draw, 600 + r, names);
        observed[draw].resize(x.size());
        for (std::size_t q = 0; q < x.size(); ++q) observed[draw][q].push_back(x[q]);
      }
    for (std::size_t q = 0; q < names.size(); ++q) {
      const auto [m2, s2] = mean_se(observed[2][q]);
      for (int reference : {0, 1}) {
        if (observed[reference].empty()) continue;  // (the one-word draw: not under the sanitizers)
        const auto [m0, s0] = mean_se(observed[reference][q]);
        std::printf("[ Blocks.Factored ] %s %s: %s %.6g +- %.2g, factored %.6g +- %.2g (%.2f SE)\n", gas.label.c_str(),
                    names[q].c_str(), draw_name[reference], m0, s0, m2, s2, (m2 - m0) / std::hypot(s0, s2));
        EXPECT_LT(std::abs(m2 - m0), 4.0 * std::hypot(s0, s2)) << names[q] << " against " << draw_name[reference];
      }
    }
  }
}

// The separable `lowrank` draw (collide.hpp, "Mixtures in blocks"; \ref sch_separable "docs/schemes.md"),
// which blocks of more than block_species_limit species take, forced on the seven gases of
// FactoredDrawMatchesOneWordDrawAndUnblocked (P = 2, 3, 20; dilute and Enskog, where chi_ik/chi_max enters
// the acceptance; a sheared frame) by Collider::set_separable_blocks(): it samples the process of the
// one-word draw and of the unblocked loop, in two stages (as up to separable_deep_above present species)
// and in three (forced by set_separable_deep_above(0)). The same observables and tolerance (4 combined SE,
// printed), 16 replicas each (8 under the sanitizers, against the unblocked loop only), no acceptance
// overshoot. Rows without 1/sqrt(m_i) (every species given the lightest one's speed bound, the rate kept
// right) move the binary gas's shares of the 1-1 and 2-2 events by about 100 and 150 SE (mutant 81).
TEST(Collide, SeparableDrawMatchesOneWordDrawAndUnblocked) {
  const std::size_t replicas = gdsmc::test::replicas(16);  // 8 under the sanitizers
  const char* draw_name[] = {"unblocked", "one-word"};
  for (const FactoredCase& gas : factored_cases()) {
    SCOPED_TRACE(gas.label);
    std::vector<std::string> names;
    // [unblocked, one-word, separable, separable in three stages][observable][replica]
    std::vector<std::vector<double>> observed[4];
    for (int draw : {0, 1, 3, 4})
      for (std::size_t r = 0; r < (draw == 1 && gdsmc::test::sanitized ? 0 : replicas); ++r) {
        const auto x = run_factored_case(gas, draw, 600 + r, names);
        auto& to = observed[draw >= 3 ? draw - 1 : draw];
        to.resize(x.size());
        for (std::size_t q = 0; q < x.size(); ++q) to[q].push_back(x[q]);
      }
    for (std::size_t q = 0; q < names.size(); ++q)
      for (int tested : {2, 3}) {
        const auto [m2, s2] = mean_se(observed[tested][q]);
        for (int reference : {0, 1}) {
          if (observed[reference].empty()) continue;  // (the one-word draw: not under the sanitizers)
          const auto [m0, s0] = mean_se(observed[reference][q]);
          std::printf("[ Blocks.Separable ] %s %s: %s %.6g +- %.2g, separable%s %.6g +- %.2g (%.2f SE)\n",
                      gas.label.c_str(), names[q].c_str(), draw_name[reference], m0, s0,
                      tested == 3 ? " in three stages" : "", m2, s2, (m2 - m0) / std::hypot(s0, s2));
          EXPECT_LT(std::abs(m2 - m0), 4.0 * std::hypot(s0, s2))
              << names[q] << " against " << draw_name[reference] << (tested == 3 ? ", three stages" : "");
        }
      }
  }
}

// The pair counts of a saved state must have the collider's own size: S^2 up to pair_event_limit species and none
// beyond (the block kernel counts them in an array of pair_event_limit^2 on the stack). A state of 2 species with
// its 4 counts fits; one whose counts were left out, or a 65-species state given 4 counts, is refused.
TEST(Collide, SavedPairCountsMustFitTheCollider) {
  const auto mix2 = binary(0.7, 0.9, 0.5);
  auto sys2 = initial(mix2, {300, 300}, {1.0, 1.0}, 5);
  Collider two(Scheme::majorant, mix2, sys2, rng::make_stream(5, 0, rng::Purpose::collisions), 1.0);
  two.advance(1e12, 1000);
  auto st = two.state();
  ASSERT_EQ(st.counters.pair_events.size(), 4u);
  EXPECT_NO_THROW(two.restore(st));
  st.counters.pair_events.clear();
  EXPECT_THROW(two.restore(st), std::invalid_argument);
  const auto mix65 = equal_count_mixture(collide::pair_event_limit + 1, 0.01, false);
  auto sys65 = initial(mix65, std::vector<std::size_t>(collide::pair_event_limit + 1, 10),
                       std::vector<double>(collide::pair_event_limit + 1, 1.0), 5);
  Collider many(Scheme::lowrank, mix65, sys65, rng::make_stream(5, 0, rng::Purpose::collisions), 1.0);
  auto st65 = many.state();
  ASSERT_TRUE(st65.counters.pair_events.empty());
  EXPECT_NO_THROW(many.restore(st65));
  st65.counters.pair_events.assign(4, 0);
  EXPECT_THROW(many.restore(st65), std::invalid_argument);
}

// Which draw a block takes (collide.hpp, "Mixtures in blocks"): up to lowrank_factor_above = 24 species
// present the one-word draw, the code before the factored draw existed, byte for byte: a 24-species gas
// (250 particles each, 2 blocks, all species in both) gives bit for bit the velocities and counts of the
// one-word draw forced (set_lowrank_factor_above(block_species_limit)), and not those of the factored
// one; with 25 species the default is the factored draw. (The golden runs, tests/golden, compare the
// output with that of the build before the change.) Also with 2 threads, and after a raised bound (the
// rows alone rebuilt): the runs go to 20 collisions per particle.
TEST(Collide, FactoredDrawOnlyAboveTheThreshold) {
  ASSERT_EQ(Collider::lowrank_factor_above, 24u);
  for (std::size_t s : {std::size_t{24}, std::size_t{25}}) {
    SCOPED_TRACE(std::to_string(s) + " species");
    const auto mix = equal_count_mixture(s, 0.01, false);
    const std::vector<std::size_t> counts(s, 6000 / s);
    const std::size_t n = 6000 / s * s;
    auto run = [&](std::size_t factor_above, int threads) {
      auto sys = initial(mix, counts, std::vector<double>(s, 1.0), 41);
      Collider c(Scheme::lowrank, mix, sys, rng::make_stream(41, 0, rng::Purpose::collisions), 1.0);
      c.use_blocks(n / 2);
      follow_scheme(c, Scheme::lowrank);
      c.use_threads(threads);
      if (factor_above != Collider::lowrank_factor_above) c.set_lowrank_factor_above(factor_above);
      EXPECT_EQ(c.blocks(), 2u);
      c.advance(1e12, 10 * n);
      EXPECT_EQ(c.counters().overshoots, 0u);
      std::vector<double> flat;
      for (const auto& v : sys.v) flat.insert(flat.end(), {v.x, v.y, v.z});
      flat.push_back(static_cast<double>(c.counters().candidates));
      flat.push_back(c.time());
      return flat;
    };
    const auto by_default = run(Collider::lowrank_factor_above, 1);
    const auto one_word = run(collide::block_species_limit, 1);
    const auto factored = run(0, 1);
    EXPECT_EQ(run(Collider::lowrank_factor_above, 2), by_default);
    EXPECT_EQ(by_default == one_word, s <= Collider::lowrank_factor_above);
    EXPECT_EQ(by_default == factored, s > Collider::lowrank_factor_above);
    EXPECT_NE(one_word, factored);
  }
}

// species_at, the mixture kernel's species of a block index, against counting by hand: for edges of
// 2, 5 (one of them empty) and 20 species (three empty, two of them last and first), every index of
// the block gets the k with edge[k] <= i < edge[k + 1], never an empty species; the block's first and
// last index and each boundary checked explicitly (the cases an off-by-one search gets wrong).
TEST(Collide, SpeciesOfABlockIndex) {
  using gdsmc::collide::species_at;
  const std::vector<std::uint32_t> two = {0, 3, 10};
  EXPECT_EQ(species_at(two.data(), 2, 0), 0u);
  EXPECT_EQ(species_at(two.data(), 2, 2), 0u);
  EXPECT_EQ(species_at(two.data(), 2, 3), 1u);
  EXPECT_EQ(species_at(two.data(), 2, 9), 1u);
  const std::vector<std::uint32_t> five = {0, 4, 4, 9, 10, 16};  // species 1 empty
  const std::uint32_t expected_five[16] = {0, 0, 0, 0, 2, 2, 2, 2, 2, 3, 4, 4, 4, 4, 4, 4};
  for (std::uint32_t i = 0; i < 16; ++i) EXPECT_EQ(species_at(five.data(), 5, i), expected_five[i]) << "index " << i;
  // 20 species: counts 0 (species 0 empty), then 1..17 of 3, 0, 2, ..., species 19 empty.
  std::vector<std::uint32_t> counts = {0, 3, 1, 4, 1, 5, 9, 2, 6, 5, 3, 5, 8, 9, 7, 9, 3, 0, 2, 0};
  std::vector<std::uint32_t> edges = {0};
  for (std::uint32_t c : counts) edges.push_back(edges.back() + c);
  std::uint32_t i = 0;
  for (std::uint32_t k = 0; k < counts.size(); ++k)
    for (std::uint32_t j = 0; j < counts[k]; ++j, ++i) EXPECT_EQ(species_at(edges.data(), 20, i), k) << "index " << i;
  EXPECT_EQ(i, edges.back());
  EXPECT_EQ(species_at(edges.data(), 20, 0), 1u);                // the first index: species 0 is empty
  EXPECT_EQ(species_at(edges.data(), 20, edges.back() - 1), 18u);  // the last index: species 19 is empty
  EXPECT_EQ(species_at(edges.data(), 20, edges[9] - 1), 8u);     // either side of a boundary
  EXPECT_EQ(species_at(edges.data(), 20, edges[9]), 9u);
}

// deal::scatter_draws and scatter_moves (deal.hpp, "Scattering"), as the remix runs them: each element goes to a
// uniformly random block, independently of the others. 5 elements in 6 blocks (fewer than blocks) and 40 in 6, 60000 scatterings each, every
// scattering starting from the order the previous one left (as in the remix): each element's frequency
// in each block and each pair's frequency of sharing a block are within 4.5 binomial SE of 1/K (a
// dealing in equal slices never puts two of 5 together; cut without the shuffle, neighbours share a
// block far more often). The displacements follow the velocities; the counts add up.
TEST(Collide, ScatterPlacesEveryParticleUniformly) {
  for (std::size_t n : {std::size_t{5}, std::size_t{40}}) {
    const std::size_t k = 6, draws = 60000, stride = 3;
    auto gen = rng::make_stream(31, 0, rng::Purpose::collisions);
    std::vector<std::size_t> data(n), second(n), counts(k * stride, 99);
    std::vector<std::uint32_t> partners(n - 1);
    for (std::size_t i = 0; i < n; ++i) data[i] = second[i] = i;
    std::vector<double> in_block(n * k, 0.0), together(n * n, 0.0);
    std::vector<std::size_t> block_of(n);
    for (std::size_t d = 0; d < draws; ++d) {
      // (the two halves the remix runs: scatter_draws in the stream, scatter_moves on the threads)
      deal::scatter_draws(gen, n, k, counts.data(), stride, partners.data());
      deal::scatter_moves(n, partners.data(), [&](std::size_t i, std::size_t q) {
        std::swap(data[i], data[q]);
        std::swap(second[i], second[q]);
      });
      ASSERT_EQ(data, second);
      std::size_t position = 0, total = 0;
      for (std::size_t j = 0; j < k; ++j) {
        total += counts[j * stride];
        for (std::size_t c = 0; c < counts[j * stride]; ++c) block_of[data[position++]] = j;
      }
      ASSERT_EQ(total, n);
      for (std::size_t a = 0; a < n; ++a) {
        in_block[a * k + block_of[a]] += 1.0;
        for (std::size_t b = a + 1; b < n; ++b) together[a * n + b] += block_of[a] == block_of[b] ? 1.0 : 0.0;
      }
    }
    const double p = 1.0 / static_cast<double>(k), se = std::sqrt(p * (1.0 - p) / static_cast<double>(draws));
    double worst_block = 0.0, worst_pair = 0.0;
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t j = 0; j < k; ++j)
        worst_block = std::max(worst_block, std::abs(in_block[a * k + j] / static_cast<double>(draws) - p) / se);
      for (std::size_t b = a + 1; b < n; ++b)
        worst_pair = std::max(worst_pair, std::abs(together[a * n + b] / static_cast<double>(draws) - p) / se);
    }
    std::printf("[ Scatter ] n = %zu in %zu blocks, %zu draws: worst element-block %.2f SE, worst pair %.2f SE\n", n, k,
                draws, worst_block, worst_pair);
    EXPECT_LT(worst_block, 4.5);
    EXPECT_LT(worst_pair, 4.5);
  }
}

// deal::scatter_draws and scatter_moves (deal.hpp): the one-pass scattering in two halves, with the same calls
// of the stream, so the same permutation and counts: checked against the one-pass Fisher-Yates and multinomial
// counts written out here, for n = 0, 1, 2, 7 and 1000 elements in 5 blocks, three scatterings in a row from
// one stream each (the stream's state after them the same too).
TEST(Collide, ScatterInHalvesIsScatter) {
  const auto one_pass = [](rng::Xoshiro256pp& gen, std::size_t n, std::size_t k, std::size_t* counts,
                           std::size_t stride, std::vector<std::size_t>& data) {
    for (std::size_t i = n; i > 1; --i) {
      const std::size_t q = gen.below(i);
      std::swap(data[i - 1], data[q]);
    }
    for (std::size_t j = 0; j < k; ++j) counts[j * stride] = 0;
    for (std::size_t i = 0; i < n; ++i) ++counts[gen.below(k) * stride];
  };
  for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{7}, std::size_t{1000}}) {
    const std::size_t k = 5, stride = 2;
    auto one = rng::make_stream(5, 1, rng::Purpose::collisions), halves = one;
    std::vector<std::size_t> a(n), b(n), counts_a(k * stride, 7), counts_b(k * stride, 9);
    std::vector<std::uint32_t> partners(n > 0 ? n - 1 : 0);
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] = i;
    for (int round = 0; round < 3; ++round) {
      one_pass(one, n, k, counts_a.data(), stride, a);
      deal::scatter_draws(halves, n, k, counts_b.data(), stride, partners.data());
      deal::scatter_moves(n, partners.data(), [&](std::size_t i, std::size_t q) { std::swap(b[i], b[q]); });
      ASSERT_EQ(a, b) << n << " elements, round " << round;
      for (std::size_t j = 0; j < k; ++j) ASSERT_EQ(counts_a[j * stride], counts_b[j * stride]) << n << " elements";
      EXPECT_EQ(one(), halves()) << n << " elements: the streams must stay together";
    }
    if (n == 1000) {
      EXPECT_NE(a[0] + a[1] + a[2], 3u) << "1000 elements left in place";
    }
  }
}

// The per-particle arrays are a list (particles.hpp System::for_each_array): the blocks' remix (dealt
// species) and scatter (a rare species) move every array a particle carries with the same permutation,
// whatever its name and type. Two extra arrays, an id (a number) and 2 id in a 3-vector, on a binary
// gas of 20000 + 60 particles in blocks of 2048 (9 blocks: the rare species scattered) whose velocities
// are all equal, so that no candidate is accepted and only the remixes move the particles: after more
// than 20 steps the ids are a permutation of each species' own ids (not the identity), and the second
// array still holds twice the id of every particle.
TEST(Particles, EveryArrayMovesWithItsParticle) {
  const auto mix = binary(0.9, 0.9, 0.9);
  particles::System sys = initial(mix, {20000, 60}, {1.0, 1.0}, 3);
  for (auto& v : sys.v) v = {0.3, -0.2, 0.1};
  auto& id = sys.add_array<double>("id");
  auto& twice = sys.add_array<particles::Vec3>("twice_id");
  for (std::size_t i = 0; i < sys.size(); ++i) {
    id[i] = static_cast<double>(i);
    twice[i] = {2.0 * static_cast<double>(i), 0.0, -2.0 * static_cast<double>(i)};
  }
  EXPECT_THROW(sys.add_array<double>("id"), std::invalid_argument);
  Collider c(Scheme::majorant, mix, sys, rng::make_stream(4, 0, rng::Purpose::collisions), 1.0);
  c.use_blocks(2048);
  ASSERT_EQ(c.blocks(), 9u);
  for (int chunk = 0; chunk < 40; ++chunk) c.advance(c.time() + 1000.0);
  EXPECT_EQ(c.counters().events, 0u);
  EXPECT_GT(c.counters().steps, 20u);
  std::size_t moved = 0;
  std::vector<bool> seen(sys.size(), false);
  for (std::size_t i = 0; i < sys.size(); ++i) {
    const auto k = static_cast<std::size_t>(id[i]);
    ASSERT_EQ(sys.species[k], sys.species[i]) << "particle " << i << " left its species' range";
    ASSERT_FALSE(seen[k]);
    seen[k] = true;
    ASSERT_EQ(twice[i].x, 2.0 * id[i]);
    ASSERT_EQ(twice[i].z, -2.0 * id[i]);
    moved += k != i;
  }
  EXPECT_GT(moved, sys.size() / 2);
  // The rare species (scattered) moved too.
  std::size_t rare_moved = 0;
  for (std::size_t i = sys.first[1]; i < sys.size(); ++i) rare_moved += static_cast<std::size_t>(id[i]) != i;
  EXPECT_GT(rare_moved, 30u);
  std::size_t names = 0;
  sys.for_each_array([&](const char*, const auto&) { ++names; });
  EXPECT_EQ(names, 3u);  // velocity, id, twice_id (no displacements tracked)
}

// The blocks' remix (collide.hpp "Blocks"): without it each block is a gas of its own for ever. Block 0
// holds the first N/K particles at the first step; they start 4 times hotter than the rest and carry a
// tag (an extra array, which moves with its particle). In an elastic gas the tagged particles' mean
// energy relaxes to the whole gas's within a few collisions per particle only if the blocks exchange
// particles; without the remix it would stay 4/((4 + 3)/4) = 2.29 times the mean (energy conserved in
// block 0). After 30 collisions per particle (every scheme that blocks, 4 blocks of 2048): within 10 %.
TEST(Collide, TheRemixMixesTheBlocks) {
  const auto mix = one_species(1.0);
  for (Scheme scheme : {Scheme::majorant, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    auto sys = initial(mix, {8192}, {1.0}, 11);
    auto& tag = sys.add_array<double>("tag");
    for (std::size_t i = 0; i < 2048; ++i) {
      tag[i] = 1.0;
      sys.v[i] = {2.0 * sys.v[i].x, 2.0 * sys.v[i].y, 2.0 * sys.v[i].z};  // 4 times the energy
    }
    Collider c(scheme, mix, sys, rng::make_stream(11, 0, rng::Purpose::collisions), 1.0);
    c.use_blocks(2048);
    ASSERT_EQ(c.blocks(), 4u);
    c.advance(1e9, 30 * 8192 / 2);
    double tagged = 0.0, all = 0.0, n_tagged = 0.0;
    for (std::size_t i = 0; i < sys.size(); ++i) {
      const double e = sys.v[i].x * sys.v[i].x + sys.v[i].y * sys.v[i].y + sys.v[i].z * sys.v[i].z;
      all += e;
      if (tag[i] == 1.0) {
        tagged += e;
        n_tagged += 1.0;
      }
    }
    ASSERT_EQ(n_tagged, 2048.0);
    const double ratio = (tagged / n_tagged) / (all / static_cast<double>(sys.size()));
    EXPECT_NEAR(ratio, 1.0, 0.1) << "tagged particles' energy over the mean (2.29 if the blocks never mix)";
  }
}

// The speed bound is raised when a collision produces a speed above it (collide.hpp "Bounds"): a gas that
// starts with every speed equal (|v| = 1, random directions) has no speed above 1 at first, and its first
// collisions make many (an elastic gas reaches the Maxwellian). Unblocked, every scheme: the bound was
// raised (the largest speed ends above 1.5) and no candidate ever had an acceptance above 1 (overshoots 0).
// Without the raise the overshoots count thousands.
TEST(Collide, TheSpeedBoundIsRaisedAboveTheStartingSpeeds) {
  const auto mix = one_species(1.0);
  for (Scheme scheme : {Scheme::majorant, Scheme::pairs, Scheme::lowrank}) {
    SCOPED_TRACE(name(scheme));
    auto sys = initial(mix, {4000}, {1.0}, 12);
    for (auto& v : sys.v) {
      const double norm = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
      v = {v.x / norm, v.y / norm, v.z / norm};
    }
    Collider c(scheme, mix, sys, rng::make_stream(12, 0, rng::Purpose::collisions), 1.0);
    c.advance(1e9, 10 * 4000 / 2);
    double largest = 0.0;
    for (const auto& v : sys.v) largest = std::max(largest, std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
    EXPECT_GT(largest, 1.5);
    EXPECT_EQ(c.counters().overshoots, 0u);
  }
}

// The margin of a blocked step near an exact event target (event_margin.hpp), against values computed by
// hand: 100 events left allow a step expected to bring 33.9733 (sqrt = (-8 + sqrt(433.6))/2.2 = 5.828665;
// 1.1 x 33.9733 + 8 x 5.828665 + 16 = 100.000), 17 allow 0.0151099, 16 or fewer none; 33.97 may not reach
// 100 (99.994), 34.0 may (100.047). At 1e6 the two functions agree to the last digit either side.
TEST(EventMargin, HandComputedValues) {
  using namespace gdsmc::event_margin;
  EXPECT_NEAR(largest_safe_mean(100.0), 33.97334, 1e-5);
  EXPECT_NEAR(largest_safe_mean(17.0), 0.0151099, 1e-7);
  EXPECT_EQ(largest_safe_mean(16.0), 0.0);
  EXPECT_EQ(largest_safe_mean(3.0), 0.0);
  EXPECT_FALSE(may_reach(33.97, 100.0));
  EXPECT_TRUE(may_reach(34.0, 100.0));
  const double mean = largest_safe_mean(1e6);
  EXPECT_NEAR(mean, 902168.54, 0.01);
  EXPECT_FALSE(may_reach(mean * (1.0 - 1e-9), 1e6));
  EXPECT_TRUE(may_reach(mean * (1.0 + 1e-9), 1e6));
}

// A gas whose bounds are all zero (no candidate comes) reaches a time target at once; an event target it
// would never reach is an error, not a sample at an infinite time.
TEST(Collide, BoundsOfZeroNeverReachAnEventTarget) {
  EXPECT_EQ(gdsmc::collide::time_at_rest(12.5), 12.5);
  EXPECT_THROW(gdsmc::collide::time_at_rest(std::numeric_limits<double>::infinity()), std::runtime_error);
}

// Before a first candidate the credit is the sum of the cuts' lengths, credit + (t_stop - time), which can
// round one step above the time (7.0000000000000007e-07 against 7e-07): restore() takes such a state, which
// every run with short first samples makes, and refuses a credit beyond the time by more than round-off.
TEST(Collide, ACreditRoundedAboveTheTimeIsRestored) {
  const auto mix = species::make_mixture({1.0}, {1.0}, {0.01}, species::PairMatrix(1, 0.9), false);
  auto sys = initial(mix, {100}, {1.0}, 1);
  Collider a(Scheme::majorant, mix, sys, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  a.advance(std::ldexp(0.04769993984813675, -4));
  a.advance(std::ldexp(0.8327644489980403, -4));
  const Collider::State saved = a.state();
  ASSERT_EQ(a.counters().candidates, 0u);
  EXPECT_GT(saved.credit, saved.time);  // (the round-off this test is about)
  auto sys_b = sys;
  Collider b(Scheme::majorant, mix, sys_b, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  EXPECT_NO_THROW(b.restore(saved));
  Collider::State forged = saved;
  forged.credit = 2.0 * saved.time;
  EXPECT_THROW(b.restore(forged), std::invalid_argument);
  forged = saved;
  forged.block_credit.assign(saved.block_credit.size(), -1.0);
  forged.max_speed2.assign(saved.max_speed2.size(), -1.0);
  EXPECT_THROW(b.restore(forged), std::invalid_argument);
}

// A sub-step's whole candidates, floor(available R): none for a negative or NaN product, at most 2^63 for one
// that a checkpoint's forged bounds make larger than a uint64 holds (the conversion would be undefined).
TEST(Collide, CandidateCountOfASubStep) {
  using gdsmc::collide::candidate_count;
  EXPECT_EQ(candidate_count(2.7), 2u);
  EXPECT_EQ(candidate_count(0.0), 0u);
  EXPECT_EQ(candidate_count(-1e-17), 0u);
  EXPECT_EQ(candidate_count(std::nan("")), 0u);
  EXPECT_EQ(candidate_count(1e30), std::uint64_t{1} << 63);
  EXPECT_EQ(candidate_count(0x1p62), std::uint64_t{1} << 62);
}
