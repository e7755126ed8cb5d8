// Every kind of output is finite (issue "Nothing lost, nothing hangs, no NaN", \ref output_units
// "docs/output.md"): small runs of each kind of input the program has (one species and mixtures,
// elastic and inelastic, sweeps, agg/frag, thermostats and shear, white noise, rough spheres,
// viscoelastic, Enskog, one replica, snapshots, displacements, --compare) are written, and every
// floating-point dataset and attribute of every file is scanned: not one NaN or Inf, /comparison and the
// sweep table included, and every dataset of /comparison has its unit. What is not given at all there is
// left out; docs/output.md and docs/physics.md keep NaN for a sweep value that is not one number and for
// the entries not given of a dataset that has some, neither of which these inputs make, and an agg/frag
// sweep's cluster sizes past a point's own are 0. An elastic run wrote G = +Inf in every bin of its
// reduced distribution before.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// Non-finite values found in one file, as "path: count" lines.
struct Scan {
  std::string file;
  std::vector<std::string> found;
  std::size_t values = 0;  ///< floating-point values looked at
};

void check_values(Scan& scan, const std::string& where, const std::vector<double>& values) {
  std::size_t bad = 0;
  for (double x : values) bad += std::isfinite(x) ? 0 : 1;
  scan.values += values.size();
  if (bad) scan.found.push_back(where + ": " + std::to_string(bad) + " of " + std::to_string(values.size()));
}

herr_t scan_attribute(hid_t object, const char* name, const H5A_info_t*, void* data) {
  auto& scan = *static_cast<std::pair<Scan*, std::string>*>(data);
  const hid_t a = H5Aopen(object, name, H5P_DEFAULT);
  const hid_t type = H5Aget_type(a);
  if (H5Tget_class(type) == H5T_FLOAT) {
    const hid_t space = H5Aget_space(a);
    std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    if (!values.empty() && H5Aread(a, H5T_NATIVE_DOUBLE, values.data()) >= 0)
      check_values(*scan.first, scan.second + "@" + name, values);
    H5Sclose(space);
  }
  H5Tclose(type);
  H5Aclose(a);
  return 0;
}

herr_t scan_object(hid_t root, const char* name, const H5O_info_t* info, void* data) {
  Scan& scan = *static_cast<Scan*>(data);
  const std::string path = std::string("/") + (std::string(name) == "." ? "" : name);
  const hid_t object = H5Oopen(root, name, H5P_DEFAULT);
  std::pair<Scan*, std::string> context{&scan, path};
  H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, scan_attribute, &context);
  if (info->type == H5O_TYPE_DATASET) {
    // Every dataset of /comparison in its quantity's unit, as the observables are (docs/output.md).
    if (path.rfind("/comparison/", 0) == 0 && H5Aexists(object, "unit") <= 0) scan.found.push_back(path + ": no unit");
    const hid_t type = H5Dget_type(object);
    if (H5Tget_class(type) == H5T_FLOAT) {
      const hid_t space = H5Dget_space(object);
      std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
      if (!values.empty() && H5Dread(object, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0)
        check_values(scan, path, values);
      H5Sclose(space);
    }
    H5Tclose(type);
  }
  H5Oclose(object);
  return 0;
}

Scan scan_file(const std::string& file) {
  Scan scan{file, {}, 0};
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) {
    scan.found.push_back("cannot be opened");
    return scan;
  }
  H5Ovisit(f, H5_INDEX_NAME, H5_ITER_NATIVE, scan_object, &scan);
  H5Fclose(f);
  return scan;
}

/// A small one-species namelist; `system`, `dsmc`, `output` and `extra` groups' lines added.
std::string namelist(const std::string& system, const std::string& dsmc, const std::string& output,
                     const std::string& extra = "") {
  return "&system\n" + system + "\n/\n&initial\n  temperature = 1.0\n/\n&dsmc\n  n_particles = 2000, replicas = 4, seed = 5\n" + dsmc +
         "\n/\n&output\n  file = 'out.h5'\n" + output + "\n/\n" + extra;
}

struct Kind {
  std::string name, text, args;
};

