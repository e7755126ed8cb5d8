/**
 * \file collide.hpp
 * \brief Binary inelastic collisions of smooth hard spheres and the homogeneous DSMC schemes.
 *
 * **Collision rule** (Bodrova and Osinsky 2024, eq. (3), Montanero and Garzo 2002, eqs. (23)-(24);
 * \ref cm_rule "docs/collision-model.md"; stated once in rules.hpp). For a (species k), b (species j), g = v_a - v_b
 * and e along the line of centres:
 *   v_a' = v_a - mu_jk (1 + alpha_kj) (g.e) e,   v_b' = v_b + mu_kj (1 + alpha_kj) (g.e) e,   mu_kj = m_k/(m_k + m_j).
 * Momentum is conserved, (g'.e) = -alpha (g.e), and the energy lost is (1 - alpha^2) m_kj (g.e)^2 / 2.
 *
 * **Rates** (\ref cm_pair_rate "docs/collision-model.md"). A species-k particle meets species-j partners at n_j pi
 * sigma_kj^2 chi_kj <|g|>: one unordered pair collides at pi sigma_kj^2 chi_kj |g| / V, or equivalently at 2 pi
 * sigma_kj^2 chi_kj |g.e| / V with e uniform on the full sphere.
 *
 * **Scheme `majorant`** (DSMC notes, steps 1-13, with the rate of \ref cm_pair_rate "docs/collision-model.md").
 * Candidate pairs (a, b), a != b uniform among all particles, arrive at R = N n B / 2, B = max_kj pi sigma_kj^2 chi_kj
 * (vmax_k + vmax_j) (DSMC notes, eq. (8), \ref sch_majorant "docs/schemes.md", N^2 F_N/V_c = N n), vmax_k the largest
 * speed of species k, so that B bounds every pair exactly. A candidate is accepted with pi sigma_kj^2 chi_kj |g| / B
 * (DSMC notes, eq. (7), \ref sch_majorant "docs/schemes.md"), and e is drawn with density proportional to (g_hat.e) on
 * the hemisphere (\ref cm_hemisphere "docs/collision-model.md"): the process of the DSMC notes' step 9 with the correct
 * rate, at twice its acceptance. A post-collision speed above vmax_k raises the bound at once; the bound is recomputed
 * exactly (lowered as the gas cools) at the start of each time step.
 *
 * **Scheme `pairs`** (Montanero and Garzo 2002, sec. 3, \ref sch_pairs "docs/schemes.md"). Ordered species pair (i, j)
 * gets candidates at R_ij = (1/2) N_i omega_max^(ij), omega_max^(ij) = 4 pi sigma_ij^2 n_j chi_ij (vmax_i + vmax_j): a
 * random particle of i, a random other of j and e uniform on the sphere, accepted with Theta(g.e) |g.e| / (vmax_i +
 * vmax_j). The pair of each candidate is drawn with probability R_ij / sum R (the paper sweeps the pairs in turn): no
 * operator-splitting error (\ref sch_thinning "docs/schemes.md").
 *
 * **Scheme `lowrank`** (Bodrova and Osinsky 2024, sec. II B, eqs. (9)-(14); \ref sch_lowrank "docs/schemes.md",
 * \ref sch_lowrank_decomposition "docs/schemes.md"). The ordered species pair (i, k) is drawn with probability A_ik / R
 * from the rank-3 majorant A_ik = pi sigma_ik^2 chi_max w_i N_i N_k / V, w_i = vmax_i, through segment trees in O(log
 * M) (segment_tree.hpp); then a particle of each species uniformly (the same one twice rejected), accepted with chi_ik
 * |g| / (chi_max (w_i + w_k)), e as in `majorant`. V = (N - 1)/n gives every particle pair the candidate rate of
 * `majorant`: the two schemes sample the same process. A raised vmax_i updates row i in O(log M).
 *
 * **Restitution**: constant alpha_kj, or viscoelastic (Bodrova and Osinsky 2024, eqs. (5)-(8),
 * \ref visco_series "docs/viscoelastic.md"), alpha from |g.e| (restitution.hpp, rules.hpp); bounds and acceptance do
 * not change. **Displacements** (Bodrova and Osinsky 2024, eq. (15), \ref sch_displacements "docs/schemes.md"), when
 * tracked: at a collision at time t both partners add v (t - t_last) to R before their velocities change.
 *
 * **Time.** Each scheme is a uniformised continuous-time process: a candidate advances time by 1 / R (the N_p = R dt
 * candidates per step of the DSMC notes, eq. (8), the fraction carried over), and collisions are processed one after
 * another with current velocities: no batch time-step bias (\ref sch_thinning "docs/schemes.md"). The time step dt =
 * step_fraction / nu_max, nu_max = 2 R / N, only sets how often the bounds are recomputed; it is written to the output.
 *
 * **Look-ahead** (\ref sch_lookahead "docs/schemes.md"; no change to the process). The particle indices of the next
 * `lookahead` candidates are drawn in advance and their velocities prefetched, so that memory reads overlap. A pair is
 * drawn independently of the state, so drawing it earlier does not change its law; `lowrank` discards its drawn-ahead
 * pairs whenever A_ik changes. They are part of the State. The block kernels draw 8 ahead, 32 in a frame ("Frame").
 *
 * **Blocks** (\ref sch_blocks "docs/schemes.md"; `use_blocks`: one species or a mixture of at most 256 species,
 * `majorant` or `lowrank`, N >= 2 block_size). The particles are split into K = N / block_size contiguous blocks;
 * during a time step each block is a gas of its own, with candidates among its N_b particles at R_b = N_b n B_b / 2,
 * B_b = 2 pi sigma^2 chi vmax_b: the pair rate is pi sigma^2 chi |g| n/(N_b - 1), every particle keeps the gas's
 * collision frequency. The blocks run one after another, each from the step's start to its end. Between steps the
 * particles are dealt round the blocks like cards from a random starting point (`remix`, in place: deal.hpp), so that
 * blocks never keep their members (but for a step shortened near an event target: below). What differs from the unblocked gas is the number of partners between remixes, N_b -
 * 1 instead of N - 1: a finite-N effect of order 1/N_b. A block's bound is recomputed exactly at its first visit in a
 * step. **Step length** (block_step_length; \ref sch_blocks "docs/schemes.md", "Step length"): within a step a bound is
 * only raised; one collision per particle dissipates at most gamma = max (1 - alpha_kj^2)/3 of the energy, and a step
 * brings c = min(sqrt(2/gamma), 6) collisions per particle: c/p majorant mean free times at the last step's acceptance
 * p, never less than block_steps = 5, times step_fraction, at most max_block_step_candidates = 3/4 of 2^24 candidates
 * unless block_steps is more (N > 5e6; the first step capped too). Viscoelastic restitution keeps block_steps; the stage
 * loop's runs do not (thermostat, shear, white noise, rough spheres: a frame maps every velocity alike, so the stored
 * ones cool by the collisions alone, and an action on each particle is followed by a pass that makes the bounds exact
 * again, reset_frame). The length sets when bounds are refreshed and blocks remixed, not the process. **Event targets**
 * (`collisions_per_particle`) are met exactly: when fewer events are left than a step could bring (R dt times the last
 * step's acceptance, 1 for a run's first step, plus 10 % and 8 standard deviations) the step is shortened (and, when
 * no longer than block_steps, keeps the blocks of the step before, no remix for a fraction of a step's events, while
 * it ends within two full steps' time of the last remix); after a step longer than block_steps the acceptance is that
 * of its first block_steps mean free times (its probe, taken at bounds as tight as a new step's) if its events per unit
 * time fell after the probe, else 1 (long: begun and run so; one begun short that ran more candidates than begun for,
 * its bounds raised, takes its acceptance times their ratio), and only after such a probe may a step near a target be longer than
 * block_steps (in a heating gas the events per unit time rise within a step), and when
 * that would leave it fewer than min(N/64, 4 N/K) events it runs on the whole gas as one block with the exact bound of
 * all particles, which samples the unblocked process and stops at the target (such a step holds at least 1.25 of the
 * whole gas's own candidates: it was sized at the blocks' R, which the separable draw's bound makes several times the
 * whole gas's; and one that ends short of its target, with fewer than min(N/64, 4 N/K) events left, goes on with its
 * bounds for 1.5 times what the events left need at its own events per unit time: extend_whole_step). Soft targets
 * (progress, checkpoints) are checked at step ends.
 *
 * **The one-species block kernel** (`run_block_one_species`; constant restitution) samples the process of `majorant`
 * (R_b, uniform pairs, acceptance |g| / (2 vmax_b), e of density (g_hat.e)/pi, bounds raised when exceeded, candidate
 * times t0 + (c + 1)/R_b) with the pair's indices from one draw (rng::Xoshiro256pp::below_pair, exact by rejection),
 * the drawn-ahead pairs in locals, the frame a template parameter, and the impulse from p = (g.e) e = (g + |g| w)/2 for
 * e = (g_hat + w)/|g_hat + w| (hemisphere_projection; w from rng::unit_vector_32, directions on a lattice of step
 * 2^-31, about 1e-9 rad). Its stream differs from run_majorant's, its law does not. With one species the rank-3
 * majorant of `lowrank` is the uniform one, so both schemes run this kernel; viscoelastic restitution runs
 * run_majorant / run_lowrank in the blocks.
 *
 * **Frame** (`set_frame`; the stage loop of thermostat.hpp). Streaming and rescaling map every velocity alike, so the
 * System may hold u in a frame, V = G u, G = S [[1, c, 0], [0, 1, 0], [0, 0, 1]]; a stage changes only G (a rescaling
 * by s multiplies S, the streaming subtracts a dt from c). A candidate's g = G (u_a - u_b) is used as above, and the
 * partners' u change by -/+ mu (1 + alpha)(g.e) G^-1 e, G^-1 e = (e_x - c e_y, e_y, e_z)/S: the same process, other
 * round-off. Bounds hold the largest |u| times ||G|| = S (|c|/2 + sqrt(1 + c^2/4)), kept within 2 % of S by the stage
 * loop (G back to 1 whenever |c| > 0.04 and at every sample). The moments Q = sum m u u^T (xx, yy, zz, xy) are kept
 * collision by collision: the kinetic energy is S^2 (Q_xx + 2 c Q_xy + c^2 Q_yy + Q_yy + Q_zz)/2 without a pass.
 * Constant restitution, no displacements. **Frames in blocks**: every block of a pass uses the master's G, the block
 * kernels take the frame as a template parameter, and each block's change of Q is added in block order after the pass.
 * The stage loop's pass that brings G back to 1 runs block by block on the block threads (`map_blocks`: each block's
 * bound kept from it, the sums added in block order); reset_frame after a caller's own pass (tests) recomputes each block's bound.
 *
 * **Mixtures in blocks.** Block j holds a slice of every species: species k's particles are dealt round K slices inside
 * k's range, ceil((N_k - j)/K) in block j, when N_k >= min_slice K (min_slice = 64). A rarer species is *scattered*: at
 * every remix its particles are shuffled and cut into K slices of multinomial counts (the first step draws the counts
 * only), each to a uniformly random block, so E[1/(N_b - 1) | both in b] = K/(N - 1) and the expected pair rate is the
 * gas's. A block runs `majorant` with B_b = max_kj pi sigma_kj^2 chi_kj (vmax_bk + vmax_bj) over its species and R_b =
 * N_b n B_b / 2, or its own `lowrank` A_ik = pi sigma_ik^2 chi_ik w_i N_i N_k / V (chi_ik itself, the slices' counts
 * and speeds, V = (N_b - 1)/n) accepted with |g| / (w_i + w_k), its species pair from an alias table of the P^2 pairs
 * present, then a particle of each slice: each pair collides at pi sigma_ik^2 chi_ik |g| n/(N_b - 1). With constant
 * restitution `run_block_mixture` samples the same process with the one-species kernel's techniques (species from the
 * block's 32-bit edges, species_at; pair constants in PairKernel; a binary `majorant` kernel `Two`); a `lowrank`
 * candidate is one 64-bit word (set_block_lowrank: 2^m >= max(P^2, 2) alias cells, the coin exact, the particles by
 * 24-bit multiply-shift with rejection) when at most lowrank_factor_above = 24 species are present in the block.
 * *The factored draw* (more than 24 present; \ref sch_factored "docs/schemes.md"): A_ik = w_i rho_i q_k|i, rho_i = N_i
 * sum_k pi sigma_ik^2 chi_ik N_k / V and q_k|i = pi sigma_ik^2 chi_ik N_k / sum_k' pi sigma_ik'^2 chi_ik' N_k'; the
 * row i is drawn from an alias table over the P species of weights w_i rho_i (times ||G|| in a frame), then the column
 * k from row i's own table of q_k|i: the pair (i, k) with probability w_i rho_i q_k|i / sum_j w_j rho_j = A_ik / R_b,
 * the one-word draw's law, at the same R_b = sum_ik A_ik and with the same acceptance |g| / (w_i + w_k), so that the
 * process is the same (the stream differs). q_k|i holds no speed (chi_ik is fixed by the densities), so a raised bound
 * rebuilds the P rows' table alone, O(P), where the one-word table is rebuilt in O(P^2) (bounds are raised about once
 * per slice's worth of events: above 24 species that rebuild outgrows the candidates); a factored candidate takes two
 * words and two dependent table reads, so up to 24 species the one-word draw costs less. set_lowrank_factor_above()
 * moves the threshold (tests). *The separable draw* (more than separable_above = 128 species, `lowrank`; blocks of
 * block_size, but of at least 8 S particles where that leaves at least 16 blocks, and while S K <= N (else K = N div
 * S), beyond 65535 species K >= ceil(N/62500), while S K <= 2 N: separable_block_count; \ref sch_separable "docs/schemes.md"): w_i = W_b/sqrt(m_i) with W_b^2 = max m |v|^2 over the block, so that A_ik =
 * (pi chi_max W_b/(4V)) sum_r u_i^(r) v_k^(r), u_i = N_i (sigma_i^2, 2 sigma_i, 1)/sqrt(m_i), v_k = N_k (1, sigma_k,
 * sigma_k^2) (Bodrova and Osinsky 2024, eqs. (12)-(14)): the term r, then the row from u^(r) and the column from v^(r),
 * from six alias tables over the P species present built once per visit; accepted with chi_ik |g| / (chi_max (w_i +
 * w_k) ||G||). No table holds a speed: a raised W_b changes R_b only. The pair's constants are computed per collision
 * (no S x S table); set_separable_blocks() forces this draw at any S (tests). *The cheaper sampler*: both are exact majorants of one pair law, so at each
 * step the master gives all blocks `lowrank` when lowrank_candidate_cost (1.15) times sum_ik pi sigma_ik^2 chi_ik
 * vmax_i N_i N_k n/(N - 1) is below N n B/2, else `majorant`, whatever the scheme (part of the State; a step after a
 * change of sampler judges its events from the last step's events per unit time and is 5 mean free times long);
 * set_block_sampler() forces one. Viscoelastic mixtures, whole-gas steps and unblocked runs keep the scheme's loops.
 * Checked by Collide.BlockedMixtureMatchesUnblocked, Collide.BlockedThreeSpeciesLowrankMatchesUnblocked,
 * Collide.BlocksRunTheCheaperSampler, Collide.ManySpeciesBlocksMatchUnblocked (the factored draw, 200 species, about 150 present in a
 * block), Collide.FactoredDrawMatchesOneWordDrawAndUnblocked (the factored draw forced at P = 2, 3, 20),
 * Collide.FactoredDrawOnlyAboveTheThreshold and the mixture validations.
 *
 * **Threads inside one replica** (`use_threads`). The blocks of a step are independent gases over the same interval and
 * run on OpenMP threads, each on a copy of the pair tables (a "worker"). At the start of each pass a 64-bit key is
 * drawn from the replica's collision stream, and block j draws from its own xoshiro256++ stream seeded by a hash of
 * (key, j) (rng::Xoshiro256pp::substream): keyed by (seed, replica, pass, block). Each block's counts and sums are
 * added in block order after the pass, so the output is the same bits for any thread count. The threads take the blocks
 * up in visit_order (consecutive ones ceil(K/T) apart: neighbouring blocks share cache lines where their slices meet).
 * Whole-gas steps run on one thread; two stages of the remix are split over the threads (deal.hpp, "Threads"), and a
 * mixture's species of fewer than N/(4T) particles are dealt one species per thread (deal_species), and the
 * scattered species' shuffles make their draws in the replica's stream and their transpositions one species per
 * thread (scatter_species; Collide.ScatteredSpeciesAreShuffledAlikeOnAnyThreadCount). Streams of
 * distinct (key, j), drawn about 1e5 times each per pass from a period of 2^256 - 1, overlap with probability below
 * 1e-60.
 *
 * Units: the user's (time e.g. in sigma sqrt(m/T0)). Namelist group `&dsmc` (scheme, step_fraction, block_size). A new
 * collision rule is a type of rules.hpp (\ref ext_rule "docs/extending.md"). Measurements and what was tried:
 * \ref perf_one_species "docs/performance.md", \ref perf_mixtures "docs/performance.md". Checked by
 * tests/collide_test.cpp and validation/ (haff_cooling, collision_rate, schemes_agree, the `*_blocks_quick` cases).
 */
