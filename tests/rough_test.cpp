// Rough spheres (dsmc/rules.hpp RoughRule; docs/rough-spheres.md): the rule by hand and its conservation
// laws, the limits, the input, and a run of the collider on the rule.
#include <gtest/gtest.h>

#include <cmath>
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
