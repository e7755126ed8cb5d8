// Every kind of output against the H5MD 1.1 specification (issue 17 item 4).
//
// The checker below is written from the specification (https://www.nongnu.org/h5md/h5md.html, version
// 1.1.0, and its implementation notes https://www.nongnu.org/h5md/implementation.html), with the HDF5 C
// API alone: it shares no code with the writer (io/h5md.cpp). The rules it checks:
//  - an H5MD root (the file root, or any group: "the root level of the H5MD structure may coincide
//    with the root of the HDF5 file or be an arbitrary group") holds the mandatory group `h5md` with
//    attribute `version`: Integer[2] = {1, 1}; subgroup `author` with attribute `name`: String
//    (optional `email`: String); subgroup `creator` with attributes `name` and `version`: String;
//  - the `observables` group holds H5MD elements, possibly in subgroups: a dataset (time-independent
//    element), or a time-dependent group with `step` (Integer, [variable] or scalar), optional `time`
//    (Float, the shape of `step`) and `value` ([variable][...], its first dimension that of `step`
//    when step is not scalar); step and time in monotonically increasing order (implementation
//    notes, "Dataset index lookup"); a group with `time` but no `step` is malformed;
//  - beyond the core rules, the averaged-data convention of the H5MD discussion page: an `error`
//    dataset beside `value` has the dimensions of `value`;
//  - modules (H5MD 1.1, "Modules"): every subgroup of `h5md/modules` has `version`: Integer[2];
//  - the units module 1.0 (https://www.nongnu.org/h5md/modules/units.html): `h5md/modules/units` with
//    `version` = {1, 0} and `system`: a scalar variable-length String; an attribute `unit` (on `time`
//    and `value` of a time-dependent element, or on a time-independent element) is a scalar
//    variable-length String of the ASCII character set whose text is a sequence of unit factors
//    separated by a space, each a number (integer or decimal fraction) or a unit symbol, optionally
//    followed by a signed non-zero integer power, at most one number and only as the first factor,
//    no symbol twice.
// And the project's own rules on top (\ref output_units "docs/output.md"): the
// units module is declared; with a system other than "SI" the module group lists its symbols
// (`symbols`), and every unit uses only those; every `time`, `value`, `error` and time-independent
// dataset of `observables` has a unit, `time` the unit "time", `error` that of `value`; `step` none.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <regex>
#include <sstream>
#include <tuple>
#include <string>
#include <vector>

#include "run/simulation.hpp"
#include "io/config.hpp"
#include "io/namelist.hpp"
#include "scratch_dir.hpp"

namespace fs = std::filesystem;

namespace {

/// Collects violations of the H5MD rules in one file.
class H5mdChecker {
 public:
  explicit H5mdChecker(const std::string& path) : path_(path) {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_ < 0) fail("/", "cannot open the file as HDF5");
  }
  ~H5mdChecker() {
    if (file_ >= 0) H5Fclose(file_);
  }
  const std::vector<std::string>& problems() const { return problems_; }
  std::size_t elements() const { return elements_; }

  /// Checks the H5MD root at `root` ("/" or a group) and its observables.
  void check_root(const std::string& root) {
    if (file_ < 0) return;
    const std::string base = root == "/" ? "" : root;
    const std::string h5md = base + "/h5md";
    if (!is_group(h5md)) {
      fail(h5md, "the mandatory h5md group is missing");
      return;
    }
    // version: Integer[2] = {1, 1}
    if (!H5Aexists_by_name(file_, h5md.c_str(), "version", H5P_DEFAULT)) {
      fail(h5md, "attribute version is missing");
    } else {
      const hid_t a = H5Aopen_by_name(file_, h5md.c_str(), "version", H5P_DEFAULT, H5P_DEFAULT);
      const hid_t t = H5Aget_type(a), s = H5Aget_space(a);
      hsize_t dims[4] = {0};
      const int rank = H5Sget_simple_extent_ndims(s);
      H5Sget_simple_extent_dims(s, dims, nullptr);
      if (H5Tget_class(t) != H5T_INTEGER) fail(h5md, "version is not of class Integer");
      if (rank != 1 || dims[0] != 2) fail(h5md, "version is not of shape [2]");
      if (H5Tget_class(t) == H5T_INTEGER && rank == 1 && dims[0] == 2) {
        int v[2] = {0, 0};
        H5Aread(a, H5T_NATIVE_INT, v);
        if (v[0] != 1 || v[1] != 1) fail(h5md, "version is not {1, 1}");
      }
      H5Tclose(t);
      H5Sclose(s);
      H5Aclose(a);
    }
    for (const char* group : {"author", "creator"}) {
      const std::string g = h5md + "/" + group;
      if (!is_group(g)) {
        fail(g, "mandatory group missing");
        continue;
      }
      check_string_attribute(g, "name", true);
      if (std::string(group) == "creator") check_string_attribute(g, "version", true);
      if (std::string(group) == "author") check_string_attribute(g, "email", false);
    }
    check_modules(h5md);
    const std::string observables = base + "/observables";
    if (is_group(observables)) walk_observables(observables);
  }

