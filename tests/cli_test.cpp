// Tests of the executables granular-dsmc and granular-theory as a user calls them (README.md, \ref output_page "docs/output.md"):
// exit status, the one-line message on stderr for bad input, and what is left in the directory.
// Each test runs the real programs in a fresh temporary directory; every run is tiny.
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "base_namelist.hpp"
#include "sanitizer_scale.hpp"
#include "io/file_lock.hpp"
#include "run/checkpoint.hpp"
#include "io/h5md.hpp"
#include "io/version.hpp"

#include <hdf5.h>

#include "io/h5md.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> base_lines = gdsmc::test::base_namelist_lines("  file = 'out.h5', n_samples = 3");

std::string base() { return gdsmc::test::join_lines(base_lines); }

std::string with_line(int line, const std::string& text) {
  return gdsmc::test::with_line(base_lines, line, text);
}

/// ulimit -v `bytes` (the soft RLIMIT_AS) for the commands run while it lives, until restore() or the end
/// of its scope; `skip` says why it could not be set (AddressSanitizer reserves terabytes of address
/// space; a hard limit below `bytes`).
class AddressSpaceLimit {
 public:
  explicit AddressSpaceLimit(rlim_t bytes) {
    if (gdsmc::test::sanitized) {
      skip = "AddressSanitizer reserves terabytes of address space: no ulimit -v";
    } else if (::getrlimit(RLIMIT_AS, &saved_) != 0) {
      skip = "getrlimit failed";
    } else if (saved_.rlim_max != RLIM_INFINITY && saved_.rlim_max < bytes) {
      skip = "hard address-space limit below " + std::to_string(bytes) + " bytes";
    } else {
      struct rlimit limited = saved_;
      limited.rlim_cur = bytes;
      set_ = ::setrlimit(RLIMIT_AS, &limited) == 0;
      if (!set_) skip = "setrlimit failed";
    }
  }
  ~AddressSpaceLimit() { restore(); }
  AddressSpaceLimit(const AddressSpaceLimit&) = delete;
  AddressSpaceLimit& operator=(const AddressSpaceLimit&) = delete;
  void restore() {
    if (set_) ::setrlimit(RLIMIT_AS, &saved_);
    set_ = false;
  }
  std::string skip;

 private:
  struct rlimit saved_ {};
  bool set_ = false;
};

/// `species` species (`lowrank`; masses k, diameters k^(1/3), equal densities), one replica of
/// `particles`, 0.5 collisions per particle, `samples` samples: n_species on line 2, n_particles on
/// line 6, n_samples on line 8.
std::string many_species_namelist(long species, long particles, long samples) {
  return "&system\n  n_species = " + std::to_string(species) +
         ", mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.9,\n"
         "  mass_law = 'linear', diameter_law = 'cube_root', density_law = 'power', density_exponent = 0.0\n/\n"
         "&initial temperature = 1.0 /\n&dsmc scheme = 'lowrank', n_particles = " + std::to_string(particles) +
         ", replicas = 1,\n  collisions_per_particle = 0.5 /\n&output file = 'out.h5', n_samples = " +
         std::to_string(samples) + " /\n";
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Result {
  int status = -1;  ///< exit status, or -1 if the program did not exit normally
  std::string out;
  std::string err;
};

/// A fresh directory per test: `run/` is the working directory of the programs (and holds only
/// what they write besides the input), `capture/` receives their stdout and stderr.
class CliFixture : public ::testing::Test {
 public:  // for the helpers below the fixtures
  fs::path root, dir, capture;

  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root = fs::temp_directory_path() /
           ("gdsmc-cli-" + std::to_string(::getpid()) + "-" + info->test_suite_name() + "-" +
            info->name());
    fs::remove_all(root);
    dir = root / "run";
    capture = root / "capture";
    fs::create_directories(dir);
    fs::create_directories(capture);
    for (const char* tool : {"granular-dsmc", "granular-theory"})
      ASSERT_TRUE(fs::exists(fs::path(GDSMC_BIN_DIR) / tool))
          << tool << " is not built in " << GDSMC_BIN_DIR << " (build all targets first)";
  }

  void TearDown() override {
    if (HasFailure()) {
      std::cerr << "kept for inspection: " << root << "\n";
      return;
    }
    std::error_code ignored;
    fs::remove_all(root, ignored);
  }

  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
  }

  /// Runs `tool args` in `dir` (args are passed to the shell as written).
  /// Runs `tool args` in the test's folder; with `timeout_seconds`, killed after that long (exit 137).
  Result run(const std::string& tool, const std::string& args, int timeout_seconds = 0) {
    const std::string limit = timeout_seconds > 0 ? "timeout -s KILL " + std::to_string(timeout_seconds) + " " : "";
    const std::string command = "cd " + quoted(dir.string()) + " && " + limit +
                                quoted((fs::path(GDSMC_BIN_DIR) / tool).string()) + " " + args +
                                " >" + quoted((capture / "stdout").string()) + " 2>" +
                                quoted((capture / "stderr").string()) + " </dev/null";
    const int raw = std::system(command.c_str());
    Result r;
    r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
    r.out = read_text(capture / "stdout");
    r.err = read_text(capture / "stderr");
    return r;
  }

  Result dsmc(const std::string& text, const std::string& extra_args = "") {
    write("t.nml", text);
    return run("granular-dsmc", "t.nml --quiet " + extra_args);
  }

  /// Names of the files in the working directory, sorted.
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  void expect_no_temporary_file() const {
    for (const auto& name : files())
      EXPECT_EQ(name.find(".tmp"), std::string::npos) << "temporary file left: " << name;
  }

  /// Exit status 2, nothing on stdout, stderr one line `tool: <prefix>...` with every key word,
  /// and nothing in the directory but the input.
  void expect_input_error(const Result& r, const std::string& tool, const std::string& prefix,
                          const std::vector<std::string>& key_words,
                          const std::vector<std::string>& expected_files = {"t.nml"}) const {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.out, "");
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.back(), '\n') << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line:\n" << r.err;
    const std::string full = tool + ": " + prefix;
    EXPECT_EQ(r.err.rfind(full, 0), 0u) << "expected '" << full << "' at the start of: " << r.err;
    for (const auto& k : key_words)
      EXPECT_NE(r.err.find(k), std::string::npos) << "'" << k << "' missing from: " << r.err;
    EXPECT_EQ(files(), expected_files);
    expect_no_temporary_file();
  }
};

class CliDsmc : public CliFixture {};
class CliTheory : public CliFixture {};

// ---------------------------------------------------------------------------------------------
// granular-dsmc: valid runs
// ---------------------------------------------------------------------------------------------

TEST_F(CliDsmc, TinyRunWritesTheFileQuietly) {
  const Result r = dsmc(base());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");  // --quiet: no progress and no summary
  EXPECT_EQ(files(), (std::vector<std::string>{"out.h5", "t.nml"}));
  expect_no_temporary_file();
  // An HDF5 file: the format signature at offset 0.
  EXPECT_EQ(read_text(dir / "out.h5").substr(0, 8), std::string("\x89HDF\r\n\x1a\n", 8));
}

// Tracked displacements that never start (msd_start_temperature below every T the run reaches) are all
// zeros: said in a warning, even with --quiet; none when they start (the first sample's T is below 100).
TEST_F(CliDsmc, DisplacementsThatNeverStartAreWarnedOf) {
  const std::string output = "  file = 'out.h5', n_samples = 3, track_displacements = .true., ";
  Result r = dsmc(with_line(16, output + "msd_start_temperature = 1e-6"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.rfind("granular-dsmc: warning: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("replicas never reached T <= msd_start_temperature = 1e-06"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/observables/msd/start_time is -1"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = dsmc(with_line(16, output + "msd_start_temperature = 100.0"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST_F(CliDsmc, WithoutQuietASummaryGoesToStderrNotStdout) {
  write("t.nml", base());
  const Result r = run("granular-dsmc", "t.nml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("wrote out.h5"), std::string::npos) << r.err;
}

// How the collisions were sampled, in the summary and in /parameters: the binary gas of 200 particles has
// too few for blocks; in blocks of 64 it has 3 (N div 64), which take the cheaper draw at each step with
// either scheme (constant restitution); one species in 3 blocks; the whole gas of `pairs` as one block.
TEST_F(CliDsmc, TheSummaryAndTheFileSayHowTheCollisionsWereSampled) {
  const auto run_with = [&](const std::string& dsmc_lines) {
    write("t.nml", with_line(12, "  n_particles = 200, " + dsmc_lines));
    const Result r = run("granular-dsmc", "t.nml --force");
    EXPECT_EQ(r.status, 0) << r.err;
    return r.err;
  };
  const auto attributes = [&]() {
    const std::string file = (dir / "out.h5").string();
    return std::to_string(std::get<long long>(gdsmc::io::h5md::read_attribute(file, "/parameters", "cache_blocks"))) +
           " " + gdsmc::io::h5md::read_string_attribute(file, "/parameters", "block_draw");
  };
  EXPECT_NE(run_with("block_size = 0").find(" s; no cache blocks\n"), std::string::npos);
  EXPECT_EQ(attributes(), "1 unblocked");
  const std::string cheaper = "majorant or lowrank, the cheaper at each step";
  EXPECT_NE(run_with("block_size = 64").find(" s; 3 cache blocks of about 67 particles (" + cheaper + ")\n"),
            std::string::npos);
  EXPECT_EQ(attributes(), "3 " + cheaper);
  EXPECT_NE(run_with("block_size = 64, scheme = 'lowrank'").find("3 cache blocks of about 67 particles (" + cheaper + ")\n"),
            std::string::npos);
  EXPECT_EQ(attributes(), "3 " + cheaper);
  EXPECT_NE(run_with("block_size = 64, scheme = 'pairs'").find(" s; no cache blocks\n"), std::string::npos);
  EXPECT_EQ(attributes(), "1 unblocked");
  write("t.nml", gdsmc::test::join_lines({"&system", "  mass = 1.0", "  diameter = 1.0", "  number_density = 0.01",
                                         "  restitution = 0.9", "/", "&initial", "  temperature = 1.0", "/", "&dsmc",
                                         "  n_particles = 200, block_size = 64, t_end = 10.0", "/", "&output",
                                         "  file = 'out.h5', n_samples = 3", "/"}));
  const Result one = run("granular-dsmc", "t.nml --force");
  EXPECT_NE(one.err.find("3 cache blocks of about 67 particles (one species)\n"), std::string::npos) << one.err;
  EXPECT_EQ(attributes(), "3 one species");
  // A sweep over N: each point's line and group says its own (120 particles: none; 200: 3 blocks).
  write("t.nml", read_text(dir / "t.nml") + "&sweep\n  variable = 'dsmc:n_particles'\n  values = 120, 200\n/\n");
  const Result sweep = run("granular-dsmc", "t.nml --force");
  EXPECT_NE(sweep.err.find("point 1 (n_particles = 120): "), std::string::npos) << sweep.err;
  EXPECT_NE(sweep.err.find(" collisions per particle; no cache blocks\ngranular-dsmc: point 2 (n_particles = 200): "),
            std::string::npos) << sweep.err;
  EXPECT_NE(sweep.err.find(" collisions per particle; 3 cache blocks of about 67 particles (one species)\ngranular-dsmc: wrote"),
            std::string::npos) << sweep.err;
  const std::string file = (dir / "out.h5").string();
  EXPECT_EQ(std::get<long long>(gdsmc::io::h5md::read_attribute(file, "/sweep/point_2", "cache_blocks")), 3);
  EXPECT_EQ(gdsmc::io::h5md::read_string_attribute(file, "/sweep/point_1", "block_draw"), "unblocked");
}

TEST_F(CliDsmc, OutputOptionOverridesTheFile) {
  const Result r = dsmc(base(), "--output other.h5");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(files(), (std::vector<std::string>{"other.h5", "t.nml"}));
  expect_no_temporary_file();
}

TEST_F(CliDsmc, SetOverridesAVariable) {
  const Result r = dsmc(base(), "--set \"output:file='set.h5'\"");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"set.h5", "t.nml"}));
}

TEST_F(CliDsmc, PrintDefaults) {
  const Result r = run("granular-dsmc", "--print-defaults");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const char* group : {"&system", "&initial", "&dsmc", "&output"})
    EXPECT_NE(r.out.find(group), std::string::npos) << group;
  EXPECT_EQ(files(), std::vector<std::string>{});
  // The template as printed is a valid input (it sets collisions_per_particle, which has no default), and
  // its run's --compare gives statistical marks (the default 4 replicas).
  write("defaults.nml", r.out);
  const Result t = run("granular-theory", "defaults.nml");
  EXPECT_EQ(t.status, 0) << t.err;
  const Result d = run("granular-dsmc", "defaults.nml --quiet --compare --set dsmc:n_particles=2000");
  ASSERT_EQ(d.status, 0) << d.err;
  EXPECT_NE(d.out.find("4 replicas: |D-T| <= 9.22 SE"), std::string::npos) << d.out;
  EXPECT_NE(d.out.find(" stat"), std::string::npos) << d.out;
}

TEST_F(CliDsmc, DenseGasWithoutEnskogWarns) {
  // phi = (pi/6)(0.1 + 0.05) = 0.0785 > 0.05 without enskog (chi = (1 - phi/2)/(1 - phi)^3 = 1.228 by hand): one warning line naming where the density is
  // set, and the run goes on; with enskog, or at the base densities (phi = 0.016), no warning.
  // (the run goes on, and stderr is exactly the warning: its start, the words `rest`, its end)
  const auto expect_warning = [&](const std::string& densities, const std::string& rest) {
    std::filesystem::remove(dir / "out.h5");
    const Result r = dsmc(with_line(5, "  number_density = " + densities));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "granular-dsmc: warning: t.nml:5: &system: number_density: packing fraction " + rest +
                         " (warned above 0.05)\n");
  };
  expect_warning("0.1, 0.05", "0.0785 without enskog: this runs a dilute (Boltzmann) gas, whose collision rate "
                              "ignores the density (the Enskog gas collides 1.23 times as often); set &system "
                              "enskog = .true. for a dense gas");
  std::filesystem::remove(dir / "out.h5");
  EXPECT_EQ(dsmc(with_line(5, "  number_density = 0.1, 0.05, enskog = .true.")).err, "");
  std::filesystem::remove(dir / "out.h5");
  EXPECT_EQ(dsmc(base()).err, "");
  // phi = (pi/6)(1.5 + 0.5) = 1.047: Carnahan-Starling's chi (-4.5e3 here) is no fluid's, and enskog would
  // refuse the gas (phi >= 0.5): the warning quotes neither.
  expect_warning("1.5, 0.5", "1.05 without enskog: this runs a dilute (Boltzmann) gas, whose collision rate ignores "
                             "the density; no Enskog gas is that dense (the Carnahan-Starling fluid ends at 0.5, where "
                             "enskog stops): check the number densities and diameters");
  // A sweep that makes the gas dense is blamed on its values line, naming the densest point, as the sweep's own
  // errors name a point (the base namelist has 17 lines: the &sweep group is lines 18-21).
  std::filesystem::remove(dir / "out.h5");
  const Result swept = dsmc(base() + "&sweep\n variable = 'system:number_density'\n"
                                     " values = '0.01, 0.005', '0.1, 0.05', '0.02, 0.01'\n/\n");
  EXPECT_EQ(swept.status, 0) << swept.err;
  EXPECT_EQ(swept.err, "granular-dsmc: warning: t.nml:20: &sweep: values: point 2 (number_density = '0.1, 0.05'): "
                       "packing fraction 0.0785 without enskog: this runs a dilute (Boltzmann) gas, whose collision "
                       "rate ignores the density (the Enskog gas collides 1.23 times as often); set &system enskog = "
                       ".true. for a dense gas (warned above 0.05)\n");
}

// Variables no point of the run uses (a new user's trial: both ran silently): a stage length other than the
// default without &thermostat or &shear, and grid = .true. without a sweep, each one warning line naming where
// it was set, and the run goes on (an older output that wrote them still reads); the default stage_step, as
// --print-defaults writes it, and a sweep that stages one of its points warn of nothing.
TEST_F(CliDsmc, UnusedStageStepAndGridWarn) {
  Result r = dsmc(base(), "--set dsmc:stage_step=0.5");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "granular-dsmc: warning: --set dsmc:stage_step=0.5: &dsmc: stage_step: only used with &thermostat "
                   "or &shear (the length of their stages): no effect here\n");
  std::filesystem::remove(dir / "out.h5");
  r = dsmc(base() + "&sweep grid = .true. /\n");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "granular-dsmc: warning: t.nml:18: &sweep: grid: only used with variable and values (a sweep): no "
                   "sweep is run\n");
  std::filesystem::remove(dir / "out.h5");
  EXPECT_EQ(dsmc(base(), "--set dsmc:stage_step=0.125").err, "");
  std::filesystem::remove(dir / "out.h5");
  r = dsmc(base() + "&sweep variable = 'thermostat:kind', values = 'none', 'gaussian' /\n", "--set dsmc:stage_step=0.5");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "") << "point 2 is staged";
}

