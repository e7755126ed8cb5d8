/**
 * \file snapshot.hpp
 * \brief Particle snapshots: every particle's velocity (and angular velocity, displacement) of every
 *        replica at chosen times, in the H5MD `particles` group; and the start of a run from one
 *        (\ref output_snapshots "docs/output.md").
 *
 * Written with `&output snapshot_times = t1, t2, ...` (a time-driven run): for each replica r (from 1)
 * the group `<root>/particles/replica_<r>` (root: "" or /sweep/point_K) holds
 * - `species`: int64 [N], the species of each particle, from 1; particles of one species are contiguous
 *   and keep their place in this order (the order of particles within a species may change between
 *   snapshots: the cache blocks deal them, and the gas has no positions to follow them by);
 * - `velocity/{step, time, value}`: an H5MD time-dependent element, value float64 [snapshots][N][3]
 *   (unit `length time-1`), time the snapshot times, step the replica's collision events then;
 * - `angular_velocity` (rough spheres, unit `time-1`) and `displacement` (with &output
 *   track_displacements: R since the start of tracking, zero before it, unit `length`), shaped as velocity;
 * - `box` with attributes `dimension` = 3 and `boundary` = none, none, none (a homogeneous gas).
 * The run collects them as rows of its replica results (model/observables.hpp: `snapshot_time`,
 * `snapshot_species`, `snapshot_velocity`, ...), so that threads, MPI ranks and checkpoints carry them
 * as any other per-replica row.
 *
 * Read with `&initial from_file = 'x.h5'`: replica r of the run starts from replica ((r - 1) mod R') + 1
 * of the file (R' replicas there) at its last snapshot; the file's species counts must be those of
 * the run (n_particles split over the species as the run splits it). Checked by
 * tests/snapshot_test.cpp and tests/cli_test.cpp (CliSnapshot.*).
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <map>

#include "io/h5md.hpp"
#include "model/observables.hpp"
#include "model/species.hpp"

namespace gdsmc::io::snapshot {

/// One replica's snapshots: per-particle arrays row-major [snapshot][particle][3].
struct Replica {
  std::vector<std::int64_t> species;        ///< [N], from 1
  std::vector<double> time;                 ///< [S]
  std::vector<std::int64_t> step;           ///< [S], collision events of the replica
  std::vector<double> velocity;             ///< [S][N][3]
  std::vector<double> angular_velocity;     ///< [S][N][3], or empty
  std::vector<double> displacement;         ///< [S][N][3], or empty
};

/// The snapshots of every replica of a point from its rows (`snapshot_time` [time, events] per snapshot,
/// `snapshot_species`, `snapshot_velocity`, ...); empty when the run took none.
std::vector<Replica> from_rows(const std::map<std::string, observables::Accumulator>& rows);

/// Writes `replicas` under `root` + "/particles" (root "" or "/sweep/point_K").
void write(h5md::Writer& writer, const std::string& root, const std::vector<Replica>& replicas);

/// The state a run starts from: one replica's last snapshot.
struct State {
  std::vector<std::uint64_t> species;     ///< [N], from 1
  std::vector<double> velocity;          ///< [N][3]
  std::vector<double> angular_velocity;  ///< [N][3], or empty
  double time = 0.0;                     ///< the snapshot's time
};

/// The temperatures of a snapshot (k_B = 1): T_k = m_k <|v - u|^2>_k / 3 about the mass-weighted mean
/// velocity u, as dsmc/sample.cpp measures them, and T_rot,k = I_k <|w|^2>_k / 3 (empty without
/// angular velocities, or when `mix` is smooth).
struct Temperatures {
  std::vector<double> translational;  ///< T_k
  std::vector<double> rotational;     ///< T_rot,k
};
/// The Temperatures of `state` for the species of `mix`.
Temperatures temperatures(const State& state, const species::Mixture& mix);

/// The number of replicas /particles of `file` holds (0 when it has none). Throws std::runtime_error
/// when `file` is missing, not a file or not an output of granular-dsmc.
std::size_t replicas(const std::string& file);
/// Replica `r` (from 0, taken modulo replicas(file)) of `file` at its last snapshot: its species from 1,
/// in order, with `counts[k]` particles of species k + 1 when `counts` is given; velocities (and angular
/// velocities) [N][3], finite. Throws std::runtime_error saying what is missing or inconsistent (a
/// sweep's output: its snapshots are per point).
State read(const std::string& file, std::size_t r, const std::vector<std::size_t>& counts = {});
/// Throws std::runtime_error when the masses of `file`'s /parameters/system are not `masses`.
void check_masses(const std::string& file, const std::vector<double>& masses);

}  // namespace gdsmc::io::snapshot
