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

Frame advance_frame(const Frame& f, double scale, const particles::Vec3& m, double shear_rate, double dt) {
  const double shift = shear_rate * dt;
  Frame out;
  out.scale = scale * f.scale;
  out.shear = f.shear - shift;  // S (u_x + c u_y) - a dt S u_y
  particles::Vec3 b{m.x + scale * (f.offset.x - m.x), m.y + scale * (f.offset.y - m.y),
                    m.z + scale * (f.offset.z - m.z)};
  b.x -= shift * b.y;
  out.offset = b;
  return out;
}

Energy frame_energy(const std::array<double, 4>& q, const particles::Vec3& p, double total_mass, const Frame& f) {
  const double s = f.scale, c = f.shear;
  const particles::Vec3& b = f.offset;
  const particles::Vec3 gp{s * (p.x + c * p.y), s * p.y, s * p.z};  // G P
  // tr sum m V V^T = tr G Q G^T + 2 (G P).b + M |b|^2
  const double trace = s * s * (q[0] + 2.0 * c * q[3] + c * c * q[1] + q[1] + q[2]) +
                       2.0 * (gp.x * b.x + gp.y * b.y + gp.z * b.z) + total_mass * (b.x * b.x + b.y * b.y + b.z * b.z);
  Energy e;
  e.mean_flow = {gp.x / total_mass + b.x, gp.y / total_mass + b.y, gp.z / total_mass + b.z};
  const particles::Vec3& u = e.mean_flow;
  e.kinetic = 0.5 * (trace - total_mass * (u.x * u.x + u.y * u.y + u.z * u.z));
  return e;
}

StageStart materialise(const species::Mixture& mix, particles::System& sys, const Frame& f) {
  StageStart out;
  out.max_speed2.assign(sys.n_species(), 0.0);
  const double s = f.scale, sc = f.scale * f.shear;
  const particles::Vec3 b = f.offset;
  double px = 0.0, py = 0.0, pz = 0.0;
  for (std::size_t k = 0; k < sys.n_species(); ++k) {
    double sx = 0.0, sy = 0.0, sz = 0.0, sxx = 0.0, syy = 0.0, szz = 0.0, sxy = 0.0, max2 = 0.0;
    const std::size_t end = sys.first[k] + sys.count[k];
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      particles::Vec3& v = sys.v[i];
      const particles::Vec3 w{s * v.x + sc * v.y + b.x, s * v.y + b.y, s * v.z + b.z};
      v = w;
      sx += w.x;
      sy += w.y;
      sz += w.z;
      sxx += w.x * w.x;
      syy += w.y * w.y;
      szz += w.z * w.z;
      sxy += w.x * w.y;
      max2 = std::max(max2, w.x * w.x + w.y * w.y + w.z * w.z);
    }
    const double m = mix.mass[k];
    out.total_mass += m * static_cast<double>(sys.count[k]);
    px += m * sx;
    py += m * sy;
    pz += m * sz;
    out.moments[0] += m * sxx;
    out.moments[1] += m * syy;
    out.moments[2] += m * szz;
    out.moments[3] += m * sxy;
    out.max_speed2[k] = max2;
  }
  const double mass = out.total_mass;
  out.kinetic = 0.5 * (out.moments[0] + out.moments[1] + out.moments[2] - (px * px + py * py + pz * pz) / mass);
  out.mean_flow = {px / mass, py / mass, pz / mass};
  return out;
}

StageStart begin_stage(const species::Mixture& mix, particles::System& sys, double scale,
                       const particles::Vec3& u, double shear_rate, double dt) {
  return materialise(mix, sys, advance_frame(Frame{}, scale, u, shear_rate, dt));
}

Rescaling gaussian_rescaling(double energy_before, double loss, const particles::Vec3& mean_flow) {
  const double after = energy_before - loss;
  if (!(after > 0.0)) throw std::runtime_error("thermostat: the gas has no kinetic energy left to rescale");
  return {std::sqrt(energy_before / after), mean_flow, loss / energy_before};
}

}  // namespace gdsmc::thermostat
