/**
 * \file rng.hpp
 * \brief Reproducible random streams: xoshiro256++ with jump-ahead, one stream per (seed, replica, purpose).
 *
 * The generator is xoshiro256++ (Blackman and Vigna 2019): 256 bits of state, period 2^256 - 1.
 * The state of the root stream is filled from the user's `seed` with splitmix64. Stream (replica r, purpose p) is the root stream advanced by p long jumps (2^192 draws
 * each) and r jumps (2^128 draws each), so streams never overlap in any run that could be executed,
 * and a replica's numbers do not depend on how many replicas run, or on which thread or rank runs
 * it. Same seed, same output, always (the generator uses only integer arithmetic, and the
 * conversions below are exact).
 *
 * Conversions: uniform doubles on [0, 1) and (0, 1] from the top 53 bits; integers in [0, n) by
 * the multiply-shift of Lemire (bias below n / 2^64, negligible for any particle count), and two at
 * once from the halves of one draw (below_pair, exact by rejection); normal
 * deviates by the Marsaglia polar method (portable, unlike std::normal_distribution) or by the ziggurat
 * method (normal_ziggurat; its cost against GSL's and the polar method: \ref perf_white_noise_halves "docs/performance.md").
 * Checked by tests/rng_test.cpp.
 */
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <limits>

namespace gdsmc::rng {

/// What a stream is used for; each purpose has its own long-jump offset.
enum class Purpose : std::uint32_t { initial_state = 0, collisions = 1, sampling = 2, forcing = 3, rotation = 4 };

class Xoshiro256pp {
 public:
  using result_type = std::uint64_t;
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

  /// Root stream of a seed (state filled by splitmix64, never all zero).
  explicit Xoshiro256pp(std::uint64_t seed);

