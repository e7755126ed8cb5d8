// Wall-clock time of smoluchowski::solve for the two reference problems of smoluchowski.hpp:
// a sticking gas from monomers to <k> = 10 (t nu0 = 16.65) and the full model (E_agg = 0.5,
// E_frag = 1.5, eps_f = 0.5, alpha = 0.8). The full model has no steady state: bounces cool the gas,
// E_frag soon lies far above the thermal energy, fragmentation stops and the clusters keep growing
// (<k> = 7 at t nu0 = 50, 32 at 200), so the K it needs grows with the end time.
// Not run by ctest: build/bin/bench_smoluchowski [sticking end] [full end], times in 1/nu0.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "theory/smoluchowski.hpp"
#include "theory/theory.hpp"

#include "bench_args.hpp"

namespace smol = gdsmc::theory::smoluchowski;

namespace {

void run(const char* name, const smol::Parameters& p, double last_time_nu0) {
  const double nu0 = gdsmc::theory::collision_frequency(p.monomer_density, p.monomer_diameter, 1.0,
                                                        p.monomer_mass, p.initial_temperature);
  std::vector<double> times;
  for (double t = 0.0; t <= last_time_nu0 * (1.0 + 1e-12); t += last_time_nu0 / 20.0)
    times.push_back(t / nu0);
  const auto start = std::chrono::steady_clock::now();
  const smol::Solution s = smol::solve(p, times);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %.3f s, K = %zu, lost mass fraction %.3g\n", name, seconds, s.max_size,
              s.lost_mass_fraction);
  std::printf("  t nu0   sum n_k/n0   <k>   n_1/n0   T/T0   E_kin   aggregations fragmentations\n");
  const std::size_t K = s.max_size;
  for (std::size_t i = 0; i < times.size(); ++i) {
    double clusters = 0.0;
    for (std::size_t k = 0; k < K; ++k) clusters += s.number_fraction[i * K + k];
    std::printf("  %7.1f %11.5g %7.3f %9.4g %8.4g %8.4g %10.5g %10.5g\n", times[i] * nu0, clusters,
                1.0 / clusters, s.number_fraction[i * K], s.total_temperature[i],
                s.kinetic_energy[i], s.aggregations[i], s.fragmentations[i]);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const gdsmc::bench::Args args(argc, argv,
                         "usage: bench_smoluchowski [t_end of the sticking run: 0..1e3] [t_end of the full model: 0..1e3] "
                         "(0: that run skipped)",
                         2);
  const double sticking_end = args.real(1, 16.65, 0.0, 1e3);
  const double full_end = args.real(2, 50.0, 0.0, 1e3);
  const double infinity = std::numeric_limits<double>::infinity();
  smol::Parameters full{.monomer_mass = 1.0, .monomer_diameter = 1.0, .monomer_density = 0.1,
                        .initial_temperature = 1.0, .restitution = 0.8,
                        .aggregation_energy = 0.5, .fragmentation_energy = 1.5,
                        .fragment_restitution = 0.5};
  smol::Parameters sticking = full;
  sticking.aggregation_energy = infinity;
  sticking.fragmentation_energy = infinity;
  try {
    if (sticking_end > 0) run("sticking", sticking, sticking_end);
    if (full_end > 0) run("full model", full, full_end);
  } catch (const std::exception& e) {  // (the sticking gas's clusters outgrow the solver beyond t of about 17)
    std::fprintf(stderr, "bench_smoluchowski: %s\n", e.what());
    return 1;
  }
}
