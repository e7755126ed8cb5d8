// 'majorant' against 'pairs' on one binary mixture. See README.md in this folder.
#include <cmath>
#include <cstring>
#include <filesystem>

#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  std::vector<char*> args(argv, argv + argc);
  std::string stem = "schemes_agree";
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--output") == 0) stem = std::filesystem::path(argv[i + 1]).replace_extension().string();
  std::vector<validation::Case> runs;
  for (const char* scheme : {"majorant", "pairs", "lowrank"}) {
    std::vector<std::string> storage = {"--set", std::string("dsmc:scheme='") + scheme + "'", "--output",
                                        stem + "_" + scheme + ".h5"};
    std::vector<char*> a;
    for (int i = 0; i < argc; ++i) {
      if (std::strcmp(argv[i], "--output") == 0) {
        ++i;
        continue;
      }
      a.push_back(argv[i]);
    }
    for (auto& s : storage) a.push_back(s.data());
    runs.push_back(validation::run_case(static_cast<int>(a.size()), a.data(), stem + ".h5"));
  }
  const std::size_t s = runs[0].config.mixture().size();
  validation::Report report("majorant vs pairs vs lowrank, binary mixture", stem + ".report.txt");
  const auto t1 = validation::observable(runs[0], "temperature");
  if (!report.require("replicas > 1, so standard errors exist", !t1.error.empty()))
    return report.exit_code();
  const std::size_t nt = t1.time.size();
  const std::size_t n_pairs = s * (s + 1) / 2;
  // 'majorant' is the reference each other scheme is compared with (printed as 'theory').
  for (std::size_t other = 1; other < runs.size(); ++other) {
    const std::string label = runs[other].config.dsmc.scheme;
    auto compare = [&](const std::string& name, const io::h5md::ObservableData& a,
                       const io::h5md::ObservableData& b, std::size_t idx) {
      report.check(label + ": " + name, b.value[idx], std::hypot(a.error[idx], b.error[idx]), a.value[idx], 4.0);
    };
    const auto t2 = validation::observable(runs[other], "temperature");
    for (std::size_t i = 1; i < nt; i += 2)
      for (std::size_t k = 0; k < s; ++k) {
        char name[128];
        std::snprintf(name, sizeof name, "T_%zu at t = %.4g", k + 1, t1.time[i]);
        compare(name, t1, t2, i * s + k);
      }
    const auto c1 = validation::observable(runs[0], "sonine_c");
    const auto c2 = validation::observable(runs[other], "sonine_c");
    for (std::size_t k = 0; k < s; ++k) compare("c_" + std::to_string(k + 1) + " at the end", c1, c2, (nt - 1) * s + k);
    const auto p1 = validation::observable(runs[0], "collisions_pair");
    const auto p2 = validation::observable(runs[other], "collisions_pair");
    for (std::size_t p = 0; p < n_pairs; ++p)
      compare("events of pair column " + std::to_string(p) + " at the end", p1, p2, (nt - 1) * n_pairs + p);
  }
  return report.exit_code();
}
