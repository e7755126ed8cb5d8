/**
 * \file output.hpp
 * \brief The layout of one point's results in the H5MD file (\ref output_h5md "docs/output.md"):
 *        what goes where, with which unit and description. No physics: every value it writes was
 *        measured or derived before (dsmc/sample.hpp), and every observable's unit and definition is
 *        the table's (model/observables.hpp).
 *
 * Under `root` ("/observables", or "/sweep/point_K/observables"):
 * - every observable of Reduction::series as an H5MD time series `<name>/{step, time, value[, error]}`
 *   (mean and standard error over the replicas), with the unit and description of the table; the
 *   `step` of a sample is the replicas' mean collision count rounded (docs/output.md "The H5MD file");
 * - `velocity_histogram/species_k` and `bin_edges`; `msd/start_time`;
 * - `scaling_state/` (c_k and T_k/T per replica, reduced), when every replica has such samples;
 * - `reduced_distribution/species_k/` (Phi_i, Delta_i, G_i) of one or two species;
 * - the time averages of the shear viscosity as attributes of `shear_viscosity`;
 * - &agg_frag points: the per-size series and the cluster temperature (ratio of the replicas' sums).
 */
#pragma once

#include <map>
#include <optional>
#include <string>

#include "io/config.hpp"
#include "io/h5md.hpp"
#include "model/observables.hpp"

namespace gdsmc::io::output {

/// One point's results, reduced over its replicas: the writer's input.
struct Point {
  std::map<std::string, observables::Accumulator> observables;  ///< per observable, the replicas' rows
  std::optional<observables::ReducedDistributions> reduced;      ///< with "reduced_distribution"
  std::optional<observables::ClusterTemperature> cluster_temperature;  ///< &agg_frag points
};

/// Writes one point of `config` under `root` (header).
void write_point(h5md::Writer& writer, const std::string& root, const config::Config& config, const Point& point);

}  // namespace gdsmc::io::output
