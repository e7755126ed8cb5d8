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
 * use it. A rule without the option (`has_projection` false) runs the kernels' general path instead; a
 * rule with arrays of its own (`kernel_needs_particles`) offers `spins(sys)` and
 * `collide_at(sys, spins, a, b, k, j, (g.e)^2, p)`.
 *
 * **ViscoelasticRule**: the same update with alpha_kj(|g.e|) of viscoelastic spheres
 * (Bodrova and Osinsky 2024, eqs. (5)-(8); \ref visco_series "docs/viscoelastic.md"; model/restitution.hpp), from
 * beta_kj. It has no projection (alpha needs |g.e|) and no frame (the thermostat and shear flow run
 * constant restitution).
 *
 * **RoughRule**: rough spheres, normal restitution alpha_kj, tangential restitution beta_kj, reduced
 * moments of inertia kappa_k (\ref rough_rule "docs/rough-spheres.md"): the impulse acts on the relative
 * velocity of the contact points, so the rule reads and writes an angular velocity per particle (the
 * System array `angular_velocity`, which the loops, blocks and checkpoints carry without naming it), and
 * reports rotational_temperature, the cumulants a20, a02, a11 and total_energy. In the block kernels it
 * takes the kernels' p = (g.e) e and forms e = p/(g.e) (`collide_at`); no frame.
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
  double ex;       ///< e, the unit vector from a to b at contact (g.e > 0: approaching; actual velocities' frame): x
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
  /// The kernels call the static collide_projected on two velocities with the Projected constants of
  /// their own table (a rule with arrays of its own sets this and offers collide_at instead).
  static constexpr bool kernel_needs_particles = false;

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

/// Rough inelastic hard spheres: normal restitution alpha_kj, tangential restitution beta_kj, reduced
/// moments of inertia kappa_k (header; \ref rough_rule "docs/rough-spheres.md").
class RoughRule {
 public:
  /// The constants of the ordered species pair (k, j): a of species k, b of species j.
  struct Pair {
    double alpha;          ///< alpha_kj
    double tangential;     ///< (1 + beta_kj) K_kj, K_kj = 1/(1 + m_kj/(kappa_k m_k) + m_kj/(kappa_j m_j))
    double mass_fraction;  ///< mu_jk = m_j/(m_k + m_j) = m_kj/m_k
    double reduced_mass;   ///< m_kj
    double half_a;         ///< sigma_k/2
    double half_b;         ///< sigma_j/2
    double spin_a;         ///< 2 m_kj/(kappa_k m_k sigma_k): w_a -= spin_a e x J
    double spin_b;         ///< 2 m_kj/(kappa_j m_j sigma_j): w_b -= spin_b e x J
    double tangential_loss;  ///< K_kj (1 - beta_kj^2): the energy lost per (m_kj/2)|g_c,t|^2
  };
  static constexpr bool has_projection = true;   ///< the block kernels' p = (g.e) e gives e = p/(g.e): collide_at
  static constexpr bool frames = false;          ///< the frames hold no angular velocity
  static constexpr bool kernel_needs_particles = true;  ///< the kernels call collide_at (spins, pair constants)
  /// The name of the angular velocities among the System's arrays (particles/angular_velocity in checkpoints).
  static constexpr const char* angular_velocity = "angular_velocity";

  /// The pair constants of `mix` (mix.rough(): roughness and moment_of_inertia given).
  explicit RoughRule(const species::Mixture& mix);
  /// The constants of pair (k, j).
  Pair pair(std::size_t k, std::size_t j) const {
    if (!table_.empty()) return table_[k * s_ + j];
    return make_pair(*mix_, k, j);
  }
  /// The pair (k, j) of `mix`.
  static Pair make_pair(const species::Mixture& mix, std::size_t k, std::size_t j);

