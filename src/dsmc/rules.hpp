/**
 * \file rules.hpp
 * \brief Collision rules: what a collision does to two particles, apart from the loops that sample
 *        which pairs collide (collide.hpp, agg_frag.hpp).
 *
 * A rule is a type (HOOMD's evaluator to its pair loop) that owns the constants of each species pair
 * and computes one collision: the post-collision velocities, the energy lost and the momentum
 * exchanged. The loops take it as a template parameter (no virtual call per collision) and own
 * everything else: the candidates, the bounds, the blocks, the frame, the look-ahead, the counts.
 *
 * **The contact** (\ref cm_hemisphere "docs/collision-model.md"). A loop hands the rule an accepted candidate's
 * unit vector e along the line of centres (drawn with density proportional to g_hat.e on the
 * hemisphere g.e > 0), g.e of the actual relative velocity g = v_a - v_b, and the direction d along
 * which the *stored* velocities change: e itself, or G^-1 e when the velocities are stored in a frame
 * V = G u (collide.hpp, "Frame").
 *
 * **SmoothRule**: smooth inelastic hard spheres with constant normal restitution alpha_kj
 * (\ref cm_rule "docs/collision-model.md"; Bodrova and Osinsky 2024, eq. (3), Montanero and Garzo 2002, eqs. (23)-(24)):
 *   v_a' = v_a - mu_jk (1 + alpha_kj) (g.e) e,   v_b' = v_b + mu_kj (1 + alpha_kj) (g.e) e,
 * mu_jk = m_j/(m_k + m_j) for a of species k and b of species j. Momentum is conserved,
 * (g'.e) = -alpha (g.e), and the energy lost is (1 - alpha^2) m_kj (g.e)^2 / 2 (\ref cm_energy "docs/collision-model.md").
 * This is the one place the code states it. Its option `collide_projected` takes p = (g.e) e instead
 * of e (collide.hpp's hemisphere_projection forms p without a root or a division): the block kernels
 * use it. A rule without the option (`has_projection` false) runs the kernels' general path instead.
 *
 * **ViscoelasticRule**: the same update with alpha_kj(|g.e|) of viscoelastic spheres
 * (Bodrova and Osinsky 2024, eqs. (5)-(8); \ref visco_series "docs/viscoelastic.md"; model/restitution.hpp), from
 * beta_kj. It has no projection (alpha needs |g.e|) and no frame (the thermostat and shear flow run
 * constant restitution).
 *
 * **Adding a rule** (docs/extending.md, \ref ext_rule "a new collision rule"): a type with `Pair`, `pair(k, j)`,
 * `attach(sys)` (its per-particle arrays beyond the velocity, an angular velocity say: arrays of
 * particles::System, which every loop, remix and checkpoint handles without naming them),
 * `collide(sys, a, b, pair, contact)` returning an Outcome, `measure(sys, rows)` (its observables, a
 * rotational temperature say), the flags `has_projection` and `frames`, and `largest_loss_fraction()`; one more alternative in `Rule` below; the namelist fields that choose
 * it (io/config) and the line of run/model.cpp that builds it.
 *
 * Units: the user's. Checked by tests/collide_test.cpp (Rules.*: momentum, the normal velocity
 * reversed with alpha, the energy loss against hand-computed values, the projected form against the
 * general one) and by every validation (the rule is what the theory describes).
 */
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <variant>
#include <vector>

#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/sample.hpp"
#include "model/restitution.hpp"
#include "model/species.hpp"