// A sample taken past its exact event target is never silent (src/run/replica.cpp, FreeGas::sample; the
// summary's warning; docs/schemes.md "Event targets"): an elastic binary with 1 % of its particles at
// T = 100 and the rest at 0.001, N = 1e5 in 20 blocks, to 2 collisions per particle. Within its blocked
// steps the cold species' bounds rise a hundredfold and the collisions outrun the approach's bound, so the
// sample is taken past 100000 collisions (this test is to change when that is fixed), and the run ends with
// one warning that counts such samples and says by how much.
TEST_F(CliDsmc, ASamplePastItsEventTargetIsSaid) {
  const std::string text =
      "&system\n n_species = 2\n mass = 1.0, 1.0\n diameter = 1.0, 1.0\n number_density = 0.0099, 0.0001\n"
      " restitution = 1.0\n/\n&initial\n temperature = 0.001, 100.0\n/\n&dsmc\n scheme = 'majorant'\n"
      " n_particles = 100000\n replicas = 1\n seed = 1\n collisions_per_particle = 2.0\n block_size = 5000\n/\n"
      "&output\n n_samples = 2\n file = 'out.h5'\n/\n";
  const Result r = dsmc(text);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto collisions = gdsmc::io::h5md::read_observable((dir / "out.h5").string(), "collisions").value;
  ASSERT_EQ(collisions.size(), 2u);
  std::printf("[ measured ] the sample at 2 collisions per particle taken at %.0f collisions (target 100000)\n",
              collisions[1]);
  ASSERT_GT(collisions[1], 100000.0);
  EXPECT_EQ(r.err, "granular-dsmc: warning: 1 sample was taken past its event target, by up to " +
                       std::to_string(static_cast<long long>(collisions[1]) - 100000) +
                       " collisions (see /observables/collisions): a cache-blocked step's collisions outran the "
                       "bound of its length, as in a gas far from equilibrium; &dsmc block_size = 0 meets every "
                       "target exactly (docs/schemes.md, \"Event targets\")\n");
}

TEST_F(CliDsmc, AggFragRunWritesClusterObservables) {
  const Result r = dsmc(
      "&system mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 0.8 /\n"
      "&dsmc scheme = 'lowrank', n_particles = 500, t_end = 5.0, replicas = 2 /\n"
      "&output file = 'out.h5', sample_times = 1.0, 2.0 /\n"
      "&agg_frag aggregation_energy = 0.5, fragmentation_energy = 1.5, fragment_restitution = 0.5 /\n");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"out.h5", "t.nml"}));
  expect_no_temporary_file();
}

// A gas that sticks into one cluster before its collisions_per_particle fails (exit 1, one line), and its
// checkpoints go with it: resumed, the run would fail the same way, and a checkpoint left behind refused the
// next run of that output with t_end, as the message advises (a user's trial: it needed --force).
TEST_F(CliDsmc, AnUnreachableEventTargetLeavesNoCheckpoint) {
  const std::string head =
      "&system mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 1.0 /\n"
      "&output file = 'out.h5', n_samples = 20, checkpoint_every = 0.0001 /\n"
      "&agg_frag aggregation_energy = 100.0 /\n";
  const Result r = dsmc(head + "&dsmc scheme = 'lowrank', n_particles = 100, collisions_per_particle = 150, replicas = 2 /\n");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.rfind("granular-dsmc: the gas aggregated into one cluster after ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("give t_end instead (this run's checkpoint, which would fail the same way, is removed)\n"),
            std::string::npos) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"t.nml"}));
  const Result again = dsmc(head + "&dsmc scheme = 'lowrank', n_particles = 100, t_end = 50.0, replicas = 2 /\n");
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"out.h5", "t.nml"}));
  // Without checkpoints there is none to remove, and the message does not say there was; it names the run's
  // target, not the sample's.
  fs::remove(dir / "out.h5");
  const Result plain = dsmc("&system mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 1.0 /\n"
                            "&output file = 'out.h5', n_samples = 20 /\n&agg_frag aggregation_energy = 100.0 /\n"
                            "&dsmc scheme = 'lowrank', n_particles = 100, collisions_per_particle = 150, replicas = 2 /\n");
  EXPECT_EQ(plain.status, 1) << plain.err;
  EXPECT_NE(plain.err.find("before collisions_per_particle = 150 was reached (its sample at "), std::string::npos)
      << plain.err;
  EXPECT_NE(plain.err.find("); give t_end instead\n"), std::string::npos) << plain.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"t.nml"}));
}

TEST_F(CliDsmc, AggFragBadInputLeavesNoFile) {
  const std::string head =
      "&system mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 0.8 /\n"
      "&dsmc scheme = 'lowrank', n_particles = 500, t_end = 5.0 /\n"
      "&output file = 'out.h5' /\n";
  expect_input_error(dsmc(head + "&agg_frag aggregation_energy = -0.5 /\n"), "granular-dsmc",
                     "t.nml:4: &agg_frag: aggregation_energy: ", {"outside"});
  expect_input_error(dsmc(head + "&agg_frag fragmentation_energy = 1.0, fragment_restitution = 2.0 /\n"),
                     "granular-dsmc", "t.nml:4: &agg_frag: fragment_restitution: ", {"outside [0, 1]"});
  expect_input_error(
      dsmc("&system mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 0.8 /\n"
           "&dsmc scheme = 'majorant', n_particles = 500, t_end = 5.0 /\n&output file = 'out.h5' /\n"
           "&agg_frag aggregation_energy = 0.5 /\n"),
      "granular-dsmc", "t.nml:2: &dsmc: scheme: ", {"'lowrank'"});
}

TEST_F(CliDsmc, ShearBadInputLeavesNoFile) {
  const std::string head =
      "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.8 /\n"
      "&dsmc n_particles = 500, t_end = 5.0 /\n"
      "&output file = 'out.h5' /\n";
  expect_input_error(dsmc(head + "&shear rate = -0.1 /\n"), "granular-dsmc", "t.nml:4: &shear: rate: ", {"outside"});
  expect_input_error(dsmc(head + "&shear rate = 1.0 /\n"), "granular-dsmc", "t.nml:4: &shear: rate: ", {"a* = "});
  expect_input_error(dsmc("&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.8 /\n"
                          "&dsmc scheme = 'lowrank', n_particles = 500, t_end = 5.0 /\n&output file = 'out.h5' /\n"
                          "&agg_frag aggregation_energy = 0.5 /\n&thermostat kind = 'gaussian' /\n"),
                     "granular-dsmc", "t.nml:5: &thermostat: kind: ", {"&agg_frag"});
  expect_input_error(
      dsmc("&system mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 0.8, enskog = .true. /\n"
           "&dsmc n_particles = 500, t_end = 5.0 /\n&output file = 'out.h5' /\n&shear rate = 0.01 /\n"),
      "granular-dsmc", "t.nml:2: &dsmc: scheme: ", {"'pairs'"});
}

TEST_F(CliDsmc, ShearRunWritesViscosity) {
  const Result r = dsmc(
      "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.9 /\n"
      "&dsmc n_particles = 500, t_end = 50.0, replicas = 2 /\n&output file = 'out.h5', n_samples = 5 /\n"
      "&thermostat kind = 'gaussian' /\n&shear rate = 0.003 /\n");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"out.h5", "t.nml"}));
  expect_no_temporary_file();
}

TEST_F(CliDsmc, NeverOverwritesTheInputOrAForeignFile) {
  // --output pointing at the input namelist: refused, the namelist intact.
  write("t.nml", base());
  Result r = run("granular-dsmc", "t.nml --quiet --output t.nml");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("is the input namelist"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(dir / "t.nml"), base());
  // An existing file that granular-dsmc did not write: refused, kept; --force replaces it.
  write("notes.txt", "my notes\n");
  r = run("granular-dsmc", "t.nml --quiet --output notes.txt");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("is not an output of granular-dsmc"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(dir / "notes.txt"), "my notes\n");
  r = run("granular-dsmc", "t.nml --quiet --output notes.txt --force");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_text(dir / "notes.txt").substr(0, 8), std::string("\x89HDF\r\n\x1a\n", 8));
  // An earlier output of the program is replaced without --force.
  r = run("granular-dsmc", "t.nml --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  r = run("granular-dsmc", "t.nml --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  expect_no_temporary_file();
}

TEST_F(CliDsmc, StaleTemporariesOfDeadRunsAreRemoved) {
  // What a SIGKILLed run leaves (its pid gone: 4194300 is above any pid this machine hands out before
  // wrapping) is removed, and so is a temporary of the output or its checkpoint whose pid is a live
  // process (this test's: a killed run's pid reused since), since the run holds the output's lock; a
  // name that is not a temporary of the run's files is kept.
  const std::string live = ".tmp." + std::to_string(::getpid());
  for (const std::string& f : std::vector<std::string>{"out.h5.tmp.4194300", "out.h5" + live, "out.checkpoint.h5" + live, "out.h5.tmp.7x",
                              "other.h5" + live})
    write(f, "left");
  const Result r = dsmc(base());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"other.h5" + live, "out.h5", "out.h5.tmp.7x", "t.nml"}));
  // The checkpoint's name as the output of a run at work (this process holds its lock): that run's temporary
  // is its own, and stays.
  for (const std::string& f : std::vector<std::string>{"other.h5" + live, "out.h5", "out.h5.tmp.7x"}) fs::remove(dir / f);
  {
    const gdsmc::io::FileLock at_work((dir / "out.checkpoint.lock").string());
    write("out.checkpoint.h5" + live, "at work");
    const Result again = dsmc(base());
    EXPECT_EQ(again.status, 0) << again.err;
    EXPECT_TRUE(fs::exists(dir / ("out.checkpoint.h5" + live)));
  }
}

/// Starts an endless run (t_end = 1e30, asked for with allow_long_run, checkpoints every 0.2 s),
/// sends it SIGINT after `wait_us` and once its first checkpoint exists (up to 60 s more: a loaded
/// machine or a sanitizer build may take longer than `wait_us` to write it), and waits up to 10 s:
/// the exit status (-1: killed after the wait), and the seconds from the signal to the end.
/// `output`, `end` and `restitution` replace the &output line, the end of the &dsmc group and the
/// restitution (another run, interrupted alike).
std::pair<int, double> interrupt_an_endless_run(
    CliFixture& f, useconds_t wait_us,
    const std::string& output = "  file = 'out.h5', n_samples = 3, checkpoint_every = 0.2",
    const std::string& end = "  t_end = 1e30, allow_long_run = .true., replicas = 1",
    const std::string& restitution = "  restitution = 0.9", bool quiet = true) {
  // It cools by ~50 decades: its relative speeds drown in round-off and events become ever rarer
  // among the candidates, so a loop that counted events only would not look at the signal again.
  auto lines = gdsmc::test::base_namelist_lines(output);
  lines[1] = "  n_species = 1";
  lines[2] = "  mass = 1.0";
  lines[3] = "  diameter = 1.0";
  lines[4] = "  number_density = 0.01";
  lines[5] = restitution;
  lines[11] = "  n_particles = 2000";
  lines[12] = end;  // one replica by default: one unit, unit_0 is the one running
  std::ofstream(f.dir / "t.nml", std::ios::binary) << gdsmc::test::join_lines(lines);
  const pid_t pid = ::fork();
  if (pid < 0) return {-2, 0.0};
  if (pid == 0) {
    if (::chdir(f.dir.c_str()) != 0) ::_exit(120);
    if (!std::freopen((f.capture / "stderr").c_str(), "w", stderr)) ::_exit(121);
    const std::string tool = (fs::path(GDSMC_BIN_DIR) / "granular-dsmc").string();
    if (quiet) ::execl(tool.c_str(), tool.c_str(), "t.nml", "--quiet", static_cast<char*>(nullptr));
    ::execl(tool.c_str(), tool.c_str(), "t.nml", static_cast<char*>(nullptr));
    ::_exit(122);
  }
  ::usleep(wait_us);
  for (int polls = 0; polls < 6000 && !fs::exists(f.dir / "out.checkpoint.h5"); ++polls) ::usleep(10000);
  const auto sent = std::chrono::steady_clock::now();
  ::kill(pid, SIGINT);
  int status = 0;
  pid_t done = 0;
  while ((done = ::waitpid(pid, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() - sent < std::chrono::seconds(10))
    ::usleep(10000);
  if (done == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    return {-1, 10.0};
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, seconds};
}

TEST_F(CliDsmc, AnEndlessRunStopsAtSigintLeavingOnlyTheCheckpoint) {
  const auto [status, seconds] = interrupt_an_endless_run(*this, 2500000);  // well into the rare events
  EXPECT_EQ(status, 130);
  EXPECT_LT(seconds, 3.0);
  const std::string err = read_text(capture / "stderr");
  EXPECT_EQ(err, "granular-dsmc: interrupted: no output written; resume with --restart out.checkpoint.h5\n");
  EXPECT_EQ(files(), (std::vector<std::string>{"out.checkpoint.h5", "t.nml"}));
}

/// Zeroes the 16-byte header of object `object` (from 1) of the first global heap collection ("GCOL", the
/// strings of the attributes) of an HDF5 file: the HDF5 library then loops without end when it loads that
/// collection (found by fuzzing --table; io/file_guard.hpp).
void damage_global_heap(const fs::path& file, int object) {
  std::string bytes = read_text(file);
  const std::size_t heap = bytes.find("GCOL");
  ASSERT_NE(heap, std::string::npos) << file;
  std::size_t at = heap + 16;  // (signature, version, reserved, collection size)
  for (int k = 1; k < object; ++k) {
    std::uint64_t size = 0;
    ASSERT_LT(at + 16, bytes.size());
    std::memcpy(&size, bytes.data() + at + 8, sizeof size);
    at += 16 + (size + 7) / 8 * 8;
  }
  ASSERT_LT(at + 16, bytes.size());
  std::fill(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.begin() + static_cast<std::ptrdiff_t>(at + 16), '\0');
  std::ofstream(file, std::ios::binary) << bytes;
}

/// GDSMC_READ_LIMIT=`seconds` for the programs run while it lives (io/file_guard.hpp).
class ReadLimit {
 public:
  explicit ReadLimit(const char* seconds) { ::setenv("GDSMC_READ_LIMIT", seconds, 1); }
  ~ReadLimit() { ::unsetenv("GDSMC_READ_LIMIT"); }
};

/// Starts `granular-dsmc t.nml --quiet --restart out.checkpoint.h5` in the fixture's run folder, its stderr in
/// capture/stderr: the child's pid (-1: fork failed).
pid_t start_restart(const CliFixture& f) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(f.dir.c_str()) != 0 || !std::freopen((f.capture / "stderr").c_str(), "w", stderr)) ::_exit(120);
    const std::string tool = (fs::path(GDSMC_BIN_DIR) / "granular-dsmc").string();
    ::execl(tool.c_str(), tool.c_str(), "t.nml", "--quiet", "--restart", "out.checkpoint.h5", static_cast<char*>(nullptr));
    ::_exit(122);
  }
  return pid;
}

