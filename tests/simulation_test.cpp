// Unit tests for gdsmc::simulation: the file a run writes, sweeps, and reproducibility.
#include "run/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "io/config.hpp"
#include "io/h5md.hpp"
#include "io/namelist.hpp"
#include "run/progress.hpp"
#include "run/replica.hpp"
#include "scratch_dir.hpp"

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
  static const test::ScratchDir dir("gdsmc_simulation_test_");  // removed when the test process ends
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

// Displacements (Bodrova and Osinsky 2024, eq. (15), \ref dif_displacements "docs/diffusion-msd.md"): an elastic gas is ballistic, <R^2> = 3 T t^2/m, long before its
// first collision (nu = 0.0709 here, t = 0.5 is 0.035 collisions), and diffusive later with
// 6 D per unit time, D = 3/(8 n sigma^2) sqrt(T/(pi m)) (first Chapman-Enskog approximation, which
// the velocity-correlation theory of Bodrova and Osinsky 2024, eq. (19), \ref dif_coefficients "docs/diffusion-msd.md" also gives for alpha = 1; the second
// approximation is 1.7 % higher, 1 + 1/58, \ref dif_second_approximation "docs/diffusion-msd.md"; the converged value about 1.9 %). Ensemble: 4 replicas x 20000 particles; slope from t = 120 to 200
// (8.5 to 14 collisions per particle) with its replica SE; tolerance 4 SE + 3 % (the approximation).
TEST(Simulation, DisplacementsBallisticThenDiffusive) {
  const auto path = scratch("msd.h5");
  const auto c = config_of(
      "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 1.0 /\n"
      "&dsmc n_particles = 20000, t_end = 200.0, replicas = 4, seed = 3 /\n"
      "&output n_samples = 401, track_displacements = .true. /\n");
  simulation::run(c, path.string(), {});
  const auto msd = io::h5md::read_observable(path.string(), "msd");
  ASSERT_EQ(msd.time.size(), 401u);
  EXPECT_NEAR(msd.value[1] / (3.0 * msd.time[1] * msd.time[1]), 1.0, 0.02);  // t = 0.5
  const std::size_t a = 240, b = 400;  // t = 120, 200
  const double slope = (msd.value[b] - msd.value[a]) / (msd.time[b] - msd.time[a]);
  const double slope_se = std::hypot(msd.error[a], msd.error[b]) / (msd.time[b] - msd.time[a]);
  const double d = 3.0 / (8.0 * 0.01) * std::sqrt(1.0 / M_PI);
  std::printf("[ Simulation.Msd ] 6D measured %.3f +- %.3f, first Chapman-Enskog %.3f\n", slope, slope_se, 6.0 * d);
  EXPECT_NEAR(slope, 6.0 * d, 4.0 * slope_se + 0.03 * 6.0 * d);
}

TEST(Simulation, DisplacementsStartLater) {
  const auto path = scratch("msd_late.h5");
  const auto c = config_of(
      "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.8 /\n"
      "&dsmc n_particles = 2000, t_end = 100.0, replicas = 2, seed = 3 /\n"
      "&output n_samples = 11, track_displacements = .true., msd_start_time = 35.0 /\n");
  simulation::run(c, path.string(), {});
  const auto msd = io::h5md::read_observable(path.string(), "msd");
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(msd.value[i], 0.0) << "t = " << msd.time[i];  // before 35
  EXPECT_GT(msd.value[4], 0.0);
  const auto start = io::h5md::read_dataset(path.string(), "/observables/msd/start_time").data;
  ASSERT_EQ(start.size(), 2u);
  EXPECT_DOUBLE_EQ(start[0], 35.0);
}

TEST(Simulation, ChunksEndAfterAboutAFixedNumberOfCandidates) {
  // Before any candidate: straight to the target.
  EXPECT_EQ(simulation::chunk_end_time(0.0, 0, 5.0), 5.0);
  EXPECT_EQ(simulation::chunk_end_time(2.0, 0, 5.0), 5.0);
  // 1000 candidates in 2 time units: 1e5 more take 200 time units at that mean rate.
  EXPECT_DOUBLE_EQ(simulation::chunk_end_time(2.0, 1000, 1e30, 1e5), 202.0);
  // Never beyond the target, which is then hit exactly.
  EXPECT_EQ(simulation::chunk_end_time(2.0, 1000, 50.0, 1e5), 50.0);
  EXPECT_EQ(simulation::chunk_end_time(2.0, 1000, std::numeric_limits<double>::infinity(), 1e5), 202.0);
}

// Issue 17 item 4: /h5md/author is &output author, else $USER (or the login name); never the old
// placeholder. `step` is the cumulative collision events (mean over replicas, rounded), not the
// sample index.
TEST(Simulation, AuthorAndStepConvention) {
  const auto path = scratch("author.h5");
  std::string text = kBinary;
  text.replace(text.find("n_samples = 4"), 13, "n_samples = 4, author = 'A. Person'");
  simulation::run(config_of(text), path.string(), {});
  EXPECT_EQ(io::h5md::read_string_attribute(path.string(), "/h5md/author", "name"), "A. Person");
  const auto t = io::h5md::read_observable(path.string(), "total_temperature");
  const auto events = io::h5md::read_observable(path.string(), "collisions");
  ASSERT_EQ(t.step.size(), events.value.size());
  for (std::size_t i = 0; i < t.step.size(); ++i) EXPECT_EQ(t.step[i], std::llround(events.value[i])) << i;
  EXPECT_GT(t.step.back(), static_cast<long long>(t.step.size()));  // not the sample index
  simulation::run(config_of(kBinary), path.string(), {});
  const std::string author = io::h5md::read_string_attribute(path.string(), "/h5md/author", "name");
  EXPECT_NE(author, "granular-dsmc user");
  EXPECT_FALSE(author.empty());
}

