#include "io/file_guard.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace gdsmc::io {

FileGuard::FileGuard(double seconds, const std::atomic<bool>* interrupt, Exit exit)
    : exit_(std::move(exit)), thread_([this, seconds, interrupt] { watch(seconds, interrupt); }) {}

FileGuard::~FileGuard() {
  {
    std::lock_guard<std::mutex> hold(mutex_);
    done_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void FileGuard::watch(double seconds, const std::atomic<bool>* interrupt) {
  using Clock = std::chrono::steady_clock;
  const auto after = [](double s) { return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s)); };
  const auto deadline = seconds < 1e9 ? Clock::now() + after(seconds) : Clock::time_point::max();
  auto interrupt_deadline = Clock::time_point::max();  // set when the flag is first seen
  std::unique_lock<std::mutex> hold(mutex_);
  for (;;) {
    if (wake_.wait_for(hold, std::chrono::milliseconds(50), [this] { return done_; })) return;
    const auto now = Clock::now();
    if (interrupt && interrupt->load() && interrupt_deadline == Clock::time_point::max())
      interrupt_deadline = now + after(exit_.interrupt_grace_seconds);
    const bool interrupted = now >= interrupt_deadline;
    if (!interrupted && now < deadline) continue;
    // The reading thread is inside the library and cannot be stopped: the process ends from here, without
    // running destructors (they would wait for that thread), after removing what it must not leave behind.
    for (const auto& path : exit_.remove) {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
    std::fprintf(stderr, "%s\n", interrupted ? exit_.interrupt_line.c_str() : exit_.timeout_line.c_str());
    std::fflush(stderr);
    std::_Exit(interrupted ? 130 : 2);
  }
}

double FileGuard::limit_seconds(const std::string& file) {
  if (const char* set = std::getenv("GDSMC_READ_LIMIT")) {
    char* end = nullptr;
    const double seconds = std::strtod(set, &end);
    if (end != set && *end == '\0' && seconds > 0.0 && seconds < 1e9) return seconds;
  }
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(file, ec);
  return ec ? 60.0 : 60.0 + static_cast<double>(bytes) / 1e7;
}

}  // namespace gdsmc::io