/// Sends SIGINT to `pid` and waits up to 10 s for it to end (then SIGKILL): whether it ended by itself, its
/// wait status, and the seconds from the signal to its end.
struct Ended {
  bool by_itself;
  int status;
  double seconds;
};
Ended interrupt_and_wait(pid_t pid) {
  const auto sent = std::chrono::steady_clock::now();
  ::kill(pid, SIGINT);
  int status = 0;
  pid_t done = 0;
  while ((done = ::waitpid(pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() - sent < std::chrono::seconds(10))
    ::usleep(10000);
  if (done == 0) ::kill(pid, SIGKILL), ::waitpid(pid, &status, 0);
  return {done != 0, status, std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count()};
}

// A checkpoint whose global heap makes HDF5 loop (damage_global_heap) is refused after the read limit in
// one line, exit status 2, with nothing left behind (no temporary output, no lock file), by --restart and by
// a fresh run that would replace it; Ctrl-C during such a read ends it within a second (status 130).
TEST_F(CliDsmc, ADamagedCheckpointThatLoopsHdf5IsRefusedInTime) {
  ASSERT_EQ(interrupt_an_endless_run(*this, 0).first, 130) << read_text(capture / "stderr");
  damage_global_heap(dir / "out.checkpoint.h5", 4);
  const std::vector<std::string> left{"out.checkpoint.h5", "t.nml"};
  const std::string unfinished = "the HDF5 library had not finished reading it after 1 s: the file is damaged, or on a "
                                 "very slow disk (GDSMC_READ_LIMIT=SECONDS allows longer)";
  {
    const ReadLimit limit("1");
    const Result resumed = run("granular-dsmc", "t.nml --quiet --restart out.checkpoint.h5", 60);
    EXPECT_EQ(resumed.status, 2);
    EXPECT_EQ(resumed.err, "granular-dsmc: --restart: checkpoint 'out.checkpoint.h5': " + unfinished + "\n");
    EXPECT_EQ(files(), left);
    const Result fresh = run("granular-dsmc", "t.nml --quiet", 60);
    EXPECT_EQ(fresh.status, 2);
    EXPECT_EQ(fresh.err, "granular-dsmc: t.nml:16: &output: file: 'out.checkpoint.h5' (the checkpoint this run would "
                         "replace): " + unfinished + "; give --force to replace it unread\n");
    EXPECT_EQ(files(), left);
  }
  const pid_t pid = start_restart(*this);
  ASSERT_GE(pid, 0);
  // SIGINT once the run has begun (its signal handler installed: the temporary output is made after it), the
  // read looping by then (the limit is 60 s)
  const auto started = std::chrono::steady_clock::now();
  const auto has_temporary = [&] {
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().rfind("out.h5.tmp.", 0) == 0) return true;
    return false;
  };
  while (!has_temporary() && std::chrono::steady_clock::now() - started < std::chrono::seconds(30)) ::usleep(10000);
  ::usleep(200000);
  const Ended ended = interrupt_and_wait(pid);
  ASSERT_TRUE(ended.by_itself) << "still reading 10 s after SIGINT";
  EXPECT_LT(ended.seconds, 2.0);  // (a loaded machine)
  EXPECT_EQ(WIFEXITED(ended.status) ? WEXITSTATUS(ended.status) : -1, 130);
  EXPECT_EQ(read_text(capture / "stderr"),
            "granular-dsmc: interrupted while reading the checkpoint 'out.checkpoint.h5': nothing written\n");
  EXPECT_EQ(files(), left);
}

// An earlier output whose global heap makes HDF5 loop is neither replaced nor waited for: whether it is
// granular-dsmc's cannot be read, so the run is refused after the read limit, the file left as it was.
TEST_F(CliDsmc, ADamagedEarlierOutputThatLoopsHdf5IsRefusedInTime) {
  ASSERT_EQ(dsmc(base()).status, 0);
  damage_global_heap(dir / "out.h5", 10);
  const std::string before = read_text(dir / "out.h5");
  const ReadLimit limit("1");
  const Result again = run("granular-dsmc", "t.nml --quiet", 60);
  EXPECT_EQ(again.status, 2);
  EXPECT_EQ(again.err, "granular-dsmc: t.nml:16: &output: file: 'out.h5' exists, and whether it is an output of "
                       "granular-dsmc is not known: the HDF5 library had not finished reading it after 1 s: the file is "
                       "damaged, or on a very slow disk (GDSMC_READ_LIMIT=SECONDS allows longer); choose another file, "
                       "or give --force to replace it\n");
  EXPECT_EQ(read_text(dir / "out.h5"), before);
  EXPECT_EQ(files(), (std::vector<std::string>{"out.h5", "t.nml"}));
}

// Without --quiet and with stderr not a terminal (a job script's log), the progress lines end themselves: the
// interrupt is one line, not an empty line and then the message.
TEST_F(CliDsmc, AnInterruptIsOneLineInALogFile) {
  const auto [status, seconds] = interrupt_an_endless_run(*this, 1500000, "  file = 'out.h5', n_samples = 3, checkpoint_every = 0.2",
                                                          "  t_end = 1e30, allow_long_run = .true., replicas = 1",
                                                          "  restitution = 0.9", false);
  EXPECT_EQ(status, 130);
  const std::string err = read_text(capture / "stderr");
  const std::string message = "granular-dsmc: interrupted: no output written; resume with --restart out.checkpoint.h5\n";
  ASSERT_GE(err.size(), message.size()) << err;
  EXPECT_EQ(err.substr(err.size() - message.size()), message);
  EXPECT_EQ(err.find("\n\n"), std::string::npos) << err;  // no empty line
  EXPECT_NE(err.front(), '\n') << err;
}

// The summary's overall rate is this process's: after --restart the events the checkpoint held (made by
// the interrupted process) are left out, and the line says so (it divided every event by the resumed
// process's wall time: an elastic gas of 2000 particles, 4e7 events (about 7 s here), interrupted at its
// first checkpoint, 0.2 s in; under the sanitizers, where 4e7 events took 198 s, 4e6 events).
TEST_F(CliDsmc, TheOverallRateAfterARestartCountsTheEventsSinceTheRestart) {
  const std::string end = gdsmc::test::sanitized ? "  collisions_per_particle = 4000, replicas = 1"
                                                 : "  collisions_per_particle = 40000, replicas = 1";
  const auto [status, seconds] = interrupt_an_endless_run(*this, 0, "  file = 'out.h5', n_samples = 3, checkpoint_every = 0.2",
                                                          end, "  restitution = 1.0");
  ASSERT_EQ(status, 130) << read_text(capture / "stderr");
  const Result resumed = run("granular-dsmc", "t.nml --restart out.checkpoint.h5");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_TRUE(std::regex_search(resumed.err, std::regex("collisions/s per thread in the collision loop \\([0-9.e+]+/s "
                                                        "overall since the restart\\)"))) << resumed.err;
  const Result fresh = run("granular-dsmc", "t.nml --force --set dsmc:collisions_per_particle=100");
  ASSERT_EQ(fresh.status, 0) << fresh.err;
  EXPECT_EQ(fresh.err.find("since the restart"), std::string::npos) << fresh.err;
}

// A checkpoint belongs to its run: a fresh run over an interrupted run's checkpoint, another input's,
// or a file that is no checkpoint is refused in one line (the checkpoint would be replaced); with
// --force it runs, and deletes at its end only a checkpoint it wrote itself, never the other run's.
TEST_F(CliDsmc, ACheckpointOfAnotherRunIsNeitherReplacedNorDeleted) {
  ASSERT_EQ(interrupt_an_endless_run(*this, 1500000).first, 130);
  ASSERT_TRUE(fs::exists(dir / "out.checkpoint.h5"));
  const std::string before = read_text(dir / "out.checkpoint.h5");
  const std::vector<std::string> left{"out.checkpoint.h5", "t.nml"};
  expect_input_error(run("granular-dsmc", "t.nml --quiet"), "granular-dsmc",
                     "t.nml:16: &output: file: 'out.checkpoint.h5' holds the checkpoint of an interrupted run of this "
                     "input: resume it with --restart out.checkpoint.h5, or give --force",
                     {}, left);
  expect_input_error(run("granular-dsmc", "t.nml --quiet --set dsmc:seed=9"), "granular-dsmc",
                     "t.nml:16: &output: file: 'out.checkpoint.h5' holds the checkpoint of a run of another input", {}, left);
  // --force, a short run (no checkpoint of its own): the interrupted run's checkpoint is still there.
  const Result forced = run("granular-dsmc", "t.nml --quiet --force --set dsmc:t_end=1.0");
  EXPECT_EQ(forced.status, 0) << forced.err;
  EXPECT_EQ(read_text(dir / "out.checkpoint.h5"), before);
  EXPECT_EQ(files(), (std::vector<std::string>{"out.checkpoint.h5", "out.h5", "t.nml"}));
  // Not a checkpoint at all: refused, and kept with --force.
  fs::remove(dir / "out.h5");
  write("out.checkpoint.h5", "my notes");
  expect_input_error(run("granular-dsmc", "t.nml --quiet --set dsmc:t_end=1.0"), "granular-dsmc",
                     "t.nml:16: &output: file: 'out.checkpoint.h5' exists and is not a checkpoint of granular-dsmc", {},
                     left);
  EXPECT_EQ(run("granular-dsmc", "t.nml --quiet --force --set dsmc:t_end=1.0").status, 0);
  EXPECT_EQ(read_text(dir / "out.checkpoint.h5"), "my notes");
}

// Two runs on one output: the second is refused in one line naming the first's process (the lock of
// io/file_lock.hpp, held here by the test itself); the lock file is gone once its holder ends.
TEST_F(CliDsmc, ASecondRunOnTheSameOutputIsRefused) {
  {
    const gdsmc::io::FileLock lock((dir / "out.lock").string());
    ASSERT_TRUE(lock.held());
    expect_input_error(dsmc(base()), "granular-dsmc",
                       "t.nml:16: &output: file: cannot write output file 'out.h5': another run (process " +
                           std::to_string(::getpid()) + ") is writing it (lock file 'out.lock')",
                       {}, {"out.lock", "t.nml"});
  }
  EXPECT_FALSE(fs::exists(dir / "out.lock"));
  const Result r = dsmc(base());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"out.h5", "t.nml"}));
  // A stale lock file of a killed run (a process id, no lock held) is taken and removed at the end.
  write("out.lock", "4194300\n");
  EXPECT_EQ(dsmc(base()).status, 0);
  EXPECT_EQ(files(), (std::vector<std::string>{"out.h5", "t.nml"}));
  // A user's file, a link or a FIFO at the lock's path is neither truncated nor removed: refused.
  write("out.lock", "my notes");
  expect_input_error(dsmc(base()), "granular-dsmc",
                     "t.nml:16: &output: file: cannot write output file 'out.h5': 'out.lock' exists and is not a lock "
                     "file of granular-dsmc",
                     {}, {"out.h5", "out.lock", "t.nml"});
  EXPECT_EQ(read_text(dir / "out.lock"), "my notes");
  fs::remove(dir / "out.lock");
  fs::create_symlink("/nonexistent/x", dir / "out.lock");
  expect_input_error(dsmc(base()), "granular-dsmc", "t.nml:16: &output: file: cannot write output file 'out.h5': ",
                     {"not a regular file"}, {"out.h5", "out.lock", "t.nml"});
  EXPECT_TRUE(fs::is_symlink(dir / "out.lock"));
}

/// Sets the scalar string attribute `name` of `object` in `file` (replacing it).
void set_string_attribute(const std::string& file, const std::string& object, const char* name, const std::string& value) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t o = H5Oopen(f, object.c_str(), H5P_DEFAULT);
  ASSERT_GE(o, 0) << object;
  if (H5Aexists(o, name) > 0) {
    ASSERT_GE(H5Adelete(o, name), 0);
  }
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(o, name, type, scalar, H5P_DEFAULT, H5P_DEFAULT);
  const char* text = value.c_str();
  ASSERT_GE(H5Awrite(a, type, &text), 0);
  H5Aclose(a);
  H5Sclose(scalar);
  H5Tclose(type);
  H5Oclose(o);
  H5Fclose(f);
}

/// Replaces the first value (with `every`, every value) of dataset `name` of the checkpoint unit `unit`
/// (reals or integers) by `value`, or with `remove_it` removes the dataset and its name from the unit's
/// list, and signs the result with a valid checksum (run/checkpoint.hpp content_checksum): a forgery that
/// the checksum cannot catch, only the check of each field.
void forge_checkpoint(const std::string& file, const std::string& unit, const std::string& name, double value,
                      bool remove_it, bool every = false) {
  const std::string dataset = unit + "/" + name;
  if (remove_it) {
    for (const char* list : {"reals", "integers"}) {
      std::string names = gdsmc::io::h5md::read_string_attribute(file, unit, list);
      const auto at = names.find(name + "\n");
      if (at == std::string::npos) continue;
      names.erase(at, name.size() + 1);
      set_string_attribute(file, unit, list, names);
    }
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(H5Ldelete(f, dataset.c_str(), H5P_DEFAULT), 0) << dataset;
    H5Fclose(f);
  } else {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
    ASSERT_GE(d, 0) << dataset;
    const hid_t space = H5Dget_space(d);
    std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    ASSERT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    values.at(0) = value;  // (converted to the dataset's type: uint64 for integers)
    if (every) std::fill(values.begin(), values.end(), value);
    ASSERT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    H5Sclose(space);
    H5Dclose(d);
    H5Fclose(f);
  }
  set_string_attribute(file, "/checkpoint", "checksum", gdsmc::simulation::content_checksum(file));
}

// A --restart with other options than the interrupted run's is refused in one line that names both sets
// of options (the checkpoint's fingerprint holds them), or says that the namelist text differs; the
// interrupt's line of a run given options names them, shell-quoted, as the resumed run needs them.
TEST_F(CliDsmc, ARestartWithOtherOptionsSaysWhichDiffer) {
  ASSERT_EQ(interrupt_an_endless_run(*this, 1500000).first, 130);
  const Result other = run("granular-dsmc", "t.nml --quiet --restart out.checkpoint.h5 --set dsmc:seed=9", 60);
  EXPECT_EQ(other.status, 2) << other.err;
  EXPECT_EQ(other.err, "granular-dsmc: --restart: checkpoint 'out.checkpoint.h5' was written for a different input: it "
                       "was written with no --set or --output, this run has --set dsmc:seed=9\n");
  write("t.nml", read_text(dir / "t.nml") + "! a comment\n");
  const Result text = run("granular-dsmc", "t.nml --quiet --restart out.checkpoint.h5", 60);
  EXPECT_EQ(text.status, 2) << text.err;
  EXPECT_EQ(text.err, "granular-dsmc: --restart: checkpoint 'out.checkpoint.h5' was written for a different input: "
                      "the namelist text differs\n");
  EXPECT_EQ(gdsmc::simulation::override_options({"dsmc:seed=9", "output:file='my run.h5'", "a:b=\"$x\""}),
            "--set dsmc:seed=9 --set \"output:file='my run.h5'\" --set \"a:b=\\\"\\$x\\\"\"");
  EXPECT_EQ(gdsmc::io::namelist::shell_word("out.checkpoint.h5"), "out.checkpoint.h5");
  EXPECT_EQ(gdsmc::io::namelist::shell_word("my run.checkpoint.h5"), "\"my run.checkpoint.h5\"");
  EXPECT_EQ(gdsmc::io::namelist::shell_word(""), "\"\"");
  EXPECT_EQ(gdsmc::io::namelist::shell_word("output:author='a b!'"), R"('output:author='\''a b!'\''')");
}

