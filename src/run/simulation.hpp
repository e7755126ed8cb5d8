/**
 * \file simulation.hpp
 * \brief A whole run: Config -> System -> collide -> sample -> H5MD file, for every replica.
 *
 * Replica r draws its initial velocities from stream (seed, r, initial_state) and its collisions
 * from stream (seed, r, collisions) (see rng.hpp), so a replica's trajectory does not depend on how
 * many replicas run or in which order. Observables are reduced, in replica order, to
 * the mean and standard error over replicas (sample.hpp) and written by io::h5md.
 *
 * A time-driven run (`t_end`) samples at the times of Config::sample_times(). A collision-driven
 * run (`collisions_per_particle`) samples when 2 x events / N reaches each value of
 * Config::sample_collisions(); its `time` datasets then hold the mean over replicas of the times
 * at which that happened, with the spread in the observable `time`.
 *
 * Replicas and sweep points are independent work units spread over MPI ranks and OpenMP threads
 * (parallel.hpp); their results are reduced in unit order, so the file is the same, byte for byte,
 * however the run is spread. With `&output checkpoint_every`, each rank rewrites its checkpoint file
 * (`<stem>.checkpoint.h5`, `<stem>.checkpoint.rank<k>.h5`) at safe points: after each chunk of 2^20
 * collisions and after each sample, where a stop changes nothing. `--restart` loads it and continues;
 * the output is the same as that of an uninterrupted run (tests/scale_out/restart.sh). The checkpoint
 * is removed when the run completes.
 *
 * The output file is opened (under a temporary name) before the first collision, so an
 * unwritable path fails at once, and renamed into place only when complete.
 */
#pragma once

#include <atomic>
#include <functional>
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/config.hpp"

namespace gdsmc::simulation {

struct Options {
  bool progress = false;                         ///< progress line on stderr
  /// stderr is a terminal: the line is rewritten in place; otherwise a full line every 10 s.
  bool progress_terminal = true;
  const std::atomic<bool>* interrupt = nullptr;  ///< set by a signal handler: stop, write nothing
  /// The line an interrupt while the output is written ends the process with, when the writing cannot see
  /// it (inside one write of the HDF5 library): the caller's (what to resume from); unset: Interrupted's.
  std::function<std::string()> interrupt_line;
  std::string restart_path;                      ///< continue from this checkpoint (empty: from the start)
  /// The output and the checkpoints replace whatever is at their paths at the end (--force); otherwise a
  /// file that is not granular-dsmc's and appeared during the run is kept (io/h5md.hpp Writer::commit).
  bool replace_any_file = false;
  /// Called on rank 0 when the file is complete, just before it is committed: may add groups (the
  /// /comparison of --compare, analysis/compare.hpp) and read the file back under writer.temporary_path().
  std::function<void(io::h5md::Writer&)> before_commit;
};

/// What the run measured, as written to the file (for the caller's summary).
struct Summary {
  double final_time = 0.0;               ///< the last point's mean final time
  double final_total_temperature = 0.0;  ///< its mean final T
  double collisions_per_particle = 0.0;  ///< its mean collisions per particle
  double wall_seconds = 0.0;             ///< the whole run, wall clock
  double events_per_second = 0.0;        ///< events per thread-second of the collision loops (ReplicaResult::collide_seconds)
  double events = 0.0;                   ///< every replica's collision events
  double restored_events = 0.0;          ///< of those, the ones a --restart checkpoint held (made by an earlier process)
  /// How a replica sampled its collisions (/parameters attributes cache_blocks and block_draw).
  struct Blocks {
    std::uint64_t count = 0;   ///< its cache blocks (1: the whole gas; 0: not known)
    std::string draw;          ///< their draw (collide.hpp BlockDraw's name)
    double per_block = 0.0;    ///< the particles (with &agg_frag, initial clusters) of a block
  };
  /// One sweep point's final values (the mean over its replicas).
  struct Point {
    std::string label;                     ///< "variable = value"
    double final_time = 0.0;               ///< t
    double final_total_temperature = 0.0;  ///< T
    double collisions_per_particle = 0.0;  ///< collisions per particle
    Blocks blocks;                         ///< its replicas' cache blocks
  };
  std::vector<Point> points;  ///< every point of a sweep (empty for a single run)
  /// Candidates of all replicas whose acceptance probability exceeded 1 (collide.hpp
  /// Counters::overshoots; also the observable `acceptance_overshoots`): 0 in a correct run.
  double acceptance_overshoots = 0.0;
  /// Samples taken past their exact event target, over every replica and point (collide.hpp "Event
  /// targets": a blocked step whose collision rate rose many times within it)
  std::uint64_t samples_past_target = 0;
  std::uint64_t most_past_target = 0;  ///< the largest number of collisions past one
  /// Replicas (of every point) with tracked displacements that never reached msd_start_time or
  /// msd_start_temperature: their msd is zero at every sample, their /observables/msd/start_time -1
  std::uint64_t msd_never_started = 0;
  std::uint64_t msd_replicas = 0;  ///< the replicas with tracked displacements
  std::string msd_start_missed;    ///< the first such replica's start, e.g. "msd_start_time = 5 (point 2)"
  Blocks blocks;  ///< the last point's cache blocks
};



/// The output file could not be created: an input error (the path), raised before any work.
struct OutputPathError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Thrown on the other ranks when rank 0 could not write the output (rank 0 says why; exit status 1).
struct RootFailed : std::runtime_error {
  RootFailed() : std::runtime_error("rank 0 could not write the output") {}
};

/// The checkpoint given to --restart cannot be used (unreadable, or written for another input).
struct RestartError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A replica cannot reach its event target (an aggregating gas became one cluster before it): the run
/// fails, and its checkpoints are removed, since a run resumed from them would fail the same way.
struct UnreachableTarget : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted: no output written") {}
};

