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
 * written) is checked first, so that any damage is reported as such. `/checkpoint@run` (outside the
 * checksum) is a random token of the run that wrote it: a complete run deletes only its own checkpoint
 * or the one it resumed, never another run's at the same path.
 */
#pragma once

#include <atomic>
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

/// The checksum of the content of the checkpoint `file` as load() computes it (whatever its stored
/// checksum says): for tools that rewrite a checkpoint, and the tests that forge one field to see it
/// refused for its content. Throws std::runtime_error for a file that is no checkpoint.
std::string content_checksum(const std::string& file);

/// The line between the namelist text and the overrides (--set, and what --output became) in an input's
/// fingerprint (simulation.cpp fingerprint_of): the text, the marker, then one override a line.
inline constexpr const char* fingerprint_overrides_marker = "\n--overrides--\n";

/// The overrides as command-line options for a message: `--set V` each (V an io::namelist::shell_word), e.g.
/// --set "output:file='x.h5'"; "" for none.
std::string override_options(const std::vector<std::string>& overrides);

/// What differs between the fingerprint a checkpoint holds and that of this run's input, for the line of
/// a refused --restart: the namelist text, or the overrides each was given (`--set V` as on the command line).
std::string fingerprint_difference(const std::string& stored, const std::string& current);

/// A random token (16 hex digits) that tells the checkpoint files of one run from those of another.
std::string new_run_token();

/// A rank's checkpoint file (header).
class CheckpointStore {
 public:
  /// `path`: the file to write; `every`: seconds between snapshots of a unit (<= 0: never); `fingerprint`:
  /// the input's (namelist text and overrides); `ranks`: the MPI ranks of the run; `units`: work units.
  CheckpointStore(std::string path, double every, std::string fingerprint, int ranks, std::size_t units)
      : path_(std::move(path)), run_token_(new_run_token()), every_(every), fingerprint_(std::move(fingerprint)), ranks_(ranks),
        last_saved_(units, Clock::now()) {}

  /// Reads a checkpoint written by write(): checks that it is intact (its checksum), that it belongs to
  /// this input and rank count, and that its layout is one this build reads. Throws std::runtime_error.
  void load(const std::string& file);
  /// The result of a unit the checkpoint found finished, or nullptr.
  const ReplicaResult* finished_result(std::size_t unit) const;
  /// The state of a unit the checkpoint found in progress, or nullptr.
  const state::Record* resume_point(std::size_t unit) const;
  /// Collision events the loaded checkpoint holds (finished units and those in progress): the work done
  /// before the restart, which the summary's overall rate leaves out. 0 without a checkpoint.
  std::uint64_t restored_events() const;
  /// Unit `unit` finished with `result` (kept for the next write).
  void finished(std::size_t unit, const ReplicaResult& result);
  /// A safe point of unit `unit`: when its snapshot is `every` seconds old, a new one (taken by
  /// `snapshot`, outside the lock) replaces it and the file is rewritten.
  void safe_point(std::size_t unit, const std::function<state::Record()>& snapshot);
  /// The run is complete: deletes the file if it is this run's (written by it: its `/checkpoint@run`
  /// token is this store's) or the checkpoint it resumed (its token, or the very file given to
  /// --restart when that has no token); a file of another run at the same path is left alone. Whether a
  /// file was removed.
  bool remove() const;
  /// Its files replace whatever is at the path (--force; io/h5md.hpp Writer::commit).
  void replace_any_file() { replace_any_ = true; }
  /// A flag (the caller's interrupt flag) that, once set, abandons a file being written between two of its
  /// datasets (a checkpoint of a gigabyte takes seconds): its temporary removed, the last checkpoint kept,
  /// and Interrupted thrown. nullptr (the default): never.
  void set_stop_flag(const std::atomic<bool>* stop) { stop_ = stop; }

 private:
  void write() const;

  std::string path_;
  std::string run_token_;                ///< `/checkpoint@run` of the files this store writes (random)
  std::string resumed_token_;            ///< that of the checkpoint load() read ("" if none or none in it)
  std::string resumed_path_;             ///< the file load() read
  mutable bool written_ = false;         ///< write() has written path_
  bool replace_any_ = false;             ///< replace_any_file()
  const std::atomic<bool>* stop_ = nullptr;  ///< set_stop_flag()
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
