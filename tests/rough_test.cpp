// Rough spheres (dsmc/rules.hpp RoughRule; docs/rough-spheres.md): the rule by hand and its conservation
// laws, the limits, the input, and a run of the collider on the rule.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/rules.hpp"
#include "model/species.hpp"
#include "theory/rough.hpp"

using namespace gdsmc;
using particles::Vec3;

namespace {

species::Mixture rough_mixture(std::vector<double> mass, std::vector<double> diameter, double alpha, double beta,
                               std::vector<double> kappa) {
  const std::size_t s = mass.size();
  species::Mixture mix = species::make_mixture(mass, diameter, std::vector<double>(s, 0.01),
                                               species::PairMatrix(s, alpha), false);
  mix.roughness = species::PairMatrix(s, beta);
  mix.moment_of_inertia = std::move(kappa);
  return mix;
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 add(const Vec3& a, const Vec3& b, double f = 1.0) { return {a.x + f * b.x, a.y + f * b.y, a.z + f * b.z}; }

}  // namespace

// One species, m = 1, sigma = 1, kappa = 0.4 (K = 2/7), alpha = 0.5, beta = 0, e = x (from a to b),
// v_a = (1, 1, 0), v_b = 0, no spin: J = (3/2, 2/7, 0), v_a' = (1/4, 6/7, 0), v_b' = (3/4, 1/7, 0),
// e x J = (0, 0, 2/7) and spin 2 m_ab/(kappa m sigma) = 5/2: w_a' = w_b' = -(0, 0, 5/7) (a, sliding
// along +y at its contact point on its +x side, is turned about -z). Energy 1 before, 0.3125 + 42/98
// after: lost (1/4)(3/4 + 2/7) = 29/112 (by hand, docs/rough-spheres.md).
TEST(Rough, RuleByHand) {
  const auto mix = rough_mixture({1.0}, {1.0}, 0.5, 0.0, {0.4});
  const rules::RoughRule rule(mix);
  Vec3 va{1.0, 1.0, 0.0}, vb{0.0, 0.0, 0.0}, wa{0.0, 0.0, 0.0}, wb{0.0, 0.0, 0.0};
  const auto out = rules::RoughRule::collide(va, vb, wa, wb, rule.pair(0, 0), {1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0});
  const double tol = 1e-15;
  EXPECT_NEAR(va.x, 0.25, tol);
  EXPECT_NEAR(va.y, 6.0 / 7.0, tol);
  EXPECT_NEAR(vb.x, 0.75, tol);
  EXPECT_NEAR(vb.y, 1.0 / 7.0, tol);
  EXPECT_EQ(va.z + vb.z, 0.0);
  EXPECT_NEAR(wa.z, -5.0 / 7.0, tol);
  EXPECT_NEAR(wb.z, -5.0 / 7.0, tol);
  EXPECT_EQ(wa.x + wa.y + wb.x + wb.y, 0.0);
  EXPECT_NEAR(out.loss, 29.0 / 112.0, tol);
  EXPECT_NEAR(out.impulse, 0.75, tol);  // m_ab (1 + alpha)(g.e)
}

// Random pairs of a binary mixture of unequal masses, diameters and kappa: linear momentum and the angular
// momentum about the contact point conserved, (g_c'.e) = -alpha (g_c.e), g_c,t' = -beta g_c,t, and the
// energy lost equal to the energy difference computed from the velocities.
TEST(Rough, RuleConservesAndReversesTheContactVelocity) {
  auto gen = rng::make_stream(11, 0, rng::Purpose::sampling);
  for (int trial = 0; trial < 2000; ++trial) {
    const double alpha = gen.uniform(), beta = 2.0 * gen.uniform() - 1.0;
    const double ka = 0.05 + 0.6 * gen.uniform(), kb = 0.05 + 0.6 * gen.uniform();
    const auto mix = rough_mixture({1.0, 0.3 + 4.0 * gen.uniform()}, {1.0, 0.5 + 2.0 * gen.uniform()}, alpha, beta, {ka, kb});
    const rules::RoughRule rule(mix);
    const double ma = mix.mass[0], mb = mix.mass[1], sa = mix.diameter[0], sb = mix.diameter[1];
    const double ia = mix.inertia(0), ib = mix.inertia(1);
    Vec3 e;
    rng::unit_vector(gen, e.x, e.y, e.z);
    Vec3 va{gen.normal(), gen.normal(), gen.normal()}, vb{gen.normal(), gen.normal(), gen.normal()};
    Vec3 wa{gen.normal(), gen.normal(), gen.normal()}, wb{gen.normal(), gen.normal(), gen.normal()};
    if (dot(add(va, vb, -1.0), e) <= 0.0) e = {-e.x, -e.y, -e.z};  // e from a to b, approaching: g.e > 0
    const auto contact_velocity = [&](const Vec3& a, const Vec3& b, const Vec3& oa, const Vec3& ob) {
      // a touches at r_a + (sigma_a/2) e, b at r_b - (sigma_b/2) e:
      // g_c = (v_a + w_a x (sigma_a/2 e)) - (v_b + w_b x (-sigma_b/2 e))
      return add(add(a, cross(oa, e), 0.5 * sa), add(b, cross(ob, e), -0.5 * sb), -1.0);
    };
    const auto angular = [&](const Vec3& a, const Vec3& b, const Vec3& oa, const Vec3& ob) {
      // about the contact point: r_a - r_c = -(sigma_a/2) e, r_b - r_c = (sigma_b/2) e
      Vec3 l{0.0, 0.0, 0.0};
      l = add(l, cross(e, a), -0.5 * sa * ma);
      l = add(l, cross(e, b), 0.5 * sb * mb);
      return add(add(l, oa, ia), ob, ib);
    };
    const auto energy = [&](const Vec3& a, const Vec3& b, const Vec3& oa, const Vec3& ob) {
      return 0.5 * (ma * dot(a, a) + mb * dot(b, b) + ia * dot(oa, oa) + ib * dot(ob, ob));
    };
    const Vec3 gc = contact_velocity(va, vb, wa, wb), l0 = angular(va, vb, wa, wb);
    const Vec3 p0 = add(Vec3{ma * va.x, ma * va.y, ma * va.z}, vb, mb);
    const double e0 = energy(va, vb, wa, wb), g_e = dot(add(va, vb, -1.0), e);
    const auto out = rules::RoughRule::collide(va, vb, wa, wb, rule.pair(0, 1), {e.x, e.y, e.z, g_e, e.x, e.y, e.z});
    const Vec3 gc1 = contact_velocity(va, vb, wa, wb), l1 = angular(va, vb, wa, wb);
    const Vec3 p1 = add(Vec3{ma * va.x, ma * va.y, ma * va.z}, vb, mb);
    const double tol = 1e-12;
    for (const auto& [x, y] : {std::pair{p0.x, p1.x}, {p0.y, p1.y}, {p0.z, p1.z}, {l0.x, l1.x}, {l0.y, l1.y}, {l0.z, l1.z}})
      ASSERT_NEAR(x, y, tol * 10.0) << "trial " << trial;
    ASSERT_NEAR(dot(gc1, e), -alpha * dot(gc, e), tol);
    const Vec3 t0 = add(gc, e, -dot(gc, e)), t1 = add(gc1, e, -dot(gc1, e));
    ASSERT_NEAR(t1.x, -beta * t0.x, tol);
    ASSERT_NEAR(t1.y, -beta * t0.y, tol);
    ASSERT_NEAR(t1.z, -beta * t0.z, tol);
    ASSERT_NEAR(e0 - energy(va, vb, wa, wb), out.loss, tol * (1.0 + e0));
    ASSERT_GE(out.loss, -tol);
  }
}

// The limits: beta = -1 leaves the spins alone and moves the velocities as the smooth rule; alpha = beta
// = 1 loses no energy.
TEST(Rough, SmoothAndElasticLimits) {
  auto gen = rng::make_stream(12, 0, rng::Purpose::sampling);
  for (int trial = 0; trial < 200; ++trial) {
    const double alpha = gen.uniform();
    const auto mix = rough_mixture({1.0, 2.5}, {1.0, 1.7}, alpha, -1.0, {0.4, 0.3});
    Vec3 e;
    rng::unit_vector(gen, e.x, e.y, e.z);
    Vec3 va{gen.normal(), gen.normal(), gen.normal()}, vb{gen.normal(), gen.normal(), gen.normal()};
    Vec3 wa{gen.normal(), gen.normal(), gen.normal()}, wb{gen.normal(), gen.normal(), gen.normal()};
    const double g_e = dot(add(va, vb, -1.0), e);
    Vec3 sa = va, sb = vb;
    const Vec3 wa0 = wa, wb0 = wb;
    const rules::Contact c{e.x, e.y, e.z, g_e, e.x, e.y, e.z};
    const auto rough = rules::RoughRule::collide(va, vb, wa, wb, rules::RoughRule(mix).pair(0, 1), c);
    const auto smooth = rules::SmoothRule::collide(sa, sb, rules::SmoothRule::make_pair(alpha, 1.0, 2.5), c);
    EXPECT_EQ(wa, wa0);
    EXPECT_EQ(wb, wb0);
    for (const auto& [x, y] : {std::pair{va.x, sa.x}, {va.y, sa.y}, {va.z, sa.z}, {vb.x, sb.x}, {vb.y, sb.y}, {vb.z, sb.z}})
      ASSERT_NEAR(x, y, 1e-14);
    ASSERT_NEAR(rough.loss, smooth.loss, 1e-14);
    const auto elastic = rough_mixture({1.0, 2.5}, {1.0, 1.7}, 1.0, 1.0, {0.4, 0.3});
    EXPECT_NEAR(rules::RoughRule::collide(va, vb, wa, wb, rules::RoughRule(elastic).pair(0, 1), c).loss, 0.0, 1e-14);
  }
}

// The collider on rough spheres with every scheme, with and without blocks: alpha = beta = 1 keeps the
// total energy (translation + rotation) to round-off over 2e5 collisions.
TEST(Rough, ColliderElasticPerfectlyRoughConservesEnergy) {
  const auto binary = rough_mixture({1.0, 3.0}, {1.0, 1.4}, 1.0, 1.0, {0.4, 0.25});
  const auto one = rough_mixture({1.0}, {1.0}, 1.0, 1.0, {0.4});
  for (const species::Mixture* m : {&binary, &one})
  for (auto scheme : {collide::Scheme::majorant, collide::Scheme::pairs, collide::Scheme::lowrank}) {
    for (std::size_t block : {std::size_t{0}, std::size_t{1024}}) {
      const species::Mixture& mix = *m;
      const bool two = mix.size() == 2;
      auto gen = rng::make_stream(3, 0, rng::Purpose::initial_state);
      auto sys = particles::make_system(mix, two ? std::vector<std::size_t>{3000, 3000} : std::vector<std::size_t>{6000},
                                        two ? std::vector<double>{1.0, 1.0} : std::vector<double>{1.0},
                                        particles::InitialDistribution::maxwell, gen);
      auto spin = rng::make_stream(3, 0, rng::Purpose::rotation);
      particles::add_angular_velocities(sys, mix, two ? std::vector<double>{2.0, 0.5} : std::vector<double>{2.0},
                                        rules::RoughRule::angular_velocity, spin);
      const auto energy = [&] {
        const auto& w = std::get<particles::ParticleArray<Vec3>>(sys.find_array(rules::RoughRule::angular_velocity)->values);
        double sum = 0.0;
        for (std::size_t i = 0; i < sys.size(); ++i) {
          const std::size_t k = sys.species[i];
          sum += 0.5 * (mix.mass[k] * dot(sys.v[i], sys.v[i]) + mix.inertia(k) * dot(w[i], w[i]));
        }
        return sum;
      };
      const double e0 = energy();
      collide::Collider collider(scheme, mix, sys, rng::make_stream(3, 0, rng::Purpose::collisions), 1.0, rules::make_rule(mix, nullptr));
      if (block > 0 && scheme != collide::Scheme::pairs) collider.use_blocks(block);
      collider.advance(1e300, 200000);
      EXPECT_GE(collider.counters().events, 200000u);
      EXPECT_NEAR(energy(), e0, 1e-10 * e0) << "scheme " << static_cast<int>(scheme) << ", blocks " << block
                                            << ", species " << mix.size();
      // The spins changed: the rule acted on them (a kernel reading another particle's spin would also
      // break the conservation above)
      const auto& w = std::get<particles::ParticleArray<Vec3>>(sys.find_array(rules::RoughRule::angular_velocity)->values);
      double t_rot = 0.0;
      for (std::size_t i = 0; i < sys.count[0]; ++i) t_rot += mix.inertia(0) * dot(w[i], w[i]) / 3.0;
      EXPECT_LT(t_rot / static_cast<double>(sys.count[0]), 1.9);  // from 2.0 towards equipartition (~1.5)
    }
  }
}

// Exact event targets in a heating gas (collide.hpp, "Event targets"; docs/schemes.md): rough spheres,
// alpha = 0.9, beta = 1, the rotation at T_rot = 100 and the translation at 1, so that the events per unit
// time rise several times over the first collisions per particle. N = 1e5 in 20 blocks, targets of 1 to 3
// collisions per particle, 3 seeds: each met exactly. (Steps near a target longer than 5 mean free times
// after a short one, with that step's acceptance, passed every target of 1 collision per particle, by 8702
// to 13913 events: tests/mutation 88; they are taken only after a probe whose gas's events per unit time fell.)
TEST(Rough, HeatingGasMeetsEventTargetsExactly) {
  const auto mix = rough_mixture({1.0}, {1.0}, 0.9, 1.0, {0.4});
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
    for (const double per_particle : {1.0, 1.5, 2.0, 2.5, 3.0}) {
      auto gen = rng::make_stream(seed, 0, rng::Purpose::initial_state);
      auto sys = particles::make_system(mix, {100000}, {1.0}, particles::InitialDistribution::maxwell, gen);
      auto spin = rng::make_stream(seed, 0, rng::Purpose::rotation);
      particles::add_angular_velocities(sys, mix, {100.0}, rules::RoughRule::angular_velocity, spin);
      collide::Collider collider(collide::Scheme::majorant, mix, sys, rng::make_stream(seed, 1, rng::Purpose::collisions),
                                 1.0, rules::make_rule(mix, nullptr));
      collider.use_blocks(5000);
      ASSERT_EQ(collider.blocks(), 20u);
      const auto target = static_cast<std::uint64_t>(per_particle * 50000.0);
      EXPECT_TRUE(collider.advance(1e12, target));
      EXPECT_EQ(collider.counters().events, target) << "seed " << seed << ", " << per_particle << " per particle";
    }
}

// The Maxwellian theory by hand (docs/rough-spheres.md): alpha = 0.9, beta = 0, kappa = 0.4 gives
// eta = 1/7, A = 0.0475 + 6/49, B = 1/19.6, C = 45/196, theta = 0.57379195, zeta* = 0.18756517; the
// smooth limit beta = -1 is (1 - alpha^2)/3 with theta 0; alpha = beta = 1 equipartitions (theta = 1)
// and does not cool.
TEST(Rough, MaxwellianTheoryByHand) {
  const auto k = theory::rough::coefficients(0.9, 0.0, 0.4);
  EXPECT_NEAR(k.a, 0.0475 + 6.0 / 49.0, 1e-15);
  EXPECT_NEAR(k.b, 1.0 / 19.6, 1e-15);
  EXPECT_NEAR(k.c, 45.0 / 196.0, 1e-15);
  const auto hcs = theory::rough::cooling_state(0.9, 0.0, 0.4);
  EXPECT_NEAR(hcs.theta, 0.5737919536973398, 1e-13);
  EXPECT_NEAR(hcs.cooling_rate_reduced, 0.18756517321786803, 1e-13);
  const auto smooth = theory::rough::cooling_state(0.7, -1.0, 0.4);
  EXPECT_EQ(smooth.theta, 0.0);
  EXPECT_NEAR(smooth.cooling_rate_reduced, (1.0 - 0.49) / 3.0, 1e-15);
  const auto elastic = theory::rough::cooling_state(1.0, 1.0, 0.25);
  EXPECT_NEAR(elastic.theta, 1.0, 1e-14);
  EXPECT_NEAR(elastic.cooling_rate_reduced, 0.0, 1e-14);
}

// The two-temperature equations: in collisions per particle they are linear with constant
// coefficients, so T(c) = exp((4/3) M c) T(0) exactly (M = [[-A, B], [B, -C]], the closed form of a
// symmetric 2 x 2 exponential); the time-driven integration reaches the same c at its times, and the
// ratio tends to theta.
TEST(Rough, TwoTemperatureEquationsAgreeWithTheClosedForm) {
  auto mix = rough_mixture({2.0}, {1.5}, 0.8, 0.4, {0.3});
  const auto k = theory::rough::coefficients(0.8, 0.4, 0.3);
  const std::vector<double> c = {0.5, 2.0, 10.0, 40.0, 300.0};
  const auto h = theory::rough::integrate(mix, 1.0, 3.0, c, true);
  // eigen decomposition of (4/3) M
  const double p = -k.a, q = k.b, r = -k.c;
  const double mean = 0.5 * (p + r), half = std::sqrt(0.25 * (p - r) * (p - r) + q * q);
  const double l1 = mean + half, l2 = mean - half;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double e1 = std::exp(4.0 / 3.0 * l1 * c[i]), e2 = std::exp(4.0 / 3.0 * l2 * c[i]);
    // exp(tM) = [(e1 - e2) M + (l1 e2 - l2 e1) I]/(l1 - l2)
    const double f = (e1 - e2) / (l1 - l2), g = (l1 * e2 - l2 * e1) / (l1 - l2);
    const double tr = (f * p + g) * 1.0 + f * q * 3.0, rot = f * q * 1.0 + (f * r + g) * 3.0;
    EXPECT_NEAR(h.translational[i], tr, 1e-9 * tr) << "c = " << c[i];
    EXPECT_NEAR(h.rotational[i], rot, 1e-9 * rot) << "c = " << c[i];
  }
  EXPECT_NEAR(h.rotational.back() / h.translational.back(), theory::rough::cooling_state(0.8, 0.4, 0.3).theta, 1e-6);
  const auto timed = theory::rough::integrate(mix, 1.0, 3.0, h.time, false);
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(timed.collisions_per_particle[i], c[i], 1e-8 * c[i]);
}

