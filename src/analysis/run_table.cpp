#include "analysis/run_table.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "analysis/csv.hpp"
#include "analysis/predictions.hpp"
#include "analysis/sweep_table.hpp"
#include "io/config.hpp"
#include "io/h5md.hpp"
#include "model/observables.hpp"

namespace gdsmc::analysis::run_table {

namespace {

using io::h5md::ObservableData;

std::size_t columns_of(const ObservableData& o) { return o.shape.size() > 1 ? o.shape[1] : 1; }

/// Points of the sweep in `file`, 0 when it is not a sweep.
std::size_t sweep_points(const std::string& file) {
  try {
    return io::h5md::read_dataset(file, "/sweep/values").shape.at(0);
  } catch (const std::exception&) {
    return 0;
  }
}

/// A time series of the table of observables that --table prints as trajectory columns.
bool is_trajectory(const observables::Observable& o) {
  return o.reduction == observables::Reduction::series && std::string(o.shape).find("bins") == std::string::npos;
}

/// One observable to print: all its columns, or the one named.
struct Series {
  std::string name;                  ///< the observable
  ObservableData data;               ///< as read
  std::optional<std::size_t> column; ///< one column only (asked for by its CSV name, e.g. temperature_2)
};

/// The observable `name` of `root`, or why it cannot be a trajectory column.
ObservableData read_series(const std::string& file, const std::string& root, const std::string& name);

/// The request `name` (an observable, or one column of one by its CSV name) of `root`.
Series resolve(const std::string& file, const std::string& root, const std::string& name) {
  bool known = true;
  try {
    observables::find(name);
  } catch (const std::out_of_range&) {
    known = false;
  }
  if (known) return {name, read_series(file, root, name), std::nullopt};
  for (const auto& o : observables::table()) {  // an observable one of whose columns has this name
    const std::string prefix = std::string(o.name) + "_";
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0 || !is_trajectory(o)) continue;
    ObservableData data;
    try {
      data = io::h5md::read_observable(file, root + "/" + o.name);
    } catch (const io::h5md::NotAsWritten&) {
      throw;
    } catch (const std::runtime_error&) {
      continue;
    }
    const auto names = column_names(o.name, columns_of(data));
    if (const auto it = std::find(names.begin(), names.end(), name); it != names.end())
      return {o.name, std::move(data), static_cast<std::size_t>(it - names.begin())};
  }
  throw std::invalid_argument("'" + name + "' is neither an observable nor a column of one this run measured "
                              "(granular-dsmc --print-observables lists them; '--table " + file +
                              "' alone prints every column; 'summary' and 'reduced_distribution' are tables of their own)");
}

ObservableData read_series(const std::string& file, const std::string& root, const std::string& name) {
  const observables::Observable* o = &observables::find(name);
  if (name == "velocity_histogram")
    throw std::invalid_argument("'velocity_histogram' is a histogram per sample: read " + root +
                                "/velocity_histogram/species_K with h5py (docs/output.md)");
  if (o->reduction == observables::Reduction::particles)
    throw std::invalid_argument("'" + name + "' is part of a particle snapshot: read /particles/replica_R with h5py "
                                "(docs/output.md \"Particle snapshots\")");
  if (!is_trajectory(*o))
    throw std::invalid_argument("'" + name + "' is not a time series: '--table " + file +
                                " summary' prints the scaling state and the time averages");
  try {
    return io::h5md::read_observable(file, root + "/" + name);
  } catch (const io::h5md::NotAsWritten&) {
    throw;
  } catch (const std::runtime_error&) {
    throw std::invalid_argument("'" + name + "' was not measured in this run (" + file + " has no " + root + "/" + name +
                                "; '--table " + file + "' alone prints every time series it has)");
  }
}

/// Every trajectory observable `root` holds, in table order (`time` is the first column anyway).
std::vector<Series> every_series(const std::string& file, const std::string& root) {
  std::vector<Series> out;
  for (const auto& o : observables::table()) {
    if (!is_trajectory(o) || std::string(o.name) == "time") continue;
    try {
      out.push_back({o.name, io::h5md::read_observable(file, root + "/" + o.name), std::nullopt});
    } catch (const io::h5md::NotAsWritten&) {
      throw;  // damaged: the table is refused, not printed without it
    } catch (const std::runtime_error&) {
      // not measured in this run
    }
  }
  return out;
}

/// The theory trajectories of the point (those granular-theory prints), by observable name; notes say why none.
std::map<std::string, Trajectory> theory_of(const Request& r, std::vector<std::string>& notes) {
  try {
    const io::config::Config config = io::config::read_from_output(r.file);
    return trajectories(predict(r.point ? config.sweep_points().at(r.point - 1) : config));
  } catch (const std::exception& e) {
    notes.push_back(std::string("theory: not computed: ") + e.what());
    return {};
  }
}

/// Adds the columns of one observable (values, errors, theory) to `columns`.
void add_columns(std::vector<csv::Column>& columns, const Series& series, const Trajectory* theory) {
  const ObservableData& o = series.data;
  const std::size_t width = columns_of(o), rows = o.time.size();
  const auto names = column_names(series.name, width);
  for (std::size_t c = 0; c < width; ++c) {
    if (series.column && c != *series.column) continue;
    csv::Column value{names[c], {}, {}}, error{names[c] + "_error", {}, {}};
    for (std::size_t row = 0; row < rows; ++row) {
      value.values.push_back(o.value[row * width + c]);
      error.values.push_back(o.error.empty() ? std::nan("") : o.error[row * width + c]);
    }
    columns.push_back(std::move(value));
    columns.push_back(std::move(error));
    if (!theory || rows == 0 || theory->value.size() != rows || theory->value.front().size() <= c) continue;
    csv::Column predicted{names[c] + "_theory", {}, {}};
    for (std::size_t row = 0; row < rows; ++row) predicted.values.push_back(theory->value[row][c]);
    columns.push_back(std::move(predicted));
  }
}

/// Whether the run of `file` was collision-driven (&dsmc collisions_per_particle, as /parameters/dsmc holds it).
bool collision_driven(const std::string& file) {
  try {
    (void)io::h5md::read_attribute(file, "/parameters/dsmc", "collisions_per_particle");
    return true;
  } catch (const std::runtime_error&) {
    return false;
  }
}

Printed trajectories(const Request& r, const std::string& root) {
  std::vector<Series> series;
  if (r.quantities.empty()) series = every_series(r.file, root);
  for (const auto& name : r.quantities) series.push_back(resolve(r.file, root, name));
  if (series.empty()) throw std::invalid_argument(r.file + " holds no time series under " + root);
  Printed printed;
  const std::size_t rows = series.front().data.time.size();
  for (const auto& s : series)
    if (s.data.time.size() != rows)
      throw std::invalid_argument("'" + series.front().name + "' has " + std::to_string(rows) + " samples and '" + s.name +
                                  "' " + std::to_string(s.data.time.size()) + ": ask for them in two tables");
  std::vector<csv::Column> columns{{"time", series.front().data.time, {}}};
  // A collision-driven run's sample times differ between replicas: time_error, NaN with one replica (a
  // time-driven run's is zero but for the round-off of a mean of equal times: no column).
  if (collision_driven(r.file)) {
    const auto time = io::h5md::read_observable(r.file, root + "/time");
    columns.push_back({"time_error", time.error.empty() ? std::vector<double>(rows, std::nan("")) : time.error, {}});
  }
  std::map<std::string, Trajectory> theory;
  if (r.theory) theory = theory_of(r, printed.notes);
  for (const auto& s : series) {
    const auto it = theory.find(s.name);
    if (r.theory && it == theory.end()) printed.notes.push_back("theory: none for '" + s.name + "'");
    add_columns(columns, s, it == theory.end() ? nullptr : &it->second);
  }
  printed.csv = csv::write(columns, rows);
  return printed;
}

Printed distribution(const std::string& file, const std::string& root) {
  const std::string group = root + "/reduced_distribution";
  std::vector<double> edges;
  try {
    edges = io::h5md::read_dataset(file, group + "/bin_edges").data;
  } catch (const std::runtime_error&) {
    throw std::invalid_argument("'reduced_distribution' was not measured in this run (" + file + " has no " + group + ")");
  }
  if (edges.size() < 2) throw std::runtime_error(file + ": " + group + "/bin_edges holds no bin");
  const std::size_t bins = edges.size() - 1;
  csv::Column centre{"v_star", {}, {}};
  for (std::size_t b = 0; b < bins; ++b) centre.values.push_back(0.5 * (edges[b] + edges[b + 1]));
  std::vector<csv::Column> columns{centre};
  for (std::size_t k = 1;; ++k) {
    const std::string species = group + "/species_" + std::to_string(k);
    const std::string suffix = std::string("_") + std::to_string(k);
    try {
      for (const std::string quantity : {"phi", "delta", "g"}) {
        const std::string dataset = quantity == "phi" ? "value" : quantity;
        const std::string error = quantity == "phi" ? "error" : dataset + "_error";
        columns.push_back({quantity + suffix, io::h5md::read_dataset(file, species + "/" + dataset).data, {}});
        const auto e = io::h5md::read_dataset_if_present(file, species + "/" + error);  // (none with one replica)
        columns.push_back({quantity + suffix + "_error", e ? e->data : std::vector<double>(bins, std::nan("")), {}});
      }
    } catch (const std::runtime_error&) {
      if (k == 1) throw;
      break;
    }
  }
  return {csv::write(columns, bins), {}};
}

}  // namespace

