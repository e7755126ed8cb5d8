#include "io/config.hpp"

#include <pwd.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <type_traits>
#include <variant>

#include "model/restitution.hpp"

namespace gdsmc::io::config {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using namelist::Error;

/// Where a value may lie: [lo, hi] with optionally open ends; only for numbers.
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  bool contains(double x) const {
    return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  std::string text() const {
    std::ostringstream s;
    s << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
    return s.str();
  }
};
const Range kPositive{0.0, kInf, true, false};
const Range kUnit{0.0, 1.0, false, false};
Range at_least(double lo) { return Range{lo, kInf, false, false}; }

/// One variable of a group: declared once, used by the reader, the checks and the writers.
template <class G>
struct Field {
  using Member = std::variant<long long G::*, double G::*, bool G::*, std::string G::*,
                              std::optional<double> G::*, std::vector<double> G::*,
                              std::vector<std::string> G::*, SweepValues G::*,
                              species::PairMatrix G::*>;
  std::string name;
  Member member;
  std::string units;
  std::string help;
  Range range{};
  std::vector<std::string> choices{};
  bool required = false;
};

// ---------------------------------------------------------------------------------------------
// The four tables. Defaults are the member initialisers in config.hpp, nowhere else.
// ---------------------------------------------------------------------------------------------
const std::vector<Field<System>>& system_fields() {
  static const std::vector<Field<System>> fields = {
      {"n_species", &System::n_species, "", "number of species S", Range{1, 1e7}},
      {"mass", &System::mass, "mass", "m_k, one per species (or species 1 with mass_law)",
       kPositive, {}, true},
      {"diameter", &System::diameter, "length",
       "sigma_k, one per species (or species 1 with diameter_law)", kPositive, {}, true},
      {"number_density", &System::number_density, "1/length^3",
       "n_k, one per species (or species 1 with density_law)", kPositive, {}, true},
      {"restitution", &System::restitution, "",
       "alpha_kj: one value for all pairs, or restitution(i,j) = ... (symmetric; required when constant)",
       kUnit, {}, true},
      {"restitution_model", &System::restitution_model, "",
       "'constant' (alpha_kj), or 'viscoelastic' (alpha from the impact speed, Bodrova and Osinsky 2024, eqs. (5)-(8), docs/viscoelastic.md)", {},
       {"constant", "viscoelastic"}},
      {"visco_a_kappa", &System::visco_a_kappa, "velocity^(-1/5)",
       "beta_11 = A kappa_11^(2/5) of the viscoelastic model; other pairs by the one-material scaling "
       "of docs/viscoelastic.md", at_least(0)},
      {"enskog", &System::enskog, "",
       ".true.: Carnahan-Starling chi_ij multiplies the collision rates (Montanero and Garzo 2002, eq. (26), docs/collision-model.md)"},
      {"mass_law", &System::mass_law, "", "'list', or 'linear': m_k = k m_1", {},
       {"list", "linear"}},
      {"diameter_law", &System::diameter_law, "", "'list', or 'cube_root': sigma_k = k^(1/3) sigma_1",
       {}, {"list", "cube_root"}},
      {"density_law", &System::density_law, "", "'list', or 'power': n_k = n_1 k^-theta", {},
       {"list", "power"}},
      {"density_exponent", &System::density_exponent, "", "theta of density_law = 'power'"},
  };
  return fields;
}

const std::vector<Field<Initial>>& initial_fields() {
  static const std::vector<Field<Initial>> fields = {
      {"temperature", &Initial::temperature, "energy",
       "T_k(0), one per species or one for all (k_B = 1)", kPositive},
      {"distribution", &Initial::distribution, "",
       "initial velocities: 'maxwell', 'shell' (equal speeds) or 'cube' (uniform in a cube)", {},
       {"maxwell", "shell", "cube"}},
  };
  return fields;
}

const std::vector<Field<Dsmc>>& dsmc_fields() {
  static const std::vector<Field<Dsmc>> fields = {
      {"scheme", &Dsmc::scheme, "",
       "'majorant' (DSMC notes, docs/schemes.md), 'pairs' (Montanero and Garzo 2002) or 'lowrank' (Bodrova and Osinsky 2024, docs/schemes.md)", {},
       {"majorant", "pairs", "lowrank"}},
      {"n_particles", &Dsmc::n_particles, "", "simulated particles, split in proportion to n_k",
       Range{2, 2e9}},
      {"t_end", &Dsmc::t_end, "time", "end of the run (or give collisions_per_particle)",
       kPositive},
      {"collisions_per_particle", &Dsmc::collisions_per_particle, "",
       "end of the run in collisions per particle, 2 x events / N (or give t_end)", kPositive},
      {"replicas", &Dsmc::replicas, "", "independent realisations, averaged", Range{1, 1e6}},
      {"seed", &Dsmc::seed, "", "seed of all random streams", at_least(0)},
      {"step_fraction", &Dsmc::step_fraction, "",
       "time step (bound refresh) in units of the majorant mean free time", Range{0, 100, true}},
      {"block_size", &Dsmc::block_size, "",
       "particles per cache block (majorant or lowrank, up to 128 species, N >= 2 block_size; with "
       "&agg_frag, clusters per block while N >= 2 block_size); at least 64, or 0: none",
       Range{0, 2e9}},
      {"stage_step", &Dsmc::stage_step, "",
       "with &thermostat or &shear: length of one streaming/collision/thermostat stage in majorant mean free "
       "times (also at most 0.01/a)",
       Range{0, 1, true}},
      {"allow_long_run", &Dsmc::allow_long_run, "",
       ".true.: run even when kinetic theory estimates more than 1e12 collision events per replica, or a "
       "cooling below 1e-40 of the initial temperature (such runs are refused by default)"},
  };
  return fields;
}

const std::vector<Field<Thermostat>>& thermostat_fields() {
  static const std::vector<Field<Thermostat>> fields = {
      {"kind", &Thermostat::kind, "",
       "'none', or 'gaussian': rescale the velocities after each collision stage so that the inelastic loss "
       "is restored (homogeneous steady state, docs/shear-viscosity.md)",
       {}, {"none", "gaussian"}},
  };
  return fields;
}

const std::vector<Field<Shear>>& shear_fields() {
  static const std::vector<Field<Shear>> fields = {
      {"rate", &Shear::rate, "1/time",
       "a of the uniform shear flow u_x = a y (Lagrangian frame; V_x -> V_x - a V_y dt each stage)", at_least(0)},
      {"average_from", &Shear::average_from, "time",
       "the shear viscosity is averaged over the samples from this time on (default: t_end/2)", at_least(0)},
  };
  return fields;
}

const std::vector<Field<Output>>& output_fields() {
  static const std::vector<Field<Output>> fields = {
      {"file", &Output::file, "", "HDF5 (H5MD) output file"},
      {"author", &Output::author, "", "name in /h5md/author of the output file (default: $USER, else the login name)"},
      {"n_samples", &Output::n_samples, "",
       "sample times, t = 0 included (at most 1e5: every sample keeps every observable of every replica in memory)",
       Range{2, 1e5}},
      {"spacing", &Output::spacing, "", "'linear' or 'log' spacing of the sample times", {},
       {"linear", "log"}},
      {"first_sample", &Output::first_sample, "time (or collisions per particle)",
       "first sample after 0 with spacing = 'log' (default: end / 1000)", kPositive},
      {"histogram_bins", &Output::histogram_bins, "", "bins of the velocity histograms",
       Range{1, 1e5}},
      {"reduced_bins", &Output::reduced_bins, "",
       "bins of the reduced speed distributions Phi_i(v*) (Montanero and Garzo 2002, eq. (22), docs/sonine.md; one or two species)",
       Range{1, 1e5}},
      {"reduced_range", &Output::reduced_range, "v0", "Phi_i(v*) covers 0 <= v* < range", kPositive},
      {"scaling_start", &Output::scaling_start, "collisions per particle",
       "Phi_i, Delta_i, G_i are accumulated over the samples from here on (the HCS after its transient)",
       at_least(0)},
      {"checkpoint_every", &Output::checkpoint_every, "s (wall clock)",
       "write the full state to <file stem>.checkpoint.h5 this often; resume with --restart (unset: never)",
       kPositive},
      {"track_displacements", &Output::track_displacements, "",
       ".true.: track every particle's displacement and write the observable msd (Bodrova and Osinsky 2024, eq. (15), docs/diffusion-msd.md)"},
      {"msd_start_time", &Output::msd_start_time, "time",
       "displacements are measured from this time (default: from t = 0)", at_least(0)},
      {"msd_start_temperature", &Output::msd_start_temperature, "energy",
       "... or from the first sample at which the total temperature is at or below this value", kPositive},
      {"histogram_range", &Output::histogram_range, "sqrt(T_k/m_k)",
       "velocity histograms cover [-range, range] in thermal units", kPositive},
      {"sample_times", &Output::sample_times, "time (or collisions per particle)",
       "explicit sample points after 0, increasing; overrides n_samples and spacing (t = 0 is always "
       "sampled, and the end of the run too)",
       kPositive},
  };
  return fields;
}

const std::vector<Field<AggFrag>>& agg_frag_fields() {
  static const std::vector<Field<AggFrag>> fields = {
      {"aggregation_energy", &AggFrag::aggregation_energy, "energy",
       "E_agg: a colliding pair whose impact energy m_kj g^2/2 is below it sticks (docs/agg-frag.md)",
       at_least(0)},
      {"fragmentation_energy", &AggFrag::fragmentation_energy, "energy",
       "E_frag: a pair (not two monomers) whose normal energy m_kj (g.e)^2/2 is above it shatters into "
       "monomers (unset: never)",
       at_least(0)},
      {"fragment_restitution", &AggFrag::fragment_restitution, "",
       "eps_f: the fragments carry eps_f^2 of the impact energy in the centre-of-mass frame (required with "
       "fragmentation_energy)",
       kUnit},
  };
  return fields;
}

const std::vector<Field<Sweep>>& sweep_fields() {
  static const std::vector<Field<Sweep>> fields = {
      {"variable", &Sweep::variable, "",
       "the swept variables as 'group:name' or an element 'group:name(i)', 'group:name(i,j)', e.g. "
       "'system:restitution(1,2)', 'system:mass(2)' (no sweep when unset)"},
      {"values", &Sweep::values, "",
       "their values point by point (one run and one output group per point), or one list per variable: "
       "values(1,v) = ..."},
      {"grid", &Sweep::grid, "",
       ".true.: every combination of the variables' lists (values(1,v) = ...), the last variable fastest"},
  };
  return fields;
}

// ---------------------------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------------------------
std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

const char* kind_name(namelist::Value::Kind kind) {
  switch (kind) {
    case namelist::Value::Kind::Integer: return "an integer";
    case namelist::Value::Kind::Real: return "a real number";
    case namelist::Value::Kind::Logical: return "a logical";
    case namelist::Value::Kind::String: return "a string";
  }
  return "a value";
}

/// Where each variable was last assigned, and the raw element assignments of pair matrices.
struct Provenance {
  std::string file;                             ///< the namelist file (for group-level errors)
  int group_line = 0;                           ///< line of '&group' (0 if absent)
  std::map<std::string, int> line;              ///< variable -> line of its last assignment
  std::map<std::string, std::string> set_in;    ///< variable -> file (or override) of that line
  /// Pair-matrix assignments in order, each with the file (or override) it came from.
  std::map<std::string, std::vector<std::pair<const namelist::Assignment*, std::string>>>
      pair_assignments;
  /// The file where `variable` was last set; the namelist file if it was not set.
  const std::string& file_of(const std::string& variable) const {
    const auto it = set_in.find(variable);
    return it == set_in.end() ? file : it->second;
  }
};

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
  const std::vector<std::string>& choices;
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
    if (v.kind != namelist::Value::Kind::Integer)
      throw r.error(v.line, name, "expected an integer, got " + std::string(kind_name(v.kind)) + " '" + v.text + "'");
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
  void operator()(std::string& out) const {
    const auto& v = one_value();
    if (v.kind != namelist::Value::Kind::String)
      throw r.error(v.line, name, "expected a quoted string, got " + std::string(kind_name(v.kind)) + " '" + v.text + "'");
    if (choices.empty()) {
      if (v.string.empty()) throw r.error(v.line, name, name + " must not be empty");
      out = v.string;
      return;
    }
    const std::string choice = lower(v.string);
    if (std::find(choices.begin(), choices.end(), choice) == choices.end()) {
      std::string list;
      for (const auto& c : choices) list += (list.empty() ? "'" : ", '") + c + "'";
      throw r.error(v.line, name, "'" + v.string + "' is not one of " + list);
    }
    out = choice;
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
  const Assigner assigner{field.name, field.range, field.choices, a, r, prov};
  std::visit([&](auto member) { assigner(target.*member); }, field.member);
  prov.line[field.name] = a.line;
  prov.set_in[field.name] = r.file;
}

/// The group a variable belongs to, if it belongs to another one (for "did you mean" hints).
std::string owning_group(const std::string& name) {
  auto has = [&](const auto& fields) {
    return std::any_of(fields.begin(), fields.end(), [&](const auto& f) { return f.name == name; });
  };
  if (has(system_fields())) return "system";
  if (has(initial_fields())) return "initial";
  if (has(dsmc_fields())) return "dsmc";
  if (has(output_fields())) return "output";
  if (has(agg_frag_fields())) return "agg_frag";
  if (has(thermostat_fields())) return "thermostat";
  if (has(shear_fields())) return "shear";
  if (has(sweep_fields())) return "sweep";
  return "";
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

// ---------------------------------------------------------------------------------------------
// Checking and deriving, group by group
// ---------------------------------------------------------------------------------------------
void resolve_restitution(System& sys, const Provenance& prov, const std::string& group) {
  const std::size_t s = static_cast<std::size_t>(sys.n_species);
  {  // one value for all pairs: a uniform matrix, stored densely only for a few species
    const auto& only = prov.pair_assignments.at("restitution");
    if (only.size() == 1 && only[0].first->index.empty() && only[0].first->values.size() == 1) {
      sys.restitution = species::PairMatrix::uniform(s, only[0].first->values[0].real);
      if (s <= species::dense_pair_limit) sys.restitution.densify();
      return;
    }
  }
  species::PairMatrix m(s, std::numeric_limits<double>::quiet_NaN());
  const auto& list = prov.pair_assignments.at("restitution");
  // (i <= j) -> value and line of its element assignment in the current source (the namelist, or
  // one --set): within one source (i,j) and (j,i) must agree; a later --set may replace the value.
  std::map<std::pair<std::size_t, std::size_t>, std::pair<double, int>> element_values;
  std::string element_source;
  for (const auto& [a, file] : list) {
    if (a->index.empty()) {
      if (a->values.size() == 1) {
        std::fill(m.values.begin(), m.values.end(), a->values[0].real);
      } else if (a->values.size() == s * s) {
        for (std::size_t c = 0; c < s * s; ++c) m(c % s, c / s) = a->values[c].real;  // column-major
        for (std::size_t i = 0; i < s; ++i)  // alpha_ij = alpha_ji: one event, whichever is "first"
          for (std::size_t j = i + 1; j < s; ++j)
            if (m(i, j) != m(j, i))
              throw Error(file, a->line, group, "restitution",
                          "the matrix is not symmetric: restitution(" + std::to_string(i + 1) + "," +
                              std::to_string(j + 1) + ") = " + a->values[i + j * s].text +
                              " but restitution(" + std::to_string(j + 1) + "," +
                              std::to_string(i + 1) + ") = " + a->values[j + i * s].text);
      } else {
        throw Error(file, a->line, group, "restitution",
                    "expected 1 or n_species^2 = " + std::to_string(s * s) + " values, got " +
                        std::to_string(a->values.size()));
      }
      continue;
    }
    std::size_t i = static_cast<std::size_t>(a->index[0] - 1);
    std::size_t j = static_cast<std::size_t>(a->index[1] - 1);
    if (file != element_source) {
      element_values.clear();
      element_source = file;
    }
    for (const auto& v : a->values) {  // consecutive elements in column-major order
      if (i >= s || j >= s)
        throw Error(file, v.line, group, "restitution",
                    "element (" + std::to_string(i + 1) + "," + std::to_string(j + 1) +
                        ") is outside the " + std::to_string(s) + " x " + std::to_string(s) +
                        " matrix");
      // alpha_ij = alpha_ji is one pair's value: (i,j) and (j,i) given differently is a conflict.
      const auto key = std::make_pair(std::min(i, j), std::max(i, j));
      if (const auto it = element_values.find(key); it != element_values.end() && it->second.first != v.real)
        throw Error(file, v.line, group, "restitution",
                    "restitution(" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ") = " + v.text +
                        " conflicts with line " + std::to_string(it->second.second) + ": the matrix is symmetric, "
                        "alpha_ij = alpha_ji");
      element_values[key] = {v.real, v.line};
      m(i, j) = v.real;
      m(j, i) = v.real;
      if (++i == s) {
        i = 0;
        ++j;
      }
    }
  }
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j)
      if (std::isnan(m(i, j)))
        throw Error(prov.file_of("restitution"), prov.line.at("restitution"), group, "restitution",
                    "restitution(" + std::to_string(i + 1) + "," + std::to_string(j + 1) +
                        ") is not given");
  sys.restitution = m;
}

void check_species_list(std::vector<double>& values, const std::string& name, const std::string& law,
                        std::size_t s, const Provenance& prov, const std::string& group) {
  const int line = prov.line.count(name) ? prov.line.at(name) : 0;
  const std::size_t expected = law == "list" ? s : 1;
  if (values.size() != expected)
    throw Error(prov.file_of(name), line, group, name,
                "expected " + std::to_string(expected) + " value(s) (" +
                    (law == "list" ? "n_species = " + std::to_string(s)
                                   : "species 1 only, with the law '" + law + "'") +
                    "), got " + std::to_string(values.size()));
  for (std::size_t k = 0; k < values.size(); ++k)
    if (std::isnan(values[k]))
      throw Error(prov.file_of(name), line, group, name,
                  name + "(" + std::to_string(k + 1) + ") is not given");
}

void check_system(System& sys, const Provenance& prov) {
  const std::string group = "system";
  const auto s = static_cast<std::size_t>(sys.n_species);
  if (sys.restitution_model == "viscoelastic") {
    if (!sys.visco_a_kappa)
      throw Error(prov.file_of("restitution_model"), prov.line.at("restitution_model"), group, "visco_a_kappa",
                  "required with restitution_model = 'viscoelastic'");
    if (prov.line.count("restitution"))
      throw Error(prov.file_of("restitution"), prov.line.at("restitution"), group, "restitution",
                  "not used with restitution_model = 'viscoelastic' (alpha follows from visco_a_kappa)");
  } else {
    if (!prov.line.count("restitution"))
      throw Error(prov.file, prov.group_line, group, "restitution", "required variable is missing");
    if (prov.line.count("visco_a_kappa"))
      throw Error(prov.file_of("visco_a_kappa"), prov.line.at("visco_a_kappa"), group, "visco_a_kappa",
                  "only used with restitution_model = 'viscoelastic'");
  }
  check_species_list(sys.mass, "mass", sys.mass_law, s, prov, group);
  check_species_list(sys.diameter, "diameter", sys.diameter_law, s, prov, group);
  check_species_list(sys.number_density, "number_density", sys.density_law, s, prov, group);
  // The default value is accepted, so that the --print-defaults template reads back.
  if (sys.density_law != "power" && prov.line.count("density_exponent") &&
      sys.density_exponent != System{}.density_exponent)
    throw Error(prov.file_of("density_exponent"), prov.line.at("density_exponent"), group,
                "density_exponent",
                "only used with density_law = 'power'");
  // derive: the species laws (Bodrova and Osinsky 2024, sec. II, \ref sch_lowrank "docs/schemes.md": m_k = k m_1, sigma_k = k^(1/3) sigma_1, n_k = n_1 k^-theta)
  for (std::size_t k = 2; k <= s; ++k) {
    const double kk = static_cast<double>(k);
    if (sys.mass_law == "linear") sys.mass.push_back(kk * sys.mass[0]);
    if (sys.diameter_law == "cube_root") sys.diameter.push_back(std::cbrt(kk) * sys.diameter[0]);
    if (sys.density_law == "power")
      sys.number_density.push_back(sys.number_density[0] * std::pow(kk, -sys.density_exponent));
  }
  if (sys.restitution_model == "constant") resolve_restitution(sys, prov, group);
  else {  // placeholder: alpha comes from the impact speed
    sys.restitution = species::PairMatrix::uniform(s, 1.0);
    if (s <= species::dense_pair_limit) sys.restitution.densify();
  }
  if (sys.enskog) {
    double phi = 0.0;
    for (std::size_t k = 0; k < s; ++k) phi += sys.number_density[k] * std::pow(sys.diameter[k], 3);
    phi *= std::acos(-1.0) / 6.0;
    if (phi >= 0.5)
      throw Error(prov.file_of("number_density"),
                  prov.line.count("number_density") ? prov.line.at("number_density") : 0,
                  group, "number_density",
                  "packing fraction " + std::to_string(phi) +
                      " is beyond the Carnahan-Starling fluid range (phi < 0.5)");
  }
}

void check_initial(Initial& ini, std::size_t s, const Provenance& prov) {
  const int line = prov.line.count("temperature") ? prov.line.at("temperature") : 0;
  for (std::size_t k = 0; k < ini.temperature.size(); ++k)
    if (std::isnan(ini.temperature[k]))
      throw Error(prov.file_of("temperature"), line, "initial", "temperature",
                  "temperature(" + std::to_string(k + 1) + ") is not given");
  if (ini.temperature.size() == 1 && s > 1) ini.temperature.assign(s, ini.temperature[0]);
  if (ini.temperature.size() != s)
    throw Error(prov.file_of("temperature"), line, "initial", "temperature",
                "expected 1 or n_species = " + std::to_string(s) + " values, got " +
                    std::to_string(ini.temperature.size()));
}

void check_dsmc(const Dsmc& d, const species::Mixture& mix, const Provenance& prov, int group_line) {
  const std::string group = "dsmc";
  if (d.t_end.has_value() == d.collisions_per_particle.has_value())
    throw Error(d.t_end ? prov.file_of("collisions_per_particle") : prov.file,
                d.t_end ? prov.line.at("collisions_per_particle") : group_line, group,
                d.t_end ? "collisions_per_particle" : "t_end",
                "give exactly one of t_end and collisions_per_particle");
  // The event targets are integers: 2 x events / N = collisions_per_particle must stay far inside
  // 64 bits (1e30 would wrap round to a run of no collisions and a file of zeros).
  if (d.collisions_per_particle && *d.collisions_per_particle * static_cast<double>(d.n_particles) / 2.0 > 1e18)
    throw Error(prov.file_of("collisions_per_particle"), prov.line.at("collisions_per_particle"), group,
                "collisions_per_particle",
                "collisions_per_particle x n_particles / 2 = " +
                    std::to_string(*d.collisions_per_particle * static_cast<double>(d.n_particles) / 2.0) +
                    " collision events: beyond 1e18, far more than any run can do");
  // 'majorant' and 'pairs' recompute their bounds over all S^2 species pairs at every time step
  // (collide.cpp rebuild_bounds), which has about N/2 candidates: with thousands of species the
  // rebuilds are the whole run (3000 species: minutes per collision per particle). 'lowrank' updates
  // its rank-3 majorant in O(S log S) (collide.hpp).
  constexpr std::size_t kMaxPairSchemeSpecies = 256;
  if (d.scheme != "lowrank" && mix.size() > kMaxPairSchemeSpecies)
    throw Error(prov.file_of("scheme"), prov.line.count("scheme") ? prov.line.at("scheme") : group_line, group,
                "scheme",
                "scheme = '" + d.scheme + "' recomputes its bounds over all n_species^2 = " +
                    std::to_string(mix.size() * mix.size()) +
                    " species pairs at every time step: with more than 256 species use scheme = 'lowrank' "
                    "(O(S log S), Bodrova and Osinsky 2024, docs/schemes.md)");
  // A block is a gas of its own for a step: it needs partners (and a block of a few particles gains
  // nothing from the cache); 64 is the mixtures' smallest slice (collide.hpp, "Mixtures in blocks").
  if (d.block_size > 0 && d.block_size < 64)
    throw Error(prov.file_of("block_size"), prov.line.count("block_size") ? prov.line.at("block_size") : group_line,
                group, "block_size",
                "a cache block needs at least 64 particles (got " + std::to_string(d.block_size) +
                    "); 0 turns the blocks off");
  const auto counts = species::particle_counts(static_cast<std::size_t>(d.n_particles), mix);
  for (std::size_t k = 0; k < counts.size(); ++k)
    if (counts[k] < 2)
      throw Error(prov.file_of("n_particles"),
                  prov.line.count("n_particles") ? prov.line.at("n_particles") : group_line,
                  group, "n_particles",
                  "n_particles = " + std::to_string(d.n_particles) + " gives " +
                      std::to_string(counts[k]) + " particle(s) of species " + std::to_string(k + 1) +
                      "; at least 2 per species are needed");
}

void check_output(Output& out, const Dsmc& d, const Provenance& prov) {
  for (const char* v : {"msd_start_time", "msd_start_temperature"})
    if (prov.line.count(v) && !out.track_displacements)
      throw Error(prov.file, prov.line.at(v), "output", v, "only used with track_displacements = .true.");
  if (out.msd_start_time && out.msd_start_temperature)
    throw Error(prov.file, prov.line.at("msd_start_temperature"), "output", "msd_start_temperature",
                "give at most one of msd_start_time and msd_start_temperature");
  if (out.msd_start_time && d.t_end && *out.msd_start_time >= *d.t_end)
    throw Error(prov.file, prov.line.at("msd_start_time"), "output", "msd_start_time",
                "msd_start_time must be below t_end");
  const double end = d.t_end ? *d.t_end : *d.collisions_per_particle;
  if (!out.sample_times.empty()) {
    const std::string file = prov.file_of("sample_times");
    const int line = prov.line.at("sample_times");
    for (const char* v : {"n_samples", "spacing", "first_sample"})
      if (prov.line.count(v))
        throw Error(prov.file_of(v), prov.line.at(v), "output", v,
                    "not used with sample_times (the explicit list sets every sample point)");
    for (std::size_t k = 0; k < out.sample_times.size(); ++k) {
      if (std::isnan(out.sample_times[k]))
        throw Error(file, line, "output", "sample_times", "sample_times(" + std::to_string(k + 1) + ") is not given");
      if (k > 0 && !(out.sample_times[k] > out.sample_times[k - 1]))
        throw Error(file, line, "output", "sample_times",
                    "sample_times must increase: element " + std::to_string(k + 1) + " is not above element " +
                        std::to_string(k));
    }
    if (out.sample_times.back() > end)
      throw Error(file, line, "output", "sample_times",
                  "the last sample point is beyond the end of the run (" + std::to_string(end) + ")");
    return;
  }
  if (out.spacing == "log") {
    if (!out.first_sample) out.first_sample = end / 1000.0;  // derive
    if (*out.first_sample >= end)
      throw Error(prov.file_of("first_sample"), prov.line.at("first_sample"), "output", "first_sample",
                  "first_sample must be below the end of the run (" + std::to_string(end) + ")");
  } else if (prov.line.count("first_sample")) {
    throw Error(prov.file_of("first_sample"), prov.line.at("first_sample"), "output", "first_sample",
                "only used with spacing = 'log'");
  }
}

/// &agg_frag (\ref af_outcome "docs/agg-frag.md"): the run starts from monomers of one constant-restitution, dilute
/// species, and the model runs in dsmc/agg_frag.hpp's own loop; every combination it cannot run is
/// refused here, naming the variable that asks for it.
void check_agg_frag(const Config& c, std::map<std::string, Provenance>& prov) {
  const std::string group = "agg_frag";
  Provenance& p = prov[group];
  const AggFrag& a = c.agg_frag;
  const auto where = [&](const std::string& g, const char* v) {
    const Provenance& q = prov[g];
    return std::make_pair(q.file_of(v), q.line.count(v) ? q.line.at(v) : q.group_line);
  };
  const auto refuse = [&](const std::string& g, const char* v, const std::string& message) {
    const auto [file, line] = where(g, v);
    throw Error(file, line, g, v, message);
  };
  if (!a.aggregation_energy && !a.fragmentation_energy)
    throw Error(p.file, p.group_line, group, "aggregation_energy",
                "&agg_frag needs aggregation_energy, fragmentation_energy or both");
  if (a.fragmentation_energy && !a.fragment_restitution)
    throw Error(p.file_of("fragmentation_energy"), p.line.at("fragmentation_energy"), group, "fragment_restitution",
                "required with fragmentation_energy");
  if (!a.fragmentation_energy && a.fragment_restitution)
    refuse(group, "fragment_restitution", "only used with fragmentation_energy");
  if (c.system.n_species != 1)
    refuse("system", "n_species",
           "&agg_frag starts from monomers: n_species must be 1 (cluster sizes become the species)");
  if (c.system.restitution_model != "constant")
    refuse("system", "restitution_model", "&agg_frag runs with restitution_model = 'constant' only");
  if (c.system.enskog) refuse("system", "enskog", "&agg_frag runs in the dilute gas only (enskog = .false.)");
  if (c.dsmc.scheme != "lowrank")
    refuse("dsmc", "scheme",
           "&agg_frag runs with scheme = 'lowrank' only (cluster sizes as species, Bodrova and Osinsky 2024, docs/schemes.md); set scheme = "
           "'lowrank'");
  if (c.output.track_displacements)
    refuse("output", "track_displacements", "displacements are not tracked with &agg_frag");
}

/// &thermostat and &shear (\ref eta_thermostat "docs/shear-viscosity.md"): what the staged loop of simulation.cpp can run, and a shear
/// rate that keeps the finite-shear correction small. Refusals name the variable that asks for the
/// combination.
void check_staged(const Config& c, std::map<std::string, Provenance>& prov) {
  const auto refuse = [&](const std::string& g, const char* v, const std::string& message) {
    const Provenance& q = prov[g];
    throw Error(q.file_of(v), q.line.count(v) ? q.line.at(v) : q.group_line, g, v, message);
  };
  if (!c.staged()) {
    if (prov["shear"].line.count("average_from"))
      refuse("shear", "average_from", "only used with a shear rate");
    return;
  }
  const std::string what = c.shear.rate ? "&shear" : "&thermostat";
  if (c.has_agg_frag)
    refuse(c.shear.rate ? "shear" : "thermostat", c.shear.rate ? "rate" : "kind",
           what + " cannot run with &agg_frag (the thermostat would feed the clusters' energy back)");
  if (c.system.enskog && c.shear.rate && c.dsmc.scheme != "pairs")
    refuse("dsmc", "scheme",
           "shear flow in the Enskog gas runs with scheme = 'pairs' only: its relative velocity "
           "g - a sigma e_y x depends on the direction e, which 'majorant' and 'lowrank' draw from g "
           "(docs/physics.md, shear flow)");
  if (c.system.restitution_model != "constant")
    refuse("system", "restitution_model", what + " runs with restitution_model = 'constant' only");
  if (c.dsmc.scheme == "lowrank" && c.system.n_species > 64)
    refuse("dsmc", "scheme", what + " runs with at most 64 species");
  if (!c.dsmc.t_end)
    refuse("dsmc", "collisions_per_particle", what + " runs are driven by t_end (stages end at times)");
  if (c.output.track_displacements)
    refuse("output", "track_displacements", "displacements are not tracked with " + what);
  if (c.shear.rate) {
    // a* = a / nu_0(T_0) with nu_0 = n T / eta_0, eta_0 = (5/(16 sigma^2)) sqrt(m T/pi) (\ref eta_thermostat "docs/shear-viscosity.md"),
    // species 1's size and mass for a mixture. Above a* = 1 at T_0 the start is far from the
    // Navier-Stokes regime the viscosity protocol measures.
    const double m = c.system.mass[0], sigma = c.system.diameter[0], t0 = c.initial.temperature[0];
    double n = 0.0;
    for (double x : c.system.number_density) n += x;
    const double eta0 = 5.0 / (16.0 * sigma * sigma) * std::sqrt(m * t0 / std::acos(-1.0));
    const double reduced = *c.shear.rate * eta0 / (n * t0);
    if (reduced > 1.0)
      refuse("shear", "rate",
             "a* = a/nu_0(T_0) = " + std::to_string(reduced) +
                 " > 1: far from the Navier-Stokes regime; lower rate or raise T_0 (a* <= 0.1 for the viscosity)");
    if (*c.shear.rate == 0.0) refuse("shear", "rate", "rate = 0: leave &shear out for no shear");
    if (c.shear.average_from && *c.shear.average_from >= *c.dsmc.t_end)
      refuse("shear", "average_from", "average_from must be below t_end");
  } else if (prov["shear"].line.count("average_from")) {
    refuse("shear", "average_from", "only used with a shear rate");
  }
}

std::vector<double> spaced(const Output& out, double end) {
  if (!out.sample_times.empty()) {  // 0, the list, and the end of the run
    std::vector<double> t{0.0};
    t.insert(t.end(), out.sample_times.begin(), out.sample_times.end());
    if (t.back() < end) t.push_back(end);
    return t;
  }
  const auto n = static_cast<std::size_t>(out.n_samples);
  std::vector<double> t(n, 0.0);
  if (out.spacing == "linear") {
    for (std::size_t i = 1; i < n; ++i) t[i] = end * static_cast<double>(i) / static_cast<double>(n - 1);
  } else {
    const double first = *out.first_sample;
    for (std::size_t i = 1; i < n; ++i)
      t[i] = n == 2 ? end
                    : first * std::pow(end / first, static_cast<double>(i - 1) / static_cast<double>(n - 2));
  }
  t.back() = end;
  return t;
}

// ---------------------------------------------------------------------------------------------
// Writing: resolved values, template, reference
// ---------------------------------------------------------------------------------------------
template <class G>
void append_resolved(std::vector<h5md::Parameter>& out, const std::string& group, const G& target,
                     const std::vector<Field<G>>& fields) {
  for (const auto& f : fields)
    std::visit(
        [&](auto member) {
          using T = std::remove_cv_t<std::remove_reference_t<decltype(target.*member)>>;
          const auto& v = target.*member;
          if constexpr (std::is_same_v<T, std::optional<double>>) {
            if (v) out.push_back({group, f.name, *v});
          } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
            // &sweep variable: one name is a string attribute, as before several could be swept.
            if (v.size() == 1) out.push_back({group, f.name, v.front()});
            else out.push_back({group, f.name, v});
          } else if constexpr (std::is_same_v<T, SweepValues>) {
            // The points run, point after point (also for lists and grids): the value texts.
            if constexpr (std::is_same_v<G, Sweep>) {
              std::vector<std::string> flat;
              for (const auto& row : target.table()) flat.insert(flat.end(), row.begin(), row.end());
              out.push_back({group, f.name, flat});
            }
          } else if constexpr (std::is_same_v<T, species::PairMatrix>) {
            // A uniform matrix of very many species (not stored densely) is written as its value.
            out.push_back({group, f.name, v.is_dense() ? v.values : std::vector<double>{v(0, 0)}});
          } else {
            out.push_back({group, f.name, v});
          }
        },
        f.member);
}

