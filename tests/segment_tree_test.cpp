// Unit tests for gdsmc::segment_tree: the SumTree (point update, prefix search, weighted draw) and
// the rank-R pair sampler of the low-rank scheme (Bodrova and Osinsky 2024, eqs. (12)-(14), \ref sch_lowrank_decomposition "docs/schemes.md").
//
// Searches are compared with a linear scan (exactly, with integer weights where boundaries matter).
// Statistical tests use fixed seeds, but each tolerance is set as if the seed were random: every
// frequency within 5 standard errors SE = sqrt(p (1 - p) / n) of its probability p. The measured
// numbers are printed. Nothing is timed against a limit; the large-M test prints its speed only.
#include "dsmc/segment_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

#include "dsmc/rng.hpp"

using gdsmc::rng::make_stream;
using gdsmc::rng::Purpose;
using gdsmc::rng::Xoshiro256pp;
using gdsmc::segment_tree::hard_sphere_factors;
using gdsmc::segment_tree::LowRankSampler;
using gdsmc::segment_tree::SumTree;

namespace {

// The reference: the i with prefix(i) <= u < prefix(i + 1) by a linear scan of sequential prefix
// sums; u at or past the total gives the last positive weight (the documented boundary rule).
std::size_t linear_find(const std::vector<double>& w, double u) {
  double prefix = 0.0;
  std::size_t last_positive = w.size();
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w[i] > 0.0) last_positive = i;
    const double next = prefix + w[i];
    if (u >= prefix && u < next) return i;
    prefix = next;
  }
  return last_positive;
}

// Sum of the weights in long double, sequentially: a reference independent of the tree's order.
long double exact_sum(const std::vector<double>& w) {
  long double s = 0.0L;
  for (double x : w) s += x;
  return s;
}

// Random weights spanning six decades, a fraction `zero_fraction` of them exactly zero.
std::vector<double> random_weights(Xoshiro256pp& gen, std::size_t m, double zero_fraction) {
  std::vector<double> w(m);
  for (auto& x : w) x = gen.uniform() < zero_fraction ? 0.0 : std::exp(13.8 * (gen.uniform() - 0.5));
  return w;
}

}  // namespace

// find() against a linear scan: sizes 1..1000 (powers of two and not), a quarter of the weights
// zero, 2e4 uniform targets in [0, total) per size. Expected: no mismatch (a mismatch could only
// come from a target within an ulp of a boundary, probability ~1e-13 per target).
TEST(SegmentTreeSumTree, FindMatchesLinearScan) {
  auto gen = make_stream(11, 0, Purpose::collisions);
  for (std::size_t m : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 9u, 31u, 100u, 1000u}) {
    std::vector<double> w = random_weights(gen, m, 0.25);
    w[gen.below(m)] = 1.0;  // at least one positive
    SumTree tree(m);
    tree.assign(w);
    ASSERT_EQ(tree.size(), m);
    for (std::size_t i = 0; i < m; ++i) ASSERT_EQ(tree.weight(i), w[i]);
    int mismatches = 0;
    for (int q = 0; q < 20000; ++q) {
      const double u = gen.uniform() * tree.total();
      const std::size_t got = tree.find(u);
      if (got != linear_find(w, u)) ++mismatches;
      ASSERT_GT(w[got], 0.0);
    }
    EXPECT_EQ(mismatches, 0) << "M = " << m;
  }
}

