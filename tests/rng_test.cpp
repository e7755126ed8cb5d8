// Unit tests for gdsmc::rng: xoshiro256++ streams, jump-ahead, and the conversions to uniform,
// integer, normal and unit-vector deviates.
//
// Statistical tests use fixed seeds (so they are deterministic), but each tolerance is set as if the
// seed were random: 5 standard errors computed from the theoretical moments, or a chi-square p-value
// above 1e-4. The comment above each test states the ensemble size, the expected value and the SE.
#include "dsmc/rng.hpp"

#include <gsl/gsl_cdf.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

using gdsmc::rng::make_stream;
using gdsmc::rng::Purpose;
using gdsmc::rng::Xoshiro256pp;

namespace {

// ---- Independent reference implementation, written from the published algorithms ----------------
// splitmix64 (Steele, Lea, Flood 2014; Vigna's splitmix64.c) and xoshiro256++ with its jump
// (Blackman and Vigna 2019, xoshiro256plusplus.c). Not shared with src/dsmc/rng.cpp on purpose.
std::uint64_t ref_splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
std::uint64_t ref_rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
struct RefXoshiro {
  std::uint64_t s[4];
  explicit RefXoshiro(std::uint64_t seed) {
    std::uint64_t x = seed;
    for (auto& w : s) w = ref_splitmix64(x);
  }
  std::uint64_t next() {
    const std::uint64_t result = ref_rotl(s[0] + s[3], 23) + s[0];
    const std::uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = ref_rotl(s[3], 45);
    return result;
  }
  void jump_with(const std::uint64_t (&poly)[4]) {
    std::uint64_t t[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int b = 0; b < 64; ++b) {
        if (poly[i] & (UINT64_C(1) << b))
          for (int w = 0; w < 4; ++w) t[w] ^= s[w];
        next();
      }
    for (int w = 0; w < 4; ++w) s[w] = t[w];
  }
  void jump() {
    static constexpr std::uint64_t kJ[4] = {0x180ec6d33cfd0abaULL, 0xd5a61266f0c9392cULL,
                                            0xa9582618e03fc9aaULL, 0x39abdc4529b1661cULL};
    jump_with(kJ);
  }
  void long_jump() {
    static constexpr std::uint64_t kLJ[4] = {0x76e15d3efefdcbbfULL, 0xc5004e441c522fb3ULL,
                                             0x77710069854ee241ULL, 0x39109bb02acbe635ULL};
    jump_with(kLJ);
  }
};

std::vector<std::uint64_t> draws(Xoshiro256pp gen, std::size_t n) {
  std::vector<std::uint64_t> out(n);
  for (auto& x : out) x = gen();
  return out;
}

}  // namespace

// Known answer: the first outputs of the root stream of seed 0, from the reference implementation
// above. The splitmix64 transcription is itself checked against its published first output for
// seed 0 (0xe220a8397b1dcdaf, the test vector of splitmix64.c).
TEST(Rng, KnownAnswerSeedZero) {
  std::uint64_t x = 0;
  EXPECT_EQ(ref_splitmix64(x), 0xe220a8397b1dcdafULL);

  RefXoshiro ref(0);
  Xoshiro256pp gen(0);
  const std::uint64_t expected_first = ref.next();
  EXPECT_EQ(gen(), expected_first);
  for (int i = 1; i < 1000; ++i) ASSERT_EQ(gen(), ref.next()) << "output " << i;
}

// jump() and long_jump() agree with the reference implementation (same published polynomials).
TEST(Rng, JumpsMatchReference) {
  for (std::uint64_t seed : {0ULL, 12345ULL}) {
    RefXoshiro ref(seed);
    Xoshiro256pp gen(seed);
    ref.jump();
    gen.jump();
    for (int i = 0; i < 100; ++i) ASSERT_EQ(gen(), ref.next());
    ref.long_jump();
    gen.long_jump();
    for (int i = 0; i < 100; ++i) ASSERT_EQ(gen(), ref.next());
  }
}

TEST(Rng, SameSeedSameSequence) {
  Xoshiro256pp a(42), b(42), c(43);
  bool differs_from_other_seed = false;
  for (int i = 0; i < 10000; ++i) {
    const auto x = a();
    ASSERT_EQ(x, b());
    differs_from_other_seed |= (x != c());
  }
  EXPECT_TRUE(differs_from_other_seed);
  EXPECT_TRUE(make_stream(7, 3, Purpose::sampling) == make_stream(7, 3, Purpose::sampling));
  // Same state after the same mixed draws, including the cached normal deviate.
  Xoshiro256pp d(9), e(9);
  for (int i = 0; i < 101; ++i) {
    ASSERT_EQ(d.normal(), e.normal());
    ASSERT_EQ(d.uniform(), e.uniform());
  }
  EXPECT_TRUE(d == e);
}

