/**
 * \file agg_frag.hpp
 * \brief Aggregation and fragmentation: a gas of clusters that stick and shatter on collision
 *        (DSMC notes, eqs. (8)-(14) and its steps 1-13, as corrected by \ref af_outcome "docs/agg-frag.md"; docs/physics.md,
 *        "Aggregation and fragmentation").
 *
 * **Clusters.** A cluster of k monomers has mass m_k = k m_1 and diameter sigma_k = k^(1/3) sigma_1
 * (contact distance sigma_kj = (sigma_k + sigma_j)/2); the cluster size is its species. The run starts
 * from N_0 monomers at temperature T_0 (&system gives the monomer: one species), and the number N of
 * simulated clusters changes: aggregation N - 1, fragmentation N + K - 2, never above N_0.
 *
 * **Outcome of a collision** of clusters a (size k) and b (size j), g = v_a - v_b,
 * m_kj = m_k m_j/(m_k + m_j), V = (m_k v_a + m_j v_b)/(m_k + m_j), classified in this order:
 * - E_imp = m_kj g^2/2 < E_agg: **aggregation**, one cluster of k + j monomers with velocity V
 *   (energy lost: exactly E_imp);
 * - else, with e drawn as in collide.hpp (density ~ g_hat.e on the hemisphere, \ref cm_hemisphere "docs/collision-model.md"),
 *   E_n = m_kj (g.e)^2/2 > E_frag and k + j >= 3: **fragmentation** into K = k + j monomers,
 *   v_i = V + u d_i, u = sqrt(k j) eps_f |g|/K, |d_i| = 1, sum_i d_i = 0 (\ref af_corrections "docs/agg-frag.md": K/2 random
 *   unit vectors and their opposites; for odd K, (K - 3)/2 such pairs and one equilateral triple
 *   a, -a/2 + (sqrt3/2) b, -a/2 - (sqrt3/2) b with b perpendicular to a). The centre-of-mass
 *   kinetic energy after is K m_1 u^2/2 = eps_f^2 E_imp, so (1 - eps_f^2) E_imp is lost. The DSMC notes'
 *   eq. (14) (K - 1 random vectors and one balancing monomer) creates energy on average: not used.
 *   Two monomers never shatter;
 * - else: **bounce**, the collision rule of \ref cm_rule "docs/collision-model.md" with the monomer restitution alpha
 *   (energy lost (1 - alpha^2) E_n).
 * The thresholds are energies, so the velocity thresholds depend on the pair (\ref af_outcome "docs/agg-frag.md").
 *
 * **Scheme.** The continuous-time low-rank scheme of Bodrova and Osinsky 2024, \ref sch_lowrank "docs/schemes.md" (eqs 9-14; collide.hpp `lowrank`,
 * segment_tree.hpp) with the cluster sizes as species: the ordered size pair (i, k) of a candidate
 * is drawn from the rank-3 majorant A_ik = pi sigma_ik^2 w_i N_i N_k / V (w_i the largest speed of
 * size i, V = (N_0 - 1)/n_1 the fixed volume: F_N and V stay fixed, only N changes, \ref af_scheme "docs/agg-frag.md"),
 * then a cluster of each size uniformly, the same cluster twice rejected, accepted with
 * |g|/(w_i + w_k). Every unordered cluster pair thus collides at pi sigma_ik^2 |g|/V, the rate of
 * the DSMC notes, eq. (8), \ref af_scheme "docs/agg-frag.md" with the current N (N(N - 1)/2 pairs). After each event the counts N_k, the bounds
 * w_k and so the trees change in O(log K) per changed size, and the next candidate comes after
 * 1/R of the new total R: time advances per candidate with the current population, so there is no
 * time-step bias (\ref af_scheme "docs/agg-frag.md": a time-stepped scheme with a fixed candidate count per step is biased
 * by |d ln N/dt| dt). A size that empties has w = 0 and reappears with the speed of its first
 * member; at every step start (step_fraction majorant mean free times) all w_k are recomputed
 * exactly. Post-collision speeds above w_k raise it at once (fragments can outrun both parents).
 *
 * **Cache blocks** (\ref af_blocks "docs/agg-frag.md"; `use_blocks`, the `&dsmc` block_size of io/config.hpp; at
 * N >= 2 block_size clusters). At N = 1e6 the clusters' velocities (24 MB) do not fit in the cache, and each
 * candidate reads two at random: the unblocked loop runs at the speed of the memory (measured:
 * \ref perf_agg_frag "docs/performance.md"). A blocked step therefore deals the N
 * clusters into K = N div block_size blocks by a uniformly random partition (a Fisher-Yates shuffle of
 * the block labels, K - N mod K blocks of N div K and N mod K of one more; the clusters, read size by
 * size in order, go to the block of their label), and each block b of n_b clusters runs the scheme
 * above as a gas of its own for the step, with the fixed volume
 *   V_b = V (n_b - 1)/(N - 1)
 * (\ref af_blocks "docs/agg-frag.md"). Two given clusters share block b with probability n_b (n_b -
 * 1)/(N (N - 1)), and there collide at pi sigma_ik^2 |g|/V_b, so the expected rate of every pair,
 * summed over the blocks, is sum_b n_b/N pi sigma_ik^2 |g|/V = pi sigma_ik^2 |g|/V: the unblocked rate
 * exactly, for every pair of sizes. What changes within a step is that a cluster's partners are the
 * n_b - 1 of its block (their composition fluctuates by O(1/sqrt(n_b)) around the gas's), and the
 * products of a block's events meet only that block until the next deal: a finite-N effect of order
 * 1/n_b, as for the particle blocks (collide.hpp, "Blocks"), checked by AggFrag.BlockedMatchesUnblocked
 * (N_1, aggregations, fragmentations, kinetic energy over replicas, within 4 combined standard errors)
 * and by the Smoluchowski validation, whose runs of 2e5 to 1e6 monomers are blocked. A block starts its
 * candidate clock at a uniformly random phase (credit u/R_b), so that its expected candidate count over
 * the step is R_b dt, not one less. A blocked step is block_steps (20) majorant mean free times of the
 * whole gas, at most max_block_step_candidates (2^24; each block notices a Ctrl-C every 2^16 of its
 * candidates), ending at t_target; after it the clusters are gathered back block by block in order, the
 * bounds recomputed exactly and the sampler rebuilt. Within a block the bounds are exact again at every
 * step_fraction mean free times of its own, so the blocked step's length sets how often the gas is
 * dealt (an O(N) pass: \ref perf_agg_frag "docs/performance.md") and how long an event's products meet only
 * their block's members, not the acceptance. Event targets: a blocked step is cut so that its expected
 * events stay below the target with margins (target_step_candidates: C candidates with
 * 1.1 p C + 8 sqrt(p C) + 16 at most the events left, p twice the run's events per candidate once the run
 * has made min_events_for_acceptance events, else 1), and one shorter than half a mean free time runs on
 * the whole gas instead, which stops at the target exactly. A blocked step that passed the target would
 * be reported as an error: it would need the step's events per candidate at more than about 2.2 times the
 * run's so far, or an excess of 8 standard deviations (the ratio measured over many gases: \ref perf_agg_frag
 * "docs/performance.md"). **Threads:** the blocks of a step are independent; block b draws from
 * rng::Xoshiro256pp::substream(key, b), the key one draw of the gas's own stream per step, and the
 * counters and clusters are gathered in block order, so the output is bit for bit the same on any
 * thread count (AggFrag.BlockThreadsAreBitwiseTheSame, scale_out.reproducibility_agg_frag). The deal runs
 * on the same threads (the gas's order cut into one part per thread; a part's clusters take the places in
 * a block list after those of the parts before it, counted first), so does the gather (block b's clusters
 * after those of the blocks before it), and so does the pass
 * that recomputes the bounds of a list of 2^16 clusters or more (in parts; the largest of the parts' largest)
 * (AggFrag.LongListsAreDealtAndBoundedAlikeOnAnyThreadCount). **Memory:**
 * the clusters are held about once at every moment (24 bytes each, plus 4 for the labels): each
 * block's list is sized at its count and reserved at its count plus an eighth, its pages touched only as
 * they are written (particles::FillLaterArray), the pages of a whole-gas list already dealt are
 * returned to the system as the deal goes (every 64 KiB, 2 MiB in huge-page lists) (particles::release_pages) and the lists freed at
 * its end, and at the gather each block's list is released as soon as it is copied (peak and cost
 * measured: \ref perf_agg_frag "docs/performance.md").
 *
 * **Storage** (no allocation per event). The velocities of the clusters of size k are one array of
 * their own, lists[k] (Vec3, 24 bytes a cluster): "a random cluster of size k" is one draw and one
 * memory read, as in a plain gas, and a cluster is (size, place in its list). A removed cluster's
 * place is taken by the last of its list (swap with last); new clusters are appended. The lists grow
 * by doubling (amortised: no allocation per event); lists[1] starts reserved for N_0 monomers, and a
 * list that has shrunk to under a quarter of its capacity is trimmed at the next step start, so the
 * memory follows the population. Per-size tables (bounds, diameters, trees) grow by doubling up to
 * the largest size present. 24 bytes per initial monomer at t = 0.
 *
 * **Observables** (\ref af_observables "docs/agg-frag.md"): N_k; the kinetic energy of each size relative to
 * u = total momentum/total mass; T_k = m_k <|v - u|^2>/3 = (2/3) E_k/N_k; the per-cluster total
 * T = sum_k N_k T_k/N (it can rise while energy is lost: aggregation removes slow pairs); the
 * kinetic energy per initial monomer; cumulative collisions, aggregations and fragmentations.
 * The energy dissipated by each event is added up (`dissipated`), so E(t) + dissipated = E(0)
 * is an exact check of the bookkeeping.
 *
 * Namelist group: `&agg_frag` (io/config.hpp). Theory: theory/smoluchowski.hpp. Checked by
 * tests/agg_frag_test.cpp and validation/aggregation_fragmentation.
 */
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "dsmc/particles.hpp"
#include "dsmc/rng.hpp"
#include "dsmc/segment_tree.hpp"
#include "dsmc/state.hpp"

