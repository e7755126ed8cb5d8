/**
 * \file particles.hpp
 * \brief The simulated particles of one replica: velocities as a structure of arrays, grouped by species.
 *
 * A homogeneous gas needs no positions (seed 003 sec. 3: a single cell), so a particle is its
 * velocity and its species. Particles of species k occupy the contiguous index range
 * [first[k], first[k] + count[k]), which makes "a random particle of species k" one integer draw
 * (pairs scheme) and keeps a species' velocities together for sampling.
 *
 * The number of simulated particles of species k is N_k = round(N n_k / n) (seed 003 eq 22 and the
 * relation N_i/N_j = n_i/n_j). Each simulated particle stands for n_k V / N_k real ones; the
 * collision schemes use the physical densities n_k directly, so V never appears.
 *
 * Initial velocities (`&initial distribution`): 'maxwell' (Gaussian, seed 003 eq 25), 'shell' (all
 * speeds equal, isotropic directions) or 'cube' (uniform in a cube). Then each species' mean velocity
 * is removed (so the total momentum is zero to round-off) and its velocities are scaled so that its
 * kinetic temperature is exactly T_k(0): the run starts at the requested temperatures, not at a
 * random estimate of them.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dsmc/rng.hpp"
#include "dsmc/species.hpp"

namespace gdsmc::particles {

enum class InitialDistribution { maxwell, shell, cube };

struct System {
  std::vector<double> vx, vy, vz;      ///< velocities, structure of arrays
  std::vector<std::uint32_t> species;  ///< species index of each particle
  std::vector<std::size_t> first;      ///< first index of species k
  std::vector<std::size_t> count;      ///< N_k

  /// Displacement tracking (seed 001 eq 15, ERRATA §7); empty when not tracked. R is the
  /// displacement accumulated up to t_last, the time of the particle's last collision (or of the
  /// start of tracking); its displacement at t >= t_last is R + v (t - t_last).
  std::vector<double> rx, ry, rz, t_last;

  std::size_t size() const { return vx.size(); }
  std::size_t n_species() const { return count.size(); }
  bool tracks_displacements() const { return !t_last.empty(); }
};

/// Starts (or restarts) displacement tracking at time t: R = 0 and t_last = t for every particle.
void start_tracking(System& sys, double t);

/// Adds particle i's free flight since t_last to R and sets t_last = t (before its velocity changes).
inline void flush_free_flight(System& sys, std::size_t i, double t) {
  const double dt = t - sys.t_last[i];
  sys.rx[i] += sys.vx[i] * dt;
  sys.ry[i] += sys.vy[i] * dt;
  sys.rz[i] += sys.vz[i] * dt;
  sys.t_last[i] = t;
}

/// N_k = round(N x_k) for each species (the caller checks N_k >= 2).
std::vector<std::size_t> species_counts(std::size_t n_particles, const species::Mixture& mix);

/// Particles with the given counts and velocities drawn from `distribution` at temperatures T_k.
System make_system(const species::Mixture& mix, const std::vector<std::size_t>& counts,
                   const std::vector<double>& temperature, InitialDistribution distribution,
                   rng::Xoshiro256pp& gen);

}  // namespace gdsmc::particles