std::vector<Kind> kinds() {
  const std::string one = "  n_species = 1, mass = 1.0, diameter = 1.0";
  const std::string dilute = one + ", number_density = 0.01, restitution = 0.8";
  const std::string binary =
      "  n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.006, 0.004, restitution = 0.7";
  return {
      {"haff-compare-msd", namelist(dilute, "  t_end = 200.0", "  n_samples = 20, track_displacements = .true."), "--compare"},
      {"binary-hcs-reduced", namelist(binary, "  collisions_per_particle = 40", "  n_samples = 10, scaling_start = 10"),
       "--compare"},
      {"elastic-reduced", namelist(one + ", number_density = 0.01, restitution = 1.0", "  collisions_per_particle = 40",
                                   "  n_samples = 10, scaling_start = 10"),
       "--compare"},
      {"one-replica", namelist(dilute, "  t_end = 50.0", "  n_samples = 5"), "--compare --set dsmc:replicas=1"},
      {"sweep", namelist(dilute, "  t_end = 50.0", "  n_samples = 5", "&sweep\n  variable = 'system:restitution'\n  values = 0.9, 0.5\n/\n"),
       "--compare"},
      // one replica, three (z_R not given below 4), a sweep of one replica: what is not given is left out
      {"sweep-one-replica", namelist(binary, "  t_end = 50.0", "  n_samples = 5",
                                     "&sweep\n  variable = 'system:restitution'\n  values = 0.9, 0.5\n/\n"),
       "--compare --set dsmc:replicas=1"},
      {"three-replicas", namelist(dilute, "  t_end = 50.0", "  n_samples = 5"), "--compare --set dsmc:replicas=3"},
      // points of different largest clusters (the table padded), with 4 replicas and with one
      {"agg-frag-sweep",
       namelist(one + ", number_density = 0.1, restitution = 0.8", "  t_end = 10.0, scheme = 'lowrank'", "  n_samples = 3",
                "&agg_frag\n  aggregation_energy = 0.5\n/\n&sweep\n  variable = 'agg_frag:aggregation_energy'\n"
                "  values = 0.2, 3.0\n/\n"),
       ""},
      {"agg-frag-sweep-one-replica",
       namelist(one + ", number_density = 0.1, restitution = 0.8", "  t_end = 10.0, scheme = 'lowrank'", "  n_samples = 3",
                "&agg_frag\n  aggregation_energy = 0.5\n/\n&sweep\n  variable = 'agg_frag:aggregation_energy'\n"
                "  values = 0.2, 3.0\n/\n"),
       "--set dsmc:replicas=1"},
      {"agg-frag", namelist(one + ", number_density = 0.1, restitution = 0.8", "  t_end = 10.0, scheme = 'lowrank'", "  sample_times = 0.5, 2.0, 10.0",
                            "&agg_frag\n  aggregation_energy = 0.5, fragmentation_energy = 1.5, fragment_restitution = 0.5\n/\n"),
       "--compare"},
      {"gaussian-shear", namelist(dilute, "  t_end = 300.0", "  n_samples = 10", "&thermostat\n  kind = 'gaussian'\n/\n&shear\n  rate = 0.003\n/\n"),
       "--compare"},
      {"white-noise", namelist(dilute, "  t_end = 300.0", "  n_samples = 10",
                               "&thermostat\n  kind = 'white_noise', noise_strength = 0.01\n/\n"),
       "--compare"},
      {"rough", namelist(dilute + ", roughness = 0.5", "  t_end = 100.0", "  n_samples = 10"), "--compare"},
      {"viscoelastic", namelist(binary.substr(0, binary.find(", restitution")) + ", restitution_model = 'viscoelastic', visco_a_kappa = 0.05",
                                "  t_end = 100.0", "  n_samples = 10"),
       "--compare"},
      {"enskog", namelist(one + ", number_density = 0.2, restitution = 0.8, enskog = .true.", "  t_end = 20.0, scheme = 'pairs'", "  n_samples = 10"),
       "--compare"},
      {"snapshots", namelist(dilute, "  t_end = 50.0", "  n_samples = 5, snapshot_times = 10.0, 40.0"), ""},
  };
}

}  // namespace

TEST(FiniteOutputs, EveryDatasetOfEveryKindOfOutputIsFinite) {
  const fs::path root = fs::temp_directory_path() / ("gdsmc-finite-" + std::to_string(::getpid()));
  fs::remove_all(root);
  std::size_t values = 0;
  for (const Kind& kind : kinds()) {
    const fs::path dir = root / kind.name;
    fs::create_directories(dir);
    std::ofstream(dir / "in.nml") << kind.text;
    const std::string command = "cd '" + dir.string() + "' && '" + (fs::path(GDSMC_BIN_DIR) / "granular-dsmc").string() +
                                "' in.nml --quiet " + kind.args + " > stdout 2> stderr";
    const int status = std::system(command.c_str());
    std::ifstream err(dir / "stderr");
    const std::string message((std::istreambuf_iterator<char>(err)), {});
    EXPECT_EQ(status, 0) << kind.name << ": " << message;
    if (status != 0) continue;
    // Read back: --table prints every kind of file (a sweep's table too, with its errors left out).
    const std::string table = "cd '" + dir.string() + "' && '" + (fs::path(GDSMC_BIN_DIR) / "granular-dsmc").string() +
                              "' --table out.h5 > table.csv 2> table.err";
    EXPECT_EQ(std::system(table.c_str()), 0) << kind.name << ": --table failed";
    const Scan scan = scan_file((dir / "out.h5").string());
    values += scan.values;
    EXPECT_GT(scan.values, 10u) << kind.name;
    for (const auto& f : scan.found) ADD_FAILURE() << kind.name << ": non-finite values in " << f;
  }
  std::printf("%zu kinds of output, %zu floating-point values scanned\n", kinds().size(), values);
  fs::remove_all(root);
}
