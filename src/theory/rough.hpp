/**
 * \file rough.hpp
 * \brief Rough spheres of one species in the Maxwellian approximation: the two-temperature cooling
 *        equations, the steady ratio theta = T_rot/T_tr of the homogeneous cooling state and its cooling rate.
 *
 * Normal restitution alpha, tangential restitution beta, reduced moment of inertia kappa = 4 I/(m sigma^2).
 * With translational and rotational velocities Maxwellian at T_tr and T_rot and uncorrelated, the energy
 * each collision moves (dsmc/rules.hpp RoughRule) averaged over the collisions gives
 * (\ref rough_maxwellian "docs/rough-spheres.md"; Huthmann and Zippelius 1997; Luding, Huthmann,
 * McNamara and Zippelius 1998, in 3D; derived in the docs page):
 *   dT_tr/dc = (4/3)(-A T_tr + B T_rot),   dT_rot/dc = (4/3)(B T_tr - C T_rot),
 *   A = (1 - alpha^2)/4 + eta (1 - eta),  B = eta^2/kappa,  C = (eta/kappa)(1 - eta/kappa),
 *   eta = kappa (1 + beta)/(2 (1 + kappa)),
 * with c the collisions per particle, dc/dt = nu = 4 n sigma^2 chi sqrt(pi T_tr/m). Their ratio tends to
 *   theta = [A - C + sqrt((A - C)^2 + 4 B^2)]/(2 B)   (beta > -1; theta = 0 for the smooth limit),
 * and T_tr then cools at zeta_tr = nu (4/3)(A - B theta): zeta* = zeta_tr/nu. beta = -1 gives the smooth
 * gas (A = (1 - alpha^2)/4, zeta* = (1 - alpha^2)/3, \ref haff_law "docs/haff-and-mixtures.md").
 *
 * Units: temperatures in energy, times in the user's time. Checked by tests/rough_test.cpp (by hand,
 * the smooth limit, the elastic perfectly rough gas) and validation/rough_spheres.
 */
#pragma once

#include <vector>

#include "model/species.hpp"

namespace gdsmc::theory::rough {

/// A, B, C of the two-temperature equations (header) for alpha, beta, kappa.
struct Coefficients {
  double a;  ///< A = (1 - alpha^2)/4 + eta (1 - eta)
  double b;  ///< B = eta^2/kappa
  double c;  ///< C = (eta/kappa)(1 - eta/kappa)
};
/// The coefficients of one species (header).
Coefficients coefficients(double alpha, double beta, double kappa);

/// nu_1 = 4 n sigma^2 chi sqrt(pi/m) of one species: the Maxwellian collision frequency is nu_1 sqrt(T_tr)
/// (\ref cm_pair_rate "docs/collision-model.md").
double frequency_unit(const species::Mixture& mix);

/// The homogeneous cooling state, Maxwellian approximation (header).
struct CoolingState {
  double theta;                 ///< T_rot/T_tr
  double cooling_rate_reduced;  ///< zeta_tr/nu = (4/3)(A - B theta)
};
/// theta and zeta_tr/nu of one species (header).
CoolingState cooling_state(double alpha, double beta, double kappa);

/// The steady state under white noise on the translational velocities (\ref wn_theory "docs/white-noise.md"):
/// the spins are not kicked, so dT_rot/dc = 0 gives theta = B/C (0 for smooth spheres), and the
/// translational loss per collision per particle is (4/3)(A - B theta) T_tr, which the noise's
/// m chi^2 per unit time balances: m chi^2 = nu (4/3)(A - B theta) T_tr. `cooling_rate_reduced` is that
/// (4/3)(A - B theta).
CoolingState driven_state(double alpha, double beta, double kappa);

/// T_tr and T_rot at a run's sample points, with the collisions per particle and the times.
struct History {
  std::vector<double> time;                     ///< sample times
  std::vector<double> translational;            ///< T_tr
  std::vector<double> rotational;               ///< T_rot
  std::vector<double> collisions_per_particle;  ///< c
};
/// The two-temperature equations of the one-species rough gas `mix` from T_tr(0), T_rot(0), at the
/// times `times` (increasing), or, with `collision_driven`, at the collisions per particle `times`.
History integrate(const species::Mixture& mix, double translational, double rotational, const std::vector<double>& times,
                  bool collision_driven);

}  // namespace gdsmc::theory::rough
