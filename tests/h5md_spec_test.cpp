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
//    dataset beside `value` has the dimensions of `value`.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "dsmc/simulation.hpp"
#include "io/config.hpp"
#include "io/namelist.hpp"

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
    const std::string observables = base + "/observables";
    if (is_group(observables)) walk_observables(observables);
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
  }

  std::string path_;
  hid_t file_ = -1;
  std::vector<std::string> problems_;
  std::size_t elements_ = 0;
};

std::string scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("gdsmc_h5md_spec_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
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

// The checker itself: a file that breaks the rules is caught (a checker that passes everything
// would prove nothing).
TEST(H5mdSpec, CheckerCatchesViolations) {
  const std::string path = scratch("bad.h5");
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t h = H5Gcreate2(f, "/h5md", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  {
    const hsize_t two = 2;
    const hid_t space = H5Screate_simple(1, &two, nullptr);
    const hid_t a = H5Acreate2(h, "version", H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT);
    const int v[2] = {1, 0};
    H5Awrite(a, H5T_NATIVE_INT, v);
    H5Aclose(a);
    H5Sclose(space);
  }
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
  H5mdChecker checker(path);
  checker.check_root("/");
  std::string all;
  for (const auto& p : checker.problems()) all += p + "\n";
  for (const char* expected : {"version is not {1, 1}", "author: mandatory group missing", "creator: mandatory group missing",
                               "step: not of class Integer", "first dimension is not that of step",
                               "not in increasing order"})
    EXPECT_NE(all.find(expected), std::string::npos) << expected << "\n" << all;
}
