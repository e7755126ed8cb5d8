#include "io/config.hpp"

#include <pwd.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <cstdio>
#include <variant>
#include <vector>

#include "io/config_detail.hpp"

namespace gdsmc::io::config {

/// The largest element index an assignment may name: above the most species (about 1.25e5), sample times (1e5)
/// and sweep values any input holds, below what an array that grows to it would take in memory.
constexpr long long kLargestIndex = 1000000;
namespace detail {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

namespace {
const char* kind_name(namelist::Value::Kind kind) {
  switch (kind) {
    case namelist::Value::Kind::Integer: return "an integer";
    case namelist::Value::Kind::Real: return "a real number";
    case namelist::Value::Kind::Logical: return "a logical";
    case namelist::Value::Kind::String: return "a string";
  }
  return "a value";
}

struct GroupReader {
  const std::string& file;
  const std::string& group;
  Error error(int line, const std::string& variable, const std::string& message) const {
    return Error(file, line, group, variable, message);
  }
  double number(const namelist::Value& v, const std::string& name, const Range& range) const {
    if (v.kind != namelist::Value::Kind::Integer && v.kind != namelist::Value::Kind::Real)
      throw error(v.line, name, "expected a real number, got " + std::string(kind_name(v.kind)) +
                                    " '" + v.text + "'");
    if (!std::isfinite(v.real)) throw error(v.line, name, "value '" + v.text + "' is not finite");
    if (!range.contains(v.real))
      throw error(v.line, name, name + " = " + v.text + " is outside " + range.text());
    return v.real;
  }
};

/// One assignment of the namelist to a field, by the field's type (assign() below).
struct Assigner {
  const std::string& name;
  const Range& range;
  const namelist::Assignment& a;
  const GroupReader& r;
  Provenance& prov;