template <class G>
std::string default_text(const G& defaults, const Field<G>& f) {
  std::ostringstream s;
  s.precision(10);
  std::visit(
      [&](auto member) {
        using T = std::remove_cv_t<std::remove_reference_t<decltype(defaults.*member)>>;
        const auto& v = defaults.*member;
        if constexpr (std::is_same_v<T, long long> || std::is_same_v<T, double>) s << v;
        else if constexpr (std::is_same_v<T, bool>) s << (v ? ".true." : ".false.");
        else if constexpr (std::is_same_v<T, std::string>) {
          if (!v.empty()) s << "'" << v << "'";  // empty: unset, shown commented out
        }
        else if constexpr (std::is_same_v<T, std::vector<double>> ||
                           std::is_same_v<T, std::vector<std::string>>) {
          for (std::size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
        }
      },
      f.member);
  return s.str();
}

template <class G>
void template_group(std::ostringstream& s, const std::string& group, const std::vector<Field<G>>& fields,
                    const std::map<std::string, std::string>& examples) {
  const G defaults{};
  s << "&" << group << "\n";
  for (const auto& f : fields) {
    std::string value = default_text(defaults, f);
    std::string prefix = "  ";
    std::string note;
    if (f.required) {
      value = examples.count(f.name) ? examples.at(f.name) : "...";
      // A help that already says when the variable is required (restitution: "required when
      // constant") is not followed by a second, unconditional "(required)".
      if (f.help.find("required") == std::string::npos) note = " (required)";
    } else if (value.empty()) {
      prefix = "! ";
      value = examples.count(f.name) ? examples.at(f.name) : "...";
      note = " (not set by default)";
    }
    std::string line = prefix + f.name + " = " + value;
    if (line.size() < 36) line.resize(36, ' ');
    s << line << " ! " << f.help << (f.units.empty() ? "" : " [" + f.units + "]") << note << "\n";
  }
  s << "/\n\n";
}

template <class G>
void reference_group(std::ostringstream& s, const std::string& group, const std::vector<Field<G>>& fields) {
  const G defaults{};
  s << "### &" << group << "\n\n| variable | default | allowed | units | meaning |\n|---|---|---|---|---|\n";
  for (const auto& f : fields) {
    std::string allowed;
    if (!f.choices.empty())
      for (const auto& c : f.choices) allowed += (allowed.empty() ? "'" : ", '") + c + "'";
    else if (std::isfinite(f.range.lo) || std::isfinite(f.range.hi))
      allowed = f.range.text();
    std::string def = f.required ? "(required)" : default_text(defaults, f);
    if (def.empty()) def = "(unset)";
    s << "| `" << f.name << "` | " << def << " | " << allowed << " | " << f.units << " | " << f.help
      << " |\n";
  }
  s << "\n";
}

Config read_point(const namelist::Document& document, const std::vector<std::string>& overrides,
                  bool expand_sweep, const RunCheck& run_check);

/// Whether `group:name` is a string variable (a quoted sweep value of any other variable is
/// inserted without its quotes, so that an array can be swept: values = '0.01, 0.02', ...).
template <class G>
bool is_string_field(const std::vector<Field<G>>& fields, const std::string& name) {
  for (const auto& f : fields)
    if (f.name == name) return std::holds_alternative<std::string G::*>(f.member);
  return false;
}

bool is_string_variable(const std::string& group, const std::string& name) {
  if (group == "system") return is_string_field(system_fields(), name);
  if (group == "initial") return is_string_field(initial_fields(), name);
  if (group == "dsmc") return is_string_field(dsmc_fields(), name);
  if (group == "output") return is_string_field(output_fields(), name);
  if (group == "agg_frag") return is_string_field(agg_frag_fields(), name);
  if (group == "thermostat") return is_string_field(thermostat_fields(), name);
  if (group == "shear") return is_string_field(shear_fields(), name);
  return false;
}

/// The override that sets sweep point `value` of `variable` ("group:name", or "group:name(i,j)"
/// for an element).
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

/// A &sweep variable as written, "group:name" or "group:name(i[,j])": its parts (lower-cased,
/// blanks removed); ok = false when it has not that form.
struct SweepTarget {
  std::string group, name;
  std::vector<long long> index;
  bool ok = false;
};

SweepTarget parse_target(const std::string& written) {
  SweepTarget t;
  std::string text;
  for (char ch : written)
    if (ch != ' ') text += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
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

/// Rank of variable `name` of `group`: 0 scalar, 1 list, 2 pair matrix; -1 unknown.
template <class G>
int field_rank(const std::vector<Field<G>>& fields, const std::string& name) {
  for (const auto& f : fields)
    if (f.name == name)
      return std::holds_alternative<std::vector<double> G::*>(f.member)   ? 1
             : std::holds_alternative<species::PairMatrix G::*>(f.member) ? 2
                                                                          : 0;
  return -1;
}

int variable_rank(const std::string& group, const std::string& name) {
  if (group == "system") return field_rank(system_fields(), name);
  if (group == "initial") return field_rank(initial_fields(), name);
  if (group == "dsmc") return field_rank(dsmc_fields(), name);
  if (group == "output") return field_rank(output_fields(), name);
  if (group == "agg_frag") return field_rank(agg_frag_fields(), name);
  if (group == "thermostat") return field_rank(thermostat_fields(), name);
  if (group == "shear") return field_rank(shear_fields(), name);
  return -1;
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
                                name == "restitution")) ||
         (group == "initial" && name == "temperature");
}

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
    if (!t.ok || t.group == "sweep" || owning_group(t.name) != t.group)
      throw Error(prov.file_of("variable"), line_of("variable"), group, "variable",
                  "'" + written + "' is not 'group:name' (or 'group:name(i)', 'group:name(i,j)') of a variable of "
                  "&system, &initial, &dsmc, &output, &agg_frag, &thermostat or &shear");
    for (std::size_t w = 0; w < v; ++w)
      if (parse_target(sweep.variable[w]).group == t.group && parse_target(sweep.variable[w]).name == t.name &&
          parse_target(sweep.variable[w]).index == t.index)
        throw Error(prov.file_of("variable"), line_of("variable"), group, "variable", "'" + written + "' is swept twice");
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