#pragma once

#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dsmc/deal.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/rules.hpp"
#include "dsmc/segment_tree.hpp"
#include "dsmc/state.hpp"
#include "model/species.hpp"

namespace gdsmc::collide {

enum class Scheme { majorant, pairs, lowrank };

/// Per-species-pair event counts are kept for mixtures of at most this many species.
inline constexpr std::size_t pair_event_limit = 64;
/// Mixtures of at most this many species may run `majorant` in blocks and the one-word or factored
/// `lowrank` draws (header "Mixtures in blocks"); above it their S x S pair tables and the factored draw's
/// column tables, O(P^2) at every block visit, cost more than the blocks save (docs/performance.md,
/// "Many species in blocks"), and only `lowrank` blocks run, by the separable draw.
inline constexpr std::size_t block_species_limit = 256;

/// The species of a block's i-th particle in the `majorant` mixture kernel: the k with edge[k] <= i <
/// edge[k + 1], edge the block's running counts (edge[0] = 0 <= i < edge[s]; an empty species has
/// edge[k] = edge[k + 1] and is never returned). Two species: one compare; up to 8: a count of the
/// edges <= i without branches; more: a search whose steps depend on s only, so that none of them is
/// mispredicted (the number of edge[1..s-1] <= i, as std::upper_bound would find it). Tested against
/// counting by hand (Collide.SpeciesOfABlockIndex).
inline std::uint32_t species_at(const std::uint32_t* edge, std::size_t s, std::uint32_t i) {
  if (s == 2) return i >= edge[1];
  std::uint32_t k = 0;
  if (s <= 8) {
    for (std::size_t q = 1; q < s; ++q) k += i >= edge[q];
    return k;
  }
  const std::uint32_t* first = edge + 1;
  std::size_t len = s - 1;
  while (len > 1) {
    const std::size_t half = len / 2;
    first = first[half] <= i ? first + half : first;
    len -= half;
  }
  return static_cast<std::uint32_t>(first - (edge + 1)) + (*first <= i);
}

/// Counts kept by a run: the observables `collisions` and `collisions_pair` come from here.
struct Counters {
  std::uint64_t events = 0;                ///< accepted collisions (binary events)
  std::uint64_t candidates = 0;            ///< candidate pairs tested
  std::vector<std::uint64_t> pair_events;  ///< S x S, events between species k and j at (min, max);
                                           ///< empty above pair_event_limit species
  std::uint64_t steps = 0;                 ///< time steps (bound recomputations)
  double step_sum = 0.0;                   ///< sum of the step lengths, for the mean dt
  double dissipated = 0.0;                 ///< kinetic energy lost so far, (1 - alpha^2) m_kj (g.e)^2/2
                                           ///< per collision (\ref cm_energy "docs/collision-model.md"): the thermostat's loss
  /// Enskog gas in shear flow (set_shear): sum over accepted collisions of m_kj sigma_kj (1 + alpha)
  /// (g.e) e e, components xx, yy, zz, xy, xz, yz: the collisional transfer (\ref eta_pressure "docs/shear-viscosity.md").
  std::array<double, 6> transfer{};
  /// Candidates whose acceptance probability came out above 1 (the bound was not a majorant), and the
  /// largest such probability: an invariant of every scheme, 0 in a correct run (validation/ fails
  /// otherwise, and the program warns).
  std::uint64_t overshoots = 0;
  double largest_acceptance = 0.0;
};

/// The mass-weighted sums of a frame pass (thermostat.hpp, "Cost: the frame"; Collider::map_blocks).
struct FramePassSums {
  double mass = 0.0;                    ///< sum m
  std::array<double, 3> momentum{};     ///< sum m V
  std::array<double, 4> moments{};      ///< sum m V V^T: xx, yy, zz, xy
};

/// The frame pass over `count` velocities of one species of mass `m` from `v` on: each u becomes
/// V = (s u_x + sc u_y, s u_y, s u_z) + b, their sums times m are added to `sums`, and the largest
/// |V|^2 (the expression of the blocks' exact bounds) is returned. Shared by thermostat::materialise
/// (species by species) and Collider::map_blocks (slice by slice), so both sum in the same way.
inline double map_velocities(particles::Vec3* v, std::size_t count, double m, double s, double sc,
                             const particles::Vec3& b, FramePassSums& sums) {
  double sx = 0.0, sy = 0.0, sz = 0.0, sxx = 0.0, syy = 0.0, szz = 0.0, sxy = 0.0, max2 = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const particles::Vec3 w{s * v[i].x + sc * v[i].y + b.x, s * v[i].y + b.y, s * v[i].z + b.z};
    v[i] = w;
    sx += w.x, sy += w.y, sz += w.z;
    sxx += w.x * w.x, syy += w.y * w.y, szz += w.z * w.z, sxy += w.x * w.y;
    max2 = std::max(max2, w.x * w.x + w.y * w.y + w.z * w.z);
  }
  sums.mass += m * static_cast<double>(count);
  sums.momentum[0] += m * sx, sums.momentum[1] += m * sy, sums.momentum[2] += m * sz;
  sums.moments[0] += m * sxx, sums.moments[1] += m * syy, sums.moments[2] += m * szz, sums.moments[3] += m * sxy;
  return max2;
}

