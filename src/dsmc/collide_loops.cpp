// The general loops of the collider (collide.hpp: `majorant`, `pairs`, `lowrank`, framed or not), templates
// on the collision rule (rules.hpp), and their dispatch.
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

// (with the loops that call them for every collision: inlined there)
bool Collider::raise_max_speed(std::size_t particle) {
  const std::uint32_t k = s_ > 1 ? sys_.species[particle] : 0;
  const particles::Vec3& v = sys_.v[particle];
  const double v2 = v.x * v.x + v.y * v.y + v.z * v.z;
  if (!block_first_.empty() && !whole_step_) {  // in blocks: the bound of the current block (and species)
    double& max2 = block_speed2_[k];
    if (v2 <= max2) return false;
    max2 = v2;
    return true;
  }
  if (v2 <= max_speed2_[k]) return false;
  max_speed_[k] = std::sqrt(v2);
  max_speed2_[k] = v2;
  raised_.push_back(k);
  return true;
}

void Collider::count_event(std::uint32_t k, std::uint32_t j) {
  ++counters_.events;
  if (counters_.pair_events.empty()) return;  // more than pair_event_limit species
  ++counters_.pair_events[std::min(k, j) * s_ + std::max(k, j)];
}

// Candidates of one sub-step at a fixed rate: candidate c (0-based) happens at
// time_ - credit_ + (c + 1)/R; what is left of the sub-step is carried in credit_.
// `try_candidate(a, b, t)` draws one candidate at time t and, when it is accepted, collides and counts it,
// sets the two particles and returns true. A template, so each scheme's loop is inlined whole.
template <class TryCandidate>
int Collider::run_substep(double t_stop, std::uint64_t event_target, TryCandidate&& try_candidate) {
  const double dt_candidate = 1.0 / rate_;
  const double available = credit_ + (t_stop - time_);
  const std::uint64_t n_candidates = candidate_count(available * rate_);
  const double t0 = time_ - credit_;
  for (std::uint64_t c = 0; c < n_candidates; ++c) {
    // An interrupt (set_stop_flag) seen every 2^16 candidates, however long the step: the run is then
    // abandoned, so the step may end here (the `pairs` scheme's steps of step_fraction = 100 took over 1 s).
    if ((c & 0xffffu) == 0xffffu && stop_requested()) [[unlikely]] {
      counters_.candidates += c;
      time_ = t0 + static_cast<double>(c) * dt_candidate;
      credit_ = 0.0;
      return static_cast<int>(Stop::reached_time);
    }
    std::size_t a, b;
    if (!try_candidate(a, b, t0 + static_cast<double>(c + 1) * dt_candidate)) continue;
    const bool raised_a = raise_max_speed(a);  // both partners, always
    const bool raised_b = raise_max_speed(b);
    const bool raised = raised_a || raised_b;
    if (raised || counters_.events >= event_target) {
      counters_.candidates += c + 1;
      time_ = t0 + static_cast<double>(c + 1) * dt_candidate;
      credit_ = 0.0;
      return static_cast<int>(raised ? Stop::bound_raised : Stop::reached_events);
    }
  }
  counters_.candidates += n_candidates;
  credit_ = available - static_cast<double>(n_candidates) * dt_candidate;
  time_ = t_stop;
  return static_cast<int>(Stop::reached_time);
}


void Collider::prefetch(const PendingPair& p) const {
  // A Vec3 may straddle two cache lines: touch its first and last byte.
  const auto* v = reinterpret_cast<const char*>(sys_.v.data());
  for (std::uint32_t i : {p.a, p.b}) {
    __builtin_prefetch(v + i * sizeof(particles::Vec3), 1);
    __builtin_prefetch(v + (i + 1) * sizeof(particles::Vec3) - 1, 1);
    if (s_ > 1) __builtin_prefetch(sys_.species.data() + i);
    if (sys_.tracks_displacements()) __builtin_prefetch(sys_.r.data() + i, 1);
  }
}

