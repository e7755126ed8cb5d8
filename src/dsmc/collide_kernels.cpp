// The block kernels of the collider (collide.hpp "Blocks", "Mixtures in blocks"): the process of the
// general loops on a block, with less work per candidate, for a rule with the projection (rules.hpp).
#include "dsmc/collide.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gdsmc::collide {

void Collider::run_block_kernels(bool lowrank, double t_stop) {
  std::visit([&](const auto& rule) { run_block_kernel(rule, lowrank, t_stop); }, rule_);
}

template <class Rule>
void Collider::run_block_kernel(const Rule& rule, bool lowrank, double t_stop) {
  if constexpr (Rule::has_projection) {
    const bool track = sys_.tracks_displacements();
    if (s_ == 1) {  // the one-species kernel
      if (framed_) {
        if constexpr (Rule::frames) run_block_one_species<Rule, false, true>(rule, t_stop);  // a frame tracks no displacements (set_frame)
        else run_block_one_species<Rule, false, false>(rule, (require_identity_frame(), t_stop));
      } else if (track)
        run_block_one_species<Rule, true, false>(rule, t_stop);
      else
        run_block_one_species<Rule, false, false>(rule, t_stop);
      return;
    }
    // The mixture kernel (header "Mixtures in blocks").
    if (framed_) {  // (a frame tracks no displacements: set_frame)
      if constexpr (Rule::frames)
        run_block_mixture_sampler<Rule, false, true>(rule, lowrank, t_stop);
      else  // a rule without frames: only the identity frame of reset_frame (white noise), run unframed
        run_block_mixture_sampler<Rule, false, false>(rule, lowrank, (require_identity_frame(), t_stop));
    } else if (track)
      run_block_mixture_sampler<Rule, true, false>(rule, lowrank, t_stop);
    else
      run_block_mixture_sampler<Rule, false, false>(rule, lowrank, t_stop);
  } else {
    (void)rule, (void)lowrank, (void)t_stop;
    throw std::logic_error("collide: the block kernels need a rule with the projection");
  }
}

void Collider::require_identity_frame() const {
  if (frame_scale_ != 1.0 || frame_shear_ != 0.0) throw std::logic_error("collide: a frame with a rule that has none");
}

template <class Rule, bool Track, bool Framed>
void Collider::run_block_mixture_sampler(const Rule& rule, bool lowrank, double t_stop) {
  // `lowrank` by the one-word or the factored draw (set_block_lowrank chose it for the block's P);
  // `majorant` with two species: a kernel of its own, whose species and offsets are two locals.
  if (lowrank)
    separable_blocks_ ? run_block_mixture<Rule, Track, true, Framed, false, false, true>(rule, t_stop)
    : block_factored_ ? run_block_mixture<Rule, Track, true, Framed, false, true>(rule, t_stop)
                      : run_block_mixture<Rule, Track, true, Framed>(rule, t_stop);
  else
    s_ == 2 ? run_block_mixture<Rule, Track, false, Framed, true>(rule, t_stop)
            : run_block_mixture<Rule, Track, false, Framed>(rule, t_stop);
}

