#pragma once
/// \file
/// A folder of the test process's own under the system's temporary folder, removed with everything in
/// it when the object is destroyed (for a function-local static: when the process ends), so that the
/// tests leave nothing behind in /tmp however often they run.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace gdsmc::test {

class ScratchDir {
 public:
  /// `prefix` followed by the process id: tests running side by side (ctest -j) never share one.
  explicit ScratchDir(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  /// The path of `name` inside the folder.
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace gdsmc::test