// The rule's observables by hand (docs/rough-spheres.md, "Observables"): two particles, m = 1, sigma = 1,
// kappa = 0.4 (I = 0.1), v = (+-1, 0, 0), w = (0, 0, 2) and 0: <c^2> = <c^4> = 1, <w^2> = 2, <w^4> = 8,
// <c^2 w^2> = 2, so T_rot = 0.1 x 2/3 = 1/15, a20 = 0.6 - 1 = -0.4, a02 = 0.6 x 8/4 - 1 = 0.2, a11 = 0,
// total_energy = (1 + 0.1 x 2)/2 = 0.6; a gas without rotation writes a02 = a11 = 0.
TEST(Rough, ObservablesByHand) {
  const auto mix = rough_mixture({1.0}, {1.0}, 0.9, 0.0, {0.4});
  particles::System sys;
  sys.v = {{1.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}};
  sys.species = {0, 0};
  sys.first = {0};
  sys.count = {2};
  rules::RoughRule rule(mix);
  rule.attach(sys);
  auto& w = std::get<particles::ParticleArray<Vec3>>(sys.find_array(rules::RoughRule::angular_velocity)->values);
  w[0] = {0.0, 0.0, 2.0};
  sample::Rows rows;
  rule.measure(sys, rows);
  const auto at = [&](const char* name) { return rows.rows.at(name).second.at(0); };
  EXPECT_NEAR(at("rotational_temperature"), 1.0 / 15.0, 1e-15);
  EXPECT_NEAR(at("cumulant_a20"), -0.4, 1e-15);
  EXPECT_NEAR(at("cumulant_a02"), 0.2, 1e-15);
  EXPECT_NEAR(at("cumulant_a11"), 0.0, 1e-15);
  EXPECT_NEAR(at("total_energy"), 0.6, 1e-15);
  w[0] = {0.0, 0.0, 0.0};
  sample::Rows still;
  rule.measure(sys, still);
  EXPECT_EQ(still.rows.at("cumulant_a02").second.at(0), 0.0);
  EXPECT_EQ(still.rows.at("cumulant_a11").second.at(0), 0.0);
}

