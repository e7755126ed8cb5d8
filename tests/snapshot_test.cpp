// Unit tests for gdsmc::io::snapshot: particle snapshots written to /particles and read back, and the
// temperatures of a snapshot against numbers computed by hand.
#include "io/snapshot.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/h5md.hpp"
#include "model/observables.hpp"
#include "model/species.hpp"

namespace {

namespace fs = std::filesystem;
using namespace gdsmc;

fs::path temporary(const std::string& name) {
  return fs::temp_directory_path() / ("gdsmc-snapshot-" + std::to_string(::getpid()) + "-" + name);
}

species::Mixture binary() {
  auto mix = species::make_mixture({1.0, 4.0}, {1.0, 2.0}, {0.01, 0.01}, species::PairMatrix(2, 0.9), false);
  mix.moment_of_inertia = {0.4, 0.5};
  return mix;
}

// Species 1 (m = 1): (1, 0, 0) and (-1, 0, 0); species 2 (m = 4): (0, 1, 0) and (0, -1, 0), all shifted by a
// mean flow (0.5, 0, 0). About the flow: T_1 = 1 (1 + 1)/(3 x 2) = 1/3, T_2 = 4 (1 + 1)/(3 x 2) = 4/3.
// Angular velocities (1, 0, 0) for species 1 and (0, 0, 2) for species 2: I_1 = 0.4 x 1 x 1/4 = 0.1,
// I_2 = 0.5 x 4 x 4/4 = 2, T_rot,1 = 0.1 x 1/3, T_rot,2 = 2 x 4/3.
io::snapshot::State by_hand() {
  io::snapshot::State s;
  s.species = {1, 1, 2, 2};
  s.velocity = {1.5, 0, 0, -0.5, 0, 0, 0.5, 1, 0, 0.5, -1, 0};
  s.angular_velocity = {1, 0, 0, 1, 0, 0, 0, 0, 2, 0, 0, 2};
  return s;
}

TEST(Snapshot, TemperaturesAboutTheMeanFlowByHand) {
  const auto t = io::snapshot::temperatures(by_hand(), binary());
  ASSERT_EQ(t.translational.size(), 2u);
  EXPECT_NEAR(t.translational[0], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(t.translational[1], 4.0 / 3.0, 1e-15);
  ASSERT_EQ(t.rotational.size(), 2u);
  EXPECT_NEAR(t.rotational[0], 0.1 / 3.0, 1e-15);
  EXPECT_NEAR(t.rotational[1], 2.0 * 4.0 / 3.0, 1e-15);
  auto smooth = by_hand();
  smooth.angular_velocity.clear();
  EXPECT_TRUE(io::snapshot::temperatures(smooth, binary()).rotational.empty());
  // A smooth run's mixture (no moments of inertia) started from a rough run's snapshot: the angular
  // velocities are not read (this read past the empty moments and crashed), the temperatures are the same.
  auto plain = binary();
  plain.moment_of_inertia.clear();
  const auto from_rough = io::snapshot::temperatures(by_hand(), plain);
  EXPECT_TRUE(from_rough.rotational.empty());
  EXPECT_EQ(from_rough.translational, t.translational);
}

TEST(Snapshot, RowsWrittenAndReadBack) {
  // Two replicas of four particles, two snapshots each: rows as a run collects them (replica.cpp).
  std::map<std::string, observables::Accumulator> rows;
  for (std::size_t r = 0; r < 2; ++r) {
    const double shift = 10.0 * static_cast<double>(r);
    rows["snapshot_time"].columns = 2;
    rows["snapshot_time"].values.push_back({0.0, 0.0, 5.0, 123.0 + shift});
    rows["snapshot_species"].columns = 4;
    rows["snapshot_species"].values.push_back({1, 1, 2, 2});
    std::vector<double> v;
    for (int s = 0; s < 2; ++s)
      for (int i = 0; i < 12; ++i) v.push_back(shift + 100.0 * s + i);
    rows["snapshot_velocity"].columns = 12;
    rows["snapshot_velocity"].values.push_back(v);
  }
  const auto replicas = io::snapshot::from_rows(rows);
  ASSERT_EQ(replicas.size(), 2u);
  EXPECT_EQ(replicas[1].time, (std::vector<double>{0.0, 5.0}));
  EXPECT_EQ(replicas[1].step, (std::vector<std::int64_t>{0, 133}));
  EXPECT_TRUE(replicas[0].angular_velocity.empty());
  const fs::path path = temporary("rows.h5");
  {
    io::h5md::Writer writer(path.string(), "test", "test", "0");
    writer.write_parameters({{"system", "mass", std::vector<double>{1.0, 4.0}}}, "&system /");  // an output's
    io::snapshot::write(writer, "", replicas);
    writer.commit();
  }
  const auto value = io::h5md::read_dataset(path.string(), "/particles/replica_2/velocity/value");
  EXPECT_EQ(value.shape, (std::vector<std::size_t>{2, 4, 3}));
  EXPECT_EQ(io::h5md::read_string_attribute(path.string(), "/particles/replica_2/velocity/value", "unit"), "length time-1");
  EXPECT_EQ(io::snapshot::replicas(path.string()), 2u);
  io::snapshot::check_masses(path.string(), {1.0, 4.0});
  EXPECT_THROW(io::snapshot::check_masses(path.string(), {1.0, 5.0}), std::runtime_error);
  EXPECT_THROW(io::snapshot::read(path.string(), 0, {3, 1}), std::runtime_error);  // 2 + 2, not 3 + 1
  const auto last = io::snapshot::read(path.string(), 3, {2, 2});  // replica 3 of a run: the file's 3 mod 2 + 1 = 2
  EXPECT_EQ(last.species, (std::vector<std::uint64_t>{1, 1, 2, 2}));
  EXPECT_DOUBLE_EQ(last.time, 5.0);
  ASSERT_EQ(last.velocity.size(), 12u);
  EXPECT_DOUBLE_EQ(last.velocity[0], 110.0);  // replica 2 (shift 10), snapshot 2 (100), component 0
  EXPECT_DOUBLE_EQ(last.velocity[11], 121.0);
  EXPECT_TRUE(last.angular_velocity.empty());
  fs::remove(path);
}

TEST(Snapshot, AFileWithoutSnapshotsSaysSo) {
  const fs::path path = temporary("none.h5");
  EXPECT_THROW(io::snapshot::replicas(path.string()), std::runtime_error);  // no such file
  {
    io::h5md::Writer writer(path.string(), "test", "test", "0");
    writer.write_parameters({}, "&system /");
    writer.commit();
  }
  EXPECT_EQ(io::snapshot::replicas(path.string()), 0u);
  try {
    io::snapshot::read(path.string(), 0);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no particle snapshot"), std::string::npos) << e.what();
  }
  fs::remove(path);
}

}  // namespace
