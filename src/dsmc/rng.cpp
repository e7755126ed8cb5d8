#include "dsmc/rng.hpp"

#include <array>
#include <cstddef>

namespace gdsmc::rng {

namespace {
std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
// Jump polynomials published with xoshiro256++ (Blackman and Vigna).
constexpr std::uint64_t kJump[4] = {0x180ec6d33cfd0abaULL, 0xd5a61266f0c9392cULL,
                                    0xa9582618e03fc9aaULL, 0x39abdc4529b1661cULL};
constexpr std::uint64_t kLongJump[4] = {0x76e15d3efefdcbbfULL, 0xc5004e441c522fb3ULL,
                                        0x77710069854ee241ULL, 0x39109bb02acbe635ULL};
}  // namespace

Xoshiro256pp::Xoshiro256pp(std::uint64_t seed) {
  std::uint64_t x = seed;
  for (auto& word : s_) word = splitmix64(x);
  if ((s_[0] | s_[1] | s_[2] | s_[3]) == 0) s_[0] = 1;  // the all-zero state is a fixed point
}

Xoshiro256pp Xoshiro256pp::substream(std::uint64_t key, std::uint64_t index) {
  // splitmix64's output function is a bijection of its state: for one key, distinct indices give
  // distinct seeds; the seed then fills the 256-bit state through splitmix64 as for a user's seed.
  std::uint64_t k = key, i = index ^ 0x6a09e667f3bcc909ULL;
  const std::uint64_t hashed_key = splitmix64(k);
  return Xoshiro256pp(hashed_key ^ splitmix64(i));
}

void Xoshiro256pp::apply_jump(const std::uint64_t (&polynomial)[4]) {
  std::uint64_t t[4] = {0, 0, 0, 0};
  for (std::uint64_t word : polynomial)
    for (int b = 0; b < 64; ++b) {
      if (word & (std::uint64_t{1} << b))
        for (int i = 0; i < 4; ++i) t[i] ^= s_[i];
      (*this)();
    }
  for (int i = 0; i < 4; ++i) s_[i] = t[i];
  has_spare_ = false;
}

void Xoshiro256pp::jump() { apply_jump(kJump); }
void Xoshiro256pp::long_jump() { apply_jump(kLongJump); }

double Xoshiro256pp::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u, v, s;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * factor;
  has_spare_ = true;
  return u * factor;
}

namespace {
/// The 128 layers of Marsaglia and Tsang's (2000) ziggurat for the normal density f(x) = exp(-x^2/2): the
/// base strip's edge r, each layer's acceptance bound k (|h| < k_i: inside the layer's rectangle), its
/// abscissa step w (x = h w_i for a signed 32-bit h) and f at its edge.
struct Ziggurat {
  static constexpr double r = 3.442619855899;          // the base strip's edge
  static constexpr double area = 9.91256303526217e-3;  // each layer's area
  std::array<std::uint32_t, 128> k{};
  std::array<double, 128> w{}, f{};
  Ziggurat() {
    const double m1 = 2147483648.0;  // 2^31
    double dn = r, tn = r;
    const double q = area / std::exp(-0.5 * dn * dn);
    k[0] = static_cast<std::uint32_t>((dn / q) * m1);
    k[1] = 0;
    w[0] = q / m1;
    w[127] = dn / m1;
    f[0] = 1.0;
    f[127] = std::exp(-0.5 * dn * dn);
    for (int i = 126; i >= 1; --i) {
      dn = std::sqrt(-2.0 * std::log(area / dn + std::exp(-0.5 * dn * dn)));
      k[static_cast<std::size_t>(i) + 1] = static_cast<std::uint32_t>((dn / tn) * m1);
      tn = dn;
      f[static_cast<std::size_t>(i)] = std::exp(-0.5 * dn * dn);
      w[static_cast<std::size_t>(i)] = dn / m1;
    }
  }
};
}  // namespace

double Xoshiro256pp::normal_ziggurat() {
  static const Ziggurat z;  // immutable after its thread-safe construction
  for (;;) {
    const std::uint64_t u = (*this)();
    const std::size_t i = static_cast<std::size_t>(u & 127u);
    const auto h = static_cast<std::int32_t>(static_cast<std::uint32_t>(u >> 32));
    const double x = static_cast<double>(h) * z.w[i];
    const std::uint32_t magnitude = h < 0 ? 0u - static_cast<std::uint32_t>(h) : static_cast<std::uint32_t>(h);
    if (magnitude < z.k[i]) return x;  // inside the layer's rectangle
    if (i == 0) {                      // the tail beyond r
      double t, y;
      do {
        t = -std::log(uniform_pos()) / Ziggurat::r;
        y = -std::log(uniform_pos());
      } while (y + y < t * t);
      return h > 0 ? Ziggurat::r + t : -(Ziggurat::r + t);
    }
    if (z.f[i] + uniform() * (z.f[i - 1] - z.f[i]) < std::exp(-0.5 * x * x)) return x;  // inside the wedge
  }
}

bool Xoshiro256pp::operator==(const Xoshiro256pp& other) const {
  for (int i = 0; i < 4; ++i)
    if (s_[i] != other.s_[i]) return false;
  return has_spare_ == other.has_spare_ && (!has_spare_ || spare_ == other.spare_);
}

Xoshiro256pp make_stream(std::uint64_t seed, std::uint64_t replica, Purpose purpose) {
  Xoshiro256pp gen(seed);
  for (std::uint32_t p = 0; p < static_cast<std::uint32_t>(purpose); ++p) gen.long_jump();
  for (std::uint64_t r = 0; r < replica; ++r) gen.jump();
  return gen;
}

}  // namespace gdsmc::rng