// The Sonine collisional moments (theory::rough::collisional_moments; docs/rough-spheres.md#rough_sonine)
// at alpha = 0.9, beta = 0, kappa = 0.4, theta = 0.5 (h = 2/7, q = 5/2), Maxwellian parts by hand from the
// Luding coefficients: eta = 1/7, A = 0.0475 + 6/49, B = (1/49)/0.4, C = (1/7)/0.4 (1 - (1/7)/0.4);
// d<v^2>/dc = 3 dT_tr/dc = 4(-A + B theta) and, with T_tr = 1, T_rot = theta, I = kappa/4,
// d<w^2>/dc = (3/I) dT_rot/dc = 16 q (B - C theta).
TEST(Rough, SonineMomentsMaxwellianPartsByHand) {
  const double a = 0.0475 + 6.0 / 49.0, b = 1.0 / 49.0 / 0.4, c = (1.0 / 7.0) / 0.4 * (1.0 - (1.0 / 7.0) / 0.4);
  const auto m = theory::rough::collisional_moments(0.9, 0.0, 0.4, 0.5);
  EXPECT_NEAR(m.v2.zero, 4.0 * (-a + b * 0.5), 1e-13);
  EXPECT_NEAR(m.w2.zero, 16.0 * 2.5 * (b - c * 0.5), 1e-13);
  // only the translational cumulants change <v^2> and <w^2> to this order: a02 does not enter
  EXPECT_EQ(m.v2.a02, 0.0);
  EXPECT_EQ(m.w2.a02, 0.0);
}

