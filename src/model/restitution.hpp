/**
 * \file restitution.hpp
 * \brief The coefficient of normal restitution: constant, or viscoelastic (impact-speed dependent).
 *
 * **Viscoelastic spheres** (Bodrova and Osinsky 2024, eqs. (5)-(8), corrected in \ref visco_series "docs/viscoelastic.md"). For a pair (k, i) with
 * normal impact speed |g.e|,
 *   alpha_ki = 1 + sum_{j=1}^{20} h_j u^j,   u = beta_ki^(1/2) |g.e|^(1/10),   beta_ki = A kappa_ki^(2/5),
 * with the h_j of \ref visco_series "docs/viscoelastic.md" (h_2 = -C_1, h_4 = 3 C_1^2/5, h_5 = 4/15, C_1 = 1.1534488580952888).
 * The series matches the contact model (force-zero end of the collision) to 3e-7 at u = 0.65 and
 * 1.1e-4 at u = 0.8, and diverges beyond u ~ 1.05: it is used up to u_max = 0.8 and refused above
 * (std::domain_error), so a negative alpha is never returned (\ref visco_cutoff "docs/viscoelastic.md").
 *
 * **One material** (\ref visco_one_material "docs/viscoelastic.md", Bodrova and Osinsky 2024, eqs. (7)-(8)): beta_ki / beta_11 =
 * [sqrt(sigma_eff,ki / sigma_eff,11) m_11 / m_ki]^(2/5), sigma_eff,ki = sigma_k sigma_i/(sigma_k + sigma_i)
 * (not the contact distance), m the reduced mass. The namelist's `visco_a_kappa` is beta_11.
 *
 * Units: |g.e| in the user's velocity unit; beta in (velocity)^(-1/5). Used by collide (the rule)
 * and theory (A3, A4 of Bodrova and Osinsky 2024). Checked by tests/diffusion_test.cpp and tests/restitution_test.cpp.
 */
#pragma once

#include <array>
#include <cmath>

#include "model/species.hpp"

namespace gdsmc::restitution {

inline constexpr int series_terms = 20;                     ///< \ref visco_series "docs/viscoelastic.md"
inline constexpr double series_c1 = 1.1534488580952888;     ///< C_1, h_2 = -C_1
inline constexpr double u_max = 0.8;                        ///< largest u the series is used at

/// h_j, index j = 1..20 (entry 0 unused), \ref visco_series "docs/viscoelastic.md".
// clang-format off
inline constexpr std::array<double, series_terms + 1> h = {
    0.0,
    0.0,        -series_c1,  0.0,        3.0 * series_c1 * series_c1 / 5.0, 4.0 / 15.0,
    -0.5228826, -0.4613795,  0.3487427,  0.4523511,  -0.1464315,
    -0.3677283, -0.0432490,  0.2818042,  0.1478526,  -0.1794421,
    -0.1784660, 0.0659336,   0.1713586,  0.0252498,  -0.1379235};  // h_1 .. h_20
// clang-format on

/// The series in u (\ref visco_series "docs/viscoelastic.md"), for 0 <= u <= u_max (not checked here: the hot path).
inline double series(double u) {
  double sum = 0.0;
  for (int j = series_terms; j >= 1; --j) sum = (sum + h[j]) * u;  // Horner
  return 1.0 + sum;
}

/// alpha for beta_ki and the normal relative speed g.e (sign irrelevant). Throws std::domain_error
/// if beta < 0, an argument is not finite, or u > u_max.
double viscoelastic(double beta_ki, double normal_speed);

/// beta_ki of one material from beta_11 (\ref visco_one_material "docs/viscoelastic.md"). Throws std::invalid_argument if beta_11 < 0.
species::PairMatrix one_material_beta(const species::Mixture& mix, double beta_11);

}  // namespace gdsmc::restitution
