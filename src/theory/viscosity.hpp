/**
 * \file viscosity.hpp
 * \brief Navier-Stokes shear viscosity of a granular gas and of a granular mixture, dilute
 *        (Boltzmann) and moderately dense (Enskog), in the first Sonine approximation, for the
 *        homogeneous cooling state (HCS) and the Gaussian-thermostatted homogeneous steady state
 *        (HSS). These are the theory curves of Montanero 2003,
 *        Figs 6-12.
 *
 * \section viscosity_intro What this module computes
 *
 * The shear viscosity eta relates the traceless pressure tensor to the velocity gradient,
 * P_xy = -eta du_x/dy. For a granular gas eta depends on the reference state the gradients are
 * applied to: in the HCS the temperature falls while the momentum relaxes (cooling coefficient
 * c = 1/2 below), with a Gaussian thermostat that compensates the cooling (HSS, the state the DSMC
 * of Montanero 2003, Sec. 3 and \ref eta_measured "docs/shear-viscosity.md" measures) it does not (c = 1). The state is chosen with
 * viscosity::State. The physics page `docs/physics.md`, section "Shear viscosity", restates these
 * equations for users.
 *
 * Notation (\ref cm_notation "docs/collision-model.md", species.hpp): species i with mass m_i, diameter sigma_i, number density n_i,
 * n = sum_i n_i, x_i = n_i/n, partial temperature T_i, T = sum_i x_i T_i;
 * sigma_ij = (sigma_i + sigma_j)/2, mu_ij = m_i/(m_i + m_j), alpha_ij, chi_ij (1 dilute,
 * Carnahan-Starling for Enskog, \ref cm_chi "docs/collision-model.md"), packing fraction phi = (pi/6) sum_i n_i sigma_i^3.
 *
 * \subsection viscosity_one One component, dilute (\ref eta_one_species "docs/shear-viscosity.md")
 * - Elastic first Chapman-Enskog value: eta_0 = (5/(16 sigma^2)) sqrt(m T/pi)
 *   (Chapman and Cowling; Montanero 2003, Fig. 6, \ref eta_one_species "docs/shear-viscosity.md" normalisation).
 * - Reduced collision frequency of the momentum flux and cooling rate, in units of
 *   nu_0 = n T/eta_0 (Brey, Dufty, Kim and Santos 1998, PRE 58, 4638; Garzo and Dufty 1999,
 *   PRE 59, 5895, eqs for nu_eta* and zeta* at d = 3):
 *   nu_eta* = (1 + alpha)(3 - alpha)/4 (1 - a2/32),  zeta* = (5/12)(1 - alpha^2)(1 + 3 a2/16),
 *   with the van Noije-Ernst a2(alpha) of theory::sonine_a2 (\ref haff_sonine "docs/haff-and-mixtures.md").
 *   (Garzo and Dufty write c* = 2 a2: their (1 - c* / 64) and (1 + 3 c* / 32) are the factors
 *   above.)
 * - eta/eta_0 = 1/(nu_eta* - c zeta*), c = 1/2 in the HCS (Brey et al. 1998), c = 1 in the HSS
 *   with a Gaussian thermostat (Garzo and Montanero 2002, Physica A 313, 336). \ref eta_one_species "docs/shear-viscosity.md":
 *   at alpha = 0.5, HCS 1.2851, HSS 1.6119.
 *
 * \subsection viscosity_enskog_one One component, Enskog (Garzo and Dufty 1999, PRE 59, 5895)
 * The shear viscosity of Garzo and Dufty 1999 at d = 3 (its equation numbers were not checked here:
 * the paper is not among the seeds; the formulas below were checked against their alpha = 1 limit,
 * their dilute limit, and the independent mixture formulas of GHD 2007 for identical species).
 * In units of eta_0 (the dilute elastic value above), with chi = chi(phi):
 * - kinetic part: eta_k* = [1 - (2/5)(1 + alpha)(1 - 3 alpha) phi chi]/(nu_eta* - c zeta*), where
 *   nu_eta* and zeta* are the dilute values multiplied by chi (every collision rate carries chi,
 *   \ref cm_chi "docs/collision-model.md");
 * - collisional transfer: eta_c* = (4/5) phi chi (1 + alpha) eta_k* + (3/5) kappa*,
 * - bulk viscosity: kappa* = (128/(5 pi)) phi^2 chi (1 + alpha)(1 - a2/16)  (their (1 - c* / 32));
 * - eta* = eta_k* + eta_c*. At alpha = 1 this is Enskog's hard-sphere result
 *   eta/eta_0 = (1/chi)(1 + (8/5) phi chi)^2 + (768/(25 pi)) phi^2 chi (Chapman and Cowling,
 *   ch. 16, dense rigid spheres, with b rho = (2 pi/3) n sigma^3 = 4 phi), which
 *   tests/viscosity_test.cpp checks.
 *
 * \subsection viscosity_mixture Mixture, any number of species (\ref eta_mixture "docs/shear-viscosity.md")
 * Garzo and Dufty 2002 (Phys. Fluids 14, 1476) for the dilute mixture; Garzo, Hrenya and Dufty
 * 2007 (PRE 76, 031303 and 031304) for the Enskog mixture, in the form implemented by MFIX
 * (model/GhdTheory/shear_viscosity.f, bulk_viscosity.f, ghd.f; our code is written from the
 * equations, not translated; the papers are not among the seeds, so their equation numbers are not
 * quoted, and every term was checked instead: see \ref viscosity_checks). Leading Sonine order:
 * each species' reference distribution is a Maxwellian at its own T_i (the c_i of \ref son_binary "docs/sonine.md" do not
 * enter; for one species this drops the a2 factors of the one-component formulas above, which
 * tests/viscosity_test.cpp uses).
 * With mbar = (1/S) sum_i m_i (the plain mean of the masses, as GHD), v0 = sqrt(2 T/mbar),
 * theta_i = m_i T/(mbar T_i), beta_ij = mu_ij theta_j - mu_ji theta_i,
 * r_ij = sqrt(theta_i + theta_j):
 *   S_i = sum_{j != i} n_j chi_ij sigma_ij^2 mu_ji (1 + alpha_ij) theta_i^(3/2) theta_j^(-1/2)
 *         [6 beta_ij/(theta_i^2 r_ij) + (9 - 3 alpha_ij)/2 mu_ji r_ij/theta_i^2
 *          + 5/(theta_i r_ij)],
 *   tau_ii = (4 sqrt(pi)/15) v0 [n_i chi_ii sigma_i^2 (2 theta_i)^(-1/2) (9 - 3 alpha_ii)
 *            (1 + alpha_ii) + 2 S_i],
 *   tau_ij = (8 sqrt(pi)/15) v0 n_i chi_ij sigma_ij^2 mu_ij theta_j^(3/2) theta_i^(-1/2)
 *            (1 + alpha_ij) [6 beta_ij/(theta_j^2 r_ij) + (9 - 3 alpha_ij)/2 mu_ji r_ij/theta_j^2
 *             - 5/(theta_j r_ij)]   (i != j),
 *   sum_j (tau_ij - c zeta_0 delta_ij) eta_j = n_i T_i + b_i         (\ref eta_mixture "docs/shear-viscosity.md"; GHD 2007 II),
 * where zeta_0 = (1/T) sum_i x_i T_i zeta_i is the Maxwellian cooling rate of the mixture at these
 * T_i, zeta_i = sum_j xi_ij the partial cooling rates of \ref haff_mixture_odes "docs/haff-and-mixtures.md" (theory::cooling_rate_matrix;
 * in the HCS all zeta_i are equal). The dilute gas has chi_ij = 1 and b_i = 0. The Enskog gas adds
 * the collisional-transfer source of the kinetic part (GHD 2007 II; MFIX shear_viscosity.f)
 *   b_i = (2 pi/15) m_i n_i sum_j n_j mu_ji sigma_ij^3 chi_ij (1 + alpha_ij)
 *         [mu_ji (3 alpha_ij - 1)(T_i/m_i + T_j/m_j) - 4 (T_i - T_j)/(m_i + m_j)],
 * and the collisional-transfer part of eta
 *   eta_c = sum_ij (4 pi/15) n_j sigma_ij^3 chi_ij mu_ji (1 + alpha_ij) eta_i + (3/5) kappa,
 *   kappa = (2 sqrt(pi)/9) v0 sum_ij mu_ij m_j n_i n_j sigma_ij^4 chi_ij (1 + alpha_ij)
 *           sqrt((theta_i + theta_j)/(theta_i theta_j))        (bulk viscosity, GHD 2007 II).
 * eta_i (the solution) are the kinetic partial viscosities, eta_k = sum_i eta_i,
 * eta = eta_k + eta_c.
 * For one species these reduce to the one-component Enskog formulas at a2 = 0 (checked).
 * The choice of mbar only sets the scale of v0 and theta_i: eta does not depend on it.
 * The linear system is solved with Eigen's column-pivoting Householder QR.
 *
 * Reference states:
 * - T_i: any vector of ratios T_i/T (normalised here so that sum_i x_i T_i/T = 1). For the
 *   HCS and HSS of a binary mixture, binary_state_temperature_ratios gives the first-Sonine
 *   gamma = T1/T2 of theory::binary_hcs_first_sonine (\ref son_binary_gamma "docs/sonine.md": in the HSS gamma equals the HCS
 *   value, \ref eta_thermostat "docs/shear-viscosity.md").
 * - Normalisation: eta_0 of the mixture = the dilute (chi_ij = 1) elastic (alpha_ij = 1) mixture at
 *   T_i = T, from the same tau_ij system with zeta_0 = 0: Chapman and Cowling's first
 *   approximation for a hard-sphere mixture (\ref eta_mixture "docs/shear-viscosity.md": DSMC divides by this). Montanero 2003, Figs. 10-12
 *   use instead eta* = nu eta/(n T) with nu = sqrt(pi) n sigma_12^2 v0,
 *   v0 = sqrt(2 T (m1 + m2)/(m1 m2)) (binary_reduced_viscosity_frequency).
 *
 * \subsection viscosity_usf Steady uniform shear flow without thermostat, dilute, one component or a binary (\ref eta_usf_steady "docs/shear-viscosity.md")
 * Viscous heating balances the collisional cooling, so the shear rate in units of nu_0 = n T/eta_0 takes
 * one value a*(alpha). Grad's solution (the moment equations of P_ij closed with the collisional moment of
 * a Maxwellian times Grad's second-order term, linear in P_ij - p delta_ij, a2 = 0; derived in
 * \ref eta_usf_steady "docs/shear-viscosity.md"; Santos, Garzo and Dufty 2004, PRE 69, 061303; for mixtures
 * Montanero and Garzo 2002, Physica A 310, 17), with nu_eta*, zeta* above at a2 = 0:
 *   a*^2 = (3/2) zeta* nu_eta*^2/(nu_eta* - zeta*),  P_yy/p = P_zz/p = 1 - zeta* / nu_eta*,
 *   P_xx/p = 1 + 2 zeta* / nu_eta*,  P_xy/p = -a* (1 - zeta* / nu_eta*)/nu_eta*,  eta/eta_0 = (1 - zeta* / nu_eta*)/nu_eta*.
 * Binary mixtures (steady_shear_grad(mix); the approach of Montanero and Garzo, Physica A 310, 17): each species a Maxwellian at
 * its T_i times Grad's term, the collisional moment of P_i = -sum_j tau_ij Pi_j - zeta_i p_i I with the tau_ij of
 * \ref viscosity_mixture and zeta_i = sum_j xi_ij; the steady state: -a P_i,xy = (3/2) zeta_i p_i,
 * Pi_yy = Pi_zz = -tau^-1 (zeta p) and a^2 (p_i + Pi_i,yy) = (3/2) [tau (zeta p)]_i, one a^2 per species, equal at
 * the temperature ratio sought (bisection in ln(T_1/T_2)). An elastic gas has no steady state (it heats): refused.
 * Its error, measured against the independent program of validation/independent_reference, is stated in
 * \ref eta_usf_steady "docs/shear-viscosity.md"; validation/shear_viscosity checks both.
 *
 * \subsection viscosity_units Units
 * Any consistent units with k_B = 1: eta in mass/(length time), e.g. eta_0 = (5/(16 sigma^2))
 * sqrt(m T/pi). The reduced functions are dimensionless.
 *
 * \subsection viscosity_checks How it is checked
 * tests/viscosity_test.cpp: \ref eta_one_species "docs/shear-viscosity.md" reference values, two identical species = one species at
 * a2 = 0, the elastic limit against Chapman-Cowling numbers computed independently (one species and
 * a binary hard-sphere mixture from Chapman and Cowling's [eta]_1 formula), the tau_ij system at
 * unequal temperatures and restitutions against a Monte Carlo evaluation of the collision integrals
 * it stands for, permutation of species, the \ref eta_mixture "docs/shear-viscosity.md" DSMC point (theory value 1.2044), the
 * Enskog mixture against the one-component Enskog formulas and its dilute limit, the one-component
 * Enskog elastic limit against Enskog's hard-sphere formula, and the thresholds Montanero 2003 states for
 * its Figs 11-12 (phi_0 ~ 0.22; the theory here crosses between 0.22 and 0.23).
 *
 * Input checks: std::invalid_argument for restitution outside [0, 1], non-positive or non-finite
 * temperatures, packing fractions outside [0, 1), a wrong number of temperature ratios, and a
 * singular or non-positive viscosity (the states where nu_eta* <= c zeta* have no Navier-Stokes
 * viscosity in this approximation).
 */
