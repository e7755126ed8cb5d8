/**
 * \file thermostat.hpp
 * \brief The Gaussian thermostat of the homogeneous steady state and the streaming of uniform shear
 *        flow (Montanero 2003, sec. 2, eqs 1-18 as corrected by \ref eta_thermostat "docs/shear-viscosity.md"; docs/physics.md, "Thermostat
 *        and uniform shear flow").
 *
 * **Stages.** A run with `&thermostat kind = 'gaussian'` or `&shear rate = a` advances in stages of
 * length dt (`&dsmc stage_step` majorant mean free times, at most 0.01/a): streaming, collisions
 * (collide.hpp, continuous time within the stage), thermostat. The operator splitting is first order
 * in dt (the reasoning of \ref stat_timestep_bias "docs/statistics.md"); the validation measures the bias at two stage lengths.
 *
 * **Streaming** (homogeneous USF in the Lagrangian frame, peculiar velocities only):
 * V_x -> V_x - a V_y dt for every particle. The total momentum is unchanged when sum m V_y = 0; the
 * energy changes by -a P_xy V dt + O(dt^2): viscous heating.
 *
 * **Gaussian thermostat** (\ref eta_thermostat "docs/shear-viscosity.md"). After the collision stage every velocity is rescaled about
 * the current mean velocity u = sum m V / sum m,
 *   V -> u + s (V - u),   s^2 = (E_after + L)/E_after,
 * with E the kinetic energy relative to u and L the inelastic loss of the stage, so that exactly the
 * inelastic loss is restored: zeta dt = L/E_before, the same zeta for all species. This is the exact
 * integral of dV/dt = zeta V/2 over the stage (Montanero 2003, eq. (16), \ref eta_thermostat "docs/shear-viscosity.md" is its Euler form). In the dilute gas
 * the collisions change the energy only by the inelastic loss, so L = E_before - E_after and
 * s^2 = T_before/T_after. Rescaling about u rather than about zero keeps round-off momentum from being
 * amplified stage after stage (the run would otherwise end up thermostatting a bulk flow). The
 * centre-of-mass velocity is removed at the start (Montanero 2003 subtracts the plain mean).
 *
 * **Enskog gas in shear flow** (`pairs` scheme; collide.hpp set_shear): a collision uses the shifted
 * relative velocity g = V_k - V_l - a sigma_ij e_y x_hat, so besides the inelastic loss it does viscous
 * work on the particles, which the thermostat must leave alone (\ref eta_thermostat "docs/shear-viscosity.md"): there the energy after the
 * collisions is measured (one more pass) and s^2 = (E_after + L)/E_after. The collisional transfer
 * P^c = sum m_ij sigma_ij (1 + alpha)(g.e) e e / (V dt) is summed by the collider and written with the
 * kinetic part; its trace is the Enskog equation of state 2 (1 + alpha) phi chi n T (validated).
 *
 * **Sampling point** (the viscosity). The sample of a stage is taken after its streaming, before its
 * collisions (\ref eta_measured "docs/shear-viscosity.md"). Within the stationary stage cycle X = -P_xy jumps by a dt P_yy at the
 * streaming and then relaxes, collisions and thermostat together, as exp(-lambda) over the stage,
 * lambda = (nu_eta - zeta) dt. With X* = a P_yy/(nu_eta - zeta) the continuous-time value, the value
 * just before the jump is X* lambda/(e^lambda - 1) = X* (1 - lambda/2 + ...), just after it
 * X* lambda/(1 - e^-lambda) = X* (1 + lambda/2 + ...), and their mean X* (1 + lambda^2/12 + ...). The
 * streaming is linear, so the value before the jump follows exactly from the one after it:
 * P_xy(before) = P_xy(after) + a dt P_yy. The viscosity therefore uses the midpoint
 * P_xy + a dt P_yy/2, which is second order in the stage length (the first-order factor
 * 1/(1 - mean zeta dt) it replaced, measured against it: \ref perf_frames "docs/performance.md").
 *
 * **Cost: the frame.** The rescaling about the mean flow m, V -> m + s (V - m), and the streaming act
 * on every velocity alike, so a stage does not touch the particles: the System holds velocities u in a
 * frame, V = G u + b with G = S [[1, c, 0], [0, 1, 0], [0, 0, 1]] and an offset b (`Frame`;
 * collide.hpp, "Frame", for how the collisions use it), and a stage only updates (S, c, b)
 * (`advance_frame`: s multiplies S, the streaming subtracts a dt from c, and b follows both maps). The
 * kinetic energy about the mean flow and the mean flow follow from the frame, the second moments
 * Q = sum m u u^T that the collider keeps collision by collision, and the momentum P = sum m u, which
 * the collisions conserve (`frame_energy`):
 *   sum m V V^T = G Q G^T + G P b^T + b (G P)^T + M b b^T,   mean flow = G P / M + b.
 * The thermostat takes its loss from the collisions' own sum (collide.hpp, Counters::dissipated), since
 * dilute collisions change the energy only by that loss and keep the momentum; in the Enskog gas in
 * shear flow the energy after the collisions comes from the moments as well. One pass over the
 * particles (`materialise`: V = G u + b, with the energy, the mean flow, the moments and the largest
 * speeds) brings the frame back to the identity at every sample and whenever |c| > frame_shear_limit,
 * which keeps the collider's bounds within 2 % of exact (collide.hpp) and the u well conditioned, or
 * S leaves [1/2, 2]. In cache blocks the pass runs block by block on the block threads (Collider::map_blocks),
 * which also gives each block its exact bound; its sums are added in block order, so they do not depend on
 * the number of threads. bench/bench_usf.cpp measures the stage loop against the plain loop of the same
 * gas (\ref perf_frames "docs/performance.md").
 *
 * **Forcings that act on each particle** (the white noise). Their action over a stage is split in
 * halves, the first at the stage's start and the second at its end, which is the next stage's start:
 * there the two halves act as one, dt_previous/2 + dt/2 (Strang's splitting, second order in the stage
 * length where the plain split, all of it at the start, is first order; \ref wn_forcing "docs/white-noise.md"). At a
 * sample the sample is taken between the two halves, so a sample at t holds the action over [0, t)
 * exactly.
 *
 * Units: the user's. Namelist groups `&thermostat`, `&shear`. Checked by tests/thermostat_test.cpp and
 * validation/shear_viscosity.
 */
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/sample.hpp"
#include "dsmc/state.hpp"
#include "model/species.hpp"

