/**
 * \file sweep_table.hpp
 * \brief The table of a sweep: the swept values and the headline results of every point, as numbers
 *        in the output file (`/sweep/values`, `/sweep/results`) and as CSV (`granular-dsmc --table`).
 *
 * \section sweep_table_layout Layout (\ref output_sweep_layout "docs/output.md")
 * - `/sweep/values`: float64 [points][variables], the value of each swept variable at each point, in
 *   the order of `&sweep variable`; attribute `variables` (strings): their names as written in the
 *   input, e.g. `system:restitution(1,2)`. A value that is not one number (a string, a quoted array)
 *   is NaN there; attribute `texts` (strings, [points * variables], point after point) holds every value
 *   as written, and `/sweep/point_K@value` the point's values.
 * - `/sweep/results/<quantity>/value` and `/error`: float64 [points][columns], columns = species (or
 *   cluster sizes of &agg_frag, padded with 0, error 0, to the widest point, as the observables give a
 *   size no replica has; one column for scalars); error = standard error over replicas (the dataset left
 *   out with one replica); NaN where a point has no such result or not the species another has.
 *   Attributes `at` (where the value is taken) and `description`; `/sweep/results@quantities` lists
 *   the quantities in table order, `/sweep/results@scaling_samples` (float64 [points]) the number of
 *   samples averaged for the scaling-state quantities of each point (0: the last sample is used).
 * - Quantities: `temperature` T_k and `total_temperature` T at the last sample (the final or, with a
 *   thermostat, the steady temperature); `temperature_over_mean` T_k/T and `sonine_c` c_k averaged over
 *   the scaling state (the samples past `&output scaling_start` collisions per particle, as
 *   `--compare`; the last sample when the run does not reach it); `cooling_rate_reduced` zeta* (one or two
 *   species, the reduced_distribution attribute); `shear_viscosity` eta/eta_0, the time average of a
 *   shear run; `collisions_per_particle` at the last sample.
 *
 * \section sweep_table_csv CSV
 * One header line, then one row per point: the swept variables (names as written), then for every
 * quantity and column `<quantity>[_<k>]` and `<quantity>[_<k>]_error` (k = species from 1; no suffix
 * for one column). A swept value that is not a number (a string, a quoted array) is written as its
 * text, without the namelist's single quotes. Fields that contain a comma or a quote are double-quoted
 * (RFC 4180); NaN is `nan`;
 * numbers have 12 significant digits.
 * Checked by tests/sweep_table_test.cpp and tests/cli_test.cpp (CliTable.*).
 */
#pragma once

#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/h5md.hpp"

namespace gdsmc::analysis::sweep_table {

/// One result quantity of every point: value and error row-major [points][columns].
struct Result {
  std::string name;         ///< the quantity, e.g. "temperature"
  std::string at;           ///< where the value is taken (the attribute `at`)
  std::string description;  ///< what it is (the attribute `description`)
  std::size_t columns = 1;  ///< species or cluster sizes (1 for a scalar)
  std::vector<double> value;  ///< [points][columns]
  std::vector<double> error;  ///< [points][columns], standard error over replicas
};

/// The table of a sweep: the swept values and the results of every point.
struct Table {
  std::vector<std::string> variables;  ///< as written in &sweep variable
  std::vector<double> values;          ///< [points][variables]
  std::vector<std::string> texts;      ///< [points][variables]: the values as written (may be empty when read)
  std::size_t points = 0;              ///< number of sweep points
  std::vector<Result> results;         ///< the quantities, in table order
  std::vector<double> scaling_samples;  ///< per point
};

/// The number a sweep value's text stands for (Fortran reals with d exponents, integers, logicals as
/// 1/0, a quoted number); NaN when it is not one number.
double numeric_value(const std::string& text);

/// The table of the sweep run `config` whose points were written to `file` (/sweep/point_K).
Table build(const io::config::Config& config, const std::string& file);
/// The same quantities for one run or sweep point (one row, no variables) whose observables are under
/// `root` of `file`: `--table FILE.h5 summary`.
Table summary(const io::config::Config& config, const std::string& file, const std::string& root = "/observables");
/// Writes /sweep/values and /sweep/results.
void write(io::h5md::Writer& writer, const Table& table);
/// Reads the table of an output file back. Throws std::runtime_error naming the file when it has none.
Table read(const std::string& file);
/// The table as CSV (\ref sweep_table_csv).
std::string csv(const Table& table);

}  // namespace gdsmc::analysis::sweep_table