template <class Draw>
Collider::PendingPair Collider::next_pair(Draw&& draw) {
  if (!pending_filled_) {
    for (PendingPair& p : pending_) {
      p = draw();
      prefetch(p);
    }
    pending_next_ = 0;
    pending_filled_ = true;
  }
  PendingPair& slot = pending_[pending_next_];
  const PendingPair p = slot;
  slot = draw();
  prefetch(slot);
  pending_next_ = (pending_next_ + 1) % lookahead;
  return p;
}

template <class Rule, bool Framed>
int Collider::run_majorant(const Rule& rule, double t_stop, std::uint64_t event_target) {
  const bool track = sys_.tracks_displacements();  // may start in the middle of a run
  // Candidates among all particles, or among those of the current block (header, "Blocks").
  const auto first = static_cast<std::uint32_t>(range_first_);
  const auto n = static_cast<std::uint32_t>(range_count_);
  particles::Vec3* v = sys_.v.data();
  const std::uint32_t* sp = sys_.species.data();
  const bool mixture = s_ > 1;
  // A mixture's block is a slice of each species (header "Blocks"): candidate i of the block's N_b is
  // particle i - cum_k of species k's slice, cum_k <= i < cum_k+1.
  const bool sliced = mixture && !block_first_.empty() && !whole_step_;
  const std::size_t* cum = sliced ? block_slice_cum() : nullptr;
  const std::size_t* slice = sliced ? block_slice_first() : nullptr;
  const auto to_particle = [&](std::uint32_t i) {
    std::size_t k = 0;
    while (i >= cum[k + 1]) ++k;
    return static_cast<std::uint32_t>(slice[k] + (i - cum[k]));
  };
  const auto draw = [&] {
    const auto a = static_cast<std::uint32_t>(gen_.below(n));
    auto b = static_cast<std::uint32_t>(gen_.below(n - 1));
    if (b >= a) ++b;
    if (sliced) return PendingPair{to_particle(a), to_particle(b), 0, 0};
    return PendingPair{first + a, first + b, 0, 0};
  };
  return run_substep(t_stop, event_target, [&](std::size_t& a, std::size_t& b, double t_collision) {
    const PendingPair p = next_pair(draw);
    a = p.a;
    b = p.b;
    const std::uint32_t ka = mixture ? sp[a] : 0, kb = mixture ? sp[b] : 0;
    const std::size_t pair = ka * s_ + kb;
    double gx = v[a].x - v[b].x, gy = v[a].y - v[b].y, gz = v[a].z - v[b].z;
    to_actual<Framed>(gx, gy, gz);
    const double g2 = gx * gx + gy * gy + gz * gz;
    // Accept with pi sigma^2 chi |g| / B (DSMC notes, eq. (7), \ref sch_majorant "docs/schemes.md"), compared squared: no root for a rejection.
    const double cross_section = cross_section_[pair];
    const double rate2 = cross_section * cross_section * g2;
    const double threshold = gen_.uniform() * bound_;
    if (threshold * threshold >= rate2) return false;
    // A probability above 1 is always accepted (U B < B < rate), so the invariant is checked here only.
    if (rate2 > bound_ * bound_) [[unlikely]] note_overshoot(std::sqrt(rate2) / bound_);
    double ex, ey, ez;
    if (!rules::hemisphere_normal(gen_, gx, gy, gz, std::sqrt(g2), ex, ey, ez)) return false;
    if constexpr (!Framed)  // (a frame tracks no displacements: set_frame)
      if (track) {
        particles::flush_free_flight(sys_, a, t_collision);
        particles::flush_free_flight(sys_, b, t_collision);
      }
    collide_pair<Rule, Framed>(rule, a, b, ka, kb, ex, ey, ez, gx * ex + gy * ey + gz * ez);
    return true;
  });
}

