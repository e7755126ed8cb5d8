/**
 * \file sonine.hpp
 * \brief Homogeneous cooling state (HCS) of a binary granular mixture in the first Sonine
 *        approximation of Garzo and Dufty: temperature ratio gamma = T1/T2, the fourth-moment
 *        coefficients c_1, c_2, the reduced cooling rate zeta* and the high-velocity tails.
 *
 * \section sonine_intro What this module computes
 *
 * In the HCS each species' distribution scales with the mixture temperature T (Montanero and Garzo 2002, eq. (12), \ref son_scaling "docs/sonine.md"),
 * f_i(v; t) = n_i v0^-3 Phi_i(v/v0), v0 = sqrt(2 T (m1 + m2)/(m1 m2)), and both partial
 * temperatures cool at the same rate, zeta_1 = zeta_2 (Montanero and Garzo 2002, eq. (10), \ref son_scaling "docs/sonine.md"), which fixes
 * gamma = T1/T2. The first Sonine approximation (Montanero and Garzo 2002, eq. (17), \ref son_scaling "docs/sonine.md") is
 * Phi_i(v*) = (lambda_i/pi)^(3/2) exp(-lambda_i v*^2)
 *            [1 + (c_i/4)(lambda_i^2 v*^4 - 5 lambda_i v*^2 + 15/4)],
 * lambda_i = T/(T_i mu_ji). Its c_i are twice the usual a2:
 * c_i = 2 [(3/5) <v^4>_i/<v^2>_i^2 - 1] (\ref son_scaling "docs/sonine.md"), so one species gives c = 2 a2 with the
 * van Noije-Ernst a2 of theory::sonine_a2.
 *
 * Notation (\ref son_binary "docs/sonine.md", Montanero and Garzo 2002, Sec. 3): species 1 and 2 are entries 0 and 1 of the Mixture;
 * mu = m1/m2, delta = n1/n2, w = sigma_1/sigma_2, x_i = n_i/n, mu_ij = m_i/(m_i + m_j),
 * sigma_12 = (sigma_1 + sigma_2)/2, chi_ij the pair correlation at contact of the Mixture
 * (1 dilute, Carnahan-Starling for Enskog, \ref cm_chi "docs/collision-model.md"), alpha_11, alpha_22, alpha_12 independent.
 * T/T2 = 1 + x1 (gamma - 1), T/T1 = (T/T2)/gamma (Montanero and Garzo 2002, eqs. (13)-(14), \ref son_binary "docs/sonine.md"),
 * lambda_1 = T/(T1 mu_21), lambda_2 = T/(T2 mu_12), eta = lambda_1/lambda_2 = mu_12/(mu_21 gamma).
 * Reduced rates: zeta* = zeta/(n sigma_12^2 v0) (Montanero and Garzo 2002, eq. (15), \ref son_scaling "docs/sonine.md").
 *
 * \section sonine_steps Steps (Montanero and Garzo 2002, App. A; \ref son_binary "docs/sonine.md")
 * 1. For a given gamma, the coefficients of Montanero and Garzo 2002, eqs. (39)-(44) as restated in \ref son_binary_coefficients "docs/sonine.md":
 *    zeta_i^(0), zeta_ii^(1), zeta_ij^(1), Omega_i^(0), Omega_ii^(1), Omega_ij^(1); species 2 from
 *    species 1 by interchanging 1 <-> 2 and eta -> 1/eta (Montanero and Garzo 2002, after eq. (44), \ref son_binary "docs/sonine.md").
 *    The partial cooling rate is zeta_i* = zeta_i^(0) + zeta_ii^(1) c_i + zeta_ij^(1) c_j and the
 *    collisional fourth moment
 *    sum_j int v*^4 J*_ij = Omega_i^(0) + Omega_ii^(1) c_i + Omega_ij^(1) c_j.
 * 2. The fourth-moment equations of Montanero and Garzo 2002, eq. (15), \ref son_binary_cumulants "docs/sonine.md" (multiply by v*^4 and integrate:
 *    -2 zeta_i* <v*^4>_i = Omega_i, <v*^4>_i = 15 (1 + c_i/2)/(4 lambda_i^2)), linearised in the
 *    c's, are the 2 x 2 system B c1 + D c2 = A, F c1 + G c2 = E with A..G of Montanero and Garzo 2002, eqs. (33)-(38), \ref son_binary_cumulants "docs/sonine.md",
 *    solved by Cramer's rule as in eqs 31-32.
 * 3. gamma solves zeta_1* = zeta_2* (Montanero and Garzo 2002, eq. (45), \ref son_binary_gamma "docs/sonine.md"), where each zeta_i* includes its c-terms.
 *    f(gamma) = zeta_1* - zeta_2* is tabulated on a logarithmic grid of gamma (1e-4 .. 1e4,
 *    40 points per decade); each sign change is refined with GSL's Brent solver
 *    (gsl_root_fsolver_brent) to a relative width of 1e-14. A sign change across which the
 *    determinant BG - DF of the linear system changes sign is a pole of the c's, not a root, and
 *    is skipped. Exactly one root must remain, else std::runtime_error (\ref son_binary_gamma "docs/sonine.md": one root exists
 *    for the cases of the papers).
 * 4. zeta* = sum_i x_i (T_i/T) zeta_i* (Montanero and Garzo 2002, eq. (11), \ref son_binary_gamma "docs/sonine.md"), equal to zeta_1* = zeta_2* at the root.
 * 5. Tails (Montanero and Garzo 2002, eqs. (18)-(21), (29)-(30); \ref son_tails "docs/sonine.md"):
 *    beta_i = pi sum_j x_j chi_ij (sigma_ij/sigma_12)^2,
 *    Phi_i ~ A_i exp(-(2 beta_i/zeta_i*) v*).
 *
 * The module is dimensionless: only mass ratios, diameter ratios, mole fractions, chi_ij and the
 * restitution coefficients enter; the overall number density enters only through chi_ij.
 *
 * Input checks: every function taking a Mixture throws std::invalid_argument unless it has exactly
 * 2 species with positive finite masses, diameters, number densities and chi_ij, and a symmetric
 * restitution matrix with entries in [0, 1].
 *
 * The coefficients are computed from their self (i-i) and cross (i-j) parts, sonine_self_terms and
 * sonine_cross_terms; the HCS of any number of species (theory/sonine_mixture.hpp) sums the same
 * pair terms over all partners.
 *
 * \section sonine_checks How it is checked
 * tests/sonine_test.cpp: the \ref son_binary_gamma "docs/sonine.md" reference numbers, the one-component limit (gamma = 1,
 * c = 2 a2, zeta* of \ref haff_sonine "docs/haff-and-mixtures.md"), the elastic limit, the 1 <-> 2 symmetry, zeta_i^(0) against the
 * Maxwellian partial cooling rates of \ref haff_mixture_odes "docs/haff-and-mixtures.md", the linearised fourth-moment equations, Enskog
 * densities. Eqs 39-44 as given in \ref son_binary_coefficients "docs/sonine.md" were also compared (once, outside the test suite)
 * with a Monte Carlo integration of the collision integrals of Montanero and Garzo 2002, eq. (16), \ref son_binary_cumulants "docs/sonine.md" over the Sonine
 * distributions (eq 17): all twelve coefficients agreed within 2 standard errors (relative
 * errors 1e-3 .. 2e-2) for mu = 10, delta = 2, w = 1, alpha = 0.5, gamma = 3.8 and for mu = 1/4,
 * delta = 1/2, w = 2, alpha_11 = 0.6, alpha_22 = 0.9, alpha_12 = 0.75, n* = 0.3, gamma = 0.7.
 */