namespace gdsmc::agg_frag {

/// The monomer and the thresholds, in the user's units.
struct Model {
  double monomer_mass = 1.0;      ///< m_1
  double monomer_diameter = 1.0;  ///< sigma_1 (a cluster of k monomers: sigma_k = k^(1/3) sigma_1)
  double monomer_density = 0.1;  ///< n_1(0): the initial monomer density
  double restitution = 1.0;      ///< alpha of a bounce
  double aggregation_energy = 0.0;                                       ///< E_agg (0: none)
  double fragmentation_energy = std::numeric_limits<double>::infinity();  ///< E_frag (inf: none)
  double fragment_restitution = 1.0;                                     ///< eps_f
};

/// What a collision of two clusters does (\ref af_outcome "docs/agg-frag.md").
enum class Outcome : int {
  aggregation = 0,    ///< the pair sticks into one cluster
  fragmentation = 1,  ///< the pair shatters into monomers
  bounce = 2          ///< the collision rule with the monomer restitution
};

/// First test of \ref af_outcome "docs/agg-frag.md": the pair sticks (impact energy m_kj g^2/2 below E_agg).
inline bool sticks(const Model& m, double impact_energy) { return impact_energy < m.aggregation_energy; }
/// Second test of \ref af_outcome "docs/agg-frag.md": a pair of sizes k, j that did not stick shatters (normal energy
/// m_kj (g.e)^2/2 above E_frag, and at least three monomers to make).
inline bool shatters(const Model& m, std::uint32_t k, std::uint32_t j, double normal_energy) {
  return k + j >= 3 && normal_energy > m.fragmentation_energy;
}

/// Counts of one replica (the observables collisions, aggregations, fragmentations).
struct Counters {
  std::uint64_t events = 0;  ///< accepted collisions, whatever their outcome
  std::uint64_t aggregations = 0;    ///< events that stuck
  std::uint64_t fragmentations = 0;  ///< events that shattered
  std::uint64_t candidates = 0;      ///< candidate pairs drawn (accepted or not)
  std::uint64_t steps = 0;           ///< bound-refresh steps started
  double step_sum = 0.0;             ///< sum of the step lengths (mean_step() = step_sum / steps)
  double dissipated = 0.0;   ///< kinetic energy lost so far, added event by event (\ref af_observables "docs/agg-frag.md")
};

/// What one collision did (for the unit tests and the event bookkeeping).
struct Event {
  Outcome outcome = Outcome::bounce;  ///< what the collision did
  double impact_energy = 0.0;  ///< m_kj g^2/2
  double normal_energy = 0.0;  ///< m_kj (g.e)^2/2 (0 for an aggregation: e is not drawn)
  double ex = 0.0;  ///< unit vector e, x component (0 for an aggregation)
  double ey = 0.0;  ///< unit vector e, y component
  double ez = 0.0;  ///< unit vector e, z component
};

/// Per-size measurement of one replica at one instant (index k - 1 for size k, up to the largest
/// size present).
struct Measurement {
  std::vector<double> number;  ///< N_k
  std::vector<double> energy;  ///< E_k = sum over size-k clusters of m_k |v - u|^2/2
  double clusters = 0.0;       ///< N
  double kinetic_energy = 0.0; ///< sum_k E_k
};

/// One replica's cluster gas and its collision loop.
class Gas {
 public:
  /// N_0 = `monomers` monomers with velocities from `distribution` at `temperature` (zero total
  /// momentum, exact kinetic temperature: particles.hpp), drawn from `initial`; `check`: the caller's look
  /// at its interrupt flag during the draws (particles::SetUpCheck), which may throw.
  Gas(const Model& model, std::size_t monomers, double temperature, particles::InitialDistribution distribution,
      rng::Xoshiro256pp initial, rng::Xoshiro256pp collisions, double step_fraction,
      const particles::SetUpCheck& check = {});
  /// An empty gas of `model`: a cache block's, filled by the gas that owns it (header, "Cache blocks").
  explicit Gas(const Model& model) : model_(model), volume_(0.0), step_fraction_(1.0), gen_(0) {}
  /// Explicit clusters (unit tests): sizes and velocities, listed in this order within each size;
  /// the initial monomer count N_0 is the sum of the sizes.
  Gas(const Model& model, const std::vector<std::uint32_t>& sizes, const std::vector<particles::Vec3>& velocities,
      rng::Xoshiro256pp collisions, double step_fraction);