// make_stream(seed, r, p) is the root stream after p long jumps and then r jumps.
TEST(Rng, MakeStreamIsRootAfterJumps) {
  const std::uint64_t seed = 2024;
  for (std::uint32_t p = 0; p < 3; ++p)
    for (std::uint64_t r = 0; r < 4; ++r) {
      Xoshiro256pp root(seed);
      for (std::uint32_t i = 0; i < p; ++i) root.long_jump();
      for (std::uint64_t i = 0; i < r; ++i) root.jump();
      Xoshiro256pp stream = make_stream(seed, r, static_cast<Purpose>(p));
      EXPECT_TRUE(stream == root) << "replica " << r << " purpose " << p;
      // And independently of the code under test:
      RefXoshiro ref(seed);
      for (std::uint32_t i = 0; i < p; ++i) ref.long_jump();
      for (std::uint64_t i = 0; i < r; ++i) ref.jump();
      for (int i = 0; i < 10; ++i) ASSERT_EQ(stream(), ref.next());
    }
  // Replica 0, purpose initial_state is the root stream itself.
  EXPECT_TRUE(make_stream(seed, 0, Purpose::initial_state) == Xoshiro256pp(seed));
}

// Streams of different replicas and purposes share no 64-bit word among their first 1e5 outputs.
// (For unrelated streams the chance of a chance coincidence is about (5e5)^2 / 2^65 ~ 1e-8.)
TEST(Rng, StreamsDifferAndDoNotOverlap) {
  const std::uint64_t seed = 1;
  const std::size_t n = 100000;
  const std::pair<std::uint64_t, Purpose> ids[] = {{0, Purpose::initial_state},
                                                   {1, Purpose::initial_state},
                                                   {2, Purpose::initial_state},
                                                   {0, Purpose::collisions},
                                                   {1, Purpose::collisions},
                                                   {0, Purpose::sampling}};
  std::vector<std::pair<std::uint64_t, int>> all;
  int tag = 0;
  for (const auto& [replica, purpose] : ids) {
    for (std::uint64_t x : draws(make_stream(seed, replica, purpose), n)) all.emplace_back(x, tag);
    ++tag;
  }
  std::sort(all.begin(), all.end());
  std::size_t shared = 0;
  for (std::size_t i = 1; i < all.size(); ++i)
    if (all[i].first == all[i - 1].first && all[i].second != all[i - 1].second) ++shared;
  EXPECT_EQ(shared, 0u);
  // Different streams also differ at their very first output.
  EXPECT_NE(make_stream(seed, 0, Purpose::collisions)(), make_stream(seed, 1, Purpose::collisions)());
  EXPECT_NE(make_stream(seed, 0, Purpose::collisions)(), make_stream(seed, 0, Purpose::sampling)());
}

// uniform() is on the 2^-53 grid of [0, 1); uniform_pos() is exactly uniform() + 2^-53 at the same
// stream position, hence on (0, 1].  Plus range checks and the mean (1e6 draws, expected 1/2,
// SE = sqrt(1/12 / 1e6) = 2.9e-4, tolerance 5 SE).
TEST(Rng, UniformRanges) {
  Xoshiro256pp gen(5), twin(5);
  const int n = 1000000;
  double sum = 0.0, lo = 1.0, hi = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = gen.uniform();
    const double up = twin.uniform_pos();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_GT(up, 0.0);
    ASSERT_LE(up, 1.0);
    ASSERT_EQ(up, u + 0x1.0p-53);
    ASSERT_EQ(u * 0x1.0p53, std::floor(u * 0x1.0p53));  // on the 53-bit grid
    sum += u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  const double se = std::sqrt(1.0 / 12.0 / n);
  EXPECT_NEAR(sum / n, 0.5, 5.0 * se);
  EXPECT_LT(lo, 1e-4);  // P(min > 1e-4) = (1 - 1e-4)^1e6 ~ e^-100
  EXPECT_GT(hi, 1.0 - 1e-4);
}

