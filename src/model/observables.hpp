/**
 * \file observables.hpp
 * \brief The table of observables: every quantity a run measures, once, with its unit, shape,
 *        definition, how its replicas are reduced and the docs section that defines it.
 *
 * As the namelist has one table of fields (io/config.hpp), the output has this one table of
 * observables. Sampling (dsmc/sample.hpp, the forcings of dsmc/thermostat.hpp, agg_frag) adds rows
 * under these names; the writer (io/output.hpp) takes each observable's unit and description from
 * here; io/units.hpp answers units from here; the sweep tables and `--compare` (analysis/) name their
 * quantities by it; `granular-dsmc --print-observables` prints it as the Markdown table of the docs
 * page \ref observables_page "observables". A name not in the table is a programming error
 * (find() throws), so that nothing is written without a unit and a definition.
 *
 * **A new observable is one entry here** plus the line that measures it (docs/extending.md,
 * \ref ext_observable "a new observable").
 */
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace gdsmc::observables {

/// How the replicas of a point are reduced, and how the observable is written.
enum class Reduction {
  series,       ///< a row per sample: mean and standard error over the replicas, /observables/\<name\> (H5MD time series)
  per_replica,  ///< one row per replica (a time average, a start time): written by its own writer beside the series
  ratio,        ///< &agg_frag per-size temperature: ratio of the replicas' sums (delta-method error)
  internal,     ///< a replica's working sum, turned into another observable before writing
  particles     ///< a particle snapshot: every replica's rows as they are, written to /particles (io/snapshot.hpp)
};

/// One observable.
struct Observable {
  const char* name;         ///< its name: the row name, and /observables/\<name\> for a series
  const char* unit;         ///< unit in the unit system "namelist" (\ref output_units "docs/output.md")
  const char* shape;        ///< its columns per sample: "1", "species", "6: xx yy zz xy xz yz", ...
  const char* description;  ///< its definition (the `description` attribute of the written observable)
  Reduction reduction;      ///< how replicas are reduced
  const char* anchor;       ///< the docs section that defines it: page and anchor, e.g. "docs/output.md#output_observables"
};

/// Every observable, in the order of the docs page.
const std::vector<Observable>& table();
/// The observable `name`; throws std::out_of_range for a name not in the table.
const Observable& find(std::string_view name);
/// The table as a Markdown table (the docs page; `granular-dsmc --print-observables`).
std::string markdown();

/// One observable's rows from all replicas of a point: values[replica][sample * columns + column].
struct Accumulator {
  std::size_t columns = 1;                  ///< values per sample (species, bins, ...)
  std::vector<std::vector<double>> values;  ///< values[replica][sample * columns + column]
  void add(std::size_t replica, const std::vector<double>& row);  ///< appends one sample row
  std::vector<double> mean() const;            ///< mean over the replicas of every entry
  std::vector<double> standard_error() const;  ///< empty when fewer than 2 replicas
};

/// The HCS distributions in reduced speed of a point, as dsmc/sample.hpp reduced_distributions()
/// derives them and io/output.hpp writes them (\ref son_reduced_distributions "docs/sonine.md").
struct ReducedDistributions {
  std::vector<double> edges;  ///< bins + 1 edges of v* over [0, range)
  /// One species' distributions (bins each; the errors empty with one replica).
  struct Species {
    std::vector<double> value;        ///< Phi_i(v*) in each bin
    std::vector<double> error;        ///< its standard error
    std::vector<double> delta;        ///< Delta_i(v*) of eq 27 (0 where the Maxwellian underflows)
    std::vector<double> delta_error;  ///< its standard error
    std::vector<double> g;            ///< G_i(v*) of eq 30
    std::vector<double> g_error;      ///< its standard error
    double sonine_c = 0.0;            ///< the measured c_i
    double lambda = 0.0;              ///< lambda_i = T/(T_i mu_ji)
    double tail_beta = 0.0;           ///< beta_i of eq 20
  };
  std::vector<Species> species;  ///< one or two
};
/// The per-size temperatures of an &agg_frag point, as dsmc/sample.hpp cluster_temperature() derives them.
struct ClusterTemperature {
  std::vector<double> value;  ///< T_k, samples x width
  std::vector<double> error;  ///< its standard error (empty with one replica)
};
}  // namespace gdsmc::observables