// Boundaries, exactly: integer weights (all sums exact) with zeros at both ends and in runs.
// u = prefix(i) must give the first positive weight at or after i; u = total, above total,
// nextafter(total, 0), negative and NaN follow the documented rules.
TEST(SegmentTreeSumTree, ExactBoundariesAndZeroRuns) {
  const std::vector<double> w = {0, 0, 3, 0, 0, 0, 1, 2, 0, 5, 0, 0, 0};
  SumTree tree;
  tree.assign(w);
  EXPECT_EQ(tree.total(), 11.0);
  double prefix = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (prefix < tree.total()) {
      std::size_t expect = i;
      while (w[expect] == 0.0) ++expect;
      EXPECT_EQ(tree.find(prefix), expect) << "u = prefix(" << i << ") = " << prefix;
      EXPECT_EQ(tree.find(prefix + 0.5), expect);
    }
    prefix += w[i];
  }
  EXPECT_EQ(tree.find(std::nextafter(11.0, 0.0)), 9u);
  EXPECT_EQ(tree.find(11.0), 9u);
  EXPECT_EQ(tree.find(1e300), 9u);
  EXPECT_EQ(tree.find(std::numeric_limits<double>::infinity()), 9u);
  EXPECT_EQ(tree.find(-1.0), 2u);
  EXPECT_EQ(tree.find(std::numeric_limits<double>::quiet_NaN()), 2u);
  for (std::size_t i = 0; i < w.size(); ++i) EXPECT_EQ(tree.find(std::nextafter(0.0, 1.0)) == i, i == 2);
}

// The leaf-0 shortcut of find() (u < w_0 returns 0 without the descent) gives what the descent gives on
// both sides of its boundary, with exact integer sums: leaf 0 up to just below w_0 = 3, then the first
// positive leaf after it (2, leaf 1 being empty), and the same with leaf 0 empty (never returned).
TEST(SegmentTreeSumTree, LeafZeroShortcutAtItsBoundary) {
  SumTree tree;
  tree.assign({3.0, 0.0, 2.0, 5.0, 0.0});
  EXPECT_EQ(tree.find(0.0), 0u);
  EXPECT_EQ(tree.find(std::nextafter(3.0, 0.0)), 0u);
  EXPECT_EQ(tree.find(3.0), 2u);
  EXPECT_EQ(tree.find(std::nextafter(5.0, 0.0)), 2u);
  EXPECT_EQ(tree.find(5.0), 3u);
  tree.set(0, 0.0);
  EXPECT_EQ(tree.find(0.0), 2u);
  EXPECT_EQ(tree.find(-0.0), 2u);
}

// Round-off cannot land on a zero-weight leaf: 200 trees of 1000 weights over 300 decades
// (1e-150..1e150, half of them zero), probed at 2e4 random targets, at the tree's own internal
// boundaries +-1 ulp (for every leaf), and at and just below the total. Every result has weight > 0.
TEST(SegmentTreeSumTree, NeverReturnsZeroWeight) {
  auto gen = make_stream(12, 0, Purpose::collisions);
  long probes = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t m = 1 + gen.below(1000);
    std::vector<double> w(m);
    for (auto& x : w) x = gen.uniform() < 0.5 ? 0.0 : std::exp(690.0 * (gen.uniform() - 0.5));
    w[gen.below(m)] = std::exp(690.0 * (gen.uniform() - 0.5));
    SumTree tree(m);
    for (std::size_t i = 0; i < m; ++i) tree.set(i, w[i]);
    const double total = tree.total();
    auto check = [&](double u) {
      ++probes;
      const std::size_t i = tree.find(u);
      ASSERT_LT(i, m);
      ASSERT_GT(tree.weight(i), 0.0) << "u = " << u << " total = " << total;
    };
    for (int q = 0; q < 100; ++q) check(gen.uniform() * total);
    double prefix = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
      check(prefix);
      check(std::nextafter(prefix, 0.0));
      check(std::nextafter(prefix, 2 * total + 1));
      prefix += w[i];
    }
    check(total);
    check(std::nextafter(total, 0.0));
    check(total * (1 - 1e-15));
  }
  std::printf("[ measured ] %ld probes, none on a zero-weight leaf\n", probes);
}

// A case found by random search where a plain descent (go right when u >= left sum, subtract) lands
// on a zero leaf: with weights {1.5 2^-46, 0, 96, 0} and u just below the total, u - left rounds to
// the whole right subtree's sum, and the descent runs off to the empty leaf 3. The guard returns 2.
TEST(SegmentTreeSumTree, RoundOffRegression) {
  SumTree tree;
  tree.assign({0x1.8p-46, 0.0, 0x1.8p+6, 0.0});
  EXPECT_EQ(tree.find(std::nextafter(tree.total(), 0.0)), 2u);
  tree.assign({0x1.6p-25, 0x1.ep-1, 0x1.4p+25, 0.0});
  EXPECT_EQ(tree.find(std::nextafter(tree.total(), 0.0)), 2u);
}

