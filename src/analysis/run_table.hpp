/**
 * \file run_table.hpp
 * \brief `granular-dsmc --table FILE.h5 [QUANTITY...] [--point K] [--theory]`: any output file as CSV
 *        (\ref output_table "docs/output.md").
 *
 * What is printed (one table per call, in the CSV of analysis/csv.hpp):
 * - **trajectories** (a run, or `--point K` of a sweep): `time`, then for each quantity (every time
 *   series of the file when none is named, in the order of the table of observables,
 *   model/observables.hpp) and each of its columns the value and `<column>_error` (the standard error
 *   over replicas; `nan` with one replica). Columns are named from the observable's shape: one column
 *   `<quantity>`; species and cluster sizes `<quantity>_<k>`, k from 1; species pairs
 *   `<quantity>_<i>_<j>`, i <= j; tensors `<quantity>_xx` ... . A collision-driven run adds `time_error`
 *   (`nan` with one replica); a time-driven run has none.
 *   With `--theory`, every column the theory predicts a trajectory for (analysis::trajectories, what
 *   granular-theory prints for the input stored in the file, on the run's sample points) gets
 *   `<column>_theory` beside it.
 * - `summary`: the headline values of the run in one row, the quantities of a sweep table
 *   (analysis/sweep_table.hpp: final temperatures, the scaling state's T_k/T and c_k, zeta*, the time
 *   average of eta/eta_0).
 * - `reduced_distribution`: one row per bin of v*, `v_star` (the bin centre), then per species k
 *   `phi_k`, `delta_k`, `g_k` and their `_error` (`nan` with one replica; \ref son_reduced_distributions
 *   "docs/sonine.md").
 * - a sweep without `--point`: the sweep table (one row per point), as sweep_table::csv.
 * A request that cannot be answered (an unknown quantity, a quantity the run did not measure, a
 * point out of range, trajectories of different sample times) throws std::invalid_argument with one
 * line saying what to ask instead; a file that cannot be read throws std::runtime_error.
 * Checked by tests/run_table_test.cpp and tests/cli_test.cpp (CliTable.*).
 */
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace gdsmc::analysis::run_table {

/// What `--table` was asked for.
struct Request {
  std::string file;                     ///< the output file
  std::vector<std::string> quantities;  ///< observables, or `summary` / `reduced_distribution`; empty: all series
  std::size_t point = 0;                ///< sweep point, from 1; 0: the run (or the sweep table)
  bool theory = false;                  ///< add the theory columns of --compare
};

/// The table and what the reader should know about it (printed on stderr).
struct Printed {
  std::string csv;                  ///< the table
  std::vector<std::string> notes;   ///< e.g. a theory that could not be computed
};

/// The CSV for `request` (above).
Printed print(const Request& request);

/// The column names of the observable `name` when it has `width` columns (from its shape in the table
/// of observables): `name`, `name_k`, `name_i_j` or `name_xx`.
std::vector<std::string> column_names(const std::string& name, std::size_t width);

}  // namespace gdsmc::analysis::run_table
