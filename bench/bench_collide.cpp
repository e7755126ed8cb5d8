// Collision-kernel throughput: accepted collisions per second and candidate pairs per second.
//
// usage: bench_collide [N] [alpha] [collisions_per_particle] [block_size (default: &dsmc's; 0: no blocks)]
// Blocks apply to majorant and lowrank (one species); pairs always runs unblocked.
// Default: the reference case, monodisperse, N = 1e6, alpha = 0.9, 'majorant' and 'pairs'.
// Figures are for comparing builds and schemes on one machine in one run (ratios), not absolute.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/species.hpp"
#include "io/config.hpp"

using namespace gdsmc;

namespace {

struct Result {
  double events_per_second, candidates_per_second, acceptance, seconds, bytes_per_particle;
};

Result measure(collide::Scheme scheme, const species::Mixture& mix, std::size_t n, double per_particle,
               std::size_t block_size) {
  auto init = rng::make_stream(1, 0, rng::Purpose::initial_state);
  auto sys = particles::make_system(mix, particles::species_counts(n, mix), std::vector<double>(mix.size(), 1.0),
                                    particles::InitialDistribution::maxwell, init);
  collide::Collider collider(scheme, mix, sys, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  collider.use_blocks(block_size);
  collider.advance(1e300, static_cast<std::uint64_t>(0.2 * n));  // warm up caches and bounds
  const auto before = collider.counters();
  const auto start = std::chrono::steady_clock::now();
  collider.advance(1e300, before.events + static_cast<std::uint64_t>(per_particle * n / 2.0));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& after = collider.counters();
  const double events = static_cast<double>(after.events - before.events);
  const double candidates = static_cast<double>(after.candidates - before.candidates);
  // Particle data (velocities, species) and the collider's per-particle buffers (blocks' remix).
  const double bytes = static_cast<double>(sys.v.capacity() * sizeof(particles::Vec3) +
                                           sys.species.capacity() * sizeof(std::uint32_t) +
                                           sys.r.capacity() * sizeof(particles::Displacement) +
                                           collider.workspace_bytes());
  return {events / seconds, candidates / seconds, events / candidates, seconds, bytes / static_cast<double>(n)};
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const double alpha = argc > 2 ? std::atof(argv[2]) : 0.9;
  const double per_particle = argc > 3 ? std::atof(argv[3]) : 10.0;
  // The default of &dsmc block_size; 0 measures the kernel without blocks.
  const std::size_t block_size = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : io::config::Dsmc{}.block_size;
  const auto mix = species::make_mixture({1.0}, {1.0}, {0.01}, species::PairMatrix(1, alpha), false);
  std::printf("monodisperse, N = %zu, alpha = %g, %g collisions per particle timed, block_size = %zu\n", n, alpha,
              per_particle, block_size);
  std::printf("%-10s %18s %18s %12s %10s %16s\n", "scheme", "collisions/s", "candidates/s", "acceptance", "seconds",
              "bytes/particle");
  for (auto [name, scheme] : {std::pair{"majorant", collide::Scheme::majorant}, std::pair{"lowrank", collide::Scheme::lowrank},
                              std::pair{"pairs", collide::Scheme::pairs}}) {
    const Result r = measure(scheme, mix, n, per_particle, block_size);
    std::printf("%-10s %18.4g %18.4g %12.4f %10.2f %16.1f\n", name, r.events_per_second, r.candidates_per_second,
                r.acceptance, r.seconds, r.bytes_per_particle);
  }
  return 0;
}