  /// Advances to `t_target` or until `event_target` collisions, whichever comes first; returns
  /// true when the event target stopped it (exactly at that event). With blocks, each blocked step
  /// ends at a step boundary, so a call ends within one step of t_target only if it is called with
  /// t_target at most block_step_end().
  bool advance(double t_target, std::uint64_t event_target = UINT64_MAX);
  /// A flag (the caller's interrupt flag) that, once set, makes advance() return false at the next
  /// step start, before its targets (as collide::Collider::set_stop_flag); the blocks of a blocked
  /// step (at most 2^24 candidates) stop as early, and the gas is then fit only to be discarded.
  /// nullptr (the default): never.
  void set_stop_flag(const std::atomic<bool>* flag) { stop_flag_ = flag; }

  /// Cache blocks of about `block_size` clusters (header, "Cache blocks"; 0: none), run on up to
  /// `threads` OpenMP threads. The results do not depend on `threads`.
  void use_blocks(std::size_t block_size, int threads = 1);
  /// Number of blocks the next step would use (1: the whole gas).
  std::size_t blocks() const;
  /// The threads set by use_blocks (1 by default).
  int threads() const { return block_threads_; }
  /// End of the blocked step that would start now (block_steps majorant mean free times, at most
  /// max_block_step_candidates); the time itself when the next step runs unblocked.
  double block_step_end() const;
  /// Blocked steps run so far.
  std::uint64_t blocked_steps() const { return blocked_steps_; }
  /// Majorant mean free times in a blocked step.
  static constexpr double block_steps = 20.0;
  /// The most candidates a blocked step holds (2^24).
  static constexpr double max_block_step_candidates = 16777216.0;
  /// The events after which a step towards an event target is sized at the run's acceptance (below them: at 1).
  static constexpr std::uint64_t min_events_for_acceptance = 1024;

