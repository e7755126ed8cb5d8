// Every path of issue 11, end to end: the collision rate of whole runs (simulation::run, the code
// granular-dsmc runs) on each path, beside the one-species `t_end` run of the same N, as ratios
// measured in one process one after another on the same machine.
//
// usage: bench_paths [--no-pairs] [--repeat R] [N ...]   (default: 100000 1000000; add 10000000 for the large case)
//        bench_paths --species [--threads T] [--repeat R] [N]   (default N = 1000000)
//   --species: the species sweep, M = 1, 2, 8, 32, 100, 128, 129, 256, 257, 1e3, 1e4, 1e5 species, `lowrank`
//               (masses k, diameters k^(1/3), equal number densities adding up to 0.01, alpha = 0.9,
//               collisions_per_particle = 10, one replica, one thread), each in a child process: its
//               collision-loop rate, ns per collision, ratio to M = 1, the whole process's wall seconds,
//               its peak memory (maximum resident set) in bytes per particle, its cache blocks and their draw;
//               with --threads T (T >= 2) each M runs again on T threads right after, and the speed-up of
//               its collision loop (events per wall second on T threads over those on one; a run of one
//               block, unblocked, uses one thread: about 1) follows the draw. With --repeat R (R >= 2) each
//               M runs R times, each right after a run of M = 1 (and followed by its run on T threads), and
//               its ratio and speed-up are the medians of the R pairs (their least and largest beside them),
//               its rate the median of its runs: a machine whose speed drifts over the sweep's minute moves
//               a pair's two runs alike.
//   --no-pairs: skip the two `pairs` rows (about 25 s each at N = 1e6), e.g. to repeat the others often.
//   --repeat R: R rounds (R >= 2) in which every path runs right after a run of the reference (one species,
//               t_end), its ratio taken against that run: on a machine whose speed drifts from second to
//               second (a shared host) the pair sees the same speed where one reference for the whole
//               table would not. Prints each path's median rate and the median, quartiles and range of
//               its R paired ratios.
//
// Paths (README "Performance", docs/performance.md): one species driven by t_end (the reference) and by
// collisions_per_particle; a binary mixture (masses 1 and 4, diameters 1 and 1.5, alpha = 0.8) with
// `majorant`, `lowrank`, Enskog (packing fraction 0.1; `majorant` and `lowrank`) and `pairs`; 20 species
// of Bodrova and Osinsky 2024's Fig 8 law with `lowrank` (13 of them scattered over the blocks at N = 1e5 and 1e6); one species with
// `pairs`; one replica of the reference case on 2 threads (its blocks on threads, collide.hpp
// "Threads inside one replica") against 1; uniform shear flow with the Gaussian thermostat (stages,
// frames in blocks) and the aggregation/fragmentation full model (cluster blocks), on 1 and 2 threads. Each run is about 10 collisions per particle. The rate is
// events per second of the collision loop (Summary::events_per_second: setup and sampling are not
// counted), on one replica; the thread row gives the ratio of wall-clock rates. "CPU coll/s" is the
// run's collisions over the CPU time of the whole run (setup and output included; all threads added),
// which a machine shared with other jobs disturbs less than the wall clock.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "run/simulation.hpp"
#include "io/config.hpp"
#include "io/namelist.hpp"

#include "bench_args.hpp"

using namespace gdsmc;