std::vector<std::string> column_names(const std::string& name, std::size_t width) {
  if (width == 1) return {name};
  const std::string shape = observables::find(name).shape;
  std::vector<std::string> out;
  if (shape.find("pairs") != std::string::npos) {
    const auto species = static_cast<std::size_t>(std::lround((std::sqrt(8.0 * static_cast<double>(width) + 1.0) - 1.0) / 2.0));
    for (std::size_t i = 1; i <= species; ++i)
      for (std::size_t j = i; j <= species; ++j) out.push_back(name + "_" + std::to_string(i) + "_" + std::to_string(j));
  } else if (const auto colon = shape.find(':'); colon != std::string::npos) {  // "6: xx yy zz xy xz yz"
    std::istringstream labels(shape.substr(colon + 1));
    for (std::string label; labels >> label;) out.push_back(name + "_" + label);
  }
  if (out.size() != width) {  // species, cluster sizes, bins: numbered from 1
    out.clear();
    for (std::size_t k = 1; k <= width; ++k) out.push_back(name + "_" + std::to_string(k));
  }
  return out;
}

Printed print(const Request& r) {
  if (std::error_code ec; !std::filesystem::is_regular_file(r.file, ec))
    throw std::runtime_error(r.file + (std::filesystem::exists(r.file, ec) ? ": not a file" : ": no such file"));
  try {
    io::h5md::read_string_attribute(r.file, "/parameters", "namelist");
  } catch (const std::runtime_error&) {
    throw std::runtime_error(r.file + " is not an output file of granular-dsmc (it has no /parameters@namelist)");
  }
  const std::size_t points = sweep_points(r.file);
  const bool summary = std::find(r.quantities.begin(), r.quantities.end(), "summary") != r.quantities.end();
  const bool reduced = std::find(r.quantities.begin(), r.quantities.end(), "reduced_distribution") != r.quantities.end();
  if ((summary || reduced) && r.quantities.size() > 1)
    throw std::invalid_argument("'summary' and 'reduced_distribution' are tables of their own: ask for them alone");
  if (r.point && !points) throw std::invalid_argument(r.file + " is not a sweep: --point applies to the output of a &sweep run");
  if (r.point > points)
    throw std::invalid_argument("--point " + std::to_string(r.point) + ": " + r.file + " is a sweep of " +
                                std::to_string(points) + " points (1.." + std::to_string(points) + ")");
  if (points && !r.point && (summary || r.quantities.empty())) return {sweep_table::csv(sweep_table::read(r.file)), {}};
  if (points && !r.point)
    throw std::invalid_argument(r.file + " is a sweep of " + std::to_string(points) + " points: give --point K (1.." +
                                std::to_string(points) + ") for the trajectories of one, or no quantity for the sweep table");
  const std::string root = r.point ? "/sweep/point_" + std::to_string(r.point) + "/observables" : "/observables";
  if (summary) {
    const auto config = io::config::read_from_output(r.file);
    return {sweep_table::csv(sweep_table::summary(r.point ? config.sweep_points().at(r.point - 1) : config, r.file, root)), {}};
  }
  if (reduced) return distribution(r.file, root);
  return trajectories(r, root);
}

}  // namespace gdsmc::analysis::run_table
