// The lock that keeps two runs off one output (file_lock.hpp).
#include "io/file_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <string>

namespace gdsmc::io {

namespace {

/// The process id a holder wrote into the lock file, or "" when it cannot be read.
std::string holder_of(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : std::string();
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid;
}

/// Whether the content of a file at the lock's path is a lock file's: empty or a process id and a newline.
bool looks_like_a_lock(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text, 0);
  if (n < 0 || n >= static_cast<ssize_t>(sizeof text)) return false;
  for (ssize_t i = 0; i < n; ++i)
    if (!((text[i] >= '0' && text[i] <= '9') || (text[i] == '\n' && i == n - 1))) return false;
  return true;
}

}  // namespace

FileLock::FileLock(std::string path) : path_(std::move(path)) {
  const std::string not_ours = "'" + path_ + "' exists and is not a lock file of granular-dsmc";
  for (int attempt = 0; attempt < 16; ++attempt) {
    struct stat named {};
    const bool exists = ::lstat(path_.c_str(), &named) == 0;
    // A link, a FIFO, a device or a directory at the path is someone else's: never opened, truncated or removed.
    if (exists && !S_ISREG(named.st_mode))
      throw LockRefused(not_ours + " (not a regular file): remove it, or choose another output file");
    const int fd = ::open(path_.c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC | (exists ? 0 : O_CREAT | O_EXCL), 0644);
    if (fd < 0) {
      if (errno == EEXIST || errno == ENOENT) continue;  // created or removed meanwhile: look again
      return;  // a read-only folder: the run fails where its output is created, with that message
    }
    if (exists && !looks_like_a_lock(fd)) {  // a user's file that happens to have the name: kept as it is
      ::close(fd);
      throw LockRefused(not_ours + ": remove or rename it, or choose another output file");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const bool busy = errno == EWOULDBLOCK;
      const std::string pid = busy ? holder_of(fd) : std::string();
      ::close(fd);
      if (!busy) return;
      throw LockRefused("another run" + (pid.empty() ? std::string() : " (process " + pid + ")") +
                        " is writing it (lock file '" + path_ + "')");
    }
    // The file locked must still be the one at the path: its last holder removes it as it ends.
    struct stat locked {}, now {};
    if (::fstat(fd, &locked) != 0 || ::lstat(path_.c_str(), &now) != 0 || locked.st_ino != now.st_ino ||
        locked.st_dev != now.st_dev) {
      ::close(fd);
      continue;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
      // The lock is held all the same; the refusal of a second run will not name this process.
    }
    fd_ = fd;
    return;
  }
}

FileLock::~FileLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // before the lock is released, so that no one locks a file about to vanish
  ::close(fd_);
}

}  // namespace gdsmc::io
