// Unit tests of dsmc/agg_frag: one collision per outcome with numbers computed by hand, the exact
// invariants over many events (\ref af_observables "docs/agg-frag.md"), bounds, and the checkpoint state.
#include "dsmc/agg_frag.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

namespace {

using Cluster = gdsmc::agg_frag::Gas::Cluster;
using gdsmc::agg_frag::Event;
using gdsmc::agg_frag::Gas;
using gdsmc::agg_frag::Model;
using gdsmc::agg_frag::Outcome;
using gdsmc::particles::Vec3;
namespace rng = gdsmc::rng;

constexpr double kInf = std::numeric_limits<double>::infinity();

Model model(double e_agg, double e_frag, double eps_f, double alpha) {
  Model m;
  m.monomer_mass = 1.0;
  m.monomer_diameter = 1.0;
  m.monomer_density = 0.1;
  m.restitution = alpha;
  m.aggregation_energy = e_agg;
  m.fragmentation_energy = e_frag;
  m.fragment_restitution = eps_f;
  return m;
}

Gas two_clusters(const Model& m, std::uint32_t k, Vec3 va, std::uint32_t j, Vec3 vb) {
  return Gas(m, {k, j}, {va, vb}, rng::make_stream(7, 0, rng::Purpose::collisions), 1.0);
}

/// Collides the two clusters of a two_clusters gas.
Event collide_both(Gas& gas, std::uint32_t k, std::uint32_t j) {
  return gas.collide(Cluster{k, 0}, Cluster{j, k == j ? 1u : 0u});
}

/// Every velocity of the gas (size by size, in list order) with its size.
std::vector<std::pair<std::uint32_t, Vec3>> all_clusters(const Gas& gas) {
  std::vector<std::pair<std::uint32_t, Vec3>> out;
  for (std::uint32_t k = 1; k <= gas.largest_size_reached(); ++k)
    for (std::uint32_t p = 0; p < gas.count(k); ++p) out.push_back({k, gas.velocity(Cluster{k, p})});
  return out;
}

TEST(AggFrag, ThresholdsAreEnergiesAndMonomerPairsNeverShatter) {
  const Model m = model(0.5, 1.5, 0.5, 0.8);
  EXPECT_TRUE(gdsmc::agg_frag::sticks(m, 0.49));
  EXPECT_FALSE(gdsmc::agg_frag::sticks(m, 0.5));
  EXPECT_TRUE(gdsmc::agg_frag::shatters(m, 1, 2, 1.51));
  EXPECT_FALSE(gdsmc::agg_frag::shatters(m, 1, 2, 1.5));
  EXPECT_FALSE(gdsmc::agg_frag::shatters(m, 1, 1, 100.0));  // nothing to split into
}

TEST(AggFrag, AggregationMakesOneClusterAtTheCentreOfMassVelocity) {
  // Monomer at (3, 0, 0) meets a dimer at rest: m_kj = 2/3, g^2 = 9, E_imp = 3 < E_agg = 5.
  // V = (1 * 3 + 2 * 0)/3 = (1, 0, 0); energy before 4.5, after 3 * 1/2 = 1.5, lost exactly E_imp = 3.
  Gas gas = two_clusters(model(5.0, kInf, 1.0, 0.8), 1, {3.0, 0.0, 0.0}, 2, {0.0, 0.0, 0.0});
  const Event e = collide_both(gas, 1, 2);
  EXPECT_EQ(e.outcome, Outcome::aggregation);
  EXPECT_DOUBLE_EQ(e.impact_energy, 3.0);
  ASSERT_EQ(gas.clusters(), 1u);
  EXPECT_EQ(gas.count(3), 1u);
  EXPECT_EQ(gas.count(1), 0u);
  EXPECT_EQ(gas.count(2), 0u);
  EXPECT_DOUBLE_EQ(gas.velocity(Cluster{3, 0}).x, 1.0);
  EXPECT_DOUBLE_EQ(gas.velocity(Cluster{3, 0}).y, 0.0);
  EXPECT_DOUBLE_EQ(gas.kinetic_energy(), 1.5);
  EXPECT_DOUBLE_EQ(gas.counters().dissipated, 3.0);
  EXPECT_EQ(gas.counters().aggregations, 1u);
  EXPECT_TRUE(gas.bounds_hold());
}

TEST(AggFrag, FragmentationOfAnOddNumberOfMonomers) {
  // Dimer at (2, 0, 0) and trimer at (-1, 0, 0): m_kj = 6/5, g = 3, E_imp = 5.4 > E_agg = 0; any
  // normal energy > E_frag = 0 shatters into K = 5 monomers. V = (4 - 3)/5 = 0.2 along x;
  // u = sqrt(6) * 0.5 * 3/5 = 0.734846923; energy after 5 * 0.04/2 + 0.25 * 5.4 = 1.45,
  // before 4 + 1.5 = 5.5, lost (1 - 0.25) * 5.4 = 4.05.
  Gas gas = two_clusters(model(0.0, 0.0, 0.5, 0.8), 2, {2.0, 0.0, 0.0}, 3, {-1.0, 0.0, 0.0});
  const Event e = collide_both(gas, 2, 3);
  EXPECT_EQ(e.outcome, Outcome::fragmentation);
  ASSERT_EQ(gas.clusters(), 5u);
  EXPECT_EQ(gas.count(1), 5u);
  const double u = std::sqrt(6.0) * 0.5 * 3.0 / 5.0;
  for (const auto& [size, v] : all_clusters(gas)) {
    EXPECT_EQ(size, 1u);
    EXPECT_NEAR(std::hypot(v.x - 0.2, v.y, v.z), u, 1e-14);
  }
  const Vec3 p = gas.momentum();
  EXPECT_NEAR(p.x, 1.0, 1e-14);
  EXPECT_NEAR(p.y, 0.0, 1e-14);
  EXPECT_NEAR(p.z, 0.0, 1e-14);
  EXPECT_NEAR(gas.kinetic_energy(), 1.45, 1e-13);
  EXPECT_NEAR(gas.counters().dissipated, 4.05, 1e-14);
  EXPECT_TRUE(gas.bounds_hold());
}

TEST(AggFrag, FragmentationOfAnEvenNumberOfMonomers) {
  // Monomer (0, 0, 4) and trimer at rest: m_kj = 3/4, g = 4, E_imp = 6; K = 4, V = (0, 0, 1),
  // u = sqrt(3) * 1 * 4/4 = sqrt(3); eps_f = 1: energy after 4 * 1/2 + 6 = 8 = before (4 * 4/2... = 8).
  Gas gas = two_clusters(model(0.0, 0.0, 1.0, 0.8), 1, {0.0, 0.0, 4.0}, 3, {0.0, 0.0, 0.0});
  const Event e = collide_both(gas, 1, 3);
  EXPECT_EQ(e.outcome, Outcome::fragmentation);
  ASSERT_EQ(gas.count(1), 4u);
  for (const auto& [size, v] : all_clusters(gas)) {
    EXPECT_EQ(size, 1u);
    EXPECT_NEAR(std::hypot(v.x, v.y, v.z - 1.0), std::sqrt(3.0), 1e-14);
  }
  EXPECT_NEAR(gas.momentum().z, 4.0, 1e-14);
  EXPECT_NEAR(gas.kinetic_energy(), 8.0, 1e-13);
  EXPECT_DOUBLE_EQ(gas.counters().dissipated, 0.0);
}

TEST(AggFrag, BounceFollowsTheCollisionRule) {
  // Monomer (1, 2, 0) and dimer (-1, 0, 0.5), alpha = 0.8, no sticking (E_agg = 0) and no
  // fragmentation: (g'.e) = -alpha (g.e), momentum kept, energy lost (1 - alpha^2) m_kj (g.e)^2/2.
  const Vec3 va{1.0, 2.0, 0.0}, vb{-1.0, 0.0, 0.5};
  Gas gas = two_clusters(model(0.0, kInf, 1.0, 0.8), 1, va, 2, vb);
  const double before = gas.kinetic_energy();
  const Event e = collide_both(gas, 1, 2);
  EXPECT_EQ(e.outcome, Outcome::bounce);
  const double g_dot_e = (va.x - vb.x) * e.ex + (va.y - vb.y) * e.ey + (va.z - vb.z) * e.ez;
  EXPECT_GT(g_dot_e, 0.0);
  EXPECT_NEAR(e.normal_energy, 0.5 * (2.0 / 3.0) * g_dot_e * g_dot_e, 1e-14);
  const Vec3 a = gas.velocity(Cluster{1, 0}), b = gas.velocity(Cluster{2, 0});
  const double after_dot_e = (a.x - b.x) * e.ex + (a.y - b.y) * e.ey + (a.z - b.z) * e.ez;
  EXPECT_NEAR(after_dot_e, -0.8 * g_dot_e, 1e-14);
  EXPECT_NEAR(a.x + 2.0 * b.x, va.x + 2.0 * vb.x, 1e-14);
  EXPECT_NEAR(a.y + 2.0 * b.y, va.y + 2.0 * vb.y, 1e-14);
  EXPECT_NEAR(a.z + 2.0 * b.z, va.z + 2.0 * vb.z, 1e-14);
  EXPECT_NEAR(before - gas.kinetic_energy(), (1.0 - 0.64) * e.normal_energy, 1e-14);
  EXPECT_EQ(gas.clusters(), 2u);
}

TEST(AggFrag, TwoMonomersBounceWhateverTheirEnergy) {
  Gas gas = two_clusters(model(0.0, 0.0, 0.5, 1.0), 1, {10.0, 0.0, 0.0}, 1, {-10.0, 0.0, 0.0});
  EXPECT_EQ(collide_both(gas, 1, 1).outcome, Outcome::bounce);
  EXPECT_EQ(gas.count(1), 2u);
}

// Exact invariants over > 1e6 events with all three outcomes active (\ref af_observables "docs/agg-frag.md" bookkeeping):
// sum_k k N_k = N_0 exactly, momentum zero to round-off, E(t) + dissipated = E(0) to 1e-10 E(0),
// and the speed bounds hold after every chunk. E_agg = 0.2, E_frag = 1.0 at T_0 = 2 keep all three
// outcomes frequent; eps_f = 0.9 and alpha = 0.98 slow the cooling (the gas would otherwise stick
// into a few large clusters well before 1e6 events).
TEST(AggFrag, ExactInvariantsOverAMillionEvents) {
  const Model m = model(0.2, 1.0, 0.9, 0.98);
  const std::size_t n0 = 20000;
  Gas gas(m, n0, 2.0, gdsmc::particles::InitialDistribution::maxwell, rng::make_stream(3, 0, rng::Purpose::initial_state),
          rng::make_stream(3, 0, rng::Purpose::collisions), 1.0);
  const double e0 = gas.kinetic_energy();
  double momentum_scale = 0.0;  // sum m |v|: the scale of round-off in the total momentum
  for (const auto& [size, v] : all_clusters(gas)) momentum_scale += gas.mass(size) * std::hypot(v.x, v.y, v.z);
  for (std::uint64_t target = 100000; target <= 1100000; target += 100000) {
    ASSERT_TRUE(gas.advance(kInf, target));
    std::size_t monomers = 0;
    for (std::size_t k = 1; k <= gas.largest_size_reached(); ++k) monomers += k * gas.count(k);
    ASSERT_EQ(monomers, n0);
    const Vec3 p = gas.momentum();
    EXPECT_LT(std::hypot(p.x, p.y, p.z), 1e-12 * momentum_scale);
    EXPECT_NEAR(gas.kinetic_energy() + gas.counters().dissipated, e0, 1e-10 * e0);
    EXPECT_TRUE(gas.bounds_hold());
  }
  const auto& c = gas.counters();
  EXPECT_GE(c.events, 1000000u);
  EXPECT_GT(c.aggregations, 20000u) << "aggregations";
  EXPECT_GT(c.fragmentations, 10000u) << "fragmentations";
  EXPECT_GT(c.events - c.aggregations - c.fragmentations, 500000u) << "bounces";
}

TEST(AggFrag, OneClusterLeftStopsTheClock) {
  // Two monomers that must stick: after that one cluster is left and advance() returns at t_target
  // (its self pair is still in the majorant and must not be drawn forever).
  Gas gas = two_clusters(model(1e9, kInf, 1.0, 0.8), 1, {1.0, 0.0, 0.0}, 1, {-1.0, 0.0, 0.0});
  EXPECT_FALSE(gas.advance(1e6));
  EXPECT_EQ(gas.clusters(), 1u);
  EXPECT_EQ(gas.time(), 1e6);
}

TEST(AggFrag, RestoredStateContinuesBitwise) {
  const Model m = model(0.3, 1.2, 0.6, 0.9);
  auto make = [&] {
    return Gas(m, 3000, 1.5, gdsmc::particles::InitialDistribution::maxwell,
               rng::make_stream(5, 1, rng::Purpose::initial_state), rng::make_stream(5, 1, rng::Purpose::collisions), 1.0);
  };
  Gas reference = make();
  reference.advance(kInf, 20000);
  const Gas::State saved = reference.state();
  reference.advance(40.0);
  Gas resumed = make();
  resumed.restore(saved);
  resumed.advance(40.0);
  ASSERT_EQ(resumed.clusters(), reference.clusters());
  EXPECT_EQ(resumed.counters().events, reference.counters().events);
  EXPECT_EQ(resumed.time(), reference.time());
  EXPECT_EQ(all_clusters(resumed), all_clusters(reference));
}

// Cache blocks (agg_frag.hpp, "Cache blocks"): the blocked gas samples the same process as the
// unblocked one. 48 replicas each (independent seeds) of 16384 monomers at T_0 = 0.5 in 8 blocks of
// 2048, all three outcomes active (E_agg = 0.3, E_frag = 0.6, eps_f = 0.9, alpha = 0.9), to t = 8 (about
// 3 collisions per monomer), blocked in two ways: in 8 calls (a blocked step ends at each, so the gas is
// dealt 8 times) and in one (one blocked step, cut at t = 8 after about 15 of its block_steps mean free
// times: products meet only their block's members all along). N_1, N, aggregations, fragmentations and the kinetic energy of each agree
// with the unblocked runs' within 4 combined standard errors. The blocks' own effect is of order 1/n_b =
// 5e-4 relative; the standard errors are 0.03 % (kinetic energy) to 0.5 % (fragmentations).
TEST(AggFrag, BlockedMatchesUnblocked) {
  const Model m = model(0.3, 0.6, 0.9, 0.9);
  constexpr std::size_t n0 = 16384, replicas = 48;
  constexpr int observables = 5, modes = 3;  // unblocked, blocked in 8 calls, blocked in one
  const char* names[observables] = {"N_1", "N", "aggregations", "fragmentations", "kinetic energy"};
  const char* mode_names[modes] = {"unblocked", "8 steps", "one step"};
  double sum[modes][observables] = {}, sum2[modes][observables] = {};
  std::uint64_t blocked_steps[modes] = {};
  for (int mode = 0; mode < modes; ++mode)
    for (std::size_t r = 0; r < replicas; ++r) {
      // different seeds for the three sets: independent samples
      Gas gas(m, n0, 0.5, gdsmc::particles::InitialDistribution::maxwell,
              rng::make_stream(11 + mode, r, rng::Purpose::initial_state),
              rng::make_stream(11 + mode, r, rng::Purpose::collisions), 1.0);
      if (mode > 0) gas.use_blocks(2048);
      if (mode == 1)
        for (double t = 1.0; t <= 8.0; t += 1.0) gas.advance(t);
      else
        gas.advance(8.0);
      blocked_steps[mode] += gas.blocked_steps();
      const double x[observables] = {static_cast<double>(gas.count(1)), static_cast<double>(gas.clusters()),
                                     static_cast<double>(gas.counters().aggregations),
                                     static_cast<double>(gas.counters().fragmentations), gas.kinetic_energy()};
      for (int q = 0; q < observables; ++q) sum[mode][q] += x[q], sum2[mode][q] += x[q] * x[q];
    }
  EXPECT_EQ(blocked_steps[0], 0u);
  EXPECT_GE(blocked_steps[1], 8 * replicas) << "each call must have run a blocked step";
  EXPECT_GE(blocked_steps[2], replicas) << "the one-call runs must have run a blocked step";
  for (int mode = 1; mode < modes; ++mode)
    for (int q = 0; q < observables; ++q) {
      double mean[2], se2[2];
      for (int b = 0; b < 2; ++b) {
        const int set = b == 0 ? 0 : mode;
        mean[b] = sum[set][q] / replicas;
        se2[b] = (sum2[set][q] / replicas - mean[b] * mean[b]) / (replicas - 1);
      }
      const double se = std::sqrt(se2[0] + se2[1]);
      std::printf("%-15s blocked (%s) %.6g, unblocked %.6g (48 + 48 replicas), combined SE %.3g: %.2f SE (limit 4)\n",
                  names[q], mode_names[mode], mean[1], mean[0], se, (mean[1] - mean[0]) / se);
      EXPECT_LT(std::abs(mean[1] - mean[0]), 4.0 * se)
          << names[q] << ": blocked (" << mode_names[mode] << ") " << mean[1] << ", unblocked " << mean[0]
          << ", combined SE " << se;
    }
}

// Event targets in blocks of small gases (agg_frag.hpp, "Cache blocks"; target_step_candidates), each
// target run as the run layer does (Clusters::advance_to_sample: a blocked step per call): 300 replicas of
// 128 monomers in 2 blocks of 64, step_fraction 0.1 (short whole-gas steps, whose first may make no event
// at all), ten targets 0.3 collisions per monomer apart; and 40 replicas of 1024 monomers in blocks of 64,
// step_fraction 0.05, ten targets 1.0 apart. Every target is met exactly and no blocked step passes one.
// The first set guards the acceptance's first estimate: taken from the run's first few events (0 after a first
// whole-gas step without an event), it lets such gases pass a target.
TEST(AggFrag, SmallBlockedGasesMeetEveryEventTarget) {
  const Model m = model(0.3, 0.6, 0.9, 0.9);
  struct Case {
    std::size_t monomers, replicas;
    double step_fraction, target_spacing;
    int targets;
  };
  for (const Case c : {Case{128, 300, 0.1, 0.3, 10}, Case{1024, 40, 0.05, 1.0, 10}}) {
    std::uint64_t blocked_steps = 0;
    for (std::size_t r = 0; r < c.replicas; ++r) {
      Gas gas(m, c.monomers, 0.5, gdsmc::particles::InitialDistribution::maxwell,
              rng::make_stream(100 + r, 0, rng::Purpose::initial_state),
              rng::make_stream(100 + r, 0, rng::Purpose::collisions), c.step_fraction);
      gas.use_blocks(64);
      for (int i = 1; i <= c.targets && gas.clusters() >= 2; ++i) {
        const auto target =
            static_cast<std::uint64_t>(std::ceil(c.target_spacing * i * static_cast<double>(c.monomers) / 2.0));
        while (gas.counters().events < target && gas.clusters() >= 2) {
          const double t_stop = gas.blocks() > 1 ? gas.block_step_end() : kInf;
          ASSERT_NO_THROW(gas.advance(t_stop, target)) << c.monomers << " monomers, replica " << r << ", target " << target;
        }
        if (gas.clusters() >= 2) {
          ASSERT_EQ(gas.counters().events, target) << c.monomers << " monomers, replica " << r;
        }
      }
      blocked_steps += gas.blocked_steps();
    }
    std::printf("%zu monomers: %llu blocked steps in %zu replicas\n", c.monomers,
                static_cast<unsigned long long>(blocked_steps), c.replicas);
    if (c.monomers == 1024) {
      EXPECT_GE(blocked_steps, c.replicas) << "the larger gases must have run blocked steps";
    }
  }
}

// The blocks of a step on 1 or 2 threads: the same clusters, counters and time bit for bit; the
// exact invariants hold across blocked steps; an event target is met exactly.
TEST(AggFrag, BlockThreadsAreBitwiseTheSameAndTargetsExact) {
  const Model m = model(0.2, 1.0, 0.9, 0.98);
  auto make = [&](int threads) {
    Gas gas(m, 20000, 2.0, gdsmc::particles::InitialDistribution::maxwell,
            rng::make_stream(4, 2, rng::Purpose::initial_state), rng::make_stream(4, 2, rng::Purpose::collisions), 1.0);
    gas.use_blocks(2500, threads);
    return gas;
  };
  Gas one = make(1), two = make(2);
  EXPECT_EQ(one.blocks(), 8u);
  const double e0 = one.kinetic_energy();
  ASSERT_TRUE(one.advance(kInf, 40000));
  ASSERT_TRUE(two.advance(kInf, 40000));
  EXPECT_EQ(one.counters().events, 40000u);
  EXPECT_GT(one.blocked_steps(), 0u);
  one.advance(6.0);
  two.advance(6.0);
  EXPECT_GT(one.blocked_steps(), 2u);
  EXPECT_EQ(one.time(), two.time());
  EXPECT_EQ(one.counters().events, two.counters().events);
  EXPECT_EQ(one.counters().candidates, two.counters().candidates);
  EXPECT_EQ(one.counters().dissipated, two.counters().dissipated);
  EXPECT_EQ(all_clusters(one), all_clusters(two));
  std::size_t monomers = 0;
  for (std::size_t k = 1; k <= one.largest_size_reached(); ++k) monomers += k * one.count(k);
  EXPECT_EQ(monomers, 20000u);
  EXPECT_NEAR(one.kinetic_energy() + one.counters().dissipated, e0, 1e-10 * e0);
  EXPECT_TRUE(one.bounds_hold());
  EXPECT_GT(one.counters().fragmentations, 0u);
}

// The deal and the bounds' pass share the threads of the blocks (agg_frag.cpp, deal_blocks and
// recompute_bounds): with lists long enough for both (140000 monomers, over 2 MiB: dealt in chunks of
// 2 MiB; over 2^16 clusters: the bounds' pass in parts), 7 blocks on 1, 2 and 3 threads (3 owning 3, 2 and 2
// blocks) make the same gas, bit for bit, over two blocked steps.
TEST(AggFrag, LongListsAreDealtAndBoundedAlikeOnAnyThreadCount) {
  const Model m = model(0.2, 1.0, 0.9, 0.98);
  auto run = [&](int threads) {
    Gas gas(m, 140000, 2.0, gdsmc::particles::InitialDistribution::maxwell,
            rng::make_stream(6, 1, rng::Purpose::initial_state), rng::make_stream(6, 1, rng::Purpose::collisions), 1.0);
    gas.use_blocks(20000, threads);
    gas.advance(gas.block_step_end());
    gas.advance(gas.block_step_end());
    return gas;
  };
  const Gas one = run(1);
  EXPECT_EQ(one.blocked_steps(), 2u);
  EXPECT_GT(one.counters().aggregations, 0u);
  EXPECT_TRUE(one.bounds_hold());
  for (int threads : {2, 3}) {
    const Gas other = run(threads);
    EXPECT_EQ(other.time(), one.time()) << threads;
    EXPECT_EQ(other.counters().events, one.counters().events) << threads;
    EXPECT_EQ(other.counters().candidates, one.counters().candidates) << threads;
    EXPECT_EQ(all_clusters(other), all_clusters(one)) << threads;
    EXPECT_EQ(other.candidate_rate(), one.candidate_rate()) << threads;
  }
}

// A checkpoint between blocked steps continues bit for bit (the blocks' streams are keyed by draws
// of the gas's own stream, which the State holds).
TEST(AggFrag, BlockedRestoredStateContinuesBitwise) {
  const Model m = model(0.3, 1.2, 0.6, 0.9);
  auto make = [&] {
    Gas gas(m, 12000, 1.5, gdsmc::particles::InitialDistribution::maxwell,
            rng::make_stream(5, 3, rng::Purpose::initial_state), rng::make_stream(5, 3, rng::Purpose::collisions), 1.0);
    gas.use_blocks(3000);
    return gas;
  };
  Gas reference = make();
  reference.advance(reference.block_step_end());
  ASSERT_EQ(reference.blocked_steps(), 1u);
  const Gas::State saved = reference.state();
  reference.advance(20.0);
  Gas resumed = make();
  resumed.restore(saved);
  resumed.advance(20.0);
  EXPECT_GT(reference.blocked_steps(), 2u);
  ASSERT_EQ(resumed.clusters(), reference.clusters());
  EXPECT_EQ(resumed.counters().events, reference.counters().events);
  EXPECT_EQ(resumed.time(), reference.time());
  EXPECT_EQ(all_clusters(resumed), all_clusters(reference));
}

}  // namespace
