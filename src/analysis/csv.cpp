#include "analysis/csv.hpp"

#include <cmath>
#include <cstdio>

namespace gdsmc::analysis::csv {

std::string field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[40];
  std::snprintf(text, sizeof text, "%.12g", value);
  return text;
}

std::string write(const std::vector<Column>& columns, std::size_t rows) {
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c) out += ',';
    out += field(columns[c].name);
  }
  out += '\n';
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c) out += ',';
      const Column& column = columns[c];
      if (r < column.texts.size() && !column.texts[r].empty()) out += field(column.texts[r]);
      else out += number(r < column.values.size() ? column.values[r] : std::nan(""));
    }
    out += '\n';
  }
  return out;
}

}  // namespace gdsmc::analysis::csv
