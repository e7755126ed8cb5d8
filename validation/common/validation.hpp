/**
 * \file validation.hpp
 * \brief Shared plumbing of the validation programs: run a namelist, read the file, report checks.
 *
 * Every validation program is invoked as
 *   PROGRAM INPUT.nml [--set group:variable=value]... [--output FILE.h5]
 * It runs the simulation the namelist describes (the same code path as `granular-dsmc`, in
 * process), reads the H5MD file back, and compares with the theory module. Each comparison prints
 * one line: quantity, measured value, its standard error over replicas, the theory value, the
 * tolerance (z standard errors plus a stated systematic allowance) and PASS or FAIL. The program
 * exits non-zero when any check fails, so ctest fails.
 */
#pragma once

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "run/simulation.hpp"
#include "io/config.hpp"
#include "io/h5md.hpp"

namespace gdsmc::validation {

/// One validation run: its checked input and its output file.
struct Case {
  io::config::Config config;  ///< the namelist, with the command line's overrides
  std::string file;  ///< the H5MD output
  /// Where the Report is copied: `<file>.report.txt` (the docs quote it).
  std::string report_file() const { return file + ".report.txt"; }
};

/// Removes `name VALUE` from the command line (argc, argv) and returns VALUE: for options of a
/// program's own, such as `--gap`, before run_case reads the rest.
std::optional<std::string> take_option(int& argc, char** argv, const std::string& name);
/// Comma-separated numbers, e.g. "0.1,0.05".
std::vector<double> number_list(const std::string& text);

/// Parses the command line, reads the namelist and runs it (unless --reuse and the file exists).
Case run_case(int argc, char** argv, const std::string& default_output);

/// A program that runs several variants of one input (a scheme each, a seed each, ...): its command
/// line without `--output`, the output stem (from `--output`, extension dropped) and the checked
/// Config of the input with its `--set` overrides.
struct Variants {
  std::string stem;                 ///< output stem: each variant writes `<stem>_<name>.h5`
  std::vector<std::string> args;    ///< the command line without `--output FILE`
  io::config::Config config;        ///< the input with the command line's overrides
  /// run_case on that command line plus `extra` (e.g. `--set ... --output FILE`).
  Case run(const std::vector<std::string>& extra) const;
};
/// Reads the command line and the namelist for Variants; on a bad input prints it and exits with 2.
Variants read_variants(int argc, char** argv, const std::string& default_stem);

/// Collects checks and prints them; `exit_code()` is 1 if any failed.
///
/// With a `copy_to` file `X.report.txt`, exit_code() also writes `X.report.json`, the machine-readable
/// report that docs/figures.md and the validation pages are generated from (validation/reports/README.md):
/// {"title", "version" (io::build_version), "date" (UTC, ISO 8601), "checks": [{"quantity", "pass",
/// "measured", "standard_error", "theory", "z", "systematic", "tolerance", "diff_se" = |measured - theory|/SE} or {"quantity",
/// "pass"} for a require(), {"quantity", "stated": true, "measured", "standard_error", "theory", "diff_se"}
/// for a state()], "notes": [...], "failed"}; non-finite numbers as null.
class Report {
 public:
  /// Prints to stdout and, when `copy_to` is not empty, also to that file (the docs quote it).
  explicit Report(std::string title, std::string copy_to = "");
  ~Report();
  /// |measured - theory| <= z * standard_error + systematic. Returns whether it passed.
  bool check(const std::string& quantity, double measured, double standard_error, double theory,
             double z, double systematic = 0.0);
  /// A plain condition (for sanity checks that are not statistical).
  bool require(const std::string& what, bool condition);
  /// A comparison stated, not asserted (no independent estimate of the reference's error exists): printed
  /// as `STATED`, in the JSON with `"stated": true` and no `pass`; it counts as no check.
  void state(const std::string& quantity, double measured, double standard_error, double reference);
  /// A line of text in the report (no check).
  void note(const std::string& text);
  /// 0 when every check passed, else 1; prints the summary line.
  int exit_code();