namespace {

struct Path {
  const char* name;
  std::string system;  // the &system group's body
  std::string scheme;
  bool time_driven;
  int threads;
  std::string extra = "";  // further groups (&thermostat and &shear, &agg_frag)
};

const std::string kOne = "n_species = 1\n mass = 1.0\n diameter = 1.0\n number_density = 0.01\n restitution = 0.9\n";
const std::string kBinary =
    "n_species = 2\n mass = 1.0, 4.0\n diameter = 1.0, 1.5\n number_density = 0.005, 0.005\n restitution = 0.8\n";
// Packing fraction pi/6 (n_1 + n_2 1.5^3) = 0.1 at n_1 = n_2 = 0.0437.
const std::string kEnskog = "n_species = 2\n mass = 1.0, 4.0\n diameter = 1.0, 1.5\n"
                            " number_density = 0.0437, 0.0437\n restitution = 0.8\n enskog = .true.\n";

// Bodrova and Osinsky 2024, Fig 8's law (validation/msd_many_species), dilute: m_k = k, sigma_k = k^(1/3), n_k = n_1 k^-3,
// 20 species (N_20 = N / (1.2 8000), 10 at N = 1e5).
const std::string kMany = "n_species = 20\n mass = 1.0\n diameter = 1.0\n number_density = 0.01\n mass_law = 'linear'\n"
                          " diameter_law = 'cube_root'\n density_law = 'power'\n density_exponent = 3.0\n restitution = 0.8\n";

// Uniform shear flow with the Gaussian thermostat (validation/shear_viscosity's rate), and the full
// aggregation/fragmentation model of validation/aggregation_fragmentation.
const std::string kShear = "&thermostat\n kind = 'gaussian'\n/\n&shear\n rate = 0.00284\n/\n";
const std::string kWhiteNoise = "&thermostat\n kind = 'white_noise'\n noise_strength = 0.001\n/\n";
const std::string kAggFrag =
    "&agg_frag\n aggregation_energy = 0.5\n fragmentation_energy = 1.5\n fragment_restitution = 0.5\n/\n";

std::string namelist(const Path& p, std::size_t n, double t_end, double per_particle) {
  const std::string initial = p.system.find("n_species = 2\n") != std::string::npos ? "1.0, 1.0" : "1.0";
  std::string text = "&system\n " + p.system + "/\n&initial\n temperature = " + initial + "\n/\n&dsmc\n scheme = '" +
                     p.scheme + "'\n n_particles = " + std::to_string(n) + "\n replicas = 1\n seed = 1\n";
  if (t_end > 0.0)
    text += " t_end = " + std::to_string(t_end) + "\n";
  else
    text += " collisions_per_particle = " + std::to_string(per_particle) + "\n";
  text += " allow_long_run = .true.\n/\n&output\n n_samples = 2\n/\n" + p.extra;
  return text;
}

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

simulation::Summary run(const std::string& text, int threads) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  const auto config = io::config::read(io::namelist::parse(text, "bench_paths.nml"));
  const std::string out = (std::filesystem::temp_directory_path() /
                           ("bench_paths_" + std::to_string(::getpid()) + ".h5")).string();
  std::filesystem::remove(out);
  const simulation::Summary s = simulation::run(config, out, simulation::Options{});
  std::filesystem::remove(out);
  return s;
}

/// What a sweep's child sends back: its collision loop's rate, and its blocks and their draw (Summary).
struct ChildReport {
  double rate;
  std::uint64_t blocks;
  char draw[64];
};

/// One run of the species sweep in a child process, so that its peak memory is its own: its report,
/// its peak resident memory in KiB and its wall seconds (whole process); false if it failed.
bool sweep_child(const std::string& text, long m, int threads, ChildReport& report, long& peak_kib, double& wall) {
  int channel[2];
  if (::pipe(channel) != 0) return false;
  std::fflush(stdout);  // (the child must not print the parent's buffer again)
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(channel[0]), ::close(channel[1]);
    return false;
  }
  if (child == 0) {
    ::close(channel[0]);
    ChildReport mine{};
    try {
      const simulation::Summary s = run(text, threads);
      mine.rate = s.events_per_second;
      mine.blocks = s.blocks.count;
      std::snprintf(mine.draw, sizeof mine.draw, "%s", s.blocks.draw.c_str());
    } catch (const std::exception& e) {  // one line, and no temporary output left (run() removes it)
      std::fprintf(stderr, "bench_paths: %ld species: %s\n", m, e.what());
      ::_exit(1);
    }
    const ssize_t written = ::write(channel[1], &mine, sizeof mine);
    ::_exit(written == sizeof mine ? 0 : 1);
  }
  ::close(channel[1]);
  report = ChildReport{};
  const ssize_t got = ::read(channel[0], &report, sizeof report);
  ::close(channel[0]);
  int status = 0;
  rusage usage{};
  ::wait4(child, &status, 0, &usage);
  wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  peak_kib = usage.ru_maxrss;
  report.draw[sizeof report.draw - 1] = '\0';
  return got == sizeof report && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// The species sweep's namelist: M species of masses k, diameters k^(1/3), equal densities adding up to 0.01.
