// A valid binary-mixture namelist shared by the input tests; their expected messages quote its
// line numbers. Line 16 is the &output line, which each test file chooses.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace gdsmc::test {

inline std::vector<std::string> base_namelist_lines(const std::string& output_line) {
  return {
      "&system",                        // 1
      "  n_species = 2",                // 2
      "  mass = 1.0, 10.0",             // 3
      "  diameter = 1.0, 1.0",          // 4
      "  number_density = 0.02, 0.01",  // 5
      "  restitution = 0.5",            // 6
      "/",                              // 7
      "&initial",                       // 8
      "  temperature = 1.0",            // 9
      "/",                              // 10
      "&dsmc",                          // 11
      "  n_particles = 200",            // 12
      "  t_end = 10.0",                 // 13
      "/",                              // 14
      "&output",                        // 15
      output_line,                      // 16
      "/",                              // 17
  };
}

inline std::string join_lines(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

/// The lines with line `line` (1-based) replaced by `text` ("" blanks it, keeping the numbering).
inline std::string with_line(std::vector<std::string> lines, int line, const std::string& text) {
  lines.at(static_cast<std::size_t>(line - 1)) = text;
  return join_lines(lines);
}

}  // namespace gdsmc::test
