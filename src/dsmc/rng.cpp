#include "dsmc/rng.hpp"

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