namespace gdsmc::rules {

/// The line of centres of an accepted candidate, as a loop hands it to a rule (header, "The contact").
struct Contact {
  double ex;       ///< e, the unit vector from b to a at contact (actual velocities' frame): x
  double ey;       ///< e: y
  double ez;       ///< e: z
  double g_dot_e;  ///< g.e > 0 of the actual relative velocity g = v_a - v_b
  double dx;       ///< the direction along which the stored velocities change (e, or G^-1 e in a frame): x
  double dy;       ///< that direction: y
  double dz;       ///< that direction: z
};

/// e with density proportional to (g_hat.e) on the hemisphere g.e > 0 (\ref cm_hemisphere "docs/collision-model.md"), the direction of
/// a collision of relative velocity g (|g| = g): e = (g_hat + w)/|g_hat + w|, w uniform on the
/// sphere, has exactly that density (the ray from the origin meets the sphere |p - g_hat| = 1 at
/// distance 2 cos(theta), with area element 4 cos(theta) dOmega). Returns false for w = -g_hat
/// exactly (probability zero). Shared by the schemes (collide.hpp) and by agg_frag.
template <class Gen>
inline bool hemisphere_normal(Gen& gen, double gx, double gy, double gz, double g, double& ex, double& ey,
                              double& ez) {
  double wx, wy, wz;
  rng::unit_vector(gen, wx, wy, wz);
  const double inv_g = 1.0 / g;
  ex = gx * inv_g + wx;
  ey = gy * inv_g + wy;
  ez = gz * inv_g + wz;
  const double norm2 = ex * ex + ey * ey + ez * ez;
  if (norm2 == 0.0) return false;
  const double inv_norm = 1.0 / std::sqrt(norm2);
  ex *= inv_norm;
  ey *= inv_norm;
  ez *= inv_norm;
  return true;
}

/// (g.e) e for e drawn as hemisphere_normal draws it, without forming e (\ref cm_hemisphere "docs/collision-model.md"):
/// with w uniform on the sphere and e = (g_hat + w)/|g_hat + w|, (g.e) e = (g + g w)/2 exactly
/// (g = |g|), which needs neither a root nor a division. Sets p to it and returns (g.e)^2 = g.p,
/// which is 0 only for w = -g_hat (probability zero: no collision, as hemisphere_normal's false).
template <class Gen>
inline double hemisphere_projection(Gen& gen, double gx, double gy, double gz, double g, double& px, double& py,
                                    double& pz) {
  double wx, wy, wz;
  rng::unit_vector_32(gen, wx, wy, wz);
  px = 0.5 * (gx + g * wx);
  py = 0.5 * (gy + g * wy);
  pz = 0.5 * (gz + g * wz);
  return gx * px + gy * py + gz * pz;
}

/// What one collision did, beside the velocities.
struct Outcome {
  double loss;     ///< kinetic energy lost
  double impulse;  ///< momentum given to b along e, m_kj (1 + alpha)(g.e) (the collisional transfer's)
};

/// Smooth inelastic hard spheres with constant restitution alpha_kj (header; \ref cm_rule "docs/collision-model.md").
class SmoothRule {
 public:
  /// The constants of the projected form of pair (k, j): particle a of species k, b of species j (the
  /// block kernels keep them in a table of their own, beside the pair's slot of the event counts).
  struct Projected {
    double share_a;  ///< mu_jk (1 + alpha): v_a -= share_a p for p = (g.e) e
    double share_b;  ///< mu_kj (1 + alpha): v_b += share_b p
    double loss;     ///< (1 - alpha^2) m_kj / 2: the energy lost per (g.e)^2
  };
  /// The constants of the ordered species pair (k, j).
  struct Pair : Projected {
    double alpha;          ///< alpha_kj
    double mass_fraction;  ///< mu_jk = m_j/(m_k + m_j), the share of the impulse a takes
    double mass_a;         ///< m_k
  };
  static constexpr bool has_projection = true;  ///< offers collide_projected (the block kernels)
  static constexpr bool frames = true;          ///< may run on velocities stored in a frame

  /// The pair constants of `mix` (a table up to species::dense_pair_limit species, else computed per call).
  explicit SmoothRule(const species::Mixture& mix);
  /// The pair (k, j) with alpha, m_k and m_j given (the cluster bounce of agg_frag.hpp).
  static Pair make_pair(double alpha, double mass_a, double mass_b) {
    const double mf = mass_b / (mass_a + mass_b);
    return {{mf * (1.0 + alpha), (1.0 - mf) * (1.0 + alpha), 0.5 * (1.0 - alpha * alpha) * mass_a * mf}, alpha, mf, mass_a};
  }
  /// The constants of pair (k, j).
  Pair pair(std::size_t k, std::size_t j) const {
    if (!table_.empty()) return table_[k * s_ + j];
    return make_pair(mix_->restitution(k, j), mix_->mass[k], mix_->mass[j]);
  }

  /// The rule (header): v_a -= mu_jk (1 + alpha)(g.e) d, v_b += mu_kj (1 + alpha)(g.e) d.
  static Outcome collide(particles::Vec3& va, particles::Vec3& vb, const Pair& p, const Contact& c) {
    const double impulse = (1.0 + p.alpha) * c.g_dot_e;  // per unit reduced mass ratio
    const double da = p.mass_fraction * impulse;          // mu_jk (1 + alpha)(g.e)
    const double db = (1.0 - p.mass_fraction) * impulse;  // mu_kj (1 + alpha)(g.e)
    va = {va.x - da * c.dx, va.y - da * c.dy, va.z - da * c.dz};
    vb = {vb.x + db * c.dx, vb.y + db * c.dy, vb.z + db * c.dz};
    return {p.loss * c.g_dot_e * c.g_dot_e, p.mass_a * p.mass_fraction * impulse};
  }
  /// The rule given q = (g.e) e (or G^-1 of it in a frame) and (g.e)^2 instead of e: the option of the
  /// block kernels, which never form e. Returns the energy lost.
  static double collide_projected(particles::Vec3& va, particles::Vec3& vb, Projected p, double g_dot_e2,
                                  particles::Vec3 q) {
    va = {va.x - p.share_a * q.x, va.y - p.share_a * q.y, va.z - p.share_a * q.z};
    vb = {vb.x + p.share_b * q.x, vb.y + p.share_b * q.y, vb.z + p.share_b * q.z};
    return p.loss * g_dot_e2;
  }
  /// max over the pairs of (1 - alpha^2)/3, the fraction of the kinetic energy one collision per
  /// particle dissipates at most (collide.hpp "Blocks", "Step length").
  std::optional<double> largest_loss_fraction() const;
  /// Adds to `sys` the per-particle arrays the rule needs beyond the velocity (System::add_array), and
  /// sets them for the start: none.
  void attach(particles::System&) {}
  /// Adds its own observables of a sample (model/observables.hpp names) to `rows`: none.
  void measure(const particles::System&, sample::Rows&) const {}
  /// The rule on particles a and b of `sys`: the form the loops call (a rule with arrays of its own
  /// reads and writes them here).
  Outcome collide(particles::System& sys, std::size_t a, std::size_t b, const Pair& p, const Contact& c) const {
    return collide(sys.v[a], sys.v[b], p, c);
  }