// total() stays the sum of the leaves: M = 1000, 1e5 set() calls with weights over six decades and
// 10 % zeros. Expected |total - sum| / sum <= 1e-12 (measured ~1e-16). For contrast, a running total
// kept by adding deltas (what the tree must not do) is printed.
TEST(SegmentTreeSumTree, TotalStaysExactAfterManyUpdates) {
  auto gen = make_stream(13, 0, Purpose::collisions);
  const std::size_t m = 1000;
  std::vector<double> w = random_weights(gen, m, 0.1);
  SumTree tree;
  tree.assign(w);
  double delta_total = tree.total();
  double worst = 0.0;
  for (int step = 0; step < 100000; ++step) {
    const std::size_t i = gen.below(m);
    const double x = gen.uniform() < 0.1 ? 0.0 : std::exp(13.8 * (gen.uniform() - 0.5));
    delta_total += x - w[i];
    w[i] = x;
    tree.set(i, x);
    if (step % 1000 == 999) {
      const long double ref = exact_sum(w);
      worst = std::max(worst, static_cast<double>(std::fabs(tree.total() - ref) / ref));
    }
  }
  const long double ref = exact_sum(w);
  const double rel = static_cast<double>(std::fabs(tree.total() - ref) / ref);
  const double rel_delta = static_cast<double>(std::fabs(delta_total - ref) / ref);
  std::printf("[ measured ] after 1e5 updates: tree rel err %.2e (worst over checks %.2e), "
              "delta-accumulated rel err %.2e\n", rel, worst, rel_delta);
  EXPECT_LE(rel, 1e-12);
  EXPECT_LE(worst, 1e-12);
  for (std::size_t i = 0; i < m; ++i) ASSERT_EQ(tree.weight(i), w[i]);
}

// Weighted draws: M = 7 weights (one zero), n = 1e6 draws of find(U total). Each frequency within
// 5 SE of w_i / total, SE = sqrt(p (1 - p) / n) (largest SE 5.0e-4); the zero weight is never drawn.
TEST(SegmentTreeSumTree, SamplingFrequencies) {
  const std::vector<double> w = {3.0, 0.0, 1.5, 0.25, 7.0, 2.0, 0.01};
  SumTree tree(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) tree.set(i, w[i]);
  auto gen = make_stream(14, 0, Purpose::collisions);
  const long n = 1000000;
  std::vector<long> count(w.size(), 0);
  for (long d = 0; d < n; ++d) ++count[tree.find(gen.uniform() * tree.total())];
  const double total = std::accumulate(w.begin(), w.end(), 0.0);
  double worst_z = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double p = w[i] / total;
    const double freq = static_cast<double>(count[i]) / n;
    if (p == 0.0) {
      EXPECT_EQ(count[i], 0);
      continue;
    }
    const double se = std::sqrt(p * (1 - p) / n);
    const double z = (freq - p) / se;
    worst_z = std::max(worst_z, std::fabs(z));
    std::printf("[ measured ] i = %zu  p = %.6f  freq = %.6f  SE = %.1e  z = %+.2f\n", i, p, freq, se, z);
    EXPECT_LE(std::fabs(z), 5.0) << "index " << i;
  }
  std::printf("[ measured ] worst |z| = %.2f\n", worst_z);
}

