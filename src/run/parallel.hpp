/**
 * \file parallel.hpp
 * \brief Where a run's work units (one replica of one sweep point) execute: MPI ranks, then threads.
 *
 * A run is a list of independent work units u = (point p, replica r), numbered point-major
 * (u = p R + r). Unit u runs on MPI rank u mod K of K ranks; within a rank, OpenMP threads take the
 * rank's units one at a time. Each unit's random numbers come from its own streams (seed, r, purpose)
 * (rng.hpp), so what a unit computes does not depend on where or when it runs. Rank 0 collects every
 * unit's result, and the replica statistics are then reduced in unit order, always the same order: the
 * output file is bitwise the same for any number of ranks and threads (simulation.hpp).
 *
 * MPI is used only when the executable was started by an MPI launcher (mpirun sets
 * OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK) and the build found MPI; otherwise there is one
 * rank, and nothing here calls MPI. Without OpenMP there is one thread per rank.
 */
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace gdsmc::parallel {

/// Initialises MPI for the lifetime of the object when launched by mpirun (see above).
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();  ///< finalises MPI if finish() was not called (a path that left by an exception)
  /// Ends MPI and returns this process's exit status for a run that ended with `status` on every rank
  /// (the ranks agree: each rank's failure or interrupt is gathered and broadcast, simulation.hpp).
  /// Every rank must call it. Open MPI's mpirun aborts the job when a rank exits non-zero, and a rank
  /// still inside MPI_Finalize then waits out the launcher's 2 s timeout before it ends; so with
  /// several ranks, rank 0 alone exits with the largest of the ranks' statuses (mpirun and srun report
  /// it), the other ranks with 0, and rank 0 only after the other ranks on its node have ended (at most 1 s).
  int finish(int status);
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

int rank();  ///< this process's rank (0 without MPI)
int size();  ///< number of ranks (1 without MPI)
bool built_with_mpi();
int threads();  ///< OpenMP threads per rank (1 without OpenMP)

/// How a rank's threads serve its `units` work units: `units` threads take the units in turn, and
/// each unit's cache blocks may use `per_unit` threads (collide.hpp, "Threads inside one replica"):
/// with at least as many units as threads, one thread per unit; with fewer, threads / units for each
/// (nested OpenMP is enabled for it). What a unit computes does not depend on either number.
struct ThreadSplit {
  int units = 1;     ///< threads taking the units in turn
  int per_unit = 1;  ///< threads of each unit's cache blocks
};
/// The split of this rank's threads() over `units` work units (see ThreadSplit).
ThreadSplit split_threads(std::size_t units);

/// A failure that every rank throws alike, the ranks having agreed on it (a refused gather or broadcast
/// below, a run's failure on any rank: simulation.cpp): the program reports it once, on rank 0.
struct AgreedFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Rank 0 receives every rank's buffer, in rank order (its own first); other ranks get an empty list.
/// Collective: beyond 2^31 - 1 bytes in all (MPI's int counts) every rank throws AgreedFailure.
std::vector<std::string> gather_to_root(const std::string& mine);
/// Rank 0's value, on every rank (collective: beyond 2^31 - 1 bytes every rank throws AgreedFailure).
std::string broadcast_from_root(const std::string& value);
/// The largest of every rank's `value`, on every rank (collective: every rank must call it).
int largest_over_ranks(int value);

}  // namespace gdsmc::parallel
