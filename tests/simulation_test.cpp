// Unit tests for gdsmc::simulation: the file a run writes, sweeps, and reproducibility.
#include "dsmc/simulation.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/config.hpp"
#include "io/h5md.hpp"
#include "io/namelist.hpp"

namespace fs = std::filesystem;
using namespace gdsmc;

namespace {

const char* kBinary =
    "&system n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.02, 0.01,\n"
    "        restitution = 0.7 /\n"
    "&dsmc n_particles = 600, t_end = 20.0, replicas = 3, seed = 9 /\n"
    "&output n_samples = 4 /\n";

io::config::Config config_of(const std::string& text) {
  return io::config::read(io::namelist::parse(text, "t.nml"));
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("gdsmc_simulation_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

}  // namespace

TEST(Simulation, SameSeedSameFileContents) {
  const auto c = config_of(kBinary);
  const auto a = scratch("a.h5"), b = scratch("b.h5");
  simulation::run(c, a.string(), {});
  simulation::run(c, b.string(), {});
  for (const char* name : {"temperature", "sonine_c", "collisions_pair", "time"}) {
    const auto x = io::h5md::read_observable(a.string(), name);
    const auto y = io::h5md::read_observable(b.string(), name);
    EXPECT_EQ(x.value, y.value) << name;  // bitwise
    EXPECT_EQ(x.error, y.error) << name;
  }
  const auto other = config_of(std::string(kBinary) + "! another seed\n");
  auto changed = other;
  changed.dsmc.seed = 10;
  simulation::run(changed, b.string(), {});
  EXPECT_NE(io::h5md::read_observable(a.string(), "temperature").value,
            io::h5md::read_observable(b.string(), "temperature").value);
}

TEST(Simulation, LayoutOfAPlainRun) {
  const auto path = scratch("plain.h5");
  simulation::run(config_of(kBinary), path.string(), {});
  const auto t = io::h5md::read_observable(path.string(), "temperature");
  ASSERT_EQ(t.shape, (std::vector<std::size_t>{4, 2}));
  EXPECT_EQ(t.time, (std::vector<double>{0.0, 20.0 / 3.0, 40.0 / 3.0, 20.0}));
  EXPECT_EQ(t.error.size(), 8u);  // replicas > 1
  const auto pairs = io::h5md::read_observable(path.string(), "collisions_pair");
  EXPECT_EQ(pairs.shape, (std::vector<std::size_t>{4, 3}));
  const auto h = io::h5md::read_observable(path.string(), "velocity_histogram/species_2");
  EXPECT_EQ(h.shape, (std::vector<std::size_t>{4, 50}));
  // Reading back the run's own input reproduces the Config.
  const auto again = io::config::read_from_output(path.string());
  EXPECT_EQ(again.dsmc.n_particles, 600);
}

TEST(Simulation, SweepWritesOneGroupPerPoint) {
  const auto path = scratch("sweep.h5");
  const auto c = config_of(std::string(kBinary) + "&sweep variable = 'system:restitution', values = 0.5, 1.0 /\n");
  simulation::run(c, path.string(), {});
  const auto inelastic = io::h5md::read_observable(path.string(), "/sweep/point_1/observables/total_temperature");
  const auto elastic = io::h5md::read_observable(path.string(), "/sweep/point_2/observables/total_temperature");
  EXPECT_LT(inelastic.value.back(), 0.9);                 // alpha = 0.5 cools
  EXPECT_NEAR(elastic.value.back(), 1.0, 1e-12);          // alpha = 1 conserves energy exactly
  EXPECT_EQ(io::h5md::read_string_attribute(path.string(), "/sweep/point_2", "value"), "1.0");
  EXPECT_EQ(io::h5md::read_string_attribute(path.string(), "/sweep", "variable"), "system:restitution");
  EXPECT_THROW(io::h5md::read_observable(path.string(), "temperature"), std::runtime_error);
}