// below(n) < n, and it is uniform: chi-square over 10 equiprobable bins with 1e6 draws (9 degrees
// of freedom; the test requires the p-value P(chi2_9 > X) > 1e-4, i.e. X < 33.72).
// Done for n = 10 (one value per bin) and n = 1000000007 (bins of values, v * 10 / n; the bins are
// equiprobable to 1e-9, far below the statistical resolution).
TEST(Rng, BelowIsBoundedAndUniform) {
  Xoshiro256pp gen(77);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(gen.below(1), 0u);
  for (std::uint64_t n : {std::uint64_t{10}, std::uint64_t{1000000007}}) {
    const int draws_n = 1000000, bins = 10;
    std::vector<double> count(bins, 0.0);
    for (int i = 0; i < draws_n; ++i) {
      const std::uint64_t v = gen.below(n);
      ASSERT_LT(v, n);
      count[static_cast<std::size_t>(static_cast<unsigned __int128>(v) * bins / n)] += 1.0;
    }
    const double expected = static_cast<double>(draws_n) / bins;
    double chi2 = 0.0;
    for (double c : count) chi2 += (c - expected) * (c - expected) / expected;
    const double p = gsl_cdf_chisq_Q(chi2, bins - 1);
    std::printf("[ Rng.Below ] n = %llu: chi2 = %.3f (9 dof), p = %.4f\n",
                static_cast<unsigned long long>(n), chi2, p);
    EXPECT_GT(p, 1e-4) << "chi2 = " << chi2;
  }
}

// below_pair(n1, n2): both < n, each uniform (chi-square over 10 equiprobable bins of 1e6 draws, as
// above) and the two independent (chi-square of the 10 x 10 joint bins against the product, 81 dof:
// P(chi2_81 > X) > 1e-4). Done for (10, 20) (one and two values per bin), for block sizes (32768, 32767),
// and for (3e9, 4e9 - 1), whose multiply-shift rejects about 30 % and 7 % of the halves (2^32 mod n / 2^32):
// the rejection branch is exercised and leaves the draws uniform and independent.
TEST(Rng, BelowPairIsUniformAndIndependent) {
  Xoshiro256pp gen(1234);
  const std::uint32_t cases[3][2] = {{10u, 20u}, {32768u, 32767u}, {3000000000u, 3999999999u}};
  for (const auto& c : cases) {
    const int draws_n = 1000000, bins = 10;
    std::vector<double> c1(bins, 0.0), c2(bins, 0.0), joint(bins * bins, 0.0);
    for (int i = 0; i < draws_n; ++i) {
      std::uint32_t x, y;
      gen.below_pair(c[0], c[1], x, y);
      ASSERT_LT(x, c[0]);
      ASSERT_LT(y, c[1]);
      const auto bx = static_cast<std::size_t>(std::uint64_t{x} * bins / c[0]);
      const auto by = static_cast<std::size_t>(std::uint64_t{y} * bins / c[1]);
      c1[bx] += 1.0;
      c2[by] += 1.0;
      joint[bx * bins + by] += 1.0;
    }
    // Bin probabilities (exact counts of values per bin: n need not be a multiple of 10).
    auto share = [&](std::uint32_t n, int b) {
      const std::uint64_t lo = (std::uint64_t{n} * static_cast<std::uint64_t>(b) + bins - 1) / bins;
      const std::uint64_t hi = (std::uint64_t{n} * static_cast<std::uint64_t>(b + 1) + bins - 1) / bins;
      return static_cast<double>(hi - lo) / n;
    };
    double chi1 = 0.0, chi2 = 0.0, chij = 0.0;
    for (int b = 0; b < bins; ++b) {
      const double e1 = draws_n * share(c[0], b), e2 = draws_n * share(c[1], b);
      chi1 += (c1[b] - e1) * (c1[b] - e1) / e1;
      chi2 += (c2[b] - e2) * (c2[b] - e2) / e2;
      for (int d = 0; d < bins; ++d) {
        const double e = draws_n * share(c[0], b) * share(c[1], d);
        chij += (joint[b * bins + d] - e) * (joint[b * bins + d] - e) / e;
      }
    }
    const double p1 = gsl_cdf_chisq_Q(chi1, bins - 1), p2 = gsl_cdf_chisq_Q(chi2, bins - 1);
    const double pj = gsl_cdf_chisq_Q(chij, (bins - 1) * (bins - 1));
    std::printf("[ Rng.BelowPair ] (%u, %u): p = %.4f, %.4f (each), %.4f (joint)\n", c[0], c[1], p1, p2, pj);
    EXPECT_GT(p1, 1e-4);
    EXPECT_GT(p2, 1e-4);
    EXPECT_GT(pj, 1e-4);
  }
}