 private:
  void print(const char* format, ...);
  void write_json() const;
  std::string title_;
  std::string copy_to_;
  std::FILE* copy_ = nullptr;
  int checks_ = 0, failures_ = 0;
  std::vector<std::string> json_checks_;  ///< each check as a JSON object
  std::vector<std::string> notes_;
};

/// The observable `name` of the case's output file.
io::h5md::ObservableData observable(const Case& c, const std::string& name);

/// An independent exact value (DSMC without time step, many replicas, by programs other than this
/// one; \ref son_binary_gamma "docs/sonine.md"), when one is known for the case.
struct ExactValue {
  bool known = false;   ///< an exact value is known for the case
  double value = 0.0;   ///< the value
  double error = 0.0;  ///< its standard error (0 where none is quoted)
};
/// gamma = T1/T2 of the dilute binary HCS: 3.7968 +- 0.0011 for mu = 10, delta = 2, w = 1,
/// alpha = 0.5; 1.3616 for mu = 2, delta = 1, w = 1, alpha = 0.5 (no SE quoted: 0.0001, the last
/// digit).
ExactValue exact_temperature_ratio(const species::Mixture& mix);
/// c_1 of the same HCS: 0.1280 +- 0.0004 for mu = 2, delta = 1, w = 1, alpha = 0.5 (species 0).
ExactValue exact_cumulant_species1(const species::Mixture& mix);
/// c = 2 a2 of one species: 0.0959 (alpha = 0.5) and 0.2078 (alpha = 0.3); no SE quoted: 0.0001.
ExactValue exact_cumulant_one_species(double alpha);

/// T_k/T and c_k of the HCS of a dilute mixture from the independent program of
/// validation/independent_reference (a second method that shares no code with src/; README.md there),
/// when the table holds the mixture (matched by mass, diameter and number-fraction ratios and one
/// common restitution; for the Enskog gas also by the number densities).
struct IndependentHcs {
  bool known = false;                ///< the table holds the mixture
  std::vector<double> ratio;         ///< T_k/T, T = sum_k x_k T_k
  std::vector<double> ratio_error;   ///< their standard errors
  std::vector<double> cumulant;      ///< c_k = 2 [(3/5) <v^4>_k/<v^2>_k^2 - 1]
  std::vector<double> cumulant_error;  ///< their standard errors
  std::string source;                ///< the command that produced the entry
};
/// The table entry for `mix` (known = false if there is none).
IndependentHcs independent_hcs_reference(const species::Mixture& mix);

/// The rows "KEYWORD t v_1 e_1 ... v_S e_S" (value and standard error per species) that
/// validation/independent_reference's program writes in its time-resolved mode (`temperature`, `msd`).
struct IndependentSeries {
  std::vector<double> time;                ///< t of each row, in file order
  std::vector<std::vector<double>> value;  ///< value[row][species]
  std::vector<std::vector<double>> error;  ///< its standard error
};
/// Reads the `keyword` rows of `file` with `species` value-error pairs each; stops at the first
/// malformed row. An unreadable file gives no rows.
IndependentSeries read_independent_series(const std::string& file, const std::string& keyword, std::size_t species);

/// The rows "quantity value se" that validation/independent_reference's program writes in its --shear modes, by
/// quantity; lines starting with '#' and malformed lines are skipped. An unreadable file gives no rows.
std::map<std::string, std::pair<double, double>> read_independent_rows(const std::string& file);

/// The scaling state of a run (its `scaling_state` group, docs/output.md): c_k and T_k/T of each replica
/// averaged over its samples past `&output scaling_start`, then over the replicas, with the standard
/// error over the replicas, which is that of the time average whatever the correlation between the
/// samples (unlike the mean of the samples' SE, an upper bound).
struct ScalingState {
  bool known = false;                  ///< the group exists with `species` values and errors
  std::vector<double> c;               ///< c_k
  std::vector<double> c_error;         ///< its SE
  std::vector<double> share;           ///< T_k/T
  std::vector<double> share_error;     ///< its SE
};
/// Reads `observables_root`/scaling_state ("/observables" or "/sweep/point_K/observables").
ScalingState read_scaling_state(const std::string& file, const std::string& observables_root, std::size_t species);

/// A steady state's mean and an upper bound of its standard error (steady_average).
struct SteadyAverage {
  double value = 0.0;  ///< the mean over the samples
  double error = 0.0;  ///< the mean of their standard errors (the samples are correlated); NaN without errors
};
/// Column `column` of an observable of `columns` columns (Nt x S, time-major; 1 for a scalar one) over the
/// samples at t >= `from`, times `scale`: the mean and the mean of the samples' standard errors.
SteadyAverage steady_average(const io::h5md::ObservableData& o, double from, double scale = 1.0, std::size_t column = 0,
                             std::size_t columns = 1);

}  // namespace gdsmc::validation
