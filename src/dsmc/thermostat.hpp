/**
 * \file thermostat.hpp
 * \brief The Gaussian thermostat of the homogeneous steady state and the streaming of uniform shear
 *        flow (seed 004 sec. 2, eqs 1-18 as corrected by ERRATA §13; docs/physics.md, "Thermostat
 *        and uniform shear flow").
 *
 * **Stages.** A run with `&thermostat kind = 'gaussian'` or `&shear rate = a` advances in stages of
 * length dt (`&dsmc stage_step` majorant mean free times, at most 0.01/a): streaming, collisions
 * (collide.hpp, continuous time within the stage), thermostat. The operator splitting is first order
 * in dt (ERRATA §9's reasoning); the validation measures the bias at two stage lengths.
 *
 * **Streaming** (homogeneous USF in the Lagrangian frame, peculiar velocities only):
 * V_x -> V_x - a V_y dt for every particle. The total momentum is unchanged when sum m V_y = 0; the
 * energy changes by -a P_xy V dt + O(dt^2): viscous heating.
 *
 * **Gaussian thermostat** (ERRATA §13). After the collision stage every velocity is rescaled about
 * the current mean velocity u = sum m V / sum m,
 *   V -> u + s (V - u),   s^2 = (E_after + L)/E_after,
 * with E the kinetic energy relative to u and L the inelastic loss of the stage, so that exactly the
 * inelastic loss is restored: zeta dt = L/E_before, the same zeta for all species. This is the exact
 * integral of dV/dt = zeta V/2 over the stage (seed 004 eq 16 is its Euler form). In the dilute gas
 * the collisions change the energy only by the inelastic loss, so L = E_before - E_after and
 * s^2 = T_before/T_after. Rescaling about u rather than about zero keeps round-off momentum from being
 * amplified stage after stage (the run would otherwise end up thermostatting a bulk flow). The
 * centre-of-mass velocity is removed at the start (seed 004 subtracts the plain mean).
 *
 * Units: the user's. Namelist groups `&thermostat`, `&shear`. Checked by tests/thermostat_test.cpp and
 * validation/shear_viscosity.
 */
#pragma once

#include "dsmc/particles.hpp"
#include "dsmc/species.hpp"

namespace gdsmc::thermostat {

/// Kinetic energy relative to the mean flow, and the mean flow u = sum m V / sum m.
struct Energy {
  double kinetic = 0.0;
  particles::Vec3 mean_flow{0.0, 0.0, 0.0};
};
Energy peculiar_energy(const species::Mixture& mix, const particles::System& sys);

/// V -> V - u for every particle: zero total momentum.
void remove_mean_flow(const species::Mixture& mix, particles::System& sys);

/// The streaming of uniform shear flow over dt: V_x -> V_x - a V_y dt.
void stream(particles::System& sys, double shear_rate, double dt);

/// The Gaussian thermostat after a collision stage of the dilute gas that began with the kinetic
/// energy `energy_before` (relative to the mean flow): restores the inelastic loss by rescaling about
/// the mean flow. Returns zeta dt = L / E_before, L = E_before - E_after.
double rescale(const species::Mixture& mix, particles::System& sys, double energy_before);

}  // namespace gdsmc::thermostat