  /// The unit string grammar of the units module, written here from its text (not the writer's).
  static bool unit_grammar(const std::string& unit) {
    static const std::regex factor_form("^(([0-9]+(\\.[0-9]+)?)|([A-Za-z]+))([+-][1-9][0-9]*)?$");
    if (unit.empty() || unit.front() == ' ' || unit.back() == ' ' || unit.find("  ") != std::string::npos)
      return false;
    std::istringstream in(unit);
    std::string factor;
    std::vector<std::string> seen;
    for (std::size_t index = 0; in >> factor; ++index) {
      std::smatch m;
      if (!std::regex_match(factor, m, factor_form)) return false;
      if (m[2].matched && index != 0) return false;  // a number only as the first factor
      if (m[4].matched) {
        if (std::find(seen.begin(), seen.end(), m[4].str()) != seen.end()) return false;
        seen.push_back(m[4].str());
      }
    }
    return true;
  }

  /// Checks a `unit` attribute of `dataset` if it has one; `required`: its absence is a problem.
  /// Returns the unit text ("" if absent or unreadable).
  std::string check_unit(const std::string& dataset, bool required) {
    if (!H5Aexists_by_name(file_, dataset.c_str(), "unit", H5P_DEFAULT)) {
      if (required) fail(dataset, "attribute unit is missing");
      return "";
    }
    const hid_t a = H5Aopen_by_name(file_, dataset.c_str(), "unit", H5P_DEFAULT, H5P_DEFAULT);
    const hid_t t = H5Aget_type(a), space = H5Aget_space(a);
    std::string text;
    if (H5Sget_simple_extent_type(space) != H5S_SCALAR) fail(dataset, "unit is not of scalar dataspace");
    if (H5Tget_class(t) != H5T_STRING) {
      fail(dataset, "unit is not of class String");
    } else if (H5Tis_variable_str(t) <= 0) {
      fail(dataset, "unit is not a variable-length string");
    } else {
      if (H5Tget_cset(t) != H5T_CSET_ASCII) fail(dataset, "unit is not of the ASCII character set");
      char* value = nullptr;
      const hid_t memory = H5Tget_native_type(t, H5T_DIR_ASCEND);
      if (H5Sget_simple_extent_type(space) == H5S_SCALAR && H5Aread(a, memory, &value) >= 0 && value) {
        text = value;
        H5free_memory(value);
      }
      H5Tclose(memory);
      if (!unit_grammar(text)) fail(dataset, "unit '" + text + "' is not a unit string");
      else if (system_ != "SI" && !symbols_.empty()) {
        std::istringstream in(text);
        std::string factor;
        while (in >> factor) {
          const std::string symbol = factor.substr(0, factor.find_first_of("+-"));
          if (!symbol.empty() && !std::isdigit(static_cast<unsigned char>(symbol[0])) &&
              std::find(symbols_.begin(), symbols_.end(), symbol) == symbols_.end())
            fail(dataset, "unit '" + text + "' uses the symbol '" + symbol + "', not one of the system's symbols");
        }
      }
    }
    H5Tclose(t);
    H5Sclose(space);
    H5Aclose(a);
    return text;
  }

  /// Checks `/sweep/results`: the value and error of every quantity carry the same valid unit.
  void check_sweep_results() {
    const std::string results = "/sweep/results";
    if (!is_group(results)) {
      fail(results, "missing");
      return;
    }
    for (const auto& q : children(results)) {
      const std::string g = results + "/" + q;
      if (!is_group(g)) continue;
      const std::string value = check_unit(g + "/value", true);
      if (!exists(g + "/error")) continue;  // (left out with one replica)
      if (check_unit(g + "/error", true) != value) fail(g + "/error", "its unit is not that of value");
    }
  }