// Checkpoints with a valid checksum but a forged field: velocities of 1e300 (the restart never ended),
// a next_sample beyond the samples recorded (an output of NaN errors), a missing array, a stream of four
// zero words (its fixed point: a direction drawn by rejection never ended, deaf to Ctrl-C), a gas at rest
// (no collision could come: infinite times), a credit beyond the time or a negative time or bound. Each is
// refused in one line with exit 2 before the unit runs.
TEST_F(CliDsmc, AForgedCheckpointFieldIsRefusedByItsCheck) {
  ASSERT_EQ(interrupt_an_endless_run(*this, 1500000).first, 130);
  const fs::path original = dir / "original.h5";
  fs::copy_file(dir / "out.checkpoint.h5", original);
  const std::string unit = "/checkpoint/running/unit_0";
  const std::vector<std::tuple<std::string, double, bool, std::string, bool>> forgeries{
      {"particles/velocity", 1e300, false, "m v^2 beyond 1e30 times the largest initial temperature", false},
      {"replica/next_sample", 99.0, false, "'replica/next_sample' is 99 but the record holds", false},
      {"gas/c_sum", 0.0, true, "'gas/c_sum' is missing", false},
      {"collider/transfer", 0.0, true, "'collider/transfer' is missing", false},
      {"collider/generator", 0.0, false, "a generator state of four zero words", true},
      {"particles/velocity", 0.0, false, "every particle is at rest", true},
      {"collider/credit", 1e300, false, "a credit exceeds the time", false},
      {"collider/time", -1.0, false, "the saved time or credit is negative", false},
      {"collider/max_speed2", -1.0, false, "speed bound is negative", false},
  };
  for (const auto& [name, value, remove_it, message, every] : forgeries) {
    fs::copy_file(original, dir / "out.checkpoint.h5", fs::copy_options::overwrite_existing);
    forge_checkpoint((dir / "out.checkpoint.h5").string(), unit, name, value, remove_it, every);
    const Result r = run("granular-dsmc", "t.nml --quiet --restart out.checkpoint.h5", 60);  // (an endless run)
    EXPECT_EQ(r.status, 2) << name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("granular-dsmc: --restart: the checkpoint is damaged: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
}

// Forged fields of a blocked run's checkpoint (31 blocks of 64 of its 2000 particles): a negative block credit
// or step time is refused (exit 2); block bounds forged to zero in a collision-driven run, under which no
// collision can come, end it in one line (exit 1) instead of samples at infinite times.
TEST_F(CliDsmc, AForgedBlockedCheckpointIsRefusedOrEndsInOneLine) {
  ASSERT_EQ(interrupt_an_endless_run(*this, 1500000, "  file = 'out.h5', n_samples = 3, checkpoint_every = 0.2",
                                     "  collisions_per_particle = 1e9, allow_long_run = .true., replicas = 1, "
                                     "block_size = 64")
                .first,
            130);
  const fs::path original = dir / "original.h5";
  fs::copy_file(dir / "out.checkpoint.h5", original);
  const std::string unit = "/checkpoint/running/unit_0";
  // (the run cooled to t ~ 1e23: a credit's round-off allowance, 1e-9 of the time, is ~1e14 there)
  const std::vector<std::tuple<std::string, double, int, std::string, bool>> forgeries{
      {"collider/block_credit", -1e300, 2, "the checkpoint is damaged: collide: the saved time or credit is negative",
       false},
      {"collider/next_step_time", -1.0, 2,
       "the checkpoint is damaged: collide: a saved step time or speed bound is negative", false},
      {"collider/block_max_speed2", 0.0, 1, "collide: every speed bound is zero, so no collision can come", true},
  };
  for (const auto& [name, value, status, message, every] : forgeries) {
    fs::copy_file(original, dir / "out.checkpoint.h5", fs::copy_options::overwrite_existing);
    forge_checkpoint((dir / "out.checkpoint.h5").string(), unit, name, value, false, every);
    const Result r = run("granular-dsmc", "t.nml --quiet --restart out.checkpoint.h5", 60);
    EXPECT_EQ(r.status, status) << name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
}

// A speed forged 1e8-fold in a blocked run's checkpoint makes the one-species kernel's sub-step hours long
// (its bound rises within it, and the candidates' rate with it): Ctrl-C still ends the resumed run within
// seconds, as the kernel looks at the flag between chunks of 2^20 candidates.
TEST_F(CliDsmc, AForgedFastParticleStillStopsAtSigint) {
  // (elastic: the speeds stay about 1, so that 1e8 raises a block's bound 1e8-fold, some 1e11 candidates; in a
  // gas cooled for ever the count would pass 2^64)
  ASSERT_EQ(interrupt_an_endless_run(*this, 1500000, "  file = 'out.h5', n_samples = 3, checkpoint_every = 0.2",
                                     "  t_end = 1e30, allow_long_run = .true., replicas = 1, block_size = 64",
                                     "  restitution = 1.0")
                .first,
            130);
  forge_checkpoint((dir / "out.checkpoint.h5").string(), "/checkpoint/running/unit_0", "particles/velocity", 1e8, false);
  const pid_t pid = start_restart(*this);
  ASSERT_GE(pid, 0);
  ::usleep(1500000);
  const Ended ended = interrupt_and_wait(pid);
  EXPECT_TRUE(ended.by_itself) << "the resumed run did not end within 10 s of SIGINT";
  // (130, or 1 when the sample after the stop finds the energy the forged speed brought: either in one line)
  ASSERT_TRUE(WIFEXITED(ended.status));
  EXPECT_TRUE(WEXITSTATUS(ended.status) == 130 || WEXITSTATUS(ended.status) == 1) << WEXITSTATUS(ended.status);
}

// A whole time series deleted from a running unit's record (valid checksum): which rows a replica writes
// depends on the input, so the record alone cannot tell; the first sample after the restart has one row
// of it where the others have all, and the run stops there (exit 2, one line), not at its end; the other
// replica, on the other thread, stops with it. An elastic run of 2000 samples (one every 250 collisions
// per particle), 2 replicas, interrupted once its first checkpoint exists.
TEST_F(CliDsmc, ARowDeletedFromARunningUnitIsRefusedAtTheNextSample) {
  ASSERT_EQ(interrupt_an_endless_run(*this, 1000000, "  file = 'out.h5', n_samples = 2000, checkpoint_every = 0.2",
                                     "  collisions_per_particle = 5e5, replicas = 2", "  restitution = 1.0").first,
            130);
  // Each unit saves its own state at its safe points (run/checkpoint.hpp): on a slow build the file may
  // hold the other thread's unit only. The first unit the file holds is the one forged.
  const std::string file = (dir / "out.checkpoint.h5").string();
  std::string unit;
  for (const char* name : {"/checkpoint/running/unit_0", "/checkpoint/running/unit_1"}) {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    const bool held = H5Lexists(f, "/checkpoint/running", H5P_DEFAULT) > 0 && H5Lexists(f, name, H5P_DEFAULT) > 0;
    H5Fclose(f);
    if (held) {
      unit = name;
      break;
    }
  }
  ASSERT_FALSE(unit.empty()) << "no running unit in " << file;
  forge_checkpoint(file, unit, "result/rows/total_temperature", 0.0, true);
  const auto started = std::chrono::steady_clock::now();
  const Result r = run("granular-dsmc", "t.nml --quiet --restart out.checkpoint.h5", 60);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 20.0);  // not the whole run
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("granular-dsmc: --restart: the checkpoint is damaged: row 'total_temperature' holds", 0), 0u)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.h5"));
}

TEST_F(CliDsmc, ADamagedCheckpointIsRefusedAsDamaged) {
  ASSERT_EQ(interrupt_an_endless_run(*this, 2500000).first, 130);
  ASSERT_TRUE(fs::exists(dir / "out.checkpoint.h5"));
  // One velocity changed in place (HDF5 itself sees nothing wrong): refused as damaged.
  const std::string file = (dir / "out.checkpoint.h5").string();
  const std::string group = "/checkpoint/running/unit_0";
  std::istringstream names(gdsmc::io::h5md::read_string_attribute(file, group, "reals"));
  bool changed = false;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  for (std::string name; !changed && std::getline(names, name);) {
    const hid_t d = H5Dopen2(f, (group + "/" + name).c_str(), H5P_DEFAULT);
    ASSERT_GE(d, 0);
    const hid_t space = H5Dget_space(d);
    std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    if (!values.empty()) {  // the first non-empty one
      ASSERT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
      values[0] = values[0] * 0.5 + 1.0;
      ASSERT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
      changed = true;
    }
    H5Sclose(space);
    H5Dclose(d);
  }
  H5Fclose(f);
  ASSERT_TRUE(changed);
  const Result r = run("granular-dsmc", "t.nml --quiet --restart out.checkpoint.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("--restart: checkpoint 'out.checkpoint.h5' is damaged"), std::string::npos) << r.err;
  // Not a checkpoint at all (the namelist): refused as such.
  const Result n = run("granular-dsmc", "t.nml --quiet --restart t.nml");
  EXPECT_EQ(n.status, 2) << n.err;
  EXPECT_NE(n.err.find("is damaged or is not a checkpoint"), std::string::npos) << n.err;
  EXPECT_EQ(std::count(n.err.begin(), n.err.end(), '\n'), 1) << n.err;
}

TEST_F(CliDsmc, AnEndlessRunIsRefusedWithTheEstimate) {
  auto lines = base_lines;
  lines[12] = "  t_end = 1e30";
  const Result r = dsmc(gdsmc::test::join_lines(lines));
  expect_input_error(r, "granular-dsmc", "t.nml:13: &dsmc: t_end: ",
                     {"collision events per replica", "a cooling to", "Haff's law", "allow_long_run = .true."});
}

// A FIFO at the output path blocked the run at the check for an earlier output (it opened it); it, a
// device and a FIFO given to --restart or --compare= are refused before any work, in one line.
TEST_F(CliDsmc, AFifoOrADeviceIsNeverOpenedOrReplaced) {
  ASSERT_EQ(::mkfifo((dir / "out.h5").c_str(), 0600), 0);
  expect_input_error(dsmc(base()), "granular-dsmc",
                     "t.nml:16: &output: file: cannot write output file 'out.h5': it is a FIFO (named pipe), not a regular file",
                     {}, {"out.h5", "t.nml"});
  expect_input_error(dsmc(base(), "--force"), "granular-dsmc", "t.nml:16: &output: file: cannot write output file 'out.h5': it is a FIFO", {},
                     {"out.h5", "t.nml"});
  expect_input_error(dsmc(base(), "--output /dev/null"), "granular-dsmc",
                     "--output /dev/null: &output: file: cannot write output file '/dev/null': it is a device, not a regular file", {}, {"out.h5", "t.nml"});
  // A folder that takes no new file (procfs, even for root) gave HDF5's own report: the system's reason now.
  expect_input_error(dsmc(base(), "--output /proc/x.h5"), "granular-dsmc",
                     "--output /proc/x.h5: &output: file: cannot write output file '/proc/x.h5': cannot create a file in "
                     "'/proc': ",
                     {}, {"out.h5", "t.nml"});
  expect_input_error(dsmc(base(), "--restart out.h5 --output x.h5"), "granular-dsmc",
                     "--restart: 'out.h5' is a FIFO (named pipe), not a checkpoint file", {}, {"out.h5", "t.nml"});
  expect_input_error(dsmc(base(), "--output x.h5 --compare=out.h5"), "granular-dsmc",
                     "--compare=out.h5: cannot write the JSON file: it is a FIFO (named pipe), not a regular file", {},
                     {"out.h5", "t.nml"});
}

// n_particles = 2e9 is allowed, and ended in std::bad_alloc (exit 1) after start; a run whose particles
// and samples alone cannot fit (here under ulimit -v 4 GB: 1e9 particles x 28 bytes) is refused before any work.
TEST_F(CliDsmc, ARunThatCannotFitInMemoryIsRefusedWithTheEstimate) {
  AddressSpaceLimit limit(4000000000ull);
  if (!limit.skip.empty()) GTEST_SKIP() << limit.skip;
  const Result r = dsmc(base(), "--set dsmc:n_particles=1000000000 --set dsmc:replicas=1");
  // The sample rows count too (64 bytes per species and sample, every replica's on rank 0): 1e5 species
  // and 1000 samples of one replica need 6.4 GB beside 5.6 MB of particles.
  write("t.nml", many_species_namelist(100000, 200000, 1000));
  const Result rows = run("granular-dsmc", "t.nml --quiet");
  limit.restore();
  expect_input_error(r, "granular-dsmc", "--set dsmc:n_particles=1000000000: &dsmc: n_particles: ",
                     {"need about 28 GB", "more than the address-space limit (ulimit -v) (4 GB)"});
  expect_input_error(rows, "granular-dsmc", "t.nml:8: &output: n_samples: ",
                     {"need about 5.6 MB, the samples' rows of every replica 6.4 GB", "(4 GB)"});
}

TEST_F(CliDsmc, EmptyFileBomNulAndRestartDirectory) {
  expect_input_error(dsmc(""), "granular-dsmc", "t.nml: is empty", {"&system"});
  write("t.nml", "\xEF\xBB\xBF" + base());
  EXPECT_EQ(run("granular-dsmc", "t.nml --quiet").status, 0);
  fs::remove(dir / "out.h5");
  expect_input_error(dsmc(base() + std::string("\0", 1)), "granular-dsmc", "t.nml:18: contains a NUL byte", {});
  fs::create_directory(dir / "cp");
  const Result r = dsmc(base(), "--restart cp");
  expect_input_error(r, "granular-dsmc", "--restart: 'cp' is a directory", {}, {"cp", "t.nml"});
}

TEST_F(CliDsmc, AWriteFailureIsOneLineAndLeavesNoFile) {
  // A file size limit (as a full disk: every write fails) while the output, or a checkpoint, is
  // written: one line, exit 1 (2 when not even the file can be created), no file left, no crash
  // at exit (HDF5's shutdown used to segfault after the failed close).
  auto checkpointed = gdsmc::test::base_namelist_lines("  file = 'out.h5', n_samples = 5, checkpoint_every = 0.001");
  checkpointed[11] = "  n_particles = 20000";
  // (8 KB and up: LLVM's OpenMP runtime needs a few KB of shared memory to start at all.)
  for (const auto& [limit, text, expected] :
       {std::tuple{"8", base(), "cannot write output file 'out.h5'"},
        std::tuple{"100", gdsmc::test::join_lines(checkpointed), "cannot write output file 'out.checkpoint.h5'"}}) {
    write("t.nml", text);
    // HDF5 keeps what it allocated for a file whose close failed: LeakSanitizer (in a sanitizer
    // build) would turn that into exit status 23.
    const std::string command = "cd " + quoted(dir.string()) + " && (ulimit -f " + limit +
                                " && ASAN_OPTIONS=detect_leaks=0 exec " +
                                quoted((fs::path(GDSMC_BIN_DIR) / "granular-dsmc").string()) +
                                " t.nml --quiet) >" + quoted((capture / "stdout").string()) + " 2>" +
                                quoted((capture / "stderr").string()) + " </dev/null";
    const int raw = std::system(command.c_str());
    ASSERT_TRUE(raw != -1 && WIFEXITED(raw)) << "killed by a signal: " << raw;
    const int status = WEXITSTATUS(raw);
    const std::string err = read_text(capture / "stderr");
    EXPECT_TRUE(status == 1 || status == 2) << status << " " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find(expected), std::string::npos) << err;
    EXPECT_NE(err.find("File too large"), std::string::npos) << err;
    EXPECT_EQ(files(), (std::vector<std::string>{"t.nml"})) << "limit " << limit;
  }
}

// The version of the build (\ref output_h5md "docs/output.md"): --version prints it, and the output
// file records the same in /h5md/creator@version; the project's version, then "+" and git describe
// when built from a git checkout.
TEST_F(CliDsmc, VersionIsTheBuildVersionAlsoInTheFile) {
  const std::string version = gdsmc::io::build_version();
  EXPECT_TRUE(std::regex_match(version, std::regex("[0-9]+\\.[0-9]+\\.[0-9]+(\\+[A-Za-z0-9._-]+)?"))) << version;
  const Result v = run("granular-dsmc", "--version");
  EXPECT_EQ(v.status, 0);
  EXPECT_EQ(v.out, "granular-dsmc " + version + "\n");
  const Result r = dsmc(base());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(gdsmc::io::h5md::read_string_attribute((dir / "out.h5").string(), "/h5md/creator", "version"), version);
}

// Threads a single replica cannot use are said once on stderr (not with --quiet), never idle silently:
// `pairs` has no cache blocks; a blocked run uses them (collide.hpp, "Threads inside one replica").
TEST_F(CliDsmc, IdleThreadsOfOneReplicaAreNoted) {
  ::setenv("OMP_NUM_THREADS", "2", 1);
  write("t.nml", base());
  const Result unblocked = run("granular-dsmc", "t.nml --set dsmc:replicas=1 --set \"dsmc:scheme='pairs'\"");
  const Result blocked = run("granular-dsmc", "t.nml --force --set dsmc:replicas=1 --set dsmc:n_particles=4000 "
                                              "--set dsmc:block_size=1000");
  const Result quiet = run("granular-dsmc", "t.nml --force --quiet --set dsmc:replicas=1 --set \"dsmc:scheme='pairs'\"");
  ::unsetenv("OMP_NUM_THREADS");
  ASSERT_EQ(unblocked.status, 0) << unblocked.err;
  EXPECT_NE(unblocked.err.find("note: 1 of the 2 threads per work unit stay idle: this run has no cache blocks"),
            std::string::npos) << unblocked.err;
  ASSERT_EQ(blocked.status, 0) << blocked.err;
  EXPECT_EQ(blocked.err.find("stay idle"), std::string::npos) << blocked.err;
  ASSERT_EQ(quiet.status, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("stay idle"), std::string::npos) << quiet.err;
}

TEST_F(CliDsmc, Help) {
  const Result r = run("granular-dsmc", "--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("usage:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--compare=F.json"), std::string::npos) << r.out;
}

// ---------------------------------------------------------------------------------------------
// granular-dsmc: bad input. Exit 2, one line naming FILE:LINE, &group and variable, no file left.
// ---------------------------------------------------------------------------------------------

TEST_F(CliDsmc, UnknownVariable) {
  expect_input_error(dsmc(with_line(6, "  restituion = 0.5")), "granular-dsmc",
                     "t.nml:6: &system: restituion: ",
                     {"unknown variable", "did you mean 'restitution'"});
}

TEST_F(CliDsmc, UnknownGroup) {
  expect_input_error(dsmc(with_line(8, "&inital")), "granular-dsmc", "t.nml:8: &inital: ",
                     {"unknown group", "did you mean '&initial'"});
}

TEST_F(CliDsmc, WrongTypeRealForInteger) {
  expect_input_error(dsmc(with_line(12, "  n_particles = 1.5")), "granular-dsmc",
                     "t.nml:12: &dsmc: n_particles: ", {"expected an integer", "'1.5'"});
}

TEST_F(CliDsmc, WrongTypeStringForNumber) {
  expect_input_error(dsmc(with_line(3, "  mass = 'heavy', 10.0")), "granular-dsmc",
                     "t.nml:3: &system: mass: ", {"expected a real number", "'heavy'"});
}

TEST_F(CliDsmc, WrongTypeLogical) {
  expect_input_error(dsmc(with_line(6, "  restitution = 0.5, enskog = 'yes'")), "granular-dsmc",
                     "t.nml:6: &system: enskog: ", {"expected a logical"});
}

TEST_F(CliDsmc, WrongArrayLength) {
  expect_input_error(dsmc(with_line(3, "  mass = 1.0, 10.0, 3.0")), "granular-dsmc",
                     "t.nml:3: &system: mass: ", {"expected 2 value(s)", "got 3"});
}

TEST_F(CliDsmc, ZeroMass) {
  expect_input_error(dsmc(with_line(3, "  mass = 0.0, 10.0")), "granular-dsmc",
                     "t.nml:3: &system: mass: ", {"mass = 0.0 is outside"});
}

TEST_F(CliDsmc, NegativeDiameter) {
  expect_input_error(dsmc(with_line(4, "  diameter = 1.0, -1.0")), "granular-dsmc",
                     "t.nml:4: &system: diameter: ", {"diameter = -1.0 is outside"});
}

TEST_F(CliDsmc, RestitutionAboveOne) {
  expect_input_error(dsmc(with_line(6, "  restitution = 1.3")), "granular-dsmc",
                     "t.nml:6: &system: restitution: ", {"restitution = 1.3 is outside [0, 1]"});
}

TEST_F(CliDsmc, RestitutionPairMissing) {
  expect_input_error(dsmc(with_line(6, "  restitution(1,1) = 0.9, restitution(1,2) = 0.5")),
                     "granular-dsmc", "t.nml:6: &system: restitution: ",
                     {"restitution(2,2)", "not given"});
}

TEST_F(CliDsmc, MissingGroup) {
  auto lines = base_lines;
  lines.erase(lines.begin() + 10, lines.begin() + 14);  // &dsmc ... /
  // A missing group has no line of its own: the message names the file and the group.
  expect_input_error(dsmc(gdsmc::test::join_lines(lines)), "granular-dsmc", "t.nml: &dsmc: ",
                     {"required group is missing"});
}

TEST_F(CliDsmc, MissingVariable) {
  expect_input_error(dsmc(with_line(5, "")), "granular-dsmc", "t.nml:1: &system: number_density: ",
                     {"required variable is missing"});
}

TEST_F(CliDsmc, UnterminatedString) {
  expect_input_error(dsmc(with_line(16, "  file = 'out.h5, n_samples = 3")), "granular-dsmc",
                     "t.nml:16: &output: file: ", {"unterminated string"});
}

TEST_F(CliDsmc, UnterminatedGroup) {
  expect_input_error(dsmc(with_line(17, "")), "granular-dsmc", "t.nml:15: &output: ",
                     {"unterminated group"});
}

TEST_F(CliDsmc, TooFewParticlesForADiluteSpecies) {
  expect_input_error(dsmc(with_line(5, "  number_density = 0.02, 0.0001")), "granular-dsmc",
                     "t.nml:12: &dsmc: n_particles: ", {"species 2", "at least 2 per species"});
}

TEST_F(CliDsmc, NegativeEnd) {
  expect_input_error(dsmc(with_line(13, "  t_end = -1")), "granular-dsmc", "t.nml:13: &dsmc: t_end: ",
                     {"t_end = -1 is outside"});
}

TEST_F(CliDsmc, NeitherEnd) {
  expect_input_error(dsmc(with_line(13, "")), "granular-dsmc", "t.nml:11: &dsmc: t_end: ",
                     {"exactly one of t_end and collisions_per_particle"});
}

TEST_F(CliDsmc, BadChoice) {
  expect_input_error(dsmc(with_line(12, "  n_particles = 200, scheme = 'bird'")), "granular-dsmc",
                     "t.nml:12: &dsmc: scheme: ", {"'bird' is not one of"});
}

TEST_F(CliDsmc, FirstSampleWithLinearSpacing) {
  expect_input_error(dsmc(with_line(16, "  file = 'out.h5', n_samples = 3, first_sample = 1.0")),
                     "granular-dsmc", "t.nml:16: &output: first_sample: ",
                     {"only used with spacing = 'log'"});
}

TEST_F(CliDsmc, UnwritableOutputInTheNamelist) {
  expect_input_error(dsmc(with_line(16, "  file = '/nonexistent-dir/x.h5', n_samples = 3")),
                     "granular-dsmc", "t.nml:16: &output: file: ",
                     {"cannot write", "/nonexistent-dir/x.h5"});
}

TEST_F(CliDsmc, UnwritableOutputInAMissingSubdirectory) {
  expect_input_error(dsmc(with_line(16, "  file = 'missing/x.h5', n_samples = 3")), "granular-dsmc",
                     "t.nml:16: &output: file: ", {"cannot write", "missing/x.h5"});
}

TEST_F(CliDsmc, OutputIsADirectory) {
  // Must fail before the run, not when the finished run cannot be renamed into place.
  fs::create_directory(dir / "taken");
  expect_input_error(dsmc(with_line(16, "  file = 'taken', n_samples = 3")), "granular-dsmc",
                     "t.nml:16: &output: file: ", {"cannot write", "'taken'", "directory"},
                     {"t.nml", "taken"});
  EXPECT_TRUE(fs::is_empty(dir / "taken"));
}

TEST_F(CliDsmc, UnwritableOutputOption) {
  expect_input_error(dsmc(base(), "--output /nonexistent-dir/x.h5"), "granular-dsmc",
                     "--output /nonexistent-dir/x.h5: &output: file: ",
                     {"cannot write", "/nonexistent-dir/x.h5"});
}

TEST_F(CliDsmc, UnwritableOutputOverrideNamesTheOverride) {
  // Another override of &output must not take the blame, nor the file's line numbers.
  expect_input_error(dsmc(base(), "--set output:n_samples=4 --set \"output:file='/nonexistent-dir/x.h5'\""),
                     "granular-dsmc", "--set output:file='/nonexistent-dir/x.h5': &output: file: ",
                     {"cannot write"});
}

TEST_F(CliDsmc, UnwritableOutputInTheFileWithAnotherOverride) {
  expect_input_error(dsmc(with_line(16, "  file = '/nonexistent-dir/x.h5', n_samples = 3"),
                          "--set output:n_samples=4"),
                     "granular-dsmc", "t.nml:16: &output: file: ", {"cannot write"});
}

TEST_F(CliDsmc, BadOverride) {
  expect_input_error(dsmc(base(), "--set dsmc:n_particles=1.5"), "granular-dsmc",
                     "--set dsmc:n_particles=1.5: &dsmc: n_particles: expected an integer, got a real number '1.5'\n",
                     {});
  // A whole number written as a real says the integer to write; an unquoted string, the form a shell
  // passes on (its quotes in quotes); in a namelist file, the quoted value alone.
  const Result real = dsmc(base(), "--set dsmc:n_particles=1e4");
  EXPECT_EQ(real.err, "granular-dsmc: --set dsmc:n_particles=1e4: &dsmc: n_particles: expected an integer, got a real "
                      "number '1e4' (write 10000)\n");
  const Result word = dsmc(base(), "--set dsmc:scheme=lowrank");
  EXPECT_EQ(word.err, "granular-dsmc: --set dsmc:scheme=lowrank: &dsmc: scheme: bad value 'lowrank': an unquoted word is "
                      "not a value (a string needs quotes: 'lowrank', on a command line --set \"dsmc:scheme='lowrank'\"; "
                      "logicals are .true. or .false.)\n");
  const Result in_file = dsmc(with_line(12, "  n_particles = 200, scheme = majorant"));
  EXPECT_NE(in_file.err.find("bad value 'majorant': an unquoted word is not a value (a string needs quotes: 'majorant'; "
                             "logicals"),
            std::string::npos)
      << in_file.err;
}

TEST_F(CliDsmc, MissingInputFile) {
  const Result r = run("granular-dsmc", "absent.nml --quiet");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("granular-dsmc: absent.nml: cannot open", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(files(), std::vector<std::string>{});
}

TEST_F(CliDsmc, UnknownOptionOrNoInput) {
  write("t.nml", base());
  const Result r = run("granular-dsmc", "t.nml --bogus");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown option --bogus"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line, not the whole usage:\n" << r.err;
  // No input, an empty argument (the fuzzer's ""), an option without its value: one line each, not the
  // whole usage (--help prints that), for both programs.
  for (const char* tool : {"granular-dsmc", "granular-theory"})
    for (const char* args : {"", "''", "t.nml ''", "t.nml --set", "t.nml \"$(printf '%s\\n%s' --output=new line.h5)\"",
                             "t.nml \"$(printf 'b\\nc')\""}) {  // (the last two: a line break inside an argument)
      const Result bad = run(tool, args);
      EXPECT_EQ(bad.status, 2) << tool << " " << args;
      EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << tool << " " << args << ":\n" << bad.err;
      EXPECT_EQ(bad.err.rfind(std::string(tool) + ": ", 0), 0u) << bad.err;
    }
  EXPECT_EQ(run("granular-dsmc", "t.nml --output").status, 2);
  EXPECT_EQ(files(), std::vector<std::string>{"t.nml"});
}

// ---------------------------------------------------------------------------------------------
// Sweep tables and --table (issue 17 item 3; analysis/sweep_table.hpp), --print-defaults' restitution line
// ---------------------------------------------------------------------------------------------

class CliTable : public CliFixture {};

// An output file whose global heap makes HDF5 loop (damage_global_heap, the case fuzzing found) is refused by
// --table after the read limit in one line, exit status 2, nothing on stdout.
TEST_F(CliTable, ADamagedFileThatLoopsHdf5IsRefusedInTime) {
  ASSERT_EQ(dsmc(base()).status, 0);
  damage_global_heap(dir / "out.h5", 10);
  const ReadLimit limit("1");
  const Result r = run("granular-dsmc", "--table out.h5", 60);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "granular-dsmc: --table out.h5: the HDF5 library had not finished reading it after 1 s: the file "
                   "is damaged, or on a very slow disk (GDSMC_READ_LIMIT=SECONDS allows longer)\n");
}

TEST_F(CliTable, ElementSweepGivesANumericTableAndCsv) {
  const Result r = dsmc(base() + "&sweep variable = 'system:restitution(1,2)', 'system:mass(2)'\n"
                                 "  values = 0.6, 2.0,  0.9, 5.0 /\n");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto values = gdsmc::io::h5md::read_dataset((dir / "out.h5").string(), "/sweep/values");
  EXPECT_EQ(values.shape, (std::vector<std::size_t>{2, 2}));
  EXPECT_EQ(values.data, (std::vector<double>{0.6, 2.0, 0.9, 5.0}));
  EXPECT_EQ(gdsmc::io::h5md::read_attribute((dir / "out.h5").string(), "/sweep/values", "variables"),
            gdsmc::io::h5md::ParameterValue(std::vector<std::string>{"system:restitution(1,2)", "system:mass(2)"}));
  const auto ratio = gdsmc::io::h5md::read_dataset((dir / "out.h5").string(), "/sweep/results/temperature/value");
  EXPECT_EQ(ratio.shape, (std::vector<std::size_t>{2, 2}));  // points x species
  // The old layout stays: /sweep/point_K with its attributes.
  EXPECT_EQ(gdsmc::io::h5md::read_string_attribute((dir / "out.h5").string(), "/sweep/point_2", "value"),
            "0.9, 5.0");
  const Result t = run("granular-dsmc", "--table out.h5");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(t.err, "");
  std::istringstream lines(t.out);
  std::string header, row1, row2, extra;
  std::getline(lines, header);
  std::getline(lines, row1);
  std::getline(lines, row2);
  EXPECT_FALSE(std::getline(lines, extra));
  EXPECT_EQ(header.rfind("\"system:restitution(1,2)\",system:mass(2),temperature_1,temperature_1_error,", 0), 0u)
      << header;
  EXPECT_NE(header.find("total_temperature"), std::string::npos) << header;
  EXPECT_NE(header.find("sonine_c_2_error"), std::string::npos) << header;
  EXPECT_EQ(row1.rfind("0.6,2,", 0), 0u) << row1;
  EXPECT_EQ(row2.rfind("0.9,5,", 0), 0u) << row2;
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), std::count(row1.begin(), row1.end(), ',') + 1)
      << "the quoted name holds one comma";
}