namespace gdsmc::thermostat {

/// Kinetic energy relative to the mean flow, and the mean flow u = sum m V / sum m.
struct Energy {
  double kinetic = 0.0;                       ///< sum m |V - u|^2 / 2
  particles::Vec3 mean_flow{0.0, 0.0, 0.0};   ///< u
};
/// The Energy of the particles, in one pass.
Energy peculiar_energy(const species::Mixture& mix, const particles::System& sys);

/// V -> V - u for every particle: zero total momentum.
void remove_mean_flow(const species::Mixture& mix, particles::System& sys);

/// The streaming of uniform shear flow over dt: V_x -> V_x - a V_y dt.
void stream(particles::System& sys, double shear_rate, double dt);

/// What one pass over the particles at the start of a stage did and found (`begin_stage`).
struct StageStart {
  double kinetic = 0.0;             ///< kinetic energy relative to the mean flow, after the pass
  particles::Vec3 mean_flow{0.0, 0.0, 0.0};  ///< u = sum m V / sum m, after the pass
  std::vector<double> max_speed2;   ///< largest |V|^2 of each species, after the pass
  std::array<double, 4> moments{};  ///< sum m V V^T after the pass: xx, yy, zz, xy
  double total_mass = 0.0;          ///< sum m
  bool block_bounds = false;        ///< the pass also set the collider's block bounds (Collider::map_blocks)
};

/// The map from the stored velocities u to the actual ones (header, "Cost: the frame"):
/// V = S (u_x + c u_y, u_y, u_z) + b, S = `scale`, c = `shear`, b = `offset`.
struct Frame {
  double scale = 1.0;                      ///< S
  double shear = 0.0;                      ///< c
  particles::Vec3 offset{0.0, 0.0, 0.0};   ///< b
};

/// The frame is brought back to the identity when |c| exceeds this: ||G||/S <= 1.0202 (collide.hpp,
/// frame_norm), so the bounds stay within 2 % of exact; at a = 0.00284 and the default stage length
/// that is a pass every ~40 stages.
inline constexpr double frame_shear_limit = 0.04;

/// The frame after the rescaling V -> m + s (V - m) (s = 1: none) and then the streaming
/// V_x -> V_x - a V_y dt: S -> s S, c -> c - a dt, b -> L (m + s (b - m)), L the streaming map.
Frame advance_frame(const Frame& frame, double scale, const particles::Vec3& mean_flow, double shear_rate,
                    double dt);

/// Kinetic energy about the mean flow, and the mean flow, of V = G u + b, from the moments
/// Q = sum m u u^T (xx, yy, zz, xy), the momentum P = sum m u and the total mass M of the stored u
/// (header, "Cost: the frame"); no pass over the particles.
Energy frame_energy(const std::array<double, 4>& moments, const particles::Vec3& momentum, double total_mass,
                    const Frame& frame);

/// One pass over the particles: V = G u + b for every particle (the stored velocities become the
/// actual ones, the frame the identity), while the kinetic energy, the mean flow, the second
/// moments and the largest speeds of the result are summed up.
StageStart materialise(const species::Mixture& mix, particles::System& sys, const Frame& frame);

/// The start of a stage in one pass over the particles without a frame: the rescaling
/// V -> u + s (V - u) that the thermostat decided at the end of the previous stage (s = 1: none),
/// then the streaming V_x -> V_x - a V_y dt; materialise(advance_frame(identity, ...)).
StageStart begin_stage(const species::Mixture& mix, particles::System& sys, double scale,
                       const particles::Vec3& mean_flow, double shear_rate, double dt);

/// The Gaussian thermostat's factor s = sqrt((E_after + L)/E_after) = sqrt(E_before/(E_before - L))
/// after a dilute collision stage that began with `energy_before` and lost `loss` (collide.hpp's
/// Counters::dissipated, summed collision by collision); the collisions keep the mean flow, so
/// `mean_flow` is that of the stage's start. The rescaling itself is left to the next begin_stage;
/// `zeta_dt` = L/E_before.
struct Rescaling {
  double scale = 1.0;                      ///< s
  particles::Vec3 mean_flow{0.0, 0.0, 0.0};   ///< the mean flow u to rescale about
  double zeta_dt = 0.0;                    ///< L / E_before
};
/// The Rescaling for a stage that began with kinetic energy `energy_before` and lost `loss`.
Rescaling gaussian_rescaling(double energy_before, double loss, const particles::Vec3& mean_flow);

/// The Gaussian thermostat in one call (two passes), for tests and callers without a loss sum: after
/// a collision stage of the dilute gas that began with the kinetic energy `energy_before` (relative
/// to the mean flow), restores the inelastic loss by rescaling about the mean flow. Returns
/// zeta dt = L / E_before, L = E_before - E_after.
double rescale(const species::Mixture& mix, particles::System& sys, double energy_before);

/// P (xx, yy, zz, xy, xz, yz) at the middle of a stage's streaming jump V_x -> V_x - h V_y (header,
/// "Sampling point"), from P after it: P before it follows exactly (P_xx + 2 h P_xy + h^2 P_yy, P_xy +
/// h P_yy, P_xz + h P_yz), and the mean of the two is second order in the stage length; h = a dt.
std::array<double, 6> midpoint_pressure(const std::array<double, 6>& after, double h);

/// The forcings: what acts on every velocity between the collision stages of a replica (LAMMPS's
/// fixes, HOOMD's updaters), each an object with its own state, saved and restored under its own
/// name, and its own observables. The stage loop (run/replica.cpp; \ref ext_forcing "docs/extending.md")
/// calls, for a stage of length dt: compose() (the map the forcing applies to every velocity at the
/// stage's start, composed into the frame of the stored velocities), the collisions, end_stage(); at a
/// sample measure(), at the end of the replica finish().
class Forcing {
 public:
  virtual ~Forcing() = default;
  /// Its name: the prefix of its state in a checkpoint.
  virtual const char* name() const = 0;
  /// The longest stage it allows.
  virtual double longest_stage() const { return std::numeric_limits<double>::infinity(); }
  /// Composes the linear map it applies at the start of the stage about to begin into `rescaling`
  /// (V -> m + s (V - m), first) and `shear_rate` (V_x -> V_x - a V_y dt, then).
  virtual void compose(Rescaling& rescaling, double& shear_rate) = 0;
  /// Whether it also acts on each particle apart (random kicks, say): then at the start of a stage the
  /// frame is applied to the velocities first (one pass, skipped for the identity frame), and act()
  /// follows the linear maps (header, "Forcings that act on each particle").
  virtual bool acts_on_particles() const { return false; }
  /// Its action on every particle over a time dt (after the linear maps), drawing from `gen`, the
  /// replica's stream of forcings (rng Purpose::forcing); returns a velocity that the pass which follows
  /// adds to every particle (the kicks' centre-of-mass velocity removed there, say, not in a pass of its own).
  virtual particles::Vec3 act(particles::System& /*sys*/, double /*dt*/, rng::Xoshiro256pp& /*gen*/) {
    return {0.0, 0.0, 0.0};
  }
  /// What the end of a stage tells it: the kinetic energy and mean flow at the stage's start (after
  /// its streaming), the inelastic loss of its collisions, and the kinetic energy after them (a
  /// function: computed only when asked for).
  struct StageEnd {
    Energy start;                          ///< at the stage's start
    double loss = 0.0;                     ///< collide.hpp Counters::dissipated over the stage
    std::function<double()> energy_after;  ///< after the collisions
  };
  /// After the stage's collisions.
  virtual void end_stage(const StageEnd& end) = 0;
  /// What a sample shows it: the time, the temperature, the total pressure tensor (xx, yy, zz, xy, xz, yz;
  /// shear-viscosity.md's midpoint), its kinetic part, and whether the sample enters time averages.
  struct Sample {
    double time = 0.0;               ///< the sample's time
    double total_temperature = 0.0;  ///< T
    std::array<double, 6> pressure{};  ///< P = P^k + P^c: xx, yy, zz, xy, xz, yz
    std::array<double, 6> kinetic{};   ///< P^k, at the middle of the streaming jump
    bool averaged = false;             ///< not the first sample: it enters time averages
  };
  /// Adds its observables of a sample to `rows` (rows.add(name, columns, row), names of model/observables.hpp).
  virtual void measure(const Sample& sample, sample::Rows& rows) = 0;
  /// Adds its observables of the whole replica (time averages) to `rows`.
  virtual void finish(sample::Rows& rows) const = 0;
  /// Its state, under "<name>/...".
  virtual void save(state::Record& record) const = 0;
  /// Continues from save()'s record; throws state::StateError.
  virtual void restore(const state::Record& record) = 0;
};

/// The Gaussian thermostat (header; \ref eta_thermostat "docs/shear-viscosity.md"): after each stage it decides the
/// rescaling V -> u + s (V - u) that restores the stage's inelastic loss, applied at the next stage's
/// start. With viscous work in the collisions (the Enskog gas in shear flow) s^2 = (E_after + L)/E_after
/// from the energy after them; otherwise gaussian_rescaling(). Observable: thermostat_zeta_dt, the
/// mean zeta dt of the stages since the last sample.
class GaussianThermostat final : public Forcing {
 public:
  /// `viscous_work`: the collisions also do work on the particles (set_shear of collide.hpp).
  explicit GaussianThermostat(bool viscous_work) : viscous_work_(viscous_work) {}
  const char* name() const override { return "thermostat"; }
  void compose(Rescaling& rescaling, double& shear_rate) override;
  void end_stage(const StageEnd& end) override;
  void measure(const Sample& sample, sample::Rows& rows) override;
  void finish(sample::Rows&) const override {}
  void save(state::Record& record) const override;
  void restore(const state::Record& record) override;