// beta = -1 (smooth): the rates of <v^2> and <v^4> are the smooth ones, by hand (d<v^2>/dc =
// -(1 - alpha^2)(1 + 3 a2/16); R_v4 = 2 alpha^4 + 7 alpha^2 - 9 + a2 (30 alpha^4 + 177 alpha^2 - 64 alpha
// - 271)/16, whose HCS balance R_v4 = 10 R_v2 (1 + a2) gives van Noije and Ernst's a2), the spins are
// untouched, and the white-noise a2 is van Noije and Ernst's 16(1 - alpha)(1 - 2 alpha^2)/(241 - 177 alpha
// + 30 alpha^2 - 30 alpha^3) = -0.0117913... at alpha = 0.9 (1.6 (-0.62)/84.13).
TEST(Rough, SonineSmoothLimitByHand) {
  for (double alpha : {0.3, 0.7, 0.9}) {
    const auto m = theory::rough::collisional_moments(alpha, -1.0, 0.4, 0.7);
    const double a2 = alpha * alpha, a4 = a2 * a2;
    EXPECT_NEAR(m.v2.zero, -(1.0 - a2), 1e-14);
    EXPECT_NEAR(m.v2.a20, -3.0 * (1.0 - a2) / 16.0, 1e-14);
    EXPECT_NEAR(m.v4.zero, 2.0 * a4 + 7.0 * a2 - 9.0, 1e-13);
    EXPECT_NEAR(m.v4.a20, (30.0 * a4 + 177.0 * a2 - 64.0 * alpha - 271.0) / 16.0, 1e-13);
    for (const auto* r : {&m.w2, &m.w4}) EXPECT_EQ(r->zero + std::abs(r->a20) + std::abs(r->a02) + std::abs(r->a11), 0.0);
    // the HCS balance with these rates is van Noije and Ernst's a2
    const double hcs = -(m.v4.zero - 10.0 * m.v2.zero) / (m.v4.a20 - 10.0 * m.v2.a20 - 10.0 * m.v2.zero);
    EXPECT_NEAR(hcs, 16.0 * (1.0 - alpha) * (1.0 - 2.0 * a2) / (81.0 - 17.0 * alpha + 30.0 * a2 * (1.0 - alpha)), 1e-13);
  }
  const auto wn = theory::rough::sonine_driven_state(0.9, -1.0, 0.4);
  ASSERT_TRUE(wn.state);
  EXPECT_NEAR(wn.state->cumulants.a20, 1.6 * (-0.62) / 84.13, 1e-12);
  EXPECT_NEAR(wn.state->cooling_rate_reduced, 0.19 / 3.0 * (1.0 + 3.0 / 16.0 * 1.6 * (-0.62) / 84.13), 1e-12);
}