/// The time a gas whose speed bounds are all zero reaches (no candidate comes): `t_target`; an infinite one
/// (an event target, never reached) throws std::runtime_error (only a damaged checkpoint makes such bounds).
double time_at_rest(double t_target);

/// The whole candidates of a sub-step, floor(`expected`) = floor(available R): 0 for none (or NaN), at most
/// 2^63 (a count past 2^64, from a checkpoint's forged bounds, would overflow the conversion; no run's
/// sub-step comes near it).
inline std::uint64_t candidate_count(double expected) {
  if (!(expected > 0.0)) return 0;
  return expected < 0x1p63 ? static_cast<std::uint64_t>(expected) : std::uint64_t{1} << 63;
}

/// The collision stage of one replica: particles, pair constants, bounds, clock and generator.
class Collider {
 public:
  /// `viscoelastic_beta`: beta_ki of the viscoelastic restitution (restitution.hpp), or nullptr
  /// for the constant alpha_kj of the mixture.
  Collider(Scheme scheme, const species::Mixture& mix, particles::System& sys,
           rng::Xoshiro256pp gen, double step_fraction,
           const species::PairMatrix* viscoelastic_beta = nullptr)
      : Collider(scheme, mix, sys, gen, step_fraction, rules::make_rule(mix, viscoelastic_beta)) {}
  /// The same with the collision rule given (rules.hpp; run/model.cpp builds it from the input), which
  /// attaches its per-particle arrays to `sys`.
  Collider(Scheme scheme, const species::Mixture& mix, particles::System& sys, rng::Xoshiro256pp gen,
           double step_fraction, rules::Rule rule);

  /// Cache blocks of about `block_size` particles (header, "Blocks"), for one species or a mixture of
  /// at most block_species_limit (256) species with the `majorant` or `lowrank` scheme, or of more with
  /// `lowrank` and a rule with the projection (the separable draw above separable_above species, in
  /// separable_block_count() blocks: of at least 8 S particles where that leaves 16 blocks, larger ones when
  /// S K would exceed N), and N >= 2 block_size; otherwise (or
  /// with 0) the whole gas is one block. Call before the first advance(). `check`: the caller's look at
  /// its interrupt flag (particles::SetUpCheck); when it throws, the collider is half set up and must be
  /// discarded.
  void use_blocks(std::size_t block_size, const particles::SetUpCheck& check = {});
  std::size_t blocks() const { return block_first_.empty() ? 1 : block_first_.size() - 1; }
  /// How the blocks draw their candidates (header "Blocks", "Mixtures in blocks", "The cheaper sampler"), for
  /// the output's record of a run (run/simulation.cpp: the attribute block_draw of /parameters). The numbers are kept in
  /// checkpoints: a new draw takes the next number.
  enum class BlockDraw : std::uint8_t {
    unblocked,    ///< the whole gas is one block (no use_blocks, too few particles, `pairs`, ...)
    one_species,  ///< one species: the one-species kernel (the general loops for a rule without the projection)
    majorant,     ///< a mixture's blocks always draw `majorant`'s uniform pairs
    lowrank,      ///< a mixture's blocks always draw from the low-rank majorant (one-word or factored table)
    separable,    ///< `lowrank` beyond separable_above species: the separable draw
    clusters,     ///< &agg_frag's cluster blocks (agg_frag.hpp)
    cheaper,      ///< a mixture's blocks take, at each step, the cheaper of the `majorant` and low-rank draws
  };
  /// Its name in the output ("unblocked", "one species", "majorant", "lowrank", "separable", "clusters",
  /// "majorant or lowrank, the cheaper at each step"); nullptr for a number that is none of them.
  static const char* block_draw_name(BlockDraw draw);
  /// The draw of this collider's blocks (use_blocks; as choose_block_lowrank decides at each step).
  BlockDraw block_draw() const {
    if (block_first_.empty()) return BlockDraw::unblocked;
    if (s_ == 1) return BlockDraw::one_species;
    if (separable_blocks_) return BlockDraw::separable;
    if (!kernels_) return scheme_ == Scheme::lowrank ? BlockDraw::lowrank : BlockDraw::majorant;  // (the scheme's own)
    if (block_sampler_ == BlockSampler::cheaper) return BlockDraw::cheaper;
    return block_sampler_ == BlockSampler::lowrank ? BlockDraw::lowrank : BlockDraw::majorant;
  }
  /// The number K of the separable draw's blocks of N = `n` particles of `species` species (use_blocks):
  /// N div block_size, at most N div (separable_particles_per_species S) but at least separable_min_blocks,
  /// and N div S where S K would exceed N (at most separable_block_limit particles on average beyond
  /// separable_species_limit species) while S K <= 2 N; fewer than 2: none.
  static std::size_t separable_block_count(std::size_t species, std::size_t n, std::size_t block_size);
  /// Which exact sampler a mixture's blocks run (header "Mixtures in blocks", "The cheaper sampler"):
  /// `cheaper` (the default) takes, at each step, the one of the `majorant` and `lowrank` block majorants
  /// whose candidates cost less in all, whatever the scheme; the other two force one (tests, benchmarks).
  /// Viscoelastic mixtures and the whole-gas steps keep the scheme's own sampler.
  enum class BlockSampler { cheaper, majorant, lowrank };
  /// The sampler of the blocks from the next step on (BlockSampler::cheaper by default).
  void set_block_sampler(BlockSampler sampler) { block_sampler_ = sampler; }
  /// With blocks: whether the blocks of the step under way (or of the last one) run the `lowrank` sampler.
  bool block_lowrank() const { return block_lowrank_; }
  /// The candidate rate of the blocks' `lowrank` (true) or `majorant` sampler, summed over the blocks,
  /// at the gas's speed bounds vmax_k (those of the step under way, or as set_max_speeds() set them),
  /// without a frame's factor: sum_ik pi sigma_ik^2 chi_ik vmax_i N_i N_k n/(N - 1) and N n B/2 with
  /// B = max_kj pi sigma_kj^2 chi_kj (vmax_k + vmax_j) (header "Mixtures in blocks"); the cheaper
  /// sampler is `lowrank` when lowrank_candidate_cost times the first is less than the second.
  double block_candidate_rate(bool lowrank) const {
    return lowrank ? lowrank_block_rate(max_speed2_.data())
                   : 0.5 * static_cast<double>(sys_.size()) * mix_.total_density() * mixture_bound(max_speed2_.data());
  }
  /// A `lowrank` block candidate's cost over a `majorant` one's, both in the mixture kernel, as measured on
  /// binary gases at N = 1e6 (\ref perf_cheaper_sampler "docs/performance.md", docs/schemes.md "The cheaper sampler").
  static constexpr double lowrank_candidate_cost = 1.15;
  /// A block's `lowrank` sampler takes the factored draw when more than this many species are present
  /// in it, the one-word draw otherwise (header "Mixtures in blocks"; the same process either way; the
  /// measurements that set it: \ref perf_factored "docs/performance.md").
  static constexpr std::size_t lowrank_factor_above = 24;
  /// A mixture of more than this many species takes the separable draw in `lowrank` blocks (header "Mixtures
  /// in blocks"): from 129 species on it costs less than the factored draw, whose O(P^2) column tables
  /// grow (\ref perf_separable "docs/performance.md").
  static constexpr std::size_t separable_above = 128;
  /// Beyond this many present species a block's separable draw reads the species' entries a stage after
  /// the cells (separable_cells), where tables and entries outgrow the core's L2; up to it, with them
  /// (\ref perf_separable_sized "docs/performance.md").
  static constexpr std::size_t separable_deep_above = 4096;
  /// Tests only: blocks with more than `species` species present take the factored draw from the next
  /// block visit on (lowrank_factor_above by default; 0: every block), so that it can be compared with
  /// the one-word draw and the unblocked loops at few species.
  void set_lowrank_factor_above(std::size_t species) {
    factor_above_ = species;
    for (Collider& worker : workers_) worker.factor_above_ = species;
  }
  /// Tests only: a mixture's `lowrank` blocks take the separable draw (header "Mixtures in blocks"), which
  /// blocks of more than separable_above species take, whatever the number of species (call after
  /// use_blocks(), before the first advance()), so that it can be compared with the other draws.
  void set_separable_blocks() {
    separable_blocks_ = lowrank_blocks() && kernels_;
    for (Collider& worker : workers_) worker.separable_blocks_ = separable_blocks_;
  }
  /// Tests only: separable blocks with more than `species` species present read the species' entries a
  /// stage after the cells (separable_deep_above by default; 0: every block), so that the three-stage
  /// draw can be checked at few species.
  void set_separable_deep_above(std::size_t species) {
    deep_above_ = species;
    for (Collider& worker : workers_) worker.deep_above_ = species;
  }
  /// OpenMP threads for the blocks of a step (header, "Threads inside one replica"); 1 by default.
  /// The results do not depend on it, bit for bit. Without blocks it has no effect.
  void use_threads(int threads);
  /// The threads set by use_threads (1 by default).
  int threads() const { return threads_; }
  /// The order in which a pass takes up K blocks on `threads` threads (header, "Threads inside one replica"):
  /// 0, h, 2h, .., 1, h + 1, .. with h = ceil(K/T), a permutation of 0..K-1 (the identity on one thread).
  static std::vector<std::size_t> visit_order(std::size_t blocks, int threads);
  /// With blocks: the time the blocks were last dealt (a remix, or the first step; header "Event targets").
  double last_remix_time() const { return remix_time_; }
  /// Memory the collider holds for the particles besides the System, in bytes: the scratch memory of
  /// the blocks' remix, done in place (deal.hpp; about (2 seg + 1) K elements and N/seg bits), and on
  /// several threads, after the first remix, one workspace per thread for a mixture's small species; with
  /// scattered species, the transpositions of a chunk of them (scatter_chunk, 1 MiB, or one larger species').
  std::size_t workspace_bytes() const {
    std::size_t bytes = remix_workspace_.bytes();
    for (const deal::Workspace& w : species_workspaces_) bytes += w.bytes();
    bytes += scatter_partners_.capacity() * sizeof(std::uint32_t);
    return bytes;
  }