namespace {

/// Prefetches the velocities (a Vec3 may straddle two cache lines: its first and last byte) and, when
/// tracked, the displacements of particles a and b of a drawn-ahead candidate (header "Look-ahead").
template <bool Track>
[[gnu::always_inline]] inline void prefetch_pair(const particles::Vec3* v, const particles::Displacement* r,
                                                 std::uint32_t a, std::uint32_t b) {
  const auto* base = reinterpret_cast<const char*>(v);
  for (std::uint32_t q : {a, b}) {
    __builtin_prefetch(base + q * sizeof(particles::Vec3), 1);
    __builtin_prefetch(base + (q + 1) * sizeof(particles::Vec3) - 1, 1);
    if constexpr (Track) __builtin_prefetch(r + q, 1);
  }
}

/// Where a block's i-th particle is (the `majorant` mixture kernel): of species k for edge[k] <= i <
/// edge[k + 1], at system index i + offset[k] (its slice's first index less cum_k), in 32-bit words, so
/// that a candidate's species and index take a compare and an add (a binary gas's edge and offsets in
/// registers: edge1, offset0, offset1).
struct BlockIndex {
  std::array<std::uint32_t, block_species_limit + 1> edge;
  std::array<std::uint32_t, block_species_limit> offset;
  std::uint32_t edge1 = 0, offset0 = 0, offset1 = 0;
};
BlockIndex block_index(const std::size_t* cum, const std::size_t* slice, std::size_t s) {
  BlockIndex x;
  for (std::size_t k = 0; k < s; ++k) {
    x.edge[k] = static_cast<std::uint32_t>(cum[k]);
    x.offset[k] = static_cast<std::uint32_t>(slice[k] - cum[k]);  // (modulo 2^32: i + offset is exact)
  }
  x.edge[s] = static_cast<std::uint32_t>(cum[s]);
  if (s >= 2) x.edge1 = x.edge[1], x.offset0 = x.offset[0], x.offset1 = x.offset[1];
  return x;
}

/// `majorant`'s candidate in a mixture's block: a uniform pair of its N_b particles (one draw), their
/// system indices and the pair i S + k of their species (`Two`: a binary gas's one compare).
template <bool Two>
[[gnu::always_inline]] inline void majorant_candidate(rng::Xoshiro256pp& gen, std::uint32_t n, std::size_t s,
                                                      const BlockIndex& index, std::uint32_t edge1, std::uint32_t offset0,
                                                      std::uint32_t offset1, std::uint32_t& a, std::uint32_t& b,
                                                      std::uint32_t& pair) {
  std::uint32_t x, y;
  gen.below_pair(n, n - 1, x, y);
  y += y >= x;
  const std::uint32_t i = Two ? x >= edge1 : species_at(index.edge.data(), s, x);
  const std::uint32_t k = Two ? y >= edge1 : species_at(index.edge.data(), s, y);
  a = x + (Two ? (i ? offset1 : offset0) : index.offset[i]);
  b = y + (Two ? (k ? offset1 : offset0) : index.offset[k]);
  pair = Two ? 2 * i + k : static_cast<std::uint32_t>(i * s + k);
}

/// "(sigma g)_max raised when exceeded" (collide.hpp header) for both partners of a collision: true when
/// either speed^2 passed its species' bound, which then rises.
[[gnu::always_inline]] inline bool raised_by(const particles::Vec3& va, const particles::Vec3& vb, double* speed2,
                                             std::uint32_t i, std::uint32_t k) {
  const double speed2_a = va.x * va.x + va.y * va.y + va.z * va.z;
  const double speed2_b = vb.x * vb.x + vb.y * vb.y + vb.z * vb.z;
  if (!(speed2_a > speed2[i] || speed2_b > speed2[k])) [[likely]]
    return false;
  speed2[i] = std::max(speed2[i], speed2_a);
  speed2[k] = std::max(speed2[k], speed2_b);
  return true;
}

/// The particles a, b of a block's `lowrank` candidate whose slices are `si` and `sk` (first, count,
/// reject), from the low two 24-bit fields of `word` by the multiply-shift with rejection of
/// lowrank_candidate (either field rejected: below_pair draws both again, on a copy of the stream, which
/// thus stays in registers).
template <class Gen, class Slice>
[[gnu::always_inline]] inline void slice_particles(Gen& gen, std::uint64_t word, const Slice& si, const Slice& sk,
                                                   std::uint32_t& a, std::uint32_t& b) {
  const std::uint64_t m1 = (word & 0xffffffULL) * si.count, m2 = ((word >> 24) & 0xffffffULL) * sk.count;
  std::uint32_t x = static_cast<std::uint32_t>(m1 >> 24), y = static_cast<std::uint32_t>(m2 >> 24);
  const bool rejected = (static_cast<std::uint32_t>(m1) & 0xffffffu) < si.reject ||
                        (static_cast<std::uint32_t>(m2) & 0xffffffu) < sk.reject;
  if (rejected) [[unlikely]] {
    rng::Xoshiro256pp rare = gen;
    rare.below_pair(si.count, sk.count, x, y);
    gen = rare;
  }
  a = si.first + x, b = sk.first + y;
}

}  // namespace

template <class Gen>
[[gnu::always_inline]] inline void Collider::lowrank_candidate(Gen& gen, const LowrankCell* cells,
                                                               const LowrankOutcome* outcomes, unsigned cell_bits,
                                                               std::uint32_t& a, std::uint32_t& b, std::uint32_t& pair) {
  // From one word (set_block_lowrank, header "Mixtures in blocks"): the alias cell from the top m bits, its
  // coin from the next 16 - m (a further uniform only when they tie with the threshold), the particles
  // from the low two 24-bit fields by below_pair's multiply-shift and rejection in 24 bits (Lemire 2019;
  // either field rejected: below_pair draws both particles of this pair again).
  const std::uint64_t r = gen();
  const LowrankCell& cell = cells[r >> (64 - cell_bits)];
  const auto q = static_cast<std::uint32_t>(r >> 48) & ((1u << (16 - cell_bits)) - 1);
  // Without a branch on q < whole (taken at random, its mispredictions cost about as much as the
  // rest of the draw): a mask selects the outcome; the tie q = whole (one in 2^(16-m)) branches.
  const std::uint32_t keep_mask = 0u - static_cast<std::uint32_t>(q < cell.whole);
  std::uint32_t outcome = (cell.keep & keep_mask) | (cell.other & ~keep_mask);
  if (q == cell.whole) [[unlikely]]
    outcome = gen.uniform() < cell.fraction ? cell.keep : cell.other;
  const LowrankOutcome& o = outcomes[outcome];
  const std::uint64_t m1 = (r & 0xffffffULL) * o.count_i, m2 = ((r >> 24) & 0xffffffULL) * o.count_k;
  std::uint32_t x = static_cast<std::uint32_t>(m1 >> 24), y = static_cast<std::uint32_t>(m2 >> 24);
  if ((static_cast<std::uint32_t>(m1) & 0xffffffu) < o.reject_i || (static_cast<std::uint32_t>(m2) & 0xffffffu) < o.reject_k)
      [[unlikely]] {
    // On a copy of the stream: the stream itself then never has its address taken and stays in
    // registers (below_pair, out of line here, would otherwise make it live in memory throughout).
    rng::Xoshiro256pp rare = gen;
    rare.below_pair(o.count_i, o.count_k, x, y);
    gen = rare;
  }
  a = o.first_i + x, b = o.first_k + y, pair = o.pair;
}