 private:
  bool viscous_work_;
  Rescaling pending_;  ///< decided at the end of a stage, applied at the start of the next
  double zeta_sum_ = 0.0, zeta_stages_ = 0.0;  ///< zeta dt summed since the last sample, and the stages
};

/// Uniform shear flow u_x = a y (header; Montanero 2003, \ref eta_enskog_shear "docs/shear-viscosity.md"): the streaming V_x -> V_x - a V_y dt of
/// every stage, stages of at most 0.01/a, and the shear viscosity eta = -P_xy/a of each sample, reduced
/// by the elastic eta_0(T) of the gas with the finite-shear-rate correction 1 - (a* eta*)^2 (\ref eta_measured "docs/shear-viscosity.md"), and
/// its time average from `average_from` on (observables shear_viscosity_raw, reduced_shear_rate,
/// shear_viscosity, shear_viscosity_kinetic with collisional transfer, and the averages).
class ShearFlow final : public Forcing {
 public:
  /// `elastic_viscosity(T)`: eta_0 of the gas at temperature T (theory/viscosity.hpp, given by the
  /// caller); `density` n; `collisional`: the Enskog gas, whose kinetic part is measured apart.
  ShearFlow(double rate, double average_from, double density, bool collisional,
            std::function<double(double)> elastic_viscosity)
      : rate_(rate), average_from_(average_from), density_(density), collisional_(collisional),
        elastic_viscosity_(std::move(elastic_viscosity)) {}
  const char* name() const override { return "shear"; }
  double longest_stage() const override { return 0.01 / rate_; }
  void compose(Rescaling&, double& shear_rate) override { shear_rate = rate_; }
  void end_stage(const StageEnd&) override {}
  void measure(const Sample& sample, sample::Rows& rows) override;
  void finish(sample::Rows& rows) const override;
  void save(state::Record& record) const override;
  void restore(const state::Record& record) override;