  /// Advances until time `t_target` or until `event_target` events, whichever comes first.
  /// Returns true when the event target stopped it. With blocks and `exact_events`, the steps near
  /// the event target run on the whole gas and stop at it exactly (header, "Blocks"); without
  /// `exact_events` (a soft target: a progress or checkpoint chunk) it is checked at the end of
  /// each blocked step only and may be passed by up to one step's events. `event_limit` is a hard
  /// target beyond a soft one (the sample's own event target): never passed, met exactly as an exact
  /// `event_target` is, so that a soft chunk's step cannot run past it. With blocks and `to_step_end`
  /// it also stops at the end of the blocked step under way (or of the one that starts now), so that
  /// a chunk that ends there never splits a step (header, "Blocks"); without blocks `to_step_end` is
  /// ignored.
  bool advance(double t_target, std::uint64_t event_target = UINT64_MAX, bool exact_events = true,
               std::uint64_t event_limit = UINT64_MAX, bool to_step_end = false);
  /// A flag (the caller's interrupt flag, set by a signal handler) that, once set, makes advance()
  /// return false at the next step start, before its targets, or within 2^16 candidates of an unblocked
  /// loop or a mixture's block, 2^20 of a one-species block (a long step is then cut: the run is abandoned); the caller sees an unfinished advance and
  /// stops. However small `step_fraction` is, a step start comes within one O(N) bound recomputation
  /// (tests/scale_out/interrupt.sh). Read only; nullptr (the default): never.
  void set_stop_flag(const std::atomic<bool>* flag) { stop_flag_ = flag; }

  /// The velocities were changed from outside between two advance() calls (the streaming of a
  /// shear flow, a thermostat's rescaling): the largest speeds and the bounds are recomputed
  /// exactly, O(N), so the majorant holds again. Not with blocks.
  void velocities_changed() {
    recompute_max_speeds();
    rebuild_bounds();
  }
  /// Uniform shear flow u_x = a y in the Enskog gas (`pairs` scheme only; \ref eta_enskog_shear "docs/shear-viscosity.md"): a partner at
  /// r_k + sigma_ij e moves with the flow a sigma_ij e_y relative to particle k, so the relative velocity
  /// of the collision is g = V_k - V_l - a sigma_ij e_y x_hat, in the acceptance Theta(g.e) |g.e| and in
  /// the update; the bound grows by a sigma_ij/2 >= |a sigma_ij e_y e_x|. Each accepted collision adds
  /// its collisional transfer to Counters::transfer. Throws std::invalid_argument for another scheme.
  void set_shear(double rate);
  /// The same when the caller has just computed the largest speed^2 of each species in its own
  /// pass over the particles (thermostat.hpp's fused stage pass): no second pass here.
  void set_max_speeds(const std::vector<double>& max_speed2) {
    for (std::size_t k = 0; k < s_; ++k) {
      max_speed2_[k] = max_speed2[k];
      max_speed_[k] = std::sqrt(max_speed2[k]);
    }
    rebuild_bounds();
  }

  /// The frame of the stored velocities (header, "Frame"): V = S (u_x + c u_y, u_y, u_z), with
  /// S = `scale`, c = `shear`. The first call starts the frame with the moments of the stored u
  /// computed by a pass; later calls only rebuild the bounds (the u are unchanged). Throws
  /// std::logic_error with viscoelastic restitution or displacement tracking.
  void set_frame(double scale, double shear);
  /// The stored u were just replaced by the actual velocities (the frame was applied to them in a
  /// pass that also computed `moments` = sum m V V^T (xx, yy, zz, xy) and the largest speed^2 of
  /// each species): G = 1 again, and the bounds exact (with blocks, each block's by a pass over it,
  /// unless `block_bounds_set`: the pass was map_blocks(), which kept them).
  void reset_frame(const std::array<double, 4>& moments, const std::vector<double>& max_speed2,
                   bool block_bounds_set = false);
  /// The sums of map_blocks(), block by block in block order.
  struct BlockPass {
    double mass = 0.0;                           ///< sum m
    particles::Vec3 momentum{0.0, 0.0, 0.0};     ///< sum m V
    std::array<double, 4> moments{};             ///< sum m V V^T: xx, yy, zz, xy
    std::vector<double> max_speed2;              ///< the largest |V|^2 of each species
  };
  /// With blocks, the pass of thermostat.hpp's stage loop ("Cost: the frame") on the block threads:
  /// V = (s u_x + sc u_y, s u_y, s u_z) + b for every particle, block by block; each block's largest
  /// |V|^2 of each species is its exact bound (for reset_frame(..., true)), and the blocks' sums are
  /// added in block order, so they are the same on any number of threads. Throws std::logic_error
  /// without blocks.
  BlockPass map_blocks(double s, double sc, const particles::Vec3& b);
  bool framed() const { return framed_; }
  double frame_scale() const { return frame_scale_; }
  double frame_shear() const { return frame_shear_; }
  /// sum m u u^T of the stored u (xx, yy, zz, xy), kept collision by collision in a frame.
  const std::array<double, 4>& frame_moments() const { return moments_; }
  /// ||G||, the factor of every speed bound in a frame (1 without one).
  static double frame_norm(double scale, double shear) {
    return scale * (0.5 * std::abs(shear) + std::sqrt(1.0 + 0.25 * shear * shear));
  }

