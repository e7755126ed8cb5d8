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
      if (framed_)
        run_block_one_species<Rule, false, true>(rule, t_stop);  // a frame tracks no displacements (set_frame)
      else if (track)
        run_block_one_species<Rule, true, false>(rule, t_stop);
      else
        run_block_one_species<Rule, false, false>(rule, t_stop);
      return;
    }
    // The mixture kernel (header "Mixtures in blocks"); `majorant` with two species: a kernel of its
    // own, whose species and offsets are two locals.
    if (framed_)  // (a frame tracks no displacements: set_frame)
      lowrank    ? run_block_mixture<Rule, false, true, true>(rule, t_stop)
      : s_ == 2  ? run_block_mixture<Rule, false, false, true, true>(rule, t_stop)
                 : run_block_mixture<Rule, false, false, true>(rule, t_stop);
    else if (lowrank)
      track ? run_block_mixture<Rule, true, true, false>(rule, t_stop) : run_block_mixture<Rule, false, true, false>(rule, t_stop);
    else if (s_ == 2)
      track ? run_block_mixture<Rule, true, false, false, true>(rule, t_stop)
            : run_block_mixture<Rule, false, false, false, true>(rule, t_stop);
    else
      track ? run_block_mixture<Rule, true, false, false>(rule, t_stop) : run_block_mixture<Rule, false, false, false>(rule, t_stop);
  } else {
    (void)rule, (void)lowrank, (void)t_stop;
    throw std::logic_error("collide: the block kernels need a rule with the projection");
  }
}

