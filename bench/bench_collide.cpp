// Collision-kernel throughput: accepted collisions per second, candidate pairs per collision and the
// cost of one candidate, for every blocked path of issue 11 and the unblocked `pairs`.
//
// usage: bench_collide [N] [alpha] [collisions_per_particle] [block_size] [paths] [rounds] [sampler]
//   block_size: default &dsmc's; 0: no blocks. Blocks apply to majorant and lowrank; pairs always runs
//               unblocked.
//   paths:      comma-separated names of the table below, or "all" (default: every path but the slow
//               `pairs` ones at N > 1e5, and but the sweep_M ones).
//               sweep_M (M = 2, 8, 32, 100, 128, 129, 256, 1000, 10000, 100000): the gas of `bench_paths
//               --species` (m_k = k, sigma_k = k^(1/3), n_k = 0.01/M, `lowrank`), so that its ratios split
//               into candidates per collision and the cost of a candidate.
//   rounds:     the paths run one after another this many times in one process (default 1); with more
//               than one, each path's best (largest rate, smallest ns/cand) and median figures follow.
//   sampler:    `cheaper` (default: a mixture's blocks run the cheaper of the two samplers, as a run does;
//               collide.hpp "Mixtures in blocks") or `scheme` (the path's own scheme's sampler: its kernel).
// Default: the reference case, N = 1e6, alpha = 0.9, 10 collisions per particle timed. The gases
// are those of bench_paths (one species; binary, masses 1 and 4, diameters 1 and 1.5; the same at packing
// fraction 0.1, Enskog; `many_*`: 20 species, m_k = k, sigma_k = k^(1/3), n_k ~ k^-3). "cand/coll" is candidates per accepted collision (1/acceptance), "ns/cand" the
// time of the timed advance() over its candidates (everything counted: collisions, bounds, remixes), so
// that ns per collision = cand/coll x ns/cand. Times are the process's CPU time (one thread), which a
// machine shared with other jobs disturbs less than the wall clock does (caches are still shared).
// Figures are for comparing builds and paths on one machine in one run (ratios), not absolute.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "model/species.hpp"
#include "io/config.hpp"

#include "bench_args.hpp"

using namespace gdsmc;

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Result {
  double events_per_second, candidates_per_event, ns_per_candidate, seconds, bytes_per_particle;
};

struct Path {
  std::string name;
  collide::Scheme scheme;
  int gas;  // 0: one species, 1: binary, 2: binary Enskog, 3: 20 species of Bodrova and Osinsky 2024's Fig 8 law,
           // 4: bench_paths --species' gas of `species` species
  long species = 1;
};

species::Mixture gas_of(int gas, double alpha, long m) {
  if (gas == 4) {  // m_k = k, sigma_k = k^(1/3), n_k = 0.01/M (bench_paths --species)
    std::vector<double> mass, diameter, density;
    for (long k = 1; k <= m; ++k) {
      mass.push_back(static_cast<double>(k));
      diameter.push_back(std::cbrt(static_cast<double>(k)));
      density.push_back(0.01 / static_cast<double>(m));
    }
    return species::make_mixture(mass, diameter, density, species::PairMatrix::uniform(static_cast<std::size_t>(m), alpha), false);
  }
  if (gas == 0) return species::make_mixture({1.0}, {1.0}, {0.01}, species::PairMatrix(1, alpha), false);
  if (gas == 3) {  // m_k = k, sigma_k = k^(1/3), n_k = 0.01 k^-3 (bench_paths' "20 species", dilute)
    std::vector<double> mass, diameter, density;
    for (int k = 1; k <= 20; ++k) {
      mass.push_back(k);
      diameter.push_back(std::cbrt(static_cast<double>(k)));
      density.push_back(0.01 / (static_cast<double>(k) * k * k));
    }
    return species::make_mixture(mass, diameter, density, species::PairMatrix(20, alpha), false);
  }
  // Packing fraction pi/6 (n_1 + n_2 1.5^3) = 0.1 at n_1 = n_2 = 0.0437 (bench_paths).
  const double n_k = gas == 1 ? 0.005 : 0.0437;
  return species::make_mixture({1.0, 4.0}, {1.0, 1.5}, {n_k, n_k}, species::PairMatrix(2, alpha), gas == 2);
}

