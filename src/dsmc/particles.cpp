#include "dsmc/particles.hpp"

#include <cmath>

namespace gdsmc::particles {

std::vector<std::size_t> species_counts(std::size_t n_particles, const species::Mixture& mix) {
  std::vector<std::size_t> counts(mix.size());
  const double n = mix.total_density();  // once: mole_fraction(k) would sum over all species each time
  for (std::size_t k = 0; k < mix.size(); ++k)
    counts[k] = static_cast<std::size_t>(
        std::llround(static_cast<double>(n_particles) * mix.number_density[k] / n));
  return counts;
}

System make_system(const species::Mixture& mix, const std::vector<std::size_t>& counts,
                   const std::vector<double>& temperature, InitialDistribution distribution,
                   rng::Xoshiro256pp& gen) {
  System sys;
  const std::size_t s = counts.size();
  sys.first.resize(s);
  sys.count = counts;
  std::size_t total = 0;
  for (std::size_t k = 0; k < s; ++k) {
    sys.first[k] = total;
    total += counts[k];
  }
  sys.vx.resize(total);
  sys.vy.resize(total);
  sys.vz.resize(total);
  sys.species.resize(total);

  for (std::size_t k = 0; k < s; ++k) {
    const std::size_t begin = sys.first[k], end = begin + counts[k];
    // Any scale will do: the velocities are rescaled to T_k below.
    for (std::size_t i = begin; i < end; ++i) {
      sys.species[i] = static_cast<std::uint32_t>(k);
      switch (distribution) {
        case InitialDistribution::maxwell:
          sys.vx[i] = gen.normal();
          sys.vy[i] = gen.normal();
          sys.vz[i] = gen.normal();
          break;
        case InitialDistribution::shell:
          rng::unit_vector(gen, sys.vx[i], sys.vy[i], sys.vz[i]);
          break;
        case InitialDistribution::cube:
          sys.vx[i] = 2.0 * gen.uniform() - 1.0;
          sys.vy[i] = 2.0 * gen.uniform() - 1.0;
          sys.vz[i] = 2.0 * gen.uniform() - 1.0;
          break;
      }
    }
    double mean[3] = {0.0, 0.0, 0.0};
    for (std::size_t i = begin; i < end; ++i) {
      mean[0] += sys.vx[i];
      mean[1] += sys.vy[i];
      mean[2] += sys.vz[i];
    }
    for (double& m : mean) m /= static_cast<double>(counts[k]);
    double sum_sq = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      sys.vx[i] -= mean[0];
      sys.vy[i] -= mean[1];
      sys.vz[i] -= mean[2];
      sum_sq += sys.vx[i] * sys.vx[i] + sys.vy[i] * sys.vy[i] + sys.vz[i] * sys.vz[i];
    }
    // T_k = m_k <|v|^2> / 3 (INTERFACE.md `temperature`)
    const double current = mix.mass[k] * sum_sq / (3.0 * static_cast<double>(counts[k]));
    const double scale = std::sqrt(temperature[k] / current);
    for (std::size_t i = begin; i < end; ++i) {
      sys.vx[i] *= scale;
      sys.vy[i] *= scale;
      sys.vz[i] *= scale;
    }
  }
  return sys;
}

void start_tracking(System& sys, double t) {
  const std::size_t n = sys.size();
  sys.rx.assign(n, 0.0);
  sys.ry.assign(n, 0.0);
  sys.rz.assign(n, 0.0);
  sys.t_last.assign(n, t);
}

}  // namespace gdsmc::particles