std::string species_namelist(long m, std::size_t n) {
  char density[32];
  std::snprintf(density, sizeof density, "%.17g", 0.01 / static_cast<double>(m));
  return "&system\n n_species = " + std::to_string(m) + "\n mass = 1.0\n diameter = 1.0\n number_density = " +
         std::string(density) + "\n mass_law = 'linear'\n diameter_law = 'cube_root'\n"
         " density_law = 'power'\n density_exponent = 0.0\n restitution = 0.9\n/\n&initial\n temperature = 1.0\n/\n"
         "&dsmc\n scheme = 'lowrank'\n n_particles = " + std::to_string(n) +
         "\n replicas = 1\n seed = 1\n collisions_per_particle = 10.0\n allow_long_run = .true.\n/\n&output\n n_samples = 2\n/\n";
}

/// The median of `v` (not empty) and its least and largest value.
struct Spread {
  double median, least, largest;
};
Spread spread(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return {v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]), v.front(), v.back()};
}

/// One M of the sweep: `repeat` rounds of (with repeat > 1) the M = 1 reference, M on one thread and (with
/// `threads` > 1) M on that many. Rates per round; false if a run of M failed.
struct SweepRounds {
  std::vector<double> rate, ratio, speedup, wall;
  long peak_kib = 0;
  ChildReport report{};
};
bool sweep_rounds(long m, std::size_t n, int threads, int repeat, double reference, SweepRounds& out) {
  const std::string text = species_namelist(m, n);
  for (int r = 0; r < repeat; ++r) {
    double ref = reference, wall = 0.0;
    long peak_kib = 0;
    if (repeat > 1) {  // (the pair's reference, right before it)
      ChildReport one{};
      if (!sweep_child(species_namelist(1, n), 1, 1, one, peak_kib, wall)) return false;
      ref = one.rate;
    }
    if (!sweep_child(text, m, 1, out.report, peak_kib, wall)) return false;
    const double rate = out.report.rate;
    out.rate.push_back(rate), out.wall.push_back(wall), out.peak_kib = std::max(out.peak_kib, peak_kib);
    out.ratio.push_back(ref > 0.0 ? rate / ref : 1.0);
    if (threads > 1) {
      ChildReport threaded{};
      long threaded_kib = 0;
      double threaded_wall = 0.0;
      if (!sweep_child(text, m, threads, threaded, threaded_kib, threaded_wall)) return false;
      // (Summary's rate is per thread-second of the collision loop, which runs on min(T, blocks) threads
      // with more than one block, else on one: its rate per wall second is that many times it)
      const auto loop_threads = threaded.blocks > 1 ? std::min<std::uint64_t>(threads, threaded.blocks) : 1;
      out.speedup.push_back(static_cast<double>(loop_threads) * threaded.rate / rate);
    }
  }
  return true;
}