// M = 1 and M = 1e5. M = 1: find always 0, an all-zero tree refuses to search. M = 1e5: integer
// weights (exact sums) with 20 % zeros, 1e5 targets compared with a binary search of the prefix
// sums, then 1e5 updates and the total compared with the sum of the leaves.
TEST(SegmentTreeSumTree, SizeOneAndLarge) {
  SumTree one(1);
  EXPECT_EQ(one.total(), 0.0);
  EXPECT_THROW(one.find(0.0), std::domain_error);
  one.set(0, 2.5);
  EXPECT_EQ(one.total(), 2.5);
  EXPECT_EQ(one.find(0.0), 0u);
  EXPECT_EQ(one.find(2.4), 0u);
  EXPECT_EQ(one.find(2.5), 0u);
  one.set(0, 0.0);
  EXPECT_THROW(one.find(0.0), std::domain_error);

  auto gen = make_stream(15, 0, Purpose::collisions);
  const std::size_t m = 100000;
  std::vector<double> w(m);
  for (auto& x : w) x = gen.uniform() < 0.2 ? 0.0 : static_cast<double>(1 + gen.below(1000));
  SumTree tree(m);
  tree.assign(w);
  std::vector<double> prefix(m + 1, 0.0);
  for (std::size_t i = 0; i < m; ++i) prefix[i + 1] = prefix[i] + w[i];
  ASSERT_EQ(tree.total(), prefix[m]);  // integers below 2^53: exact
  for (int q = 0; q < 100000; ++q) {
    const double u = std::floor(gen.uniform() * prefix[m]) + (gen.uniform() < 0.5 ? 0.0 : 0.5);
    // First i with prefix[i + 1] > u.
    const std::size_t expect =
        static_cast<std::size_t>(std::upper_bound(prefix.begin() + 1, prefix.end(), u) - prefix.begin() - 1);
    ASSERT_EQ(tree.find(u), expect) << "u = " << u;
    ASSERT_GT(w[expect], 0.0);
  }
  for (int s = 0; s < 100000; ++s) {
    const std::size_t i = gen.below(m);
    w[i] = gen.uniform() < 0.2 ? 0.0 : gen.uniform();
    tree.set(i, w[i]);
  }
  const long double ref = exact_sum(w);
  const double rel = static_cast<double>(std::fabs(tree.total() - ref) / ref);
  std::printf("[ measured ] M = 1e5 after 1e5 updates: total rel err %.2e\n", rel);
  EXPECT_LE(rel, 1e-12);
}

