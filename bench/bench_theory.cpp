// Wall-clock time of the s-species theory (\ref perf_theory "docs/performance.md": s = 100 in under a second,
// s = 1000 within a minute) on the polydisperse mixture of examples/03-polydisperse-lowrank:
// species k = 1..s with m_k = k m_1, sigma_k = k^(1/3) sigma_1, n_k = n_1 k^-theta, alpha = 0.8,
// T_k(0) = 1; dilute (n_1 = 0.01, theta = 1.5) and Enskog (n_1 = 0.05, theta = 2).
// Prints per s and density the time of one evaluation of the Maxwellian cooling rates (\ref haff_mixture_odes "docs/haff-and-mixtures.md")
// entry by entry (theory.hpp) and of 100 by the pair sums of theory/maxwellian_rates.hpp,
// the partial-temperature ODEs to t = 500 on 12 log-spaced times, the asymptotic ratios, the
// first-Sonine HCS (theory/sonine_mixture.hpp) and analysis::predict() on the equivalent namelist
// (everything granular-theory computes for it).
// Not run by ctest: build/bin/bench_theory [s ...] (default 10 100 1000).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <unistd.h>
#include <vector>

#include "io/config.hpp"
#include "theory/maxwellian_rates.hpp"
#include "analysis/predictions.hpp"
#include "theory/sonine_mixture.hpp"
#include "theory/theory.hpp"

#include "bench_args.hpp"

namespace theory = gdsmc::theory;
using gdsmc::species::Mixture;
using gdsmc::species::PairMatrix;

namespace {

struct Law {
  const char* name;
  double n1, theta;
  bool enskog;
};

Mixture law_mixture(std::size_t s, const Law& law) {
  std::vector<double> m(s), sigma(s), n(s);
  for (std::size_t k = 0; k < s; ++k) {
    const double kk = static_cast<double>(k + 1);
    m[k] = kk;
    sigma[k] = std::cbrt(kk);
    n[k] = law.n1 * std::pow(kk, -law.theta);
  }
  return gdsmc::species::make_mixture(m, sigma, n, PairMatrix::uniform(s, 0.8), law.enskog);
}

std::string namelist(std::size_t s, const Law& law) {
  char text[1024];
  std::snprintf(text, sizeof text,
                "&system\n n_species = %zu\n mass = 1.0\n mass_law = 'linear'\n diameter = 1.0\n"
                " diameter_law = 'cube_root'\n number_density = %g\n density_law = 'power'\n"
                " density_exponent = %g\n restitution = 0.8\n enskog = %s\n/\n"
                "&initial\n temperature = 1.0\n/\n"
                "&dsmc\n scheme = 'lowrank'\n n_particles = 1000000000\n t_end = 500.0\n/\n"
                "&output\n n_samples = 12\n spacing = 'log'\n first_sample = 5.0\n/\n",
                s, law.n1, law.theta, law.enskog ? ".true." : ".false.");
  return text;
}

/// Wall-clock and CPU seconds of f() (the CPU time is the honest figure on a shared machine).
template <class F>
std::pair<double, double> seconds(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu = std::clock();
  f();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
          static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC};
}

template <class F>
void timed(const char* what, F&& f) {
  try {
    const auto [wall, cpu] = seconds(f);
    std::printf("  %-28s %9.4f s wall %9.4f s cpu\n", what, wall, cpu);
  } catch (const std::exception& e) {
    std::printf("  %-28s failed: %s\n", what, e.what());
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const gdsmc::bench::Args args(argc, argv, "usage: bench_theory [number of species >= 1 ...] (default 10 100 1000)", argc);
  std::vector<std::size_t> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(args.whole(i, 0, 1, 1000000));
  if (sizes.empty()) sizes = {10, 100, 1000};
  const Law laws[] = {{"dilute", 0.01, 1.5, false}, {"enskog", 0.05, 2.0, true}};
  const auto file = std::filesystem::temp_directory_path() /
                    ("bench_theory_" + std::to_string(::getpid()) + ".nml");
  for (std::size_t s : sizes)
    for (const Law& law : laws) {
      const Mixture mix = law_mixture(s, law);
      std::printf("s = %zu, %s (phi = %.3f)\n", s, law.name, mix.packing_fraction());
      const std::vector<double> T0(s, 1.0);
      timed("cooling rates (1 eval)", [&] { theory::partial_temperature_rates(mix, T0); });
      {
        const theory::detail::MaxwellianRates rates(mix);
        std::vector<double> zeta(s);
        timed("pair sums (100 evals)", [&] {
          for (int i = 0; i < 100; ++i) rates.cooling_rates_and_collision_rate(T0, zeta);
        });
      }
      std::vector<double> times;
      for (int i = 0; i < 12; ++i) times.push_back(5.0 * std::pow(100.0, i / 11.0));
      timed("partial-temperature ODEs", [&] { theory::integrate_partial_temperatures(mix, T0, times); });
      timed("asymptotic ratios", [&] { theory::asymptotic_temperature_ratios(mix); });
      timed("first-Sonine HCS", [&] { theory::hcs_first_sonine(mix); });
      std::ofstream(file) << namelist(s, law);
      timed("predict (granular-theory)", [&] {
        const auto p = gdsmc::analysis::predict(gdsmc::io::config::read_file(file.string()));
        for (const auto& note : p.notes) std::printf("    note: %s\n", note.c_str());
      });
    }
  std::filesystem::remove(file);
}
