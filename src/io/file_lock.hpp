/**
 * \file file_lock.hpp
 * \brief The lock that keeps two runs off one output (\ref output_checkpoint "docs/output.md"): an
 *        advisory `flock` on `<output stem>.lock`, beside the output and its checkpoint.
 *
 * The kernel releases the lock when its holder ends, also by SIGKILL, so a lock file left by a
 * killed run is taken again at once; a run that ends removes its lock file. The file holds the
 * holder's process id, which the refusal of a second run names. A file that the last holder
 * removed between another run's open() and flock() is noticed (its inode is no longer the path's)
 * and the lock is taken again on the new file. Only a lock held by a live process refuses a run: a
 * lock file that cannot be created (a read-only folder) leaves the run to fail where the output is
 * created, with that message. Anything at the path that is not a lock file (a link, a FIFO, a user's
 * file: content other than a process id) refuses the run and is left untouched.
 */
#pragma once

#include <stdexcept>
#include <string>

namespace gdsmc::io {

/// Another process holds the lock, or the path holds something that is not a lock file.
struct LockRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// An exclusive advisory lock on `path` (header), held from construction to destruction.
class FileLock {
 public:
  /// Takes the lock on `path` (created when absent). Throws LockRefused "another run (process P) is
  /// writing it" when a live process holds it, and when the path holds anything but a lock file (a
  /// link, a FIFO, a file whose content is not a process id: never truncated, never removed); does
  /// nothing (holds no lock) when the file cannot be created for another reason (a read-only folder).
  explicit FileLock(std::string path);
  /// Removes the lock file and releases the lock.
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  /// Whether the lock is held (false when the file could not be created).
  bool held() const { return fd_ >= 0; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace gdsmc::io