// normal(): 1e6 deviates. Expected <x> = 0 (SE = 1/sqrt(N)), <x^2> = 1 (Var x^2 = 3 - 1 = 2,
// SE = sqrt(2/N)), <x^4> = 3 (Var x^4 = 105 - 9 = 96, SE = sqrt(96/N)); tolerance 5 SE each.
TEST(Rng, NormalMoments) {
  Xoshiro256pp gen(314159);
  const double n = 1e6;
  double m1 = 0.0, m2 = 0.0, m4 = 0.0;
  for (int i = 0; i < 1000000; ++i) {
    const double x = gen.normal();
    const double x2 = x * x;
    m1 += x;
    m2 += x2;
    m4 += x2 * x2;
  }
  m1 /= n;
  m2 /= n;
  m4 /= n;
  const double se1 = std::sqrt(1.0 / n), se2 = std::sqrt(2.0 / n), se4 = std::sqrt(96.0 / n);
  std::printf("[ Rng.Normal ] <x> = %.5f (SE %.5f, exp 0), <x^2> = %.5f (SE %.5f, exp 1), "
              "<x^4> = %.5f (SE %.5f, exp 3)\n", m1, se1, m2, se2, m4, se4);
  EXPECT_NEAR(m1, 0.0, 5.0 * se1);
  EXPECT_NEAR(m2, 1.0, 5.0 * se2);
  EXPECT_NEAR(m4, 3.0, 5.0 * se4);
}

// normal_ziggurat(): 2e6 deviates against the normal distribution. Moments: <x> = 0 (SE 1/sqrt(N)), <x^2> = 1
// (SE sqrt(2/N)), <x^3> = 0 (Var x^3 = 15, SE sqrt(15/N)), <x^4> = 3 (SE sqrt(96/N)); tails P(|x| > t) =
// erfc(t/sqrt 2) at t = 1, 2, r = 3.4426 (the base strip's edge, beyond which the tail method draws) and 4,
// binomial SE, and again for r, 4 and 4.5 with 2e7 more deviates (the tail's shape); 5 SE each. Shape: 64 cells equally likely under the normal CDF, the chi-square p-value above
// 1e-4. The same seed gives the same deviates, and normal()'s spare is left alone.
TEST(Rng, ZigguratNormalMatchesTheNormalDistribution) {
  Xoshiro256pp gen(271828);
  const int count = 2000000;
  const double n = count;
  const std::vector<double> edges{1.0, 2.0, 3.442619855899, 4.0};
  std::vector<double> beyond(edges.size(), 0.0), cells(64, 0.0);
  double m1 = 0.0, m2 = 0.0, m3 = 0.0, m4 = 0.0;
  for (int i = 0; i < count; ++i) {
    const double x = gen.normal_ziggurat(), x2 = x * x;
    m1 += x, m2 += x2, m3 += x2 * x, m4 += x2 * x2;
    for (std::size_t e = 0; e < edges.size(); ++e) beyond[e] += std::abs(x) > edges[e] ? 1.0 : 0.0;
    cells[std::min<std::size_t>(63, static_cast<std::size_t>(64.0 * gsl_cdf_ugaussian_P(x)))] += 1.0;
  }
  EXPECT_NEAR(m1 / n, 0.0, 5.0 * std::sqrt(1.0 / n));
  EXPECT_NEAR(m2 / n, 1.0, 5.0 * std::sqrt(2.0 / n));
  EXPECT_NEAR(m3 / n, 0.0, 5.0 * std::sqrt(15.0 / n));
  EXPECT_NEAR(m4 / n, 3.0, 5.0 * std::sqrt(96.0 / n));
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const double p = std::erfc(edges[e] / std::sqrt(2.0));
    EXPECT_NEAR(beyond[e], n * p, 5.0 * std::sqrt(n * p * (1.0 - p))) << "P(|x| > " << edges[e] << ")";
  }
  // The tail beyond r, where 1 deviate in 1700 falls, with 2e7 more: P(|x| > 4) and P(|x| > 4.5) test its shape.
  const std::vector<double> far{3.442619855899, 4.0, 4.5};
  std::vector<double> far_count(far.size(), 0.0);
  const double n_far = 2e7;
  for (int i = 0; i < 20000000; ++i) {
    const double x = std::abs(gen.normal_ziggurat());
    for (std::size_t e = 0; e < far.size(); ++e) far_count[e] += x > far[e] ? 1.0 : 0.0;
  }
  for (std::size_t e = 0; e < far.size(); ++e) {
    const double p = std::erfc(far[e] / std::sqrt(2.0));
    EXPECT_NEAR(far_count[e], n_far * p, 5.0 * std::sqrt(n_far * p * (1.0 - p))) << "P(|x| > " << far[e] << "), 2e7 deviates";
  }
  double chi2 = 0.0;
  for (double c : cells) chi2 += (c - n / 64.0) * (c - n / 64.0) / (n / 64.0);
  const double p_value = gsl_cdf_chisq_Q(chi2, 63.0);
  std::printf("[ Rng.Ziggurat ] <x> %.5f <x^2> %.5f <x^3> %.5f <x^4> %.5f; chi^2 = %.1f (63 dof), p = %.3f\n", m1 / n,
              m2 / n, m3 / n, m4 / n, chi2, p_value);
  EXPECT_GT(p_value, 1e-4);

  Xoshiro256pp a(9), b(9);
  (void)a.normal();  // a spare is kept
  (void)b.normal();
  Xoshiro256pp copy = a;
  const double spare = copy.normal();  // the spare a holds
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.normal_ziggurat(), b.normal_ziggurat()) << "deviate " << i;
  EXPECT_EQ(a.normal(), spare);  // still a's spare after 1000 ziggurat deviates
}