 private:
  void fail(const std::string& where, const std::string& what) { problems_.push_back(path_ + ":" + where + ": " + what); }

  bool exists(const std::string& path) const {
    // Every parent must exist before H5Lexists may be asked about the child.
    std::string prefix;
    std::size_t start = 1;
    while (start <= path.size()) {
      const auto slash = path.find('/', start);
      prefix = path.substr(0, slash);
      if (H5Lexists(file_, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
      if (slash == std::string::npos) break;
      start = slash + 1;
    }
    return true;
  }
  H5I_type_t type_of(const std::string& path) const {
    if (!exists(path)) return H5I_BADID;
    const hid_t object = H5Oopen(file_, path.c_str(), H5P_DEFAULT);
    if (object < 0) return H5I_BADID;
    const H5I_type_t type = H5Iget_type(object);
    H5Oclose(object);
    return type;
  }
  bool is_group(const std::string& path) const { return type_of(path) == H5I_GROUP; }
  bool is_dataset(const std::string& path) const { return type_of(path) == H5I_DATASET; }

  void check_string_attribute(const std::string& object, const char* name, bool required) {
    if (!H5Aexists_by_name(file_, object.c_str(), name, H5P_DEFAULT)) {
      if (required) fail(object, std::string("attribute ") + name + " is missing");
      return;
    }
    const hid_t a = H5Aopen_by_name(file_, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t t = H5Aget_type(a);
    if (H5Tget_class(t) != H5T_STRING) fail(object, std::string("attribute ") + name + " is not of class String");
    H5Tclose(t);
    H5Aclose(a);
  }

  /// Reads a string attribute (fixed or variable length) of `object`; "" if it cannot.
  std::string string_attribute(const std::string& object, const char* name) const {
    std::string text;
    const hid_t a = H5Aopen_by_name(file_, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t t = H5Aget_type(a);
    if (H5Tget_class(t) == H5T_STRING) {
      const hid_t memory = H5Tget_native_type(t, H5T_DIR_ASCEND);
      if (H5Tis_variable_str(t) > 0) {
        char* value = nullptr;
        if (H5Aread(a, memory, &value) >= 0 && value) {
          text = value;
          H5free_memory(value);
        }
      } else {
        std::vector<char> buffer(H5Tget_size(t) + 1, '\0');
        if (H5Aread(a, memory, buffer.data()) >= 0) text = buffer.data();
      }
      H5Tclose(memory);
    }
    H5Tclose(t);
    H5Aclose(a);
    return text;
  }

  /// Reads an Integer[2] attribute; false (and a problem) if it is not one.
  bool integer_pair(const std::string& object, const char* name, int (&v)[2]) {
    if (!H5Aexists_by_name(file_, object.c_str(), name, H5P_DEFAULT)) {
      fail(object, std::string("attribute ") + name + " is missing");
      return false;
    }
    const hid_t a = H5Aopen_by_name(file_, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t t = H5Aget_type(a), s = H5Aget_space(a);
    hsize_t dims[4] = {0};
    const int rank = H5Sget_simple_extent_ndims(s);
    H5Sget_simple_extent_dims(s, dims, nullptr);
    bool ok = H5Tget_class(t) == H5T_INTEGER && rank == 1 && dims[0] == 2;
    if (!ok) fail(object, std::string(name) + " is not Integer[2]");
    else ok = H5Aread(a, H5T_NATIVE_INT, v) >= 0;
    H5Tclose(t);
    H5Sclose(s);
    H5Aclose(a);
    return ok;
  }

  /// `h5md/modules`: a version for every module; the units module as described at the top.
  void check_modules(const std::string& h5md) {
    system_.clear();
    symbols_.clear();
    const std::string modules = h5md + "/modules", units = modules + "/units";
    if (is_group(modules))
      for (const auto& name : children(modules)) {
        if (name == "units") continue;  // below
        int v[2] = {0, 0};
        if (is_group(modules + "/" + name)) integer_pair(modules + "/" + name, "version", v);
        else fail(modules + "/" + name, "a module is not a group");
      }
    if (!is_group(units)) {
      if (require_units_) fail(units, "the units module is not declared");
      return;
    }
    int v[2] = {0, 0};
    if (integer_pair(units, "version", v) && (v[0] != 1 || v[1] != 0))
      fail(units, "version is not {1, 0}");
    if (!H5Aexists_by_name(file_, units.c_str(), "system", H5P_DEFAULT)) {
      fail(units, "attribute system is missing");
    } else {
      const hid_t a = H5Aopen_by_name(file_, units.c_str(), "system", H5P_DEFAULT, H5P_DEFAULT);
      const hid_t t = H5Aget_type(a), space = H5Aget_space(a);
      if (H5Sget_simple_extent_type(space) != H5S_SCALAR) fail(units, "system is not of scalar dataspace");
      if (H5Tget_class(t) != H5T_STRING || H5Tis_variable_str(t) <= 0)
        fail(units, "system is not a variable-length String");
      H5Tclose(t);
      H5Sclose(space);
      H5Aclose(a);
      system_ = string_attribute(units, "system");
    }
    if (system_ != "SI") {  // project rule: a system of its own lists its symbols
      if (!H5Aexists_by_name(file_, units.c_str(), "symbols", H5P_DEFAULT)) {
        fail(units, "a system other than SI without the attribute symbols");
      } else {
        const hid_t a = H5Aopen_by_name(file_, units.c_str(), "symbols", H5P_DEFAULT, H5P_DEFAULT);
        const hid_t t = H5Aget_type(a), space = H5Aget_space(a);
        const hssize_t n = H5Sget_simple_extent_npoints(space);
        if (H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) > 0 && n > 0) {
          std::vector<char*> names(static_cast<std::size_t>(n), nullptr);
          const hid_t memory = H5Tget_native_type(t, H5T_DIR_ASCEND);
          if (H5Aread(a, memory, names.data()) >= 0)
            for (char* name : names) {
              symbols_.emplace_back(name ? name : "");
              H5free_memory(name);
            }
          H5Tclose(memory);
        } else {
          fail(units, "symbols is not an array of variable-length strings");
        }
        H5Tclose(t);
        H5Sclose(space);
        H5Aclose(a);
        for (const auto& symbol : symbols_)
          if (!std::regex_match(symbol, std::regex("^[A-Za-z]+$"))) fail(units, "'" + symbol + "' is not a unit symbol");
      }
    }
  }

  std::vector<std::string> children(const std::string& group) const {
    std::vector<std::string> names;
    const hid_t g = H5Gopen2(file_, group.c_str(), H5P_DEFAULT);
    H5G_info_t info;
    H5Gget_info(g, &info);
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      char name[256];
      H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT);
      names.emplace_back(name);
    }
    H5Gclose(g);
    return names;
  }

  struct Shape {
    H5T_class_t type_class = H5T_NO_CLASS;
    std::vector<hsize_t> dims;  ///< empty: scalar
  };
  Shape shape_of(const std::string& path) const {
    Shape s;
    const hid_t d = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    const hid_t t = H5Dget_type(d), space = H5Dget_space(d);
    s.type_class = H5Tget_class(t);
    const int rank = H5Sget_simple_extent_ndims(space);
    s.dims.resize(static_cast<std::size_t>(rank));
    if (rank > 0) H5Sget_simple_extent_dims(space, s.dims.data(), nullptr);
    H5Tclose(t);
    H5Sclose(space);
    H5Dclose(d);
    return s;
  }
  std::vector<double> read_doubles(const std::string& path) const {
    const Shape s = shape_of(path);
    hsize_t n = 1;
    for (hsize_t d : s.dims) n *= d;
    std::vector<double> out(n);
    const hid_t d = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    if (n) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
    H5Dclose(d);
    return out;
  }

  void walk_observables(const std::string& group) {
    for (const auto& name : children(group)) {
      const std::string path = group + "/" + name;
      if (is_dataset(path)) {
        ++elements_;  // a time-independent element
        check_unit(path, require_units_);
      } else if (is_group(path)) {
        if (is_dataset(path + "/step") || exists(path + "/time")) check_time_dependent(path);
        else walk_observables(path);  // a subgroup of elements
      }
    }
  }

  void check_time_dependent(const std::string& g) {
    ++elements_;
    if (!is_dataset(g + "/step")) {
      fail(g, "time-dependent group without a step dataset");
      return;
    }
    if (!is_dataset(g + "/value")) {
      fail(g, "time-dependent group without a value dataset");
      return;
    }
    const Shape step = shape_of(g + "/step"), value = shape_of(g + "/value");
    if (step.type_class != H5T_INTEGER) fail(g + "/step", "not of class Integer");
    if (step.dims.size() > 1) fail(g + "/step", "neither [variable] nor scalar");
    if (step.dims.size() == 1) {
      if (value.dims.empty() || value.dims[0] != step.dims[0])
        fail(g + "/value", "its first dimension is not that of step");
      const auto s = read_doubles(g + "/step");
      for (std::size_t i = 1; i < s.size(); ++i)
        if (s[i] < s[i - 1]) {
          fail(g + "/step", "not in increasing order at index " + std::to_string(i));
          break;
        }
    }
    if (exists(g + "/time")) {
      if (!is_dataset(g + "/time")) {
        fail(g + "/time", "not a dataset");
      } else {
        const Shape time = shape_of(g + "/time");
        if (time.type_class != H5T_FLOAT) fail(g + "/time", "not of class Float");
        if (time.dims != step.dims) fail(g + "/time", "not of the shape of step");
        const auto t = read_doubles(g + "/time");
        for (std::size_t i = 1; i < t.size(); ++i)
          if (t[i] < t[i - 1]) {
            fail(g + "/time", "not in increasing order at index " + std::to_string(i));
            break;
          }
      }
    }
    if (is_dataset(g + "/error") && shape_of(g + "/error").dims != value.dims)
      fail(g + "/error", "its dimensions are not those of value");
    // Units: the module's rules on every unit, the project's on which datasets carry one.
    if (H5Aexists_by_name(file_, (g + "/step").c_str(), "unit", H5P_DEFAULT) > 0)
      fail(g + "/step", "a step count carries a unit");
    if (is_dataset(g + "/time")) {
      const std::string time_unit = check_unit(g + "/time", require_units_);
      if (require_units_ && !time_unit.empty() && time_unit != "time")
        fail(g + "/time", "unit '" + time_unit + "' is not \"time\"");
    }
    const std::string value_unit = check_unit(g + "/value", require_units_);
    for (const auto& name : children(g)) {
      if (name == "step" || name == "time" || name == "value" || !is_dataset(g + "/" + name)) continue;
      const std::string unit = check_unit(g + "/" + name, require_units_);
      if (name == "error" && unit != value_unit) fail(g + "/error", "its unit is not that of value");
    }
  }


  std::string path_;
  hid_t file_ = -1;
  std::vector<std::string> problems_;
  std::size_t elements_ = 0;
  bool require_units_ = true;  ///< the project's rule: every dataset of `observables` carries a unit
  std::string system_;                ///< `system` of the units module of the root being checked
  std::vector<std::string> symbols_;  ///< its `symbols`
};

std::string scratch(const std::string& name) {
  static const gdsmc::test::ScratchDir dir("gdsmc_h5md_spec_test_");  // removed when the test process ends
  return (dir / name).string();
}

/// Runs `text` and checks its file: the root, and every sweep point as a root of its own.
void expect_conforming(const std::string& name, const std::string& text, std::size_t sweep_points = 0) {
  const auto config = gdsmc::io::config::read(gdsmc::io::namelist::parse(text, name + ".nml"));
  const std::string path = scratch(name + ".h5");
  gdsmc::simulation::run(config, path, {});
  H5mdChecker checker(path);
  checker.check_root("/");
  for (std::size_t k = 1; k <= sweep_points; ++k) checker.check_root("/sweep/point_" + std::to_string(k));
  if (sweep_points > 0) checker.check_sweep_results();
  EXPECT_GT(checker.elements(), 0u) << name << ": no observable found";
  for (const auto& p : checker.problems()) ADD_FAILURE() << p;
}

}  // namespace

TEST(H5mdSpec, PlainRun) {
  expect_conforming("plain",
                    "&system mass = 1.0, diameter = 1.0, number_density = 0.02, restitution = 0.8 /\n"
                    "&dsmc n_particles = 400, t_end = 5.0, replicas = 2 /\n&output n_samples = 5 /\n");
}

TEST(H5mdSpec, MixtureWithDisplacements) {
  expect_conforming("mixture",
                    "&system n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.02, 0.01,\n"
                    "        restitution = 0.7 /\n"
                    "&dsmc n_particles = 600, collisions_per_particle = 3.0, replicas = 3 /\n"
                    "&output n_samples = 4, track_displacements = .true., scaling_start = 1.0 /\n");
}

TEST(H5mdSpec, SweepEveryPointIsARoot) {
  expect_conforming("sweep",
                    "&system n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.02, 0.01,\n"
                    "        restitution = 0.7 /\n"
                    "&dsmc n_particles = 400, t_end = 5.0, replicas = 2 /\n&output n_samples = 3 /\n"
                    "&sweep variable = 'system:restitution(1,2)', 'system:mass(2)', values = 0.6, 2.0, 0.9, 3.0 /\n",
                    2);
}

TEST(H5mdSpec, AggregationFragmentation) {
  expect_conforming("agg_frag",
                    "&system mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 0.98 /\n"
                    "&initial temperature = 2.0 /\n"
                    "&dsmc scheme = 'lowrank', n_particles = 2000, t_end = 5.0, replicas = 2 /\n"
                    "&output sample_times = 1.0, 2.0 /\n"
                    "&agg_frag aggregation_energy = 0.2, fragmentation_energy = 1.0, fragment_restitution = 0.9 /\n");
}

TEST(H5mdSpec, ShearWithThermostat) {
  expect_conforming("shear",
                    "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.8 /\n"
                    "&dsmc n_particles = 1000, t_end = 20.0, replicas = 2 /\n&output n_samples = 5 /\n"
                    "&thermostat kind = 'gaussian' /\n&shear rate = 0.002 /\n");
}

// Every problem the checker finds in the file at `path`, one per line.
static std::string problems_of(const std::string& path) {
  H5mdChecker checker(path);
  checker.check_root("/");
  std::string all;
  for (const auto& p : checker.problems()) all += p + "\n";
  return all;
}

// An Integer[2] `version` attribute {major, minor} on an open group (the test files built by hand).
static void write_version(hid_t group, int major, int minor) {
  const hsize_t two = 2;
  const hid_t space = H5Screate_simple(1, &two, nullptr);
  const hid_t a = H5Acreate2(group, "version", H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT);
  const int v[2] = {major, minor};
  H5Awrite(a, H5T_NATIVE_INT, v);
  H5Aclose(a);
  H5Sclose(space);
}

// The checker itself: a file that breaks the rules is caught (a checker that passes everything
// would prove nothing).
TEST(H5mdSpec, CheckerCatchesViolations) {
  const std::string path = scratch("bad.h5");
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t h = H5Gcreate2(f, "/h5md", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_version(h, 1, 0);
  H5Gclose(h);
  // A time-dependent group with a float step out of order, and a value of another length.
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  const hid_t x = H5Gcreate2(f, "/observables/x", lcpl, H5P_DEFAULT, H5P_DEFAULT);
  {
    const hsize_t n = 3, m = 4;
    const hid_t s3 = H5Screate_simple(1, &n, nullptr), s4 = H5Screate_simple(1, &m, nullptr);
    const double step[3] = {0.0, 2.0, 1.0};
    const hid_t ds = H5Dcreate2(x, "step", H5T_IEEE_F64LE, s3, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, step);
    const hid_t dv = H5Dcreate2(x, "value", H5T_IEEE_F64LE, s4, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(ds);
    H5Dclose(dv);
    H5Sclose(s3);
    H5Sclose(s4);
  }
  H5Gclose(x);
  H5Pclose(lcpl);
  H5Fclose(f);
  const std::string all = problems_of(path);
  for (const char* expected : {"version is not {1, 1}", "author: mandatory group missing", "creator: mandatory group missing",
                               "step: not of class Integer", "first dimension is not that of step",
                               "not in increasing order"})
    EXPECT_NE(all.find(expected), std::string::npos) << expected << "\n" << all;
}

namespace {

/// A scalar string attribute `name` = `text` on `object`: variable length or fixed, of `cset`.
void put_string(hid_t object, const char* name, const char* text, bool variable = true,
                H5T_cset_t cset = H5T_CSET_ASCII) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, variable ? H5T_VARIABLE : std::string(text).size() + 1);
  H5Tset_cset(type, cset);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (variable) H5Awrite(a, type, &text);
  else H5Awrite(a, type, text);
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
}

/// A float64 [3] dataset `name` in `group` (an Integer one if `integer`), with a unit if `unit` is given.
hid_t put_dataset(hid_t group, const char* name, const char* unit = nullptr, bool integer = false) {
  const hsize_t n = 3;
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t d = H5Dcreate2(group, name, integer ? H5T_STD_I64LE : H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                             H5P_DEFAULT);
  const double data[3] = {0.0, 1.0, 2.0};
  H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  if (unit) put_string(d, "unit", unit);
  H5Sclose(space);
  return d;
}

}  // namespace

// The checker of the units module: a file that breaks each of its rules is caught.
TEST(H5mdSpec, CheckerCatchesUnitViolations) {
  const std::string path = scratch("bad_units.h5");
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  // The units module at version {1, 1}, without system; a symbol list; a module without a version.
  const hid_t units = H5Gcreate2(f, "/h5md/modules/units", lcpl, H5P_DEFAULT, H5P_DEFAULT);
  write_version(units, 1, 1);
  {
    const hsize_t one = 1;
    const hid_t list = H5Screate_simple(1, &one, nullptr);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t s = H5Acreate2(units, "symbols", type, list, H5P_DEFAULT, H5P_DEFAULT);
    const char* symbols[1] = {"time"};
    H5Awrite(s, type, symbols);
    H5Aclose(s);
    H5Tclose(type);
    H5Sclose(list);
  }
  H5Gclose(units);
  H5Gclose(H5Gcreate2(f, "/h5md/modules/other", lcpl, H5P_DEFAULT, H5P_DEFAULT));
  // A time-dependent element: a unit on step, time in a symbol the system lacks, a zero power on value,
  // an error in another unit than value.
  const hid_t y = H5Gcreate2(f, "/observables/y", lcpl, H5P_DEFAULT, H5P_DEFAULT);
  for (const auto& [name, unit, integer] : {std::tuple{"step", "1", true}, std::tuple{"time", "s", false},
                                            std::tuple{"value", "time+0", false}, std::tuple{"error", "time", false}})
    H5Dclose(put_dataset(y, name, unit, integer));
  H5Gclose(y);
  // Time-independent elements: a number after a symbol, a symbol twice, a fixed-length unit, a UTF-8
  // unit, no unit.
  const hid_t o = H5Gopen2(f, "/observables", H5P_DEFAULT);
  H5Dclose(put_dataset(o, "number_last", "time 60"));
  H5Dclose(put_dataset(o, "symbol_twice", "time time-1"));
  hid_t d = put_dataset(o, "fixed_length");
  put_string(d, "unit", "1", false);
  H5Dclose(d);
  d = put_dataset(o, "utf8");
  put_string(d, "unit", "1", true, H5T_CSET_UTF8);
  H5Dclose(d);
  H5Dclose(put_dataset(o, "no_unit"));
  H5Gclose(o);
  H5Pclose(lcpl);
  H5Fclose(f);

  const std::string all = problems_of(path);
  for (const char* expected :
       {"units: version is not {1, 0}", "units: attribute system is missing", "other: attribute version is missing",
        "step: a step count carries a unit", "time: unit 's' is not \"time\"", "uses the symbol 's'",
        "value: unit 'time+0' is not a unit string", "error: its unit is not that of value",
        "number_last: unit 'time 60' is not a unit string", "symbol_twice: unit 'time time-1' is not a unit string",
        "fixed_length: unit is not a variable-length string", "utf8: unit is not of the ASCII character set",
        "no_unit: attribute unit is missing"})
    EXPECT_NE(all.find(expected), std::string::npos) << expected << "\n" << all;

  // And the grammar accepts what the module's own examples write.
  for (const char* good : {"nm+3", "um+2 s-1", "60 s", "10+3 m", "1", "0.5 energy length-3 time", "length+2"})
    EXPECT_TRUE(H5mdChecker::unit_grammar(good)) << good;
  for (const char* bad : {"", " m", "m ", "m  s", "m+", "m+01", "s 60", "m-0", "m^2", "m/s", "1.", "m m"})
    EXPECT_FALSE(H5mdChecker::unit_grammar(bad)) << bad;
}
