#include "analysis/sweep_table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "analysis/compare.hpp"
#include "analysis/csv.hpp"
#include "io/units.hpp"
#include "model/observables.hpp"

namespace gdsmc::analysis::sweep_table {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// One point's results, before they are put into columns of equal width.
struct PointValues {
  std::vector<double> value, error;
  bool present = false;
};

std::vector<double> errors_or_nan(const io::h5md::ObservableData& o) {
  return o.error.empty() ? std::vector<double>(o.value.size(), kNaN) : o.error;
}
std::size_t columns_of(const io::h5md::ObservableData& o) { return o.shape.size() > 1 ? o.shape[1] : 1; }

/// The last row of an observable.
PointValues last(const io::h5md::ObservableData& o) {
  PointValues p;
  const std::size_t c = columns_of(o), nt = o.value.empty() ? 0 : o.value.size() / c;
  if (nt == 0) return p;
  const auto e = errors_or_nan(o);
  p.value.assign(o.value.end() - static_cast<std::ptrdiff_t>(c), o.value.end());
  p.error.assign(e.end() - static_cast<std::ptrdiff_t>(c), e.end());
  p.present = true;
  return p;
}

}  // namespace

double numeric_value(const std::string& written) {
  std::string text = written;
  if (text.size() >= 2 && text.front() == '\'' && text.back() == '\'') text = text.substr(1, text.size() - 2);
  while (!text.empty() && text.front() == ' ') text.erase(text.begin());
  while (!text.empty() && text.back() == ' ') text.pop_back();
  const std::string l = lower(text);
  if (l == ".true." || l == ".t." || l == "t") return 1.0;
  if (l == ".false." || l == ".f." || l == "f") return 0.0;
  std::string number = l;
  std::replace(number.begin(), number.end(), 'd', 'e');  // Fortran 1.5d-3
  if (number.empty()) return kNaN;
  char* end = nullptr;
  const double x = std::strtod(number.c_str(), &end);
  return end && *end == '\0' && std::isfinite(x) ? x : kNaN;
}

