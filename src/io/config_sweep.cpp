#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/config_detail.hpp"

namespace gdsmc::io::config {
namespace detail {

std::string sweep_override(const std::string& variable, const std::string& value) {
  const auto colon = variable.find(':');
  std::string name = variable.substr(colon + 1);
  name = name.substr(0, name.find('('));
  name.erase(std::remove(name.begin(), name.end(), ' '), name.end());
  const bool quoted = value.size() >= 2 && value.front() == '\'' && value.back() == '\'';
  if (quoted && !is_string_variable(lower(variable.substr(0, colon)), lower(name))) {
    std::string text;  // unquote: '' inside stands for one quote
    for (std::size_t i = 1; i + 1 < value.size(); ++i) {
      text += value[i];
      if (value[i] == '\'' && value[i + 1] == '\'') ++i;
    }
    return variable + "=" + text;
  }
  return variable + "=" + value;
}

namespace {
/// A &sweep variable as written, "group:name" or "group:name(i[,j])": its parts (lower-cased,
/// blanks removed); ok = false when it has not that form.
struct SweepTarget {
  std::string group, name;
  std::vector<long long> index;
  bool ok = false;
};

/// The variables of &output that belong to the run, not to a point (read from the run's Config only: one
/// output file and one checkpoint hold every point).
bool run_only(const std::string& group, const std::string& name) {
  return group == "output" && (name == "file" || name == "checkpoint_every" || name == "author");
}

/// `text` in lower case without its spaces: how a sweep's variable is read ('System:Mass( 2)' is 'system:mass(2)').
std::string folded(const std::string& text) {
  std::string out;
  for (char ch : text)
    if (ch != ' ') out += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

/// The swept variable closest to `written` among "group:name" of every variable a sweep may set, with
/// `written`'s index, for "did you mean"; "" when none is near.
std::string closest_target(const std::string& written) {
  std::vector<std::string> names;
  const auto add = [&](const char* group, const auto& fields) {
    for (const auto& f : fields)
      if (!run_only(group, f.name)) names.push_back(std::string(group) + ":" + f.name);
  };
  add("system", system_fields()), add("initial", initial_fields()), add("dsmc", dsmc_fields());
  add("output", output_fields()), add("agg_frag", agg_frag_fields()), add("thermostat", thermostat_fields());
  add("shear", shear_fields());
  const std::string text = folded(written.substr(0, written.find('(')));
  const std::size_t open = written.find('(');
  const std::string index = open == std::string::npos ? "" : written.substr(open);
  if (const std::string home = owning_group(text);
      text.find(':') == std::string::npos && !home.empty() && home != "sweep" && !run_only(home, text))
    return home + ":" + text + index;  // (the group left out)
  const std::string hint = namelist::closest_name(text, names);
  return hint.empty() ? hint : hint + index;
}

SweepTarget parse_target(const std::string& written) {
  SweepTarget t;
  const std::string text = folded(written);
  const auto colon = text.find(':');
  if (colon == std::string::npos) return t;
  t.group = text.substr(0, colon);
  std::string rest = text.substr(colon + 1);
  const auto open = rest.find('(');
  t.name = rest.substr(0, open);
  if (t.name.empty()) return t;
  if (open != std::string::npos) {
    if (rest.back() != ')') return t;
    std::istringstream list(rest.substr(open + 1, rest.size() - open - 2));
    for (std::string item; std::getline(list, item, ',');) {
      if (item.empty() || item.size() > 9 || item.find_first_not_of("0123456789") != std::string::npos) return t;
      t.index.push_back(std::stoll(item));
      if (t.index.back() < 1) return t;
    }
    if (t.index.empty()) return t;
  }
  t.ok = true;
  return t;
}

/// A mistake in the shape of &sweep: the variable to name and the message.
struct SweepShapeError {
  std::string variable, message;
};

/// The points of a sweep, row k = the value text of every variable at point k; throws
/// SweepShapeError when the values do not make points (docs/output.md "Sweeps").
std::vector<std::vector<std::string>> sweep_rows(const Sweep& sweep) {
  const std::size_t nv = sweep.variable.size();
  const SweepValues& sv = sweep.values;
  std::vector<std::vector<std::string>> rows;
  if (nv == 0 || sv.empty()) return rows;
  if (!sv.points.empty() && !sv.lists.empty())
    throw SweepShapeError{"values", "give the values point by point (values = ...) or one list per variable "
                                    "(values(1,v) = ...), not both"};
  if (!sv.points.empty()) {
    if (sweep.grid && nv > 1)
      throw SweepShapeError{"grid", "grid = .true. takes one list per variable: values(1,1) = ..., "
                                    "values(1,2) = ..."};
    if (sv.points.size() % nv != 0)
      throw SweepShapeError{"values", std::to_string(sv.points.size()) + " values for " + std::to_string(nv) +
                                          " variables given point by point: not a whole number of points (" +
                                          std::to_string(nv) + " values per point)"};
    for (std::size_t k = 0; k < sv.points.size(); k += nv)
      rows.emplace_back(sv.points.begin() + static_cast<std::ptrdiff_t>(k),
                        sv.points.begin() + static_cast<std::ptrdiff_t>(k + nv));
    return rows;
  }
  if (sv.lists.size() > nv)
    throw SweepShapeError{"values", "values(1," + std::to_string(sv.lists.size()) + ") is given, but there are only " +
                                        std::to_string(nv) + " variables"};
  for (std::size_t v = 0; v < nv; ++v)
    if (v >= sv.lists.size() || sv.lists[v].empty())
      throw SweepShapeError{"values", "no list for variable " + std::to_string(v + 1) + " ('" + sweep.variable[v] +
                                          "'): give values(1," + std::to_string(v + 1) + ") = ..."};
  if (!sweep.grid) {
    for (std::size_t v = 1; v < nv; ++v)
      if (sv.lists[v].size() != sv.lists[0].size())
        throw SweepShapeError{"values", "'" + sweep.variable[v] + "' has " + std::to_string(sv.lists[v].size()) +
                                            " values (values(1," + std::to_string(v + 1) + ")) but '" +
                                            sweep.variable[0] + "' has " + std::to_string(sv.lists[0].size()) +
                                            ": joint variables take lists of the same length (or set grid = "
                                            ".true. for every combination)"};
    for (std::size_t k = 0; k < sv.lists[0].size(); ++k) {
      rows.emplace_back();
      for (std::size_t v = 0; v < nv; ++v) rows.back().push_back(sv.lists[v][k]);
    }
    return rows;
  }
  constexpr double kMaxGridPoints = 1e6;
  double count = 1.0;
  for (const auto& list : sv.lists) count *= static_cast<double>(list.size());
  if (count > kMaxGridPoints)
    throw SweepShapeError{"grid", "the grid has " + std::to_string(static_cast<long long>(count)) +
                                      " points, more than 1e6"};
  std::vector<std::size_t> at(nv, 0);  // odometer, the last variable fastest
  for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k) {
    rows.emplace_back();
    for (std::size_t v = 0; v < nv; ++v) rows.back().push_back(sv.lists[v][at[v]]);
    for (std::size_t v = nv; v-- > 0;) {
      if (++at[v] < sv.lists[v].size()) break;
      at[v] = 0;
    }
  }
  return rows;
}

/// "restitution(1,2) = 0.7, mass(2) = 2.0": the assignments of one row of the sweep table.
std::string row_label(const Sweep& sweep, const std::vector<std::string>& row) {
  std::string joined;
  for (std::size_t v = 0; v < row.size() && v < sweep.variable.size(); ++v) {
    const auto colon = sweep.variable[v].find(':');
    joined += joined.empty() ? "" : ", ";
    joined += sweep.variable[v].substr(colon == std::string::npos ? 0 : colon + 1);
    joined += " = ";
    joined += row[v];
  }
  return joined;
}

/// The species-indexed variables, whose indices run to n_species.
bool per_species(const std::string& group, const std::string& name) {
  return (group == "system" && (name == "mass" || name == "diameter" || name == "number_density" ||
                                name == "restitution" || name == "roughness" || name == "moment_of_inertia")) ||
         (group == "initial" && (name == "temperature" || name == "rotational_temperature")) ||
         (group == "thermostat" && name == "noise_strength");
}
}  // namespace

/// &sweep: every variable names a variable (or an element of one) of another group, the values
/// make points, and every point reads and checks as a Config of its own (so a bad value stops the
/// run before any work).
void check_sweep(const Config& c, const Provenance& prov, const namelist::Document& document,
                 const std::vector<std::string>& overrides, const RunCheck& run_check) {
  const std::string group = "sweep";
  const auto line_of = [&](const char* v) { return prov.line.count(v) ? prov.line.at(v) : 0; };
  const Sweep& sweep = c.sweep;
  if (sweep.variable.empty() && sweep.values.empty()) return;  // grid alone: no sweep
  // Messages name where each was set: the namelist line, or the --set that gave it.
  if (sweep.variable.empty())
    throw Error(prov.file_of("values"), line_of("values"), group, "variable", "required with values");
  if (sweep.values.empty())
    throw Error(prov.file_of("variable"), line_of("variable"), group, "values", "required with variable");
  for (std::size_t v = 0; v < sweep.variable.size(); ++v) {
    const std::string& written = sweep.variable[v];
    const SweepTarget t = parse_target(written);
    if (!t.ok || t.group == "sweep" || owning_group(t.name) != t.group) {
      const std::string hint = closest_target(written);
      if (!hint.empty() && folded(written) == folded(hint))  // (the name is right: its index is the fault)
        throw Error(prov.file_of("variable"), line_of("variable"), group, "variable",
                    "'" + written + "': an index is a whole number from 1, as in 'group:name(i)' or 'group:name(i,j)'");
      throw Error(prov.file_of("variable"), line_of("variable"), group, "variable",
                  "'" + written + "' is not 'group:name' (or 'group:name(i)', 'group:name(i,j)') of a variable of "
                  "&system, &initial, &dsmc, &output, &agg_frag, &thermostat or &shear" +
                      (hint.empty() ? std::string() : " (did you mean '" + hint + "'?)"));
    }
    if (run_only(t.group, t.name))
      throw Error(prov.file_of("variable"), line_of("variable"), group, "variable",
                  "'" + written + "' belongs to the run, not to a point: one output file (and one checkpoint) holds "
                  "every point of a sweep");
    // (the matrices are symmetric: (i,j) and (j,i) are one element, which the second would set over the first)
    const auto element = [](std::vector<long long> index) {
      if (index.size() == 2 && index[0] > index[1]) std::swap(index[0], index[1]);
      return index;
    };
    for (std::size_t w = 0; w < v; ++w) {
      const SweepTarget other = parse_target(sweep.variable[w]);
      if (other.group != t.group || other.name != t.name) continue;
      if (element(other.index) == element(t.index))
        throw Error(prov.file_of("variable"), line_of("variable"), group, "variable",
                    "'" + written + "' is swept twice" +
                        (other.index == t.index ? std::string() : " (as '" + sweep.variable[w] + "': the matrix is symmetric)"));
      // (the whole variable and one of its elements: which value an element took would depend on their order)
      if (other.index.empty() != t.index.empty())
        throw Error(prov.file_of("variable"), line_of("variable"), group, "variable",
                    "'" + written + "' and '" + sweep.variable[w] + "' both set " +
                        (t.index.empty() ? sweep.variable[w] : written) + ": sweep the whole " + t.name +
                        " or its elements, not both");
    }
    const int rank = variable_rank(t.group, t.name);
    if (!t.index.empty() && static_cast<int>(t.index.size()) != rank)
      throw Error(prov.file_of("variable"), line_of("variable"), group, "variable",
                  "'" + written + "': " + t.name +
                      (rank == 0   ? " is a scalar and takes no index"
                       : rank == 1 ? " is a list: one index, " + t.name + "(k)"
                                   : " is a matrix: two indices, " + t.name + "(i,j)"));
    if (per_species(t.group, t.name))
      for (long long i : t.index)
        if (i > c.system.n_species)
          throw Error(prov.file_of("variable"), line_of("variable"), group, "variable",
                      "'" + written + "': index " + std::to_string(i) + " is out of range (n_species = " +
                          std::to_string(c.system.n_species) + ")");
  }
  std::vector<std::vector<std::string>> rows;
  try {
    rows = sweep_rows(sweep);
  } catch (const SweepShapeError& e) {
    throw Error(prov.file_of(e.variable), line_of(e.variable.c_str()), group, e.variable, e.message);
  }
  for (std::size_t k = 0; k < rows.size(); ++k) {
    auto o = overrides;
    for (std::size_t v = 0; v < rows[k].size(); ++v) o.push_back(sweep_override(sweep.variable[v], rows[k][v]));
    try {
      read_point(document, o, false, run_check);
    } catch (const Error& e) {
      // A bad value the namelist gave is blamed on its line; one a --set gave, on that --set (the
      // point's own override, which e.file names, is this sweep's doing, not the user's command).
      throw Error(prov.file_of("values"), line_of("values"), group, "values",
                  "point " + std::to_string(k + 1) + " (" + row_label(sweep, rows[k]) + "): " + e.message);
    }
  }
}

}  // namespace detail

using namespace detail;  // the tables and steps of config_detail.hpp

std::vector<std::vector<std::string>> Sweep::table() const {
  try {
    return sweep_rows(*this);
  } catch (const SweepShapeError&) {
    return {};  // refused when the namelist was read
  }
}

std::string Sweep::names() const {
  std::string joined;
  for (const auto& v : variable) joined += (joined.empty() ? "" : ", ") + v;
  return joined;
}

std::string Sweep::row_text(const std::vector<std::string>& row) {
  std::string joined;
  for (const auto& v : row) joined += (joined.empty() ? "" : ", ") + v;
  return joined;
}

std::string Sweep::row_label(const std::vector<std::string>& row) const { return detail::row_label(*this, row); }

std::vector<Config> Config::sweep_points() const {
  if (!is_sweep()) return {*this};
  const namelist::Document document = namelist::parse(namelist_text, source_file);
  std::vector<Config> points;
  for (const auto& row : sweep.table()) {
    auto o = overrides;
    for (std::size_t v = 0; v < row.size(); ++v) o.push_back(sweep_override(sweep.variable[v], row[v]));
    points.push_back(read_point(document, o, false, {}));
  }
  return points;
}

}  // namespace gdsmc::io::config