/// Candidates between two looks at the interrupt flag (and the progress line and checkpoints) in
/// the loops that call advance(): about 1e5, a few milliseconds of work; more (up to 2^24) when one
/// time step has more (simulation.cpp, run_replica).
inline constexpr double chunk_candidates = 131072.0;

/// The end in time of the next advance() chunk of a replica: `chunk` candidates at the run's mean
/// candidate rate so far, candidates / time (time advances 1/R per candidate, collide.hpp), never
/// beyond `t_target`; `t_target` itself before the first candidate. The chunks end at the events
/// too (2^20), but an event can take ever more candidates (a gas cooled by many decades: its relative
/// speeds fall below the round-off of the conserved momentum, and almost every candidate is rejected),
/// so the time ends keep the interrupt flag seen within a second. The end depends only on the state a
/// checkpoint restores, so a resumed run splits its chunks at the same times.
double chunk_end_time(double time, std::uint64_t candidates, double t_target, double chunk = chunk_candidates);

/// `<output stem>.checkpoint.h5` (\ref output_checkpoint "docs/output.md"), `.rank<k>` before `.h5` for MPI rank k > 0.
std::string checkpoint_path(const std::string& output_path, int rank = 0);

/// The memory a rank of this run holds at most, in bytes (a lower bound, to refuse runs that cannot fit):
/// the particle arrays of the replicas it runs at once (min(its units, threads)) at 28 bytes per particle
/// (velocity, species), 32 more with displacements, 24 more for rough spheres' angular velocities, and
/// as much again while a checkpoint or snapshot copies them; &agg_frag clusters as particles; and the
/// sample rows of its units (all of them on rank 0, which gathers them), 64 bytes per species and sample.
double estimated_memory_bytes(const io::config::Config& config, int threads, int ranks);
/// Of that, the sample rows: every unit's (rank 0 gathers them), 64 bytes per species and sample.
double estimated_sample_bytes(const io::config::Config& config);

/// `<output stem>.lock`: the lock file that keeps two runs off one output and its checkpoint (io/file_lock.hpp).
std::string lock_path(const std::string& output_path);

/// What lies at a checkpoint path: nothing, the checkpoint of a run of this input (an interrupted one:
/// same namelist text and overrides), that of another input, or a file that is not a checkpoint.
enum class CheckpointFound { none, this_input, other_input, not_a_checkpoint };
/// What lies at the checkpoint path of `output_path` (rank 0's file). A fresh run starts only on `none`
/// (granular-dsmc refuses the others without --restart or --force: the checkpoint would be replaced).
CheckpointFound find_checkpoint(const io::config::Config& config, const std::string& output_path);

/// FNV-1a (64 bits) of `bytes` bytes at `data`, continuing from `hash`: the checksum of checkpoints.
std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t bytes);

/// Runs the simulation the Config describes and writes `output_path`. Throws OutputPathError when
/// the file cannot be created (before any work), simulation::Interrupted when interrupted, and
/// std::runtime_error on any other failure; nothing is left behind in every case.
Summary run(const io::config::Config& config, const std::string& output_path, const Options& options);

}  // namespace gdsmc::simulation
