/**
 * \file particles.hpp
 * \brief The simulated particles of one replica: velocities and species as parallel arrays, grouped by species.
 *
 * A homogeneous gas needs no positions (Montanero and Garzo 2002, sec. 3, \ref sch_pairs "docs/schemes.md": a single cell), so a particle is its
 * velocity and its species. Particles of species k occupy the contiguous index range
 * [first[k], first[k] + count[k]), which makes "a random particle of species k" one integer draw
 * (pairs scheme) and keeps a species' velocities together for sampling.
 *
 * The number of simulated particles of species k is N_k = round(N n_k / n) (Montanero and Garzo 2002, eq. (22), \ref cm_initial "docs/collision-model.md" and the
 * relation N_i/N_j = n_i/n_j). Each simulated particle stands for n_k V / N_k real ones; the
 * collision schemes use the physical densities n_k directly, so V never appears.
 *
 * Layout: each particle's three velocity components are stored together (Vec3, 24 bytes), beside a
 * parallel species array (4 bytes): a collision reads and writes all three components of two random
 * particles, so this is one memory access per particle where three separate component arrays would
 * be three, which is what limits the collision loop at N = 1e6 (bench/bench_collide.cpp; measured:
 * \ref perf_lookahead "docs/performance.md").
 * Tracked displacements keep R and t_last together (32 bytes) for the same reason.
 *
 * Initial velocities (`&initial distribution`): 'maxwell' (Gaussian, Montanero and Garzo 2002, eq. (25), \ref cm_initial "docs/collision-model.md"), 'shell' (all
 * speeds equal, isotropic directions) or 'cube' (uniform in a cube). Then each species' mean velocity
 * is removed (so the total momentum is zero to round-off) and its velocities are scaled so that its
 * kinetic temperature is exactly T_k(0): the run starts at the requested temperatures, not at a
 * random estimate of them.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <functional>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "dsmc/rng.hpp"
#include "dsmc/state.hpp"
#include "model/species.hpp"

namespace gdsmc::particles {

/// Initial velocity distribution (`&initial distribution`).
enum class InitialDistribution {
  maxwell,  ///< Gaussian at the initial temperature
  shell,    ///< every speed equal, directions uniform
  cube      ///< components uniform in a cube
};

/// Allocator for the per-particle arrays: blocks of 2 MiB and more are 2 MiB-aligned and, on Linux,
/// marked for transparent huge pages (madvise). The collision loop reads particles at random; with
/// 4 KiB pages, 1e6 particles span 7000 pages, more than the TLB holds, and every read would
/// also miss the TLB. Falls back to ordinary pages where huge pages are unavailable.
void* allocate_bytes(std::size_t bytes);  ///< throws std::bad_alloc; free with std::free

/// Returns to the system the whole memory pages inside [begin, end) of a buffer whose bytes there will
/// not be read again before it is freed (Linux: madvise MADV_DONTNEED; elsewhere nothing), so that
/// the resident memory falls while a large array is consumed front to back and copied elsewhere
/// (agg_frag.hpp, "Cache blocks": the deal). Returns the end of the last page released, or `begin`
/// when [begin, end) holds no whole page: the next call then starts there.
const char* release_pages(const char* begin, const char* end);

/// std::allocator replacement that takes its blocks from allocate_bytes (huge pages where possible).
template <class T>
struct LargePageAllocator {
  using value_type = T;  ///< the element type
  LargePageAllocator() = default;
  /// Rebinding copy (stateless).
  template <class U>
  LargePageAllocator(const LargePageAllocator<U>&) {}
  /// Storage for `n` elements; throws std::bad_alloc.
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_bytes(n * sizeof(T))); }
  /// Frees storage of allocate().
  void deallocate(T* p, std::size_t) { std::free(p); }
  /// Stateless: all instances are equal.
  template <class U>
  bool operator==(const LargePageAllocator<U>&) const { return true; }
};

/// A per-particle array on LargePageAllocator.
template <class T>
using ParticleArray = std::vector<T, LargePageAllocator<T>>;

/// LargePageAllocator whose resize() default-initialises: for a trivial T the new elements are left
/// unwritten, so that an array sized first and filled later (by several threads, at places computed in
/// advance) touches each page only when it writes it (agg_frag.hpp, "Memory").
template <class T>
struct FillLaterAllocator : LargePageAllocator<T> {
  FillLaterAllocator() = default;
  /// Rebinding copy (stateless).
  template <class U>
  FillLaterAllocator(const FillLaterAllocator<U>&) {}
  /// Default-initialises without arguments, as placement new with them otherwise.
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0)
      ::new (static_cast<void*>(p)) U;
    else
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// An array on FillLaterAllocator: resize() leaves trivial elements unwritten.
template <class T>
using FillLaterArray = std::vector<T, FillLaterAllocator<T>>;

/// A velocity (or any 3-vector) in the user's units.
struct Vec3 {
  double x;  ///< x component
  double y;  ///< y component
  double z;  ///< z component
  bool operator==(const Vec3&) const = default;  ///< componentwise, exact
};

/// A tracked displacement R, accumulated up to the time t_last (see System::r).
struct Displacement {
  double x;       ///< R_x up to t_last
  double y;       ///< R_y up to t_last
  double z;       ///< R_z up to t_last
  double t_last;  ///< time of the last collision (or of the start of tracking)
  bool operator==(const Displacement&) const = default;  ///< componentwise, exact
};

/// The particles of one replica, sorted by species: particle i of species k is at first[k] + i.
struct System {
  ParticleArray<Vec3> v;               ///< velocities
  ParticleArray<std::uint32_t> species;  ///< species index of each particle
  std::vector<std::size_t> first;      ///< first index of species k
  std::vector<std::size_t> count;      ///< N_k

  /// Displacement tracking (Bodrova and Osinsky 2024, eq. (15), \ref sch_displacements "docs/schemes.md"); empty when not tracked. R is the
  /// displacement accumulated up to t_last, the time of the particle's last collision (or of the
  /// start of tracking); its displacement at t >= t_last is R + v (t - t_last).
  ParticleArray<Displacement> r;

  /// A further per-particle array of a collision rule or a forcing (the angular velocity of rough
  /// spheres, say): its name, and one value (a number or a 3-vector) per particle.
  struct Extra {
    std::string name;  ///< its name: particles/\<name\> in checkpoints
    std::variant<ParticleArray<double>, ParticleArray<Vec3>> values;  ///< one per particle, in particle order
  };
  std::deque<Extra> extra;  ///< the further arrays, in the order they were added (a deque: adding one keeps the others in place)

  /// Calls f(name, array) for every per-particle array that moves with its particle: `velocity`,
  /// `displacement` (when tracked) and each extra array, `array` a ParticleArray of its own element
  /// type. Whatever permutes the particles (the blocks' remix and scatter, collide.hpp) or saves them
  /// (checkpoints) goes through this list, so that an array a new rule adds needs no change there.
  /// The species array never moves (the species' ranges are fixed) and is not in the list.
  template <class F>
  void for_each_array(F&& f) {
    visit_arrays(*this, f);
  }
  /// The same, read only.
  template <class F>
  void for_each_array(F&& f) const {
    visit_arrays(*this, f);
  }
  /// An extra array named `name`, of values of type T (double or Vec3), all zero; throws
  /// std::invalid_argument when the name is taken.
  template <class T>
  ParticleArray<T>& add_array(const std::string& name) {
    if (name == "velocity" || name == "displacement" || find_array(name))
      throw std::invalid_argument("particles: an array named '" + name + "' exists");
    extra.push_back({name, ParticleArray<T>(size(), T{})});
    return std::get<ParticleArray<T>>(extra.back().values);
  }
  /// The extra array named `name`, or nullptr.
  Extra* find_array(const std::string& name) {
    for (Extra& e : extra)
      if (e.name == name) return &e;
    return nullptr;
  }

  /// N, the number of particles.
  std::size_t size() const { return v.size(); }

 private:
  template <class Self, class F>
  static void visit_arrays(Self& self, F& f) {
    f("velocity", self.v);
    if (self.tracks_displacements()) f("displacement", self.r);
    for (auto& e : self.extra) std::visit([&](auto& values) { f(e.name.c_str(), values); }, e.values);
  }

 public:
  /// S, the number of species.
  std::size_t n_species() const { return count.size(); }
  /// Displacements are tracked (r is not empty).
  bool tracks_displacements() const { return !r.empty(); }
};

/// Every array of `sys` (System::for_each_array) under "particles/\<name\>" as its doubles in particle
/// order, and the species under "particles/species", for checkpoints (dsmc/state.hpp).
void save(const System& sys, state::Record& record);
/// Restores save()'s arrays into a System made for the same input (the same counts: the species must
/// be those the input gives); a "particles/displacement" starts the tracking. Throws state::StateError.
void restore(System& sys, const state::Record& record);

/// The caller's look at its interrupt flag during a set-up whose time grows with N (make_system,
/// add_angular_velocities, collide::Collider::use_blocks): called about every set_up_stride particles, it
/// may throw to abandon the set-up, whose partial result is then discarded, so that Ctrl-C is noticed
/// within a second however large the gas. Empty (the default): never called.
using SetUpCheck = std::function<void()>;
/// Particles between two calls of a SetUpCheck: a few milliseconds of velocity draws.
inline constexpr std::size_t set_up_stride = std::size_t{1} << 16;

/// Adds the array `name` of angular velocities of rough spheres: Gaussian components, scaled per species
/// so that I_k <|w|^2>/3 is exactly T_rot,k (I_k = mix.inertia(k)); the mean is not removed (angular
/// velocities have no conserved mean). Drawn from `gen` (its own stream: the velocities' draws stay those of
/// the smooth gas).
void add_angular_velocities(System& sys, const species::Mixture& mix, const std::vector<double>& rotational_temperature,
                            const std::string& name, rng::Xoshiro256pp& gen, const SetUpCheck& check = {});

/// Starts (or restarts) displacement tracking at time t: R = 0 and t_last = t for every particle.
void start_tracking(System& sys, double t);

/// Adds particle i's free flight since t_last to R and sets t_last = t (before its velocity changes).
inline void flush_free_flight(System& sys, std::size_t i, double t) {
  Displacement& r = sys.r[i];
  const Vec3& v = sys.v[i];
  const double dt = t - r.t_last;
  r.x += v.x * dt;
  r.y += v.y * dt;
  r.z += v.z * dt;
  r.t_last = t;
}

/// Particles with the given counts and velocities drawn from `distribution` at temperatures T_k.
System make_system(const species::Mixture& mix, const std::vector<std::size_t>& counts,
                   const std::vector<double>& temperature, InitialDistribution distribution,
                   rng::Xoshiro256pp& gen, const SetUpCheck& check = {});

}  // namespace gdsmc::particles
