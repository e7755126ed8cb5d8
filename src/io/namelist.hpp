/**
 * \file namelist.hpp
 * \brief Syntax-level reader for Fortran namelist input files.
 *
 * Turns namelist text into groups of assignments with exact line numbers, so that the caller
 * (io::config) can check names, types and shapes against what the program knows and report
 * mistakes at the line the user wrote them. This module knows nothing about which groups or
 * variables exist.
 *
 * Fortran rules supported:
 * - A group starts with `&name` or `$name` and ends with `/`, `&end` or `$end`; group and
 *   variable names are case-insensitive and stored lower-cased. An empty group `&g /` is allowed.
 * - Text outside groups is ignored (a `&`/`$` there starts a group only at the start of a line or
 *   after a blank or a `/`, so prose such as "R&D" is harmless); `!` starts a comment to the end
 *   of the line except inside a quoted string.
 * - `name = values`, `name(i) = values`, `name(i,j,...) = values` with 1-based positive indices;
 *   blanks are allowed around `=` and inside the parentheses. Several values after an indexed name
 *   fill consecutive elements (column-major in Fortran): only the start index and the values are
 *   recorded, the caller resolves them.
 * - Values are separated by commas and/or blanks and may continue over several lines; the next
 *   `name =` or `name(...) =` starts a new assignment. A trailing comma before the next name or
 *   the end of the group is allowed.
 * - `r*value` repeats a value r times (r a positive integer, at most max_repeat).
 * - Integers (`12`, `-3`, `+4`), reals (`1.0`, `.5`, `3.`, `1e-3`, `1.5d-3`, `1.5D+3`),
 *   logicals (`.true.`, `.false.`, `.t.`, `.f.`, `t`, `f`, any case) and strings in single or
 *   double quotes, a doubled quote inside standing for one quote character.
 *
 * Deliberately not supported (reported as errors rather than silently guessed): Fortran null
 * values (`a = 1,,3`, `a =` with nothing, `3*` without a value), strings continued over a line
 * break, complex values, kind suffixes (`1_8`), array sections (`a(1:3)`), derived-type
 * components (`a%b`), and logical spellings such as `.TRUEabc` or `true`. Also errors, although
 * Fortran would accept them: the same group twice in one file, and the same variable assigned
 * twice as a whole in one group (both are almost always editing mistakes in an input file).
 *
 * Every error is a namelist::Error whose what() is one line `FILE:LINE: &group: variable: message`.
 * Checked by tests/namelist_test.cpp.
 */
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace gdsmc::io::namelist {

/// A syntax error; what() is `FILE:LINE: &group: variable: message`, the `&group: ` and
/// `variable: ` parts left out when empty and `:LINE` left out when line <= 0 (file-level errors).
struct Error : std::runtime_error {
  /// The error at `file`:`line` in `group`, `variable` (either may be empty).
  Error(std::string file, int line, std::string group, std::string variable, std::string message);
  std::string file;      ///< the namelist file
  int line;              ///< 1-based line; <= 0 for a file-level error
  std::string group;     ///< without the '&'
  std::string variable;  ///< lower-cased
  std::string message;   ///< what is wrong
};

/// One value of an assignment, after repeat expansion.
struct Value {
  /// The type of the token.
  enum class Kind {
    Integer,  ///< 12, -3
    Real,     ///< 1.5, 2e-3, 1.0d0
    Logical,  ///< .true., .false. (also .t., t, .f., f)
    String    ///< 'text'
  };
  Kind kind = Kind::Integer;  ///< the token's type
  std::string text;       ///< the token as written, without any `r*` prefix; for strings the string
  long long integer = 0;  ///< Kind::Integer
  double real = 0.0;      ///< Kind::Real, and also set for Integer (converted)
  bool logical = false;   ///< Kind::Logical
  std::string string;     ///< Kind::String (quotes removed, doubled quotes collapsed)
  int line = 0;           ///< line of this value
};

/// `name = values` or `name(i,...) = values`.
struct Assignment {
  std::string name;           ///< lower-cased
  std::vector<int> index;     ///< 1-based start index; empty for a whole-variable assignment
  std::vector<Value> values;  ///< repeats expanded; never empty
  int line = 0;               ///< line of the name
};

/// One `&name ... /` group.
struct Group {
  std::string name;                     ///< lower-cased, without '&'
  int line = 0;                         ///< line of '&name'
  std::vector<Assignment> assignments;  ///< in input order
  /// First whole or indexed assignment of `name` (any case), or nullptr.
  const Assignment* find(std::string_view name) const;
};

/// A parsed namelist file.
struct Document {
  std::string file;           ///< name used in messages
  std::string text;           ///< the original text, verbatim
  std::vector<Group> groups;  ///< in input order
  /// The group called `group` (any case, without '&'), or nullptr if absent.
  const Group* find(std::string_view group) const;
};

/// Largest accepted repeat count r in `r*value`; a typo such as `10000000000*1.0` must not
/// exhaust memory before the caller can compare the count with the array size.
inline constexpr long long max_repeat = 1'000'000;

/// Parses namelist text; `file_name` is used in messages ("<input>" if empty). Throws Error.
Document parse(std::string_view text, std::string file_name);

/// Reads and parses a file; `path` is used in messages. Throws Error (also "cannot open").
Document parse_file(const std::string& path);

/// The candidate closest to `name` by Damerau-Levenshtein (edit) distance, for "did you mean"
/// hints; empty if none is within max(2, name.size()/3) edits. Case-insensitive; the first of
/// equally close candidates wins.
std::string closest_name(std::string_view name, const std::vector<std::string>& candidates);

/// `word` as a shell reads it back, for the commands that messages suggest: itself when no character is
/// special to a shell, else in double quotes ($, `, \ and " escaped), or in single quotes (' written '\'')
/// when it holds a ! (which an interactive bash expands even in double quotes).
std::string shell_word(std::string_view word);

/// `text` for a one-line message: control characters (a newline, a NUL) written as escapes (`\n`,
/// `\x00`), cut after `limit` characters with "..." (an absurdly long name, value or argument).
std::string printable(std::string_view text, std::size_t limit = 200);

}  // namespace gdsmc::io::namelist