#pragma once

#include <vector>

#include "model/species.hpp"

namespace gdsmc::theory {

/// HCS of a binary mixture in the first Sonine approximation (Montanero and Garzo 2002, App. A, \ref son_binary "docs/sonine.md").
struct BinaryHcs {
  double temperature_ratio;  ///< gamma = T1/T2 (root of Montanero and Garzo 2002, eq. (45), \ref son_binary_gamma "docs/sonine.md")
  double sonine_c[2];        ///< c1, c2 of Montanero and Garzo 2002, eq. (17) (= 2 a2 for one species, \ref son_scaling "docs/sonine.md")
  double cooling_rate;       ///< zeta* = zeta/(n sigma_12^2 v0), common to both species (\ref son_scaling "docs/sonine.md")
  /// beta_i = pi sum_j x_j chi_ij (sigma_ij/sigma_12)^2 (Montanero and Garzo 2002, eq. (20), \ref son_tails "docs/sonine.md")
  double tail_beta[2];
};

/// Reduced partial cooling rates zeta_i* (with their c-terms, Montanero and Garzo 2002, eq. (45), \ref son_binary_gamma "docs/sonine.md") and the c_i of the
/// linearised fourth-moment equations (Montanero and Garzo 2002, eqs. (31)-(38), \ref son_binary_cumulants "docs/sonine.md") at a given gamma.
struct SonineAtGamma {
  double zeta[2];  ///< zeta_1*, zeta_2*
  double c[2];     ///< c_1, c_2
};

/// The coefficients of Montanero and Garzo 2002, eqs. (39)-(44) (\ref son_binary_coefficients "docs/sonine.md") at a given gamma, indexed by species
/// (0 = species 1, 1 = species 2). zeta1[i][j] is zeta_ij^(1): zeta_i* = zeta0[i] + sum_j
/// zeta1[i][j] c_j; likewise omega1[i][j] = Omega_ij^(1). lambda[i] = lambda_i,
/// eta = lambda_1/lambda_2.
struct SonineCoefficients {
  double lambda[2];     ///< lambda_i = T/(T_i mu_ji)
  double eta;           ///< lambda_1/lambda_2
  double zeta0[2];      ///< zeta_i^(0)
  double zeta1[2][2];   ///< zeta_ij^(1)
  double omega0[2];     ///< Omega_i^(0)
  double omega1[2][2];  ///< Omega_ij^(1)
};

/// The collision terms of one species pair in Montanero and Garzo 2002, eqs. (39)-(44) (\ref son_binary_coefficients "docs/sonine.md"), split by partner:
/// the contribution of collisions of species i with species j (j = i: the self terms) to
/// zeta_i* = zeta0 + zeta_self c_i + zeta_partner c_j and to
/// int v*^4 J*_ij = omega0 + omega_self c_i + omega_partner c_j, in the units of a binary mixture
/// {i, j} (zeta in n sigma_ij^2 v0, v0 = sqrt(2 T (m_i + m_j)/(m_i m_j)); Omega in n sigma_ij^2 v0^5).
/// Summing the self and cross terms of species i gives the binary coefficients of
/// binary_sonine_coefficients. The s-species HCS (sonine_mixture.hpp) is built from them.
struct SonineTerms {
  double zeta0;          ///< Maxwellian part of zeta_i*
  double zeta_self;      ///< coefficient of c_i in zeta_i*
  double zeta_partner;   ///< coefficient of c_j in zeta_i*
  double omega0;         ///< Maxwellian part of the fourth moment
  double omega_self;     ///< coefficient of c_i in it
  double omega_partner;  ///< coefficient of c_j in it
};

/// The i-i terms of Montanero and Garzo 2002, eqs. (39), (40), (42), (43) (\ref son_binary_coefficients "docs/sonine.md": the terms proportional to
/// s = weight = x_i chi_ii (sigma_i/sigma_12)^2), at lambda_i. zeta_partner = omega_partner = 0.
/// No input checks.
SonineTerms sonine_self_terms(double weight, double alpha_ii, double lambda_i);

/// The i-j terms of Montanero and Garzo 2002, eqs. (39)-(44) (\ref son_binary_coefficients "docs/sonine.md": the terms proportional to c = weight =
/// x_j chi_ij), at mu_ji = m_j/(m_i + m_j), lambda_i = T/(T_i mu_ji), lambda_j = T/(T_j mu_ij);
/// eta = lambda_i/lambda_j. No input checks.
SonineTerms sonine_cross_terms(double weight, double mu_ji, double alpha_ij, double lambda_i,
                               double lambda_j);

/// Coefficients of Montanero and Garzo 2002, eqs. (39)-(44) (\ref son_binary_coefficients "docs/sonine.md") at gamma = T1/T2. Throws std::invalid_argument
/// for a bad mixture (see "Input checks" in the file description) or unless gamma is positive and
/// finite.
SonineCoefficients binary_sonine_coefficients(const species::Mixture& mix, double gamma);

/// zeta_i* and c_i at gamma = T1/T2 (Montanero and Garzo 2002, eqs. (31)-(38), \ref son_binary_cumulants "docs/sonine.md" and the two sides of eq 45). Throws
/// std::invalid_argument for a bad mixture or gamma (as binary_sonine_coefficients),
/// std::runtime_error if the linear system is singular.
SonineAtGamma binary_sonine_at_gamma(const species::Mixture& mix, double gamma);

/// Solves Montanero and Garzo 2002, eq. (45), \ref son_binary_gamma "docs/sonine.md" for gamma (see \ref sonine_steps). Throws std::invalid_argument for a bad
/// mixture (see "Input checks" in the file description), std::runtime_error if zeta_1* - zeta_2*
/// has no root or several roots in 1e-4 <= gamma <= 1e4.
BinaryHcs binary_hcs_first_sonine(const species::Mixture& mix);

/// Predicted high-velocity decay of Phi_i(v*) ~ A_i exp(-k v*): k = 2 beta_i/zeta*_i (Montanero and Garzo 2002,
/// eqs. (21), (29)-(30); \ref son_tails "docs/sonine.md"), zeta*_i = hcs.cooling_rate (equal for both species in the HCS).
/// `species` is 0 or 1 (else std::invalid_argument). Elastic mixtures (zeta* = 0) give +infinity:
/// no exponential tail.
double tail_decay_rate(const BinaryHcs& hcs, int species);


// -------------------------------------------------------------------------------------------------
// One species beyond first Sonine (docs/sonine.md "Beyond first Sonine").
// -------------------------------------------------------------------------------------------------
/**
 * \section sonine_higher One species: second (and higher) Sonine approximation
 *
 * The scaled HCS distribution of one species, c = v/sqrt(2T/m), truncated after the Sonine
 * polynomial of order K (Brilliantov and Poeschel, Europhys. Lett. 74, 424 (2006); Noskowicz,
 * Bar-Lev, Serero and Goldhirsch, Europhys. Lett. 79, 60001 (2007); Santos and Montanero, Granular
 * Matter 11, 157 (2009)):
 *   F(c) = pi^(-3/2) exp(-c^2) [1 + sum_{k=2}^{K} a_k S_k(c^2)],  S_k = L_k^(1/2) (generalised
 *   Laguerre; S_2(x) = x^2/2 - 5x/2 + 15/8, S_3(x) = -x^3/6 + 7x^2/4 - 35x/8 + 35/16).
 * Then <c^4> = (15/4)(1 + a2), <c^6> = (105/8)(1 + 3 a2 - a3), and in general
 * <c^2p> = sum_k a_k <c^2p S_k>_Maxwell. The collisional moments
 *   mu_p = -int c^p I[F, F] dc = -(1/2) int dc1 dc2 int_{g.e>0} de (g.e) F(c1) F(c2) Delta(c1^p + c2^p)
 * (collision rule of docs/collision-model.md, \ref cm_rule "docs/collision-model.md") are quadratic forms in (1, a_2, .., a_K).
 * The HCS moment equations are mu_p = (p/3) mu_2 <c^p>, p = 4, 6, .., 2K (K - 1 equations for
 * a_2..a_K). K = 2 is first Sonine, K = 3 second Sonine (a2 and a3).
 *
 * The collisional moments are computed, not transcribed: the integrand is a polynomial times
 * Gaussians, so a product Gauss rule is exact (Gauss-Hermite in the centre-of-mass velocity,
 * generalised Gauss-Laguerre in g^2/2, Gauss-Legendre in cos(theta) and the trapezoid rule in phi
 * for e, each with enough nodes for the degree; GSL gsl_integration_fixed). Checks that this
 * reproduces the published closed forms (tests/sonine_test.cpp):
 *  - mu_2 = sqrt(2 pi)(1 - alpha^2)(1 + 3 a2/16 + a3/64) to linear order (van Noije and Ernst,
 *    Granular Matter 1, 57 (1998); Brilliantov and Poeschel 2006), and
 *  - K = 2, linearised, gives exactly the van Noije-Ernst a2 of sonine_a2.
 * Closure: `linear` drops the products a_k a_l (the linearised theory of van Noije-Ernst for K = 2
 * and Brilliantov-Poeschel 2006 for K = 3); otherwise the full quadratic system is solved by Newton
 * from the linear solution (the "nonlinear" Sonine approximation).
 *
 * Values (nonlinear, this code): alpha = 0.5: K = 2 c = 2 a2 = 0.1059, K = 3 a2 = 0.04498,
 * a3 = -0.01855 (c = 0.0900), K = 4 c = 0.0979, K = 5 c = 0.0934; alpha = 0.3: K = 2 0.2438,
 * K = 3 0.1760 (a3 = -0.0647), K = 4 0.2308, K = 5 0.1810.
 * Accuracy against the exact values (DSMC without time step, many replicas; docs/sonine.md:
 * c = 0.0959 at alpha = 0.5, 0.2078 at alpha = 0.3): second Sonine is 6.2 % low at alpha = 0.5 and
 * 15.3 % low at alpha = 0.3 (first Sonine, linear: 9.4 % and 13.6 % high). Successive orders
 * alternate around the exact value (K = 2..5 at both alphas), so orders K and K + 1 bracket it;
 * sonine_cumulant_bracket uses K = 4 and 5: midpoint 0.3 % (alpha = 0.5) and 0.9 % (alpha = 0.3)
 * from the exact values, half-widths 2.4 % and 12 %.
 */
struct OneSpeciesSonine {
  int order;                 ///< K: highest Sonine polynomial kept
  std::vector<double> a;     ///< a_2 .. a_K (a[0] = a2, a[1] = a3, ...)
  double cumulant_c;         ///< c = 2 a2 (the sonine_c convention of this file, \ref son_scaling "docs/sonine.md")
  double cooling_factor;     ///< mu_2 / (sqrt(2 pi)(1 - alpha^2)): zeta/zeta_Maxwell (1 + 3 a2/16 + ..)
  /// Collision frequency over its Maxwellian value, <|g|>_F/<|g|>_Maxwell (1 - a2/16 + .., van Noije
  /// and Ernst 1998), with the same closure (products of the a_k dropped when `linear`).
  double collision_factor;
};

/// The HCS of one species in the Sonine approximation of order K = `order` (2 <= K <= 6), see
/// \ref sonine_higher. Throws std::invalid_argument unless 0 <= alpha < 1 and 2 <= order <= 6,
/// std::runtime_error if Newton fails. Cost grows as K^5 (K = 3: ~0.1 s, K = 5: ~2 s).
OneSpeciesSonine one_species_hcs_sonine(double alpha, int order, bool linear = false);

/// Second Sonine (K = 3, nonlinear; Brilliantov and Poeschel 2006): a2 and a3.
inline OneSpeciesSonine second_sonine(double alpha) { return one_species_hcs_sonine(alpha, 3); }

/// The collisional moment mu_p (p = 2, 4, .., 2K) of the truncated distribution with coefficients
/// a = {a_2, .., a_K} (K = a.size() + 1), in the units of \ref sonine_higher (mu_2 of a Maxwellian
/// is sqrt(2 pi)(1 - alpha^2)). For tests.
double sonine_collision_moment(double alpha, int p, const std::vector<double>& a);

/// The cumulant c = 2 a2 of one species as the bracket of the Sonine approximations of order 4 and
/// 5 (\ref sonine_higher): value = their midpoint, half_width = half their difference; likewise the
/// cooling-rate factor zeta/zeta_Maxwell = mu_2/(sqrt(2 pi)(1 - alpha^2)).
struct CumulantBracket {
  double value;               ///< c, midpoint of orders 4 and 5
  double half_width;          ///< half their difference
  double cooling_factor;      ///< zeta/zeta_Maxwell, midpoint
  double cooling_half_width;  ///< half the difference of the cooling factors
};
/// The CumulantBracket at restitution `alpha`.
CumulantBracket sonine_cumulant_bracket(double alpha);

}  // namespace gdsmc::theory