template <class Rule, bool Framed>
int Collider::run_pairs(const Rule& rule, double t_stop, std::uint64_t event_target) {
  const bool track = sys_.tracks_displacements();  // may start in the middle of a run
  return run_substep(t_stop, event_target, [&](std::size_t& k, std::size_t& l, double t_collision) {
    // The ordered species pair (i, j) with probability R_ij / R.
    const double u = gen_.uniform() * rate_;
    const std::size_t pair = static_cast<std::size_t>(
        std::upper_bound(pair_cumulative_.begin(), pair_cumulative_.end(), u) -
        pair_cumulative_.begin());
    if (pair >= s_ * s_) return false;  // u == R to round-off
    const std::size_t i = pair / s_, j = pair % s_;
    k = sys_.first[i] + gen_.below(sys_.count[i]);
    if (i == j) {
      l = sys_.first[j] + gen_.below(sys_.count[j] - 1);
      if (l >= k) ++l;
    } else {
      l = sys_.first[j] + gen_.below(sys_.count[j]);
    }
    double ex, ey, ez;
    rng::unit_vector(gen_, ex, ey, ez);  // Montanero and Garzo 2002, step (1), \ref sch_pairs "docs/schemes.md": e uniform on the sphere
    double gx = sys_.v[k].x - sys_.v[l].x, gy = sys_.v[k].y - sys_.v[l].y, gz = sys_.v[k].z - sys_.v[l].z;
    to_actual<Framed>(gx, gy, gz);
    const double g_dot_e = gx * ex + gy * ey + gz * ez;
    if (shear_rate_ > 0.0) {  // Enskog in shear flow: the shifted relative velocity (set_shear, \ref eta_enskog_shear "docs/shear-viscosity.md")
      const double sigma = contact_[pair];
      const double shifted = g_dot_e - shear_rate_ * sigma * ey * ex;
      const double g_max = (max_speed_[i] + max_speed_[j]) * speed_factor_ + 0.5 * shear_rate_ * sigma;
      if (shifted <= 0.0 || gen_.uniform() * g_max >= shifted) return false;
      if (shifted > g_max) [[unlikely]] note_overshoot(shifted / g_max);  // accepted, as every p > 1
      // (no displacements: a shear flow tracks none)
      const rules::Outcome out =
          collide_pair<Rule, Framed>(rule, k, l, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), ex, ey, ez, shifted);
      const double w = out.impulse * sigma;  // m_ij sigma_ij (1 + alpha)(g.e)
      auto& t = counters_.transfer;
      t[0] += w * ex * ex, t[1] += w * ey * ey, t[2] += w * ez * ez;
      t[3] += w * ex * ey, t[4] += w * ex * ez, t[5] += w * ey * ez;
      return true;
    }
    // Step (2): accept with Theta(g.e) |g.e| / g_max, g_max = vmax_i + vmax_j.
    const double g_max = (max_speed_[i] + max_speed_[j]) * speed_factor_;
    if (g_dot_e <= 0.0 || gen_.uniform() * g_max >= g_dot_e) return false;
    if (g_dot_e > g_max) [[unlikely]] note_overshoot(g_dot_e / g_max);  // accepted, as every p > 1
    if constexpr (!Framed)  // (a frame tracks no displacements: set_frame)
      if (track) {
        particles::flush_free_flight(sys_, k, t_collision);
        particles::flush_free_flight(sys_, l, t_collision);
      }
    collide_pair<Rule, Framed>(rule, k, l, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), ex, ey, ez, g_dot_e);
    return true;
  });
}