/// The species sweep (usage above); with `threads` > 1 each M also runs on that many threads, right after
/// its one-thread run, and the speed-up of its collision loop (wall-clock rates) is printed; with `repeat` > 1
/// each M's ratio to M = 1 and speed-up are medians of paired runs.
int species_sweep(std::size_t n, int threads, int repeat) {
  const std::vector<long> counts = {1, 2, 8, 32, 100, 128, 129, 256, 257, 1000, 10000, 100000};
  std::printf("species sweep: N = %zu, lowrank, masses k, diameters k^(1/3), equal densities (0.01 in all), "
              "alpha = 0.9, 10 collisions per particle, one replica, one thread%s%s\n", n,
              threads > 1 ? (", and on " + std::to_string(threads) + " threads").c_str() : "",
              repeat > 1 ? (", " + std::to_string(repeat) + " rounds each, each after a run of one species: medians "
                            "(least-largest) of the paired ratios").c_str() : "");
  std::printf("%8s %14s %12s %8s %10s %14s %7s  %s\n", "species", "collisions/s", "ns/collision", "ratio", "seconds",
              "bytes/particle", "blocks", threads > 1 ? "draw, speed-up" : "draw");
  double reference = 0.0;  // (one round: the first M's rate)
  for (long m : counts) {
    if (static_cast<std::size_t>(2 * m) > n) break;  // at least 2 particles a species
    SweepRounds rounds;
    if (!sweep_rounds(m, n, threads, repeat, reference, rounds)) {
      std::printf("%8ld %14s\n", m, "(failed)");
      continue;
    }
    const Spread rate = spread(rounds.rate), ratio = spread(rounds.ratio);
    if (reference == 0.0) reference = rate.median;
    const double bytes = 1024.0 * static_cast<double>(rounds.peak_kib) / static_cast<double>(n);
    std::printf("%8ld %14.4g %12.1f %8.2f %10.2f %14.0f %7llu  %s", m, rate.median, 1e9 / rate.median, ratio.median,
                spread(rounds.wall).median, bytes, static_cast<unsigned long long>(rounds.report.blocks),
                rounds.report.draw);
    if (repeat > 1) std::printf(" (ratio %.2f-%.2f)", ratio.least, ratio.largest);
    if (threads > 1) {
      const Spread speedup = spread(rounds.speedup);
      std::printf(", %.2f", speedup.median);
      if (repeat > 1) std::printf(" (%.2f-%.2f)", speedup.least, speedup.largest);
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "--species") {
    const char* usage =
        "usage: bench_paths --species [--threads T: 1..1024] [--repeat R: 1..1000] [N]   (N: 2..1e9; default 1000000)\n";
    unsigned long long n = 1000000ull, threads = 1, repeat = 1;
    bool sized = false, threaded = false, repeated = false;
    for (int i = 2; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h") {
        std::printf("%s", usage);
        return 0;
      }
      const bool ok =
          arg == "--threads"  ? !threaded && i + 1 < argc && (threaded = bench::parse_whole(argv[++i], 1, 1024, threads))
          : arg == "--repeat" ? !repeated && i + 1 < argc && (repeated = bench::parse_whole(argv[++i], 1, 1000, repeat))
                              : !sized && (sized = bench::parse_whole(argv[i], 2, 1000000000ull, n));
      if (!ok) {
        std::fprintf(stderr, "bench_paths: bad or repeated argument '%s'\n%s", argv[i], usage);
        return 2;
      }
    }
    return species_sweep(n, static_cast<int>(threads), static_cast<int>(repeat));
  }
  std::vector<std::size_t> sizes;
  bool pairs = true;
  int repeat = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--no-pairs") {
      pairs = false;
      continue;
    }
    unsigned long long n = 0, r = 0;
    if (std::string(argv[i]) == "--repeat" && i + 1 < argc && bench::parse_whole(argv[i + 1], 1, 1000, r)) {
      repeat = static_cast<int>(r);
      ++i;
      continue;
    }
    if (!bench::parse_whole(argv[i], 2, 1000000000ull, n)) {
      const bool help = std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h";
      std::fprintf(help ? stdout : stderr,
                   "usage: bench_paths [--no-pairs] [--repeat R: 1..1000] [N ...]   (N: 2..1e9; default 100000 1000000)\n"
                   "       bench_paths --species [--threads T] [--repeat R] [N]\n");
      return help ? 0 : 2;
    }
    sizes.push_back(n);
  }
  if (sizes.empty()) sizes = {100000, 1000000};
  const std::vector<Path> paths = {
      {"one species, t_end", kOne, "majorant", true, 1},
      {"one species, collisions_per_particle", kOne, "majorant", false, 1},
      {"binary mixture, majorant", kBinary, "majorant", true, 1},
      {"binary mixture, lowrank", kBinary, "lowrank", true, 1},
      {"binary mixture, Enskog (phi = 0.1)", kEnskog, "majorant", true, 1},
      {"binary mixture, Enskog, lowrank", kEnskog, "lowrank", true, 1},
      {"20 species (Fig 8 law), lowrank", kMany, "lowrank", true, 1},
      {"binary mixture, pairs", kBinary, "pairs", true, 1},
      {"one species, pairs", kOne, "pairs", true, 1},
      {"one species, t_end, 2 threads", kOne, "majorant", true, 2},
      {"one species, shear flow + thermostat", kOne, "majorant", true, 1, kShear},
      {"the same, 2 threads", kOne, "majorant", true, 2, kShear},
      {"aggregation/fragmentation", kOne, "lowrank", true, 1, kAggFrag},
      {"the same, 2 threads", kOne, "lowrank", true, 2, kAggFrag},
      {"rough, one species (beta = 0)", kOne + " roughness = 0.0\n", "majorant", true, 1},
      {"rough, binary mixture (beta = 0.5)", kBinary + " roughness = 0.5\n", "majorant", true, 1},
      {"one species, white noise", kOne, "majorant", true, 1, kWhiteNoise},
  };
  constexpr double per_particle = 10.0;
  struct Measured {
    double rate, per_particle, wall, cpu_rate;
  };
  for (std::size_t n : sizes) {
    // The time of ~10 collisions per particle of each path, from a short collision-driven pilot of the same gas.
    std::vector<double> t_end(paths.size(), 0.0);
    for (std::size_t q = 0; q < paths.size(); ++q)
      if (paths[q].time_driven) {
        Path pilot = paths[q];
        if (pilot.extra != kAggFrag) pilot.scheme = "majorant";  // a staged run takes only t_end: its plain gas
        if (pilot.extra == kShear || pilot.extra == kWhiteNoise) pilot.extra.clear();
        t_end[q] = run(namelist(pilot, pilot.system == kMany ? 100000 : 20000, 0.0, per_particle), 1).final_time;
      }
    const auto measure = [&](std::size_t q) {
      const auto start = std::chrono::steady_clock::now();
      const double cpu_start = cpu_seconds();
      const simulation::Summary s = run(namelist(paths[q], n, t_end[q], per_particle), paths[q].threads);
      const double cpu = cpu_seconds() - cpu_start;
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return Measured{s.events_per_second, s.collisions_per_particle, wall,
                      s.collisions_per_particle * static_cast<double>(n) / 2.0 / cpu};
    };
    const auto skipped = [&](std::size_t q) { return paths[q].scheme == "pairs" && (!pairs || n > 1000000); };
    if (repeat == 1) {
      std::printf("N = %zu, one replica, ~%g collisions per particle per run\n", n, per_particle);
      std::printf("%-40s %14s %12s %10s %10s %12s\n", "path", "collisions/s", "coll/part.", "seconds", "ratio",
                  "CPU coll/s");
      double reference = 0.0;
      for (std::size_t q = 0; q < paths.size(); ++q) {
        if (skipped(q)) {  // pairs: ~3e5 collisions/s, minutes at N = 1e7
          if (pairs) std::printf("%-40s %14s\n", paths[q].name, "(skipped above N = 1e6)");
          continue;
        }
        const Measured m = measure(q);
        if (reference == 0.0) reference = m.rate;
        std::printf("%-40s %14.4g %12.2f %10.2f %10.2f %12.4g\n", paths[q].name, m.rate, m.per_particle, m.wall,
                    m.rate / reference, m.cpu_rate);
        std::fflush(stdout);
      }
      continue;
    }
    // Paired rounds: reference, path; reference, next path; ... R times.
    std::vector<std::vector<double>> rates(paths.size()), ratios(paths.size());
    for (int r = 0; r < repeat; ++r) {
      for (std::size_t q = 1; q < paths.size(); ++q) {
        if (skipped(q)) continue;
        const Measured ref = measure(0), m = measure(q);
        rates[0].push_back(ref.rate);
        rates[q].push_back(m.rate);
        ratios[q].push_back(m.rate / ref.rate);
      }
      std::fprintf(stderr, "bench_paths: N = %zu, round %d of %d done\n", n, r + 1, repeat);
    }
    const auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      const std::size_t m = v.size() / 2;
      return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
    };
    std::printf("N = %zu, one replica, ~%g collisions per particle per run, %d paired rounds\n", n, per_particle, repeat);
    std::printf("%-40s %14s %8s %15s %15s\n", "path", "median coll/s", "ratio", "quartiles", "range");
    std::printf("%-40s %14.4g %8.2f\n", paths[0].name, median(rates[0]), 1.0);
    for (std::size_t q = 1; q < paths.size(); ++q) {
      if (ratios[q].empty()) continue;
      std::vector<double> v = ratios[q];
      std::sort(v.begin(), v.end());
      const std::size_t k = v.size();
      std::printf("%-40s %14.4g %8.2f %7.2f-%-7.2f %7.2f-%-7.2f\n", paths[q].name, median(rates[q]), median(v),
                  v[k / 4], v[(3 * k) / 4 < k ? (3 * k) / 4 : k - 1], v.front(), v.back());
    }
    std::fflush(stdout);
  }
  return 0;
}