  /// The rule (\ref rough_rule "docs/rough-spheres.md", derived there; the model of Huthmann and Zippelius
  /// 1997, for mixtures Santos, Kremer and Garzo 2010):
  /// with e the unit vector from a to b (g.e > 0: approaching), g_c = g + (sigma_k w_a + sigma_j w_b)/2 x e
  /// the relative velocity of the contact points and J = (1 + alpha)(g.e) e + (1 + beta) K g_c,t (g_c,t
  /// its part normal to e),
  ///   v_a -= mu_jk J,  v_b += mu_kj J,  w_a -= spin_a e x J,  w_b -= spin_b e x J,
  /// so that (g_c'.e) = -alpha (g_c.e) and g_c,t' = -beta g_c,t; linear momentum and the angular
  /// momentum about the contact point are conserved, and the energy lost is
  /// (m_kj/2)[(1 - alpha^2)(g.e)^2 + K (1 - beta^2)|g_c,t|^2].
  static Outcome collide(particles::Vec3& va, particles::Vec3& vb, particles::Vec3& wa, particles::Vec3& wb,
                         const Pair& p, const Contact& c) {
    const double ex = c.ex, ey = c.ey, ez = c.ez;
    // s = (sigma_k w_a + sigma_j w_b)/2; g_c = g + s x e (e from a to b: a touches at +sigma_k/2 e)
    const double sx = p.half_a * wa.x + p.half_b * wb.x, sy = p.half_a * wa.y + p.half_b * wb.y,
                 sz = p.half_a * wa.z + p.half_b * wb.z;
    const double gcx = (va.x - vb.x) + (sy * ez - sz * ey);
    const double gcy = (va.y - vb.y) + (sz * ex - sx * ez);
    const double gcz = (va.z - vb.z) + (sx * ey - sy * ex);
    const double normal = gcx * ex + gcy * ey + gcz * ez;  // g_c.e = g.e (s x e is normal to e)
    const double tx = gcx - normal * ex, ty = gcy - normal * ey, tz = gcz - normal * ez;
    const double jn = (1.0 + p.alpha) * c.g_dot_e;
    const double jx = jn * ex + p.tangential * tx, jy = jn * ey + p.tangential * ty, jz = jn * ez + p.tangential * tz;
    const double fa = p.mass_fraction, fb = 1.0 - p.mass_fraction;
    va = {va.x - fa * jx, va.y - fa * jy, va.z - fa * jz};
    vb = {vb.x + fb * jx, vb.y + fb * jy, vb.z + fb * jz};
    // e x J = (1 + beta) K e x g_c,t (e x e = 0, formed so that beta = -1 leaves the spins exactly alone)
    const double cx = p.tangential * (ey * tz - ez * ty), cy = p.tangential * (ez * tx - ex * tz),
                 cz = p.tangential * (ex * ty - ey * tx);
    wa = {wa.x - p.spin_a * cx, wa.y - p.spin_a * cy, wa.z - p.spin_a * cz};
    wb = {wb.x - p.spin_b * cx, wb.y - p.spin_b * cy, wb.z - p.spin_b * cz};
    const double t2 = tx * tx + ty * ty + tz * tz;
    return {0.5 * p.reduced_mass * ((1.0 - p.alpha * p.alpha) * c.g_dot_e * c.g_dot_e + p.tangential_loss * t2),
            p.reduced_mass * jn};
  }
  /// max over the pairs of [(1 - alpha^2) + t (2 - t)]/3, t = (1 + beta) K: the fraction of the
  /// translational energy one collision per particle removes in the mean when the spins are still (the
  /// most: spins only give energy back; \ref rough_maxwellian "docs/rough-spheres.md", 4A/3), for the
  /// blocks' step length (collide.hpp "Blocks", "Step length"), which the speed bounds follow.
  std::optional<double> largest_loss_fraction() const;
  /// Adds the angular velocities (`angular_velocity`, zero) unless the initial state has them.
  void attach(particles::System& sys);
  /// rotational_temperature, cumulant_a20, cumulant_a02, cumulant_a11 and total_energy (model/observables.hpp).
  void measure(const particles::System& sys, sample::Rows& rows) const;
  /// The rule on particles a and b of `sys`.
  Outcome collide(particles::System& sys, std::size_t a, std::size_t b, const Pair& p, const Contact& c) const {
    auto& w = std::get<particles::ParticleArray<particles::Vec3>>(sys.extra[spin_index_].values);
    return collide(sys.v[a], sys.v[b], w[a], w[b], p, c);
  }
  /// The angular velocities of `sys` (the kernels prefetch them for their drawn-ahead candidates).
  particles::Vec3* spins(particles::System& sys) const {
    return std::get<particles::ParticleArray<particles::Vec3>>(sys.extra[spin_index_].values).data();
  }
  /// The block kernels' form: particles a (species k) and b (species j) given q = (g.e) e and (g.e)^2,
  /// with e = q/(g.e) (g.e > 0).
  /// Out of line: the kernels' candidate loop keeps its registers (only a fraction of candidates collide).
  /// `spin` is spins(sys), which the kernels hold.
  [[gnu::noinline]] Outcome collide_at(particles::System& sys, particles::Vec3* spin, std::size_t a, std::size_t b,
                                       std::size_t k, std::size_t j, double g_dot_e2, const particles::Vec3& q) const {
    const double g_dot_e = std::sqrt(g_dot_e2), inv = 1.0 / g_dot_e;
    const double ex = q.x * inv, ey = q.y * inv, ez = q.z * inv;
    const Contact c{ex, ey, ez, g_dot_e, ex, ey, ez};
    if (!table_.empty()) return collide(sys.v[a], sys.v[b], spin[a], spin[b], table_[k * s_ + j], c);
    return collide(sys.v[a], sys.v[b], spin[a], spin[b], make_pair(*mix_, k, j), c);
  }

 private:
  const species::Mixture* mix_;
  std::size_t s_;
  std::vector<Pair> table_;     ///< S x S (empty above species::dense_pair_limit species)
  std::size_t spin_index_ = 0;  ///< the angular velocities' place in System::extra
};

/// Every collision rule; the collider dispatches on it once per stretch of candidates.
using Rule = std::variant<SmoothRule, ViscoelasticRule, RoughRule>;

/// The rule of `mix`: viscoelastic with `viscoelastic_beta` (beta_kj), else constant alpha_kj.
Rule make_rule(const species::Mixture& mix, const species::PairMatrix* viscoelastic_beta);

}  // namespace gdsmc::rules