// Bad input is refused with the index and value in the message; a failed assign leaves all zero.
TEST(SegmentTreeSumTree, RejectsInvalidInput) {
  SumTree tree(4);
  EXPECT_THROW(tree.set(4, 1.0), std::out_of_range);
  EXPECT_THROW(tree.set(0, -1.0), std::invalid_argument);
  EXPECT_THROW(tree.set(0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(tree.set(0, std::numeric_limits<double>::infinity()), std::invalid_argument);
  try {
    tree.set(2, -0.5);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("weight 2 = -0.5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(tree.assign({1.0, 2.0, -3.0}), std::invalid_argument);
  EXPECT_EQ(tree.total(), 0.0);
  EXPECT_THROW(tree.find(0.0), std::domain_error);
  SumTree empty;
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_EQ(empty.total(), 0.0);
  EXPECT_THROW(empty.set(0, 1.0), std::out_of_range);
}

namespace {

using Vec3 = std::array<double, 3>;

// Draws n pairs and checks each of the M x M frequencies against C_ik / R within 5 SE; pairs with
// C_ik = 0 must never be drawn. Returns the largest |z|.
double check_pair_frequencies(const LowRankSampler<3>& s, Xoshiro256pp& gen, long n) {
  const std::size_t m = s.size();
  std::vector<long> count(m * m, 0);
  for (long d = 0; d < n; ++d) {
    const auto [i, k] = s.sample(gen);
    ++count[i * m + k];
  }
  long double r = 0.0L;
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = 0; k < m; ++k) r += s.entry(i, k);
  double worst = 0.0;
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = 0; k < m; ++k) {
      const double p = static_cast<double>(s.entry(i, k) / r);
      const long c = count[i * m + k];
      if (p == 0.0) {
        EXPECT_EQ(c, 0) << "pair (" << i << ", " << k << ") has C = 0";
        continue;
      }
      const double se = std::sqrt(p * (1 - p) / n);
      const double z = (static_cast<double>(c) / n - p) / se;
      worst = std::max(worst, std::fabs(z));
      EXPECT_LE(std::fabs(z), 5.0) << "pair (" << i << ", " << k << ") p = " << p;
    }
  return worst;
}

double brute_total(const LowRankSampler<3>& s) {
  long double r = 0.0L;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t k = 0; k < s.size(); ++k) r += s.entry(i, k);
  return static_cast<double>(r);
}

}  // namespace

// LowRankSampler<3>, M = 5, random positive u, v in (0.1, 1.1): n = 2e6 draws, all 25 pair
// frequencies within 5 SE of C_ik / R. Then species 1's row becomes
// zero, species 3's column keeps only term 2, and species 0's row and 4's column are redrawn: total()
// equals the brute-force sum to 1e-14 relative, and another 2e6 draws match the new C_ik / R within
// 5 SE, with no draw of a pair whose C_ik is 0.
TEST(SegmentTreeLowRank, PairFrequenciesRank3) {
  auto gen = make_stream(21, 0, Purpose::collisions);
  const std::size_t m = 5;
  std::vector<Vec3> u(m), v(m);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t r = 0; r < 3; ++r) {
      u[i][r] = 0.1 + gen.uniform();
      v[i][r] = 0.1 + gen.uniform();
    }
  LowRankSampler<3> s(m);
  for (std::size_t i = 0; i < m; ++i) {
    s.set_row(i, u[i]);
    s.set_column(i, v[i]);
  }
  EXPECT_NEAR(s.total(), brute_total(s), 1e-14 * brute_total(s));
  const double z1 = check_pair_frequencies(s, gen, 2000000);

  s.set_row(1, {0.0, 0.0, 0.0});
  s.set_column(3, {0.0, 0.7, 0.0});
  s.set_row(0, {2.0, 0.05, 0.3});
  s.set_column(4, {0.0, 3.0, 0.2});
  const double brute = brute_total(s);
  std::printf("[ measured ] after updates: total %.17g, brute force %.17g, rel diff %.1e\n", s.total(),
              brute, std::fabs(s.total() - brute) / brute);
  EXPECT_NEAR(s.total(), brute, 1e-14 * brute);
  EXPECT_EQ(s.row(1), (Vec3{0.0, 0.0, 0.0}));
  EXPECT_EQ(s.column(3), (Vec3{0.0, 0.7, 0.0}));
  const double z2 = check_pair_frequencies(s, gen, 2000000);
  std::printf("[ measured ] 25 pairs x 2e6 draws: worst |z| = %.2f (initial), %.2f (after updates)\n", z1,
              z2);
}

// Terms of zero weight are never chosen: only term 3 is non-zero, and within it a single row and
// column, so every draw is that pair.
TEST(SegmentTreeLowRank, SingleTermAndSinglePair) {
  LowRankSampler<3> s(6);
  s.set_row(4, {0.0, 0.0, 2.0});
  s.set_column(1, {5.0, 0.0, 3.0});  // term 1 has a column but no row: weight 0
  s.set_row(2, {0.0, 1.0, 0.0});     // term 2 has a row but no column: weight 0
  EXPECT_EQ(s.total(), 6.0);
  EXPECT_EQ(s.term_total(0), 0.0);
  EXPECT_EQ(s.term_total(1), 0.0);
  auto gen = make_stream(22, 0, Purpose::collisions);
  for (int d = 0; d < 100000; ++d) ASSERT_EQ(s.sample(gen), (std::pair<std::size_t, std::size_t>{4, 1}));
  LowRankSampler<3> zero(3);
  EXPECT_THROW(zero.sample(gen), std::domain_error);
  LowRankSampler<3> one(1);
  one.set_row(0, {1.0, 2.0, 3.0});
  one.set_column(0, {1.0, 1.0, 1.0});
  EXPECT_EQ(one.total(), 6.0);
  for (int d = 0; d < 1000; ++d) ASSERT_EQ(one.sample(gen), (std::pair<std::size_t, std::size_t>{0, 0}));
}

