// Fortran namelist reader: a hand-written scanner over the whole text, because what a word means
// (variable name or logical value `t`/`f`) depends on what follows it, and every error must carry
// the exact line. See namelist.hpp for the rules.
#include "io/namelist.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <system_error>
#include <utility>

namespace gdsmc::io::namelist {

std::string shell_word(std::string_view word) {
  if (!word.empty() && word.find_first_of("'\" $`\\\t;&|<>()*?[]#~!{}") == std::string_view::npos) return std::string(word);
  std::string quoted;
  if (word.find('!') != std::string_view::npos) {
    quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
  }
  quoted = "\"";
  for (char c : word) quoted += (c == '"' || c == '$' || c == '`' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return quoted + "\"";
}

std::string printable(std::string_view text, std::size_t limit) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (out.size() >= limit) {
      out.append("...");
      break;
    }
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      out.append("\\n");
    } else if (c < 0x20 || c == 0x7f) {
      static const char hex[] = "0123456789abcdef";
      out.append("\\x").push_back(hex[c >> 4]);
      out.push_back(hex[c & 15]);
    } else {
      out.push_back(static_cast<char>(c));
    }
  }
  return out;
}

namespace {

std::string format_error(const std::string& file, int line, const std::string& group,
                         const std::string& variable, const std::string& message) {
  // Appended piece by piece: GCC 12 warns spuriously (-Wrestrict) on `"&" + group + ": "`.
  // Names are cut at 64 characters and the message at 1000: one readable line whatever the input.
  std::string s = printable(file, 4096);
  if (line > 0) s.append(":").append(std::to_string(line));
  s.append(": ");
  if (!group.empty()) s.append("&").append(printable(group, 64)).append(": ");
  if (!variable.empty()) s.append(printable(variable, 64)).append(": ");
  s.append(printable(message, 1000));
  return s;
}

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

std::string lowered(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), lower);
  return out;
}

bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_char(char c) { return is_letter(c) || is_digit(c) || c == '_'; }
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
bool is_quote(char c) { return c == '\'' || c == '"'; }
bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), is_digit);
}

// Characters that end an unquoted value. '*' is not among them: it is split off afterwards so that
// the whole `r*value` can be quoted in messages.
bool ends_value(char c) { return is_blank(c) || c == ',' || c == '/' || c == '!' || is_quote(c); }

// Positive integer written with digits only (an optional '+' for indices); 0 if not one or too big.
long long positive_integer(std::string_view s, bool allow_plus) {
  if (allow_plus && !s.empty() && s.front() == '+') s.remove_prefix(1);
  if (!all_digits(s)) return 0;
  long long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return 0;
  return v;
}

// Fortran real-literal grammar: [sign] (digits [. [digits]] | . digits) [(e|d) [sign] digits].
// Checked by hand because from_chars also accepts "inf", "nan" and hex forms Fortran does not.
bool is_real_literal(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  std::size_t mantissa_digits = 0;
  while (i < s.size() && is_digit(s[i])) ++i, ++mantissa_digits;
  bool point = false;
  if (i < s.size() && s[i] == '.') {
    point = true;
    ++i;
    while (i < s.size() && is_digit(s[i])) ++i, ++mantissa_digits;
  }
  if (mantissa_digits == 0) return false;
  bool exponent = false;
  if (i < s.size() && (lower(s[i]) == 'e' || lower(s[i]) == 'd')) {
    exponent = true;
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (i == s.size() || !is_digit(s[i])) return false;
    while (i < s.size() && is_digit(s[i])) ++i;
  }
  return i == s.size() && (point || exponent);
}

bool is_integer_literal(std::string_view s) {
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) s.remove_prefix(1);
  return all_digits(s);
}