namespace {

/// The quantities of the table and where each is taken.
const std::vector<std::pair<std::string, std::string>>& quantities() {
  static const std::vector<std::pair<std::string, std::string>> names = {
      {"temperature", "last sample (final temperature; steady with a thermostat)"},
      {"total_temperature", "last sample (final temperature; steady with a thermostat)"},
      {"temperature_over_mean", "scaling state: samples past &output scaling_start averaged per replica, SE over the replicas (else the last sample)"},
      {"sonine_c", "scaling state: samples past &output scaling_start averaged per replica, SE over the replicas (else the last sample)"},
      {"cooling_rate_reduced", "scaling state (reduced_distribution@cooling_rate_reduced)"},
      {"shear_viscosity", "time average from &shear average_from (shear_viscosity@time_average)"},
      {"collisions_per_particle", "last sample"}};
  return names;
}

/// The results of one run or sweep point (`root`: its observables group), in the order of quantities();
/// `scaling_samples` = the samples averaged for the scaling state (0: the last sample is used).
std::vector<PointValues> point_results(const io::config::Config& point, const std::string& file,
                                       const std::string& root, double& scaling_samples) {
  std::vector<PointValues> per(quantities().size());
  const compare::Measured m = compare::read_measured(file, root);
  const auto get = [&](const char* name) -> const io::h5md::ObservableData* {
    const auto it = m.observables.find(name);
    return it == m.observables.end() ? nullptr : &it->second;
  };
  if (const auto* o = get("temperature")) per[0] = last(*o);
  if (const auto* o = get("total_temperature")) per[1] = last(*o);
  if (const auto* o = get("collisions_per_particle")) per[6] = last(*o);
  scaling_samples = 0.0;
  if (!point.has_agg_frag && get("temperature") && get("total_temperature") && get("collisions_per_particle")) {
    // The scaling state (compare.hpp scaling_state): past scaling_start, else the last sample.
    const auto& cpp = get("collisions_per_particle")->value;
    const double start = point.output.scaling_start;
    const bool any = std::any_of(cpp.begin(), cpp.end(), [&](double x) { return x >= start; });
    const double from = any ? start : (cpp.empty() ? 0.0 : cpp.back());
    if (const auto state = compare::scaling_state(m, from, any)) {
      scaling_samples = any ? static_cast<double>(state->samples) : 0.0;
      const bool present = !state->ratio.empty() && !get("total_temperature")->value.empty();
      per[2] = {state->ratio, state->ratio_error, present};
      per[3] = {state->cumulant, state->cumulant_error, present};
    }
  }
  const auto attribute = [&](const char* key) {
    const auto it = m.attributes.find(key);
    return it == m.attributes.end() ? kNaN : it->second;
  };
  if (m.attributes.count("reduced_distribution@cooling_rate_reduced"))
    per[4] = {{attribute("reduced_distribution@cooling_rate_reduced")},
              {attribute("reduced_distribution@cooling_rate_reduced_error")}, true};
  if (m.attributes.count("shear_viscosity@time_average"))
    per[5] = {{attribute("shear_viscosity@time_average")}, {attribute("shear_viscosity@time_average_error")}, true};
  return per;
}

/// The table of `points` (configs) whose observables are under `roots` of `file`.
Table tabulate(Table t, const std::vector<io::config::Config>& points, const std::vector<std::string>& roots,
               const std::string& file) {
  const auto& names = quantities();
  std::vector<std::vector<PointValues>> per(names.size(), std::vector<PointValues>(t.points));
  t.scaling_samples.assign(t.points, 0.0);
  for (std::size_t k = 0; k < t.points; ++k) {
    const auto results = point_results(points[k], file, roots[k], t.scaling_samples[k]);
    for (std::size_t q = 0; q < names.size(); ++q) per[q][k] = results[q];
  }
  for (std::size_t q = 0; q < names.size(); ++q) {
    std::size_t width = 0;
    for (const auto& p : per[q])
      if (p.present) width = std::max(width, p.value.size());
    if (width == 0) continue;  // no point has this result
    // What each quantity is: the table of observables' definition (model/observables.hpp).
    Result r{names[q].first, names[q].second, observables::find(names[q].first).description, width, {}, {}};
    // An &agg_frag point's cluster sizes past its largest: 0, as the observables give a size no replica
    // has (\ref af_observables "docs/agg-frag.md"), with error 0 where the point has standard errors (with
    // one replica none has one); NaN for a point without the result, or without a species another has
    // (a sweep over n_species: the species is not there, its temperature is no number).
    for (std::size_t k = 0; k < t.points; ++k) {
      const PointValues& p = per[q][k];
      const bool sizes = points[k].has_agg_frag;
      const bool errors = std::any_of(p.error.begin(), p.error.end(), [](double e) { return std::isfinite(e); });
      for (std::size_t c = 0; c < width; ++c) {
        r.value.push_back(!p.present ? kNaN : c < p.value.size() ? p.value[c] : sizes ? 0.0 : kNaN);
        r.error.push_back(!p.present ? kNaN : c < p.error.size() ? p.error[c] : sizes && errors ? 0.0 : kNaN);
      }
    }
    t.results.push_back(std::move(r));
  }
  return t;
}

}  // namespace

Table build(const io::config::Config& config, const std::string& file) {
  Table t;
  t.variables = config.sweep.variable;
  const auto rows = config.sweep.table();
  t.points = rows.size();
  for (const auto& row : rows)
    for (const auto& v : row) {
      t.values.push_back(numeric_value(v));
      t.texts.push_back(v);
    }
  std::vector<std::string> roots;
  for (std::size_t k = 0; k < t.points; ++k) roots.push_back("/sweep/point_" + std::to_string(k + 1) + "/observables");
  return tabulate(std::move(t), config.sweep_points(), roots, file);
}

Table summary(const io::config::Config& config, const std::string& file, const std::string& root) {
  Table t;
  t.points = 1;
  return tabulate(std::move(t), {config}, {root}, file);
}

void write(io::h5md::Writer& writer, const Table& t) {
  writer.write_dataset("/sweep/values", t.values, {t.points, t.variables.size()});
  writer.write_attribute("/sweep/values", "variables", t.variables);
  writer.write_attribute("/sweep/values", "texts", t.texts);
  writer.write_group("/sweep/results");
  std::vector<std::string> quantities;
  for (const auto& r : t.results) {
    const std::string g = "/sweep/results/" + r.name;
    writer.write_dataset(g + "/value", r.value, {t.points, r.columns});
    // The unit of the quantity (\ref output_units "docs/output.md"), as on its observable.
    writer.write_unit(g + "/value", io::units::of_observable(r.name));
    // (no standard error at all, as with one replica: left out, not written as NaN)
    if (std::any_of(r.error.begin(), r.error.end(), [](double e) { return std::isfinite(e); })) {
      writer.write_dataset(g + "/error", r.error, {t.points, r.columns});
      writer.write_unit(g + "/error", io::units::of_observable(r.name));
    }
    writer.write_attribute(g, "at", r.at);
    writer.write_attribute(g, "description", r.description);
    quantities.push_back(r.name);
  }
  writer.write_attribute("/sweep/results", "quantities", quantities);
  writer.write_attribute("/sweep/results", "scaling_samples", t.scaling_samples);
}