/// The lines of `text`.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The fields of one CSV line without quoted commas.
std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

TEST_F(CliTable, TableOfARunPrintsEveryTrajectoryWithSpeciesFromOne) {
  ASSERT_EQ(dsmc(base(), "--set dsmc:replicas=2").status, 0);
  const Result r = run("granular-dsmc", "--table out.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto lines = lines_of(r.out);
  const auto temperature = gdsmc::io::h5md::read_observable((dir / "out.h5").string(), "temperature");
  ASSERT_EQ(lines.size(), temperature.time.size() + 1);  // the header, one row per sample
  const auto header = fields_of(lines[0]);
  EXPECT_EQ(header.at(0), "time");
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  for (const char* name : {"temperature_1", "temperature_1_error", "temperature_2", "temperature_2_error",
                           "total_temperature", "sonine_c_2_error", "collisions_pair_1_2", "collisions_per_particle"})
    EXPECT_LT(column(name), header.size()) << name << " missing from " << lines[0];
  EXPECT_EQ(column("temperature_0"), header.size()) << "species count from 1";
  for (std::size_t row = 1; row < lines.size(); ++row) {
    const auto fields = fields_of(lines[row]);
    ASSERT_EQ(fields.size(), header.size()) << lines[row];
    EXPECT_DOUBLE_EQ(std::stod(fields[0]), temperature.time[row - 1]);
    EXPECT_NEAR(std::stod(fields[column("temperature_2")]), temperature.value[(row - 1) * 2 + 1],
                1e-11 * temperature.value[(row - 1) * 2 + 1]);
    EXPECT_NEAR(std::stod(fields[column("temperature_2_error")]), temperature.error[(row - 1) * 2 + 1],
                1e-11 * temperature.error[(row - 1) * 2 + 1] + 1e-300);
  }
}

TEST_F(CliTable, NamedQuantitiesWithTheTheoryOfCompare) {
  ASSERT_EQ(dsmc(base(), "--set dsmc:replicas=1").status, 0);
  const Result r = run("granular-dsmc", "--table out.h5 total_temperature sonine_c --theory");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[0], "time,total_temperature,total_temperature_error,total_temperature_theory,sonine_c_1,"
                      "sonine_c_1_error,sonine_c_2,sonine_c_2_error");
  EXPECT_EQ(lines[1].rfind("0,1,nan,1,", 0), 0u) << lines[1];  // T(0) = 1, one replica: no error
  EXPECT_NE(r.err.find("theory: none for 'sonine_c'"), std::string::npos) << r.err;
  const Result summary = run("granular-dsmc", "--table out.h5 summary");
  ASSERT_EQ(summary.status, 0) << summary.err;
  const auto rows = lines_of(summary.out);
  ASSERT_EQ(rows.size(), 2u) << summary.out;
  EXPECT_EQ(rows[0].rfind("temperature_1,temperature_1_error,temperature_2,", 0), 0u) << rows[0];
  EXPECT_NE(rows[0].find("temperature_over_mean_2,"), std::string::npos) << rows[0];
}

// The columns of a table do not depend on the number of replicas: time_error for a collision-driven run
// only (NaN with one replica; a time-driven run's times differ by the round-off of a mean of equal times,
// which put the column in with 3 replicas and not with 4), and the reduced distribution of one replica
// (no error datasets in the file) with NaN errors; it failed to read the missing error before.
TEST_F(CliTable, TheColumnsDoNotDependOnTheReplicas) {
  for (const char* replicas : {"1", "3", "4"}) {
    SCOPED_TRACE(std::string("replicas = ") + replicas);
    ASSERT_EQ(dsmc(base(), std::string("--set dsmc:replicas=") + replicas).status, 0);
    const Result timed = run("granular-dsmc", "--table out.h5 total_temperature");
    ASSERT_EQ(timed.status, 0) << timed.err;
    EXPECT_EQ(lines_of(timed.out).at(0), "time,total_temperature,total_temperature_error");
    ASSERT_EQ(dsmc(with_line(13, "  collisions_per_particle = 4.0"), std::string("--force --set dsmc:replicas=") + replicas)
                  .status,
              0);
    const Result driven = run("granular-dsmc", "--table out.h5 total_temperature");
    ASSERT_EQ(driven.status, 0) << driven.err;
    const auto lines = lines_of(driven.out);
    EXPECT_EQ(lines.at(0), "time,time_error,total_temperature,total_temperature_error");
    EXPECT_EQ(fields_of(lines.at(2)).at(1) == "nan", std::string(replicas) == "1") << lines.at(2);
    const Result reduced = run("granular-dsmc", std::string(GDSMC_EXAMPLES_DIR) + "/haff.nml --quiet --force --output h.h5 "
                                                "--set dsmc:n_particles=2000 --set dsmc:replicas=" + replicas);
    ASSERT_EQ(reduced.status, 0) << reduced.err;
    const Result table = run("granular-dsmc", "--table h.h5 reduced_distribution");
    ASSERT_EQ(table.status, 0) << table.err;
    const auto rows = lines_of(table.out);
    ASSERT_GE(rows.size(), 3u);
    EXPECT_EQ(rows[0], "v_star,phi_1,phi_1_error,delta_1,delta_1_error,g_1,g_1_error");
    EXPECT_EQ(fields_of(rows[1]).at(2) == "nan", std::string(replicas) == "1") << rows[1];
  }
}

