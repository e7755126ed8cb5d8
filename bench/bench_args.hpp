/**
 * @file
 * The positional arguments of the bench programs (the bench_ programs of bench/): `--help` (or `-h`) prints the program's usage
 * line and exits 0; a value that is not a number where one is expected, a number out of its range, or too many
 * arguments print one line naming the argument, then the usage, to stderr and exit 2 (never a crash or a run
 * with a value nobody asked for).
 */
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>

namespace gdsmc::bench {

/// `text` as a whole number in [least, most] (digits only: no sign, no blank, no wrap-around), else nothing.
inline bool parse_whole(const char* text, unsigned long long least, unsigned long long most, unsigned long long& value) {
  const char* last = text + std::strlen(text);
  const auto [end, error] = std::from_chars(text, last, value);
  return error == std::errc() && end == last && end != text && value >= least && value <= most;
}

class Args {
 public:
  /// `usage`: "usage: bench_x [N] [alpha] ...", printed for --help and after an error; `most`: the largest
  /// number of positional arguments the program takes.
  Args(int argc, char** argv, const char* usage, int most) : argc_(argc), argv_(argv), usage_(usage) {
    for (int i = 1; i < argc; ++i)
      if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
        std::printf("%s\n", usage);
        std::exit(0);
      }
    if (argc - 1 > most) fail("too many arguments (" + std::to_string(argc - 1) + ", at most " + std::to_string(most) + ")");
  }
  /// Whether argument `i` (from 1) was given.
  bool given(int i) const { return i < argc_; }
  /// Argument `i` as a whole number in [least, most], or `fallback` when it is absent.
  unsigned long long whole(int i, unsigned long long fallback, unsigned long long least = 0,
                           unsigned long long most = ~0ull) const {
    if (!given(i)) return fallback;
    const char* text = argv_[i];
    unsigned long long value = 0;
    if (!parse_whole(text, least, most, value))
      fail("argument " + std::to_string(i) + " '" + text + "' is not a whole number " +
           (most == ~0ull ? "of at least " + std::to_string(least)
                          : "in [" + std::to_string(least) + ", " + std::to_string(most) + "]"));
    return value;
  }
  /// Argument `i` as a finite number in [least, most], or `fallback` when it is absent.
  double real(int i, double fallback, double least = -HUGE_VAL, double most = HUGE_VAL) const {
    if (!given(i)) return fallback;
    const char* text = argv_[i];
    const char* last = text + std::strlen(text);
    double value = 0.0;
    const auto [end, error] = std::from_chars(text, last, value);
    if (error != std::errc() || end != last || end == text || !std::isfinite(value) || value < least || value > most)
      fail("argument " + std::to_string(i) + " '" + text + "' is not a finite number" +
           (least > -HUGE_VAL ? " of at least " + shortest(least) : std::string()) +
           (most < HUGE_VAL ? " and at most " + shortest(most) : std::string()));
    return value;
  }
  /// Argument `i` as text, or `fallback` when it is absent.
  std::string text(int i, const std::string& fallback) const { return given(i) ? argv_[i] : fallback; }
  /// One line naming what is wrong, then the usage, to stderr; exit status 2.
  [[noreturn]] void fail(const std::string& what) const {
    std::fprintf(stderr, "%s: %s\n%s\n", argv_[0], what.c_str(), usage_);
    std::exit(2);
  }

 private:
  static std::string shortest(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
  }
  int argc_;
  char** argv_;
  const char* usage_;
};

}  // namespace gdsmc::bench
