/**
 * \file diffusion.hpp
 * \brief Self-diffusion in a homogeneously cooling granular mixture: viscoelastic restitution,
 *        velocity correlation times, diffusion coefficients, partial temperatures with
 *        viscoelastic restitution and the mean squared displacement (MSD) of each species.
 *
 * \section diffusion_intro What this module computes
 *
 * The theory of Bodrova and Osinsky 2024 (eqs. (5)-(8), (16)-(24) and Appendix A1-A4) in the corrected
 * form of \ref dif_correlation_time "docs/diffusion-msd.md", \ref visco_series "docs/viscoelastic.md". Notation as in theory.hpp and \ref cm_notation "docs/collision-model.md": s_ki = T_k/m_k + T_i/m_i,
 * sigma_ki = (sigma_k + sigma_i)/2, mu_ik = m_i/(m_i + m_k), chi_ki the pair correlation at contact
 * (Bodrova and Osinsky 2024's g_2(sigma_ki)), X_ki = (T_k m_i + T_i m_k)/(T_k (m_i + m_k)) (not symmetric).
 * Every species is Maxwellian with its own partial temperature T_k (as in theory.hpp).
 *
 * \subsection diffusion_visco Viscoelastic restitution (\ref visco_series "docs/viscoelastic.md"; Bodrova and Osinsky 2024, eqs. (5)-(8))
 * alpha_ki(g.e) = 1 + sum_{j=1}^{20} h_j u^j, u = beta_ki^(1/2) |g.e|^(1/10), with the h_j of
 * \ref visco_series "docs/viscoelastic.md" (h_2 = -C_1, C_1 = 1.1534488580952888, h_4 = C_2 = 3 C_1^2/5 and h_5 = 4/15 are used
 * at full precision, the others as listed). The series is that of the viscoelastic (Hertz plus
 * dissipative) contact x'' + x^(3/2) + u^2 x^(1/2) x' = 0, x(0) = 0, x'(0) = 1, which ends when
 * the contact force vanishes (x + u^2 x' = 0) with alpha = -x'(end). Integrating that contact
 * (tests/diffusion_test.cpp does so up to u = 0.8) the series is off by 3.1e-7 at u = 0.65,
 * 1.1e-4 at u = 0.8, 2.2e-3 at u = 0.9 and 2.7e-2 at u = 1 (it diverges beyond u about 1.05).
 * Cut-off: viscoelastic_u_max = 0.8; above it viscoelastic_restitution throws std::domain_error
 * instead of returning an untrusted (possibly negative) alpha.
 * beta_ki = A kappa_ki^(2/5) carries units of (velocity)^(-1/5). One material (\ref visco_one_material "docs/viscoelastic.md";
 * Bodrova and Osinsky 2024, eqs. (7)-(8)): beta_ki/beta_11 = [sqrt(sigma_eff,ki/sigma_eff,11) m_11/m_ki]^(2/5) with
 * sigma_eff,ki = sigma_i sigma_k/(sigma_i + sigma_k) (not the contact distance) and m_ki the
 * reduced mass. Convention: the seed's "A kappa^(2/5) = 0.09" is beta_11 = 0.09 for the pair of
 * species 1 (index 0); callers record that convention in their output.
 *
 * \subsection diffusion_rates Correlation times and cooling rates (\ref visco_averaged "docs/viscoelastic.md"; Bodrova and Osinsky 2024 A1-A4)
 * base_ki = (8 sqrt(2 pi)/3) n_i sigma_ki^2 chi_ki mu_ik sqrt(s_ki), with n_i the density of the
 * partner species i and mu_ik = m_i/(m_i + m_k) the partner's mass fraction.
 * - A1, constant alpha: tau_v,ki^-1 = base_ki X_ki (1 + alpha_ki)^2/4. This is nu_ki - xi_ki/2,
 *   with nu_ki = base_ki (1 + alpha_ki)/2 the momentum relaxation rate of a k particle drifting
 *   through Maxwellian i particles and xi_ki the cooling rate (A2); \ref dif_correlation_time "docs/diffusion-msd.md": keep
 *   (1 + alpha)^2/4.
 * - A2 = \ref haff_mixture_odes "docs/haff-and-mixtures.md": xi_ki = base_ki (1 + alpha_ki) [1 - (1/2)(1 + alpha_ki) X_ki], which is
 *   theory::cooling_rate_matrix.
 * - A3, viscoelastic: tau_v,ki^-1 = base_ki X_ki (1 + (1/2) sum_{n=1}^{40} A_n B_n).
 * - A4, viscoelastic: xi_ki = 2 base_ki [1 - X_ki + sum_n B_n (h_n - (1/2) X_ki A_n)]
 *   (n runs to 40, with h_n = 0 for n > 20).
 * - A_n = 4 h_n + sum_{j+l=n; 1<=j,l<=20} h_j h_l, B_n = (1/2) Gamma(2 + n/20) beta_ki^(n/2)
 *   (2 s_ki)^(n/20) (\ref dif_correlation_time "docs/diffusion-msd.md"; equal to the printed (20 + n) n Gamma(n/20)/800 form).
 * A3 and A4 are A1 and A2 averaged term by term over the restitution series with the weight
 * g_n^3 exp(-g_n^2/(2 s_ki)) of the normal relative speed g_n (then B_n = <u^n>/2):
 * tau_v,ki^-1 = base_ki X_ki <(1 + alpha)^2>/4 and
 * xi_ki = base_ki [<1 + alpha> - (1/2) X_ki <(1 + alpha)^2>]; tests/diffusion_test.cpp checks this
 * against quadrature of viscoelastic_restitution. With beta = 0 they are A1 and A2 at alpha = 1
 * (for a mixture A4 then keeps the elastic energy exchange 2 base_ki (1 - X_ki)).
 * Cut-off of the averaged series: the typical u of a pair, u_ki = beta_ki^(1/2) (2 s_ki)^(1/20)
 * (B_n = Gamma(2 + n/20) u_ki^n/2), must not exceed viscoelastic_u_max, else std::domain_error.
 * Collisions in the Maxwellian tail beyond the cut-off enter through the term-by-term average;
 * their share is negligible for u_ki well below the cut-off (0.32 for beta = 0.09, T = m = 1).
 * With viscoelastic restitution Mixture::restitution is ignored.
 *
 * \subsection diffusion_coefficients Diffusion coefficients (Bodrova and Osinsky 2024, eqs. (19)-(20); \ref dif_coefficients "docs/diffusion-msd.md")
 * D_k = T_k tau_v,k/m_k with tau_v,k^-1 = sum_i tau_v,ki^-1. One species, constant alpha:
 * D = 3/(2 (1 + alpha)^2 n sigma^2 chi) sqrt(T/(pi m)) (Brilliantov and Poeschel; alpha = 1 gives
 * the Chapman-Enskog 3/(8 n sigma^2) sqrt(T/(pi m))).
 *
 * \subsection diffusion_msd Mean squared displacement (Bodrova and Osinsky 2024, eqs. (16)-(18), (21); \ref dif_msd "docs/diffusion-msd.md")
 * <R_k^2(t)> = 6 int_0^t dt1 D_k(t1) [1 - exp(-(tau_k(t) - tau_k(t1))/tauhat_v,k(t1))]  (eq 17)
 * with tauhat_v,k(t) = tau_v,k(t) sqrt(T_k(t)/T_k(0)) (eq 18) and, as \ref dif_correlation_time "docs/diffusion-msd.md" defines it,
 * tau_k(t) = int_0^t sqrt(T_k(t')/T_k(0)) dt'. <R^2> = (1/n) sum_k n_k <R_k^2> (eq 16).
 * Long-time form (eq 21): <R_k^2> = 6 int_0^t D_k(t1) dt1.
 * Properties (checked in tests/diffusion_test.cpp):
 * - t << tau_v,k: <R_k^2> = 3 T_k(0) t^2/m_k (ballistic).
 * - Constant temperatures (elastic, one species):
 *   <R_k^2> = 6 D_k t - 6 D_k tau_v,k (1 - exp(-t/tau_v,k)) (Ornstein-Uhlenbeck).
 * - One species, constant alpha (Haff, T = T0/(1 + t/t0)^2, t0 = 2/zeta_0, \ref haff_law "docs/haff-and-mixtures.md"), exactly:
 *   <R^2> = 6 D0 t0 ln(1 + t/t0) - 6 D0 tau_v0 [1 - (1 + t/t0)^(-t0/tau_v0)], so the logarithmic
 *   law 6 D0 tau0 ln(1 + t/tau0) of \ref dif_msd "docs/diffusion-msd.md" holds with tau0 = t0 = 2/zeta_0 (the Haff time), up
 *   to the constant -6 D0 tau_v0; eq 21 gives 6 D0 t0 ln(1 + t/t0) exactly. A mixture started at
 *   the asymptotic temperature ratios follows the same form species by species (common t0).
 * Eq 17 is the adiabatic form of the velocity autocorrelation integral (the correlation decays
 * with the correlation time frozen at t1); it is implemented as printed, not replaced by the
 * exact double integral.
 *
 * \subsection diffusion_numerics Numerics of the MSD
 * T_k(t) comes from CVODE (integrate_partial_temperatures for constant alpha, or
 * integrate_partial_temperatures_viscoelastic) on a node grid uniform in s = ln(1 + t/t_c), 64
 * nodes per unit of s, t_c = 1/max_k (tau_v,k^-1 + sum_i |xi_ki|) at t = 0: every rate of the
 * problem scales like 1/(t_c + t), so this grid resolves the transient and the power-law regime
 * alike. Between nodes ln T_k(t) is a cubic Hermite interpolant (node values from CVODE, slopes
 * -sum_i xi_ki from the rate formulas). tau_k at the nodes is accumulated with GSL quadrature
 * (gsl_integration_qag, 15-point Gauss-Kronrod, rtol 1e-12) of sqrt(T_k/T_k(0)) over each interval
 * of the interpolant, and interpolated between nodes by cubic Hermite (slope sqrt(T_k/T_k(0))).
 * The t1 integrals of eqs 17 and 21 use gsl_integration_qag (21-point rule, rtol 1e-10) on pieces
 * of [0, t] bounded by every 32nd node, 1 - exp(-x) evaluated as -expm1(-x) so that the ballistic
 * regime keeps full precision. Measured against the closed forms above: relative error below 1e-8.
 * The GSL error handler is switched off (and restored) around these calls; a failed quadrature
 * throws std::runtime_error. Not thread-safe for that reason (GSL's handler is global).
 *
 * \subsection diffusion_units Units
 * Consistent user units, k_B = 1 (T is an energy), as in theory.hpp.
 */
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "model/restitution.hpp"
#include "model/species.hpp"
#include "theory/theory.hpp"

