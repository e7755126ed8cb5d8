#include "dsmc/thermostat.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gdsmc::thermostat {

Energy peculiar_energy(const species::Mixture& mix, const particles::System& sys) {
  double mass = 0.0, px = 0.0, py = 0.0, pz = 0.0, twice_energy = 0.0;
  for (std::size_t k = 0; k < sys.n_species(); ++k) {
    const double m = mix.mass[k];
    double sx = 0.0, sy = 0.0, sz = 0.0, s2 = 0.0;
    const std::size_t end = sys.first[k] + sys.count[k];
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      const particles::Vec3& v = sys.v[i];
      sx += v.x;
      sy += v.y;
      sz += v.z;
      s2 += v.x * v.x + v.y * v.y + v.z * v.z;
    }
    mass += m * static_cast<double>(sys.count[k]);
    px += m * sx;
    py += m * sy;
    pz += m * sz;
    twice_energy += m * s2;
  }
  Energy e;
  e.mean_flow = {px / mass, py / mass, pz / mass};
  // sum m |V - u|^2 = sum m V^2 - M u^2
  e.kinetic = 0.5 * (twice_energy - (px * px + py * py + pz * pz) / mass);
  return e;
}

void remove_mean_flow(const species::Mixture& mix, particles::System& sys) {
  const particles::Vec3 u = peculiar_energy(mix, sys).mean_flow;
  for (auto& v : sys.v) {
    v.x -= u.x;
    v.y -= u.y;
    v.z -= u.z;
  }
}

void stream(particles::System& sys, double shear_rate, double dt) {
  const double shift = shear_rate * dt;
  for (auto& v : sys.v) v.x -= shift * v.y;
}

double rescale(const species::Mixture& mix, particles::System& sys, double energy_before) {
  const Energy after = peculiar_energy(mix, sys);
  if (!(after.kinetic > 0.0)) throw std::runtime_error("thermostat: the gas has no kinetic energy left to rescale");
  const double loss = energy_before - after.kinetic;
  const double s = std::sqrt((after.kinetic + loss) / after.kinetic);  // = sqrt(T_before/T_after)
  const particles::Vec3 u = after.mean_flow;
  for (auto& v : sys.v) v = {u.x + s * (v.x - u.x), u.y + s * (v.y - u.y), u.z + s * (v.z - u.z)};
  return loss / energy_before;
}

StageStart begin_stage(const species::Mixture& mix, particles::System& sys, double scale,
                       const particles::Vec3& u, double shear_rate, double dt) {
  StageStart out;
  out.max_speed2.assign(sys.n_species(), 0.0);
  const double shift = shear_rate * dt;
  double mass = 0.0, px = 0.0, py = 0.0, pz = 0.0, twice_energy = 0.0;
  for (std::size_t k = 0; k < sys.n_species(); ++k) {
    double sx = 0.0, sy = 0.0, sz = 0.0, s2 = 0.0, max2 = 0.0;
    const std::size_t end = sys.first[k] + sys.count[k];
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      particles::Vec3& v = sys.v[i];
      particles::Vec3 w{u.x + scale * (v.x - u.x), u.y + scale * (v.y - u.y), u.z + scale * (v.z - u.z)};
      w.x -= shift * w.y;
      v = w;
      sx += w.x;
      sy += w.y;
      sz += w.z;
      const double w2 = w.x * w.x + w.y * w.y + w.z * w.z;
      s2 += w2;
      max2 = std::max(max2, w2);
    }
    const double m = mix.mass[k];
    mass += m * static_cast<double>(sys.count[k]);
    px += m * sx;
    py += m * sy;
    pz += m * sz;
    twice_energy += m * s2;
    out.max_speed2[k] = max2;
  }
  out.kinetic = 0.5 * (twice_energy - (px * px + py * py + pz * pz) / mass);
  out.mean_flow = {px / mass, py / mass, pz / mass};
  return out;
}

Rescaling gaussian_rescaling(double energy_before, double loss, const particles::Vec3& mean_flow) {
  const double after = energy_before - loss;
  if (!(after > 0.0)) throw std::runtime_error("thermostat: the gas has no kinetic energy left to rescale");
  return {std::sqrt(energy_before / after), mean_flow, loss / energy_before};
}

}  // namespace gdsmc::thermostat