 private:
  double rate_, average_from_, density_;
  bool collisional_;
  std::function<double(double)> elastic_viscosity_;
  double window_sum_ = 0.0, window_kinetic_sum_ = 0.0, window_samples_ = 0.0;  ///< the time average's sums
  /// The same window's sums of a* and P_ij/(n T), T = tr P^k/(3 n) at the middle of the streaming jump
  /// (shear_state_average: a*, P_xx, P_yy, P_zz, P_xy over n T).
  std::array<double, 5> state_sum_{};
};

/// The white-noise thermostat (\ref wn_forcing "docs/white-noise.md"; van Noije and Ernst 1998; mixtures: Barrat
/// and Trizac 2002): the kicks over a time dt (Stages splits a stage's in halves, header) are, for every
/// particle of species k, an independent Gaussian dv = sqrt(chi^2_k dt) xi per component, and then the
/// kicks' centre-of-mass velocity sum m dv / sum m is taken from every particle (returned, for the pass
/// that follows), so the total momentum stays zero (the energy input is (3/2) sum_k N_k m_k chi^2_k dt (1 - m_k/M) in the mean). Angular
/// velocities are not kicked. No state of its own (the stream is the stages'); no observables.
class WhiteNoise final : public Forcing {
 public:
  /// chi^2_k per species of `mix`.
  WhiteNoise(const species::Mixture& mix, std::vector<double> strength) : mix_(mix), strength_(std::move(strength)) {}
  const char* name() const override { return "white_noise"; }
  void compose(Rescaling&, double&) override {}
  bool acts_on_particles() const override { return true; }
  particles::Vec3 act(particles::System& sys, double dt, rng::Xoshiro256pp& gen) override;
  void end_stage(const StageEnd&) override {}
  void measure(const Sample&, sample::Rows&) override {}
  void finish(sample::Rows&) const override {}
  void save(state::Record&) const override {}
  void restore(const state::Record&) override {}

