// Uniform shear flow with the Gaussian thermostat (issue 10): the collision rate of the stage loop
// (thermostat.hpp: streaming, collisions, thermostat, with the velocity frame) against the plain
// homogeneous loop of the same gas at the same N, whole runs through simulation::run, alternated
// side by side in one process.
//
// usage: bench_usf [N] [t_end] [rounds]     (defaults 20000, 4230 = 300/nu_0, 5)
// The gas is that of validation/shear_viscosity/usf.nml (n = 0.01, sigma = m = T0 = 1, alpha = 1,
// a = 0.00284, majorant): the HCS run is the same namelist without &thermostat and &shear. Prints
// collisions per second of each round and the median ratio USF/HCS (the target: >= 0.7).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "run/simulation.hpp"
#include "io/config.hpp"

#include "bench_args.hpp"

using namespace gdsmc;

namespace {

std::string namelist(std::size_t n, double t_end, bool sheared) {
  std::string s = "&system mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 1.0 /\n"
                  "&initial temperature = 1.0 /\n"
                  "&dsmc scheme = 'majorant', n_particles = " + std::to_string(n) +
                  ", replicas = 1, seed = 404, t_end = " + std::to_string(t_end) + " /\n"
                  "&output n_samples = 301 /\n";
  if (sheared) s += "&thermostat kind = 'gaussian' /\n&shear rate = 0.00284 /\n";
  return s;
}

double rate(const std::string& text, const std::string& stem) {
  const std::string input = stem + ".nml", output = stem + ".h5";
  std::ofstream(input) << text;
  const auto config = io::config::read_file(input);
  std::remove(output.c_str());
  const auto summary = simulation::run(config, output, simulation::Options{});
  std::remove(output.c_str());
  std::remove(input.c_str());
  return summary.events_per_second;
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Args args(argc, argv, "usage: bench_usf [N: 2..1e9] [t_end: 0..1e7] [rounds: 1..1000]", 3);
  const std::size_t n = args.whole(1, 20000, 2, 1000000000);
  const double t_end = args.real(2, 4230.0, 1e-9, 1e7);
  const int rounds = static_cast<int>(args.whole(3, 5, 1, 1000));
  const std::string stem = "/tmp/bench_usf." + std::to_string(getpid());
  std::vector<double> usf, hcs, ratio;
  std::printf("N = %zu, t_end = %g, one replica, one thread\n%8s %14s %14s %8s\n", n, t_end, "round", "USF coll/s",
              "HCS coll/s", "ratio");
  for (int r = 0; r < rounds; ++r) {
    usf.push_back(rate(namelist(n, t_end, true), stem + ".usf"));
    hcs.push_back(rate(namelist(n, t_end, false), stem + ".hcs"));
    ratio.push_back(usf.back() / hcs.back());
    std::printf("%8d %14.4g %14.4g %8.3f\n", r + 1, usf.back(), hcs.back(), ratio.back());
  }
  std::printf("median %14.4g %14.4g %8.3f   (USF/HCS; target >= 0.7)\n", median(usf), median(hcs), median(ratio));
  return 0;
}