Result measure(const Path& path, double alpha, std::size_t n, double per_particle, std::size_t block_size,
               bool scheme_sampler) {
  const species::Mixture mix = gas_of(path.gas, alpha, path.species);
  auto init = rng::make_stream(1, 0, rng::Purpose::initial_state);
  auto sys = particles::make_system(mix, species::particle_counts(n, mix), std::vector<double>(mix.size(), 1.0),
                                    particles::InitialDistribution::maxwell, init);
  collide::Collider collider(path.scheme, mix, sys, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  collider.use_blocks(block_size);
  if (scheme_sampler)
    collider.set_block_sampler(path.scheme == collide::Scheme::lowrank ? collide::Collider::BlockSampler::lowrank
                                                                       : collide::Collider::BlockSampler::majorant);
  // Warm up caches and bounds (the first step runs on the whole gas), then time by t_end as a
  // time-driven run does: the time of per_particle collisions per particle at the warm-up's rate.
  collider.advance(1e300, static_cast<std::uint64_t>(0.2 * n));
  const auto before = collider.counters();
  const double t0 = collider.time();
  const double t_end = t0 + t0 / (2.0 * static_cast<double>(before.events) / static_cast<double>(n)) * per_particle;
  const double start = cpu_seconds();
  collider.advance(t_end);
  const double seconds = cpu_seconds() - start;
  const auto& after = collider.counters();
  const double events = static_cast<double>(after.events - before.events);
  const double candidates = static_cast<double>(after.candidates - before.candidates);
  // Particle data (velocities, species) and the collider's per-particle buffers (blocks' remix).
  const double bytes = static_cast<double>(sys.v.capacity() * sizeof(particles::Vec3) +
                                           sys.species.capacity() * sizeof(std::uint32_t) +
                                           sys.r.capacity() * sizeof(particles::Displacement) +
                                           collider.workspace_bytes());
  return {events / seconds, candidates / events, 1e9 * seconds / candidates, seconds,
          bytes / static_cast<double>(n)};
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const std::size_t m = x.size() / 2;
  return x.size() % 2 ? x[m] : 0.5 * (x[m - 1] + x[m]);
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Args args(argc, argv,
                         "usage: bench_collide [N: 100..1e9] [alpha in [0, 1]] [collisions_per_particle: 0..1e4] "
                         "[block_size: 0 or >= 64] [paths|all] [rounds: 1..1000] [cheaper|scheme]",
                         7);
  const std::size_t n = args.whole(1, 1000000, 100, 1000000000);
  const double alpha = args.real(2, 0.9, 0.0, 1.0);
  const double per_particle = args.real(3, 10.0, 1e-9, 1e4);
  // The default of &dsmc block_size; 0 measures the kernels without blocks.
  const auto block_size = static_cast<std::size_t>(args.whole(4, io::config::Dsmc{}.block_size, 0, 1000000000));
  if (block_size != 0 && block_size < 64) args.fail("block_size must be 0 (no blocks) or at least 64");
  const std::string selected = args.text(5, "");
  const int rounds = static_cast<int>(args.whole(6, 1, 1, 1000));
  const std::string sampler = args.text(7, "cheaper");
  if (sampler != "cheaper" && sampler != "scheme") {
    std::fprintf(stderr, "bench_collide: sampler must be 'cheaper' or 'scheme', not '%s'\n", sampler.c_str());
    return 2;
  }
  std::vector<Path> all = {
      {"one_majorant", collide::Scheme::majorant, 0},    {"one_lowrank", collide::Scheme::lowrank, 0},
      {"binary_majorant", collide::Scheme::majorant, 1}, {"binary_lowrank", collide::Scheme::lowrank, 1},
      {"enskog_majorant", collide::Scheme::majorant, 2}, {"enskog_lowrank", collide::Scheme::lowrank, 2},
      {"many_majorant", collide::Scheme::majorant, 3},   {"many_lowrank", collide::Scheme::lowrank, 3},
      {"one_pairs", collide::Scheme::pairs, 0},          {"binary_pairs", collide::Scheme::pairs, 1},
  };
  for (long m : {2L, 8L, 32L, 100L, 128L, 129L, 256L, 1000L, 10000L, 100000L})
    all.push_back({"sweep_" + std::to_string(m), collide::Scheme::lowrank, 4, m});
  std::vector<Path> paths;
  for (const Path& p : all) {
    const bool chosen = selected.empty() ? ((p.scheme != collide::Scheme::pairs || n <= 100000) && p.gas != 4)
                                         : selected == "all" || ("," + selected + ",").find("," + p.name + ",") !=
                                                                    std::string::npos;
    if (chosen) paths.push_back(p);
  }
  // A name that is no path is a typo, not an empty table.
  if (!selected.empty() && selected != "all") {
    std::string rest = selected + ",";
    for (std::size_t at = 0, comma; (comma = rest.find(',', at)) != std::string::npos; at = comma + 1) {
      const std::string name = rest.substr(at, comma - at);
      if (std::none_of(all.begin(), all.end(), [&](const Path& p) { return p.name == name; })) {
        std::fprintf(stderr, "bench_collide: no path '%s' (paths: all", name.c_str());
        for (const Path& p : all) std::fprintf(stderr, ", %s", p.name.c_str());
        std::fprintf(stderr, ")\n");
        return 2;
      }
    }
  }
  std::printf("N = %zu, alpha = %g, %g collisions per particle timed, block_size = %zu, %d round(s)\n", n, alpha,
              per_particle, block_size, rounds);
  std::printf("%-16s %14s %10s %9s %9s %10s\n", "path", "collisions/s", "cand/coll", "ns/cand", "seconds",
              "bytes/part");
  std::map<std::string, std::vector<Result>> results;
  // (a sweep gas needs at least 2 particles a species, as bench_paths --species)
  std::erase_if(paths, [&](const Path& p) {
    const bool too_few = p.gas == 4 && static_cast<std::size_t>(2 * p.species) > n;
    if (too_few) std::fprintf(stderr, "bench_collide: %s skipped: N = %zu is below 2 particles a species\n", p.name.c_str(), n);
    return too_few;
  });
  for (int round = 0; round < rounds; ++round)
    for (const Path& p : paths) {
      const Result r = measure(p, alpha, n, per_particle, block_size, sampler == "scheme");
      results[p.name].push_back(r);
      std::printf("%-16s %14.4g %10.3f %9.2f %9.2f %10.1f\n", p.name.c_str(), r.events_per_second,
                  r.candidates_per_event, r.ns_per_candidate, r.seconds, r.bytes_per_particle);
      std::fflush(stdout);
    }
  if (rounds > 1) {
    std::printf("\n%-16s %22s %10s %20s\n", "path", "collisions/s max/med", "cand/coll", "ns/cand min/med");
    for (const Path& p : paths) {
      std::vector<double> rate, cand, ns;
      for (const Result& r : results[p.name]) {
        rate.push_back(r.events_per_second);
        cand.push_back(r.candidates_per_event);
        ns.push_back(r.ns_per_candidate);
      }
      std::printf("%-16s %10.4g %10.4g %10.3f %9.2f %9.2f\n", p.name.c_str(), *std::max_element(rate.begin(), rate.end()),
                  median(rate), median(cand), *std::min_element(ns.begin(), ns.end()), median(ns));
    }
  }
  return 0;
}
