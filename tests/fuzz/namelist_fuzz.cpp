// libFuzzer harness for the namelist path (issue 12): arbitrary bytes through the namelist reader, the
// config checks (with a --set when the input starts with one), the sweep expansion and the sample
// points. The reader's own error (io::namelist::Error) is the expected outcome of bad input and must
// be one line; any other exception, a crash, a sanitizer report or a time-out is a finding.
// Build and run: tests/fuzz/README.md.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/run_checks.hpp"
#include "io/config.hpp"
#include "io/namelist.hpp"

namespace {

namespace config = gdsmc::io::config;
namespace namelist = gdsmc::io::namelist;

void exercise(const std::string& text, const std::vector<std::string>& overrides) {
  const config::Config c = config::read(namelist::parse(text, "fuzz.nml"), overrides, gdsmc::analysis::check_run_cost);
  (void)c.sample_times();
  (void)c.sample_collisions();
  (void)c.resolved();
  // Expand at most 64 points: the values given point by point, or the product of the lists' lengths
  // (a grid), saturated.
  std::size_t points = c.sweep.values.points.size(), grid = 1;
  for (const auto& list : c.sweep.values.lists) grid = std::min<std::size_t>(grid * std::max<std::size_t>(list.size(), 1), 1u << 20);
  if (points <= 64 && grid <= 64)
    for (const auto& point : c.sweep_points()) {
      (void)point.sample_times();
      (void)point.sample_collisions();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (std::size_t{1} << 16)) return 0;  // namelists are small; keeps every run fast
  std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> overrides;
  // "--set group:variable=value" on the first line: an override, the rest the namelist.
  if (text.rfind("--set ", 0) == 0) {
    const std::size_t end = text.find('\n');
    overrides.push_back(text.substr(6, end == std::string::npos ? std::string::npos : end - 6));
    text = end == std::string::npos ? std::string() : text.substr(end + 1);
  }
  try {
    exercise(text, overrides);
  } catch (const namelist::Error& e) {
    const std::string message = e.what();
    if (message.find('\n') != std::string::npos || message.find('\r') != std::string::npos)
      __builtin_trap();  // a message of more than one line
  }
  // Any other exception leaves this function: libFuzzer reports it as a crash.
  return 0;
}