template <class Gen>
[[gnu::always_inline]] inline void Collider::factored_candidate(Gen& gen, const FactoredView& tables, std::uint32_t& a,
                                                                std::uint32_t& b, std::uint32_t& pair,
                                                                std::uint32_t& row_column) {
  // The factored draw (set_block_factored; \ref sch_factored "docs/schemes.md"). Word 1: the row cell from
  // its top m bits and its coin from bits 32..63-m, the column cell of the row's table from bits 32-m..31
  // and its coin from bits 0..31-m (a further uniform only when a coin ties with its threshold, one in
  // 2^(32-m)); without a branch on q < whole (taken at random): a mask selects the outcome.
  const unsigned bits = tables.bits;
  const std::uint64_t r = gen();
  const std::size_t row_index = r >> (64 - bits);
  const FactoredCell& row_cell = tables.rows[row_index];
  const auto q = static_cast<std::uint32_t>(r >> 32) & ((1u << (32 - bits)) - 1);
  const std::uint32_t keep_row = 0u - static_cast<std::uint32_t>(q < row_cell.whole);
  std::uint32_t row = (row_cell.keep & keep_row) | (row_cell.other & ~keep_row);
  if (q == row_cell.whole) [[unlikely]]
    row = gen.uniform() < tables.row_fraction[row_index] ? row_cell.keep : row_cell.other;
  const auto low = static_cast<std::uint32_t>(r);
  const std::size_t column_index = (static_cast<std::size_t>(row) << bits) + (low >> (32 - bits));
  const FactoredCell& column_cell = tables.columns[column_index];
  const std::uint32_t q2 = low & ((1u << (32 - bits)) - 1);
  const std::uint32_t keep_column = 0u - static_cast<std::uint32_t>(q2 < column_cell.whole);
  std::uint32_t column = (column_cell.keep & keep_column) | (column_cell.other & ~keep_column);
  if (q2 == column_cell.whole) [[unlikely]]
    column = gen.uniform() < tables.column_fraction[column_index] ? column_cell.keep : column_cell.other;
  const FactoredSpecies& si = tables.species[row];
  const FactoredSpecies& sk = tables.species[column];
  // Word 2: the particles from the low two 24-bit fields, as in lowrank_candidate.
  slice_particles(gen, gen(), si, sk, a, b);
  pair = si.pair_row + sk.species, row_column = row | column << 16;
}

template <class Gen>
[[gnu::always_inline]] inline void Collider::separable_words(Gen& gen, const SeparableView& tables,
                                                             SeparableWords& words) {
  // The separable draw (set_block_separable; \ref sch_separable "docs/schemes.md"). Word 1: the term r (a
  // uniform against term0, term01); word 2: the row cell of u^(r)'s table from its top m bits, the column
  // cell of v^(r)'s from bits 32-m..31 (their coins in the other bits: separable_cells); word 3: the
  // particles. The two cells, independent of each other, are prefetched here.
  const unsigned bits = tables.bits;
  const double u = gen.uniform();
  const std::size_t term = static_cast<std::size_t>(u >= tables.term0) + static_cast<std::size_t>(u >= tables.term01);
  words.cells = gen();
  words.particles = gen();
  words.row_index = static_cast<std::uint32_t>((term << bits) + (words.cells >> (64 - bits)));
  words.column_index = static_cast<std::uint32_t>((term << bits) + (static_cast<std::uint32_t>(words.cells) >> (32 - bits)));
  __builtin_prefetch(tables.rows + words.row_index);
  __builtin_prefetch(tables.columns + words.column_index);
}