// total() equals the brute-force double sum after many updates: M = 60, 2e4 random set_row /
// set_column calls (weights over six decades, 10 % zero). Expected rel diff <= 1e-12.
TEST(SegmentTreeLowRank, TotalMatchesBruteForceAfterUpdates) {
  auto gen = make_stream(23, 0, Purpose::collisions);
  const std::size_t m = 60;
  LowRankSampler<3> s(m);
  auto draw = [&] {
    Vec3 x{};
    for (auto& c : x) c = gen.uniform() < 0.1 ? 0.0 : std::exp(13.8 * (gen.uniform() - 0.5));
    return x;
  };
  std::vector<Vec3> rows(m), cols(m);
  for (std::size_t i = 0; i < m; ++i) {
    rows[i] = draw();
    cols[i] = draw();
  }
  s.assign(rows, cols);
  double worst = 0.0;
  for (int step = 0; step < 20000; ++step) {
    const std::size_t i = gen.below(m);
    if (gen.uniform() < 0.5)
      s.set_row(i, draw());
    else
      s.set_column(i, draw());
    if (step % 500 == 499) {
      const double brute = brute_total(s);
      worst = std::max(worst, std::fabs(s.total() - brute) / brute);
    }
  }
  std::printf("[ measured ] M = 60, 2e4 updates: worst total rel diff %.2e\n", worst);
  EXPECT_LE(worst, 1e-12);
}

// set_rows (every row at once, O(M): the collider's rebuild of all species' bounds) leaves the same
// trees as set_row for each row in turn, bit for bit: the same totals, and the same pairs drawn.
TEST(SegmentTreeLowRank, SetRowsEqualsSetRowOneByOne) {
  auto gen = make_stream(29, 0, Purpose::collisions);
  const std::size_t m = 1000;  // (not a power of two: padding leaves)
  std::vector<Vec3> rows(m), cols(m), later(m);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t r = 0; r < 3; ++r) {
      rows[i][r] = std::exp(10.0 * (gen.uniform() - 0.5));
      cols[i][r] = std::exp(10.0 * (gen.uniform() - 0.5));
      later[i][r] = gen.uniform() < 0.05 ? 0.0 : std::exp(10.0 * (gen.uniform() - 0.5));
    }
  LowRankSampler<3> one_by_one(m), at_once(m);
  one_by_one.assign(rows, cols);
  at_once.assign(rows, cols);
  for (std::size_t i = 0; i < m; ++i) one_by_one.set_row(i, later[i]);
  at_once.set_rows(later);
  EXPECT_EQ(one_by_one.total(), at_once.total());
  for (std::size_t r = 0; r < 3; ++r) EXPECT_EQ(one_by_one.term_total(r), at_once.term_total(r));
  auto g1 = make_stream(31, 0, Purpose::collisions), g2 = make_stream(31, 0, Purpose::collisions);
  for (int k = 0; k < 10000; ++k) ASSERT_EQ(one_by_one.sample(g1), at_once.sample(g2)) << "draw " << k;
  EXPECT_THROW(at_once.set_rows(std::vector<Vec3>(m - 1)), std::invalid_argument);
}

