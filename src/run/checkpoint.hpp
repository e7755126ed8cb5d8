/**
 * \file checkpoint.hpp
 * \brief The checkpoint file of a rank (\ref output_checkpoint "docs/output.md"): the results of its
 *        finished work units and the state of those in progress, each a state::Record written by the
 *        modules themselves (dsmc/state.hpp), with a checksum, the input's fingerprint and the layout.
 *
 * The file is rewritten whole (temporary file + rename, io/h5md.hpp) whenever a unit in progress
 * reaches a safe point and its own snapshot is `every` seconds old, so that every thread's unit is
 * saved, not only the first to reach a safe point. `/checkpoint/format` is the layout of the records
 * (state::layout): this build writes 2 and reads 2 and 1 (the positional layout of the checkpoints
 * written before 2026-11-29, translated to the names of layout 2 as it is read); any other layout is
 * refused with a line that names it. The checksum (FNV-1a over every name and value in the order
 * written) is checked first, so that any damage is reported as such.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "dsmc/state.hpp"
#include "run/progress.hpp"
#include "run/results.hpp"

namespace gdsmc::simulation {

/// Rank k's file of the checkpoint whose rank-0 file is `path`.
std::string rank_file(const std::string& path, int rank);

/// A rank's checkpoint file (header).
class CheckpointStore {
 public:
  /// `path`: the file to write; `every`: seconds between snapshots of a unit (<= 0: never); `fingerprint`:
  /// the input's (namelist text and overrides); `ranks`: the MPI ranks of the run; `units`: work units.
  CheckpointStore(std::string path, double every, std::string fingerprint, int ranks, std::size_t units)
      : path_(std::move(path)), every_(every), fingerprint_(std::move(fingerprint)), ranks_(ranks),
        last_saved_(units, Clock::now()) {}

  /// Reads a checkpoint written by write(): checks that it is intact (its checksum), that it belongs to
  /// this input and rank count, and that its layout is one this build reads. Throws std::runtime_error.
  void load(const std::string& file);
  /// The result of a unit the checkpoint found finished, or nullptr.
  const ReplicaResult* finished_result(std::size_t unit) const;
  /// The state of a unit the checkpoint found in progress, or nullptr.
  const state::Record* resume_point(std::size_t unit) const;
  /// Unit `unit` finished with `result` (kept for the next write).
  void finished(std::size_t unit, const ReplicaResult& result);
  /// A safe point of unit `unit`: when its snapshot is `every` seconds old, a new one (taken by
  /// `snapshot`, outside the lock) replaces it and the file is rewritten.
  void safe_point(std::size_t unit, const std::function<state::Record()>& snapshot);
  /// Deletes the file (the run is complete).
  void remove() const;

 private:
  void write() const;

  std::string path_;
  double every_;
  std::string fingerprint_;
  int ranks_;
  std::mutex mutex_;
  std::map<std::size_t, ReplicaResult> done_;
  std::map<std::size_t, state::Record> running_;
  std::vector<Clock::time_point> last_saved_;  ///< per unit
};

/// Renames the values of a unit's record of layout 1 (positional arrays) to those of layout 2
/// (state::layout). Throws state::StateError for a record too short for its layout.
void upgrade_layout_1(state::Record& record);

}  // namespace gdsmc::simulation