TEST(Simulation, ScalingStateIsTheReplicasAverages) {
  // /observables/scaling_state (docs/output.md): in a collision-driven run every replica samples at the
  // same collisions per particle, so the mean over the replicas of each replica's average of c_k over
  // its samples past scaling_start is the average of the replica means over those samples; T_k/T
  // satisfies sum_k x_k T_k/T = 1 (T = sum_k x_k T_k) in every replica; the SE is that of 3 numbers.
  const std::string text =
      "&system n_species = 3, mass = 1.0, 2.0, 4.0, diameter = 1.0, 1.1, 1.2, number_density = 3*0.01,\n"
      "        restitution = 0.8 /\n"
      "&dsmc n_particles = 900, collisions_per_particle = 12.0, replicas = 3, seed = 5 /\n"
      "&output n_samples = 13, scaling_start = 6.0 /\n";
  const auto path = scratch("scaling.h5");
  simulation::run(config_of(text), path.string(), {});
  const auto c = io::h5md::read_observable(path.string(), "sonine_c");
  const auto per_particle = io::h5md::read_observable(path.string(), "collisions_per_particle");
  const std::size_t s = 3;
  std::vector<double> average(s, 0.0);
  double samples = 0.0;
  for (std::size_t i = 1; i < per_particle.value.size(); ++i) {
    if (per_particle.value[i] < 6.0) continue;
    for (std::size_t k = 0; k < s; ++k) average[k] += c.value[i * s + k];
    samples += 1.0;
  }
  ASSERT_EQ(samples, 7.0);  // 6, 7, ..., 12 collisions per particle
  const auto state_c = io::h5md::read_dataset(path.string(), "/observables/scaling_state/sonine_c");
  const auto state_c_error = io::h5md::read_dataset(path.string(), "/observables/scaling_state/sonine_c_error");
  const auto share = io::h5md::read_dataset(path.string(), "/observables/scaling_state/temperature_over_mean");
  ASSERT_EQ(state_c.shape, std::vector<std::size_t>{s});
  double closure = 0.0;
  for (std::size_t k = 0; k < s; ++k) {
    EXPECT_NEAR(state_c.data[k], average[k] / samples, 1e-12) << "species " << k + 1;
    EXPECT_GT(state_c_error.data[k], 0.0);
    closure += share.data[k] / 3.0;  // x_k = 1/3
  }
  EXPECT_NEAR(closure, 1.0, 1e-12);
  EXPECT_EQ(io::h5md::read_double_attribute(path.string(), "/observables/scaling_state", "scaling_start"), 6.0);
}

// The energy guard of free and cluster gases (run/replica.hpp): a rise beyond 1e-6 relative between two
// samples stops the run in one line naming both values and times; a fall, or a rise of round-off
// (elastic gases: ~1e-12), does not. By hand on rows of total_temperature.
TEST(Simulation, TheEnergyGuardStopsAGasThatHeats) {
  gdsmc::simulation::ReplicaResult r;
  r.add("time", 1, {0.0});
  r.add("total_temperature", 1, {1.0});
  EXPECT_NO_THROW(gdsmc::simulation::check_energy_does_not_grow(r, "total_temperature"));  // one sample
  r.add("time", 1, {5.0});
  r.add("total_temperature", 1, {1.0 + 1e-9});
  EXPECT_NO_THROW(gdsmc::simulation::check_energy_does_not_grow(r, "total_temperature"));
  r.add("time", 1, {10.0});
  r.add("total_temperature", 1, {0.5});
  EXPECT_NO_THROW(gdsmc::simulation::check_energy_does_not_grow(r, "total_temperature"));
  r.add("time", 1, {20.0});
  r.add("total_temperature", 1, {0.51});
  try {
    gdsmc::simulation::check_energy_does_not_grow(r, "total_temperature");
    ADD_FAILURE() << "a rise of 2 % passed";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("rose from 0.5 to 0.51 between t = 10 and t = 20"), std::string::npos) << m;
  }
  EXPECT_NO_THROW(gdsmc::simulation::check_energy_does_not_grow(r, "total_energy"));  // no such row
}

// The progress line's t and T with more replicas than threads: the replicas that have not begun (t = 0)
// and those done (later t, lower T) are left out while any runs; when none runs, the finished ones'.
TEST(Progress, PositionOfTheRunningReplicas) {
  const double none = std::nan("");
  // 0, 1 finished at t = 8 (T 0.5, 0.7), 2, 3 running at t = 3 and 2 (T 1.0, 2.0), 4 not begun
  const std::vector<double> fraction{1.0, 1.0, 0.4, 0.3, 0.0}, time{8.0, 8.0, 3.0, 2.0, 0.0},
      temperature{0.5, 0.7, 1.0, 2.0, none};
  const std::vector<char> started{1, 1, 1, 1, 0};
  EXPECT_EQ(gdsmc::simulation::replicas_position(fraction, time, temperature, started), ", t = 2, T = 1.5 at the last sample");
  // none running: the finished ones' latest t and mean T
  const std::vector<char> waiting{1, 1, 0, 0, 0};
  EXPECT_EQ(gdsmc::simulation::replicas_position(fraction, time, temperature, waiting), ", t = 8, T = 0.6 at the last sample");
  // a running replica without a sample yet: no T
  EXPECT_EQ(gdsmc::simulation::replicas_position({0.1}, {0.5}, {none}, {1}), ", t = 0.5");
  // nothing begun
  EXPECT_EQ(gdsmc::simulation::replicas_position({0.0, 0.0}, {0.0, 0.0}, {none, none}, {0, 0}), ", t = 0");
}
