#include "dsmc/particles.hpp"

#include <new>
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <cstring>
#include <cmath>
#include <numeric>

namespace gdsmc::particles {

void* allocate_bytes(std::size_t bytes) {
  constexpr std::size_t huge_page = std::size_t{1} << 21;
  if (bytes < huge_page) {
    void* p = std::malloc(bytes == 0 ? 1 : bytes);
    if (!p) throw std::bad_alloc();
    return p;
  }
  const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
  void* p = std::aligned_alloc(huge_page, rounded);
  if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure only costs speed
#endif
  return p;
}

const char* release_pages(const char* begin, const char* end) {
#if defined(__linux__) && defined(MADV_DONTNEED)
  static const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const std::uintptr_t lo = (reinterpret_cast<std::uintptr_t>(begin) + page - 1) / page * page;
  const std::uintptr_t hi = reinterpret_cast<std::uintptr_t>(end) / page * page;
  if (hi <= lo) return begin;
  madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_DONTNEED);  // a hint: failure only keeps the memory
  return reinterpret_cast<const char*>(hi);
#else
  (void)end;
  return begin;
#endif
}


System make_system(const species::Mixture& mix, const std::vector<std::size_t>& counts,
                   const std::vector<double>& temperature, InitialDistribution distribution,
                   rng::Xoshiro256pp& gen, const SetUpCheck& check) {
  System sys;
  const std::size_t s = counts.size();
  sys.first.resize(s);
  sys.count = counts;
  std::size_t total = 0;
  for (std::size_t k = 0; k < s; ++k) {
    sys.first[k] = total;
    total += counts[k];
  }
  sys.v.resize(total);
  sys.species.resize(total);

  for (std::size_t k = 0; k < s; ++k) {
    const std::size_t begin = sys.first[k], end = begin + counts[k];
    // Any scale will do: the velocities are rescaled to T_k below.
    for (std::size_t i = begin; i < end; ++i) {
      if (i % set_up_stride == 0 && check) check();
      sys.species[i] = static_cast<std::uint32_t>(k);
      switch (distribution) {
        case InitialDistribution::maxwell:
          sys.v[i].x = gen.normal();
          sys.v[i].y = gen.normal();
          sys.v[i].z = gen.normal();
          break;
        case InitialDistribution::shell:
          rng::unit_vector(gen, sys.v[i].x, sys.v[i].y, sys.v[i].z);
          break;
        case InitialDistribution::cube:
          sys.v[i].x = 2.0 * gen.uniform() - 1.0;
          sys.v[i].y = 2.0 * gen.uniform() - 1.0;
          sys.v[i].z = 2.0 * gen.uniform() - 1.0;
          break;
      }
    }
    double mean[3] = {0.0, 0.0, 0.0};
    for (std::size_t i = begin; i < end; ++i) {
      mean[0] += sys.v[i].x;
      mean[1] += sys.v[i].y;
      mean[2] += sys.v[i].z;
    }
    for (double& m : mean) m /= static_cast<double>(counts[k]);
    double sum_sq = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      sys.v[i].x -= mean[0];
      sys.v[i].y -= mean[1];
      sys.v[i].z -= mean[2];
      sum_sq += sys.v[i].x * sys.v[i].x + sys.v[i].y * sys.v[i].y + sys.v[i].z * sys.v[i].z;
    }
    // T_k = m_k <|v|^2> / 3 (`temperature`, \ref output_observables "docs/output.md")
    const double current = mix.mass[k] * sum_sq / (3.0 * static_cast<double>(counts[k]));
    const double scale = std::sqrt(temperature[k] / current);
    for (std::size_t i = begin; i < end; ++i) {
      sys.v[i].x *= scale;
      sys.v[i].y *= scale;
      sys.v[i].z *= scale;
    }
  }
  return sys;
}

void add_angular_velocities(System& sys, const species::Mixture& mix, const std::vector<double>& rotational_temperature,
                            const std::string& name, rng::Xoshiro256pp& gen, const SetUpCheck& check) {
  auto& w = sys.add_array<Vec3>(name);
  for (std::size_t k = 0; k < sys.n_species(); ++k) {
    const std::size_t begin = sys.first[k], end = begin + sys.count[k];
    double sum_sq = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      if (i % set_up_stride == 0 && check) check();
      w[i] = {gen.normal(), gen.normal(), gen.normal()};
      sum_sq += w[i].x * w[i].x + w[i].y * w[i].y + w[i].z * w[i].z;
    }
    // T_rot,k = I_k <|w|^2>/3 (\ref rough_observables "docs/rough-spheres.md")
    const double current = mix.inertia(k) * sum_sq / (3.0 * static_cast<double>(sys.count[k]));
    const double scale = rotational_temperature[k] > 0.0 ? std::sqrt(rotational_temperature[k] / current) : 0.0;
    for (std::size_t i = begin; i < end; ++i) w[i] = {w[i].x * scale, w[i].y * scale, w[i].z * scale};
  }
}

void start_tracking(System& sys, double t) {
  const std::size_t n = sys.size();
  sys.r.assign(n, Displacement{0.0, 0.0, 0.0, t});
}

void save(const System& sys, state::Record& r) {
  sys.for_each_array([&](const char* name, const auto& a) {
    std::string key = "particles/";  // (not "particles/" + name: a false -Warray-bounds of GCC 12)
    key += name;
    std::vector<double> out(a.size() * (sizeof(a[0]) / sizeof(double)));
    std::memcpy(out.data(), a.data(), out.size() * sizeof(double));
    r.put(key, std::move(out));
  });
  r.put("particles/species", std::vector<std::uint64_t>(sys.species.begin(), sys.species.end()));
}

void restore(System& sys, const state::Record& r) {
  const auto& species = r.integer_array("particles/species");
  if (species.size() != sys.size()) throw state::StateError("the particle count does not match the input");
  for (std::size_t i = 0; i < sys.size(); ++i)  // the species layout is fixed by the input's counts
    if (species[i] != sys.species[i])
      throw state::StateError("particle " + std::to_string(i) + " has species " + std::to_string(species[i]) +
                              ", the input gives " + std::to_string(sys.species[i]));
  // Tracking may have started during the run: the displacements then exist from there on.
  if (r.has("particles/displacement") && !sys.tracks_displacements()) sys.r.resize(sys.size());
  sys.for_each_array([&](const char* name, auto& a) {
    std::string key = "particles/";
    key += name;
    const auto& values = r.array(key, a.size() * (sizeof(a[0]) / sizeof(double)));
    std::memcpy(a.data(), values.data(), values.size() * sizeof(double));
  });
  // A gas at rest is no state of a run (it starts at T > 0, and no collision stops both partners): nothing
  // would collide again, and a collision-driven sample would never come.
  if (std::all_of(sys.v.begin(), sys.v.end(), [](const Vec3& u) { return u.x == 0.0 && u.y == 0.0 && u.z == 0.0; }))
    throw state::StateError("every particle is at rest");
}

}  // namespace gdsmc::particles