  /// A cluster: its size and its place in the list of that size.
  struct Cluster {
    std::uint32_t size;   ///< number of monomers k (>= 1)
    std::uint32_t place;  ///< index in the list of size-k clusters
  };
  /// Collides two different clusters as an accepted candidate: classification, outcome and
  /// bookkeeping. Places of other clusters may change (swap with last). Public for the unit tests.
  Event collide(Cluster a, Cluster b);

  /// Simulation time reached.
  double time() const { return time_; }
  /// Event and candidate counts so far.
  const Counters& counters() const { return counters_; }
  /// Mean length in time of the bound-refresh steps (step_fraction majorant mean free times each).
  double mean_step() const { return counters_.steps ? counters_.step_sum / static_cast<double>(counters_.steps) : 0.0; }
  /// Number of clusters N now.
  std::size_t clusters() const { return clusters_; }
  /// N_0, the monomers at the start (the total mass in monomer units, conserved).
  std::size_t initial_monomers() const { return initial_monomers_; }
  /// Largest cluster size that has existed so far.
  std::size_t largest_size_reached() const { return largest_reached_; }
  /// N_k: number of clusters of `size` monomers (0 beyond the tables).
  std::size_t count(std::size_t size) const { return size < lists_.size() ? lists_[size].size() : 0; }
  /// Velocity of cluster `c`.
  const particles::Vec3& velocity(Cluster c) const { return lists_[c.size][c.place]; }
  /// m_k = k m_1.
  double mass(std::size_t size) const { return model_.monomer_mass * static_cast<double>(size); }
  /// Total momentum and kinetic energy (lab frame), for the invariant checks.
  particles::Vec3 momentum() const;
  /// Total kinetic energy, sum of m_k |v|^2/2 over the clusters (lab frame).
  double kinetic_energy() const;
  /// Candidate rate R = sum_ik A_ik now.
  double candidate_rate() const { return sampler_.total(); }
  /// Bytes held: the cluster arrays (reserved for N_0 at the start, never more), the member lists
  /// and the per-size tables.
  std::size_t memory_bytes() const;
  /// Whether w_k >= every speed of size k (the majorant holds): for the tests.
  bool bounds_hold() const;