namespace gdsmc::theory {

// ---------------------------------------------------------------------------------------------
// Viscoelastic restitution (\ref visco_series "docs/viscoelastic.md"; Bodrova and Osinsky 2024, eqs. (5)-(8))
// ---------------------------------------------------------------------------------------------

// The series itself lives in model/restitution.hpp (the collision rule uses it); these names keep
// the theory's vocabulary.
inline constexpr int restitution_series_terms = restitution::series_terms;  ///< terms h_1..h_20 of the series
inline constexpr double restitution_c1 = restitution::series_c1;          ///< C_1, h_2 = -C_1
inline constexpr double viscoelastic_u_max = restitution::u_max;          ///< largest u the series is used for

/// h_j of \ref visco_series "docs/viscoelastic.md", j = 1..20. Throws std::out_of_range for other j.
double restitution_series_coefficient(int j);

/// A_n = 4 h_n + sum_{j+l=n} h_j h_l, n = 1..40 (\ref visco_averaged "docs/viscoelastic.md"). Throws std::out_of_range otherwise.
double restitution_series_square_coefficient(int n);

/// \ref visco_series "docs/viscoelastic.md" / Bodrova and Osinsky 2024, eq. (5) (restitution::viscoelastic).
inline double viscoelastic_restitution(double beta_ki, double normal_speed) {
  return restitution::viscoelastic(beta_ki, normal_speed);
}

/// One-material beta_ki (\ref visco_one_material "docs/viscoelastic.md"; restitution::one_material_beta).
inline PairMatrix viscoelastic_beta(const Mixture& mix, double beta_11) {
  return restitution::one_material_beta(mix, beta_11);
}

// ---------------------------------------------------------------------------------------------
// Velocity correlation times and cooling rates (\ref dif_correlation_time "docs/diffusion-msd.md"; Bodrova and Osinsky 2024, App. A)
// temperature[k] = T_k; beta is an S x S matrix of beta_ki >= 0 (viscoelastic_beta)
// ---------------------------------------------------------------------------------------------

/// \ref dif_correlation_time "docs/diffusion-msd.md": base_ki = (8 sqrt(2 pi)/3) n_i sigma_ki^2 chi_ki mu_ik sqrt(s_ki), row k, column i.
PairMatrix velocity_correlation_base_rate(const Mixture& mix,
                                          const std::vector<double>& temperature);

/// A1 (\ref dif_correlation_time "docs/diffusion-msd.md"): tau_v,ki^-1 = base_ki X_ki (1 + alpha_ki)^2/4, constant restitution.
PairMatrix inverse_velocity_correlation_time(const Mixture& mix,
                                             const std::vector<double>& temperature);

/// A3 (\ref visco_averaged "docs/viscoelastic.md"): tau_v,ki^-1 = base_ki X_ki (1 + (1/2) sum_n A_n B_n). Throws std::domain_error
/// if a pair's typical u exceeds viscoelastic_u_max (\ref diffusion_rates).
PairMatrix inverse_velocity_correlation_time_viscoelastic(const Mixture& mix,
                                                          const PairMatrix& beta,
                                                          const std::vector<double>& temperature);

/// A4 (\ref visco_averaged "docs/viscoelastic.md"): xi_ki = 2 base_ki [1 - X_ki + sum_n B_n (h_n - (1/2) X_ki A_n)], such that
/// dT_k/dt = -T_k sum_i xi_ki. Throws std::domain_error like A3.
PairMatrix cooling_rate_matrix_viscoelastic(const Mixture& mix, const PairMatrix& beta,
                                            const std::vector<double>& temperature);

/// Bodrova and Osinsky 2024, eqs. (19)-(20), \ref dif_coefficients "docs/diffusion-msd.md": D_k = T_k tau_v,k/m_k, tau_v,k^-1 = sum_i tau_v,ki^-1, from A1 or, when
/// `beta` is given, from A3.
std::vector<double> diffusion_coefficients(const Mixture& mix,
                                           const std::vector<double>& temperature,
                                           const PairMatrix* beta = nullptr);

/// D_k/D_1 (entry 0 is 1) at the given temperatures, A1 or (with beta) A3.
std::vector<double> diffusion_coefficient_ratio(const Mixture& mix,
                                                const std::vector<double>& temperature,
                                                const PairMatrix* beta = nullptr);

/**
 * D_k/D_1 at long times for constant restitution (the JSON key `diffusion_coefficient_ratio`,
 * Bodrova and Osinsky 2024, Figs. 4, 5, 7; \ref dif_coefficients "docs/diffusion-msd.md"): D_k is homogeneous of degree 1/2 in the temperatures, so once T_k/T_1 has
 * settled (asymptotic_temperature_ratios, \ref haff_ratios "docs/haff-and-mixtures.md") the ratio is constant. With viscoelastic
 * restitution there is no such constant: the mixture drifts towards equipartition and the elastic
 * limit as T -> 0 (Bodrova and Osinsky 2024, Sec. III, \ref dif_limits "docs/diffusion-msd.md"); use the overload above at the temperatures of interest.
 */
std::vector<double> diffusion_coefficient_ratio(const Mixture& mix);

// ---------------------------------------------------------------------------------------------
// Accuracy of the first approximation: Chapman-Enskog second approximation for tracer diffusion of
// elastic hard spheres (Chapman and Cowling, ch. 9-10; \ref dif_second_approximation "docs/diffusion-msd.md")
// ---------------------------------------------------------------------------------------------

/**
 * Sonine matrix elements of the tracer (Lorentz-Boltzmann) collision operator for a tracer of mass
 * m_t among Maxwellian partners of mass m_p, elastic hard spheres, equal temperatures
 * (\ref dif_second_approximation "docs/diffusion-msd.md"): a_pq = <psi_p (-L) psi_q>/(pi sigma^2 n_p <g^3>),
 * psi_p = v_x S_p(m_t v^2/(2T)), S_0 = 1, S_1 = 5/2 - m_t v^2/(2T). With M = m_p/(m_t + m_p):
 * a_00 = M^2/3, a_01 = -M^3/6, a_11 = M^2 (27 M^2 - 44 M + 30)/12.
 */
struct TracerSonineMatrix {
  double a00 = 0.0;  ///< <psi_0 (-L) psi_0>, reduced
  double a01 = 0.0;  ///< <psi_0 (-L) psi_1>, reduced
  double a11 = 0.0;  ///< <psi_1 (-L) psi_1>, reduced
};

/// The reduced matrix elements of TracerSonineMatrix for tracer mass m_tracer and partner mass
/// m_partner (\ref dif_second_approximation "docs/diffusion-msd.md"). Throws std::invalid_argument
/// unless both masses are positive and finite.
TracerSonineMatrix tracer_sonine_matrix(double m_tracer, double m_partner);

/**
 * [D_k]_2/[D_k]_1 = 1/(1 - Delta_k) for a tagged particle of each species k of `mix` (Chapman and
 * Cowling's second approximation to the tracer diffusion coefficient, elastic hard spheres, every
 * species at one temperature; \ref dif_second_approximation "docs/diffusion-msd.md"): the matrix
 * elements are summed over the partner species i (the tagged particle's own species included) with
 * the weights n_i sigma_ki^2 chi_ki mu_ki^(-3/2) (mu_ki the reduced mass), and
 * Delta_k = A_01^2/(A_00 A_11). Limits: equal masses and sizes 59/58 (self-diffusion), a light tracer
 * among heavy partners 13/12 (Lorentz gas; exact 32/(9 pi)), a heavy tracer 1 (Rayleigh gas).
 * Restitution and temperatures of `mix` are not used: it is the elastic estimate of the error of the
 * first approximation (Bodrova and Osinsky 2024, eq. (19) at alpha = 1).
 */
std::vector<double> tracer_diffusion_second_approximation_ratio(const Mixture& mix);

/**
 * Sonine matrix of the inelastic tracer (Boltzmann-Lorentz) collision operator, per unit
 * n_p sigma_tp^2 chi_tp, for a tracer of mass m_tracer and temperature t_tracer among Maxwellian
 * partners of mass m_partner and temperature t_partner, constant restitution alpha
 * (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md"): with c^2 = m_t v^2/(2 T_t) and the Sonine
 * polynomials S_0 = 1, S_1 = 5/2 - c^2, S_2 = c^4/2 - 7 c^2/2 + 35/8,
 * l[p][q] = -<v S_p(c^2) . L[f_M v S_q]>/(n_t 2 T_t/m_t): row p the test function v S_p, column q the
 * component v S_q; `cooling` is the partner's share xi_tp of the tracer's cooling rate. Computed by
 * quadrature, exact for the polynomial parts (no closed form is used), so it also checks A1 and A2
 * independently: l[0][0] = (3/2) nu_tp and `cooling` = xi_tp (\ref dif_correlation_time "docs/diffusion-msd.md").
 */
struct InelasticTracerSonine {
  static constexpr int terms = 3;  ///< Sonine functions v S_0, v S_1, v S_2
  double l[terms][terms] = {};     ///< the reduced matrix elements, row p, column q
  double cooling = 0.0;            ///< xi_tp, the partner's share of the tracer's cooling rate
};

/// The elements of InelasticTracerSonine. Throws std::invalid_argument unless masses and
/// temperatures are positive and finite and alpha lies in [0, 1].
InelasticTracerSonine inelastic_tracer_sonine_matrix(double m_tracer, double t_tracer, double m_partner,
                                                     double t_partner, double alpha);

/**
 * Z_pq of the cooling term (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md"): the
 * -zeta T d/dT of the Chapman-Enskog equation acting on the component v S_q of the normal solution
 * (which scales as T^-2 at fixed v), projected on v S_p and divided by n 2T/m: zeta Z_pq, with
 * Z = ((-3/4, 0, 0), (15/4, -45/8, 0), (0, 105/8, -525/32)). Throws std::out_of_range unless p, q are in 0..2.
 */
double tracer_sonine_cooling_matrix(int p, int q);

/**
 * D_k[terms]/D_k[1]: the tracer diffusion coefficient of a tagged particle of each species k of `mix`
 * in the Sonine approximation with `terms` functions (1, 2 or 3) over the first Sonine
 * (Maxwellian) one, in the homogeneous cooling state at the given partial temperatures (constant
 * restitution; the tagged particle's own species among its partners; every species Maxwellian;
 * \ref dif_second_sonine_inelastic "docs/diffusion-msd.md"). The first Sonine value is Bodrova and
 * Osinsky 2024, eq. (19) with A1; the ratios estimate eq. (19)'s inelastic error independently of any
 * DSMC. At alpha = 1, equal temperatures and terms = 2 it equals
 * tracer_diffusion_second_approximation_ratio. A species whose truncated Sonine system has no positive
 * solution (a heavy, dilute tracer whose higher modes relax more slowly than the gas cools) gets NaN for
 * terms >= 2. Throws std::invalid_argument for a species without partners or terms outside 1..3.
 */
std::vector<double> tracer_diffusion_sonine_ratio(const Mixture& mix, const std::vector<double>& temperature,
                                                  int terms);

/// tracer_diffusion_sonine_ratio for terms = 1, 2, 3 at once (entry N - 1), from one set of matrix
/// elements (S^2 quadratures of a few ms each).
std::array<std::vector<double>, 3> tracer_diffusion_sonine_ratios(const Mixture& mix,
                                                                  const std::vector<double>& temperature);

/**
 * Tail of the Sonine series beyond three functions, in units of the last increment
 * D[3] - D[2], in the case where it converges slowest and the converged value is known: the
 * Lorentz gas, (32/(9 pi) - 425/384)/(425/384 - 13/12) = 1.0666
 * (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md"; tests/diffusion_test.cpp computes the
 * three approximants by hand). The validation's allowance for the first Sonine value is
 * |D[3]/D[1] - 1| + sonine_tail_factor |D[3] - D[2]|/D[1].
 */
inline constexpr double sonine_tail_factor = (32.0 / (9.0 * 3.14159265358979323846) - 425.0 / 384.0) /
                                             (425.0 / 384.0 - 13.0 / 12.0);

// ---------------------------------------------------------------------------------------------
// Partial temperatures with viscoelastic restitution (Bodrova and Osinsky 2024, eqs. (22)-(23), \ref visco_averaged "docs/viscoelastic.md" with A4)
// ---------------------------------------------------------------------------------------------

/**
 * Integrates dT_k/dt = -T_k sum_i xi_ki with xi from A4 by CVODE, as integrate_partial_temperatures
 * does for constant restitution (BDF, dense Newton, state ln(T_k/T_ref), T_ref = sum_k x_k T_k(0),
 * absolute tolerance 1e-11 on ln T_k; collisions per unit volume with rtol 1e-10). Reports at
 * `times` (non-negative, strictly increasing). Throws std::invalid_argument for bad input and
 * std::runtime_error naming the failing SUNDIALS call (a std::domain_error of A4 in the right-hand
 * side is quoted in that message).
 */
TemperatureHistory integrate_partial_temperatures_viscoelastic(
    const Mixture& mix, const PairMatrix& beta, const std::vector<double>& initial_temperature,
    const std::vector<double>& times);

// ---------------------------------------------------------------------------------------------
// Mean squared displacement (Bodrova and Osinsky 2024, eqs. (16)-(18), (21); \ref dif_msd "docs/diffusion-msd.md")
// ---------------------------------------------------------------------------------------------

/// Partial and total MSDs at the requested times.
struct MsdResult {
  std::vector<double> time;              ///< the requested times
  std::vector<std::vector<double>> msd;  ///< [time][species] <R_k^2(t)>
  std::vector<double> total;             ///< eq 16: (1/n) sum_k n_k <R_k^2(t)>
};

/**
 * Eq 17 (with eq 16 for `total`) from T_k(0) = initial_temperature[k] at `times` (non-negative,
 * strictly increasing; times[0] may be 0). Constant restitution (A1, A2) unless `beta` is given
 * (A3, A4). Numerics: \ref diffusion_numerics. Throws std::invalid_argument for bad input,
 * std::domain_error beyond the viscoelastic cut-off, std::runtime_error if CVODE or GSL fails.
 */
MsdResult mean_squared_displacement(const Mixture& mix,
                                    const std::vector<double>& initial_temperature,
                                    const std::vector<double>& times,
                                    const PairMatrix* beta = nullptr);

/// Eq 21, the long-time form 6 int_0^t D_k(t1) dt1 (and eq 16), same arguments and numerics as
/// mean_squared_displacement. It exceeds eq 17 by 6 int_0^t D_k(t1) exp(...) dt1 > 0, which tends
/// to the constant 6 D0 tau_v0 for one species with constant restitution.
MsdResult long_time_msd(const Mixture& mix, const std::vector<double>& initial_temperature,
                        const std::vector<double>& times, const PairMatrix* beta = nullptr);

}  // namespace gdsmc::theory