TEST_F(CliTable, RequestsThatCannotBeAnsweredAreRefusedInOneLine) {
  ASSERT_EQ(dsmc(base()).status, 0);
  const std::vector<std::string> both{"out.h5", "t.nml"};
  expect_input_error(run("granular-dsmc", "--table out.h5 bogus"), "granular-dsmc", "--table out.h5: ",
                     {"'bogus' is neither an observable nor a column", "--print-observables"}, both);
  expect_input_error(run("granular-dsmc", "--table out.h5 msd"), "granular-dsmc", "--table out.h5: ",
                     {"'msd' was not measured"}, both);
  expect_input_error(run("granular-dsmc", "--table out.h5 scaling_sonine_c"), "granular-dsmc", "--table out.h5: ",
                     {"not a time series", "summary"}, both);
  expect_input_error(run("granular-dsmc", "--table out.h5 --point 1"), "granular-dsmc", "--table out.h5: ",
                     {"not a sweep"}, both);
  expect_input_error(run("granular-dsmc", "--table out.h5 --point x"), "granular-dsmc", "--table: ",
                     {"--point x"}, both);
  expect_input_error(run("granular-dsmc", "--table out.h5 --bogus"), "granular-dsmc", "--table: ",
                     {"unknown option --bogus"}, both);
  expect_input_error(run("granular-dsmc", "--table out.h5 summary temperature"), "granular-dsmc", "--table out.h5: ",
                     {"alone"}, both);
  expect_input_error(run("granular-dsmc", "--table absent.h5"), "granular-dsmc", "--table absent.h5: ", {"absent.h5"},
                     both);
  expect_input_error(run("granular-dsmc", "--table"), "granular-dsmc", "--table: ", {"no output file"}, both);
}

TEST_F(CliTable, SweepPointsHaveTrajectoriesOfTheirOwn) {
  ASSERT_EQ(dsmc(base() + "&sweep variable = 'system:restitution(1,2)', values = 0.6, 0.9 /\n").status, 0);
  const Result point = run("granular-dsmc", "--table out.h5 --point 2 temperature --theory");
  ASSERT_EQ(point.status, 0) << point.err;
  const auto lines = lines_of(point.out);
  const auto t = gdsmc::io::h5md::read_observable((dir / "out.h5").string(), "/sweep/point_2/observables/temperature");
  ASSERT_EQ(lines.size(), t.time.size() + 1);
  EXPECT_EQ(lines[0], "time,temperature_1,temperature_1_error,temperature_1_theory,temperature_2,temperature_2_error,"
                      "temperature_2_theory");
  EXPECT_NEAR(std::stod(fields_of(lines.back()).at(1)), t.value[t.value.size() - 2], 1e-11 * t.value[t.value.size() - 2]);
  const std::vector<std::string> both{"out.h5", "t.nml"};
  expect_input_error(run("granular-dsmc", "--table out.h5 --point 3"), "granular-dsmc", "--table out.h5: ",
                     {"--point 3", "sweep of 2 points"}, both);
  expect_input_error(run("granular-dsmc", "--table out.h5 temperature"), "granular-dsmc", "--table out.h5: ",
                     {"give --point K"}, both);
  EXPECT_EQ(lines_of(run("granular-dsmc", "--table out.h5 summary").out).size(), 3u);  // the sweep table
  const auto one = lines_of(run("granular-dsmc", "--table out.h5 --point 2 summary").out);  // point 2's row
  ASSERT_EQ(one.size(), 2u);
  EXPECT_EQ(one[0].rfind("temperature_1,", 0), 0u) << one[0];
}

TEST_F(CliTable, SweepVariableThatDoesNotExist) {
  expect_input_error(dsmc(base() + "&sweep variable = 'system:restitutio(1,2)', values = 0.5 /\n"), "granular-dsmc",
                     "t.nml:18: &sweep: variable: ", {"'system:restitutio(1,2)'", "is not 'group:name'"});
}

TEST_F(CliTable, SweepIndexOutOfRange) {
  expect_input_error(dsmc(base() + "&sweep variable = 'system:mass(3)', values = 2.0 /\n"), "granular-dsmc",
                     "t.nml:18: &sweep: variable: ", {"'system:mass(3)'", "index 3 is out of range", "n_species = 2"});
}

TEST_F(CliTable, JointListsOfDifferentLengths) {
  expect_input_error(dsmc(base() + "&sweep variable = 'system:restitution(1,2)', 'system:mass(2)'\n"
                                   "  values(1,1) = 0.6, 0.7, 0.8\n  values(1,2) = 2.0, 3.0 /\n"),
                     "granular-dsmc", "t.nml:20: &sweep: values: ",
                     {"'system:mass(2)' has 2 values", "'system:restitution(1,2)' has 3", "grid = .true."});
}

TEST_F(CliDsmc, PrintDefaultsSaysRequiredOnce) {
  const Result r = run("granular-dsmc", "--print-defaults");
  ASSERT_EQ(r.status, 0);
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_EQ(line.find("(required) (required)"), std::string::npos) << line;
    if (line.find("restitution = ") == 2) {
      EXPECT_NE(line.find("required when constant"), std::string::npos) << line;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// granular-dsmc --compare (analysis/compare.hpp)
// ---------------------------------------------------------------------------------------------

class CliCompare : public CliFixture {
 protected:
  /// examples/haff.nml, made small: 2000 particles x 3 replicas to t = 1500 (about 30 collisions per particle).
  Result run_small_haff(const std::string& compare_option) {
    write("haff.nml", read_text(fs::path(GDSMC_EXAMPLES_DIR) / "haff.nml"));
    return run("granular-dsmc", "haff.nml --quiet --set dsmc:n_particles=2000 --set dsmc:replicas=3 "
                                "--set dsmc:t_end=1500.0 --output out.h5 " + compare_option);
  }
};

TEST_F(CliCompare, HaffTableFileAndJson) {
  const Result r = run_small_haff("--compare=cmp.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(files(), (std::vector<std::string>{"cmp.json", "haff.nml", "out.h5"}));
  expect_no_temporary_file();
  // The table: a header, Haff T(t) and the collision count (Maxwellian), c (first Sonine), marks.
  for (const char* text : {"granular-dsmc --compare", "quantity", "+- SE", "theory", "approximation", "(D-T)/SE",
                           "\nT  ", "collisions/particle", "c_1", "zeta*", "maxwellian", "first_sonine",
                           "scaling state", "mark: stat"})
    EXPECT_NE(r.out.find(text), std::string::npos) << "'" << text << "' missing from:\n" << r.out;
  // The file: /comparison/total_temperature with value, error, theory on the sample times.
  const std::string h5 = (dir / "out.h5").string();
  namespace h5md = gdsmc::io::h5md;
  const auto value = h5md::read_dataset(h5, "/comparison/total_temperature/value");
  const auto theory = h5md::read_dataset(h5, "/comparison/total_temperature/theory");
  const auto error = h5md::read_dataset(h5, "/comparison/total_temperature/error");
  const auto observed = h5md::read_observable(h5, "total_temperature");
  ASSERT_EQ(value.data.size(), 60u);  // examples/haff.nml: n_samples = 60
  EXPECT_EQ(value.data, observed.value);
  EXPECT_EQ(error.data, observed.error);
  EXPECT_EQ(theory.data.size(), 60u);
  EXPECT_DOUBLE_EQ(theory.data[0], 1.0);
  EXPECT_NEAR(theory.data.back() / value.data.back(), 1.0, 0.05);
  EXPECT_EQ(h5md::read_string_attribute(h5, "/comparison/total_temperature", "approximation"), "maxwellian");
  const auto time = std::get<std::vector<double>>(h5md::read_attribute(h5, "/comparison/total_temperature", "time"));
  EXPECT_EQ(time, observed.time);
  EXPECT_EQ(h5md::read_dataset(h5, "/comparison/sonine_c/value").shape, (std::vector<std::size_t>{1}));
  EXPECT_EQ(h5md::read_string_attribute(h5, "/comparison/sonine_c", "approximation"), "first_sonine");
  // The JSON: the same numbers.
  const std::string json = read_text(dir / "cmp.json");
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(std::count(json.begin(), json.end(), '{'), std::count(json.begin(), json.end(), '}'));
  EXPECT_EQ(std::count(json.begin(), json.end(), '['), std::count(json.begin(), json.end(), ']'));
  EXPECT_NE(json.find("\"total_temperature\": {\"label\": \"T\", \"approximation\": \"maxwellian\""),
            std::string::npos);
  char last[64];
  std::snprintf(last, sizeof last, "%.17g]", value.data.back());
  EXPECT_NE(json.find(last), std::string::npos) << "final T " << last << " not in the JSON";
}

TEST_F(CliCompare, TableOnlyAndNoCompareWithoutTheOption) {
  const Result with = run_small_haff("--compare");
  ASSERT_EQ(with.status, 0) << with.err;
  EXPECT_NE(with.out.find("collisions/particle"), std::string::npos) << with.out;
  EXPECT_EQ(files(), (std::vector<std::string>{"haff.nml", "out.h5"}));
  const Result without = run_small_haff("");
  ASSERT_EQ(without.status, 0) << without.err;
  EXPECT_EQ(without.out, "");
  EXPECT_THROW(gdsmc::io::h5md::read_dataset((dir / "out.h5").string(), "/comparison/total_temperature/value"),
               std::runtime_error);
}

TEST_F(CliDsmc, CompareJsonPathEmpty) {
  write("t.nml", base());
  expect_input_error(run("granular-dsmc", "t.nml --quiet --compare="), "granular-dsmc", "--compare=: ",
                     {"no JSON file named"});
}

TEST_F(CliDsmc, CompareJsonIsTheInput) {
  write("t.nml", base());
  expect_input_error(run("granular-dsmc", "t.nml --quiet --compare=t.nml"), "granular-dsmc", "--compare=t.nml: ",
                     {"input namelist"});
  EXPECT_EQ(read_text(dir / "t.nml"), base());
}

TEST_F(CliDsmc, CompareJsonIsTheOutput) {
  write("t.nml", base());
  expect_input_error(run("granular-dsmc", "t.nml --quiet --compare=./out.h5"), "granular-dsmc",
                     "--compare=./out.h5: ", {"output file"});
}

// (the JSON went to the run's checkpoint path, and the next run of the input was refused for a file there
// that is no checkpoint)
TEST_F(CliDsmc, CompareJsonIsTheCheckpoint) {
  write("t.nml", base());
  expect_input_error(run("granular-dsmc", "t.nml --quiet --compare=out.checkpoint.h5"), "granular-dsmc",
                     "--compare=out.checkpoint.h5: ", {"where this run's checkpoints go"});
  EXPECT_FALSE(std::filesystem::exists(dir / "out.checkpoint.h5"));
  // (and its lock file, which the run's end removes: the JSON was lost with --force, and without it the lock
  // this run had just taken was called a file that is no JSON)
  for (const char* force : {"", " --force"}) {
    expect_input_error(run("granular-dsmc", std::string("t.nml --quiet --compare=out.lock") + force), "granular-dsmc",
                       "--compare=out.lock: ", {"this run's lock file"});
    EXPECT_FALSE(std::filesystem::exists(dir / "out.h5")) << force;
  }
}

TEST_F(CliDsmc, CompareJsonUnwritable) {
  write("t.nml", base());
  expect_input_error(run("granular-dsmc", "t.nml --quiet --compare=missing/c.json"), "granular-dsmc",
                     "--compare=missing/c.json: ", {"cannot write the JSON file"});
}

// ---------------------------------------------------------------------------------------------
// granular-theory
// ---------------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------------
// Particle snapshots (io/snapshot.hpp): &output snapshot_times, &initial from_file
// ---------------------------------------------------------------------------------------------

class CliSnapshot : public CliFixture {};

TEST_F(CliSnapshot, EveryParticleAtTheChosenTimesAndARunStartedFromThem) {
  // Run A: 200 particles (mass 1 and 10), 2 replicas, snapshots at 0, 4 and t_end = 10.
  ASSERT_EQ(dsmc(with_line(16, "  file = 'a.h5', n_samples = 3, snapshot_times = 0.0, 4.0, 10.0"),
                 "--set dsmc:replicas=2").status, 0);
  const std::string a = (dir / "a.h5").string();
  const auto v = gdsmc::io::h5md::read_dataset(a, "/particles/replica_2/velocity/value");
  ASSERT_EQ(v.shape, (std::vector<std::size_t>{3, 200, 3}));
  EXPECT_EQ(gdsmc::io::h5md::read_dataset(a, "/particles/replica_1/velocity/time").data,
            (std::vector<double>{0.0, 4.0, 10.0}));
  const auto species = gdsmc::io::h5md::read_integers(a, "/particles/replica_1/species");
  EXPECT_EQ(std::count(species.begin(), species.end(), 1u), 133);  // N_k ~ N n_k/n: 0.02 : 0.01
  EXPECT_EQ(std::count(species.begin(), species.end(), 2u), 67);
  const auto step = gdsmc::io::h5md::read_integers(a, "/particles/replica_1/velocity/step");
  ASSERT_EQ(step.size(), 3u);
  EXPECT_EQ(step[0], 0u);
  EXPECT_LT(step[1], step[2]);
  // The velocities are the gas's: T_k of the last snapshots (about the mean flow, mean over the replicas)
  // is the observable T_k at t_end.
  const auto observed = gdsmc::io::h5md::read_observable(a, "temperature");
  std::vector<double> from_snapshots(2, 0.0);
  for (const char* replica : {"replica_1", "replica_2"}) {
    const auto all = gdsmc::io::h5md::read_dataset(a, std::string("/particles/") + replica + "/velocity/value").data;
    const std::vector<double> u(all.end() - 600, all.end());
    double p[3] = {0, 0, 0}, mass = 0;
    for (std::size_t i = 0; i < 200; ++i) {
      const double m = species[i] == 1 ? 1.0 : 10.0;
      for (int d = 0; d < 3; ++d) p[d] += m * u[3 * i + d];
      mass += m;
    }
    std::vector<double> sum(2, 0.0), count(2, 0.0);
    for (std::size_t i = 0; i < 200; ++i) {
      const std::size_t k = species[i] - 1;
      for (int d = 0; d < 3; ++d) sum[k] += (u[3 * i + d] - p[d] / mass) * (u[3 * i + d] - p[d] / mass);
      count[k] += 1.0;
    }
    for (std::size_t k = 0; k < 2; ++k) from_snapshots[k] += 0.5 * (k == 0 ? 1.0 : 10.0) * sum[k] / (3.0 * count[k]);
  }
  for (std::size_t k = 0; k < 2; ++k)
    EXPECT_NEAR(from_snapshots[k], observed.value[observed.value.size() - 2 + k], 1e-12 * from_snapshots[k]) << k;
  // Run B starts from A's last snapshots (replica r from A's replica r): the same velocities, and its
  // T_k(0) (observable and /parameters) is A's final T_k.
  std::string b_text = with_line(9, "  from_file = 'a.h5'");
  b_text.replace(b_text.find("  file = 'out.h5', n_samples = 3"), std::string("  file = 'out.h5', n_samples = 3").size(),
                 "  file = 'b.h5', n_samples = 3, snapshot_times = 0.0");
  write("b.nml", b_text);
  const Result rb = run("granular-dsmc", "b.nml --quiet --set dsmc:replicas=2");
  ASSERT_EQ(rb.status, 0) << rb.err;
  const std::string b = (dir / "b.h5").string();
  for (const char* replica : {"replica_1", "replica_2"}) {
    const auto va = gdsmc::io::h5md::read_dataset(a, std::string("/particles/") + replica + "/velocity/value").data;
    const auto vb = gdsmc::io::h5md::read_dataset(b, std::string("/particles/") + replica + "/velocity/value").data;
    ASSERT_EQ(vb.size(), 600u);
    EXPECT_TRUE(std::equal(vb.begin(), vb.end(), va.end() - 600)) << replica;
  }
  const auto ta = gdsmc::io::h5md::read_observable(a, "temperature");
  const auto tb = gdsmc::io::h5md::read_observable(b, "temperature");
  for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(tb.value[k], ta.value[ta.value.size() - 2 + k], 1e-13) << k;
  const auto initial = std::get<std::vector<double>>(gdsmc::io::h5md::read_attribute(b, "/parameters/initial", "temperature"));
  for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(initial[k], tb.value[k], 1e-13) << k;
  // Its theory, read later: from /parameters, which a smooth gas's run fills without a rotational temperature
  // (its absence stopped the theory: "not computed: ... can't locate attribute").
  const Result t = run("granular-dsmc", "--table b.h5 temperature --theory");
  EXPECT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(t.err, "");
  EXPECT_NE(t.out.find("_theory"), std::string::npos) << t.out;
}

TEST_F(CliSnapshot, RequestsThatCannotBeMetAreRefusedInOneLine) {
  std::vector<std::string> lines = gdsmc::test::base_namelist_lines("  file = 'out.h5', snapshot_times = 1.0");
  lines[12] = "  collisions_per_particle = 5.0";
  expect_input_error(dsmc(gdsmc::test::join_lines(lines)), "granular-dsmc", "t.nml:16: &output: snapshot_times: ",
                     {"needs t_end"});
  expect_input_error(dsmc(with_line(16, "  file = 'out.h5', snapshot_times = 2.0, 1.0")), "granular-dsmc",
                     "t.nml:16: &output: snapshot_times: ", {"must increase"});
  expect_input_error(dsmc(with_line(16, "  file = 'out.h5', snapshot_times = 20.0")), "granular-dsmc",
                     "t.nml:16: &output: snapshot_times: ", {"beyond t_end"});
  expect_input_error(dsmc(with_line(9, "  from_file = 'absent.h5'")), "granular-dsmc", "t.nml:9: &initial: from_file: ",
                     {"cannot start from it", "absent.h5"});
  // A snapshot of 200 particles for a run of 300.
  ASSERT_EQ(dsmc(with_line(16, "  file = 'a.h5', snapshot_times = 10.0")).status, 0);
  expect_input_error(dsmc(with_line(9, "  from_file = 'a.h5'"), "--set dsmc:n_particles=300"), "granular-dsmc",
                     "t.nml:9: &initial: from_file: ", {"has 133 particles of species 1, this run 200"}, {"a.h5", "t.nml"});
  expect_input_error(dsmc(with_line(9, "  temperature = 2.0, from_file = 'a.h5'")), "granular-dsmc",
                     "t.nml:9: &initial: temperature: ", {"not used with from_file"}, {"a.h5", "t.nml"});
  // The output that would replace its own starting snapshot (it read the snapshot, then wrote over it).
  const std::string snapshot_before = read_text(dir / "a.h5");
  std::string self = with_line(9, "  from_file = 'a.h5'");
  self.replace(self.find("  file = 'out.h5'"), std::string("  file = 'out.h5'").size(), "  file = 'a.h5'");
  expect_input_error(dsmc(self), "granular-dsmc", "t.nml:16: &output: file: ",
                     {"the output file 'a.h5' is the snapshot of &initial from_file: it would be overwritten"},
                     {"a.h5", "t.nml"});
  EXPECT_EQ(read_text(dir / "a.h5"), snapshot_before);
  // A snapshot file whose global heap makes HDF5 loop is refused after the read limit, where from_file is set.
  fs::copy_file(dir / "a.h5", dir / "bad.h5");
  damage_global_heap(dir / "bad.h5", 10);
  {
    const ReadLimit limit("1");
    expect_input_error(dsmc(with_line(9, "  from_file = 'bad.h5'")), "granular-dsmc", "t.nml:9: &initial: from_file: ",
                       {"cannot start from it: the HDF5 library had not finished reading it after 1 s"},
                       {"a.h5", "bad.h5", "t.nml"});
  }
  fs::remove(dir / "bad.h5");
  expect_input_error(dsmc(with_line(9, "  from_file = 'a.h5'"), "--set \"system:mass=1.0, 5.0\""), "granular-dsmc",
                     "t.nml:9: &initial: from_file: ", {"masses", "another gas"}, {"a.h5", "t.nml"});
  // A snapshot whose velocities overflow the temperature is refused as from_file's (the input sets no
  // temperature), not as temperature's.
  fs::copy_file(dir / "a.h5", dir / "hot.h5");
  {
    const hid_t f = H5Fopen((dir / "hot.h5").string().c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "/particles/replica_1/velocity/value", H5P_DEFAULT);
    ASSERT_GE(d, 0);
    std::vector<double> values(200 * 3);  // (its one snapshot, at t = 10)
    ASSERT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    values.at(16) = 1e200;
    ASSERT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    H5Dclose(d);
    H5Fclose(f);
  }
  expect_input_error(dsmc(with_line(9, "  from_file = 'hot.h5'")), "granular-dsmc", "t.nml:9: &initial: from_file: ",
                     {"its snapshot's velocities give temperature(", ") = inf is outside [1e-100, 1e100]"},
                     {"a.h5", "hot.h5", "t.nml"});
  fs::remove(dir / "hot.h5");
  // The gas with forcings is refused, not written wrong (its velocities live in a moving frame).
  expect_input_error(dsmc(with_line(16, "  file = 'b.h5', snapshot_times = 5.0") + "&thermostat kind = 'gaussian' /\n"),
                     "granular-dsmc", "t.nml:16: &output: snapshot_times: ", {"not with &thermostat or &shear"},
                     {"a.h5", "t.nml"});
  // A sweep's output has its snapshots per point.
  ASSERT_EQ(dsmc(with_line(16, "  file = 's.h5', snapshot_times = 10.0") +
                 "&sweep variable = 'system:restitution', values = 0.5, 0.6 /\n").status, 0);
  expect_input_error(dsmc(with_line(9, "  from_file = 's.h5'")), "granular-dsmc", "t.nml:9: &initial: from_file: ",
                     {"a sweep's output", "/sweep/point_K/particles"}, {"a.h5", "s.h5", "t.nml"});
}

TEST_F(CliSnapshot, ARoughRunFromASmoothSnapshotAndTheTableOfItElsewhere) {
  ASSERT_EQ(dsmc(with_line(16, "  file = 'a.h5', n_samples = 3, snapshot_times = 10.0")).status, 0);
  const auto ta = gdsmc::io::h5md::read_observable((dir / "a.h5").string(), "temperature");
  // Rough spheres from a smooth snapshot: T_rot,k(0) defaults to the snapshot's T_k, as temperature's default.
  std::string b = with_line(9, "  from_file = 'a.h5'");
  b.replace(b.find("  restitution = 0.5"), std::string("  restitution = 0.5").size(), "  restitution = 0.5, roughness = 0.2");
  b.replace(b.find("  file = 'out.h5', n_samples = 3"), std::string("  file = 'out.h5', n_samples = 3").size(),
            "  file = 'b.h5', n_samples = 3");
  write("b.nml", b);
  ASSERT_EQ(run("granular-dsmc", "b.nml --quiet").status, 0);
  const std::string file = (dir / "b.h5").string();
  const auto rotational = gdsmc::io::h5md::read_observable(file, "rotational_temperature");
  const auto initial = std::get<std::vector<double>>(gdsmc::io::h5md::read_attribute(file, "/parameters/initial", "rotational_temperature"));
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(initial[k], ta.value[ta.value.size() - 2 + k], 1e-12) << k;
    EXPECT_NEAR(rotational.value[k], initial[k], 0.25 * initial[k]) << k;  // drawn at it: 4 x 67 particles at least
  }
  // Read later from elsewhere, the run's theory comes from its /parameters, not from a.h5 again.
  fs::create_directories(dir / "elsewhere");
  const std::string tool = quoted((fs::path(GDSMC_BIN_DIR) / "granular-dsmc").string());
  const Result t = run("granular-dsmc", "--version && cd elsewhere && " + tool + " --table ../b.h5 summary && " + tool +
                                            " --table ../b.h5 temperature --theory");
  EXPECT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(t.err.find("not computed"), std::string::npos) << t.err;
}

// Issue "Nothing lost, nothing hangs, no NaN": unclear messages, reproduced as reported, then fixed.
TEST_F(CliDsmc, RestartOfAMissingFileSaysItIsMissing) {
  // It said "is damaged or is not a checkpoint of granular-dsmc".
  expect_input_error(dsmc(base(), "--restart absent.checkpoint.h5"), "granular-dsmc",
                     "--restart: checkpoint 'absent.checkpoint.h5': no such file", {});
}

TEST_F(CliDsmc, OutputWithALineBreakNamesTheOutputOption) {
  // It was reported as a `--set output:file=...` the user never typed.
  expect_input_error(dsmc(base(), "--output \"$(printf 'a\\nb.h5')\""), "granular-dsmc",
                     "--output: a file name with a line break is not accepted", {});
}

TEST_F(CliDsmc, NameWithANonAsciiCharacterIsNamed) {
  // `restitución = 0.9` was reported as a bad value of number_density, the variable before it.
  expect_input_error(dsmc(with_line(6, "  restitución = 0.5")), "granular-dsmc", "t.nml:6: &system: restitución: ",
                     {"outside A-Z, 0-9 and _"});
}

TEST_F(CliTheory, EveryKeyItPrintsIsInItsHelp) {
  // Keys of the JSON for the inputs of every kind of theory, against --help.
  const std::string help = run("granular-theory", "--help").out;
  const std::vector<std::string> inputs = {
      base(),
      with_line(16, "  file = 'out.h5', track_displacements = .true."),
      base() + "&sweep variable = 'system:restitution', values = 0.6, 0.9 /\n",
      with_line(6, "  restitution = 0.5, roughness = 0.3"),
      with_line(6, "  restitution = 0.5, roughness = 0.3") + "&thermostat kind = 'white_noise', noise_strength = 0.01 /\n",
      "&system\n n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.8, roughness = 0.2\n/\n"
      "&dsmc\n n_particles = 200, t_end = 10.0\n/\n",
      "&system\n n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 0.8\n/\n"
      "&dsmc\n n_particles = 2000, t_end = 1.0\n/\n&agg_frag\n aggregation_energy = 0.5\n/\n",
      "&system\n n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.8\n/\n"
      "&dsmc\n n_particles = 200, t_end = 10.0\n/\n&thermostat\n kind = 'gaussian'\n/\n&shear\n rate = 0.01\n/\n"};
  const std::regex key("\"([a-z_0-9]+)\":");
  for (const auto& text : inputs) {
    write("t.nml", text);
    const Result r = run("granular-theory", "t.nml");
    ASSERT_EQ(r.status, 0) << text << r.err;
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), key); it != std::sregex_iterator(); ++it) {
      const std::string name = (*it)[1];
      EXPECT_NE(help.find(name), std::string::npos) << "'" << name << "' is printed but not in --help, for\n" << text;
    }
  }
}

