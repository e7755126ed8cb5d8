// Aggregation and fragmentation (issue 9): cost per event of the cluster gas against a plain
// collision of a monodisperse gas of the same N, measured side by side in one process.
//
// usage: bench_agg_frag [N] [full_model_collisions_per_monomer]
// 1. plain: the one-species collision loop (collide.hpp `majorant`), unblocked and with the default
//    cache blocks, 2 collisions per particle;
// 2. sticking: every collision aggregates (E_agg huge), from N monomers to mean size <k> = 100;
// 2b. the same to <k> = 4, where N stays above 2 block_size at N = 1e6; each with and without the
//    cache blocks (agg_frag.hpp, "Cache blocks");
// 3. full model (with and without blocks): E_agg = 0.5, E_frag = 1.5, eps_f = 0.5, alpha = 0.8, T0 = 1, n = 0.1, for the given
//    collisions per initial monomer (default 10: by then <k> ~ 25, aggregation dominates).
// Prints events per second, the ratio of the plain rate to it (the target: <= 3) and the
// memory per initial monomer at the start and the end (it must not grow).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "dsmc/agg_frag.hpp"
#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "model/species.hpp"
#include "io/config.hpp"

#include "bench_args.hpp"

using namespace gdsmc;

namespace {

using Clock = std::chrono::steady_clock;

double plain_rate(std::size_t n, std::size_t block_size) {
  const auto mix = species::make_mixture({1.0}, {1.0}, {0.1}, species::PairMatrix(1, 0.8), false);
  auto init = rng::make_stream(1, 0, rng::Purpose::initial_state);
  auto sys = particles::make_system(mix, {n}, {1.0}, particles::InitialDistribution::maxwell, init);
  collide::Collider collider(collide::Scheme::majorant, mix, sys, rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  collider.use_blocks(block_size);
  collider.advance(1e300, static_cast<std::uint64_t>(0.2 * n));
  const auto before = collider.counters().events;
  const auto start = Clock::now();
  // time-driven, as the blocked loop needs: about 2 collisions per particle at T ~ 1
  const double t = collider.time() + 2.0 / (4.0 * std::sqrt(std::acos(-1.0)) * 0.1);
  collider.advance(t);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return static_cast<double>(collider.counters().events - before) / seconds;
}

struct Run {
  double events_per_second, seconds, bytes_start, bytes_end, mean_size;
  std::uint64_t events, aggregations, fragmentations;
  double candidates_per_event;
};

Run cluster_rate(std::size_t n, const agg_frag::Model& model, std::uint64_t events, std::size_t block_size) {
  agg_frag::Gas gas(model, n, 1.0, particles::InitialDistribution::maxwell, rng::make_stream(1, 0, rng::Purpose::initial_state),
                    rng::make_stream(1, 0, rng::Purpose::collisions), 1.0);
  gas.use_blocks(block_size);
  const double bytes_start = static_cast<double>(gas.memory_bytes());
  const auto start = Clock::now();
  gas.advance(std::numeric_limits<double>::infinity(), events);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const auto& c = gas.counters();
  return {static_cast<double>(c.events) / seconds, seconds, bytes_start, static_cast<double>(gas.memory_bytes()),
          static_cast<double>(n) / static_cast<double>(gas.clusters()), c.events, c.aggregations, c.fragmentations,
          static_cast<double>(c.candidates) / static_cast<double>(c.events)};
}

void print(const char* name, const Run& r, double plain, double plain_blocked, std::size_t n) {
  std::printf("%-12s %12.4g %8.2f %8.2f %10.2f %8.1f %12llu %12llu %12.1f %12.1f %10.2f\n", name, r.events_per_second,
              plain / r.events_per_second, plain_blocked / r.events_per_second, r.seconds, r.mean_size,
              static_cast<unsigned long long>(r.aggregations), static_cast<unsigned long long>(r.fragmentations),
              r.bytes_start / static_cast<double>(n), r.bytes_end / static_cast<double>(n), r.candidates_per_event);
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Args args(argc, argv, "usage: bench_agg_frag [monomers N: 100..1e9] [collisions per monomer: 0..1e4]", 2);
  const std::size_t n = args.whole(1, 1000000, 100, 1000000000);
  const double per_monomer = args.real(2, 10.0, 1e-9, 1e4);
  const double plain = plain_rate(n, 0);
  const double plain_blocked = plain_rate(n, static_cast<std::size_t>(io::config::Dsmc{}.block_size));
  std::printf("N = %zu monomers; plain one-species collisions/s: %.4g unblocked, %.4g with blocks\n", n, plain,
              plain_blocked);
  std::printf("%-12s %12s %8s %8s %10s %8s %12s %12s %12s %12s %10s\n", "run", "events/s", "plain/", "blocked/",
              "seconds", "<k>", "aggregations", "fragments", "bytes/N0 t=0", "bytes/N0 end", "cand/event");
  agg_frag::Model sticking;
  sticking.monomer_density = 0.1;
  sticking.restitution = 0.8;
  sticking.aggregation_energy = 1e300;  // every collision sticks
  const auto block_size = static_cast<std::size_t>(io::config::Dsmc{}.block_size);
  // to <k> = 100 (blocks while N >= 2 block_size), and to <k> = 4 (blocked throughout at N = 1e6)
  print("sticking", cluster_rate(n, sticking, n - n / 100, 0), plain, plain_blocked, n);
  print("+ blocks", cluster_rate(n, sticking, n - n / 100, block_size), plain, plain_blocked, n);
  print("to <k>=4", cluster_rate(n, sticking, n - n / 4, 0), plain, plain_blocked, n);
  print("+ blocks", cluster_rate(n, sticking, n - n / 4, block_size), plain, plain_blocked, n);
  agg_frag::Model full = sticking;
  full.aggregation_energy = 0.5;
  full.fragmentation_energy = 1.5;
  full.fragment_restitution = 0.5;
  const auto full_events = static_cast<std::uint64_t>(per_monomer * static_cast<double>(n) / 2.0);
  print("full model", cluster_rate(n, full, full_events, 0), plain, plain_blocked, n);
  print("+ blocks", cluster_rate(n, full, full_events, block_size), plain, plain_blocked, n);
  return 0;
}