// unit_vector: |e| = 1 to round-off; over 1e6 vectors the components have mean 0 (each has variance
// 1/3, SE = sqrt(1/(3N))) and <z^2> = 1/3 (Var z^2 = 1/5 - 1/9 = 4/45, SE = sqrt(4/(45 N)));
// tolerance 5 SE.
TEST(Rng, UnitVectorIsotropic) {
  Xoshiro256pp gen(2718);
  const int n = 1000000;
  double sx = 0.0, sy = 0.0, sz = 0.0, sz2 = 0.0, worst = 0.0;
  for (int i = 0; i < n; ++i) {
    double x, y, z;
    gdsmc::rng::unit_vector(gen, x, y, z);
    worst = std::max(worst, std::abs(std::sqrt(x * x + y * y + z * z) - 1.0));
    sx += x;
    sy += y;
    sz += z;
    sz2 += z * z;
  }
  EXPECT_LT(worst, 1e-15);
  const double se_mean = std::sqrt(1.0 / 3.0 / n), se_z2 = std::sqrt(4.0 / 45.0 / n);
  std::printf("[ Rng.UnitVector ] <x,y,z> = (%.5f, %.5f, %.5f) (SE %.5f), <z^2> = %.5f "
              "(SE %.5f, exp 0.33333)\n", sx / n, sy / n, sz / n, se_mean, sz2 / n, se_z2);
  EXPECT_NEAR(sx / n, 0.0, 5.0 * se_mean);
  EXPECT_NEAR(sy / n, 0.0, 5.0 * se_mean);
  EXPECT_NEAR(sz / n, 0.0, 5.0 * se_mean);
  EXPECT_NEAR(sz2 / n, 1.0 / 3.0, 5.0 * se_z2);
}

// unit_vector_32: the same moments as unit_vector (above); |e| = 1 to round-off.
TEST(Rng, UnitVector32Isotropic) {
  Xoshiro256pp gen(2719);
  const int n = 1000000;
  double sx = 0.0, sy = 0.0, sz = 0.0, sz2 = 0.0, worst = 0.0;
  for (int i = 0; i < n; ++i) {
    double x, y, z;
    gdsmc::rng::unit_vector_32(gen, x, y, z);
    worst = std::max(worst, std::abs(std::sqrt(x * x + y * y + z * z) - 1.0));
    sx += x;
    sy += y;
    sz += z;
    sz2 += z * z;
  }
  EXPECT_LT(worst, 1e-15);
  const double se_mean = std::sqrt(1.0 / 3.0 / n), se_z2 = std::sqrt(4.0 / 45.0 / n);
  std::printf("[ Rng.UnitVector32 ] <x,y,z> = (%.5f, %.5f, %.5f) (SE %.5f), <z^2> = %.5f (SE %.5f, exp 0.33333)\n",
              sx / n, sy / n, sz / n, se_mean, sz2 / n, se_z2);
  EXPECT_NEAR(sx / n, 0.0, 5.0 * se_mean);
  EXPECT_NEAR(sy / n, 0.0, 5.0 * se_mean);
  EXPECT_NEAR(sz / n, 0.0, 5.0 * se_mean);
  EXPECT_NEAR(sz2 / n, 1.0 / 3.0, 5.0 * se_z2);
}

// Four zero words are xoshiro's fixed point (it draws 0 for ever): a checkpoint holding them is refused.
TEST(Rng, AStateOfZeroWordsIsRefused) {
  gdsmc::rng::Xoshiro256pp gen(7);
  gdsmc::rng::Xoshiro256pp::State zero{{0, 0, 0, 0}, false, 0.0};
  EXPECT_THROW(gen.set_state(zero), std::invalid_argument);
  zero.s[3] = 1;
  EXPECT_NO_THROW(gen.set_state(zero));
}