namelist::Document parse_override(const std::string& text) {
  const auto colon = text.find(':');
  const auto equal = text.find('=');
  if (colon == std::string::npos || equal == std::string::npos || colon > equal)
    throw Error("--set", 0, "", "", "'" + text + "' is not of the form group:variable=value");
  const std::string group = text.substr(0, colon);
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

std::optional<species::PairMatrix> Config::viscoelastic_beta() const {
  if (system.restitution_model != "viscoelastic") return std::nullopt;
  return restitution::one_material_beta(mixture(), *system.visco_a_kappa);
}

species::Mixture Config::mixture() const {
  return species::make_mixture(system.mass, system.diameter, system.number_density,
                               system.restitution, system.enskog);
}

std::vector<double> Config::sample_times() const {
  return dsmc.t_end ? spaced(output, *dsmc.t_end) : std::vector<double>{};
}

std::vector<double> Config::sample_collisions() const {
  return dsmc.collisions_per_particle ? spaced(output, *dsmc.collisions_per_particle)
                                      : std::vector<double>{};
}

std::vector<h5md::Parameter> Config::resolved() const {
  std::vector<h5md::Parameter> out;
  append_resolved(out, "system", system, system_fields());
  append_resolved(out, "initial", initial, initial_fields());
  append_resolved(out, "dsmc", dsmc, dsmc_fields());
  append_resolved(out, "output", output, output_fields());
  if (has_agg_frag) append_resolved(out, "agg_frag", agg_frag, agg_frag_fields());
  if (staged()) {
    append_resolved(out, "thermostat", thermostat, thermostat_fields());
    append_resolved(out, "shear", shear, shear_fields());
  }
  if (is_sweep()) append_resolved(out, "sweep", sweep, sweep_fields());
  return out;
}

namespace {
Config read_point(const namelist::Document& document, const std::vector<std::string>& overrides,
                  bool expand_sweep, const RunCheck& run_check);
}

Config read(const namelist::Document& document, const std::vector<std::string>& overrides, const RunCheck& run_check) {
  return read_point(document, overrides, true, run_check);
}

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

std::string Sweep::row_label(const std::vector<std::string>& row) const { return config::row_label(*this, row); }

std::string author_name(const Output& output) {
  if (!output.author.empty()) return output.author;
  const char* user = std::getenv("USER");
  if (user && *user) return user;
  if (const passwd* entry = ::getpwuid(::getuid()); entry && entry->pw_name && *entry->pw_name)
    return entry->pw_name;  // no $USER (cron, containers): the login name of the user id
  return "unknown";
}

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

namespace {
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

  for (const auto& [group, p] : prov)
    for (const auto& [variable, line] : p.line)
      c.origin[group + ":" + variable] = {p.file_of(variable), line};
  // restitution is required by the constant model only (the viscoelastic one derives alpha).
  check_required(system_fields(), prov["system"], document.file, "system", document.find("system")->line,
                 c.system.restitution_model == "viscoelastic" ? "restitution" : "");
  prov["system"].group_line = document.find("system")->line;
  check_system(c.system, prov["system"]);
  check_initial(c.initial, static_cast<std::size_t>(c.system.n_species), prov["initial"]);
  check_dsmc(c.dsmc, c.mixture(), prov["dsmc"], document.find("dsmc")->line);
  check_output(c.output, c.dsmc, prov["output"]);
  if (c.has_agg_frag) check_agg_frag(c, prov);
  check_staged(c, prov);
  if (run_check) run_check(c);
  if (expand_sweep && !prov["sweep"].line.empty()) {
    check_sweep(c, prov["sweep"], document, overrides, run_check);
  }
  return c;
}
}  // namespace

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
  return read(namelist::parse(text, file), overrides);
}