// A second method: the 20 coefficients by Monte Carlo integration of the collision rule written out here
// (not the generated polynomials): E[Theta(g.e)(g.e) dpsi w_k] (sqrt(pi)/2) with V, g, Omega, delta
// Gaussian, e = z, the Sonine weights w_k of the header, at alpha = 0.7, beta = 0.3, kappa = 0.4,
// theta = 0.8. Ensemble 4e6 pairs (half of them approach; 400000 could not see a 2 % change of the a02
// coefficient of <w^4>), seed 12; each coefficient within 4.5 of its standard errors (20 comparisons: a
// false alarm has probability below 1e-4).
TEST(Rough, SonineMomentsAgreeWithMonteCarlo) {
  const double alpha = 0.7, beta = 0.3, kappa = 0.4, theta = 0.8, k = kappa / (1.0 + kappa), r2 = 4.0 * theta / kappa;
  const auto exact = theory::rough::collisional_moments(alpha, beta, kappa, theta);
  const std::array<const theory::rough::MomentRate*, 5> rates{&exact.v2, &exact.w2, &exact.v4, &exact.w4, &exact.v2w2};
  std::mt19937_64 gen(12);
  std::normal_distribution<double> normal;
  const auto gauss = [&](double variance) { return Vec3{std::sqrt(variance) * normal(gen), std::sqrt(variance) * normal(gen), std::sqrt(variance) * normal(gen)}; };
  const auto s1 = [](double x) { return 1.5 - x; };
  const auto s2 = [](double x) { return 15.0 / 8.0 - 2.5 * x + 0.5 * x * x; };
  const auto psi = [](const Vec3& v1, const Vec3& v2, const Vec3& w1, const Vec3& w2) {
    const double a = dot(v1, v1), b = dot(v2, v2), c = dot(w1, w1), d = dot(w2, w2);
    return std::array<double, 5>{a + b, c + d, a * a + b * b, c * c + d * d, a * c + b * d};
  };
  constexpr int kSamples = 4000000;
  std::array<std::array<double, 4>, 5> sum{}, sum2{};
  const Vec3 e{0.0, 0.0, 1.0};
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 cm = gauss(0.5), g = gauss(2.0), om = gauss(r2 / 2.0), dl = gauss(2.0 * r2);
    if (g.z <= 0.0) continue;
    const Vec3 gc = add(g, cross(e, om), -1.0);  // g - e x (w1 + w2)/2
    const Vec3 gct = add(gc, e, -gc.z);
    const Vec3 j = add(Vec3{0.0, 0.0, (1.0 + alpha) * g.z}, gct, (1.0 + beta) * k);
    const Vec3 ej = cross(e, j);
    const Vec3 v1 = add(cm, g, 0.5), v2 = add(cm, g, -0.5), w1 = add(om, dl, 0.5), w2 = add(om, dl, -0.5);
    const auto before = psi(v1, v2, w1, w2);
    const auto after = psi(add(v1, j, -0.5), add(v2, j, 0.5), add(w1, ej, -1.0 / kappa), add(w2, ej, -1.0 / kappa));
    const double c1 = dot(v1, v1) / 2.0, c2 = dot(v2, v2) / 2.0, x1 = dot(w1, w1) / (2.0 * r2), x2 = dot(w2, w2) / (2.0 * r2);
    const std::array<double, 4> weight{1.0, s2(c1) + s2(c2), s2(x1) + s2(x2), s1(c1) * s1(x1) + s1(c2) * s1(x2)};
    for (std::size_t p = 0; p < 5; ++p)
      for (std::size_t w = 0; w < 4; ++w) {
        const double y = std::sqrt(M_PI) / 2.0 * g.z * (after[p] - before[p]) * weight[w];
        sum[p][w] += y;
        sum2[p][w] += y * y;
      }
  }
  for (std::size_t p = 0; p < 5; ++p) {
    const std::array<double, 4> value{rates[p]->zero, rates[p]->a20, rates[p]->a02, rates[p]->a11};
    for (std::size_t w = 0; w < 4; ++w) {
      const double mean = sum[p][w] / kSamples, se = std::sqrt((sum2[p][w] / kSamples - mean * mean) / kSamples);
      EXPECT_LE(std::abs(mean - value[w]), 4.5 * se + 1e-12) << "moment " << p << " weight " << w << ": exact " << value[w]
                                                             << ", Monte Carlo " << mean << " +- " << se;
    }
  }
}