  /// N_k, E_k, N and the kinetic energy relative to the mean flow, now.
  Measurement measure() const;

  /// Everything that evolves, for checkpoints; the trees are rebuilt from counts and bounds
  /// (segment_tree.hpp recomputes every sum from its leaves, for the same capacity).
  struct State {
    std::vector<double> velocity;     ///< 3 N, size by size, each list in order
    std::vector<std::uint64_t> count; ///< N_k, k = 1..capacity
    std::vector<double> max_speed;    ///< w_k, k = 1..capacity
    double time = 0.0;                ///< simulation time
    double credit = 0.0;              ///< time already waited towards the next candidate
    double next_step_time = 0.0;      ///< end of the current bound-refresh step
    std::uint64_t capacity = 0;       ///< size of the per-size tables K
    std::uint64_t largest_reached = 0;  ///< largest size so far
    Counters counters;                ///< event counts
    rng::Xoshiro256pp::State generator{};  ///< the collision stream
  };
  /// The evolving state, for a checkpoint.
  State state() const;
  /// Restores a state() of a Gas of the same input (same N_0); throws std::runtime_error when the
  /// tables do not add up to N_0.
  void restore(const State& state);
  /// The State under named values "clusters/..." (dsmc/state.hpp), for checkpoints.
  void save(state::Record& record) const;
  /// Continues from save()'s record (as restore(State)); throws state::StateError for a missing or
  /// misshapen value.
  void restore(const state::Record& record);