template <class Gen>
[[gnu::always_inline]] inline void Collider::separable_cells(Gen& gen, const SeparableView& tables,
                                                             SeparableWords& words) {
  // The cells' coins from the bits their indices left (a further uniform only when a coin ties with its
  // threshold, one in 2^(32-m)), without a branch on q < whole: a mask selects the outcome. The two
  // present species' entries are prefetched here, their particles drawn a stage later.
  const unsigned bits = tables.bits;
  const SeparableCell& row_cell = tables.rows[words.row_index];
  const auto q = static_cast<std::uint32_t>(words.cells >> 32) & ((1u << (32 - bits)) - 1);
  const std::uint32_t keep_row = 0u - static_cast<std::uint32_t>(q < row_cell.whole);
  words.row = (row_cell.keep & keep_row) | (row_cell.other & ~keep_row);
  if (q == row_cell.whole) [[unlikely]]
    words.row = gen.uniform() < tables.row_fraction[words.row_index] ? row_cell.keep : row_cell.other;
  const SeparableCell& column_cell = tables.columns[words.column_index];
  const std::uint32_t q2 = static_cast<std::uint32_t>(words.cells) & ((1u << (32 - bits)) - 1);
  const std::uint32_t keep_column = 0u - static_cast<std::uint32_t>(q2 < column_cell.whole);
  words.column = (column_cell.keep & keep_column) | (column_cell.other & ~keep_column);
  if (q2 == column_cell.whole) [[unlikely]]
    words.column = gen.uniform() < tables.column_fraction[words.column_index] ? column_cell.keep : column_cell.other;
  __builtin_prefetch(tables.species + words.row);
  __builtin_prefetch(tables.species + words.column);
}

template <class Gen>
[[gnu::always_inline]] inline void Collider::separable_candidate(Gen& gen, const SeparableView& tables,
                                                                 const SeparableWords& words, std::uint32_t& a,
                                                                 std::uint32_t& b) {
  slice_particles(gen, words.particles, tables.species[words.row], tables.species[words.column], a, b);  // as lowrank_candidate
}

template <class Rule, bool Framed>
[[gnu::always_inline]] inline double Collider::kernel_collision(const PairKernel& pk, std::uint32_t i, std::uint32_t k,
                                                                particles::Vec3& va, particles::Vec3& vb, double g_dot_e2,
                                                                const particles::Vec3& p, std::array<double, 4>& moments) const {
  if constexpr (Framed) {  // the stored u move along G^-1 (g.e) e; the moments follow them (header "Frame")
    const double ma = mix_.mass[i], mb = mix_.mass[k];
    add_moments(moments, va, -ma);
    add_moments(moments, vb, -mb);
    const double lost = Rule::collide_projected(va, vb, pk.constants, g_dot_e2, to_stored(p.x, p.y, p.z));
    add_moments(moments, va, ma);
    add_moments(moments, vb, mb);
    return lost;
  } else {
    (void)i, (void)k, (void)moments;
    return Rule::collide_projected(va, vb, pk.constants, g_dot_e2, p);
  }
}

template <bool Lowrank, bool Framed>
void Collider::after_raise(const std::size_t* cum, std::uint32_t n, double* speed2) {
  if constexpr (Lowrank) {
    if (block_factored_)
      raise_block_factored();  // the rows only: the columns do not depend on the speeds
    else
      set_block_lowrank(mix_.total_density());  // the block's A_ik over the raised bounds
  } else {
    bound_ = mixture_bound(speed2, cum);
    if constexpr (Framed) bound_ *= speed_factor_;
    rate_ = 0.5 * static_cast<double>(n) * mix_.total_density() * bound_;
  }
}