std::string defaults_template() {
  std::ostringstream s;
  s << "! granular-dsmc input: every variable with its default (granular-dsmc --print-defaults).\n"
       "! Fortran namelist rules: case-insensitive names, '!' comments, 'a = 1.0, 2.0' arrays,\n"
       "! '3*1.0' repeats, .true./.false., quoted strings, a(2) = ... element assignment.\n\n";
  template_group(s, "system", system_fields(),
                 {{"mass", "1.0"}, {"diameter", "1.0"}, {"number_density", "0.01"}, {"restitution", "0.9"}});
  template_group(s, "initial", initial_fields(), {});
  template_group(s, "dsmc", dsmc_fields(), {{"t_end", "100.0"}, {"collisions_per_particle", "50.0"}});
  template_group(s, "output", output_fields(), {{"first_sample", "0.1"}, {"sample_times", "1.0, 2.0, 5.0"}});
  s << "! Aggregation and fragmentation: uncomment the group to switch it on (one species = the monomer,\n"
       "! scheme = 'lowrank').\n";
  {
    std::ostringstream g;
    template_group(g, "agg_frag", agg_frag_fields(),
                   {{"aggregation_energy", "0.5"}, {"fragmentation_energy", "1.5"}, {"fragment_restitution", "0.5"}});
    std::istringstream lines(g.str());
    for (std::string line; std::getline(lines, line);)
      s << (line.empty() || line.rfind("!", 0) == 0 ? line : "! " + line) << "\n";
  }
  template_group(s, "thermostat", thermostat_fields(), {});
  template_group(s, "shear", shear_fields(), {{"rate", "0.05"}, {"average_from", "50.0"}});
  template_group(s, "sweep", sweep_fields(),
                 {{"variable", "'system:restitution'"}, {"values", "0.5, 0.7, 0.9"}});
  return s.str();
}

std::string reference_markdown() {
  std::ostringstream s;
  reference_group(s, "system", system_fields());
  reference_group(s, "initial", initial_fields());
  reference_group(s, "dsmc", dsmc_fields());
  reference_group(s, "output", output_fields());
  reference_group(s, "agg_frag", agg_frag_fields());
  reference_group(s, "thermostat", thermostat_fields());
  reference_group(s, "shear", shear_fields());
  reference_group(s, "sweep", sweep_fields());
  return s.str();
}

}  // namespace gdsmc::io::config