  result_type operator()() {
    const std::uint64_t result = rotl(s_[0] + s_[3], 23) + s_[0];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  /// An independent stream for item `index` of a pass keyed by `key` (collide.hpp, "Threads inside
  /// one replica"): the root stream of a 64-bit hash of (key, index), distinct for distinct indices.
  static Xoshiro256pp substream(std::uint64_t key, std::uint64_t index);

  void jump();       ///< advance by 2^128 draws
  void long_jump();  ///< advance by 2^192 draws

  /// Uniform on [0, 1).
  double uniform() { return static_cast<double>((*this)() >> 11) * 0x1.0p-53; }
  /// Uniform on (0, 1]: safe to take the logarithm of.
  double uniform_pos() { return static_cast<double>(((*this)() >> 11) + 1) * 0x1.0p-53; }
  /// Uniform integer in [0, n), n > 0.
  std::uint64_t below(std::uint64_t n) {
    return static_cast<std::uint64_t>((static_cast<unsigned __int128>((*this)()) * n) >> 64);
  }
  /// Two independent uniform integers in [0, n1) and [0, n2), 0 < n1, n2 < 2^32, from one 64-bit
  /// draw: each half by the 32-bit multiply-shift of Lemire (2019), which is exactly uniform once the
  /// products whose low half is below 2^32 mod n are rejected (fewer than n of the 2^32: the pair is
  /// then drawn again, which keeps the two independent). Half the draws of two below() calls.
  void below_pair(std::uint32_t n1, std::uint32_t n2, std::uint32_t& i1, std::uint32_t& i2) {
    for (;;) {
      const std::uint64_t r = (*this)();
      const std::uint64_t m1 = (r & 0xffffffffULL) * n1, m2 = (r >> 32) * n2;
      if (static_cast<std::uint32_t>(m1) < n1 && static_cast<std::uint32_t>(m1) < (0u - n1) % n1) continue;
      if (static_cast<std::uint32_t>(m2) < n2 && static_cast<std::uint32_t>(m2) < (0u - n2) % n2) continue;
      i1 = static_cast<std::uint32_t>(m1 >> 32);
      i2 = static_cast<std::uint32_t>(m2 >> 32);
      return;
    }
  }
  /// Standard normal deviate (Marsaglia polar method; the second deviate is kept).
  double normal();
  /// Standard normal deviate by the ziggurat method (Marsaglia and Tsang 2000, 128 layers): one draw in
  /// about 97 % of calls, its low 7 bits the layer and its top 32 the abscissa (bits apart, so that the
  /// layer and the value are independent: Doornik 2005 found the original's shared bits correlated);
  /// the wedges by rejection, the tail beyond r = 3.4426 by Marsaglia's exponential method. About half
  /// the time of normal(), for the forcings that draw three deviates per particle and stage
  /// (thermostat.hpp WhiteNoise). Leaves normal()'s spare alone.
  double normal_ziggurat();

  bool operator==(const Xoshiro256pp& other) const;

  /// The complete state, for checkpoints: restoring it continues the stream exactly.
  struct State {
    std::uint64_t s[4];
    bool has_spare;
    double spare;
  };
  State state() const { return {{s_[0], s_[1], s_[2], s_[3]}, has_spare_, spare_}; }
  /// Throws std::invalid_argument for four zero words: xoshiro's fixed point, which draws 0 for ever (a
  /// direction drawn by rejection would never end), never a state of a seeded stream.
  void set_state(const State& state) {
    if ((state.s[0] | state.s[1] | state.s[2] | state.s[3]) == 0)
      throw std::invalid_argument("rng: a generator state of four zero words (xoshiro256++'s fixed point)");
    for (int k = 0; k < 4; ++k) s_[k] = state.s[k];
    has_spare_ = state.has_spare;
    spare_ = state.spare;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  void apply_jump(const std::uint64_t (&polynomial)[4]);
  std::uint64_t s_[4];
  bool has_spare_ = false;
  double spare_ = 0.0;
};

/// The stream of one replica and purpose, derived from the user's seed.
Xoshiro256pp make_stream(std::uint64_t seed, std::uint64_t replica, Purpose purpose);

/// A unit vector uniform on the sphere (Marsaglia 1972): (u1, u2) uniform in the unit disc,
/// s = u1^2 + u2^2, then (2 u1 sqrt(1 - s), 2 u2 sqrt(1 - s), 1 - 2 s). z = 1 - 2s is uniform on
/// [-1, 1] (Archimedes) and the azimuth is that of (u1, u2): no trigonometric calls, pi/4 of the
/// pairs accepted.
template <class Gen>
inline void unit_vector(Gen& gen, double& x, double& y, double& z) {
  double u1, u2, s;
  do {
    u1 = 2.0 * gen.uniform() - 1.0;
    u2 = 2.0 * gen.uniform() - 1.0;
    s = u1 * u1 + u2 * u2;
  } while (s >= 1.0);
  const double scale = 2.0 * std::sqrt(1.0 - s);
  x = u1 * scale;
  y = u2 * scale;
  z = 1.0 - 2.0 * s;
}

/// The same from 32-bit halves: each try of the pair (u1, u2) takes one 64-bit draw instead of two,
/// u1 and u2 on the lattice of step 2^-31 in [-1, 1) (the directions resolved to about 1e-9 rad
/// instead of 1e-16: far below any statistical resolution). For the collision kernels' hemisphere
/// directions (collide.hpp, hemisphere_projection).
template <class Gen>
inline void unit_vector_32(Gen& gen, double& x, double& y, double& z) {
  double u1, u2, s;
  do {
    const std::uint64_t r = gen();
    u1 = static_cast<double>(static_cast<std::int32_t>(static_cast<std::uint32_t>(r))) * 0x1.0p-31;
    u2 = static_cast<double>(static_cast<std::int32_t>(static_cast<std::uint32_t>(r >> 32))) * 0x1.0p-31;
    s = u1 * u1 + u2 * u2;
  } while (s >= 1.0);
  const double scale = 2.0 * std::sqrt(1.0 - s);
  x = u1 * scale;
  y = u2 * scale;
  z = 1.0 - 2.0 * s;
}

}  // namespace gdsmc::rng