// The elastic perfectly rough gas (alpha = beta = 1) is in equilibrium: the Sonine HCS is theta = 1 with
// every cumulant 0 and no cooling. Where the cumulants would exceed 1 (HCS alpha = 0.5, beta = -0.5,
// kappa = 0.4: a02 about 20) the theory gives a reason, not numbers.
TEST(Rough, SonineEquilibriumAndBreakdown) {
  const auto eq = theory::rough::sonine_cooling_state(1.0, 1.0, 0.4);
  ASSERT_TRUE(eq.state) << eq.why_not;
  EXPECT_NEAR(eq.state->theta, 1.0, 1e-12);
  EXPECT_NEAR(eq.state->cumulants.a20, 0.0, 1e-12);
  EXPECT_NEAR(eq.state->cumulants.a02, 0.0, 1e-12);
  EXPECT_NEAR(eq.state->cumulants.a11, 0.0, 1e-12);
  EXPECT_NEAR(eq.state->cooling_rate_reduced, 0.0, 1e-12);
  const auto broken = theory::rough::sonine_cooling_state(0.5, -0.5, 0.4);
  EXPECT_FALSE(broken.state);
  EXPECT_NE(broken.why_not.find("breaks down"), std::string::npos) << broken.why_not;
  EXPECT_FALSE(theory::rough::sonine_cooling_state(0.9, -1.0, 0.4).state);  // smooth: not this theory
}

// Mixtures, Maxwellian (theory::rough::pair_energy_rates; docs/rough-spheres.md#rough_mixtures): the closed
// form against a Monte Carlo average of the DSMC's own rule (RoughRule::collide) over Maxwellian pairs at
// unequal temperatures, masses 1 and 3, diameters 1 and 2, kappa 0.4 and 0.25, alpha 0.8, beta 0.3:
// 4 pi E[Theta(g.e)(g.e) dE] with e = z, for both orders of every pair (8 values). Ensemble 400000 pairs,
// seed 13; each within 4.5 standard errors.
TEST(Rough, MixtureEnergyRatesAgreeWithMonteCarloOfTheRule) {
  const auto mix = rough_mixture({1.0, 3.0}, {1.0, 2.0}, 0.8, 0.3, {0.4, 0.25});
  const rules::RoughRule rule(mix);
  const std::vector<double> t{1.0, 1.7}, r{0.6, 1.2};
  auto gen = rng::make_stream(13, 0, rng::Purpose::sampling);
  const auto maxwell = [&](double variance) {
    const double s = std::sqrt(variance);
    return Vec3{s * gen.normal(), s * gen.normal(), s * gen.normal()};
  };
  for (std::size_t a = 0; a < 2; ++a)
    for (std::size_t b = 0; b < 2; ++b) {
      const auto exact = theory::rough::pair_energy_rates(mix, a, b, t, r);
      constexpr int kSamples = 400000;
      double sum_t = 0.0, sum2_t = 0.0, sum_r = 0.0, sum2_r = 0.0;
      for (int i = 0; i < kSamples; ++i) {
        Vec3 va = maxwell(t[a] / mix.mass[a]), vb = maxwell(t[b] / mix.mass[b]);
        Vec3 wa = maxwell(r[a] / mix.inertia(a)), wb = maxwell(r[b] / mix.inertia(b));
        const double g_e = va.z - vb.z;
        if (g_e <= 0.0) continue;
        const double ta = 0.5 * mix.mass[a] * dot(va, va), ra = 0.5 * mix.inertia(a) * dot(wa, wa);
        rules::RoughRule::collide(va, vb, wa, wb, rule.pair(a, b), {0.0, 0.0, 1.0, g_e, 0.0, 0.0, 1.0});
        const double dt = 4.0 * M_PI * g_e * (0.5 * mix.mass[a] * dot(va, va) - ta);
        const double dr = 4.0 * M_PI * g_e * (0.5 * mix.inertia(a) * dot(wa, wa) - ra);
        sum_t += dt, sum2_t += dt * dt, sum_r += dr, sum2_r += dr * dr;
      }
      const auto compare = [&](double sum, double sum2, double value, const char* what) {
        const double mean = sum / kSamples, se = std::sqrt((sum2 / kSamples - mean * mean) / kSamples);
        EXPECT_LE(std::abs(mean - value), 4.5 * se) << what << " of " << a << " with " << b << ": closed form " << value
                                                    << ", Monte Carlo " << mean << " +- " << se;
      };
      compare(sum_t, sum2_t, exact.translational, "translational");
      compare(sum_r, sum2_r, exact.rotational, "rotational");
    }
}