  double time() const { return time_; }
  const Counters& counters() const { return counters_; }
  /// The collision rule's own observables of a sample (rules.hpp measure), added to `rows`.
  void measure_rule(sample::Rows& rows) const {
    std::visit([&](const auto& rule) { rule.measure(sys_, rows); }, rule_);
  }
  /// Mean length of the time steps so far (0 before the first step).
  double mean_step() const { return counters_.steps ? counters_.step_sum / counters_.steps : 0.0; }
  double candidate_rate() const { return rate_; }
  /// With blocks: the candidates per unit time of the blocked step under way, or of the one that just
  /// ended at a step end (0 before the first candidate); the simulation sizes its chunks with it.
  double recent_candidate_rate() const {
    const double elapsed = time_ - step_start_;
    return elapsed > 0.0 ? static_cast<double>(counters_.candidates - step_candidates_start_) / elapsed : 0.0;
  }

  /// Everything that evolves during a run, for checkpoints. The bounds and samplers are not stored:
  /// they are functions of the speeds vmax_k (rebuilt exactly on restore), and so is every tree
  /// and table of `lowrank` (segment_tree.hpp recomputes its sums from the leaves).
  struct State {
    double time = 0.0, credit = 0.0, next_step_time = 0.0;
    std::vector<double> max_speed, max_speed2;
    Counters counters;
    rng::Xoshiro256pp::State generator{};
    std::vector<std::uint32_t> pending;  ///< the drawn-ahead candidates, 4 per candidate
    std::size_t pending_next = 0;
    bool pending_filled = false;
    std::vector<double> block_max_speed2, block_credit;  ///< with blocks (use_blocks)
    std::vector<std::uint64_t> slice_counts;             ///< with scattered species: each block's counts, K x S
    double step_start = 0.0;                             ///< with blocks: when this step began
    double remix_time = 0.0;                             ///< with blocks: when the blocks were last dealt
    bool whole_step = false;                             ///< with blocks: the step runs on the whole gas
    double step_acceptance = 0.0;
    std::uint64_t step_events_start = 0, step_candidates_start = 0;
    double step_planned_candidates = 0.0;  ///< with blocks: R dt of the step as begun (0: not known)
    int probe = 0;                     ///< with blocks: the step's probe (Probe: 0 none, 1 pending, 2 measured)
    double probe_time = 0.0;           ///< when the probe is taken
    std::uint64_t probe_events = 0;    ///< the step's events up to the probe, once measured
    std::uint64_t probe_candidates = 0;  ///< the step's candidates up to the probe, once measured
    int block_lowrank = -1;  ///< with blocks: the step's sampler (1 `lowrank`, 0 `majorant`; -1 unknown: the scheme's)
    bool framed = false;                                 ///< set_frame: the frame and its moments
    double frame_scale = 1.0, frame_shear = 0.0;
    std::array<double, 4> moments{};
  };
  State state() const;
  /// Continues from `state`, taken from a Collider of the same scheme, mixture and particle counts
  /// at the end of an advance(); the System must hold the particles of that moment.
  void restore(const State& state);
  /// The State under named values "collider/..." (dsmc/state.hpp), for checkpoints.
  void save(state::Record& record) const;
  /// Continues from save()'s record (as restore(State)); throws state::StateError for a missing,
  /// misshapen or impossible value (a drawn-ahead candidate naming no particle, a frame's scale <= 0).
  void restore(const state::Record& record);