// The hard-sphere decomposition (Bodrova and Osinsky 2024, eqs. (12)-(14), \ref sch_lowrank_decomposition "docs/schemes.md"): for random species,
// sum_r u_i^(r) v_k^(r) = A_ik = pi sigma_ik^2 w_i N_i N_k / V with sigma_ik = (sigma_i + sigma_k)/2,
// and R = sum A_ik equals the ordered-pair majorant sum_{i,k} N_i N_k pi sigma_ik^2 (w_i + w_k)/(2V).
TEST(SegmentTreeLowRank, HardSphereFactors) {
  auto gen = make_stream(24, 0, Purpose::collisions);
  const std::size_t m = 8;
  const double volume = 123.0;
  std::vector<double> count(m), sigma(m), w(m);
  LowRankSampler<3> s(m);
  for (std::size_t i = 0; i < m; ++i) {
    count[i] = static_cast<double>(1 + gen.below(1000));
    sigma[i] = std::exp(4.6 * gen.uniform());  // 1 .. 100
    w[i] = 0.1 + 5 * gen.uniform();
    const auto f = hard_sphere_factors(count[i], sigma[i], w[i], volume);
    s.set_row(i, f.row);
    s.set_column(i, f.column);
  }
  double worst = 0.0;
  long double majorant = 0.0L;
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = 0; k < m; ++k) {
      const double sik = 0.5 * (sigma[i] + sigma[k]);
      const double a = std::numbers::pi * sik * sik * w[i] * count[i] * count[k] / volume;
      worst = std::max(worst, std::fabs(s.entry(i, k) - a) / a);
      majorant += count[i] * count[k] * std::numbers::pi * sik * sik * (w[i] + w[k]) / (2 * volume);
    }
  const double rel = std::fabs(s.total() - static_cast<double>(majorant)) / static_cast<double>(majorant);
  std::printf("[ measured ] A_ik rel err %.1e, R vs ordered-pair majorant rel err %.1e\n", worst, rel);
  EXPECT_LE(worst, 1e-14);
  EXPECT_LE(rel, 1e-13);
}

// M = 1e5 species with hard-sphere factors (a tenth of them empty): 1e6 draws, each a pair with
// C_ik > 0; 1e5 species updates (count or speed changed), total() against the brute-force sum
// computed as sum_r (sum_i u) (sum_k v) in long double. Speed is printed, never asserted.
TEST(SegmentTreeLowRank, LargeM) {
  auto gen = make_stream(25, 0, Purpose::collisions);
  const std::size_t m = 100000;
  std::vector<Vec3> rows(m), cols(m);
  auto species = [&](std::size_t i) {
    const double n = gen.uniform() < 0.1 ? 0.0 : static_cast<double>(1 + gen.below(100));
    const auto f = hard_sphere_factors(n, std::cbrt(1.0 + static_cast<double>(i)), 0.5 + gen.uniform(), 1e6);
    rows[i] = f.row;
    cols[i] = f.column;
  };
  for (std::size_t i = 0; i < m; ++i) species(i);
  LowRankSampler<3> s;
  s.assign(rows, cols);
  ASSERT_EQ(s.size(), m);

  const auto t0 = std::chrono::steady_clock::now();
  const long draws = 1000000;
  std::size_t checksum = 0;
  for (long d = 0; d < draws; ++d) {
    const auto [i, k] = s.sample(gen);
    checksum += i ^ k;
    if (!(s.entry(i, k) > 0.0)) FAIL() << "drew (" << i << ", " << k << ") with C = 0";
  }
  const auto t1 = std::chrono::steady_clock::now();
  for (int u = 0; u < 100000; ++u) {
    const std::size_t i = gen.below(m);
    species(i);
    s.set_row(i, rows[i]);
    s.set_column(i, cols[i]);
  }
  const auto t2 = std::chrono::steady_clock::now();
  long double ref = 0.0L;
  for (std::size_t r = 0; r < 3; ++r) {
    long double su = 0.0L, sv = 0.0L;
    for (std::size_t i = 0; i < m; ++i) {
      su += rows[i][r];
      sv += cols[i][r];
    }
    ref += su * sv;
  }
  const double rel = static_cast<double>(std::fabs(s.total() - ref) / ref);
  const double ns_draw = std::chrono::duration<double, std::nano>(t1 - t0).count() / draws;
  const double ns_update = std::chrono::duration<double, std::nano>(t2 - t1).count() / 1e5;
  std::printf("[ measured ] M = 1e5: %.0f ns per draw (incl. the C_ik check), %.0f ns per species update "
              "(row + column), total rel err %.1e, checksum %zu (not asserted)\n",
              ns_draw, ns_update, rel, checksum);
  EXPECT_LE(rel, 1e-12);
}