// One species is the closed form of cooling_state (theta), and two equal species split from it keep
// T_1 = T_2 and the same theta: the mixture solver by hand against the one-species closed form.
TEST(Rough, MixtureCoolingStateReducesToOneSpecies) {
  for (const double beta : {-0.5, 0.0, 0.9}) {
    const auto one = theory::rough::cooling_state(0.7, beta, 0.4);
    const auto single = theory::rough::mixture_cooling_state(rough_mixture({1.0}, {1.0}, 0.7, beta, {0.4}));
    ASSERT_EQ(single.theta.size(), 1u);
    EXPECT_NEAR(single.theta[0], one.theta, 1e-8 * one.theta);
    EXPECT_NEAR(single.translational_over_mean[0], 1.0, 1e-12);
    const auto split = theory::rough::mixture_cooling_state(rough_mixture({1.0, 1.0}, {1.0, 1.0}, 0.7, beta, {0.4, 0.4}));
    ASSERT_EQ(split.theta.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_NEAR(split.theta[k], one.theta, 1e-8 * one.theta);
      EXPECT_NEAR(split.translational_over_mean[k], 1.0, 1e-10);
    }
  }
}

// The Maxwellian equations of a mixture (integrate_mixture) are those of one species for one species, and
// for two equal species split from it (the same sums, another order of the terms).
TEST(Rough, MixtureHistoryReducesToOneSpecies) {
  const auto mix = rough_mixture({1.0}, {1.0}, 0.8, 0.2, {0.4});
  const std::vector<double> times{0.1, 1.0, 5.0};
  for (const bool by_collisions : {true, false}) {
    const auto one = theory::rough::integrate(mix, 1.0, 2.0, times, by_collisions);
    const auto many = theory::rough::integrate_mixture(mix, {1.0}, {2.0}, times, by_collisions);
    const auto split = theory::rough::integrate_mixture(rough_mixture({1.0, 1.0}, {1.0, 1.0}, 0.8, 0.2, {0.4, 0.4}), {1.0, 1.0},
                                                        {2.0, 2.0}, times, by_collisions);
    for (std::size_t i = 0; i < times.size(); ++i) {
      EXPECT_NEAR(many.translational[i][0], one.translational[i], 1e-12);
      EXPECT_NEAR(many.rotational[i][0], one.rotational[i], 1e-12);
      EXPECT_NEAR(many.time[i], one.time[i], 1e-9 * one.time[i]);
      EXPECT_NEAR(many.collisions_per_particle[i], one.collisions_per_particle[i], 1e-9 * one.collisions_per_particle[i]);
      // two species of density 0.01 each: twice the collision rate per unit time, the same per collision
      if (by_collisions) {
        EXPECT_NEAR(split.translational[i][1], one.translational[i], 1e-12);
        EXPECT_NEAR(split.rotational[i][0], one.rotational[i], 1e-12);
      }
    }
  }
}

// The mixture HCS where it is not a plain fixed point: elastic and perfectly rough (equipartition, exactly),
// a species whose spins touch nothing (beta = -1 with every species: a reason, no NaN), and a hard case for
// the solver (20 species, masses 1..2, quasi-smooth beta = -0.99), whose solution must make every
// temperature cool at one rate.
TEST(Rough, MixtureCoolingStateEdgeCases) {
  const auto elastic = theory::rough::mixture_cooling_state(rough_mixture({1.0, 3.0}, {1.0, 1.0}, 1.0, 1.0, {0.4, 0.2}));
  ASSERT_TRUE(elastic.why_not.empty()) << elastic.why_not;
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(elastic.theta[k], 1.0);
    EXPECT_EQ(elastic.translational_over_mean[k], 1.0);
  }
  auto decoupled = rough_mixture({1.0, 2.0}, {1.0, 1.0}, 0.9, -1.0, {0.4, 0.4});
  decoupled.roughness(1, 1) = 0.5;
  const auto none = theory::rough::mixture_cooling_state(decoupled);
  EXPECT_TRUE(none.theta.empty());
  EXPECT_NE(none.why_not.find("species 1 has beta = -1 with every species"), std::string::npos) << none.why_not;
  std::vector<double> mass, sigma;
  for (int k = 0; k < 20; ++k) mass.push_back(1.0 + k / 19.0), sigma.push_back(1.0);
  const auto many = rough_mixture(mass, sigma, 0.9, -0.99, std::vector<double>(20, 0.4));
  const auto hcs = theory::rough::mixture_cooling_state(many);
  ASSERT_EQ(hcs.theta.size(), 20u) << hcs.why_not;
  std::vector<double> t(20), r(20);
  for (std::size_t k = 0; k < 20; ++k) t[k] = hcs.translational_over_mean[k], r[k] = hcs.theta[k] * t[k];
  const auto history = theory::rough::integrate_mixture(many, t, r, {0.01}, true);  // one short step of the equations
  for (std::size_t k = 0; k < 20; ++k) {  // every ratio to T_1 stays put
    EXPECT_NEAR(history.translational[0][k] / history.translational[0][0], t[k] / t[0], 1e-9);
    EXPECT_NEAR(history.rotational[0][k] / history.translational[0][0], r[k] / t[0], 1e-9 * r[k] / t[0]);
  }
}

