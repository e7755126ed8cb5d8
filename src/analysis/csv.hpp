/**
 * \file csv.hpp
 * \brief The CSV every table of `granular-dsmc --table` is printed in (\ref output_table "docs/output.md").
 *
 * One header line, then one line per row; fields separated by commas, a field that holds a comma, a
 * double quote or a line break double-quoted with its quotes doubled (RFC 4180); numbers with 12
 * significant digits (`%.12g`), NaN as `nan`, infinities as `inf` and `-inf`. A column holds numbers
 * or, where `texts` is set, the text of that row (a sweep value that is not one number).
 * Used by analysis/sweep_table.hpp and analysis/run_table.hpp; checked by tests/run_table_test.cpp.
 */
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace gdsmc::analysis::csv {

/// One column: its header and a value per row (a text per row instead where `texts[row]` is not empty).
struct Column {
  std::string name;                ///< the header
  std::vector<double> values;      ///< one per row
  std::vector<std::string> texts;  ///< empty, or one per row: a non-empty text replaces the number
};

/// A field as CSV writes it: quoted when it holds a comma, a quote or a line break.
std::string field(const std::string& text);
/// A number as CSV writes it: `%.12g`, `nan`, `inf`, `-inf`.
std::string number(double value);
/// The table: the header line, then `rows` lines (every column has `rows` values).
std::string write(const std::vector<Column>& columns, std::size_t rows);

}  // namespace gdsmc::analysis::csv