 private:
  const species::Mixture* mix_;
  std::size_t s_;
  std::vector<Pair> table_;  ///< S x S, row-major (empty above species::dense_pair_limit species)
};

/// Viscoelastic spheres: alpha_kj(|g.e|) (header; \ref visco_series "docs/viscoelastic.md").
class ViscoelasticRule {
 public:
  /// The constants of the ordered species pair (k, j).
  struct Pair {
    double sqrt_beta;      ///< beta_kj^(1/2)
    double mass_fraction;  ///< mu_jk = m_j/(m_k + m_j)
    double mass_a;         ///< m_k
  };
  static constexpr bool has_projection = false;  ///< no collide_projected: alpha needs |g.e|
  static constexpr bool frames = false;          ///< the stage loop runs constant restitution only

  /// beta_kj of the material (restitution::one_material_beta) for the species of `mix`.
  ViscoelasticRule(const species::Mixture& mix, const species::PairMatrix& beta);
  /// The constants of pair (k, j).
  Pair pair(std::size_t k, std::size_t j) const {
    if (!sqrt_beta_.empty()) return {sqrt_beta_[k * s_ + j], mass_fraction_[k * s_ + j], mix_->mass[k]};
    return {std::sqrt(beta_(k, j)), mix_->mass[j] / (mix_->mass[k] + mix_->mass[j]), mix_->mass[k]};
  }
  /// alpha(|g.e|) of the pair (\ref visco_series "docs/viscoelastic.md"); throws std::domain_error beyond the series' range.
  static double restitution(const Pair& p, double g_dot_e) {
    const double u = p.sqrt_beta * std::pow(std::abs(g_dot_e), 0.1);
    if (u > restitution::u_max) return restitution::viscoelastic(p.sqrt_beta * p.sqrt_beta, g_dot_e);  // throws
    return restitution::series(u);
  }
  /// SmoothRule::collide with alpha = restitution(p, g.e).
  static Outcome collide(particles::Vec3& va, particles::Vec3& vb, const Pair& p, const Contact& c) {
    const double alpha = restitution(p, c.g_dot_e);
    const double impulse = (1.0 + alpha) * c.g_dot_e;
    const double da = p.mass_fraction * impulse, db = (1.0 - p.mass_fraction) * impulse;
    va = {va.x - da * c.dx, va.y - da * c.dy, va.z - da * c.dz};
    vb = {vb.x + db * c.dx, vb.y + db * c.dy, vb.z + db * c.dz};
    return {0.5 * (1.0 - alpha * alpha) * p.mass_a * p.mass_fraction * c.g_dot_e * c.g_dot_e,
            p.mass_a * p.mass_fraction * impulse};
  }
  /// None: alpha depends on the impact speed (blocked steps keep their shortest length).
  std::optional<double> largest_loss_fraction() const { return std::nullopt; }
  /// No arrays beyond the velocity.
  void attach(particles::System&) {}
  /// No observables of its own.
  void measure(const particles::System&, sample::Rows&) const {}
  /// The rule on particles a and b of `sys` (the loops' form).
  Outcome collide(particles::System& sys, std::size_t a, std::size_t b, const Pair& p, const Contact& c) const {
    return collide(sys.v[a], sys.v[b], p, c);
  }

 private:
  const species::Mixture* mix_;
  std::size_t s_;
  std::vector<double> sqrt_beta_, mass_fraction_;  ///< S x S (empty above species::dense_pair_limit species)
  species::PairMatrix beta_;                        ///< beta_kj (above the limit)
};

/// Every collision rule; the collider dispatches on it once per stretch of candidates.
using Rule = std::variant<SmoothRule, ViscoelasticRule>;

/// The rule of `mix`: viscoelastic with `viscoelastic_beta` (beta_kj), else constant alpha_kj.
Rule make_rule(const species::Mixture& mix, const species::PairMatrix* viscoelastic_beta);

}  // namespace gdsmc::rules