class Parser {
 public:
  Parser(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

  std::vector<Group> run() {
    std::vector<Group> groups;
    while (find_group_start(groups.empty() ? nullptr : &groups.back())) {
      const int line = line_;
      advance();  // '&' or '$'
      std::string name = lowered(read_name());
      if (name == "end")
        fail(line, "", "", "'&end' outside a group (did a '/' end the previous group early?)");
      for (const Group& g : groups)
        if (g.name == name)
          fail(line, name, "", "group name repeated (first at line " + std::to_string(g.line) + ")");
      groups.push_back(parse_group(std::move(name), line));
    }
    return groups;
  }

 private:
  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  int line_ = 1;
  std::size_t line_begin_ = 0;  ///< where line_ begins in text_

  [[noreturn]] void fail(int line, const std::string& group, const std::string& variable,
                         const std::string& message) const {
    throw Error(file_, line, group, variable, message);
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek(std::size_t ahead = 0) const {
    return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
  }
  void advance() {
    if (text_[pos_] == '\n') ++line_, line_begin_ = pos_ + 1;
    ++pos_;
  }
  void skip_comment() {
    while (!at_end() && peek() != '\n') advance();
  }
  // Blanks, line ends and comments separate everything inside a group.
  void skip_blanks() {
    while (!at_end()) {
      if (is_blank(peek())) advance();
      else if (peek() == '!') skip_comment();
      else break;
    }
  }
  std::string_view read_name() {
    const std::size_t start = pos_;
    while (!at_end() && is_name_char(peek())) advance();
    return text_.substr(start, pos_ - start);
  }

  // Whether the text at pos_ is `name =` or `name(...) =`: an assignment.
  bool assignment_at() const {
    std::size_t p = pos_;
    while (p < text_.size() && is_name_char(text_[p])) ++p;
    while (p < text_.size() && is_blank(text_[p]) && text_[p] != '\n') ++p;
    if (p < text_.size() && text_[p] == '(') {
      while (p < text_.size() && text_[p] != ')' && text_[p] != '\n') ++p;
      if (p < text_.size() && text_[p] == ')') ++p;
      while (p < text_.size() && is_blank(text_[p]) && text_[p] != '\n') ++p;
    }
    return p < text_.size() && text_[p] == '=' && (p + 1 >= text_.size() || text_[p + 1] != '=');
  }

  // Skips free text up to the next `&name`/`$name`; false at the end of the text. Free text is a comment
  // (Fortran's rule), but a line that starts with an assignment is a variable the groups would not read (a
  // '/' that ended the group above early): refused, where Fortran would skip it silently. `previous`: the
  // group before the text (nullptr: none).
  bool find_group_start(const Group* previous) {
    bool line_start = pos_ == 0 || text_[pos_ - 1] == '\n';  // only blanks since the line began
    while (!at_end()) {
      const char c = peek();
      if (c == '!') {
        skip_comment();
        continue;
      }
      if (line_start && is_letter(c) && assignment_at()) {
        const int line = line_;
        const std::string name(read_name());
        fail(line, "", name,
             "an assignment outside any group is not read" +
                 (previous ? " (&" + previous->name + " of line " + std::to_string(previous->line) +
                                 " ended before it: a '/' too early?)"
                           : std::string(" (no group has begun: &name first)")));
      }
      if (c == '\n') line_start = true;
      else if (!is_blank(c)) line_start = false;
      if ((c == '&' || c == '$') && is_letter(peek(1))) {
        const char before = pos_ == 0 ? '\n' : text_[pos_ - 1];
        if (is_blank(before) || before == '/') return true;
      }
      advance();
    }
    return false;
  }

  // True if the word at pos_ is a variable name, i.e. followed by '=' or '('; decides between a
  // name and the logicals `t`/`f`, which Fortran distinguishes the same way.
  bool word_is_name() const {
    std::size_t p = pos_;
    while (p < text_.size() && is_name_char(text_[p])) ++p;
    while (p < text_.size()) {
      if (is_blank(text_[p])) ++p;
      else if (text_[p] == '!')
        while (p < text_.size() && text_[p] != '\n') ++p;
      else break;
    }
    return p < text_.size() && (text_[p] == '=' || text_[p] == '(');
  }

  // The word at pos_ when it is a variable name but for a character outside ASCII (a name typed
  // with an accent, restitución = 0.9): else empty. Such a word would otherwise read as a bad value of
  // the variable before it.
  std::string foreign_name() const {
    std::size_t p = pos_;
    bool foreign = false;
    while (p < text_.size() && (is_name_char(text_[p]) || static_cast<unsigned char>(text_[p]) >= 0x80)) {
      foreign = foreign || static_cast<unsigned char>(text_[p]) >= 0x80;
      ++p;
    }
    const std::size_t end = p;
    while (p < text_.size() && is_blank(text_[p])) ++p;
    if (!foreign || p >= text_.size() || (text_[p] != '=' && text_[p] != '(')) return "";
    return std::string(text_.substr(pos_, end - pos_));
  }

  Group parse_group(std::string name, int group_line) {
    Group g;
    g.name = std::move(name);
    g.line = group_line;
    Assignment* current = nullptr;
    bool need_value = false;  // after '=' and before its first value
    bool after_comma = false;  // a comma after the last value, so another comma is a null value

    // Fortran would leave the variable unchanged; in an input file that is almost always a typo.
    auto check_has_value = [&](int line) {
      if (need_value)
        fail(line, g.name, current->name,
             "no value after '=' (Fortran null values are not supported)");
    };

    while (true) {
      skip_blanks();
      if (at_end())
        fail(group_line, g.name, "",
             "unterminated group: end of file reached without '/' or '&end' (group started at "
             "line " + std::to_string(group_line) + ")");
      const int line = line_;
      const char c = peek();
      if (c == '/') {
        check_has_value(line);
        advance();
        return g;
      }
      if (c == '&' || c == '$') {
        advance();
        const std::string other = lowered(read_name());
        if (other.empty())
          fail(line, g.name, current ? current->name : "", std::string("stray '") + c + "'");
        if (other == "end") {
          check_has_value(line);
          return g;
        }
        fail(line, g.name, "",
             "group &" + other + " starts inside group &" + g.name + " (started at line " +
                 std::to_string(group_line) + "); is its '/' missing?");
      }
      if (c == ',') {
        if (current == nullptr || need_value || after_comma)
          fail(line, g.name, current ? current->name : "",
               "empty value between separators (Fortran null values are not supported)");
        after_comma = true;
        advance();
        continue;
      }
      if (c == '=')
        fail(line, g.name, current ? current->name : "",
             "value without a variable name ('=' not preceded by a name)");
      if (const std::string word = foreign_name(); !word.empty())
        fail(line, g.name, word,
             "the name '" + word + "' has a character outside A-Z, 0-9 and _ (variable names are ASCII)");
      if (is_letter(c) && word_is_name()) {
        check_has_value(line);
        g.assignments.push_back(parse_assignment_head(g));
        current = &g.assignments.back();
        need_value = true;
        after_comma = false;
        continue;
      }
      if (current == nullptr) {
        const std::size_t start = pos_;
        while (!at_end() && !ends_value(peek())) advance();
        const std::string token(text_.substr(start, std::max<std::size_t>(pos_ - start, 1)));
        fail(line, g.name, "",
             "value without a variable name: expected 'name = value', found '" + token + "'");
      }
      parse_values(g, *current, after_comma);
      need_value = false;
      after_comma = false;
    }
  }

  // `name [(i, ...)] =`; leaves pos_ after the '='.
  Assignment parse_assignment_head(const Group& g) {
    Assignment a;
    a.line = line_;
    a.name = lowered(read_name());
    skip_blanks();
    if (peek() == '(') {
      advance();
      while (true) {
        skip_blanks();
        const int line = line_;
        const std::size_t start = pos_;
        while (!at_end() && !is_blank(peek()) && peek() != ',' && peek() != ')' && peek() != '=' &&
               peek() != '/' && peek() != '!')
          advance();
        const std::string_view token = text_.substr(start, pos_ - start);
        const long long i = positive_integer(token, true);
        if (i <= 0 || i > std::numeric_limits<int>::max()) {
          std::string why = "bad index '" + std::string(token) + "' (indices are integers from 1)";
          if (token.find(':') != std::string_view::npos)
            why = "bad index '" + std::string(token) + "' (array sections are not supported)";
          else if (token.empty())
            why = "missing index in '" + a.name + "(...)'";
          fail(line, g.name, a.name, why);
        }
        a.index.push_back(static_cast<int>(i));
        skip_blanks();
        if (peek() == ',') {
          advance();
          continue;
        }
        if (peek() == ')') {
          advance();
          break;
        }
        fail(line_, g.name, a.name, "expected ',' or ')' in the index");
      }
      skip_blanks();
    }
    if (peek() != '=')
      fail(line_, g.name, a.name, "expected '=' after '" + a.name + (a.index.empty() ? "" : "(...)") + "'");
    advance();
    if (a.index.empty())
      for (const Assignment& earlier : g.assignments)
        if (earlier.name == a.name && earlier.index.empty())
          fail(a.line, g.name, a.name,
               "assigned twice in one group (first at line " + std::to_string(earlier.line) + ")");
    return a;
  }

  // One value item at pos_ (a constant or `r*constant`), appended `r` times to `a`; `after_comma`: a comma
  // came after a's last value.
  void parse_values(const Group& g, Assignment& a, bool after_comma) {
    const int line = line_;
    const std::size_t start = pos_;
    // The first item of a later line, after a value of `a` with no comma behind it: where a name whose '='
    // was forgotten lands (convert names it, when it is a plain word).
    // (only the line's leading blanks are read: a long list on one line stays linear)
    const bool starts_line = line != a.line && text_.find_first_not_of(" \t\r", line_begin_) == start;
    const bool name_position = starts_line && !a.values.empty() && !after_comma;
    while (!at_end() && !ends_value(peek())) advance();
    const std::string_view raw = text_.substr(start, pos_ - start);

    long long repeat = 1;
    std::string_view constant = raw;
    if (const std::size_t star = raw.find('*'); star != std::string_view::npos) {
      const std::string_view count = raw.substr(0, star);
      repeat = positive_integer(count, false);
      if (repeat <= 0)
        fail(line, g.name, a.name,
             "repeat count must be a positive integer, found '" + std::string(count) + "' in '" +
                 std::string(raw) + "'");
      if (repeat > max_repeat)
        fail(line, g.name, a.name,
             "repeat count " + std::string(count) + " is larger than " +
                 std::to_string(max_repeat));
      constant = raw.substr(star + 1);
    }

    Value v;
    v.line = line;
    if (constant.empty() && is_quote(peek())) {
      v.kind = Value::Kind::String;
      v.string = read_string(g, a);
      v.text = v.string;
    } else if (constant.empty()) {
      fail(line, g.name, a.name,
           "'" + std::string(raw) + "' without a value (Fortran null values are not supported)");
    } else {
      if (is_quote(peek()))
        fail(line, g.name, a.name,
             "bad value '" + std::string(raw) + peek() + "...' (a quote inside a value)");
      v = convert(constant, g, a, line, name_position && constant == raw);
    }
    if (!at_end() && !ends_value(peek()))
      fail(line_, g.name, a.name, "missing separator after the value '" + v.text + "'");
    if (!at_end() && is_quote(peek()))
      fail(line_, g.name, a.name, "missing separator before the quote after '" + v.text + "'");
    a.values.insert(a.values.end(), static_cast<std::size_t>(repeat), v);
  }

  // Quoted string at pos_; a doubled quote stands for one. Must close on its own line, so that a
  // missing quote is reported where it is missing rather than at the end of the file.
  std::string read_string(const Group& g, const Assignment& a) {
    const int line = line_;
    const char quote = peek();
    advance();
    std::string s;
    while (true) {
      if (at_end() || peek() == '\n')
        fail(line, g.name, a.name,
             std::string("unterminated string (missing closing ") + quote + " on this line)");
      const char c = peek();
      advance();
      if (c != quote) {
        s += c;
      } else if (peek() == quote) {
        s += quote;
        advance();
      } else {
        return s;
      }
    }
  }

  Value convert(std::string_view token, const Group& g, const Assignment& a, int line, bool name_position) const {
    Value v;
    v.text = std::string(token);
    v.line = line;
    const std::string low = lowered(token);
    if (low == ".true." || low == ".t." || low == "t" || low == ".false." || low == ".f." ||
        low == "f") {
      v.kind = Value::Kind::Logical;
      v.logical = low == ".true." || low == ".t." || low == "t";
      return v;
    }
    // from_chars takes no leading '+'.
    std::string_view digits = token;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    if (is_integer_literal(token)) {
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v.integer);
      if (ec != std::errc() || end != digits.data() + digits.size())
        fail(line, g.name, a.name, "integer '" + v.text + "' out of range");
      v.kind = Value::Kind::Integer;
      v.real = static_cast<double>(v.integer);
      return v;
    }
    if (is_real_literal(token)) {
      std::string c(digits);
      std::replace_if(c.begin(), c.end(), [](char ch) { return ch == 'd' || ch == 'D'; }, 'e');
      const auto [end, ec] = std::from_chars(c.data(), c.data() + c.size(), v.real);
      if (ec != std::errc() || end != c.data() + c.size())
        fail(line, g.name, a.name, "real '" + v.text + "' out of range");
      v.kind = Value::Kind::Real;
      return v;
    }
    // A plain word where a name whose '=' was forgotten lands (parse_values; not in a --set, which has no lines).
    const bool plain_word = is_letter(token.front()) && std::all_of(token.begin(), token.end(), is_name_char);
    if (name_position && plain_word && file_.rfind("--set ", 0) != 0)
      fail(line, g.name, lowered(v.text),
           "'" + v.text + "' without '=': expected '" + v.text + " = value' (read as a value of " + a.name +
               " from line " + std::to_string(a.line) + ", it would be an unquoted word, which is not a value)");
    if (is_letter(token.front())) {
      // (on a shell's command line the quotes of --set need quotes of their own: the form to type)
      const std::string quoted = "'" + v.text + "'";
      std::string index;
      for (std::size_t i = 0; i < a.index.size(); ++i) index += (i ? "," : "(") + std::to_string(a.index[i]);
      if (!index.empty()) index += ")";
      const std::string typed =
          file_.rfind("--set ", 0) == 0
              ? ", on a command line --set " + shell_word(g.name + ":" + a.name + index + "=" + quoted)
              : "";
      fail(line, g.name, a.name,
           "bad value '" + v.text + "': an unquoted word is not a value (a string needs quotes: " + quoted + typed +
               "; logicals are .true. or .false.)");
    }
    fail(line, g.name, a.name, "bad value '" + v.text + "'");
  }
};

}  // namespace