 private:
  void recompute_max_speeds();
  void rebuild_bounds();
  /// `lowrank` after a raised bound: the rows of the species in raised_ anew, and rate_.
  void raise_lowrank_rows();
  bool raise_max_speed(std::size_t particle);
  template <class TryCandidate>
  int run_substep(double t_stop, std::uint64_t event_target, TryCandidate&& try_candidate);
  /// How a stretch of candidates ended (the loops return it as an int).
  enum class Stop { reached_time, bound_raised, reached_events };
  /// The unblocked loop `loop` (the scheme's, or a whole-gas step's) with the collider's rule, up to
  /// t_stop or the event target (returns a Stop, collide.cpp): the rule_ and the frame dispatched here,
  /// once per sub-step, to the loops that take them as template parameters.
  int run_loop(Scheme loop, double t_stop, std::uint64_t event_target);
  /// On a worker: the current block in the block kernel of the collider's rule (one species or a
  /// mixture, `lowrank`'s sampler or `majorant`'s), for a rule with the projection (rules.hpp).
  void run_block_kernels(bool lowrank, double t_stop);
  template <class Rule>
  void run_block_kernel(const Rule& rule, bool lowrank, double t_stop);
  template <class Rule, bool Framed>
  int run_majorant(const Rule& rule, double t_stop, std::uint64_t event_target);
  bool advance_blocks(double t_target, std::uint64_t event_target, bool exact_events, std::uint64_t event_limit,
                      bool to_step_end);
  /// The length of a blocked step that starts now at candidate rate `rate` (header "Blocks", "Step length");
  /// `acceptance_unknown`: the last step's acceptance is another sampler's (block_steps mean free times).
  double block_step_length(double rate, bool acceptance_unknown = false) const;
  void set_whole_gas_bound();       ///< bound_, rate_ and range of a whole-gas step (with blocks)
  /// With blocks: an exact target given inside a step ends the step here when its rest could pass it.
  void end_step_at_target(std::uint64_t exact_target);
  /// With blocks, at a step's start: the last step's acceptance, the gas's bounds from the blocks', the
  /// step's sampler (`sampler_changed`: not the last step's) and its candidate rate R.
  double blocked_step_rate(bool& sampler_changed);
  /// With blocks: the step of length `step` at rate R shortened near an exact event target, or run on the
  /// whole gas (whole_step_) when too few events are left for a blocked one (header "Blocks").
  double approach_target(double step, double rate, std::uint64_t exact_target, bool sampler_changed);
  /// With blocks: min(N/64, 4 N/K), the fewest events left to a target that a blocked step approaches.
  double fewest_block_events() const;
  /// With blocks: lengthens a whole-gas step that ended short of `exact_target` (true), instead of a new
  /// step, while fewer than fewest_block_events() are left.
  bool extend_whole_step(std::uint64_t exact_target);
  /// With blocks: starts the step of length `step` at candidate rate `rate` (a remix, the whole gas's exact
  /// bound, or neither: keeps_blocks_), and its probe when it is long and `exact_target` is set.
  void begin_blocked_step(double step, double rate, bool exact_target);
  bool keeps_blocks_ = false;       ///< with blocks: this step approaches an exact event target and keeps the last step's blocks (no remix)
  bool whole_step_ = false;         ///< with blocks: this step runs on the whole gas (near an event target)
  double step_acceptance_ = 0.0;    ///< with blocks: events per candidate in the last step
  std::uint64_t step_events_start_ = 0, step_candidates_start_ = 0;  ///< counters at this step's start
  double step_planned_candidates_ = 0.0;  ///< with blocks: R dt of this step as begun (0: not known, an older checkpoint)
  /// With blocks, a step longer than block_steps mean free times (header "Event targets"): its probe, the
  /// counts of its first block_steps mean free times, taken at probe_time_ (none, pending, measured).
  enum class Probe { none, pending, measured };
  Probe probe_ = Probe::none;
  double probe_time_ = 0.0;
  std::uint64_t probe_events_ = 0, probe_candidates_ = 0;  ///< since the step's start, once measured
  std::vector<std::array<std::uint64_t, 2>> block_probe_;  ///< the pass holding probe_time_: each block's events, candidates before it
  /// With blocks: the acceptance a step near an exact target expects (approach_target), at candidate rate
  /// `rate`; `cooling_probe`: taken from the last step's probe, its events per unit time having fallen after it.
  struct ApproachAcceptance {
    double value;
    bool cooling_probe;
  };
  ApproachAcceptance approach_acceptance(double rate, bool sampler_changed) const;
  double short_step_candidates() const;                ///< block_steps mean free times' candidates, N block_steps step_fraction / 2
  bool is_long_step(double candidates) const;          ///< more than 1.01 short_step_candidates()
  void remix();
  // Blocks (empty block_first_: none). Candidates are drawn in [range_first_, + range_count_).
  std::vector<std::size_t> block_first_;  ///< K + 1 boundaries
  std::vector<double> block_max_speed2_;  ///< vmax_k^2 of each block and species, K x S (raised within a step)
  std::vector<double> block_credit_;      ///< each block's carried candidate time
  std::size_t current_block_ = 0;
  /// A worker running block j (run_block): the block's vmax_k^2, in the master's block_max_speed2_.
  double* block_speed2_ = nullptr;
  double pass_density_ = 0.0;  ///< the gas's number density for a pass's block visits (run_blocks_pass; O(S) to sum)
  // Threads inside one replica (header): the workers, and each block's counts of the current pass.
  int threads_ = 1;
  std::vector<Collider> workers_;
  std::vector<Counters> block_counters_;
  /// In a frame: each block's change of the moments sum m u u^T in the pass, added in block order.
  std::vector<std::array<double, 4>> block_moments_;
  void make_workers();
  /// On a worker: block j of `master` over [t_start, t_stop), drawing from the stream (key, j); its
  /// counts go to master.block_counters_[j], its bounds and credit to the master's arrays.
  /// `probe`: inside (t_start, t_stop), the block's counts at that time go to master.block_probe_[j].
  void run_block(Collider& master, std::size_t j, double t_start, double t_stop, bool first_visit,
                 std::uint64_t key, double probe);
  void run_blocks_pass(double t_start, double t_stop);  ///< every block once, on the threads
  /// On a worker: the current block of one species with constant restitution up to t_stop, the
  /// `majorant` process of run_majorant in a loop of its own (header "Blocks", the kernel): raised
  /// bounds are handled inside. Leaves time_, credit_, bound_ and rate_ as run_substep does.
  template <class Rule, bool Track, bool Framed>
  void run_block_one_species(const Rule& rule, double t_stop);
  /// On a worker: the current block of a mixture with constant restitution up to t_stop, the process of
  /// run_majorant (`Lowrank` false) or run_lowrank (true) on the block's slices in a loop of its own
  /// (header "Mixtures in blocks", the kernel): raised bounds are handled inside. Leaves time_, credit_,
  /// bound_ and rate_ as run_substep does. `Two`: `majorant` with two species (their edge and
  /// offsets in locals); `Factored`: `lowrank` by the factored draw (block_factored_); `Separable`:
  /// `lowrank` by the separable draw (separable_blocks_).
  template <class Rule, bool Track, bool Lowrank, bool Framed, bool Two = false, bool Factored = false,
            bool Separable = false>
  void run_block_mixture(const Rule& rule, double t_stop);
  /// The mixture kernel's instance for the block's sampler (`lowrank` or `majorant`) and draw.
  template <class Rule, bool Track, bool Framed>
  void run_block_mixture_sampler(const Rule& rule, bool lowrank, double t_stop);
  /// A rule without frames runs framed only in the identity frame (reset_frame: white noise); throws
  /// std::logic_error otherwise.
  void require_identity_frame() const;
  /// The constants of species pair (k, j) in the mixture block kernel, row-major S x S (at most
  /// block_species_limit species): the rule's projected constants (rules.hpp; the kernels run only a
  /// rule with the projection, SmoothRule) and the pair's slot in the event counts, in one record of
  /// 32 bytes read only for a collision.
  struct PairKernel {
    rules::SmoothRule::Projected constants;  ///< share_a, share_b, loss
    std::uint32_t event;  ///< min(k, j) S + max(k, j): the slot in Counters::pair_events (0 without them)
  };
  std::vector<PairKernel> pair_kernel_;
  /// The acceptance's constants of pair k S + j, read for every candidate (PairKernel only for a
  /// collision): (pi sigma_kj^2 chi_kj)^2, the `majorant` acceptance compared squared, and for `lowrank`
  /// in blocks w_k + w_j, the acceptance |g| / (w_k + w_j) (set_block_lowrank).
  std::vector<double> pair_cross_section2_, pair_limit_;
  std::vector<std::uint32_t> pair_species_;  ///< (k, j) of pair k S + j, 2 per pair
  /// A mixture with `lowrank` in blocks: each block samples its own low-rank A_ik (header "Mixtures in blocks").
  bool lowrank_blocks() const { return scheme_ == Scheme::lowrank && s_ > 1 && !block_first_.empty(); }
  BlockSampler block_sampler_ = BlockSampler::cheaper;
  bool block_lowrank_ = false;  ///< the blocks of this step run the `lowrank` sampler (choose_block_lowrank)
  /// The step's block sampler from the gas's bounds max_speed2_ (header "Mixtures in blocks", "The cheaper
  /// sampler"): the two block_candidate_rate() weighed by lowrank_candidate_cost.
  bool choose_block_lowrank() const;
  /// sum_ik pi sigma_ik^2 chi_ik w_i N_i N_k n/(N - 1) over the gas's species (w_i = sqrt(max_speed2[i])):
  /// the blocks' `lowrank` candidate rate summed over the blocks, to within the slices' rounding.
  double lowrank_block_rate(const double* max_speed2) const;
  /// On a worker: the current block's A_ik, their alias table and R (`measure_speeds`: set_block_separable).
  void set_block_lowrank(double n, bool measure_speeds = false);
  /// The one-word draw's alias cells and outcomes over the P^2 pairs of the P `present_species` (running
  /// counts `cum`), and rate_ = R_b (set_block_lowrank).
  void set_block_one_word(const std::uint32_t* present_species, std::size_t p, const std::size_t* cum);
  std::vector<double> pair_weights_;   ///< a block's A_ik, S x S (set_block_lowrank; factored: a table's weights)
  segment_tree::AliasTable pair_alias_;  ///< over the S^2 pairs (run_lowrank in a block: viscoelastic)
  /// The mixture kernel's draw of a `lowrank` candidate from one 64-bit word (header "Mixtures in blocks"):
  /// an alias table over 2^m >= max(P^2, 2) cells (the pairs, then zero weights), the cell from the top m
  /// bits, its coin from the next 16 - m, two 24-bit halves for the particles (Lemire, exact by rejection).
  struct LowrankOutcome {
    std::uint32_t first_i, count_i, first_k, count_k;  ///< the slices of species i and k (system indices)
    std::uint32_t reject_i, reject_k;                  ///< 2^24 mod count: a 24-bit half below it is rejected (2^24: every one, below_pair draws)
    std::uint32_t pair;                                ///< i S + k: the pair's PairKernel (and pair_species_)
  };
  struct LowrankCell {
    double fraction;        ///< t 2^c - whole, t the cell's alias threshold, c = 16 - m coin bits
    std::uint32_t whole;    ///< floor(t 2^c): the coin q keeps the cell if q < whole (q = whole: fraction decides)
    std::uint32_t keep;     ///< the cell's outcome (the pair it stands for)
    std::uint32_t other;    ///< its alias's outcome
  };
  std::vector<LowrankCell> lowrank_cells_;        ///< P cells (set_block_lowrank)
  /// The factored draw (header "Mixtures in blocks", \ref sch_factored "docs/schemes.md"), for blocks with
  /// more than factor_above_ species present: the row i from the row table over the P present species
  /// (weights w_i rho_i ||G||), then the column k from row i's own table (weights q_k|i); the particles
  /// from a second word. A species present in the block, in the order of the tables:
  struct FactoredSpecies {
    std::uint32_t first, count;  ///< the species' slice in the block (system indices)
    std::uint32_t reject;        ///< 2^24 mod count: a 24-bit field below it is rejected (2^24: all, below_pair draws)
    std::uint32_t pair_row;      ///< i S: the pair (i, k)'s index (PairKernel, pair_species_) is pair_row + k
    std::uint32_t species;       ///< i
  };
  /// An alias cell of the factored draw in 8 bytes (the column tables, P 2^m cells, are read at random
  /// for every candidate): the coin's c = 32 - m bits q keep the cell if q < whole = floor(t 2^c), t the
  /// cell's alias threshold (on a tie its fraction t 2^c - whole, in an array of its own, decides);
  /// outcomes are indices of present species (P <= block_species_limit < 2^16).
  struct FactoredCell {
    std::uint32_t whole;
    std::uint16_t keep, other;  ///< the cell's own outcome, its alias's
  };
  static_assert(block_species_limit < (std::size_t{1} << 16), "FactoredCell holds species in 16 bits");
  /// The current block's factored tables (set_block_factored).
  struct FactoredTables {
    std::vector<FactoredSpecies> species;  ///< the P species present
    std::vector<FactoredCell> rows;        ///< 2^m cells: w_i rho_i ||G|| (rebuilt when a bound is raised)
    std::vector<FactoredCell> columns;     ///< P 2^m cells, row a's from a 2^m: q_k|i (built once per visit)
    std::vector<double> row_fraction, column_fraction;  ///< the cells' fractions
    /// w_i of each present species: the acceptance |g| / ((w_i + w_k) ||G||) from these (1 KB) rather
    /// than from pair_limit_ (S^2 doubles read at random)
    std::vector<double> w;
    std::vector<double> rho;  ///< rho_i = N_i sum_k pi sigma_ik^2 chi_ik N_k / V of each present species
    unsigned bits = 1;        ///< m: 2^m >= max(P, 2) cells per table
  };
  FactoredTables factored_;
  bool block_factored_ = false;  ///< the current block's `lowrank` draw is the factored one (set_block_lowrank)
  std::size_t factor_above_ = lowrank_factor_above;  ///< set_lowrank_factor_above (tests)
  std::size_t deep_above_ = separable_deep_above;    ///< set_separable_deep_above (tests)
  const std::atomic<bool>* stop_flag_ = nullptr;     ///< set_stop_flag
  bool stop_requested() const { return stop_flag_ && stop_flag_->load(std::memory_order_relaxed); }
  /// The factored tables as the kernel reads them (pointers into factored_; taken anew after a raise).
  struct FactoredView {
    const FactoredCell *rows, *columns;
    const double *row_fraction, *column_fraction, *w;
    const FactoredSpecies* species;
    unsigned bits;
  };
  FactoredView factored_view() const {
    return {factored_.rows.data(), factored_.columns.data(), factored_.row_fraction.data(),
            factored_.column_fraction.data(), factored_.w.data(), factored_.species.data(), factored_.bits};
  }
  /// The factored tables of the current block over its P `present` species (running counts `cum`),
  /// and rate_ = R_b.
  void set_block_factored(const std::uint32_t* present, std::size_t p, const std::size_t* cum);
  void build_factored_rows();   ///< the row cells from w_i rho_i ||G||, and rate_ = R_b = sum_i w_i rho_i ||G||
  void raise_block_factored();  ///< after a raised bound: w_i and the rows (the columns hold no speed)
  /// The separable draw (header "Mixtures in blocks", \ref sch_separable "docs/schemes.md"), for blocks of a
  /// mixture of more than separable_above species: the rank-3 A_ik of segment_tree.hpp with chi_max and
  /// w_i = W_b / sqrt(m_i), W_b^2 = max m_k |v|^2 over the block, so that a raised bound scales every row
  /// alike and no table is rebuilt. A species present in the block, in the order of the tables:
  struct SeparableSpecies {
    std::uint32_t first, count;  ///< the species' slice in the block (system indices)
    std::uint32_t reject;        ///< 2^24 mod count (as FactoredSpecies)
    std::uint32_t species;       ///< i
    double inverse_root_mass;    ///< 1/sqrt(m_i): w_i = W_b / sqrt(m_i)
    double mass;                 ///< m_i (32 bytes in all: two entries to a cache line)
  };
  /// An alias cell of the separable draw in 8 bytes, as FactoredCell (use_blocks: P <= S < 2^16), so that the
  /// six tables of 10000 species (0.8 MB) stay in a 1 MiB L2 beside the block.
  struct SeparableCell {
    std::uint32_t whole;
    std::uint16_t keep, other;
  };
  /// SeparableCell's 16-bit outcomes hold at most this many present species: beyond this many species the
  /// separable blocks hold at most separable_block_limit particles on average (separable_block_count).
  static constexpr std::size_t separable_species_limit = 65535;
  /// The separable blocks' mean size beyond separable_species_limit species: a block's count, multinomial
  /// about its mean when every species is scattered, stays below 2^16 by over 12 standard deviations (a
  /// chance below 1e-30); 1e6 particles make 16 blocks, each visit's six tables of 2^16 cells whatever its size.
  static constexpr std::size_t separable_block_limit = 62500;
  /// The separable blocks hold at least this many particles per species on average (separable_block_count):
  /// a visit builds six tables of about S cells, which blocks of fewer particles would rebuild more often.
  static constexpr std::size_t separable_particles_per_species = 8;
  /// ... but there are at least this many blocks, where N div block_size allows them: so many threads
  /// share a replica's blocks (the count cannot follow the threads: a checkpoint resumes on any number).
  static constexpr std::size_t separable_min_blocks = 16;
  /// The current block's separable tables (set_block_separable), built once per visit: none holds a speed.
  /// Term r of A_ik = sum_r u_i^(r) v_k^(r) (segment_tree.hpp's hard_sphere_factors) is drawn first, then
  /// the row from u^(r) and the column from v^(r), independently (two table reads in parallel).
  struct SeparableTables {
    std::vector<SeparableSpecies> species;              ///< the P species present
    std::vector<SeparableCell> rows;                    ///< 3 2^m cells, term r's from r 2^m: N_i (sigma_i^2, 2 sigma_i, 1)_r / sqrt(m_i)
    std::vector<SeparableCell> columns;                 ///< 3 2^m cells: N_k (1, sigma_k, sigma_k^2)_r
    std::vector<double> row_fraction, column_fraction;  ///< the cells' fractions
    double term0 = 1.0, term01 = 1.0;  ///< term r = 0 for a uniform below term0, 1 below term01, else 2
    double scale = 0.0;    ///< R_b = scale W_b ||G||: pi chi_max/(4V) times the terms' sum
    double energy2 = 0.0;  ///< W_b^2 = max over the block's species of m_k vmax_k^2
    unsigned bits = 1;     ///< m: 2^m >= max(P, 2) cells per table
  };
  SeparableTables separable_;
  bool separable_blocks_ = false;  ///< blocks of more than separable_above species (use_blocks): the separable draw
  struct SeparableView {
    const SeparableCell *rows, *columns;
    const double *row_fraction, *column_fraction;
    const SeparableSpecies* species;
    double term0, term01;
    unsigned bits;
  };
  SeparableView separable_view() const {
    return {separable_.rows.data(),    separable_.columns.data(), separable_.row_fraction.data(),
            separable_.column_fraction.data(), separable_.species.data(), separable_.term0,
            separable_.term01,         separable_.bits};
  }
  /// The separable tables of the current block (running counts `cum`), and rate_ = R_b; with `measure_speeds`
  /// (a first visit) the block's exact bounds in the same pass over its slices, as set_block_max_speed2.
  void set_block_separable(const std::size_t* cum, bool measure_speeds);
  static constexpr std::size_t separable_prefetch_ahead = 16;  ///< (set_block_separable's reads of the slices)
  /// The candidate rate of the separable blocks summed over them at the gas's bounds max_speed2_ (within
  /// the slices' rounding; W the largest of the blocks' W_b, so a bound of it).
  double separable_block_rate() const;
  /// Alias cells of c = 32 - `bits` coin bits from the 2^bits weights `w` (zero-padded past the `p`
  /// outcomes), handed over by pair_alias_.build_cells (no table of its own in between): a cell's own
  /// outcome is its index, a padding cell's its alias.
  template <class Cell>
  void fill_alias_cells(const std::vector<double>& w, std::size_t p, unsigned bits, Cell* out, double* fraction);
  /// `lowrank`'s separable candidate in a block in three stages, so that what each reads at random was
  /// prefetched a few candidates before: `separable_words` draws its three 64-bit words and prefetches the
  /// two table cells they name; `separable_cells` reads them (the present species' indices `row`, of a,
  /// and `column`, of b) and prefetches the two species' entries; `separable_candidate` reads those: the
  /// particles a and b. The entries are read a stage after the cells beyond separable_deep_above present
  /// species, where tables and entries outgrow the core's L2; with the cells below, where the further
  /// stage costs more than it saves (docs/performance.md, perf_separable_sized).
  struct SeparableWords {
    std::uint64_t cells, particles;       ///< the cells' word, the particles' word
    std::uint32_t row_index, column_index;  ///< the cells in rows and columns
    std::uint32_t row, column;              ///< the present species drawn from them (separable_cells)
  };
  template <class Gen>
  static void separable_words(Gen& gen, const SeparableView& tables, SeparableWords& words);
  template <class Gen>
  static void separable_cells(Gen& gen, const SeparableView& tables, SeparableWords& words);
  template <class Gen>
  static void separable_candidate(Gen& gen, const SeparableView& tables, const SeparableWords& words,
                                  std::uint32_t& a, std::uint32_t& b);
  /// `lowrank`'s factored candidate in a block from two 64-bit words: particles a, b, the pair i S + k and
  /// the present species' indices of i and k (row_column = row | column << 16, for the acceptance).
  template <class Gen>
  static void factored_candidate(Gen& gen, const FactoredView& tables, std::uint32_t& a, std::uint32_t& b,
                                 std::uint32_t& pair, std::uint32_t& row_column);
  /// `lowrank`'s candidate in a block from one 64-bit word (header "Mixtures in blocks"): particles a,
  /// b and the pair i S + k, by the block's cells and outcomes (collide_kernels.cpp). Its cell and coin
  /// share 16 bits: 2^m >= P^2 cells leave 16 - m >= 0 coin bits for every P up to the limit.
  static_assert(block_species_limit * block_species_limit <= (std::size_t{1} << 16),
                "the one-word draw's cell index and coin share 16 bits of a candidate's word");
  template <class Gen>
  static void lowrank_candidate(Gen& gen, const LowrankCell* cells, const LowrankOutcome* outcomes, unsigned cell_bits,
                                std::uint32_t& a, std::uint32_t& b, std::uint32_t& pair);
  /// The mixture kernel's collision of a (species i) and b (species k): the rule's projected form with
  /// p = (g.e) e (in a frame along G^-1 p, the moments following); the energy lost.
  template <class Rule, bool Framed>
  double kernel_collision(const PairKernel& pk, std::uint32_t i, std::uint32_t k, particles::Vec3& va, particles::Vec3& vb,
                          double g_dot_e2, const particles::Vec3& p, std::array<double, 4>& moments) const;
  /// The mixture kernel after a raised bound: the block's A_ik (`lowrank`) or B_b and R_b anew.
  template <bool Lowrank, bool Framed>
  void after_raise(const std::size_t* cum, std::uint32_t n, double* speed2);
  std::vector<LowrankOutcome> lowrank_outcomes_;  ///< P^2 outcomes, the pairs of the P species present in the block
  unsigned lowrank_cell_bits_ = 0;                ///< m
  double step_start_ = 0.0;
  double remix_time_ = 0.0;  ///< with blocks: when the blocks were last dealt (a remix, or the first step)
  /// Exact vmax_k^2 of block j's slices, read in order, into out[k].
  void set_block_max_speed2(std::size_t block, double* out);
  /// max_kj pi sigma_kj^2 chi_kj (vmax_k + vmax_j), over the species present in a block when its running
  /// counts `cum` are given (a scattered species may have none there), else over all species
  double mixture_bound(const double* max_speed2, const std::size_t* cum = nullptr) const;
  /// Slices (header "Blocks"): species k's particles of block j are [slice_first_[j S + k], + count),
  /// count = slice_cum_[j (S+1) + k + 1] - slice_cum_[j (S+1) + k]; cum is the block's running count.
  /// The master's only (make_workers): a worker reads them through slice_owner_.
  std::vector<std::size_t> slice_first_, slice_cum_;
  /// The collider whose slices this one's blocks read: its master (run_block), nullptr for the master itself.
  const Collider* slice_owner_ = nullptr;
  /// Block j's slice starts (S) and running counts (S + 1), from the slices' owner.
  const std::size_t* slice_first_of(std::size_t j) const {
    return (slice_owner_ != nullptr ? *slice_owner_ : *this).slice_first_.data() + j * s_;
  }
  const std::size_t* slice_cum_of(std::size_t j) const {  ///< (as slice_first_of)
    return (slice_owner_ != nullptr ? *slice_owner_ : *this).slice_cum_.data() + j * (s_ + 1);
  }
  const std::size_t* block_slice_first() const { return slice_first_of(current_block_); }  ///< the current block's
  const std::size_t* block_slice_cum() const { return slice_cum_of(current_block_); }      ///< the current block's
  /// A species with at least min_slice K particles is dealt round the K blocks in equal slices; a rarer
  /// one is scattered (header "Mixtures in blocks": each particle to a uniformly random block, anew at
  /// every remix).
  static constexpr std::size_t min_slice = 64;
  std::vector<std::uint8_t> scattered_;   ///< per species: 1 if scattered (with blocks)
  bool scattered_any_ = false;
  std::vector<std::size_t> slice_count_;  ///< each block's count of each species, K x S
  /// Shuffles every scattered species' particles and draws their slice counts (deal.hpp scatter): the draws
  /// in species order from the stream, in chunks of at most scatter_chunk partners, each chunk's
  /// transpositions then on the block threads, a species a thread (their ranges are apart), so that the
  /// result does not depend on the threads.
  void scatter_species();
  static constexpr std::size_t scatter_chunk = std::size_t{1} << 18;
  std::vector<std::uint32_t> scatter_partners_;  ///< a chunk's transpositions (deal.hpp scatter_draws)
  void set_slices();                      ///< slice_first_, slice_cum_ and block_first_ from slice_count_
  /// With blocks a step is this many majorant mean free times (times step_fraction): each block
  /// is then visited for about one collision per particle, which repays bringing it into the cache.
  static constexpr double block_steps = 5.0;
  /// ... or longer, to block_step_collisions_ collisions per particle (header "Blocks", "Step length"),
  /// which is at most this many (an elastic gas's bounds do not loosen within a step) ...
  static constexpr double block_step_collisions_max = 6.0;
  double block_step_collisions_ = 0.0;  ///< 0: block_steps mean free times (viscoelastic restitution)
  /// ... and of at most this many candidates (3/4 of 2^24, about 0.25 s of work) when longer than
  /// block_steps: the simulation's chunks of 2^24 candidates at the last step's rate then end at its
  /// end, not just before it, even after the rate fell by a quarter from one step to the next.
  static constexpr double max_block_step_candidates = 12582912.0;
  std::size_t range_first_ = 0, range_count_ = 0;
  deal::Workspace remix_workspace_;  ///< remix() deals the particles in place with this (deal.hpp)
  /// ... and, on several threads, the species of fewer than N/(4 threads) particles with these, one per thread
  std::vector<deal::Workspace> species_workspaces_;
  /// remix()'s deal of a mixture's species that are not scattered, from their starting points `offset`.
  void deal_species(const std::vector<std::size_t>& offset);
  template <class Rule, bool Framed>
  int run_pairs(const Rule& rule, double t_stop, std::uint64_t event_target);
  template <class Rule, bool Framed>
  int run_lowrank(const Rule& rule, double t_stop, std::uint64_t event_target);
  /// Species k's factors of the low-rank majorant (row scaled by chi_max) at the current vmax_k.
  segment_tree::HardSphereFactors lowrank_factors(std::size_t species) const;
  void set_lowrank_row(std::size_t species);
  void count_event(std::uint32_t k, std::uint32_t j);
  /// The general loops' collision of particles a (species k) and b (species j) along e with `g_dot_e`
  /// of the actual velocities: the rule (rules.hpp) on the stored velocities (in a frame along G^-1 e,
  /// the frame's moments following them: header "Frame"), the energy lost added up, the event counted.
  template <class Rule, bool Framed>
  rules::Outcome collide_pair(const Rule& rule, std::size_t a, std::size_t b, std::uint32_t k, std::uint32_t j,
                              double ex, double ey, double ez, double g_dot_e) {
    rules::Contact contact{ex, ey, ez, g_dot_e, ex, ey, ez};
    particles::Vec3& ua = sys_.v[a];
    particles::Vec3& ub = sys_.v[b];
    rules::Outcome out;
    if constexpr (Framed) {
      const particles::Vec3 w = to_stored(ex, ey, ez);  // G^-1 e
      contact.dx = w.x, contact.dy = w.y, contact.dz = w.z;
      const double ma = mix_.mass[k], mb = mix_.mass[j];
      // The moments change by m (u'u'^T - u u^T) for each partner.
      add_moments(moments_, ua, -ma);
      add_moments(moments_, ub, -mb);
      out = rule.collide(sys_, a, b, rule.pair(k, j), contact);
      add_moments(moments_, ua, ma);
      add_moments(moments_, ub, mb);
    } else {
      out = rule.collide(sys_, a, b, rule.pair(k, j), contact);
    }
    counters_.dissipated += out.loss;
    count_event(k, j);
    return out;
  }
  /// The actual relative velocity G g of a stored one (header, "Frame"); the identity without a frame.
  template <bool Framed>
  void to_actual(double& gx, double& gy, double& gz) const {
    if constexpr (Framed) {
      gx = frame_scale_ * (gx + frame_shear_ * gy);
      gy *= frame_scale_;
      gz *= frame_scale_;
    }
  }
  /// G^-1 w of an actual vector w (header, "Frame"): the change of the stored u for an impulse along w.
  particles::Vec3 to_stored(double wx, double wy, double wz) const {
    return {(wx - frame_shear_ * wy) * frame_inverse_scale_, wy * frame_inverse_scale_, wz * frame_inverse_scale_};
  }
  /// q += w u u^T in the frame's four moments (xx, yy, zz, xy).
  static void add_moments(std::array<double, 4>& q, const particles::Vec3& u, double w) {
    q[0] += w * u.x * u.x, q[1] += w * u.y * u.y, q[2] += w * u.z * u.z;
    q[3] += w * u.x * u.y;
  }