template <class Rule, bool Track, bool Framed>
void Collider::run_block_one_species(const Rule& rule, double t_stop) {
  // The process of run_majorant on the block's N_b particles (header "Blocks", "The one-species kernel"):
  // candidates at R_b = N_b n B_b / 2, B_b = 2 pi sigma^2 chi vmax_b, a uniform pair accepted with
  // |g| / (2 vmax_b), with less work per candidate; the stream in a local copy (its state in registers).
  rng::Xoshiro256pp gen = gen_;
  const auto first = static_cast<std::uint32_t>(range_first_);
  const auto n = static_cast<std::uint32_t>(range_count_);
  particles::Vec3* v = sys_.v.data() + first;
  [[maybe_unused]] particles::Vec3* spin = nullptr;  // (from the block's first particle)
  if constexpr (Rule::kernel_needs_particles) spin = rule.spins(sys_) + first;
  const double n_density = mix_.total_density();
  // One species: both partners take half the impulse, share_a = share_b (scalars, kept in registers).
  [[maybe_unused]] double share = 0.0, loss = 0.0;
  if constexpr (!Rule::kernel_needs_particles) {
    const typename Rule::Pair both = rule.pair(0, 0);
    share = both.share_a, loss = both.loss;
  }
  double max_speed2 = block_speed2_[0];
  // The drawn-ahead pairs (header "Look-ahead"): uniform, independent of the state, prefetched.
  std::array<std::uint32_t, 2 * block_lookahead<Framed>> ahead;
  const auto draw = [&](std::size_t slot) {
    std::uint32_t a, b;
    gen.below_pair(n, n - 1, a, b);
    b += b >= a;
    ahead[2 * slot] = a;
    ahead[2 * slot + 1] = b;
    prefetch_pair<Track>(v, Track ? sys_.r.data() + first : nullptr, a, b);  // (no arithmetic on an empty array's null)
    if constexpr (Rule::kernel_needs_particles) prefetch_pair<false>(spin, nullptr, a, b);  // the rule's own array
  };
  for (std::size_t slot = 0; slot < block_lookahead<Framed>; ++slot) draw(slot);
  std::size_t next = 0;
  std::uint64_t events = 0, candidates = 0;
  double dissipated = 0.0;
  [[maybe_unused]] const double mass = mix_.mass[0];
  [[maybe_unused]] std::array<double, 4> moments{};  // the change of sum m u u^T (xx, yy, zz, xy)
  for (;;) {
    double vmax = std::sqrt(max_speed2);
    if constexpr (Framed) vmax *= speed_factor_;  // |G g| <= ||G|| |g|
    const double limit = 2.0 * vmax;  // |g| <= 2 vmax_b
    bound_ = 2.0 * cross_section_[0] * vmax;
    rate_ = 0.5 * static_cast<double>(n) * n_density * bound_;
    const double dt_candidate = 1.0 / rate_;
    const double available = credit_ + (t_stop - time_);
    const std::uint64_t n_candidates = candidate_count(available * rate_);
    const double t0 = time_ - credit_;
    bool raised = false, stopped = false;
    std::uint64_t c = 0;
    // One candidate, the k-th of the sub-step (from 0): true when a partner passed the bound, which then rises
    // and ends the sub-step.
    const auto candidate = [&](std::uint64_t k) __attribute__((always_inline)) {
      const std::uint32_t a = ahead[2 * next], b = ahead[2 * next + 1];
      draw(next);
      next = (next + 1) % block_lookahead<Framed>;
      double gx = v[a].x - v[b].x, gy = v[a].y - v[b].y, gz = v[a].z - v[b].z;
      to_actual<Framed>(gx, gy, gz);
      const double g2 = gx * gx + gy * gy + gz * gz;
      // Accept with |g| / (2 vmax_b) = pi sigma^2 chi |g| / B_b (\ref sch_majorant "docs/schemes.md"), compared squared.
      const double threshold = gen.uniform() * limit;
      if (threshold * threshold >= g2) return false;
      if (g2 > limit * limit) [[unlikely]] note_overshoot(std::sqrt(g2) / limit);
      double px, py, pz;
      const double g_dot_e2 = rules::hemisphere_projection(gen, gx, gy, gz, std::sqrt(g2), px, py, pz);
      if (g_dot_e2 == 0.0) return false;
      if constexpr (Track) {
        const double t_collision = t0 + static_cast<double>(k + 1) * dt_candidate;
        particles::flush_free_flight(sys_, first + a, t_collision);
        particles::flush_free_flight(sys_, first + b, t_collision);
      }
      particles::Vec3& va = v[a];
      particles::Vec3& vb = v[b];
      if constexpr (Framed) {  // (the mass, common to all, multiplies the sum at the end)
        add_moments(moments, va, -1.0);
        add_moments(moments, vb, -1.0);
        dissipated += Rule::collide_projected(va, vb, {share, share, loss}, g_dot_e2, to_stored(px, py, pz));  // G^-1 (g.e) e
        add_moments(moments, va, 1.0);
        add_moments(moments, vb, 1.0);
      } else if constexpr (Rule::kernel_needs_particles) {
        dissipated += rule.collide_at(sys_, spin - first, first + a, first + b, 0, 0, g_dot_e2, {px, py, pz}).loss;
      } else {
        dissipated += Rule::collide_projected(va, vb, {share, share, loss}, g_dot_e2, {px, py, pz});
      }
      ++events;
      // "(sigma g)_max raised when exceeded" (header), for either partner: a new sub-step from here.
      const double speed2 = std::max(va.x * va.x + va.y * va.y + va.z * va.z, vb.x * vb.x + vb.y * vb.y + vb.z * vb.z);
      if (speed2 <= max_speed2) return false;
      max_speed2 = speed2;
      return true;
    };
    // A sub-step is short in a run, but one begun from an extreme state (a bound raised a millionfold) could
    // take hours: past 2^20 candidates (about 10 ms) it runs in chunks between which an interrupt is seen, so
    // that the common loop looks at no flag.
    constexpr std::uint64_t chunk = std::uint64_t{1} << 20;
    if (n_candidates <= chunk) {
      for (; c < n_candidates; ++c)
        if (candidate(c)) {
          raised = true;
          ++c;
          break;
        }
    } else {
      while (c < n_candidates && !raised) {
        if (c > 0 && stop_requested()) [[unlikely]] {
          stopped = true;
          break;
        }
        for (const std::uint64_t chunk_end = std::min(n_candidates, c + chunk); c < chunk_end; ++c)
          if (candidate(c)) {
            raised = true;
            ++c;
            break;
          }
      }
    }
    candidates += c;
    credit_ = raised || stopped ? 0.0 : available - static_cast<double>(n_candidates) * dt_candidate;
    time_ = raised || stopped ? t0 + static_cast<double>(c) * dt_candidate : t_stop;
    if (!raised) break;
  }
  gen_ = gen;
  block_speed2_[0] = max_speed2;
  if constexpr (Framed)
    for (std::size_t q = 0; q < 4; ++q) moments_[q] += mass * moments[q];
  counters_.events += events;
  counters_.candidates += candidates;
  counters_.dissipated += dissipated;
  if (!counters_.pair_events.empty()) counters_.pair_events[0] += events;
}