Table read(const std::string& file) {
  Table t;
  io::h5md::ArrayData values;
  try {
    values = io::h5md::read_dataset(file, "/sweep/values");
  } catch (const std::runtime_error& e) {
    // A file that cannot be read at all says why; one without the table says that.
    try {
      (void)io::h5md::read_string_attribute(file, "/h5md/creator", "name");
    } catch (const std::runtime_error&) {
      throw std::runtime_error(e.what());
    }
    bool old_sweep = false;  // a sweep written before tables existed: /sweep@variable without /sweep/values
    try {
      (void)io::h5md::read_attribute(file, "/sweep", "variable");
      old_sweep = true;
    } catch (const std::runtime_error&) {
    }
    throw std::runtime_error("'" + file + "' has no sweep table (/sweep/values): " +
                             (old_sweep ? std::string("a sweep written before sweep tables existed; run it again")
                                        : std::string("it is not the output of a &sweep run")));
  }
  if (values.shape.size() != 2) throw std::runtime_error("'" + file + "': /sweep/values is not [points][variables]");
  t.points = values.shape[0];
  t.values = values.data;
  const auto names = io::h5md::read_attribute(file, "/sweep/values", "variables");
  if (const auto* v = std::get_if<std::vector<std::string>>(&names)) t.variables = *v;
  else if (const auto* one = std::get_if<std::string>(&names)) t.variables = {*one};
  try {
    const auto texts = io::h5md::read_attribute(file, "/sweep/values", "texts");
    if (const auto* v = std::get_if<std::vector<std::string>>(&texts)) t.texts = *v;
    else if (const auto* one = std::get_if<std::string>(&texts)) t.texts = {*one};
  } catch (const std::runtime_error&) {
  }
  const auto quantities = io::h5md::read_attribute(file, "/sweep/results", "quantities");
  std::vector<std::string> list;
  if (const auto* v = std::get_if<std::vector<std::string>>(&quantities)) list = *v;
  else if (const auto* one = std::get_if<std::string>(&quantities)) list = {*one};
  for (const auto& name : list) {
    Result r;
    r.name = name;
    const auto v = io::h5md::read_dataset(file, "/sweep/results/" + name + "/value");
    r.columns = v.shape.size() > 1 ? v.shape[1] : 1;
    r.value = v.data;
    r.error.assign(r.value.size(), kNaN);  // (left out where no point has one: one replica)
    if (auto e = io::h5md::read_dataset_if_present(file, "/sweep/results/" + name + "/error")) r.error = std::move(e->data);
    t.results.push_back(std::move(r));
  }
  return t;
}

std::string csv(const Table& t) {
  std::vector<csv::Column> columns;
  const std::size_t nv = t.variables.size();
  for (std::size_t v = 0; v < nv; ++v) {
    csv::Column column{t.variables[v], {}, {}};
    for (std::size_t k = 0; k < t.points; ++k) {
      const std::size_t i = k * nv + v;
      column.values.push_back(t.values[i]);
      std::string text;
      if (std::isnan(t.values[i]) && i < t.texts.size()) {  // a string or an array: its text, unquoted
        text = t.texts[i];
        if (text.size() >= 2 && text.front() == '\'' && text.back() == '\'') text = text.substr(1, text.size() - 2);
      }
      column.texts.push_back(text);
    }
    columns.push_back(std::move(column));
  }
  for (const auto& r : t.results)
    for (std::size_t c = 0; c < r.columns; ++c) {
      const std::string name = r.columns > 1 ? r.name + "_" + std::to_string(c + 1) : r.name;
      csv::Column value{name, {}, {}}, error{name + "_error", {}, {}};
      for (std::size_t k = 0; k < t.points; ++k) {
        value.values.push_back(r.value[k * r.columns + c]);
        error.values.push_back(r.error[k * r.columns + c]);
      }
      columns.push_back(std::move(value));
      columns.push_back(std::move(error));
    }
  return csv::write(columns, t.points);
}

}  // namespace gdsmc::analysis::sweep_table