// What an hour of fuzzing the command line found (tests/fuzz/README.md "Fuzzing the command line"), each refused
// before any work in one line, or run as it should.
TEST_F(CliDsmc, FindingsOfTheCommandLineFuzzer) {
  write("t.nml", base());
  // --compare=F.json replaced any file; now only an earlier --compare JSON, or anything with --force.
  write("notes.json", "precious");
  expect_input_error(run("granular-dsmc", "t.nml --quiet --compare=notes.json"), "granular-dsmc",
                     "--compare=notes.json: 'notes.json' exists and is not a --compare JSON of granular-dsmc", {},
                     {"notes.json", "t.nml"});
  EXPECT_EQ(read_text(dir / "notes.json"), "precious");
  // A link that leads nowhere at the output path ran to the end and failed (exit 1): refused at once.
  fs::create_symlink("nowhere/x.h5", dir / "dang.h5");
  expect_input_error(run("granular-dsmc", "t.nml --quiet --output dang.h5"), "granular-dsmc",
                     "--output dang.h5: &output: file: 'dang.h5' exists and is not an output of granular-dsmc", {},
                     {"dang.h5", "notes.json", "t.nml"});
  fs::remove(dir / "dang.h5");
  // A step_fraction of 1e-9 never ended (each step is O(N)): refused with the count of steps (here 1e-12:
  // about 5e11 steps of 200 particles, beyond 1e13 updates).
  expect_input_error(run("granular-dsmc", "t.nml --quiet --set dsmc:step_fraction=1e-12"), "granular-dsmc",
                     "--set dsmc:step_fraction=1e-12: &dsmc: step_fraction: step_fraction = 1e-12 makes at least",
                     {"time steps", "allow_long_run"}, {"notes.json", "t.nml"});
  // The same of a thermostat's stages (stage_step = 1e-300 never ended), and a white noise that heats the gas
  // (noise_strength = 1e20 from T = 1, to about 3e14: its collisions grow as sqrt(T); 1e13 events to t = 1e5).
  write("t.nml", base() + "&thermostat\n  kind = 'gaussian'\n/\n");
  expect_input_error(run("granular-dsmc", "t.nml --quiet --set dsmc:stage_step=1e-300"), "granular-dsmc",
                     "--set dsmc:stage_step=1e-300: &dsmc: stage_step: stage_step = 1e-300 makes at least",
                     {"stages", "allow_long_run"}, {"notes.json", "t.nml"});
  write("t.nml", base() + "&thermostat\n  kind = 'white_noise', noise_strength = 1e20\n/\n");
  expect_input_error(run("granular-dsmc", "t.nml --quiet --set dsmc:t_end=1e5"), "granular-dsmc", "--set dsmc:t_end=1e5:",
                     {"&dsmc: t_end: kinetic theory estimates", "the white noise heating the gas up to", "allow_long_run"},
                     {"notes.json", "t.nml"});
  write("t.nml", base());
  // Line breaks in --restart, --compare= and --table names were echoed raw (a message of 2-3 lines).
  for (const char* args : {"t.nml --restart 'a\nb.h5'", "t.nml --compare='a\nb.json'", "--table 'a\nb.h5'"}) {
    const Result r = run("granular-dsmc", args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("a file name with a line break is not accepted"), std::string::npos) << r.err;
  }
  // An empty --output was reported as a --set output:file='' the user never typed.
  expect_input_error(run("granular-dsmc", "t.nml --quiet --output ''"), "granular-dsmc",
                     "--output '': &output: file: file must not be empty", {}, {"notes.json", "t.nml"});
  // A 255-character name passed the checks and failed in H5Fcreate with HDF5's internals.
  const std::string long_name(252, 'L');
  expect_input_error(run("granular-dsmc", "t.nml --quiet --output " + long_name + ".h5"), "granular-dsmc",
                     "--output " + long_name + ".h5: &output: file: the file name is 255 characters long: at most 200",
                     {}, {"notes.json", "t.nml"});
  // Two particles: the pair at the bound itself (g = 2 v_max exactly) was counted as an overshoot of
  // round-off (acceptance 1 + 2e-16) with a warning asking to report the input.
  const Result two = run("granular-dsmc", std::string(GDSMC_EXAMPLES_DIR) +
                                              "/haff.nml --quiet --set dsmc:n_particles=2 --output two.h5");
  EXPECT_EQ(two.status, 0) << two.err;
  EXPECT_EQ(two.err.find("acceptance probability above 1"), std::string::npos) << two.err;
}

TEST_F(CliTheory, VersionAndASetWithoutValue) {
  const Result v = run("granular-theory", "--version");
  EXPECT_EQ(v.status, 0);
  EXPECT_EQ(v.out.rfind("granular-theory ", 0), 0u) << v.out;
  write("t.nml", base());
  const Result r = run("granular-theory", "t.nml --set");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "granular-theory: --set needs a value (--set group:variable=value)\n");
}

TEST_F(CliTheory, TwoInputFilesAreRefused) {
  // It used the last one silently.
  write("t.nml", base());
  write("u.nml", base());
  const Result r = run("granular-theory", "t.nml u.nml");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "granular-theory: one input file only (got 't.nml' and 'u.nml')\n");
}

// A mixture's theory holds O(S^2) pair tables (run_checks.hpp: 0.2 GB + 60 S^2 bytes): 20000 species need
// about 24.2 GB, refused under ulimit -v 4 GB before any work, naming n_species, by granular-theory and by
// granular-dsmc --compare (70000 species ended in std::bad_alloc: granular-theory exit 1, --compare a
// table line "std::bad_alloc" after the whole run); granular-dsmc without --compare runs. --compare's
// theory runs beside the particles: their sum is checked.
TEST_F(CliTheory, TheoryBeyondTheMachinesMemoryIsRefused) {
  AddressSpaceLimit limit(4000000000ull);
  if (!limit.skip.empty()) GTEST_SKIP() << limit.skip;
  write("t.nml", many_species_namelist(20000, 60000, 2));
  const Result theory = run("granular-theory", "t.nml");
  const Result compare = run("granular-dsmc", "t.nml --quiet --compare");
  // Each fits alone, not both: 5000 species' theory 1.7 GB beside 1e8 particles x 28 bytes = 2.8 GB.
  const Result both = run("granular-dsmc", "t.nml --quiet --compare --set system:n_species=5000 "
                                           "--set dsmc:n_particles=100000000");
  limit.restore();
  const std::vector<std::string> said = {"the theory of 20000 species needs about 24.2 GB",
                                         "more than the address-space limit (ulimit -v) (4 GB)"};
  expect_input_error(theory, "granular-theory", "t.nml:2: &system: n_species: ", said);
  expect_input_error(compare, "granular-dsmc", "--compare: t.nml:2: &system: n_species: ", said);
  EXPECT_NE(compare.err.find("run without --compare"), std::string::npos) << compare.err;
  expect_input_error(both, "granular-dsmc", "--set dsmc:n_particles=100000000: &dsmc: n_particles: ",
                     {"need about 2.8 GB, the samples' rows of every replica 640 kB, --compare's theory beside them 1.7 GB",
                      "(4 GB)", "or no --compare"});
  const Result plain = run("granular-dsmc", "t.nml --quiet");
  EXPECT_EQ(plain.status, 0) << plain.err;
  EXPECT_TRUE(fs::exists(dir / "out.h5"));
}

TEST_F(CliTheory, PrintsOneJsonObject) {
  write("t.nml", base());
  const Result r = run("granular-theory", "t.nml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  std::string out = r.out;
  while (!out.empty() && std::isspace(static_cast<unsigned char>(out.back()))) out.pop_back();
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out.front(), '{') << out;
  EXPECT_EQ(out.back(), '}') << out;
  for (const char* key : {"\"cooling_rate\"", "\"collision_frequency\"", "\"temperature\"",
                          "\"hcs\": {\"first_sonine\": {\"temperature_over_mean\"", "\"sonine_c\"",
                          "\"maxwellian\": {\"temperature_over_mean\"", "\"approximations\": {",
                          "\"cooling_rate\": \"maxwellian\"", "\"hcs.first_sonine\": \"first_sonine\"",
                          // (the agg/frag theory's rates: events per volume and time, and d ln N_1/dt; were "1")
                          "\"initial_rates\": \"length-3 time-1\"", "\"log_monomer_rate\": \"time-1\""})
    EXPECT_NE(out.find(key), std::string::npos) << key;
  EXPECT_EQ(std::count(out.begin(), out.end(), '{'), std::count(out.begin(), out.end(), '}'));
  EXPECT_EQ(std::count(out.begin(), out.end(), '['), std::count(out.begin(), out.end(), ']'));
  EXPECT_EQ(files(), std::vector<std::string>{"t.nml"});  // writes no file
}

