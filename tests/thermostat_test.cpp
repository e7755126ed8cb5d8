// Unit tests of dsmc/thermostat (Gaussian thermostat, USF streaming; \ref eta_measured "docs/shear-viscosity.md") and of the kinetic
// pressure tensor of dsmc/sample, with numbers computed by hand.
#include "dsmc/thermostat.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <tuple>

#include "dsmc/collide.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/sample.hpp"

namespace {

using gdsmc::particles::System;
using gdsmc::particles::Vec3;
namespace species = gdsmc::species;

/// One species of mass m at density n with the given velocities.
System gas(const std::vector<Vec3>& v) {
  System sys;
  sys.v.assign(v.begin(), v.end());
  sys.species.assign(v.size(), 0);
  sys.first = {0};
  sys.count = {v.size()};
  return sys;
}

species::Mixture one_species(double m, double n) {
  return species::make_mixture({m}, {1.0}, {n}, species::PairMatrix(1, 0.9), false);
}

// The white-noise kicks (docs/white-noise.md): a binary gas at rest, one stage of dt = 0.5 with chi^2 =
// 0.2 for species 1 and, by equal forces, 0.2/4 for species 2 (m = 1, 2): the total momentum stays 0 to
// round-off, each species' mean |dv|^2 is 3 chi^2_k dt (1 - m_k/M) -- 0.3 and 0.075 less the centre-of-mass
// share -- within 4 standard errors (2e5 particles each: the SE of a mean of chi^2 variables with 3 degrees
// of freedom is sqrt(2/3)/sqrt(N) of it, 0.18 %).
TEST(Thermostat, WhiteNoiseKicksKeepTheMomentumAndHaveTheirVariance) {
  const auto mix = species::make_mixture({1.0, 2.0}, {1.0, 1.0}, {0.1, 0.1}, species::PairMatrix(2, 0.9), false);
  const std::size_t n = 200000;
  System sys = gas(std::vector<Vec3>(2 * n, Vec3{0.0, 0.0, 0.0}));
  for (std::size_t i = n; i < 2 * n; ++i) sys.species[i] = 1;
  sys.first = {0, n};
  sys.count = {n, n};
  gdsmc::thermostat::WhiteNoise noise(mix, {0.2, 0.05});
  auto gen = gdsmc::rng::make_stream(4, 0, gdsmc::rng::Purpose::forcing);
  const Vec3 shift = noise.act(sys, 0.5, gen);
  for (auto& v : sys.v) v = {v.x + shift.x, v.y + shift.y, v.z + shift.z};
  double px = 0.0, py = 0.0, pz = 0.0, scale = 0.0;
  double mean2[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < 2 * n; ++i) {
    const double m = mix.mass[sys.species[i]];
    px += m * sys.v[i].x, py += m * sys.v[i].y, pz += m * sys.v[i].z;
    scale += m * std::sqrt(sys.v[i].x * sys.v[i].x + sys.v[i].y * sys.v[i].y + sys.v[i].z * sys.v[i].z);
    mean2[sys.species[i]] += (sys.v[i].x * sys.v[i].x + sys.v[i].y * sys.v[i].y + sys.v[i].z * sys.v[i].z) / n;
  }
  EXPECT_LT(std::abs(px) + std::abs(py) + std::abs(pz), 1e-12 * scale);
  const double total_mass = 3.0 * n;
  for (std::size_t k = 0; k < 2; ++k) {
    const double chi2 = k == 0 ? 0.2 : 0.05, expected = 3.0 * chi2 * 0.5 * (1.0 - mix.mass[k] / total_mass);
    EXPECT_NEAR(mean2[k], expected, 4.0 * std::sqrt(2.0 / 3.0 / n) * expected) << "species " << k + 1;
  }
}

TEST(Thermostat, RescaleRestoresTheLossAboutTheMeanFlow) {
  // u = (1, 0, 0); peculiar velocities +-1 along x: E_after = 2 (1/2)(1)^2 = 1. With E_before = 1.5 the
  // loss is 0.5, s^2 = 1.5/1 = 1.5: velocities u +- sqrt(1.5), momentum 2 kept, zeta dt = 0.5/1.5 = 1/3.
  const auto mix = one_species(1.0, 0.1);
  System sys = gas({{2.0, 0.0, 0.0}, {0.0, 0.0, 0.0}});
  const double zeta_dt = gdsmc::thermostat::rescale(mix, sys, 1.5);
  EXPECT_NEAR(zeta_dt, 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(sys.v[0].x, 1.0 + std::sqrt(1.5), 1e-15);
  EXPECT_NEAR(sys.v[1].x, 1.0 - std::sqrt(1.5), 1e-15);
  EXPECT_NEAR(sys.v[0].x + sys.v[1].x, 2.0, 1e-15);
  EXPECT_NEAR(gdsmc::thermostat::peculiar_energy(mix, sys).kinetic, 1.5, 1e-14);
}

TEST(Thermostat, PeculiarEnergyAndMeanFlowRemoval) {
  // masses 2: velocities (3, 0, 0) and (1, 2, 0): u = (2, 1, 0); peculiar (1, -1, 0), (-1, 1, 0): E = 2 * 2/2 * 2 = 4
  const auto mix = one_species(2.0, 0.1);
  System sys = gas({{3.0, 0.0, 0.0}, {1.0, 2.0, 0.0}});
  const auto e = gdsmc::thermostat::peculiar_energy(mix, sys);
  EXPECT_NEAR(e.kinetic, 4.0, 1e-14);
  EXPECT_NEAR(e.mean_flow.x, 2.0, 1e-15);
  EXPECT_NEAR(e.mean_flow.y, 1.0, 1e-15);
  gdsmc::thermostat::remove_mean_flow(mix, sys);
  EXPECT_NEAR(sys.v[0].x, 1.0, 1e-15);
  EXPECT_NEAR(sys.v[1].y, 1.0, 1e-15);
}

TEST(Thermostat, StreamingShiftsVxByMinusAVyDt) {
  System sys = gas({{1.0, 2.0, 3.0}, {0.0, -4.0, 1.0}});
  gdsmc::thermostat::stream(sys, 0.5, 0.1);  // V_x -= 0.05 V_y
  EXPECT_DOUBLE_EQ(sys.v[0].x, 0.9);
  EXPECT_DOUBLE_EQ(sys.v[1].x, 0.2);
  EXPECT_DOUBLE_EQ(sys.v[0].y, 2.0);
  EXPECT_DOUBLE_EQ(sys.v[0].z, 3.0);
}

TEST(Sample, KineticPressureTensorByHand) {
  // m = 2, n = 0.5, N = 2: P = (m n / N) sum V V = 0.5 sum V V. V = (1, 1, 0), (-1, -1, 0), u = 0:
  // P_xx = P_yy = P_xy = 0.5 * 2 = 1, the rest 0.
  const auto mix = one_species(2.0, 0.5);
  System sys = gas({{1.0, 1.0, 0.0}, {-1.0, -1.0, 0.0}});
  const auto m = gdsmc::sample::measure(mix, sys);
  const auto p = gdsmc::sample::kinetic_pressure_tensor(mix, sys, m);
  EXPECT_DOUBLE_EQ(p[0], 1.0);
  EXPECT_DOUBLE_EQ(p[1], 1.0);
  EXPECT_DOUBLE_EQ(p[2], 0.0);
  EXPECT_DOUBLE_EQ(p[3], 1.0);
  EXPECT_DOUBLE_EQ(p[4], 0.0);
  EXPECT_DOUBLE_EQ(p[5], 0.0);
  // Trace/3 = n T: T = m <V^2>/3 = 2 * 2/3 = 4/3, n T = 2/3 = (1 + 1 + 0)/3.
  EXPECT_NEAR((p[0] + p[1] + p[2]) / 3.0, 0.5 * m.total_temperature, 1e-15);
}

TEST(Thermostat, BeginStageRescalesThenStreamsInOnePass) {
  // m = 1, u = (0, 0, 0), s = 2: (1, 1, 0) -> (2, 2, 0) -> streaming a dt = 0.25: (1.5, 2, 0);
  // (-1, -1, 0) -> (-2, -2, 0) -> (-1.5, -2, 0). E = 2 * (2.25 + 4)/2 = 6.25, max |V|^2 = 6.25.
  const auto mix = one_species(1.0, 0.1);
  System sys = gas({{1.0, 1.0, 0.0}, {-1.0, -1.0, 0.0}});
  const auto start = gdsmc::thermostat::begin_stage(mix, sys, 2.0, Vec3{0.0, 0.0, 0.0}, 0.5, 0.5);
  EXPECT_DOUBLE_EQ(sys.v[0].x, 1.5);
  EXPECT_DOUBLE_EQ(sys.v[0].y, 2.0);
  EXPECT_DOUBLE_EQ(sys.v[1].x, -1.5);
  EXPECT_DOUBLE_EQ(start.kinetic, 6.25);
  EXPECT_DOUBLE_EQ(start.max_speed2[0], 6.25);
  EXPECT_DOUBLE_EQ(start.mean_flow.x, 0.0);
}

TEST(Thermostat, RescalingFromTheLossSum) {
  // E_before = 2, loss 0.5: s = sqrt(2/1.5), zeta dt = 0.25.
  const auto r = gdsmc::thermostat::gaussian_rescaling(2.0, 0.5, Vec3{0.1, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(r.scale, std::sqrt(2.0 / 1.5));
  EXPECT_DOUBLE_EQ(r.zeta_dt, 0.25);
  EXPECT_DOUBLE_EQ(r.mean_flow.x, 0.1);
  EXPECT_THROW(gdsmc::thermostat::gaussian_rescaling(1.0, 1.0, Vec3{0.0, 0.0, 0.0}), std::runtime_error);
}

// The thermostat takes the stage's loss from the collider's sum: it must equal the energy the
// particles lost, for every scheme and a mixture (\ref cm_energy "docs/collision-model.md": (1 - alpha^2) m_kj (g.e)^2/2 per collision).
TEST(Thermostat, ColliderLossSumEqualsTheEnergyLost) {
  namespace collide = gdsmc::collide;
  namespace rng = gdsmc::rng;
  const auto mix = species::make_mixture({1.0, 3.0}, {1.0, 1.4}, {0.02, 0.01}, species::PairMatrix(2, 0.7), false);
  for (auto scheme : {collide::Scheme::majorant, collide::Scheme::pairs, collide::Scheme::lowrank}) {
    auto init = rng::make_stream(9, 0, rng::Purpose::initial_state);
    System sys = gdsmc::particles::make_system(mix, {2000, 1000}, {1.0, 2.0},
                                               gdsmc::particles::InitialDistribution::maxwell, init);
    const double before = gdsmc::thermostat::peculiar_energy(mix, sys).kinetic;
    collide::Collider collider(scheme, mix, sys, rng::make_stream(9, 0, rng::Purpose::collisions), 1.0);
    collider.advance(1e300, 20000);
    const double after = gdsmc::thermostat::peculiar_energy(mix, sys).kinetic;
    EXPECT_NEAR(before - after, collider.counters().dissipated, 1e-10 * before) << static_cast<int>(scheme);
    EXPECT_GT(collider.counters().dissipated, 0.1 * before);
  }
}

}  // namespace

namespace {
// Two species, masses 1 and 3, velocities that do not sum to zero momentum.
gdsmc::species::Mixture two_species() {
  return gdsmc::species::make_mixture({1.0, 3.0}, {1.0, 1.0}, {0.1, 0.1}, gdsmc::species::PairMatrix(2, 0.9),
                                      false);
}
System two_species_gas() {
  System sys;
  sys.v = {{1.0, 2.0, -0.5}, {-0.3, 0.4, 1.1}, {0.7, -1.2, 0.2}, {0.25, 0.5, -0.75}};
  sys.species = {0, 0, 1, 1};
  sys.first = {0, 2};
  sys.count = {2, 2};
  return sys;
}
}  // namespace

// advance_frame by hand: from the identity, s = 2 about m = (1, 0, 0), then a dt = 0.1 with b_y = 0:
// S = 2, c = -0.1, b = (1 + 2 (0 - 1), 0, 0) = (-1, 0, 0). Then V = G u + b applied by materialise
// equals rescaling about m and streaming each velocity (begin_stage), and frame_energy from the
// moments and momentum of u equals the energy of the materialised velocities.
TEST(Thermostat, FrameComposesRescalingAndStreaming) {
  const auto f = gdsmc::thermostat::advance_frame(gdsmc::thermostat::Frame{}, 2.0, Vec3{1.0, 0.0, 0.0}, 0.5, 0.2);
  EXPECT_DOUBLE_EQ(f.scale, 2.0);
  EXPECT_DOUBLE_EQ(f.shear, -0.1);
  EXPECT_DOUBLE_EQ(f.offset.x, -1.0);
  EXPECT_DOUBLE_EQ(f.offset.y, 0.0);
  // A second stage: s = 0.5 about m = (0.2, 0.4, 0), a dt = 0.3: S = 1, c = -0.4,
  // b = L(m + 0.5 (b - m)) = L((-0.4, 0.2, 0)) = (-0.4 - 0.3 * 0.2, 0.2, 0) = (-0.46, 0.2, 0).
  const auto g = gdsmc::thermostat::advance_frame(f, 0.5, Vec3{0.2, 0.4, 0.0}, 1.0, 0.3);
  EXPECT_DOUBLE_EQ(g.scale, 1.0);
  EXPECT_NEAR(g.shear, -0.4, 1e-15);
  EXPECT_NEAR(g.offset.x, -0.46, 1e-15);
  EXPECT_NEAR(g.offset.y, 0.2, 1e-15);

  const auto mix = two_species();
  System by_frame = two_species_gas(), by_hand = two_species_gas();
  // moments and momentum of the stored u
  std::array<double, 4> q{};
  Vec3 p{0.0, 0.0, 0.0};
  double mass = 0.0;
  for (std::size_t i = 0; i < by_frame.size(); ++i) {
    const double m = mix.mass[by_frame.species[i]];
    const Vec3& u = by_frame.v[i];
    q[0] += m * u.x * u.x, q[1] += m * u.y * u.y, q[2] += m * u.z * u.z, q[3] += m * u.x * u.y;
    p = {p.x + m * u.x, p.y + m * u.y, p.z + m * u.z};
    mass += m;
  }
  const auto energy = gdsmc::thermostat::frame_energy(q, p, mass, g);
  const auto pass = gdsmc::thermostat::materialise(mix, by_frame, g);
  for (const auto& [scale, m, rate, dt] :
       {std::tuple{2.0, Vec3{1.0, 0.0, 0.0}, 0.5, 0.2}, std::tuple{0.5, Vec3{0.2, 0.4, 0.0}, 1.0, 0.3}})
    for (auto& v : by_hand.v) {
      v = {m.x + scale * (v.x - m.x), m.y + scale * (v.y - m.y), m.z + scale * (v.z - m.z)};
      v.x -= rate * dt * v.y;
    }
  for (std::size_t i = 0; i < by_hand.size(); ++i) {
    EXPECT_NEAR(by_frame.v[i].x, by_hand.v[i].x, 1e-14);
    EXPECT_NEAR(by_frame.v[i].y, by_hand.v[i].y, 1e-14);
    EXPECT_NEAR(by_frame.v[i].z, by_hand.v[i].z, 1e-14);
  }
  const auto exact = gdsmc::thermostat::peculiar_energy(mix, by_hand);
  EXPECT_NEAR(pass.kinetic, exact.kinetic, 1e-13);
  EXPECT_NEAR(energy.kinetic, exact.kinetic, 1e-13);
  EXPECT_NEAR(energy.mean_flow.x, exact.mean_flow.x, 1e-14);
  EXPECT_NEAR(energy.mean_flow.y, exact.mean_flow.y, 1e-14);
  EXPECT_NEAR(energy.mean_flow.z, exact.mean_flow.z, 1e-14);
  EXPECT_NEAR(pass.total_mass, 8.0, 1e-15);
  // the pass's moments are those of the new velocities
  double xy = 0.0;
  for (std::size_t i = 0; i < by_hand.size(); ++i) xy += mix.mass[by_hand.species[i]] * by_hand.v[i].x * by_hand.v[i].y;
  EXPECT_NEAR(pass.moments[3], xy, 1e-13);
}

namespace {

/// A forcing that kicks every particle at each stage's start: +kick along x, plus a random normal
/// kick of size `noise` per component from the forcings' stream (the door a white-noise forcing uses).
class Kick final : public gdsmc::thermostat::Forcing {
 public:
  Kick(double kick, double noise) : kick_(kick), noise_(noise) {}
  const char* name() const override { return "kick"; }
  void compose(gdsmc::thermostat::Rescaling&, double&) override {}
  bool acts_on_particles() const override { return true; }
  Vec3 act(System& sys, double dt, gdsmc::rng::Xoshiro256pp& gen) override {
    for (auto& v : sys.v) v = {v.x + kick_ + noise_ * gen.normal(), v.y + noise_ * gen.normal(), v.z + noise_ * gen.normal()};
    ++acts;
    times.push_back(dt);
    return {0.0, 0.0, 0.0};
  }
  void end_stage(const StageEnd&) override {}
  void measure(const Sample&, gdsmc::sample::Rows& rows) override { rows.add("kicks", 1, {static_cast<double>(acts)}); }
  void finish(gdsmc::sample::Rows&) const override {}
  void save(gdsmc::state::Record& r) const override { r.put_integer("kick/acts", acts); }
  void restore(const gdsmc::state::Record& r) override { acts = r.integer("kick/acts"); }
  std::uint64_t acts = 0;
  std::vector<double> times;  ///< the dt of each act()

 private:
  double kick_, noise_;
};

/// A run of `stages` stages of `Stages` with one Kick forcing on a one-species gas of 2000 particles.
struct KickedGas {
  species::Mixture mix = one_species(1.0, 0.01);
  System sys;
  gdsmc::collide::Collider collider;
  gdsmc::thermostat::Stages stages;
  Kick* kick;
  KickedGas(double kick_size, double noise)
      : sys([this] {
          auto gen = gdsmc::rng::make_stream(3, 0, gdsmc::rng::Purpose::initial_state);
          return gdsmc::particles::make_system(mix, {2000}, {1.0}, gdsmc::particles::InitialDistribution::maxwell, gen);
        }()),
        collider(gdsmc::collide::Scheme::majorant, mix, sys, gdsmc::rng::make_stream(3, 0, gdsmc::rng::Purpose::collisions), 1.0),
        stages(mix, sys, collider, forcings(kick_size, noise), 0.125, 0.0, false,
               gdsmc::rng::make_stream(3, 0, gdsmc::rng::Purpose::forcing)) {
    collider.velocities_changed();
  }
  std::vector<std::unique_ptr<gdsmc::thermostat::Forcing>> forcings(double kick_size, double noise) {
    std::vector<std::unique_ptr<gdsmc::thermostat::Forcing>> f;
    f.push_back(std::make_unique<Kick>(kick_size, noise));
    kick = static_cast<Kick*>(f.back().get());
    return f;
  }
  void run(int n) {
    for (int s = 0; s < n; ++s) {
      const double end = stages.stage_end(1e30);
      stages.begin(end - collider.time(), false);
      stages.end(end);
    }
  }
  Vec3 mean_velocity() const {
    Vec3 m{0.0, 0.0, 0.0};
    for (const auto& v : sys.v) m = {m.x + v.x, m.y + v.y, m.z + v.z};
    const double n = static_cast<double>(sys.size());
    return {m.x / n, m.y / n, m.z / n};
  }
};

}  // namespace

// The stages' door for a forcing that acts on each particle (thermostat.hpp Forcing::act): called once
// per stage, after a pass that applies the frame, with the replica's stream of forcings. A kick of
// +0.25 along x per stage raises the mean velocity by exactly 0.25 a stage (the collisions conserve
// momentum: to 1e-12 after 20 stages); the random kicks come from the stream (seed, replica,
// forcing): two gases of the same seed agree bit for bit, and a gas restored from a saved record
// continues as the one that was not stopped.
TEST(Stages, AForcingActsOnEveryParticleOncePerStage) {
  KickedGas g(0.25, 0.0);
  const Vec3 before = g.mean_velocity();
  g.run(20);
  EXPECT_EQ(g.kick->acts, 20u);
  EXPECT_NEAR(g.mean_velocity().x - before.x, 20 * 0.25, 1e-12);
  EXPECT_NEAR(g.mean_velocity().y - before.y, 0.0, 1e-12);
  EXPECT_EQ(g.stages.count(), 20.0);
  EXPECT_GT(g.collider.counters().events, 0u);

  KickedGas a(0.0, 0.1), b(0.0, 0.1);
  a.run(5);
  b.run(5);
  gdsmc::state::Record saved;
  gdsmc::particles::save(b.sys, saved);
  b.collider.save(saved);
  b.stages.save(saved);
  EXPECT_EQ(saved.integer("kick/acts"), 5u);
  a.run(5);
  KickedGas c(0.0, 0.1);
  gdsmc::particles::restore(c.sys, saved);
  c.collider.restore(saved);
  c.stages.restore(saved);
  c.run(5);
  for (std::size_t i = 0; i < a.sys.size(); ++i) ASSERT_EQ(a.sys.v[i], c.sys.v[i]) << "particle " << i;
  EXPECT_EQ(c.kick->acts, 10u);
  gdsmc::sample::Rows rows;
  c.stages.begin(0.1, true);
  c.stages.measure(gdsmc::sample::measure(c.mix, c.sys), 0.1, true, rows);
  // A sampled stage: the last stage's second half acts before the sample (11 acts), this stage's first half
  // after it (12).
  EXPECT_EQ(rows.rows.at("kicks").second, std::vector<double>{11.0});
  EXPECT_EQ(c.kick->acts, 12u);
  EXPECT_EQ(rows.rows.count("pressure_tensor"), 1u);
}

// Strang's splitting of a forcing's action (thermostat.hpp, "Forcings that act on each particle"): the
// first stage's first half at its start, (dt_{k-1} + dt_k)/2 between stages k-1 and k, and at a sample
// dt_{k-1}/2 before it and dt_k/2 after it; so the actions up to a sample add up to its time exactly,
// and a record saved between stages carries the half still owed.
TEST(Stages, AForcingActsHalfAStageAtEachEndAndASampleSitsBetweenTheHalves) {
  KickedGas g(0.0, 0.0);
  std::vector<double> dt;
  for (int s = 0; s < 4; ++s) {
    const double end = g.stages.stage_end(1e30);
    dt.push_back(end - g.collider.time());
    g.stages.begin(dt.back(), false);
    g.stages.end(end);
  }
  ASSERT_EQ(g.kick->times.size(), 4u);
  EXPECT_EQ(g.kick->times[0], dt[0] / 2.0);
  for (std::size_t k = 1; k < 4; ++k) EXPECT_EQ(g.kick->times[k], dt[k - 1] / 2.0 + dt[k] / 2.0) << "stage " << k;
  gdsmc::state::Record saved;
  g.stages.save(saved);
  EXPECT_EQ(saved.real("stages/pending_act"), dt[3] / 2.0);
  gdsmc::sample::Rows rows;
  g.stages.begin(0.3, true);
  EXPECT_EQ(g.kick->times.size(), 5u);  // before the sample: the last stage's second half
  EXPECT_EQ(g.kick->times[4], dt[3] / 2.0);
  g.stages.measure(gdsmc::sample::measure(g.mix, g.sys), 0.3, true, rows);
  ASSERT_EQ(g.kick->times.size(), 6u);  // after it: this stage's first half
  EXPECT_EQ(g.kick->times[5], 0.15);
  double total = 0.0;
  for (std::size_t k = 0; k < 5; ++k) total += g.kick->times[k];
  EXPECT_NEAR(total, g.collider.time(), 1e-12 * g.collider.time());
}

// The shear state (thermostat.hpp ShearFlow; docs/output.md "The shear state"): each replica's time average, from
// average_from on and without the first sample, of a* = a eta_0(T)/(n T) and P_ij/(n T) with T = tr P^k/(3 n) at the
// middle of the streaming jump (not the sample's temperature, taken after it). By hand: n = 0.01, a = 0.02, eta_0(T)
// = 2 sqrt(T) (a stand-in), two averaged samples with tr P^k/3 = 0.004 and 0.0025 (T = 0.4, 0.25).
TEST(ShearFlow, TheShearStateAveragesAStarAndStressesAtTheMiddleOfTheJump) {
  gdsmc::thermostat::ShearFlow shear(0.02, 10.0, 0.01, false, [](double t) { return 2.0 * std::sqrt(t); });
  gdsmc::sample::Rows rows;
  using Sample = gdsmc::thermostat::Forcing::Sample;
  const auto sample = [](double time, double p, bool averaged) {
    Sample s;
    s.time = time;
    s.total_temperature = 123.0;  // (after the jump: must not enter the shear state)
    s.kinetic = {1.4 * p, 0.76 * p, 0.84 * p, -0.5 * p, 0.0, 0.0};
    s.pressure = s.kinetic;
    s.averaged = averaged;
    return s;
  };
  shear.measure(sample(5.0, 0.003, true), rows);    // before average_from: not averaged
  shear.measure(sample(10.0, 0.004, true), rows);   // T = 0.4: a* = 0.02 * 2 sqrt(0.4)/0.004
  shear.measure(sample(20.0, 0.0025, true), rows);  // T = 0.25: a* = 0.02 * 2 * 0.5/0.0025
  shear.finish(rows);
  const auto& state = rows.rows.at("shear_state_average");
  ASSERT_EQ(state.first, 5u);
  ASSERT_EQ(state.second.size(), 5u);
  EXPECT_NEAR(state.second[0], 0.5 * (0.04 * std::sqrt(0.4) / 0.004 + 0.04 * 0.5 / 0.0025), 1e-12);
  EXPECT_NEAR(state.second[1], 1.4, 1e-12);
  EXPECT_NEAR(state.second[2], 0.76, 1e-12);
  EXPECT_NEAR(state.second[3], 0.84, 1e-12);
  EXPECT_NEAR(state.second[4], -0.5, 1e-12);
}