  /// An acceptance probability `p` > 1 (header of Counters::overshoots); kept out of line, it never
  /// happens in a correct run. A pair at the bound itself (two particles of zero total momentum have
  /// g = 2 v_max exactly) gives p = 1 within round-off, 1 + 2e-16: not an overshoot, and no bias.
  [[gnu::cold]] void note_overshoot(double p) {
    if (p <= 1.0 + 1e-12) return;
    ++counters_.overshoots;
    counters_.largest_acceptance = std::max(counters_.largest_acceptance, p);
  }

  /// A candidate drawn ahead: particles a and b, of species i and k (lowrank; 0 otherwise).
  struct PendingPair {
    std::uint32_t a, b, i, k;
  };
  static constexpr std::size_t lookahead = 8;  ///< candidates drawn ahead (header, "Look-ahead")
  /// The same in the block kernels: more in a frame, whose stages leave the blocks out of the caches (header "Look-ahead").
  template <bool Framed>
  static constexpr std::size_t block_lookahead = Framed ? 32 : 8;
  void prefetch(const PendingPair& p) const;
  /// The oldest drawn-ahead candidate; `draw()` replaces it at the end of the queue.
  template <class Draw>
  PendingPair next_pair(Draw&& draw);
  std::array<PendingPair, lookahead> pending_{};
  std::size_t pending_next_ = 0;
  bool pending_filled_ = false;

