/**
 * \file file_guard.hpp
 * \brief A watch over a read or a write of an HDF5 file, inside which neither a flag of this program nor a
 *        time limit of its own reaches: the library can loop without end in a damaged file the user names
 *        (a zeroed object header in its global heap of strings, say), and one call can write a gigabyte.
 *
 * While a FileGuard lives, a thread of its own looks every 50 ms at the clock and at the caller's interrupt
 * flag; when the work outlasts its limit it removes the files the caller names (a temporary output: nothing
 * half-written is left), writes the caller's one line and ends the process with exit status 2 (a damaged
 * file: bad input); when the flag has been set (Ctrl-C, SIGTERM) for the caller's grace it does the same with
 * its interrupt line and status 130. Reads (docs/output.md, "Reading files back") have no grace and the limit
 * of limit_seconds: 60 s and 1 s more per 10 MB of the file, or the environment's `GDSMC_READ_LIMIT` seconds,
 * read that long by no intact file of this program's. The writing of a run's output on one rank
 * (run/simulation.cpp) has no limit and a quarter of a second's grace, in which its own look at the flag
 * between points ends it with the usual line. Destroying the guard (the work done) dismisses it. Checked by
 * CliTable.ADamagedFileThatLoopsHdf5IsRefusedInTime, CliDsmc.ADamagedCheckpointThatLoopsHdf5IsRefusedInTime and
 * tests/scale_out/interrupt.sh (writing-a-sweep).
 */
#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace gdsmc::io {

/// The watch over one read or write (header): ends the process with one line when the work outlasts its
/// limit or an interrupt comes during it and is not seen by the work within the grace.
class FileGuard {
 public:
  /// What the guard says and removes when it ends the process.
  struct Exit {
    std::string timeout_line;    ///< written (a newline added) when the read outlasts the limit; exit status 2
    std::string interrupt_line;  ///< written when `interrupt` is set during the read; exit status 130
    std::vector<std::string> remove;  ///< files removed first (missing ones ignored)
    double interrupt_grace_seconds = 0.0;  ///< how long an interrupt is left to the work itself
  };
  /// Starts the watch: `seconds` from now (infinity: never), or `exit.interrupt_grace_seconds` after `*interrupt`
  /// is set (nullptr: never), the process ends as `exit` says.
  FileGuard(double seconds, const std::atomic<bool>* interrupt, Exit exit);
  /// The work is done: the watch ends.
  ~FileGuard();
  FileGuard(const FileGuard&) = delete;
  FileGuard& operator=(const FileGuard&) = delete;

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
