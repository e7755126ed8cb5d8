/**
 * \file results.hpp
 * \brief What one replica measured, how it travels between MPI ranks and into checkpoints, and how
 *        the replicas of one point are reduced, in replica order, to mean and standard error.
 *
 * A replica's rows (sample::Rows: per observable of model/observables.hpp its columns and its rows)
 * are reduced to one observables::Accumulator per observable: the replicas' rows in replica order, so that
 * every sum is the same however the replicas were spread over threads and ranks
 * (\ref output_page "docs/output.md": the same file, byte for byte).
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "dsmc/sample.hpp"
#include "dsmc/state.hpp"

namespace gdsmc::simulation {

/// What one replica of one point measured: its rows, and the scalars of the run's summary.
struct ReplicaResult : sample::Rows {
  double mean_step = 0.0;       ///< mean time step (bound refresh, or stage) of the replica
  std::uint64_t events = 0;     ///< its collision events
  double collide_seconds = 0.0; ///< thread-seconds of its collision loops: wall seconds x the threads its blocks ran on (the summary's rate)
  std::uint64_t cache_blocks = 0;  ///< its cache blocks (collide::Collider::blocks(); 1: the whole gas; 0: not known)
  std::uint64_t block_draw = 0;    ///< their draw (collide::Collider::BlockDraw as a number)
  std::uint64_t samples_past_target = 0;  ///< samples taken past their exact event target (replica.cpp, FreeGas::sample)
  std::uint64_t most_past_target = 0;     ///< the largest number of collisions past one
};

/// What one point (all its replicas) measured.
struct PointResult {
  std::map<std::string, observables::Accumulator> observables;  ///< per observable, the replicas' rows
  double mean_step = 0.0;        ///< the mean over the replicas of their mean step
  std::uint64_t events = 0;      ///< all replicas' events
  double collide_seconds = 0.0;  ///< all replicas' collision seconds
  std::uint64_t cache_blocks = 0;  ///< the replicas' cache blocks (the first that knows them; 0: none does)
  std::uint64_t block_draw = 0;    ///< and their draw (collide::Collider::BlockDraw)
  std::uint64_t samples_past_target = 0;  ///< the replicas' samples taken past their exact event target
  std::uint64_t most_past_target = 0;     ///< the largest number of collisions past one
};

/// Appends `result` of work unit `unit` to `out` (bytes of this machine: for another rank of the same run).
void pack(std::string& out, std::uint64_t unit, const ReplicaResult& result);
/// The result pack() wrote at `pos` (advanced past it), and its unit; throws std::runtime_error when cut short.
ReplicaResult unpack(const std::string& in, std::size_t& pos, std::uint64_t& unit);

/// The result under "result/..." of a checkpoint (dsmc/state.hpp).
void save(const ReplicaResult& result, state::Record& record);
/// The result save() wrote; throws state::StateError.
ReplicaResult load_result(const state::Record& record);

/// The rows of a result read from a checkpoint, checked against what `samples` samples make (a record
/// is read, not trusted: a row cut short would be read beyond its end when reduced): every row a whole
/// number of rows of its columns; a time series (observables.hpp Reduction::series) one row per sample;
/// a per-replica row exactly one (when `finished`; a unit in progress has none yet). Throws
/// state::StateError naming the row.
void check_rows(const ReplicaResult& result, std::size_t samples, bool finished);

/// The replica results of one point, reduced in replica order (the same order in every run). Throws
/// std::runtime_error when two replicas' rows of one observable differ in columns or length.
PointResult reduce_point(std::vector<ReplicaResult>& replicas);

/// The per-size observables of an &agg_frag replica ("number", "size_energy"): each sample's row as
/// wide as the largest cluster present then ("name@i"), padded with zeros to one width at the end of
/// the replica (pad_size_rows), and to the width of the widest replica of the point (pad_size_columns).
inline constexpr const char* kSizeObservables[] = {"number", "size_energy"};
/// "name@i": the row of sample i of a per-size observable.
std::string sample_row(const char* name, std::size_t i);
/// Joins a replica's `n_samples` rows "name@i" of each per-size observable into one padded observable.
void pad_size_rows(ReplicaResult& result, std::size_t n_samples);
/// Pads the per-size rows of all replicas of a point to the largest size any of them reached.
void pad_size_columns(std::vector<ReplicaResult>& replicas);

}  // namespace gdsmc::simulation
