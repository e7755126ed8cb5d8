/**
 * \file read_guard.hpp
 * \brief A watch over the read of a file the user names (a checkpoint, an output read back by `--table`):
 *        the HDF5 library can loop without end inside a damaged file (a zeroed object header in its global
 *        heap of strings, say), where neither a flag of this program nor a time limit of its own reaches.
 *
 * While a ReadGuard lives, a thread of its own looks every 50 ms at the clock and at the caller's interrupt
 * flag; when the read outlasts its limit it removes the files the caller names (a temporary output: nothing
 * half-written is left), writes the caller's one line and ends the process with exit status 2 (a damaged
 * file: bad input); when the flag is set (Ctrl-C, SIGTERM) it does the same with its interrupt line and status
 * 130 (docs/output.md, "Reading files back"). The limit (limit_seconds) is 60 s and 1 s more per 10 MB of the
 * file, or the environment's `GDSMC_READ_LIMIT` seconds, read that long by no intact file of this program's.
 * Destroying the guard (the read done) dismisses it. Checked by CliTable.ADamagedFileThatLoopsHdf5IsRefusedInTime
 * and CliDsmc.ADamagedCheckpointThatLoopsHdf5IsRefusedInTime.
 */
#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace gdsmc::io {

/// The watch over one read (header): ends the process with one line when the read outlasts its limit or an
/// interrupt comes during it.
class ReadGuard {
 public:
  /// What the guard says and removes when it ends the process.
  struct Exit {
    std::string timeout_line;    ///< written (a newline added) when the read outlasts the limit; exit status 2
    std::string interrupt_line;  ///< written when `interrupt` is set during the read; exit status 130
    std::vector<std::string> remove;  ///< files removed first (missing ones ignored)
  };
  /// Starts the watch: `seconds` from now, or at `*interrupt` (nullptr: never), the process ends as `exit` says.
  ReadGuard(double seconds, const std::atomic<bool>* interrupt, Exit exit);
  /// The read is done: the watch ends.
  ~ReadGuard();
  ReadGuard(const ReadGuard&) = delete;
  ReadGuard& operator=(const ReadGuard&) = delete;

  /// The limit for reading `file`: `GDSMC_READ_LIMIT` seconds when set to a positive number, else 60 s and
  /// 1 s more per 10 MB of the file (60 s when its size cannot be read).
  static double limit_seconds(const std::string& file);

 private:
  void watch(double seconds, const std::atomic<bool>* interrupt);
  Exit exit_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace gdsmc::io