  Scheme scheme_;
  const species::Mixture& mix_;
  particles::System& sys_;
  rng::Xoshiro256pp gen_;
  double step_fraction_;
  std::size_t s_;
  bool tables_;  ///< pair constants stored as S x S tables (all but lowrank with very many species)
  std::vector<double> cross_section_;   ///< pi sigma_kj^2 chi_kj, row-major S x S
  rules::Rule rule_;                    ///< what a collision does (rules.hpp)
  /// The rule has the projection option (rules.hpp), which the block kernels need; without it
  /// (viscoelastic) the blocks run the general loops.
  bool kernels_ = true;
  std::vector<double> max_speed_;       ///< vmax_k
  std::vector<double> max_speed2_;      ///< vmax_k^2
  std::vector<std::size_t> raised_;     ///< species whose vmax was raised since the last rebuild
  segment_tree::LowRankSampler<3> lowrank_;  ///< A_ik (lowrank)
  double chi_max_ = 1.0;                ///< max_ik chi_ik (lowrank)
  double shear_rate_ = 0.0;             ///< a of set_shear (pairs, Enskog)
  std::vector<double> contact_;         ///< sigma_ij (set_shear)
  double lowrank_volume_ = 0.0;         ///< V = (N - 1)/n (lowrank)
  bool framed_ = false;                 ///< velocities stored in a frame (set_frame)
  double frame_scale_ = 1.0, frame_shear_ = 0.0;  ///< S and c of the frame
  double frame_inverse_scale_ = 1.0;    ///< 1/S, set with S (to_stored needs no division per collision)
  double speed_factor_ = 1.0;           ///< ||G|| (frame_norm), 1 without a frame: every bound's factor
  std::array<double, 4> moments_{};     ///< sum m u u^T: xx, yy, zz, xy (in a frame)
  bool lowrank_columns_set_ = false;    ///< columns v_k set and frozen (they never change in a run)
  // Bounds.
  double bound_ = 0.0;                  ///< B (majorant)
  std::vector<double> pair_rate_;       ///< R_ij (pairs), cumulative in pair_cumulative_
  std::vector<double> pair_cumulative_;
  double rate_ = 0.0;                   ///< total candidate rate R
  double time_ = 0.0;
  double credit_ = 0.0;          ///< time since the last candidate, carried between sub-steps
  double next_step_time_ = 0.0;  ///< when the bounds are next recomputed
  Counters counters_;
};


}  // namespace gdsmc::collide