template <class Rule, bool Track, bool Lowrank, bool Framed, bool Two, bool Factored, bool Separable>
void Collider::run_block_mixture([[maybe_unused]] const Rule& rule, double t_stop) {
  // The process of run_majorant (or run_lowrank) on the block's slices, with less work per candidate
  // (header "Mixtures in blocks"); the stream in a local copy (its state in registers).
  rng::Xoshiro256pp gen = gen_;
  const std::size_t s = s_;
  const std::size_t* cum = block_slice_cum();
  const std::size_t* slice = block_slice_first();
  const auto n = static_cast<std::uint32_t>(range_count_);
  particles::Vec3* v = sys_.v.data();
  [[maybe_unused]] particles::Vec3* spin = nullptr;
  if constexpr (Rule::kernel_needs_particles) spin = rule.spins(sys_);
  if constexpr (!Rule::kernel_needs_particles)
    static_assert(std::is_same_v<typename Rule::Projected, rules::SmoothRule::Projected>,
                  "the kernels' table (PairKernel) holds SmoothRule's projected constants");
  const PairKernel* kernel = pair_kernel_.data();
  // (the acceptance's constant of each pair apart: `majorant` (pi sigma^2 chi)^2, `lowrank` w_i + w_k)
  const double* acceptance = Lowrank ? pair_limit_.data() : pair_cross_section2_.data();
  double* speed2 = block_speed2_;
  // The events per pair are counted on this thread's stack and added to the counters at the end: the
  // workers' own vectors are small heap blocks that can share a cache line with another thread's data,
  // and an increment per event on such a line stalls both threads (\ref perf_two_threads "docs/performance.md").
  std::array<std::uint64_t, pair_event_limit * pair_event_limit> local_events;  // (the first `counted` used)
  const std::size_t counted = counters_.pair_events.size();  // S^2 up to pair_event_limit species, else 0 (restore)
  if (counted > local_events.size()) throw std::logic_error("collide: more pair counts than pair_event_limit^2");
  std::fill_n(local_events.data(), counted, std::uint64_t{0});
  std::uint64_t sink = 0, *pair_events = counted == 0 ? &sink : local_events.data();
  [[maybe_unused]] const bool counting_pairs = counted != 0;
  const BlockIndex index = Lowrank ? BlockIndex{} : block_index(cum, slice, s);
  [[maybe_unused]] const std::uint32_t edge1 = index.edge1, offset0 = index.offset0, offset1 = index.offset1;
  const LowrankCell* cells = lowrank_cells_.data();
  const LowrankOutcome* outcomes = lowrank_outcomes_.data();
  const unsigned cell_bits = lowrank_cell_bits_;
  [[maybe_unused]] FactoredView factored = factored_view();
  [[maybe_unused]] const double speed_factor = speed_factor_;
  // (separable: W_b^2, and the acceptance's W_b ||G|| chi_max; chi_ik in the Enskog gas only)
  [[maybe_unused]] const SeparableView separable = separable_view();
  [[maybe_unused]] double energy2 = separable_.energy2;
  [[maybe_unused]] double energy_bound = std::sqrt(energy2) * speed_factor * chi_max_;
  [[maybe_unused]] const bool enskog = mix_.enskog;
  [[maybe_unused]] const std::optional<double> alpha_constant = mix_.restitution.constant;
  // The drawn-ahead candidates: particles a, b and the pair i S + k, in three arrays of 32-bit words.
  const std::uint32_t* pair_species = pair_species_.data();
  std::array<std::uint32_t, block_lookahead<Framed>> ahead_a, ahead_b, ahead_pair;
  // (factored: row | column<<16; separable: the column, the row in ahead_pair)
  [[maybe_unused]] std::array<std::uint32_t, block_lookahead<Framed>> ahead_row_column;
  // (separable: the words of the candidates L and 2L ahead, L = block_lookahead: their species read, their cells;
  // the species read with the cells, L ahead, up to separable_deep_above present species)
  [[maybe_unused]] std::array<SeparableWords, block_lookahead<Framed>> separable_species, separable_cells_ahead;
  [[maybe_unused]] const bool deep = separable_.species.size() > deep_above_;
  const auto draw = [&](std::size_t slot) __attribute__((always_inline)) {  // (GCC kept the factored draw out of line)
    std::uint32_t a, b, pair;
    if constexpr (Lowrank && Separable) {
      if (deep) {  // (three stages, L = block_lookahead candidates apart: the particles of the words whose
        // species' entries were prefetched L candidates ago, the species of those whose cells were
        // prefetched 2L ago, new words)
        separable_candidate(gen, separable, separable_species[slot], a, b);
        pair = separable_species[slot].row, ahead_row_column[slot] = separable_species[slot].column;
        separable_cells(gen, separable, separable_cells_ahead[slot]);
        separable_species[slot] = separable_cells_ahead[slot];
      } else {  // (two: the cells of the words drawn L candidates ago, then their species at once)
        separable_cells(gen, separable, separable_cells_ahead[slot]);
        separable_candidate(gen, separable, separable_cells_ahead[slot], a, b);
        pair = separable_cells_ahead[slot].row, ahead_row_column[slot] = separable_cells_ahead[slot].column;
      }
      separable_words(gen, separable, separable_cells_ahead[slot]);
    } else if constexpr (Lowrank && Factored) {
      factored_candidate(gen, factored, a, b, pair, ahead_row_column[slot]);
    } else if constexpr (Lowrank) {
      lowrank_candidate(gen, cells, outcomes, cell_bits, a, b, pair);
    } else {
      majorant_candidate<Two>(gen, n, s, index, edge1, offset0, offset1, a, b, pair);
    }
    ahead_a[slot] = a, ahead_b[slot] = b, ahead_pair[slot] = pair;
    prefetch_pair<Track>(v, sys_.r.data(), a, b);
    if constexpr (Rule::kernel_needs_particles) prefetch_pair<false>(spin, nullptr, a, b);  // the rule's own array
  };
  if constexpr (Separable) {
    for (std::size_t slot = 0; slot < block_lookahead<Framed>; ++slot) separable_words(gen, separable, separable_cells_ahead[slot]);
    for (std::size_t slot = 0; deep && slot < block_lookahead<Framed>; ++slot) {
      separable_cells(gen, separable, separable_cells_ahead[slot]);
      separable_species[slot] = separable_cells_ahead[slot];
      separable_words(gen, separable, separable_cells_ahead[slot]);
    }
  }
  for (std::size_t slot = 0; slot < block_lookahead<Framed>; ++slot) draw(slot);
  std::size_t next = 0;
  std::uint64_t events = 0, candidates = 0;
  double dissipated = 0.0;
  [[maybe_unused]] std::array<double, 4> moments{};  // the change of sum m u u^T (xx, yy, zz, xy)
  for (;;) {
    // rate_ (and bound_, or the alias table and w_k) are those of the block's current bounds.
    const double bound = bound_, dt_candidate = 1.0 / rate_, available = credit_ + (t_stop - time_);
    const std::uint64_t n_candidates = candidate_count(available * rate_);
    const double t0 = time_ - credit_;
    bool raised = false, stopped = false;
    std::uint64_t c = 0;
    for (; c < n_candidates; ++c) {
      // An interrupt seen every 2^16 candidates: a candidate of many species costs several of one species',
      // so a step can take seconds; an abandoned run may end its block here.
      if ((c & 0xffffu) == 0xffffu && stop_requested()) [[unlikely]] {
        stopped = true;
        break;
      }
      const std::uint32_t a = ahead_a[next], b = ahead_b[next], pair = ahead_pair[next];
      [[maybe_unused]] const std::uint32_t row_column = Factored || Separable ? ahead_row_column[next] : 0;
      draw(next);
      next = (next + 1) % block_lookahead<Framed>;
      if (Lowrank && a == b) continue;  // the self pair is part of the majorant's sum, never a collision
      double gx = v[a].x - v[b].x, gy = v[a].y - v[b].y, gz = v[a].z - v[b].z;
      to_actual<Framed>(gx, gy, gz);
      const double g2 = gx * gx + gy * gy + gz * gz;
      // Accept with |g| / (w_i + w_k) (`lowrank`) or pi sigma_kj^2 chi_kj |g| / B_b (\ref sch_majorant "docs/schemes.md"), squared.
      // (factored: (w_i + w_k) ||G|| from the present species' w, as pair_limit_ holds it for the one-word draw)
      // (separable: chi_ik |g| / (chi_max W_b ||G|| (1/sqrt(m_i) + 1/sqrt(m_k))))
      [[maybe_unused]] double chi = 1.0;
      if constexpr (Separable)
        if (enskog) chi = mix_.pair_correlation(separable.species[pair].species, separable.species[row_column].species);
      const double limit =
          Separable  ? (separable.species[pair].inverse_root_mass + separable.species[row_column].inverse_root_mass) *
                          energy_bound
          : Factored ? (factored.w[row_column & 0xffffu] + factored.w[row_column >> 16]) * speed_factor
          : Lowrank  ? acceptance[pair]
                     : bound;
      const double rate2 = Separable ? chi * chi * g2 : Lowrank ? g2 : acceptance[pair] * g2;
      const double threshold = gen.uniform() * limit;
      if (threshold * threshold >= rate2) continue;
      if (rate2 > limit * limit) [[unlikely]] note_overshoot(std::sqrt(rate2) / limit);
      double px, py, pz;
      const double g_dot_e2 = rules::hemisphere_projection(gen, gx, gy, gz, std::sqrt(g2), px, py, pz);
      if (g_dot_e2 == 0.0) continue;
      if constexpr (Track) {
        const double t_collision = t0 + static_cast<double>(c + 1) * dt_candidate;
        particles::flush_free_flight(sys_, a, t_collision);
        particles::flush_free_flight(sys_, b, t_collision);
      }
      particles::Vec3& va = v[a];
      particles::Vec3& vb = v[b];
      const std::uint32_t i = Separable ? separable.species[pair].species : pair_species[2 * pair];
      const std::uint32_t k = Separable ? separable.species[row_column].species : pair_species[2 * pair + 1];
      // (separable: the masses from the present species' entries, read for the particles, not from the S
      // masses at random; a frame's moments still read them: kernel_collision)
      [[maybe_unused]] const double mass_i = Separable ? separable.species[pair].mass : 0.0;
      [[maybe_unused]] const double mass_k = Separable ? separable.species[row_column].mass : 0.0;
      if constexpr (Rule::kernel_needs_particles) {
        dissipated += rule.collide_at(sys_, spin, a, b, i, k, g_dot_e2, {px, py, pz}).loss;
      } else if constexpr (Separable) {  // (no S x S table read at random: the pair's constants computed, rules.hpp)
        const double alpha = alpha_constant ? *alpha_constant : mix_.restitution(i, k);
        dissipated += kernel_collision<Rule, Framed>(PairKernel{rules::SmoothRule::make_pair(alpha, mass_i, mass_k), 0},
                                                     i, k, va, vb, g_dot_e2, {px, py, pz}, moments);
      } else {
        dissipated += kernel_collision<Rule, Framed>(kernel[pair], i, k, va, vb, g_dot_e2, {px, py, pz}, moments);
      }
      ++events;
      if constexpr (Separable)  // (above pair_event_limit species the counts are not kept: the sink)
        ++pair_events[counting_pairs ? std::min(i, k) * s + std::max(i, k) : 0];
      else
        ++pair_events[kernel[pair].event];
      if constexpr (Separable) {  // the species' bounds follow (the master's rate), W_b^2 is the block's bound
        const double speed2_a = va.x * va.x + va.y * va.y + va.z * va.z;
        const double speed2_b = vb.x * vb.x + vb.y * vb.y + vb.z * vb.z;
        speed2[i] = std::max(speed2[i], speed2_a);
        speed2[k] = std::max(speed2[k], speed2_b);
        if (mass_i * speed2_a > energy2 || mass_k * speed2_b > energy2) [[unlikely]] {
          energy2 = std::max({energy2, mass_i * speed2_a, mass_k * speed2_b});
          raised = true;
          ++c;
          break;
        }
      } else if (raised_by(va, vb, speed2, i, k)) [[unlikely]] {  // a new sub-step from here
        raised = true;
        ++c;
        break;
      }
    }
    candidates += c;
    credit_ = raised || stopped ? 0.0 : available - static_cast<double>(n_candidates) * dt_candidate;
    time_ = raised || stopped ? t0 + static_cast<double>(c) * dt_candidate : t_stop;
    if (!raised) break;
    if constexpr (Separable) {  // only R_b scales with W_b: the drawn-ahead pairs keep their law
      separable_.energy2 = energy2;
      energy_bound = std::sqrt(energy2) * speed_factor * chi_max_;
      rate_ = separable_.scale * std::sqrt(energy2) * speed_factor;
      continue;
    }
    after_raise<Lowrank, Framed>(cum, n, speed2);
    if constexpr (Lowrank) {  // the drawn-ahead pairs came from the old A_ik: redrawn
      cells = lowrank_cells_.data();  // (their sizes do not change: the same data)
      factored = factored_view();
      for (std::size_t slot = 0; slot < block_lookahead<Framed>; ++slot) draw(slot);
      next = 0;
    }
  }
  counters_.events += events, counters_.candidates += candidates, counters_.dissipated += dissipated;
  for (std::size_t p = 0; p < counted; ++p) counters_.pair_events[p] += local_events[p];
  if constexpr (Framed)
    for (std::size_t q = 0; q < 4; ++q) moments_[q] += moments[q];
  gen_ = gen;
}

}  // namespace gdsmc::collide