  const namelist::Value& one_value() const {
    if (!a.index.empty()) throw r.error(a.line, name, name + " is a scalar and takes no index");
    if (a.values.size() != 1) throw r.error(a.line, name, "expected one value, got " + std::to_string(a.values.size()));
    return a.values.front();
  }
  void operator()(long long& out) const {
    const auto& v = one_value();
    if (v.kind != namelist::Value::Kind::Integer) {
      // (a whole number written as a real, 1e5: the integer to write instead)
      const bool whole = v.kind == namelist::Value::Kind::Real && std::isfinite(v.real) && v.real == std::floor(v.real) &&
                         std::fabs(v.real) < 1e15 && range.contains(v.real);
      throw r.error(v.line, name, "expected an integer, got " + std::string(kind_name(v.kind)) + " '" + v.text + "'" +
                                      (whole ? " (write " + std::to_string(static_cast<long long>(v.real)) + ")" : ""));
    }
    if (!range.contains(static_cast<double>(v.integer)))
      throw r.error(v.line, name, name + " = " + v.text + " is outside " + range.text());
    out = v.integer;
  }
  void operator()(double& out) const { out = r.number(one_value(), name, range); }
  void operator()(std::optional<double>& out) const { out = r.number(one_value(), name, range); }
  void operator()(bool& out) const {
    const auto& v = one_value();
    if (v.kind != namelist::Value::Kind::Logical)
      throw r.error(v.line, name, "expected a logical (.true. or .false.), got " + std::string(kind_name(v.kind)) + " '" +
                                      v.text + "'");
    out = v.logical;
  }
  const namelist::Value& one_string() const {
    const auto& v = one_value();
    if (v.kind != namelist::Value::Kind::String)
      throw r.error(v.line, name, "expected a quoted string, got " + std::string(kind_name(v.kind)) + " '" + v.text + "'");
    return v;
  }
  void operator()(std::string& out) const {
    const auto& v = one_string();
    if (v.string.empty()) throw r.error(v.line, name, name + " must not be empty");
    out = v.string;
  }
  template <Choice E>
  void operator()(E& out) const {
    const auto& v = one_string();
    const auto& names = Choices<E>::names;
    const auto it = std::find(names.begin(), names.end(), lower(v.string));
    if (it == names.end()) {
      std::string list;
      for (const auto c : names) list += (list.empty() ? "'" : ", '") + std::string(c) + "'";
      throw r.error(v.line, name, "'" + v.string + "' is not one of " + list);
    }
    out = static_cast<E>(it - names.begin());
  }
  void operator()(std::vector<double>& vec) const {
    if (a.index.size() > 1) throw r.error(a.line, name, name + " is one-dimensional: use " + name + "(k)");
    if (a.index.empty()) vec.clear();
    const std::size_t start = a.index.empty() ? 0 : static_cast<std::size_t>(a.index[0] - 1);
    if (vec.size() < start + a.values.size()) vec.resize(start + a.values.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < a.values.size(); ++i) vec[start + i] = r.number(a.values[i], name, range);
  }
  void operator()(std::vector<std::string>& list) const {
    // A list of quoted strings (the names of &sweep variable), kept without their quotes.
    if (!a.index.empty()) throw r.error(a.line, name, name + " takes no index");
    list.clear();
    for (const auto& v : a.values) {
      if (v.kind != namelist::Value::Kind::String)
        throw r.error(v.line, name, "expected a quoted string, got " + std::string(kind_name(v.kind)) + " '" + v.text + "'");
      if (v.string.empty()) throw r.error(v.line, name, name + " must not be empty");
      list.push_back(v.string);
    }
  }
  void operator()(SweepValues& sv) const {
    // Kept as namelist text, to be applied later as `group:variable=value`: `values = ...` point by
    // point, or `values(1,v) = ...` the list of variable v.
    std::vector<std::string> list;
    for (const auto& v : a.values) {
      if (v.kind != namelist::Value::Kind::String) {
        list.push_back(v.text);
        continue;
      }
      std::string quoted = "'";
      for (char ch : v.string) quoted += ch == '\'' ? std::string("''") : std::string(1, ch);
      list.push_back(quoted + "'");
    }
    if (a.index.empty()) {
      sv.points = std::move(list);
      return;
    }
    if (a.index.size() != 2 || a.index[0] != 1)
      throw r.error(a.line, name,
                    "one list per variable is written values(1,v) = ... (v = 1, 2, ... in the order of variable)");
    const auto v = static_cast<std::size_t>(a.index[1]);
    if (sv.lists.size() < v) sv.lists.resize(v);
    sv.lists[v - 1] = std::move(list);
  }
  void operator()(species::PairMatrix&) const {
    // Resolved once n_species is known (check stage); the values are checked now.
    if (a.index.size() == 1 || a.index.size() > 2) throw r.error(a.line, name, name + " is a matrix: use " + name + "(i,j)");
    for (const auto& v : a.values) r.number(v, name, range);
    if (a.index.empty()) prov.pair_assignments[name].clear();
    prov.pair_assignments[name].emplace_back(&a, r.file);
  }
};

template <class G>
void assign(G& target, const Field<G>& field, const namelist::Assignment& a, const GroupReader& r,
            Provenance& prov) {
  const Assigner assigner{field.name, field.range, a, r, prov};
  std::visit([&](auto member) { assigner(target.*member); }, field.member);
  prov.line[field.name] = a.line;
  prov.set_in[field.name] = r.file;
}

template <class G>
void read_group(G& target, const std::vector<Field<G>>& fields, const namelist::Group& group,
                const std::string& file, Provenance& prov) {
  GroupReader reader{file, group.name};
  // The same element assigned twice in one group is a mistake to report, not a value to overwrite
  // silently (a whole variable twice is refused by the namelist reader); --set overrides are
  // documents of their own and may replace.
  std::map<std::string, int> assigned;
  for (const auto& a : group.assignments) {
    if (a.index.empty()) continue;
    // (an element far beyond any array of the input: refused before the array grows to it)
    for (long long i : a.index)
      if (i > kLargestIndex)
        throw reader.error(a.line, a.name, a.name + " element " + std::to_string(i) + " is beyond any array of the input (at most " +
                                               std::to_string(kLargestIndex) + " elements)");
    std::string key = a.name;
    for (long long i : a.index) {
      key += ',';
      key += std::to_string(i);
    }
    if (const auto it = assigned.find(key); it != assigned.end())
      throw reader.error(a.line, a.name,
                         a.name + " element is assigned twice (also on line " +
                             std::to_string(it->second) + ")");
    assigned[key] = a.line;
  }
  for (const auto& a : group.assignments) {
    const auto it = std::find_if(fields.begin(), fields.end(),
                                 [&](const Field<G>& f) { return f.name == a.name; });
    if (it == fields.end()) {
      const std::string home = owning_group(a.name);
      if (!home.empty())
        throw reader.error(a.line, a.name, "unknown variable here: it belongs to &" + home);
      std::vector<std::string> names;
      for (const auto& f : fields) names.push_back(f.name);
      const std::string hint = namelist::closest_name(a.name, names);
      throw reader.error(a.line, a.name,
                         "unknown variable" + (hint.empty() ? std::string()
                                                            : " (did you mean '" + hint + "'?)"));
    }
    assign(target, *it, a, reader, prov);
  }
}

template <class G>
void check_required(const std::vector<Field<G>>& fields, const Provenance& prov,
                    const std::string& file, const std::string& group, int group_line,
                    const std::string& not_required = "") {
  for (const auto& f : fields)
    if (f.required && f.name != not_required && !prov.line.count(f.name))
      throw Error(file, group_line, group, f.name, "required variable is missing");
}

namelist::Document parse_override(const std::string& text) {
  const auto colon = text.find(':');
  const auto equal = text.find('=');
  if (colon == std::string::npos || equal == std::string::npos || colon > equal)
    throw Error("--set", 0, "", "", "'" + text + "' is not of the form group:variable=value");
  // (blanks around the group's name are dropped: " system : mass = 2" is system:mass=2, as in a file)
  const auto first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t", colon - 1);
  const std::string group = first < colon && last != std::string::npos ? text.substr(first, last + 1 - first) : "";
  if (group.empty() || group.find_first_of(" \t") != std::string::npos)
    throw Error("--set", 0, "", "", "'" + text + "' is not of the form group:variable=value");
  // One command-line argument, not a file: its messages and origins carry no line number.
  namelist::Document doc;
  try {
    doc = namelist::parse("&" + group + " " + text.substr(colon + 1) + " /", "--set " + text);
  } catch (const Error& e) {
    throw Error(e.file, 0, e.group, e.variable, e.message);
  }
  // One --set is one value (or one array) of one variable: a '/' that ends the group early and
  // starts another, or a second assignment, is refused rather than quietly applied or ignored.
  if (doc.groups.size() != 1 || doc.groups[0].assignments.size() != 1)
    throw Error("--set " + text, 0, group, "",
                "one --set assigns one variable: give each variable a --set of its own");
  for (auto& g : doc.groups) {
    g.line = 0;
    for (auto& a : g.assignments) {
      a.line = 0;
      for (auto& v : a.values) v.line = 0;
    }
  }
  return doc;
}
}  // namespace

Config read_point(const namelist::Document& document, const std::vector<std::string>& overrides,
                  bool expand_sweep, const RunCheck& run_check) {
  Config c;
  c.source_file = document.file;
  // A sweep point does not copy the document's text (nor read its &sweep group, below): with a long
  // list of values both would make the check of every point, and so of the whole sweep, quadratic.
  if (expand_sweep) c.namelist_text = document.text;
  c.overrides = overrides;

  static const std::vector<std::string> known = {"system", "initial", "dsmc", "output", "agg_frag", "thermostat", "shear", "sweep"};
  for (const auto& g : document.groups)
    if (std::find(known.begin(), known.end(), g.name) == known.end()) {
      const std::string hint = namelist::closest_name(g.name, known);
      throw Error(document.file, g.line, g.name, "",
                  "unknown group" + (hint.empty() ? std::string() : " (did you mean '&" + hint + "'?)"));
    }
  for (const char* required : {"system", "dsmc"})
    if (!document.find(required))
      throw Error(document.file, 0, required, "", "required group is missing");

  std::vector<namelist::Document> extra;
  extra.reserve(overrides.size());
  for (const auto& o : overrides) extra.push_back(parse_override(o));

  std::map<std::string, Provenance> prov;
  auto read_all = [&](const std::string& name, auto& target, const auto& fields) {
    Provenance& p = prov[name];
    p.file = document.file;
    if (const auto* g = document.find(name)) p.group_line = g->line;
    if (const auto* g = document.find(name)) read_group(target, fields, *g, document.file, p);
    for (const auto& doc : extra)  // errors and origins of what an override sets name the override
      if (const auto* g = doc.find(name)) {
        read_group(target, fields, *g, doc.file, p);
      } else if (!doc.groups.empty() &&
                 std::find(known.begin(), known.end(), doc.groups[0].name) == known.end()) {
        const std::string hint = namelist::closest_name(doc.groups[0].name, known);
        throw Error(doc.file, 0, doc.groups[0].name, "",
                    "unknown group" + (hint.empty() ? std::string() : " (did you mean '&" + hint + "'?)"));
      }
  };
  read_all("system", c.system, system_fields());
  read_all("initial", c.initial, initial_fields());
  read_all("dsmc", c.dsmc, dsmc_fields());
  read_all("output", c.output, output_fields());
  read_all("agg_frag", c.agg_frag, agg_frag_fields());
  read_all("thermostat", c.thermostat, thermostat_fields());
  read_all("shear", c.shear, shear_fields());
  if (expand_sweep) read_all("sweep", c.sweep, sweep_fields());
  c.has_agg_frag = document.find("agg_frag") != nullptr;
  for (const auto& doc : extra) c.has_agg_frag = c.has_agg_frag || doc.find("agg_frag") != nullptr;
  // &agg_frag runs with the low-rank scheme only: an input that names no scheme gets it (a named other
  // scheme is refused by check_agg_frag)
  if (c.has_agg_frag && !prov["dsmc"].line.count("scheme")) c.dsmc.scheme = Scheme::lowrank;
  // The white noise's kicks are split in halves around each stage (second order in its length): its stages
  // default to the longest allowed (docs/white-noise.md, "Stage length").
  if (c.thermostat.kind == ThermostatKind::white_noise && !prov["dsmc"].line.count("stage_step"))
    c.dsmc.stage_step = Dsmc::white_noise_stage_step;

  for (const auto& [group, p] : prov)
    for (const auto& [variable, line] : p.line)
      c.origin[group + ":" + variable] = {p.file_of(variable), line};
  // restitution is required by the constant model only (the viscoelastic one derives alpha).
  check_required(system_fields(), prov["system"], document.file, "system", document.find("system")->line,
                 c.system.restitution_model == RestitutionModel::viscoelastic ? "restitution" : "");
  prov["system"].group_line = document.find("system")->line;
  check_system(c.system, prov["system"]);
  check_initial(c.initial, static_cast<std::size_t>(c.system.n_species), prov["initial"]);
  check_rough(c, prov);
  check_scales(c, prov);
  check_dsmc(c.dsmc, c.mixture(), prov["dsmc"], document.find("dsmc")->line);
  check_output(c.output, c.dsmc, prov["output"]);
  if (c.has_agg_frag) check_agg_frag(c, prov);
  check_staged(c, prov);
  check_white_noise(c, prov);
  check_snapshots(c, prov);
  // Again after the snapshots of from_file, whose temperatures replace &initial's.
  check_scales(c, prov);
  check_viscoelastic_range(c, prov);
  if (run_check) run_check(c);
  if (expand_sweep && !prov["sweep"].line.empty()) {
    check_sweep(c, prov["sweep"], document, overrides, run_check);
  }
  return c;
}

}  // namespace detail

using namespace detail;  // the tables and steps of config_detail.hpp

Config read(const namelist::Document& document, const std::vector<std::string>& overrides, const RunCheck& run_check) {
  return read_point(document, overrides, true, run_check);
}

Config read_file(const std::string& path, const std::vector<std::string>& overrides, const RunCheck& run_check) {
  return read(namelist::parse_file(path), overrides, run_check);
}

Config read_from_output(const std::string& h5_path) {
  const std::string text = h5md::read_string_attribute(h5_path, "/parameters", "namelist");
  const std::string file = h5md::read_string_attribute(h5_path, "/parameters", "source_file");
  const std::string joined = h5md::read_string_attribute(h5_path, "/parameters", "overrides");
  std::vector<std::string> overrides;
  std::istringstream lines(joined);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) overrides.push_back(line);
  // A run started from a snapshot (&initial from_file) has its initial temperatures in /parameters: the
  // snapshot file may since have moved or changed, and is not read again (its assignment is dropped).
  namelist::Document document = namelist::parse(text, file);
  std::string from_file;
  try {
    from_file = h5md::read_string_attribute(h5_path, "/parameters/initial", "from_file");
  } catch (const std::runtime_error&) {
    // written before from_file existed
  }
  if (!from_file.empty()) {
    for (auto& group : document.groups)
      if (group.name == "initial")
        std::erase_if(group.assignments, [](const namelist::Assignment& a) { return a.name == "from_file"; });
    std::erase_if(overrides, [](const std::string& o) { return o.rfind("initial:from_file", 0) == 0; });
    for (const char* name : {"temperature", "rotational_temperature"}) {
      // (smooth spheres have no rotational temperature, and their outputs none)
      if (std::string(name) == "rotational_temperature" && !h5md::has_attribute(h5_path, "/parameters/initial", name))
        continue;
      const auto stored = h5md::read_attribute(h5_path, "/parameters/initial", name);
      const auto* values = std::get_if<std::vector<double>>(&stored);
      if (!values || values->empty()) continue;
      std::string list;
      for (double v : *values) {
        char number[32];
        std::snprintf(number, sizeof number, "%.17g", v);
        list += (list.empty() ? "" : ", ") + std::string(number);
      }
      overrides.push_back(std::string("initial:") + name + "=" + list);
    }
  }
  return read(document, overrides);
}

std::string author_name(const Output& output) {
  if (!output.author.empty()) return output.author;
  const char* user = std::getenv("USER");
  if (user && *user) return user;
  if (const passwd* entry = ::getpwuid(::getuid()); entry && entry->pw_name && *entry->pw_name)
    return entry->pw_name;  // no $USER (cron, containers): the login name of the user id
  return "unknown";
}

}  // namespace gdsmc::io::config