template <class Rule, bool Framed>
int Collider::run_lowrank(const Rule& rule, double t_stop, std::uint64_t event_target) {
  const bool track = sys_.tracks_displacements();  // may start in the middle of a run
  particles::Vec3* v = sys_.v.data();
  // In a block (a worker, header "Mixtures in blocks"): the particles of the block's slice of each species.
  const bool sliced = !block_first_.empty() && !whole_step_;
  const std::size_t* cum = sliced ? block_slice_cum() : nullptr;
  const std::size_t* slice = sliced ? block_slice_first() : nullptr;
  const auto draw = [&] {
    if (sliced) {  // (i, k) with probability A_ik / R from the block's alias table (set_block_lowrank)
      const std::size_t pair = pair_alias_.sample(gen_.uniform());
      const std::size_t i = pair / s_, k = pair % s_;
      return PendingPair{static_cast<std::uint32_t>(slice[i] + gen_.below(cum[i + 1] - cum[i])),
                         static_cast<std::uint32_t>(slice[k] + gen_.below(cum[k + 1] - cum[k])),
                         static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(k)};
    }
    const auto [i, k] = lowrank_.sample(gen_);  // (i, k) with probability A_ik / R
    return PendingPair{static_cast<std::uint32_t>(sys_.first[i] + gen_.below(sys_.count[i])),
                       static_cast<std::uint32_t>(sys_.first[k] + gen_.below(sys_.count[k])),
                       static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(k)};
  };
  return run_substep(t_stop, event_target, [&](std::size_t& a, std::size_t& b, double t_collision) {
    const PendingPair p = next_pair(draw);
    a = p.a;
    b = p.b;
    if (a == b) return false;  // the self pair is part of the majorant's sum, never a collision
    const std::size_t i = p.i, k = p.k;
    double gx = v[a].x - v[b].x, gy = v[a].y - v[b].y, gz = v[a].z - v[b].z;
    to_actual<Framed>(gx, gy, gz);
    const double g2 = gx * gx + gy * gy + gz * gz;
    // Accept with chi_ik |g| / (chi_max (w_i + w_k)) (Bodrova and Osinsky 2024, eq. (11) with \ref cm_pair_rate "docs/collision-model.md"), compared squared;
    // in a block, whose A_ik hold chi_ik itself (set_block_lowrank), with |g| / (w_i + w_k).
    const double chi = mix_.pair_correlation(i, k);
    const double bound = (sliced ? chi : chi_max_) * ((max_speed_[i] + max_speed_[k]) * speed_factor_);
    const double rate2 = chi * chi * g2;
    const double threshold = gen_.uniform() * bound;
    if (threshold * threshold >= rate2) return false;
    if (rate2 > bound * bound) [[unlikely]] note_overshoot(std::sqrt(rate2) / bound);  // accepted, as every p > 1
    double ex, ey, ez;  // e ~ (g_hat.e) on the hemisphere, as in run_majorant
    if (!rules::hemisphere_normal(gen_, gx, gy, gz, std::sqrt(g2), ex, ey, ez)) return false;
    if constexpr (!Framed)  // (a frame tracks no displacements: set_frame)
      if (track) {
        particles::flush_free_flight(sys_, a, t_collision);
        particles::flush_free_flight(sys_, b, t_collision);
      }
    collide_pair<Rule, Framed>(rule, a, b, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(k), ex, ey, ez,
                               gx * ex + gy * ey + gz * ez);
    return true;
  });
}

// After the loops' definitions: clang instantiates the templates a generic lambda names only where they are
// defined before it (the clang build of scripts/clang-fuzz.sh failed to link otherwise).
int Collider::run_loop(Scheme loop, double t_stop, std::uint64_t event_target) {
  return std::visit(
      [&](const auto& rule) -> int {
        using Rule = std::decay_t<decltype(rule)>;
        if constexpr (Rule::frames) {
          if (framed_)
            return loop == Scheme::majorant ? run_majorant<Rule, true>(rule, t_stop, event_target)
                   : loop == Scheme::pairs  ? run_pairs<Rule, true>(rule, t_stop, event_target)
                                            : run_lowrank<Rule, true>(rule, t_stop, event_target);
        }
        return loop == Scheme::majorant ? run_majorant<Rule, false>(rule, t_stop, event_target)
               : loop == Scheme::pairs  ? run_pairs<Rule, false>(rule, t_stop, event_target)
                                        : run_lowrank<Rule, false>(rule, t_stop, event_target);
      },
      rule_);
}

}  // namespace gdsmc::collide