 private:
  void grow_to(std::size_t size);        ///< per-size tables for sizes up to `size`
  void set_diameters(std::size_t first, std::size_t last);  ///< sigma_k = k^(1/3) sigma_1, k = first..last
  void update_size(std::uint32_t size);  ///< row and column of one size in the sampler
  void rebuild_sampler();                ///< every row and column, from the counts and bounds
  void raise_bound(std::uint32_t size, const particles::Vec3& v);
  void recompute_bounds();
  void add(std::uint32_t size, const particles::Vec3& v);
  void remove(Cluster c);
  void remove_pair(Cluster a, Cluster b);  ///< both, whatever their order in one list
  void start_step();
  /// End of the blocked step that may run now towards t_target and `event_target` (header, "Cache
  /// blocks"), or -1 when the next step runs on the whole gas.
  double blocked_step_end(double t_target, std::uint64_t event_target) const;
  /// The most candidates a blocked step may hold with `events_left` to an event target (header, "Cache blocks").
  double target_step_candidates(std::uint64_t events_left) const;
  /// One blocked step from time_ to `end`: deal, run the blocks, gather.
  void blocked_step(double end);
  /// The deal of a blocked step: the clusters to the blocks of a uniformly random partition.
  void deal_blocks();
  /// The deal's labels: a uniformly random partition of the clusters into blocks of the sizes of deal_blocks().
  void draw_labels();
  /// Block b's lists sized for the deal: each size's count over the `parts` parts, whose counts in
  /// `place` (part x size present x block) become the parts' first places in them.
  void size_block_lists(std::size_t b, std::size_t parts, const std::vector<std::uint32_t>& present, std::size_t* place);
  /// The deal's copy of the gas's clusters [lo, hi) (in the order of the lists `present`, list k from
  /// first[k]) to the block lists, from the places `place` (size present x block) on; `to`: room for K
  /// pointers (no allocation here).
  void deal_part(const std::vector<std::size_t>& first, const std::vector<std::uint32_t>& present,
                 const std::size_t* place, particles::Vec3** to, std::size_t lo, std::size_t hi);
  /// Block b of a blocked step up to `end`, with the stream substream(key, b) and the volume of its members.
  void run_block(std::size_t b, double end, std::uint64_t key, double volume_per_partner);
  /// The gather of a blocked step: the blocks' lists and counters back into the gas, in block order.
  void gather_blocks();
  /// This gas as block `index` of `whole` for one step: empty lists of whole's capacity, its model.
  void reset_as_block(const Gas& whole);

  Model model_;
  std::size_t initial_monomers_ = 0;
  double volume_;  ///< V = (N_0 - 1)/n_1
  double step_fraction_;
  /// A list of clusters: sized first and filled later by the deal and the gather (particles.hpp FillLaterArray).
  using ClusterList = particles::FillLaterArray<particles::Vec3>;
  std::vector<ClusterList> lists_;  ///< lists_[k]: velocities of size k
  std::size_t clusters_ = 0;                                      ///< N
  std::vector<double> max_speed_;                                 ///< w_k (index k; 0 unused)
  std::vector<double> diameter_;                                  ///< sigma_k (index k)
  segment_tree::LowRankSampler<3> sampler_;                       ///< A_ik, index k - 1
  std::size_t capacity_ = 0;                                      ///< largest size the tables hold
  std::size_t largest_reached_ = 1;
  rng::Xoshiro256pp gen_;
  double time_ = 0.0, credit_ = 0.0, next_step_time_ = 0.0;
  Counters counters_;
  std::vector<std::uint32_t> touched_;  ///< sizes whose count or bound changed in this event
  std::vector<std::uint32_t> present_;  ///< recompute_bounds: the sizes present
  std::size_t block_size_ = 0;          ///< cache blocks (0: none)
  int block_threads_ = 1;               ///< threads for the blocks of a step
  std::uint64_t blocked_steps_ = 0;     ///< blocked steps so far (not part of the State)
  const std::atomic<bool>* stop_flag_ = nullptr;  ///< set_stop_flag
  bool bounds_exact_ = false;           ///< a blocked step just recomputed them (a restored gas recomputes: same values)
  std::vector<Gas> blocks_;             ///< the blocks' gases, kept between steps for their lists
  std::vector<std::uint32_t> labels_;   ///< the block of each cluster in a deal
};

}  // namespace gdsmc::agg_frag
