/**
 * \file rng.hpp
 * \brief Reproducible random streams: xoshiro256++ with jump-ahead, one stream per (seed, replica, purpose).
 *
 * The generator is xoshiro256++ (Blackman and Vigna 2019): 256 bits of state, period 2^256 - 1,
 * about 1 ns per 64-bit output. The state of the root stream is filled from the user's `seed` with
 * splitmix64. Stream (replica r, purpose p) is the root stream advanced by p long jumps (2^192 draws
 * each) and r jumps (2^128 draws each), so streams never overlap in any run that could be executed,
 * and a replica's numbers do not depend on how many replicas run, or on which thread or rank runs
 * it. Same seed, same output, always (the generator uses only integer arithmetic, and the
 * conversions below are exact).
 *
 * Conversions: uniform doubles on [0, 1) and (0, 1] from the top 53 bits; integers in [0, n) by
 * the multiply-shift of Lemire (bias below n / 2^64, negligible for any particle count); normal
 * deviates by the Marsaglia polar method (portable, unlike std::normal_distribution).
 * Checked by tests/rng_test.cpp.
 */
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

namespace gdsmc::rng {

/// What a stream is used for; each purpose has its own long-jump offset.
enum class Purpose : std::uint32_t { initial_state = 0, collisions = 1, sampling = 2 };

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
  /// Standard normal deviate (Marsaglia polar method; the second deviate is kept).
  double normal();

  bool operator==(const Xoshiro256pp& other) const;

  /// The complete state, for checkpoints: restoring it continues the stream exactly.
  struct State {
    std::uint64_t s[4];
    bool has_spare;
    double spare;
  };
  State state() const { return {{s_[0], s_[1], s_[2], s_[3]}, has_spare_, spare_}; }
  void set_state(const State& state) {
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

}  // namespace gdsmc::rng