 private:
  const species::Mixture& mix_;
  std::vector<double> strength_;
};

/// The stages of a replica with forcings (header, "Stages" and "Cost: the frame"): per stage of length
/// dt, the forcings' linear maps composed into the frame of the stored velocities (V = G u + b; G in
/// the collider, b here), one pass over the particles when the frame strays (|c| > frame_shear_limit,
/// S outside [1/2, 2]), at a sample, or when a forcing acts on each particle, then the collisions of the
/// stage (collide.hpp, continuous time) and the forcings' ends. A sample is taken at a stage's start,
/// after its streaming (header, "Sampling point"): the pressure tensor (kinetic, at the middle of the
/// streaming jump, and collisional in the Enskog gas in shear flow) and the forcings' observables.
class Stages {
 public:
  /// The stages of the gas `mix` in `sys` with `collider`, under `forcings` (in the order they act),
  /// of `stage_step` majorant mean free times at most; `shear_rate` a and `collisional` (the Enskog
  /// gas in shear flow, collide.hpp set_shear) for the pressure tensor; `gen`: the forcings' stream.
  Stages(const species::Mixture& mix, particles::System& sys, collide::Collider& collider,
         std::vector<std::unique_ptr<Forcing>> forcings, double stage_step, double shear_rate, bool collisional,
         rng::Xoshiro256pp gen);
  /// The end of a stage of the default length from now, not beyond `limit` (then exactly `limit`).
  double stage_end(double limit) const;
  /// The start of a stage of length `dt` (header): the forcings' maps and actions; with `sample`, the
  /// velocities are the actual ones afterwards (a pass), ready to be measured.
  void begin(double dt, bool sample);
  /// The collisions of the stage up to `end`, then the forcings' ends.
  void end(double end);
  /// A sample at the start of a stage of length `dt` (after begin(dt, true)): the pressure tensors of
  /// the moments `m`, then each forcing's observables (`averaged`: the sample enters time averages).
  void measure(const sample::Moments& m, double dt, bool averaged, sample::Rows& rows);
  /// The end of the replica: the forcings' time averages.
  void finish(sample::Rows& rows) const;
  /// Stages run so far.
  double count() const { return count_; }
  /// Its state and the forcings' under "stages/...", "<forcing>/...".
  void save(state::Record& record) const;
  /// Continues from save()'s record (after the collider's restore: the frame's G is the collider's).
  void restore(const state::Record& record);

