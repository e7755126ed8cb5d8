// Every collision scheme on one binary mixture: 'majorant' without cache blocks (the reference),
// 'majorant' with cache blocks, 'pairs' and 'lowrank' agree on T_k, c_k, the events per species pair
// and the MSD per species at 4 combined standard errors, with no systematic allowance (issue 13).
// See README.md in this folder.
#include <cmath>
#include <filesystem>
#include <iostream>

#include "validation.hpp"

using namespace gdsmc;

namespace {

struct Variant {
  std::string label;   ///< in the report
  std::string scheme;  ///< &dsmc scheme
  bool blocks;         ///< the namelist's block_size (true) or block_size = 0 (false)
};

// The cache blocks that collide.cpp use_blocks() forms for a majorant mixture: K = N / block_size,
// lowered until every species has at least 64 particles per block; none below 2.
std::size_t expected_blocks(long long n, long long block_size, const std::vector<double>& counts) {
  if (block_size <= 0 || n < 2 * block_size) return 1;
  long long k = n / block_size;
  for (double c : counts) k = std::min(k, static_cast<long long>(c) / 64);
  return k < 2 ? 1 : static_cast<std::size_t>(k);
}

}  // namespace

int main(int argc, char** argv) {
  const validation::Variants command = validation::read_variants(argc, argv, "schemes_agree");
  const std::string& stem = command.stem;
  const io::config::Config& config = command.config;
  const long long seed = config.dsmc.seed, block_size = config.dsmc.block_size;

  // Each variant has its own seed (seed + index), so that the five ensembles are independent and the
  // standard error of a difference is the combined one, sqrt(SE_1^2 + SE_2^2).
  const std::vector<Variant> variants = {{"majorant, no blocks", "majorant", false},
                                         {"majorant, blocks", "majorant", true},
                                         {"pairs", "pairs", false},
                                         {"lowrank", "lowrank", false},
                                         {"lowrank, blocks", "lowrank", true}};
  std::vector<validation::Case> runs;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const auto& variant = variants[v];
    runs.push_back(command.run({"--set", "dsmc:scheme='" + variant.scheme + "'",
                                "--set", "dsmc:seed=" + std::to_string(seed + static_cast<long long>(v)),
                                "--set", "dsmc:block_size=" + std::to_string(variant.blocks ? block_size : 0),
                                "--output", stem + "_" + variant.scheme + (variant.blocks ? "_blocks" : "") + ".h5"}));
  }
  const std::size_t s = runs[0].config.mixture().size();
  validation::Report report("all schemes (majorant and lowrank with and without blocks, pairs), binary mixture",
                            stem + ".report.txt");
  const auto t_ref = validation::observable(runs[0], "temperature");
  if (!report.require("replicas > 1, so standard errors exist", !t_ref.error.empty()))
    return report.exit_code();
  const auto number = validation::observable(runs[0], "number");
  const std::size_t blocks = expected_blocks(config.dsmc.n_particles, block_size,
                                             std::vector<double>(number.value.begin(), number.value.begin() + s));
  report.require("the blocked run has at least 2 cache blocks (N = " + std::to_string(config.dsmc.n_particles) +
                     ", block_size = " + std::to_string(block_size) + ": " + std::to_string(blocks) + " blocks)",
                 blocks >= 2);
  if (!report.require("particles are tracked (&output track_displacements), so the MSD is compared",
                      config.output.track_displacements))
    return report.exit_code();
  report.note("ensemble per scheme: " + std::to_string(config.dsmc.replicas) + " replicas x " +
              std::to_string(config.dsmc.n_particles) + " particles, seeds " + std::to_string(seed) + ".." +
              std::to_string(seed + static_cast<long long>(variants.size()) - 1) +
              " (independent ensembles); each line: the scheme's value +- the combined SE of the difference, "
              "the reference (majorant without blocks), |diff| in combined SE, tolerance 4 SE, no allowance");

  const std::size_t nt = t_ref.time.size();
  const std::size_t n_pairs = s * (s + 1) / 2;
  const auto c_ref = validation::observable(runs[0], "sonine_c");
  const auto p_ref = validation::observable(runs[0], "collisions_pair");
  const auto msd_ref = validation::observable(runs[0], "msd");
  for (std::size_t other = 1; other < runs.size(); ++other) {
    const std::string label = variants[other].label;
    auto compare = [&](const std::string& name, const io::h5md::ObservableData& a,
                       const io::h5md::ObservableData& b, std::size_t idx) {
      report.check(label + ": " + name, b.value[idx], std::hypot(a.error[idx], b.error[idx]), a.value[idx], 4.0);
    };
    const auto t = validation::observable(runs[other], "temperature");
    const auto c = validation::observable(runs[other], "sonine_c");
    const auto p = validation::observable(runs[other], "collisions_pair");
    const auto msd = validation::observable(runs[other], "msd");
    if (!report.require(label + ": the same sample times as the reference", t.time == t_ref.time))
      continue;
    // T_k and MSD_k at every second sample time; c_k and the pair events at every fourth and at the end.
    for (std::size_t i = 1; i < nt; ++i) {
      const bool every_second = i % 2 == 1 || i == nt - 1, every_fourth = i % 4 == 0 || i == nt - 1;
      char at[64];
      std::snprintf(at, sizeof at, " at t = %.4g", t_ref.time[i]);
      for (std::size_t k = 0; k < s && every_second; ++k) {
        compare("T_" + std::to_string(k + 1) + at, t_ref, t, i * s + k);
        compare("<R_" + std::to_string(k + 1) + "^2>" + at, msd_ref, msd, i * s + k);
      }
      for (std::size_t k = 0; k < s && every_fourth; ++k) compare("c_" + std::to_string(k + 1) + at, c_ref, c, i * s + k);
      for (std::size_t q = 0; q < n_pairs && every_fourth; ++q)
        compare("events of pair column " + std::to_string(q) + at, p_ref, p, i * n_pairs + q);
    }
  }
  return report.exit_code();
}
