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

namespace {

/// The kinetic energy about the mean flow and the mean flow of a pass, from its sums and the momentum.
void finish_pass(StageStart& out, const particles::Vec3& p) {
  const double mass = out.total_mass;
  out.kinetic = 0.5 * (out.moments[0] + out.moments[1] + out.moments[2] - (p.x * p.x + p.y * p.y + p.z * p.z) / mass);
  out.mean_flow = {p.x / mass, p.y / mass, p.z / mass};
}

}  // namespace

StageStart materialise(const species::Mixture& mix, particles::System& sys, const Frame& f) {
  StageStart out;
  out.max_speed2.assign(sys.n_species(), 0.0);
  collide::FramePassSums sums;
  for (std::size_t k = 0; k < sys.n_species(); ++k)
    out.max_speed2[k] = collide::map_velocities(sys.v.data() + sys.first[k], sys.count[k], mix.mass[k], f.scale,
                                                f.scale * f.shear, f.offset, sums);
  out.total_mass = sums.mass;
  out.moments = sums.moments;
  finish_pass(out, {sums.momentum[0], sums.momentum[1], sums.momentum[2]});
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

std::array<double, 6> midpoint_pressure(const std::array<double, 6>& after, double h) {
  // (xx, yy, zz, xy, xz, yz) before the jump V_x -> V_x - h V_y, from after it (header, "Sampling point")
  const std::array<double, 6> before{after[0] + 2.0 * h * after[3] + h * h * after[1], after[1], after[2],
                                     after[3] + h * after[1], after[4] + h * after[5], after[5]};
  std::array<double, 6> mid;
  for (std::size_t c = 0; c < 6; ++c) mid[c] = 0.5 * (after[c] + before[c]);
  return mid;
}

void GaussianThermostat::compose(Rescaling& rescaling, double&) {
  rescaling = pending_;  // decided at the end of the last stage
  pending_ = Rescaling{};
}

void GaussianThermostat::end_stage(const StageEnd& end) {
  if (viscous_work_) {
    // The Enskog collisions in shear flow also do viscous work, which the thermostat must not remove
    // (\ref eta_thermostat "docs/shear-viscosity.md"): only the inelastic loss is restored, s^2 = (E_after + L)/E_after.
    const double after = end.energy_after();
    pending_ = {std::sqrt((after + end.loss) / after), end.start.mean_flow, end.loss / end.start.kinetic};
  } else {
    // The dilute collisions change the energy only by their inelastic loss and keep the mean flow, so
    // the thermostat needs no pass over the particles (header, "Cost: the frame").
    pending_ = gaussian_rescaling(end.start.kinetic, end.loss, end.start.mean_flow);
  }
  zeta_sum_ += pending_.zeta_dt;
  zeta_stages_ += 1.0;
}

void GaussianThermostat::measure(const Sample&, sample::Rows& rows) {
  rows.add("thermostat_zeta_dt", 1, {zeta_stages_ > 0.0 ? zeta_sum_ / zeta_stages_ : 0.0});
  zeta_sum_ = zeta_stages_ = 0.0;
}

particles::Vec3 WhiteNoise::act(particles::System& sys, double dt, rng::Xoshiro256pp& gen) {
  // dv = sqrt(chi^2_k dt) xi (\ref wn_forcing "docs/white-noise.md"); the kicks' centre-of-mass velocity, returned, is removed
  // in the pass that follows (Stages::act)
  double px = 0.0, py = 0.0, pz = 0.0, total_mass = 0.0;
  for (std::size_t k = 0; k < sys.n_species(); ++k) {
    const double sd = std::sqrt(strength_[k] * dt), m = mix_.mass[k];
    double kx = 0.0, ky = 0.0, kz = 0.0;
    for (std::size_t i = sys.first[k]; i < sys.first[k] + sys.count[k]; ++i) {
      const double dx = sd * gen.normal_ziggurat(), dy = sd * gen.normal_ziggurat(), dz = sd * gen.normal_ziggurat();
      sys.v[i] = {sys.v[i].x + dx, sys.v[i].y + dy, sys.v[i].z + dz};
      kx += dx, ky += dy, kz += dz;
    }
    px += m * kx, py += m * ky, pz += m * kz;
    total_mass += m * static_cast<double>(sys.count[k]);
  }
  return {-px / total_mass, -py / total_mass, -pz / total_mass};
}

void GaussianThermostat::save(state::Record& r) const {
  r.put("thermostat/pending_scale", pending_.scale);
  r.put("thermostat/pending_mean_flow", std::vector<double>{pending_.mean_flow.x, pending_.mean_flow.y, pending_.mean_flow.z});
  r.put("thermostat/zeta_sum", zeta_sum_);
  r.put("thermostat/zeta_stages", zeta_stages_);
}

void GaussianThermostat::restore(const state::Record& r) {
  const auto& m = r.array("thermostat/pending_mean_flow", 3);
  pending_ = {r.real("thermostat/pending_scale"), {m[0], m[1], m[2]}, 0.0};
  zeta_sum_ = r.real("thermostat/zeta_sum");
  zeta_stages_ = r.real("thermostat/zeta_stages");
}

void ShearFlow::measure(const Sample& sample, sample::Rows& rows) {
  const double viscosity = -sample.pressure[3] / rate_;  // eta = -P_xy/a, P_xy at the middle of the jump
  rows.add("shear_viscosity_raw", 1, {viscosity});
  // eta/eta_0(T) with the finite-shear-rate correction of \ref eta_measured "docs/shear-viscosity.md", 1 - (a* eta*)^2,
  // a* = a/nu_0(T), nu_0 = n T/eta_0; eta_0 of one species (\ref eta_one_species "docs/shear-viscosity.md"), or of the elastic
  // mixture at the same T (Chapman and Cowling's first approximation; theory/viscosity.hpp).
  const double eta0 = elastic_viscosity_(sample.total_temperature);
  const double reduced_rate = rate_ * eta0 / (density_ * sample.total_temperature);
  const double corrected = viscosity / eta0;
  double eta = corrected;
  for (int it = 0; it < 20; ++it) eta = corrected / (1.0 - reduced_rate * reduced_rate * eta * eta);
  const double kinetic_part = eta * sample.kinetic[3] / sample.pressure[3];  // the same correction for each part
  rows.add("reduced_shear_rate", 1, {reduced_rate});
  rows.add("shear_viscosity", 1, {eta});
  if (collisional_) rows.add("shear_viscosity_kinetic", 1, {kinetic_part});
  if (sample.time >= average_from_ * (1.0 - 1e-12) && sample.averaged) {
    window_sum_ += eta;
    window_kinetic_sum_ += kinetic_part;
    window_samples_ += 1.0;
    // T and P at the same point, the middle of the jump (the temperature of `sample` is after it: a dt |P_xy|/(3 n)
    // higher); a* of that T (\ref eta_usf_steady "docs/shear-viscosity.md")
    const double temperature = (sample.kinetic[0] + sample.kinetic[1] + sample.kinetic[2]) / (3.0 * density_);
    const double nt = density_ * temperature;
    state_sum_[0] += rate_ * elastic_viscosity_(temperature) / nt;
    for (std::size_t c = 0; c < 4; ++c) state_sum_[c + 1] += sample.pressure[c] / nt;
  }
}

void ShearFlow::finish(sample::Rows& rows) const {
  if (!(window_samples_ > 0.0)) return;
  rows.add("shear_viscosity_average", 1, {window_sum_ / window_samples_});
  std::vector<double> state(state_sum_.begin(), state_sum_.end());
  for (double& x : state) x /= window_samples_;
  rows.add("shear_state_average", 5, state);
  if (collisional_) rows.add("shear_viscosity_kinetic_average", 1, {window_kinetic_sum_ / window_samples_});
}

void ShearFlow::save(state::Record& r) const {
  r.put("shear/window_sum", window_sum_);
  r.put("shear/window_kinetic_sum", window_kinetic_sum_);
  r.put("shear/window_samples", window_samples_);
  r.put("shear/state_sum", std::vector<double>(state_sum_.begin(), state_sum_.end()));
}

void ShearFlow::restore(const state::Record& r) {
  window_sum_ = r.real("shear/window_sum");
  window_kinetic_sum_ = r.real("shear/window_kinetic_sum");
  window_samples_ = r.real("shear/window_samples");
  if (r.has("shear/state_sum")) {
    const auto state = r.array("shear/state_sum", state_sum_.size());
    std::copy(state.begin(), state.end(), state_sum_.begin());
  } else if (window_samples_ > 0.0) {  // a checkpoint of a version without the shear state, its window begun
    throw state::StateError("'shear/state_sum' is missing: the checkpoint comes from a version of granular-dsmc without "
                            "the shear state's averages, and its averaging window has begun; start the run again");
  } else {
    state_sum_ = {};  // (such a checkpoint before its window: nothing to add up yet)
  }
}

Stages::Stages(const species::Mixture& mix, particles::System& sys, collide::Collider& collider,
               std::vector<std::unique_ptr<Forcing>> forcings, double stage_step, double shear_rate, bool collisional,
               rng::Xoshiro256pp gen)
    : mix_(mix), sys_(sys), collider_(collider), forcings_(std::move(forcings)), stage_step_(stage_step),
      stage_cap_(std::numeric_limits<double>::infinity()), shear_rate_(shear_rate), collisional_(collisional),
      acts_(false), gen_(gen) {
  for (const auto& f : forcings_) {
    stage_cap_ = std::min(stage_cap_, f->longest_stage());
    acts_ = acts_ || f->acts_on_particles();
  }
  for (std::size_t k = 0; k < sys.n_species(); ++k) total_mass_ += mix.mass[k] * static_cast<double>(sys.count[k]);
}

double Stages::stage_end(double limit) const {
  const double free_time = static_cast<double>(sys_.size()) / (2.0 * collider_.candidate_rate());
  const double end = collider_.time() + std::min(stage_step_ * free_time, stage_cap_);
  return end < limit ? end : limit;
}

void Stages::begin(double dt, bool sample) {
  // The forcings' maps of this stage (the thermostat's rescaling decided at the end of the last stage,
  // then the shear's streaming), composed into the frame (header, "Cost: the frame").
  Rescaling rescaling;
  double shear_rate = 0.0;
  for (const auto& f : forcings_) f->compose(rescaling, shear_rate);
  frame_ = advance_frame(frame_, rescaling.scale, rescaling.mean_flow, shear_rate, dt);
  if (!sample && !acts_ && collider_.framed() && std::abs(frame_.shear) <= frame_shear_limit && frame_.scale >= 0.5 &&
      frame_.scale <= 2.0) {
    collider_.set_frame(frame_.scale, frame_.shear);
    start_ = frame_energy(collider_.frame_moments(), momentum_, total_mass_, frame_);
    return;
  }
  // Half of each stage's action at its start, half at its end (header, "Forcings that act on each particle"):
  // here the previous stage's second half and this one's first, at a sample on either side of it.
  double first_half = 0.0, second_half = 0.0;
  if (acts_) {
    first_half = dt / 2.0, second_half = pending_act_;
    pending_act_ = first_half;
  }
  const bool acts_now = acts_ && (!sample || second_half > 0.0);
  // One pass: V = G u + b for every particle, the energy, the moments and the largest speeds (the
  // collider's bounds, exact again); the frame is the identity afterwards. A forcing acting on each
  // particle acts then, and a second pass measures what it left; the first is skipped when it would
  // only measure (the identity frame) and the second follows.
  const bool identity = frame_.scale == 1.0 && frame_.shear == 0.0 && frame_.offset.x == 0.0 &&
                        frame_.offset.y == 0.0 && frame_.offset.z == 0.0;
  StageStart first = identity && acts_now ? StageStart{} : materialise_pass(frame_);
  frame_ = Frame{};
  if (sample && acts_) deferred_act_ = first_half;  // after the sample (measure())
  if (acts_now) {
    act(sample ? second_half : second_half + first_half);
    return;
  }
  start_from(first);
}

StageStart Stages::materialise_pass(const Frame& f) {
  if (collider_.blocks() <= 1) return materialise(mix_, sys_, f);
  collide::Collider::BlockPass sums = collider_.map_blocks(f.scale, f.scale * f.shear, f.offset);
  StageStart out;
  out.total_mass = total_mass_;  // (as materialise's: the sum over species, not over blocks)
  out.moments = sums.moments;
  out.max_speed2 = std::move(sums.max_speed2);
  out.block_bounds = true;
  finish_pass(out, sums.momentum);
  return out;
}

void Stages::act(double dt) {
  Frame shift;  // the identity map and the velocity the forcings ask to add
  for (const auto& f : forcings_)
    if (f->acts_on_particles()) {
      const particles::Vec3 u = f->act(sys_, dt, gen_);
      shift.offset = {shift.offset.x + u.x, shift.offset.y + u.y, shift.offset.z + u.z};
    }
  start_from(materialise_pass(shift));
}

void Stages::start_from(const StageStart& pass) {
  momentum_ = {pass.mean_flow.x * total_mass_, pass.mean_flow.y * total_mass_, pass.mean_flow.z * total_mass_};
  collider_.reset_frame(pass.moments, pass.max_speed2, pass.block_bounds);
  start_ = {pass.kinetic, pass.mean_flow};
}

void Stages::end(double end) {
  const double dissipated_before = collider_.counters().dissipated;
  collider_.advance(end);
  const Forcing::StageEnd stage_end{
      start_, collider_.counters().dissipated - dissipated_before,
      [&] { return frame_energy(collider_.frame_moments(), momentum_, total_mass_, frame_).kinetic; }};
  for (const auto& f : forcings_) f->end_stage(stage_end);
  count_ += 1.0;
}

void Stages::measure(const sample::Moments& m, double dt, bool averaged, sample::Rows& rows) {
  // P at the middle of this stage's streaming jump (header, "Sampling point").
  const auto kinetic = midpoint_pressure(sample::kinetic_pressure_tensor(mix_, sys_, m), shear_rate_ * dt);
  // Collisional transfer since the previous sample (\ref eta_pressure "docs/shear-viscosity.md"): P^c = sum m sigma (1 + alpha)(g.e) e e
  // / (V dt), V = N/n the simulated volume; 0 in the dilute gas.
  std::array<double, 6> collisional{};
  const double now = collider_.time();
  if (collisional_ && now > last_sample_time_) {
    const auto& transfer = collider_.counters().transfer;
    const double volume = static_cast<double>(sys_.size()) / mix_.total_density();
    for (std::size_t q = 0; q < 6; ++q) collisional[q] = (transfer[q] - last_transfer_[q]) / (volume * (now - last_sample_time_));
    last_transfer_ = transfer;
  }
  last_sample_time_ = now;
  std::array<double, 6> total;
  for (std::size_t q = 0; q < 6; ++q) total[q] = kinetic[q] + collisional[q];
  rows.add("pressure_tensor_kinetic", 6, std::vector<double>(kinetic.begin(), kinetic.end()));
  rows.add("pressure_tensor_collisional", 6, std::vector<double>(collisional.begin(), collisional.end()));
  rows.add("pressure_tensor", 6, std::vector<double>(total.begin(), total.end()));
  const Forcing::Sample sample{now, m.total_temperature, total, kinetic, averaged};
  for (const auto& f : forcings_) f->measure(sample, rows);
  if (deferred_act_ > 0.0) {  // this stage's first half, after its sample (header, "Forcings that act on each particle")
    act(deferred_act_);
    deferred_act_ = 0.0;
  }
}

void Stages::finish(sample::Rows& rows) const {
  for (const auto& f : forcings_) f->finish(rows);
}

void Stages::save(state::Record& r) const {
  r.put("stages/count", count_);
  r.put("stages/last_sample_time", last_sample_time_);
  r.put("stages/last_transfer", std::vector<double>(last_transfer_.begin(), last_transfer_.end()));
  r.put("stages/frame_offset", std::vector<double>{frame_.offset.x, frame_.offset.y, frame_.offset.z});
  r.put("stages/momentum", std::vector<double>{momentum_.x, momentum_.y, momentum_.z});
  r.put("stages/pending_act", pending_act_);
  const auto g = gen_.state();
  r.put("stages/generator", std::vector<std::uint64_t>(std::begin(g.s), std::end(g.s)));
  r.put("stages/generator_spare", g.spare);
  r.put_integer("stages/generator_has_spare", g.has_spare);
  for (const auto& f : forcings_) f->save(r);
}

void Stages::restore(const state::Record& r) {
  count_ = r.real("stages/count");
  last_sample_time_ = r.real("stages/last_sample_time");
  const auto& transfer = r.array("stages/last_transfer", 6);
  std::copy(transfer.begin(), transfer.end(), last_transfer_.begin());
  const auto& offset = r.array("stages/frame_offset", 3);
  const auto& momentum = r.array("stages/momentum", 3);
  frame_ = {collider_.frame_scale(), collider_.frame_shear(), {offset[0], offset[1], offset[2]}};
  momentum_ = {momentum[0], momentum[1], momentum[2]};
  if (r.has("stages/pending_act")) {
    pending_act_ = r.real("stages/pending_act");
  } else if (acts_) {
    throw state::StateError("'stages/pending_act' is missing: the checkpoint of an earlier build, whose white-noise "
                            "kicks were split otherwise; run the input again without --restart");
  }
  // (a checkpoint of layout 1 has no forcings' stream: none of its forcings drew from it)
  if (r.has_integers("stages/generator")) {
    rng::Xoshiro256pp::State g{};
    const auto& s = r.integer_array("stages/generator", 4);
    std::copy(s.begin(), s.end(), std::begin(g.s));
    g.spare = r.real("stages/generator_spare");
    g.has_spare = r.flag("stages/generator_has_spare");
    gen_.set_state(g);
  }
  for (const auto& f : forcings_) f->restore(r);
}

}  // namespace gdsmc::thermostat