Error::Error(std::string file_, int line_, std::string group_, std::string variable_,
             std::string message_)
    : std::runtime_error(format_error(file_, line_, group_, variable_, message_)),
      file(std::move(file_)),
      line(line_),
      group(std::move(group_)),
      variable(std::move(variable_)),
      message(std::move(message_)) {}

const Assignment* Group::find(std::string_view wanted) const {
  const std::string key = lowered(wanted);
  for (const Assignment& a : assignments)
    if (a.name == key) return &a;
  return nullptr;
}

const Group* Document::find(std::string_view wanted) const {
  const std::string key = lowered(wanted);
  for (const Group& g : groups)
    if (g.name == key) return &g;
  return nullptr;
}

Document parse(std::string_view text, std::string file_name) {
  Document doc;
  doc.file = file_name.empty() ? "<input>" : std::move(file_name);
  doc.text = std::string(text);
  // A NUL byte is no part of a text file (a binary file given by mistake, or a damaged one).
  if (const auto nul = doc.text.find('\0'); nul != std::string::npos)
    throw Error(doc.file, 1 + static_cast<int>(std::count(doc.text.begin(), doc.text.begin() + static_cast<std::ptrdiff_t>(nul), '\n')),
                "", "", "contains a NUL byte: not a text namelist");
  // A UTF-8 byte-order mark (some editors write one) is not text: skipped, the lines unchanged.
  std::string_view body = doc.text;
  if (body.substr(0, 3) == "\xEF\xBB\xBF") body.remove_prefix(3);
  doc.groups = Parser(body, doc.file).run();
  return doc;
}