 private:
  const species::Mixture& mix_;
  particles::System& sys_;
  collide::Collider& collider_;
  std::vector<std::unique_ptr<Forcing>> forcings_;
  double stage_step_, stage_cap_, shear_rate_;
  bool collisional_, acts_;  ///< the Enskog gas in shear flow; a forcing acts on each particle
  double deferred_act_ = 0.0;  ///< at a sample: the time over which the forcings act after it
  double pending_act_ = 0.0;   ///< the second half of the last stage, over which the forcings have not yet acted
  /// The forcings' actions on each particle over dt, then a pass (the stage's start values).
  void act(double dt);
  /// The stage's start values from a pass: momentum, the collider's exact bounds, energy and mean flow.
  void start_from(const StageStart& pass);
  /// materialise(mix_, sys_, frame), or with cache blocks the same pass on the block threads (Collider::map_blocks).
  StageStart materialise_pass(const Frame& frame);
  rng::Xoshiro256pp gen_;
  double total_mass_ = 0.0;
  Frame frame_;
  particles::Vec3 momentum_{0.0, 0.0, 0.0};  ///< sum m u of the stored u
  Energy start_;                             ///< the energy and mean flow at the stage's start
  double count_ = 0.0;
  double last_sample_time_ = 0.0;
  std::array<double, 6> last_transfer_{};  ///< collide.hpp Counters::transfer at the previous sample
};

}  // namespace gdsmc::thermostat