// Walker's alias table (Vose's construction), by hand. w = (1, 3): scaled (0.5, 1.5); cell 0 keeps itself
// with 0.5 and sends the rest to 1, which is left at 1.0: thresholds (0.5, 1), aliases (1, 1), so that
// P(0) = 0.5/2. w = (0, 2, 1, 1): scaled (0, 2, 1, 1), small = [0], large = [1, 2, 3] (1.0 is not below 1):
// cell 0 -> alias 3 (scaled 3 becomes 0: small), cell 3 -> alias 2 (then 0), cell 2 -> alias 1 (then 1):
// thresholds (0, 1, 0, 0), aliases (3, 1, 1, 2); P = (0, 1/2, 1/4, 1/4). All zero: no cells.
TEST(SegmentTreeAlias, VoseByHand) {
  gdsmc::segment_tree::AliasTable t;
  t.build({1.0, 3.0});
  EXPECT_EQ(t.threshold, (std::vector<double>{0.5, 1.0}));
  EXPECT_EQ(t.alias, (std::vector<std::size_t>{1, 1}));
  t.build({0.0, 2.0, 1.0, 1.0});
  EXPECT_EQ(t.threshold, (std::vector<double>{0.0, 1.0, 0.0, 0.0}));
  EXPECT_EQ(t.alias, (std::vector<std::size_t>{3, 1, 1, 2}));
  EXPECT_EQ(t.sample(0.3), 1u);   // cell 1, kept
  EXPECT_EQ(t.sample(0.55), 1u);  // cell 2 (x = 2.2), threshold 0: its alias 1
  EXPECT_EQ(t.sample(0.8), 2u);   // cell 3 (x = 3.2): alias 2
  EXPECT_EQ(t.sample(0.1), 3u);   // cell 0 (x = 0.4): alias 3
  int cells = 0;
  EXPECT_FALSE(t.build_cells({0.0, 0.0, 0.0}, [&](std::size_t, double, std::size_t) { ++cells; }));
  EXPECT_EQ(cells, 0);
  t.build({0.0, 0.0});
  EXPECT_EQ(t.threshold, (std::vector<double>{0.0, 0.0}));
}

// build_cells hands every cell over exactly once, with build()'s threshold and alias, each threshold in
// [0, 1] (the blocks take floor(t 2^c) as an integer conversion: collide_blocks.cpp); and the table's
// probabilities, summed over the cells, are w_k / sum w to round-off. 200 tables of 1..5000 weights, a
// quarter zero, spanning twelve decades.
TEST(SegmentTreeAlias, BuildCellsHandsOverBuildsTable) {
  auto gen = make_stream(77, 0, Purpose::collisions);
  gdsmc::segment_tree::AliasTable t, u;
  for (int table = 0; table < 200; ++table) {
    const std::size_t n = 1 + gen.below(5000);
    std::vector<double> w(n);
    for (auto& x : w) x = gen.uniform() < 0.25 ? 0.0 : std::pow(10.0, 12.0 * gen.uniform() - 6.0);
    w[gen.below(n)] = 1.0;  // (one positive weight at least)
    t.build(w);
    std::vector<int> seen(n, 0);
    std::vector<double> probability(n, 0.0);
    ASSERT_TRUE(u.build_cells(w, [&](std::size_t k, double threshold, std::size_t alias) {
      ++seen[k];
      EXPECT_EQ(threshold, t.threshold[k]);
      EXPECT_EQ(alias, t.alias[k]);
      EXPECT_GE(threshold, 0.0);
      EXPECT_LE(threshold, 1.0);
      probability[k] += threshold / static_cast<double>(n);
      probability[alias] += (1.0 - threshold) / static_cast<double>(n);
    }));
    const double total = std::accumulate(w.begin(), w.end(), 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      ASSERT_EQ(seen[k], 1) << "cell " << k << " of " << n;
      EXPECT_NEAR(probability[k], w[k] / total, 1e-12) << "outcome " << k << " of " << n;
    }
  }
}