Document parse_file(const std::string& path) {
  if (std::error_code ec; std::filesystem::is_directory(path, ec))  // opens, and reads as nothing
    throw Error(path, 0, "", "", "is a directory, not a namelist file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, 0, "", "", std::string("cannot open: ") + std::strerror(errno));
  if (in.peek() == std::ifstream::traits_type::eof() && !in.bad())
    throw Error(path, 0, "", "", "is empty: a namelist needs at least the groups &system and &dsmc");
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad() || contents.fail()) throw Error(path, 0, "", "", "cannot read the file");
  return parse(contents.str(), path);
}

std::string closest_name(std::string_view name, const std::vector<std::string>& candidates) {
  // Unrestricted Damerau-Levenshtein (Lowrance-Wagner), so "tmeperature" is one edit away from
  // "temperature" even when other edits are also needed.
  auto distance = [](const std::string& a, const std::string& b) {
    const std::size_t n = a.size(), m = b.size();
    const std::size_t inf = n + m;
    std::vector<std::vector<std::size_t>> d(n + 2, std::vector<std::size_t>(m + 2, 0));
    d[0][0] = inf;
    for (std::size_t i = 0; i <= n; ++i) d[i + 1][0] = inf, d[i + 1][1] = i;
    for (std::size_t j = 0; j <= m; ++j) d[0][j + 1] = inf, d[1][j + 1] = j;
    std::map<char, std::size_t> last_row;  // last row in which each character of `a` occurred
    for (std::size_t i = 1; i <= n; ++i) {
      std::size_t last_col = 0;  // last column in this row where a[i-1] matched
      for (std::size_t j = 1; j <= m; ++j) {
        const std::size_t i1 = last_row.count(b[j - 1]) ? last_row[b[j - 1]] : 0;
        const std::size_t j1 = last_col;
        const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
        if (cost == 0) last_col = j;
        d[i + 1][j + 1] = std::min({d[i][j] + cost, d[i + 1][j] + 1, d[i][j + 1] + 1,
                                    d[i1][j1] + (i - i1 - 1) + 1 + (j - j1 - 1)});
      }
      last_row[a[i - 1]] = i;
    }
    return d[n + 1][m + 1];
  };
  const std::string key = lowered(name);
  const std::size_t limit = std::max<std::size_t>(2, key.size() / 3);
  std::string best;
  std::size_t best_distance = limit + 1;
  for (const std::string& c : candidates) {
    const std::size_t dist = distance(key, lowered(c));
    if (dist < best_distance) best = c, best_distance = dist;
  }
  return best;
}

}  // namespace gdsmc::io::namelist
