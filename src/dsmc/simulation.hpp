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
#include <string>

#include "io/config.hpp"

namespace gdsmc::simulation {

struct Options {
  bool progress = false;                         ///< progress line on stderr
  /// stderr is a terminal: the line is rewritten in place; otherwise a full line every 10 s.
  bool progress_terminal = true;
  const std::atomic<bool>* interrupt = nullptr;  ///< set by a signal handler: stop, write nothing
  std::string restart_path;                      ///< continue from this checkpoint (empty: from the start)
  /// Called on rank 0 when the file is complete, just before it is committed: may add groups (the
  /// /comparison of --compare, io/compare.hpp) and read the file back under writer.temporary_path().
  std::function<void(io::h5md::Writer&)> before_commit;
};

/// What the run measured, as written to the file (for the caller's summary).
struct Summary {
  double final_time = 0.0;
  double final_total_temperature = 0.0;
  double collisions_per_particle = 0.0;
  double wall_seconds = 0.0;
  double events_per_second = 0.0;
  /// Candidates of all replicas whose acceptance probability exceeded 1 (collide.hpp
  /// Counters::overshoots; also the observable `acceptance_overshoots`): 0 in a correct run.
  double acceptance_overshoots = 0.0;
};



/// The output file could not be created: an input error (the path), raised before any work.
struct OutputPathError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The checkpoint given to --restart cannot be used (unreadable, or written for another input).
struct RestartError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted: no output written") {}
};

/// Runs the simulation the Config describes and writes `output_path`. Throws OutputPathError when
/// the file cannot be created (before any work), simulation::Interrupted when interrupted, and
/// std::runtime_error on any other failure; nothing is left behind in every case.
Summary run(const io::config::Config& config, const std::string& output_path, const Options& options);

}  // namespace gdsmc::simulation