template <class Rule, bool Track, bool Framed>
void Collider::run_block_one_species(const Rule& rule, double t_stop) {
  // The process of run_majorant on the block's N_b particles (header "Blocks"): candidates at
  // R_b = N_b n B_b / 2, B_b = 2 pi sigma^2 chi vmax_b, candidate c of a sub-step at t0 + (c + 1)/R_b,
  // a uniform pair accepted with |g| / (2 vmax_b). Only the work per candidate is less: the pair from
  // one draw (rng::Xoshiro256pp::below_pair), the drawn-ahead pairs in locals, no species,
  // and (g.e) e without e (hemisphere_projection), the same collision as hemisphere_normal's e gives.
  // Framed (header, "Frame"): g = G (u_a - u_b), the bound times ||G||, the impulse mapped back with
  // G^-1 (linear, so applied to (g.e) e itself), the change of Q summed here and added at the end.
  // The block's stream in a local copy, written back at the end (as run_block_mixture): its state
  // then stays in registers instead of being stored at every draw. The same draws.
  rng::Xoshiro256pp gen = gen_;
  const auto first = static_cast<std::uint32_t>(range_first_);
  const auto n = static_cast<std::uint32_t>(range_count_);
  particles::Vec3* v = sys_.v.data() + first;
  const double n_density = mix_.total_density();
  // One species: both partners take half the impulse, share_a = share_b. (The constants as scalars,
  // which stay in registers; a record of them was read from the stack in the loop.)
  const typename Rule::Pair both = rule.pair(0, 0);
  const double share = both.share_a, loss = both.loss;
  double max_speed2 = block_speed2_[0];
  // The drawn-ahead pairs (header "Look-ahead"): uniform, independent of the state, prefetched.
  std::array<std::uint32_t, 2 * block_lookahead<Framed>> ahead;
  const auto draw = [&](std::size_t slot) {
    std::uint32_t a, b;
    gen.below_pair(n, n - 1, a, b);
    b += b >= a;
    ahead[2 * slot] = a;
    ahead[2 * slot + 1] = b;
    const auto* base = reinterpret_cast<const char*>(v);
    for (std::uint32_t i : {a, b}) {
      __builtin_prefetch(base + i * sizeof(particles::Vec3), 1);
      __builtin_prefetch(base + (i + 1) * sizeof(particles::Vec3) - 1, 1);
      if constexpr (Track) __builtin_prefetch(sys_.r.data() + first + i, 1);
    }
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
    const auto n_candidates = static_cast<std::uint64_t>(available * rate_);
    const double t0 = time_ - credit_;
    bool raised = false;
    std::uint64_t c = 0;
    for (; c < n_candidates; ++c) {
      const std::uint32_t a = ahead[2 * next], b = ahead[2 * next + 1];
      draw(next);
      next = (next + 1) % block_lookahead<Framed>;
      double gx = v[a].x - v[b].x, gy = v[a].y - v[b].y, gz = v[a].z - v[b].z;
      to_actual<Framed>(gx, gy, gz);
      const double g2 = gx * gx + gy * gy + gz * gz;
      // Accept with |g| / (2 vmax_b) = pi sigma^2 chi |g| / B_b (\ref sch_majorant "docs/schemes.md"), compared squared.
      const double threshold = gen.uniform() * limit;
      if (threshold * threshold >= g2) continue;
      if (g2 > limit * limit) [[unlikely]] note_overshoot(std::sqrt(g2) / limit);
      double px, py, pz;
      const double g_dot_e2 = rules::hemisphere_projection(gen, gx, gy, gz, std::sqrt(g2), px, py, pz);
      if (g_dot_e2 == 0.0) continue;
      if constexpr (Track) {
        const double t_collision = t0 + static_cast<double>(c + 1) * dt_candidate;
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
      } else {
        dissipated += Rule::collide_projected(va, vb, {share, share, loss}, g_dot_e2, {px, py, pz});
      }
      ++events;
      // "(sigma g)_max raised when exceeded" (header), for either partner: a new sub-step from here.
      const double speed2 = std::max(va.x * va.x + va.y * va.y + va.z * va.z, vb.x * vb.x + vb.y * vb.y + vb.z * vb.z);
      if (speed2 > max_speed2) {
        max_speed2 = speed2;
        raised = true;
        ++c;
        break;
      }
    }
    candidates += c;
    if (raised) {
      time_ = t0 + static_cast<double>(c) * dt_candidate;
      credit_ = 0.0;
      continue;
    }
    credit_ = available - static_cast<double>(n_candidates) * dt_candidate;
    time_ = t_stop;
    break;
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

template <class Rule, bool Track, bool Lowrank, bool Framed, bool Two>
void Collider::run_block_mixture([[maybe_unused]] const Rule& rule, double t_stop) {
  // The process of run_majorant (or run_lowrank) on the block's slices (header "Mixtures in blocks"):
  // candidates at R_b, candidate c of a sub-step at t0 + (c + 1)/R_b; `majorant`: a uniform pair of the
  // block's N_b particles accepted with pi sigma_kj^2 chi_kj |g| / B_b; `lowrank`: (i, k) from the block's
  // alias table, a particle of each slice, accepted with |g| / (w_i + w_k). Only the work per candidate
  // is less, as in run_block_one_species: a pair of indices from one draw, the drawn-ahead pairs (with
  // their species, known from the slice, so no read of the species array) in locals, no viscoelastic
  // branch, the pair's constants in one record, and (g.e) e without e (hemisphere_projection).
  // Framed: as run_block_one_species (g = G (u_a - u_b), bounds times ||G||, the impulse mapped back with
  // G^-1, the change of Q summed here with each partner's mass).
  // The block's stream in a local copy (written back at the end): its state then stays in registers
  // instead of being stored and loaded again at every draw (the same draws, 2-5 % less time per candidate).
  rng::Xoshiro256pp gen = gen_;
  const std::size_t s = s_;
  const std::size_t* cum = slice_cum_.data() + current_block_ * (s + 1);
  const std::size_t* slice = slice_first_.data() + current_block_ * s;
  const auto n = static_cast<std::uint32_t>(range_count_);
  particles::Vec3* v = sys_.v.data();
  const double n_density = mix_.total_density();
  static_assert(std::is_same_v<typename Rule::Projected, rules::SmoothRule::Projected>,
                "the kernels' table (PairKernel) holds SmoothRule's projected constants");
  const PairKernel* kernel = pair_kernel_.data();
  // The acceptance's constant of each pair, apart from PairKernel so that a candidate reads 8 bytes at
  // 8 pair: `majorant` (pi sigma^2 chi)^2, `lowrank` w_i + w_k (set_block_lowrank).
  const double* acceptance = Lowrank ? pair_limit_.data() : pair_cross_section2_.data();
  double* speed2 = block_speed2_;
  // Per-pair event counts (up to pair_event_limit species; above, every pair's slot 0 of a sink).
  std::uint64_t sink = 0;
  std::uint64_t* pair_events = counters_.pair_events.empty() ? &sink : counters_.pair_events.data();
  // The block's i-th particle (0 <= i < N_b) is of species k for edge[k] <= i < edge[k + 1], at system
  // index i + offset[k] (its slice's first index less cum_k): 32-bit locals, so that a candidate's
  // species and indices take a compare and an add each instead of loads of the size_t slice tables.
  std::array<std::uint32_t, block_species_limit + 1> edge;
  std::array<std::uint32_t, block_species_limit> offset;
  if constexpr (!Lowrank) {
    for (std::size_t k = 0; k < s; ++k) {
      edge[k] = static_cast<std::uint32_t>(cum[k]);
      offset[k] = static_cast<std::uint32_t>(slice[k] - cum[k]);  // (modulo 2^32: x + offset is exact)
    }
    edge[s] = static_cast<std::uint32_t>(cum[s]);
  }
  // (species_at: a binary mixture's species by one compare; the general loop cost it a dozen instructions.)
  const auto species_of = [&](std::uint32_t i) { return species_at(edge.data(), s, i); };
  [[maybe_unused]] const std::uint32_t edge1 = Two ? edge[1] : 0, offset0 = Two ? offset[0] : 0,
                                       offset1 = Two ? offset[1] : 0;
  // `lowrank`'s one-word draw (set_block_lowrank), rebuilt with A_ik.
  const LowrankCell* cells = lowrank_cells_.data();
  const LowrankOutcome* outcomes = lowrank_outcomes_.data();
  const unsigned cell_bits = lowrank_cell_bits_;
  const std::uint32_t coin_mask = (1u << (16 - cell_bits)) - 1;
  // A drawn-ahead candidate: its particles' system indices and the pair i S + k (its PairKernel; its
  // species i and k, whose bounds are read only after a collision, from pair_species_).
  // In three arrays of 32-bit words rather than one of 12-byte records: a slot's words are then at
  // 4 slot, which an x86 address scales by itself (a record's 12 slot took extra instructions).
  struct Candidate {
    std::uint32_t a, b, pair;
  };
  const std::uint32_t* pair_species = pair_species_.data();
  std::array<std::uint32_t, block_lookahead<Framed>> ahead_a, ahead_b, ahead_pair;
  const auto draw = [&](std::size_t slot) {
    Candidate p;
    if constexpr (Lowrank) {  // (i, k) with probability A_ik / R_b, then a particle of each slice
      // From one word (set_block_lowrank): the alias cell from the top m bits, its coin from the next
      // 16 - m (a further uniform only when they tie with the threshold), the particles from the low two
      // 24-bit fields by below_pair's multiply-shift and rejection in 24 bits (Lemire 2019; either field
      // rejected: below_pair draws both particles of this pair again). A block with a slice of 2^24 or
      // more has every reject at 2^24: below_pair draws each of its candidates.
      const std::uint64_t r = gen();
      const LowrankCell& cell = cells[r >> (64 - cell_bits)];
      const auto q = static_cast<std::uint32_t>(r >> 48) & coin_mask;
      // Without a branch on q < whole (taken at random, its mispredictions cost about as much as the
      // rest of the draw): a mask selects the outcome; the tie q = whole (one in 2^(16-m)) branches.
      const std::uint32_t keep_mask = 0u - static_cast<std::uint32_t>(q < cell.whole);
      std::uint32_t outcome = (cell.keep & keep_mask) | (cell.other & ~keep_mask);
      if (q == cell.whole) [[unlikely]]
        outcome = gen.uniform() < cell.fraction ? cell.keep : cell.other;
      const LowrankOutcome& o = outcomes[outcome];
      const std::uint64_t m1 = (r & 0xffffffULL) * o.count_i, m2 = ((r >> 24) & 0xffffffULL) * o.count_k;
      std::uint32_t x = static_cast<std::uint32_t>(m1 >> 24), y = static_cast<std::uint32_t>(m2 >> 24);
      if ((static_cast<std::uint32_t>(m1) & 0xffffffu) < o.reject_i ||
          (static_cast<std::uint32_t>(m2) & 0xffffffu) < o.reject_k) [[unlikely]] {
        // On a copy of the stream: the stream itself then never has its address taken and stays in
        // registers (below_pair, out of line here, would otherwise make it live in memory throughout).
        rng::Xoshiro256pp rare = gen;
        rare.below_pair(o.count_i, o.count_k, x, y);
        gen = rare;
      }
      p = {o.first_i + x, o.first_k + y, o.pair};
    } else {  // a uniform pair of the block's particles
      std::uint32_t x, y;
      gen.below_pair(n, n - 1, x, y);
      y += y >= x;
      if constexpr (Two) {  // species_at's one compare, with edge[1] and the offsets in registers
        const std::uint32_t i = x >= edge1, k = y >= edge1;
        p = {x + (i ? offset1 : offset0), y + (k ? offset1 : offset0), 2 * i + k};
      } else {
        const std::uint32_t i = species_of(x), k = species_of(y);
        p = {x + offset[i], y + offset[k], static_cast<std::uint32_t>(i * s + k)};
      }
    }
    ahead_a[slot] = p.a;
    ahead_b[slot] = p.b;
    ahead_pair[slot] = p.pair;
    const auto* base = reinterpret_cast<const char*>(v);
    for (std::uint32_t q : {p.a, p.b}) {
      __builtin_prefetch(base + q * sizeof(particles::Vec3), 1);
      __builtin_prefetch(base + (q + 1) * sizeof(particles::Vec3) - 1, 1);
      if constexpr (Track) __builtin_prefetch(sys_.r.data() + q, 1);
    }
  };
  for (std::size_t slot = 0; slot < block_lookahead<Framed>; ++slot) draw(slot);
  std::size_t next = 0;
  std::uint64_t events = 0, candidates = 0;
  double dissipated = 0.0;
  [[maybe_unused]] std::array<double, 4> moments{};  // the change of sum m u u^T (xx, yy, zz, xy)
  for (;;) {
    // rate_ (and bound_, or the alias table and w_k = max_speed_) are those of the block's current bounds.
    const double bound = bound_;
    const double dt_candidate = 1.0 / rate_;
    const double available = credit_ + (t_stop - time_);
    const auto n_candidates = static_cast<std::uint64_t>(available * rate_);
    const double t0 = time_ - credit_;
    bool raised = false;
    std::uint64_t c = 0;
    for (; c < n_candidates; ++c) {
      const std::uint32_t a = ahead_a[next], b = ahead_b[next], pair = ahead_pair[next];
      draw(next);
      next = (next + 1) % block_lookahead<Framed>;
      if constexpr (Lowrank)
        if (a == b) continue;  // the self pair is part of the majorant's sum, never a collision
      double gx = v[a].x - v[b].x, gy = v[a].y - v[b].y, gz = v[a].z - v[b].z;
      to_actual<Framed>(gx, gy, gz);
      const double g2 = gx * gx + gy * gy + gz * gz;
      if constexpr (Lowrank) {
        // Accept with |g| / (w_i + w_k) (run_lowrank in a block: chi_ik cancels), compared squared.
        const double limit = acceptance[pair];  // w_i + w_k
        const double threshold = gen.uniform() * limit;
        if (threshold * threshold >= g2) continue;
        if (g2 > limit * limit) [[unlikely]] note_overshoot(std::sqrt(g2) / limit);
      } else {
        // Accept with pi sigma_kj^2 chi_kj |g| / B_b (\ref sch_majorant "docs/schemes.md"), compared squared.
        const double rate2 = acceptance[pair] * g2;  // (pi sigma^2 chi)^2 g^2: the same product as (cs cs) g2
        const double threshold = gen.uniform() * bound;
        if (threshold * threshold >= rate2) continue;
        if (rate2 > bound * bound) [[unlikely]] note_overshoot(std::sqrt(rate2) / bound);
      }
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
      const PairKernel& pk = kernel[pair];  // (read only for a collision)
      const std::uint32_t i = pair_species[2 * pair], k = pair_species[2 * pair + 1];
      if constexpr (Framed) {
        const double ma = mix_.mass[i], mb = mix_.mass[k];
        add_moments(moments, va, -ma);
        add_moments(moments, vb, -mb);
        dissipated += Rule::collide_projected(va, vb, pk.constants, g_dot_e2, to_stored(px, py, pz));  // G^-1 (g.e) e
        add_moments(moments, va, ma);
        add_moments(moments, vb, mb);
      } else {
        dissipated += Rule::collide_projected(va, vb, pk.constants, g_dot_e2, {px, py, pz});
      }
      ++events;
      ++pair_events[pk.event];
      // "(sigma g)_max raised when exceeded" (header), for both partners: a new sub-step from here.
      const double speed2_a = va.x * va.x + va.y * va.y + va.z * va.z;
      const double speed2_b = vb.x * vb.x + vb.y * vb.y + vb.z * vb.z;
      if (speed2_a > speed2[i] || speed2_b > speed2[k]) [[unlikely]] {
        speed2[i] = std::max(speed2[i], speed2_a);
        speed2[k] = std::max(speed2[k], speed2_b);
        raised = true;
        ++c;
        break;
      }
    }
    candidates += c;
    if (raised) {
      time_ = t0 + static_cast<double>(c) * dt_candidate;
      credit_ = 0.0;
      if constexpr (Lowrank) {
        set_block_lowrank(n_density);
        cells = lowrank_cells_.data();  // (their sizes do not change: the same data)
        for (std::size_t slot = 0; slot < block_lookahead<Framed>; ++slot) draw(slot);  // drawn from the old A_ik: redraw
        next = 0;
      } else {
        bound_ = mixture_bound(speed2, cum);
        if constexpr (Framed) bound_ *= speed_factor_;
        rate_ = 0.5 * static_cast<double>(n) * n_density * bound_;
      }
      continue;
    }
    credit_ = available - static_cast<double>(n_candidates) * dt_candidate;
    time_ = t_stop;
    break;
  }
  counters_.events += events;
  counters_.candidates += candidates;
  counters_.dissipated += dissipated;
  if constexpr (Framed)
    for (std::size_t q = 0; q < 4; ++q) moments_[q] += moments[q];
  gen_ = gen;
}

}  // namespace gdsmc::collide