// The Sonine HCS balances written out here from the docs (rough-spheres.md#rough_sonine), independently of
// the solver's rows: at its solution for alpha = 0.7, beta = 0.5 (and 0.9, 0) the linearised
// d ln<v^4> = 2 d ln T_tr, d ln<w^4> = 2 d ln T_rot, d ln<v^2 w^2> = d ln T_tr + d ln T_rot and
// d ln T_rot = d ln T_tr hold to round-off; the white-noise balances likewise.
TEST(Rough, SonineSolutionsSatisfyTheBalancesOfTheDocs) {
  for (const auto& [alpha, beta] : {std::pair{0.7, 0.5}, std::pair{0.9, 0.0}}) {
    const double kappa = 0.4;
    const auto hcs = theory::rough::sonine_cooling_state(alpha, beta, kappa);
    ASSERT_TRUE(hcs.state) << hcs.why_not;
    const auto& st = *hcs.state;
    const auto m = theory::rough::collisional_moments(alpha, beta, kappa, st.theta);
    const double r2 = 4.0 * st.theta / kappa;  // <w_x^2> with T_tr = 1
    const double v2 = 3.0, w2 = 3.0 * r2, v4 = 15.0, w4 = 15.0 * r2 * r2, v2w2 = 9.0 * r2;  // Maxwellian moments
    const auto& x = st.cumulants;
    const double lam = m.v2.at(x) / v2, mu = m.w2.at(x) / w2, lam0 = m.v2.zero / v2, mu0 = m.w2.zero / w2;
    // R_psi/<psi> with <psi> = Maxwellian (1 + a): linearised, (R0 + R1.a)/M - 2 lam (1 + a) -> drop lam1 a
    EXPECT_NEAR(m.v4.at(x) / v4 - 2.0 * lam - 2.0 * lam0 * x.a20, 0.0, 1e-12);
    EXPECT_NEAR(m.w4.at(x) / w4 - 2.0 * mu - 2.0 * mu0 * x.a02, 0.0, 1e-12);
    EXPECT_NEAR(m.v2w2.at(x) / v2w2 - (lam + mu) - (lam0 + mu0) * x.a11, 0.0, 1e-12);
    EXPECT_NEAR(mu - lam, 0.0, 1e-12);
    EXPECT_NEAR(st.cooling_rate_reduced, -m.v2.at(x) / 3.0, 1e-14);

    const auto driven = theory::rough::sonine_driven_state(alpha, beta, kappa);
    ASSERT_TRUE(driven.state) << driven.why_not;
    const auto& d = *driven.state;
    const auto md = theory::rough::collisional_moments(alpha, beta, kappa, d.theta);
    const double chi2 = -md.v2.at(d.cumulants) / 3.0, rd = 4.0 * d.theta / kappa;
    // d<v^4>/dt: + 10 chi^2 <v^2>; d<v^2 w^2>/dt: + 3 chi^2 <w^2>; spins: nothing
    EXPECT_NEAR(md.v4.at(d.cumulants) + 10.0 * chi2 * 3.0, 0.0, 1e-12);
    EXPECT_NEAR(md.w4.at(d.cumulants) / (rd * rd), 0.0, 1e-12);
    EXPECT_NEAR(md.v2w2.at(d.cumulants) / rd + 3.0 * chi2 * 3.0, 0.0, 1e-12);
    EXPECT_NEAR(md.w2.at(d.cumulants) / rd, 0.0, 1e-12);
  }
}

// The white-noise state of a mixture (mixture_driven_state) is the one-species balance for one species, by
// hand: T^(3/2) = m chi^2/(zeta* nu_1), zeta* = (1 - alpha^2)/3 (smooth) or (4/3)(A - B^2/C) with theta = B/C
// (rough; rough.hpp driven_state), nu_1 = 4 n sigma^2 sqrt(pi/m); and two equal species split from one
// share its temperature (the noise strength is per particle).
TEST(Rough, MixtureWhiteNoiseReducesToOneSpecies) {
  const double chi2 = 0.001, nu1 = 4.0 * 0.01 * std::sqrt(M_PI);
  auto smooth = species::make_mixture({1.0}, {1.0}, {0.01}, species::PairMatrix(1, 0.9), false);
  const auto one = theory::rough::mixture_driven_state(smooth, {chi2});
  ASSERT_EQ(one.translational.size(), 1u) << one.why_not;
  EXPECT_TRUE(one.theta.empty());
  EXPECT_NEAR(one.translational[0], std::pow(chi2 / (0.19 / 3.0 * nu1), 2.0 / 3.0), 1e-9);
  const auto rough = theory::rough::mixture_driven_state(rough_mixture({1.0}, {1.0}, 0.9, 0.0, {0.4}), {chi2});
  const auto state = theory::rough::driven_state(0.9, 0.0, 0.4);
  ASSERT_EQ(rough.theta.size(), 1u) << rough.why_not;
  EXPECT_NEAR(rough.theta[0], state.theta, 1e-9);
  EXPECT_NEAR(rough.translational[0], std::pow(chi2 / (state.cooling_rate_reduced * nu1), 2.0 / 3.0), 1e-9);
  // split: two species of density 0.005 each
  auto split = species::make_mixture({1.0, 1.0}, {1.0, 1.0}, {0.005, 0.005}, species::PairMatrix(2, 0.9), false);
  const auto two = theory::rough::mixture_driven_state(split, {chi2, chi2});
  ASSERT_EQ(two.translational.size(), 2u) << two.why_not;
  for (double t : two.translational) EXPECT_NEAR(t, one.translational[0], 1e-9);
  // elastic and smooth: no steady state
  EXPECT_FALSE(theory::rough::mixture_driven_state(species::make_mixture({1.0, 2.0}, {1.0, 1.0}, {0.005, 0.005},
                                                                         species::PairMatrix(2, 1.0), false), {chi2, chi2})
                   .why_not.empty());
}