#pragma once

#include <vector>

#include "model/species.hpp"

namespace gdsmc::theory::viscosity {

/// Reference state of the Chapman-Enskog expansion: it fixes the cooling coefficient c.
enum class State {
  homogeneous_cooling,  ///< HCS, free cooling: c = 1/2 (Brey et al. 1998)
  gaussian_thermostat,  ///< HSS, Gaussian thermostat: c = 1 (Garzo and Montanero 2002; \ref eta_thermostat "docs/shear-viscosity.md")
};

/// c of eta/eta_0 = 1/(nu_eta* - c zeta*): 1/2 for the HCS, 1 for the HSS.
double cooling_coefficient(State state);

// ---------------------------------------------------------------------------------------------
// One component
// ---------------------------------------------------------------------------------------------

/// \ref eta_one_species "docs/shear-viscosity.md": elastic dilute first Chapman-Enskog viscosity
/// eta_0 = (5/(16 sigma^2)) sqrt(m T/pi).
double elastic_viscosity(double mass, double diameter, double temperature);

/// \ref eta_one_species "docs/shear-viscosity.md": nu_eta* = (1 + alpha)(3 - alpha)/4 (1 - a2/32) (dilute; Enskog multiplies by chi).
double reduced_momentum_collision_frequency(double alpha, double a2);

/// \ref eta_one_species "docs/shear-viscosity.md": zeta* = (5/12)(1 - alpha^2)(1 + 3 a2/16) (dilute; Enskog multiplies by chi).
double reduced_cooling_rate(double alpha, double a2);

/// \ref eta_one_species "docs/shear-viscosity.md": dilute eta/eta_0 = 1/(nu_eta* - c zeta*) with the given a2.
double dilute_reduced_viscosity(double alpha, State state, double a2);

/// \ref eta_one_species "docs/shear-viscosity.md": dilute eta/eta_0 with the van Noije-Ernst a2(alpha) (theory::sonine_a2).
double dilute_reduced_viscosity(double alpha, State state);

/// The steady uniform shear flow without thermostat of one dilute component, Grad's solution (see
/// \ref viscosity_usf; \ref eta_usf_steady "docs/shear-viscosity.md"). Pressures in units of p = n T.
struct SteadyShear {
  double reduced_shear_rate = 0.0;  ///< a* = a eta_0(T)/(n T)
  double viscosity = 0.0;           ///< eta/eta_0 = -P_xy/(a eta_0)
  double pressure_xx = 0.0;         ///< P_xx/p
  double pressure_yy = 0.0;         ///< P_yy/p (= P_zz/p in this approximation)
  double pressure_zz = 0.0;         ///< P_zz/p
  double pressure_xy = 0.0;         ///< P_xy/p (negative)
};

/// \ref eta_usf_steady "docs/shear-viscosity.md": Grad's steady state at restitution alpha in [0, 1].
SteadyShear steady_shear_grad(double alpha);

/// The same for a dilute binary mixture (\ref viscosity_usf): the partial temperatures and the mixture's
/// a* (over the elastic mixture's eta_0) and P_ij/p.
struct MixtureSteadyShear {
  std::vector<double> temperature_ratio;  ///< T_i/T
  double reduced_shear_rate = 0.0;        ///< a* = a eta_0(T)/(n T), eta_0 of the elastic mixture
  double pressure_xx = 0.0;               ///< P_xx/p
  double pressure_yy = 0.0;               ///< P_yy/p
  double pressure_zz = 0.0;               ///< P_zz/p (= P_yy/p)
  double pressure_xy = 0.0;               ///< P_xy/p
};

/// \ref eta_usf_steady "docs/shear-viscosity.md": Grad's steady state of a dilute binary mixture; throws
/// std::invalid_argument for another mixture, std::runtime_error when no temperature ratio balances it.
MixtureSteadyShear steady_shear_grad(const species::Mixture& mix);

/// One-component Enskog viscosity in units of eta_0 (see \ref viscosity_enskog_one).
struct EnskogReducedViscosity {
  double kinetic;      ///< eta_k/eta_0
  double collisional;  ///< eta_c/eta_0 = (4/5) phi chi (1 + alpha) eta_k* + (3/5) kappa*
  double bulk;         ///< kappa/eta_0 (bulk viscosity)
  double total;        ///< eta/eta_0 = kinetic + collisional
};

/// Garzo and Dufty 1999: one-component Enskog eta/eta_0 at packing fraction phi and pair
/// correlation chi (e.g. Carnahan-Starling (1 - phi/2)/(1 - phi)^3), with the given a2.
EnskogReducedViscosity enskog_reduced_viscosity(double alpha, double packing_fraction, double chi,
                                                State state, double a2);

/// As above with a2 = theory::sonine_a2(alpha) and chi = Carnahan-Starling (\ref cm_chi "docs/collision-model.md").
EnskogReducedViscosity enskog_reduced_viscosity(double alpha, double packing_fraction, State state);

// ---------------------------------------------------------------------------------------------
// Mixtures (leading Sonine order, Maxwellian partial temperatures)
// ---------------------------------------------------------------------------------------------

/// Viscosity of a mixture at temperature T (see \ref viscosity_mixture). All viscosities in the
/// user's units.
struct MixtureViscosity {
  std::vector<double> partial;  ///< eta_i, kinetic partial viscosities (solution of the tau system)
  double kinetic = 0.0;         ///< eta_k = sum_i eta_i
  double collisional = 0.0;     ///< collisional transfer part (0 for a dilute mixture)
  double bulk = 0.0;            ///< bulk viscosity kappa (0 for a dilute mixture)
  double total = 0.0;           ///< eta = kinetic + collisional
  double elastic = 0.0;         ///< eta_0: dilute elastic mixture, equal temperatures, same T
  double reduced = 0.0;         ///< total/elastic
  double cooling_rate = 0.0;    ///< zeta_0 used (Maxwellian, \ref haff_mixture_odes "docs/haff-and-mixtures.md")
};

/**
 * Shear viscosity of a mixture at mixture temperature `temperature` with partial temperatures
 * T_i = temperature_ratio[i] T (the ratios are normalised so that sum_i x_i T_i = T). A Mixture
 * with `enskog` adds chi_ij and the collisional-transfer parts; a dilute one has chi_ij = 1.
 * Throws std::invalid_argument for bad input, std::runtime_error if the tau system is singular.
 */
MixtureViscosity mixture_viscosity(const species::Mixture& mix,
                                   const std::vector<double>& temperature_ratio, double temperature,
                                   State state);

/// eta_0 of the mixture: dilute, elastic, T_i = T (Chapman and Cowling's first approximation).
double elastic_mixture_viscosity(const species::Mixture& mix, double temperature);

/// T_i/T of the HCS (= HSS, \ref eta_mixture "docs/shear-viscosity.md") of a binary mixture from the first-Sonine
/// gamma = T1/T2 (theory::binary_hcs_first_sonine, \ref son_binary_gamma "docs/sonine.md"): T1/T = gamma/(1 + x1 (gamma - 1)),
/// T2/T = 1/(1 + x1 (gamma - 1)).
std::vector<double> binary_state_temperature_ratios(const species::Mixture& mix);

/// Shear viscosity of a binary mixture in its HCS/HSS (temperature ratios from
/// binary_state_temperature_ratios).
MixtureViscosity binary_viscosity(const species::Mixture& mix, double temperature, State state);

/// Montanero 2003, Figs. 10-12, \ref eta_mixture "docs/shear-viscosity.md": nu = sqrt(pi) n sigma_12^2 v0, v0 = sqrt(2 T (m1 + m2)/(m1 m2)); the
/// reduced viscosity there is eta* = nu eta/(n T).
double binary_reduced_viscosity_frequency(const species::Mixture& mix, double temperature);

}  // namespace gdsmc::theory::viscosity
