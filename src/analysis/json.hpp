/**
 * \file json.hpp
 * \brief The JSON scalars granular-theory and `--compare=FILE.json` write: numbers that any JSON reader
 *        takes, strings escaped as RFC 8259 requires.
 *
 * - number: `%.17g` (round-trips a double); NaN and infinities, which JSON has no word for, are `null`.
 * - quote: the text in double quotes, `"` and `\` escaped, control characters (a TAB in a sweep value, a
 *   line break) as `\n`, `\t`, `\r` or `\u00XX`; other bytes (UTF-8) as they are.
 * Checked by tests/run_table_test.cpp (Json.*).
 */
#pragma once

#include <string>
#include <vector>

namespace gdsmc::analysis::json {

/// A double as JSON: `%.17g`, `null` when not finite.
std::string number(double x);
/// `[x, ...]` of number().
std::string array(const std::vector<double>& values);
/// A JSON string literal of `text`.
std::string quote(const std::string& text);

}  // namespace gdsmc::analysis::json