// An Enskog binary mixture in shear flow (Montanero 2003, Figs. 10-12, \ref eta_mixture "docs/shear-viscosity.md"): the first-Sonine eta/eta_0 and its
// kinetic part, the values validation/shear_viscosity states against the DSMC (mu = 4, phi = 0.2,
// alpha = 0.9: 1.9075 and 0.9084, HSS).
TEST_F(CliTheory, EnskogMixtureShearViscosity) {
  write("t.nml",
        "&system n_species = 2, mass = 4.0, 1.0, diameter = 1.0, 1.0, number_density = 0.191, 0.191,\n"
        "  restitution = 0.9, enskog = .true. /\n&dsmc scheme = 'pairs', n_particles = 8000, t_end = 100.0 /\n"
        "&thermostat kind = 'gaussian' /\n&shear rate = 0.07 /\n");
  const Result r = run("granular-theory", "t.nml");
  EXPECT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"shear_viscosity_ratio\": {\"hcs\": 1.834", "\"hss\": 1.907",
                          "\"shear_viscosity_kinetic_ratio\": {\"hcs\": 0.857", "\"hss\": 0.908",
                          "\"shear_viscosity_kinetic_ratio\": \"first_sonine\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
}

namespace {
/// The number after `"key": {"hcs": ..., "hss": ` (the HSS value of a {hcs, hss} entry) in `json`.
double hss_value(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": {\"hcs\"");
  if (at == std::string::npos) return std::nan("");
  const auto hss = json.find("\"hss\": ", at);
  return std::stod(json.substr(hss + 7));
}
}  // namespace

// Montanero 2003's units of Figs. 10-12 (\ref eta_mixture "docs/shear-viscosity.md"): eta* = nu eta/(n T), nu =
// sqrt(pi) n sigma_12^2 v0, v0 = sqrt(2 T (m1 + m2)/(m1 m2)). By hand, two identical species (m, sigma):
// eta_0 = (5/(16 sigma^2)) sqrt(m T/pi), v0 = 2 sqrt(T/m), so nu eta_0/(n T) = 2 sqrt(pi) 5/(16 sqrt(pi)) = 5/8
// whatever m, sigma, n and T. The Enskog kinetic part takes the same factor. Fig. 12: at phi = 0.2 and
// alpha = 0.9, eta* rises with the mass ratio (mu = 2, 4, 8), as the paper's figure shows (eta/eta_0 falls).
TEST_F(CliTheory, MontaneroReducedShearViscosity) {
  write("t.nml",
        "&system n_species = 2, mass = 2.5, 2.5, diameter = 1.3, 1.3, number_density = 0.004, 0.006,\n"
        "  restitution = 0.8 /\n&dsmc n_particles = 8000, t_end = 100.0 /\n&thermostat kind = 'gaussian' /\n");
  const Result same = run("granular-theory", "t.nml");
  ASSERT_EQ(same.status, 0) << same.err;
  EXPECT_NEAR(hss_value(same.out, "shear_viscosity_reduced") / hss_value(same.out, "shear_viscosity_ratio"), 0.625,
              1e-12) << same.out;
  double previous = 0.0;
  for (const char* mu : {"2.0", "4.0", "8.0"}) {
    write("t.nml", std::string("&system n_species = 2, mass = ") + mu +
                       ", 1.0, diameter = 1.0, 1.0, number_density = 0.191, 0.191,\n"
                       "  restitution = 0.9, enskog = .true. /\n&dsmc scheme = 'pairs', n_particles = 8000, "
                       "t_end = 100.0 /\n&thermostat kind = 'gaussian' /\n");
    const Result r = run("granular-theory", "t.nml");
    ASSERT_EQ(r.status, 0) << r.err;
    // nu eta_0/(n T) holds no chi (nu and eta_0 are the dilute gas's): the same factor as without enskog.
    const double factor = hss_value(r.out, "shear_viscosity_kinetic_reduced") /
                          hss_value(r.out, "shear_viscosity_kinetic_ratio");
    write("d.nml", std::string("&system n_species = 2, mass = ") + mu +
                       ", 1.0, diameter = 1.0, 1.0, number_density = 0.191, 0.191,\n  restitution = 0.9 /\n"
                       "&dsmc n_particles = 8000, t_end = 100.0 /\n&thermostat kind = 'gaussian' /\n");
    const Result dilute = run("granular-theory", "d.nml");
    ASSERT_EQ(dilute.status, 0) << dilute.err;
    EXPECT_NEAR(factor, hss_value(dilute.out, "shear_viscosity_reduced") / hss_value(dilute.out, "shear_viscosity_ratio"),
                1e-12 * factor) << mu;
    EXPECT_NE(r.out.find("\"shear_viscosity_kinetic_reduced\": \"first_sonine\""), std::string::npos) << r.out;
    EXPECT_GT(hss_value(r.out, "shear_viscosity_reduced"), previous) << "mu = " << mu;
    previous = hss_value(r.out, "shear_viscosity_reduced");
  }
}

// Rough spheres (\ref rough_maxwellian "docs/rough-spheres.md"): the INTERFACE keys rough_hcs.maxwellian {theta,
// zeta_star} (alpha = 0.9, beta = 0, kappa = 0.4: 0.57379, 0.18757, by hand in tests/rough_test.cpp), the
// Sonine entry {theta, a20, a02, a11, zeta_star} (theory::rough, checked in tests/rough_test.cpp; the values
// of docs/rough-spheres.md's table), rotational_temperature on the sample times, and no smooth-sphere key
// (sonine_a2). Where the Sonine state breaks down (alpha = 0.5, beta = -0.5) the entry is a sentence.
TEST_F(CliTheory, RoughSpheresGiveThetaAndTheRotationalTemperature) {
  write("t.nml",
        "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.9, roughness = 0.0 /\n"
        "&dsmc n_particles = 1000, collisions_per_particle = 10.0 /\n&output n_samples = 3 /\n");
  const Result r = run("granular-theory", "t.nml");
  EXPECT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"rough_hcs\": {\"maxwellian\": {\"theta\": 0.57379", "\"zeta_star\": 0.18756",
                          "\"sonine\": {\"theta\": 0.5528", "\"a20\": -0.0040", "\"a02\": 0.1855", "\"a11\": 0.0647",
                          "\"zeta_star\": 0.1882", "\"rotational_temperature\": {\"time\"",
                          "\"rough_hcs.maxwellian\": \"maxwellian\"", "\"rough_hcs.sonine\": \"first_sonine\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  EXPECT_EQ(r.out.find("sonine_a2"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("[]"), std::string::npos) << r.out;  // (no key written empty: D_k/D_1 is not computed)
  write("t.nml",
        "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.5, roughness = -0.5 /\n"
        "&dsmc n_particles = 1000, collisions_per_particle = 10.0 /\n&output n_samples = 3 /\n");
  const Result broken = run("granular-theory", "t.nml");
  EXPECT_EQ(broken.status, 0) << broken.err;
  EXPECT_NE(broken.out.find("\"sonine\": \"the Sonine approximation breaks down here"), std::string::npos) << broken.out;
  // a binary (validation/rough_spheres/rough_binary.nml's gas): the Maxwellian HCS ratios of theory::rough
  // (checked in tests/rough_test.cpp), the Sonine entry a sentence
  write("t.nml",
        "&system n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.006, 0.004, restitution = 0.8,\n"
        "  roughness = 0.2, moment_of_inertia = 0.4, 0.3 /\n"
        "&dsmc n_particles = 1000, collisions_per_particle = 10.0 /\n&output n_samples = 3 /\n");
  const Result binary = run("granular-theory", "t.nml");
  EXPECT_EQ(binary.status, 0) << binary.err;
  for (const char* key : {"\"rough_hcs\": {\"maxwellian\": {\"theta\": [0.80597", ", 0.94532",
                          "\"translational_temperature_over_mean\": [0.87542", "\"sonine\": \"not computed"})
    EXPECT_NE(binary.out.find(key), std::string::npos) << key << " in " << binary.out;
  // keys the rough mixture's theory does not compute are left out, not written as empty arrays
  for (const char* key : {"\"cooling_rate\": [", "\"diffusion_coefficient_ratio\"", "[]"})
    EXPECT_EQ(binary.out.find(key), std::string::npos) << key << " in " << binary.out;
}

// White noise (\ref wn_theory "docs/white-noise.md"), alpha = 0.9, n = 0.01, chi^2 = 0.001: the Maxwellian
// T_tr^(3/2) = 3 m chi^2/((1 - alpha^2) 4 n sigma^2 sqrt(pi/m)) = 0.0157895.../0.0708982... -> T = 0.367413,
// the Sonine a20 = van Noije and Ernst's -0.0117913 (by hand in tests/rough_test.cpp) and its T_tr (zeta* times
// 1 + 3 a2/16: T = 0.367413 (1 + 3 a2/16)^(-2/3) = 0.367956), which is the top-level translational_temperature;
// rough spheres (beta = 0, kappa = 0.4) add theta (Maxwellian B/C = 2/9, Sonine 0.21875).
TEST_F(CliTheory, WhiteNoiseGivesTheMaxwellianAndSonineStates) {
  const std::string system = "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.9";
  const std::string rest = " /\n&thermostat kind = 'white_noise', noise_strength = 0.001 /\n"
                           "&dsmc n_particles = 1000, t_end = 10.0 /\n&output n_samples = 3 /\n";
  write("t.nml", system + rest);
  const Result smooth = run("granular-theory", "t.nml");
  EXPECT_EQ(smooth.status, 0) << smooth.err;
  for (const char* key : {"\"white_noise\": {\"maxwellian\": {\"translational_temperature\": 0.36741",
                          "\"sonine\": {\"translational_temperature\": 0.36795", "\"a20\": -0.011791",
                          "}, \"translational_temperature\": 0.36795", "\"white_noise.translational_temperature\": \"first_sonine\""})
    EXPECT_NE(smooth.out.find(key), std::string::npos) << key << " in " << smooth.out;
  write("t.nml", system + ", roughness = 0.0" + rest);
  const Result rough = run("granular-theory", "t.nml");
  EXPECT_EQ(rough.status, 0) << rough.err;
  for (const char* key : {"\"theta\": 0.22222", "\"theta\": 0.21875", "\"a02\": 0.0218", "\"a11\": 0.0644"})
    EXPECT_NE(rough.out.find(key), std::string::npos) << key << " in " << rough.out;
  // elastic: no steady state, said so, and no inf in the JSON
  write("t.nml", "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 1.0" + rest);
  const Result elastic = run("granular-theory", "t.nml");
  EXPECT_EQ(elastic.status, 0) << elastic.err;
  EXPECT_EQ(elastic.out.find("white_noise\""), std::string::npos) << elastic.out;
  EXPECT_EQ(elastic.out.find("inf"), std::string::npos) << elastic.out;
  EXPECT_NE(elastic.err.find("white noise: no steady state"), std::string::npos) << elastic.err;
  // a binary (docs/white-noise.md's measured mixture): the Maxwellian T_k of theory::rough::mixture_driven_state
  // (checked in tests/rough_test.cpp) and the first-Sonine T_k, c_k of theory::white_noise_first_sonine (checked in
  // tests/sonine_mixture_test.cpp), arrays; the Sonine T_k is the one the key translational_temperature gives.
  // Rough, the Sonine entry is a sentence.
  write("t.nml", "&system n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.006, 0.004, "
                 "restitution = 0.8" + rest);
  const Result binary = run("granular-theory", "t.nml");
  EXPECT_EQ(binary.status, 0) << binary.err;
  for (const char* key : {"\"white_noise\": {\"maxwellian\": {\"translational_temperature\": [0.17951", ", 0.15857",
                          "\"sonine\": {\"translational_temperature\": [0.17989", ", 0.15842", "\"sonine_c\": [-0.0192",
                          "]}, \"translational_temperature\": [0.17989", "\"white_noise.translational_temperature\": \"first_sonine\""})
    EXPECT_NE(binary.out.find(key), std::string::npos) << key << " in " << binary.out;
  write("t.nml", "&system n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.006, 0.004, "
                 "restitution = 0.8, roughness = 0.3" + rest);
  const Result rough_binary = run("granular-theory", "t.nml");
  EXPECT_EQ(rough_binary.status, 0) << rough_binary.err;
  EXPECT_NE(rough_binary.out.find("\"sonine\": \"not computed: the Sonine theory of driven rough mixtures"), std::string::npos)
      << rough_binary.out;
  // elastic and perfectly rough: no loss either, whatever kappa (round-off must not make a steady state)
  for (const char* kappa : {"0.1", "0.4", "0.6666666666666666"}) {
    write("t.nml", "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 1.0, roughness = 1.0, "
                   "moment_of_inertia = " + std::string(kappa) + rest);
    const Result rough_elastic = run("granular-theory", "t.nml");
    EXPECT_EQ(rough_elastic.status, 0) << rough_elastic.err;
    EXPECT_EQ(rough_elastic.out.find("white_noise\""), std::string::npos) << kappa << ": " << rough_elastic.out;
    EXPECT_EQ(rough_elastic.out.find("nan"), std::string::npos) << kappa << ": " << rough_elastic.out;
    EXPECT_EQ(rough_elastic.out.find("inf"), std::string::npos) << kappa << ": " << rough_elastic.out;
  }
}

TEST_F(CliTheory, AFailedIntegrationNamesTheEndOfTheRun) {
  // CVODE gives up long before t_end = 1e300: an input error naming t_end and its line.
  auto lines = base_lines;
  lines[12] = "  t_end = 1e300, allow_long_run = .true.";
  write("t.nml", gdsmc::test::join_lines(lines));
  expect_input_error(run("granular-theory", "t.nml"), "granular-theory", "t.nml:13: &dsmc: t_end: ",
                     {"the theory cannot integrate to t_end = 1e+300", "CVode"});
}

TEST_F(CliTheory, APartOfTheTheoryThatFailsIsLeftOutWithAWordWhy) {
  // A mass ratio of 1e20: the HCS ratios' ODE (CVODE) gives up, reached also through D_k/D_1; D_k/D_1 is then
  // left out with a note, as the HCS keys are, and the temperatures over the run are still printed (exit 0).
  write("t.nml",
        "&system n_species = 2, mass = 1.0, 1e20, diameter = 1.0, 1.0, number_density = 0.005, 0.005,\n"
        "  restitution = 0.9 /\n&dsmc n_particles = 2000, t_end = 100.0 /\n&output n_samples = 3 /\n");
  const Result r = run("granular-theory", "t.nml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"temperature\": {\"time\": [0, 50, 100]"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\"diffusion_coefficient_ratio\""), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("diffusion_coefficient_ratio left out: SUNDIALS call CVode failed"), std::string::npos) << r.err;
}

TEST_F(CliTheory, RefusesWhatTheSimulationRefusesTheSameWay) {
  auto lines = base_lines;
  lines[12] = "  t_end = 1e300";
  write("t.nml", gdsmc::test::join_lines(lines));
  const Result theory = run("granular-theory", "t.nml");
  expect_input_error(theory, "granular-theory", "t.nml:13: &dsmc: t_end: ", {"allow_long_run"});
  const Result dsmc = run("granular-dsmc", "t.nml --quiet");
  EXPECT_EQ(dsmc.status, 2);
  EXPECT_EQ(dsmc.err.substr(std::string("granular-dsmc").size()), theory.err.substr(std::string("granular-theory").size()));
}

TEST_F(CliTheory, BadInput) {
  write("t.nml", with_line(6, "  restitution = 1.3"));
  expect_input_error(run("granular-theory", "t.nml"), "granular-theory",
                     "t.nml:6: &system: restitution: ", {"is outside [0, 1]"});
}

TEST_F(CliTheory, UnknownVariable) {
  write("t.nml", with_line(9, "  temprature = 1.0"));
  expect_input_error(run("granular-theory", "t.nml"), "granular-theory",
                     "t.nml:9: &initial: temprature: ", {"did you mean 'temperature'"});
}

TEST_F(CliTheory, MissingGroup) {
  auto lines = base_lines;
  lines.erase(lines.begin(), lines.begin() + 7);  // &system ... /
  write("t.nml", gdsmc::test::join_lines(lines));
  expect_input_error(run("granular-theory", "t.nml"), "granular-theory", "t.nml: &system: ",
                     {"required group is missing"});
}

TEST_F(CliTheory, BadOverride) {
  write("t.nml", base());
  expect_input_error(run("granular-theory", "t.nml --set system:restitution=1.3"),
                     "granular-theory", "--set system:restitution=1.3: &system: restitution: ",
                     {"is outside [0, 1]"});
}

}  // namespace
