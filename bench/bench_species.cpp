// Cost per accepted collision against the number of species M (issue 4): the same total particle
// count N, species m_k = k m_1, sigma_k = k^(1/3) sigma_1, equal number densities, alpha = 0.9.
//
// usage: bench_species [N] [max_M]
// Prints, for M = 1, 10, 100, ... up to max_M, accepted collisions per second of `lowrank`, `pairs`
// and `majorant`, and each scheme's cost relative to M = 1. Ratios are what to compare; on a shared
// virtual machine they vary by +-30 % between runs, so for a deterministic comparison count
// instructions instead (valgrind --tool=callgrind on granular-dsmc, see docs/validation-summary.md).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "model/species.hpp"

#include "bench_args.hpp"

using namespace gdsmc;

namespace {

double collisions_per_second(collide::Scheme scheme, std::size_t n, std::size_t m) {
  std::vector<double> mass(m), diameter(m), density(m, 0.01 / static_cast<double>(m));
  for (std::size_t k = 0; k < m; ++k) {
    mass[k] = static_cast<double>(k + 1);
    diameter[k] = std::cbrt(static_cast<double>(k + 1));
  }
  // One restitution for all pairs, stored as one number (as the namelist reader does for many species).
  const auto mix = species::make_mixture(mass, diameter, density, species::PairMatrix::uniform(m, 0.9), false);
  auto init = rng::make_stream(1, 0, rng::Purpose::initial_state);
  auto sys = particles::make_system(mix, species::particle_counts(n, mix), std::vector<double>(m, 1.0),
                                    particles::InitialDistribution::maxwell, init);
  collide::Collider collider(scheme, mix, sys, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  collider.advance(1e300, n / 5);  // warm up
  const auto before = collider.counters().events;
  const auto start = std::chrono::steady_clock::now();
  collider.advance(1e300, before + 5 * n);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return static_cast<double>(collider.counters().events - before) / seconds;
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Args args(argc, argv, "usage: bench_species [N: 2..1e9] [largest number of species: 1..1e6]", 2);
  const std::size_t n = args.whole(1, 200000, 2, 1000000000);
  const std::size_t max_m = args.whole(2, 1000, 1, 1000000);
  std::printf("N = %zu, m_k = k, sigma_k = k^(1/3), equal densities, alpha = 0.9\n", n);
  std::printf("%8s %14s %9s %14s %9s %14s %9s\n", "M", "lowrank /s", "cost", "pairs /s", "cost", "majorant /s", "cost");
  double base[3] = {0, 0, 0};
  for (std::size_t m = 1; m <= max_m && 2 * m <= n; m *= 10) {
    const collide::Scheme schemes[3] = {collide::Scheme::lowrank, collide::Scheme::pairs, collide::Scheme::majorant};
    double rate[3] = {0, 0, 0};
    for (int s = 0; s < 3; ++s) {
      // pairs and majorant keep S x S tables (and majorant rescans them each step): not above
      // species::dense_pair_limit species, where only lowrank is meant to run.
      if (s > 0 && m > species::dense_pair_limit) continue;
      rate[s] = collisions_per_second(schemes[s], n, m);
      if (m == 1) base[s] = rate[s];
    }
    std::printf("%8zu %14.4g %9.2f", m, rate[0], base[0] / rate[0]);
    for (int s = 1; s < 3; ++s)
      if (rate[s] > 0) std::printf(" %14.4g %9.2f", rate[s], base[s] / rate[s]);
      else std::printf(" %14s %9s", "-", "-");
    std::printf("\n");
  }
  return 0;
}
