#include "dsmc/collide.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <exception>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gdsmc::collide {

const char* Collider::block_draw_name(BlockDraw draw) {
  switch (draw) {
    case BlockDraw::one_species: return "one species";
    case BlockDraw::majorant: return "majorant";
    case BlockDraw::lowrank: return "lowrank";
    case BlockDraw::separable: return "separable";
    case BlockDraw::clusters: return "clusters";
    case BlockDraw::cheaper: return "majorant or lowrank, the cheaper at each step";
    case BlockDraw::unblocked: return "unblocked";
  }
  return nullptr;
}

Collider::Collider(Scheme scheme, const species::Mixture& mix, particles::System& sys, rng::Xoshiro256pp gen,
                   double step_fraction, rules::Rule rule)
    : scheme_(scheme), mix_(mix), sys_(sys), gen_(gen), step_fraction_(step_fraction),
      s_(mix.size()), tables_(!(scheme == Scheme::lowrank && s_ > species::dense_pair_limit)),
      rule_(std::move(rule)),
      kernels_(std::visit([](const auto& r) { return std::decay_t<decltype(r)>::has_projection; }, rule_)) {
  if (sys.size() > UINT32_MAX) throw std::invalid_argument("collide: more than 2^32 - 1 particles in one replica");
  std::visit([&](auto& r) { r.attach(sys); }, rule_);
  // The S x S cross sections make the majorant and pairs loops table lookups; the lowrank scheme with
  // thousands of species computes the few pair quantities it needs per accepted collision instead.
  if (tables_) {
    cross_section_.resize(s_ * s_);
    for (std::size_t k = 0; k < s_; ++k)
      for (std::size_t j = 0; j < s_; ++j) {
        const double sigma = mix.contact_distance(k, j);
        cross_section_[k * s_ + j] = std::numbers::pi * sigma * sigma * mix.pair_correlation(k, j);
      }
  }
  if (tables_ && s_ > 1 && s_ <= block_species_limit) {  // the mixture block kernel's pair constants
    pair_limit_.assign(s_ * s_, 0.0);
    // (the projected constants for SmoothRule; a rule whose kernels call collide_at uses only the slot)
    const auto* smooth = std::get_if<rules::SmoothRule>(&rule_);
    for (std::size_t k = 0; k < s_; ++k)
      for (std::size_t j = 0; j < s_; ++j)
        pair_kernel_.push_back({smooth ? smooth->pair(k, j) : rules::SmoothRule::Projected{},
                                s_ <= pair_event_limit ? static_cast<std::uint32_t>(std::min(k, j) * s_ + std::max(k, j))
                                                       : 0u});
    for (std::size_t k = 0; k < s_; ++k)
      for (std::size_t j = 0; j < s_; ++j) {
        pair_cross_section2_.push_back(cross_section_[k * s_ + j] * cross_section_[k * s_ + j]);
        pair_species_.insert(pair_species_.end(), {static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(j)});
      }
  }
  max_speed_.assign(s_, 0.0);
  max_speed2_.assign(s_, 0.0);
  range_first_ = 0;
  range_count_ = sys.size();
  if (scheme_ == Scheme::pairs) {
    pair_rate_.assign(s_ * s_, 0.0);
    pair_cumulative_.assign(s_ * s_, 0.0);
  }
  if (s_ <= pair_event_limit) counters_.pair_events.assign(s_ * s_, 0);
  if (scheme_ == Scheme::lowrank) {
    chi_max_ = mix.enskog ? mix.pair_correlation.max() : 1.0;
    lowrank_ = segment_tree::LowRankSampler<3>(s_);
    lowrank_volume_ = static_cast<double>(sys.size() - 1) / mix.total_density();
  }
}

segment_tree::HardSphereFactors Collider::lowrank_factors(std::size_t k) const {
  // A_ik = pi sigma_ik^2 chi_max w_i N_i N_k / V in rank-3 form (segment_tree.hpp, \ref sch_lowrank_decomposition "docs/schemes.md")
  auto f = segment_tree::hard_sphere_factors(static_cast<double>(sys_.count[k]), mix_.diameter[k],
                                             max_speed_[k] * speed_factor_, lowrank_volume_);
  for (double& x : f.row) x *= chi_max_;
  return f;
}

void Collider::set_lowrank_row(std::size_t k) {
  const auto f = lowrank_factors(k);
  lowrank_.set_row(k, f.row);
  // v_k depends on N_k and sigma_k only: set once, then sampled from alias tables (segment_tree.hpp).
  if (!lowrank_columns_set_) lowrank_.set_column(k, f.column);
}

void Collider::raise_lowrank_rows() {
  // O(log M) per raised species, not a rebuild: every tree node is recomputed from its children, so the
  // sums are those a rebuild would give (segment_tree.hpp, "Round-off").
  for (std::size_t k : raised_) set_lowrank_row(k);
  raised_.clear();
  rate_ = lowrank_.total();
  pending_filled_ = false;  // drawn from the old A_ik: redraw (header, "Look-ahead")
}

void Collider::recompute_max_speeds() {
  for (std::size_t k = 0; k < s_; ++k) {
    double max2 = 0.0;
    const std::size_t end = sys_.first[k] + sys_.count[k];
    for (std::size_t i = sys_.first[k]; i < end; ++i)
      max2 = std::max(max2, sys_.v[i].x * sys_.v[i].x + sys_.v[i].y * sys_.v[i].y + sys_.v[i].z * sys_.v[i].z);
    max_speed_[k] = std::sqrt(max2);
    max_speed2_[k] = max2;
  }
}

void Collider::rebuild_bounds() {
  const double n = mix_.total_density();
  const double n_sim = static_cast<double>(sys_.size());
  if (scheme_ == Scheme::lowrank) {
    // Every row at once: O(S) instead of a tree update of O(log S) per row (with 1e5 species, each
    // whole-gas step near an event target rebuilds them). The same sums (segment_tree.hpp).
    std::vector<segment_tree::LowRankSampler<3>::Vector> rows(s_);
    for (std::size_t k = 0; k < s_; ++k) {
      const auto f = lowrank_factors(k);
      rows[k] = f.row;
      if (!lowrank_columns_set_) lowrank_.set_column(k, f.column);
    }
    lowrank_.set_rows(rows);
    if (!lowrank_columns_set_) {
      lowrank_.freeze_columns();
      lowrank_columns_set_ = true;
    }
    raised_.clear();
    rate_ = lowrank_.total();
    pending_filled_ = false;  // drawn from the old A_ik: redraw (header, "Look-ahead")
  } else if (scheme_ == Scheme::majorant) {
    bound_ = 0.0;
    for (std::size_t k = 0; k < s_; ++k)
      for (std::size_t j = 0; j < s_; ++j)
        bound_ = std::max(bound_, cross_section_[k * s_ + j] * ((max_speed_[k] + max_speed_[j]) * speed_factor_));
    rate_ = 0.5 * n_sim * n * bound_;  // R = N n B / 2 (DSMC notes, eq. (8) with \ref sch_majorant "docs/schemes.md")
  } else {
    double total = 0.0;
    for (std::size_t i = 0; i < s_; ++i)
      for (std::size_t j = 0; j < s_; ++j) {
        // The simulated density of species j, n N_j / N, so that both schemes see the same gas.
        const double n_j = n * static_cast<double>(sys_.count[j]) / n_sim;
        // R_ij = (1/2) N_i omega_max^(ij), omega_max = 4 pi sigma_ij^2 n_j chi_ij g_max (Montanero and Garzo 2002, sec. 3, \ref sch_pairs "docs/schemes.md")
        // (with shear, the bound of |g.e| grows by a sigma_ij/2: set_shear)
        const double g_max = (max_speed_[i] + max_speed_[j]) * speed_factor_ +
                             (shear_rate_ > 0.0 ? 0.5 * shear_rate_ * contact_[i * s_ + j] : 0.0);
        pair_rate_[i * s_ + j] = 2.0 * static_cast<double>(sys_.count[i]) * n_j * cross_section_[i * s_ + j] * g_max;
        total += pair_rate_[i * s_ + j];
        pair_cumulative_[i * s_ + j] = total;
      }
    rate_ = total;
  }
}

Collider::State Collider::state() const {
  State st;
  st.time = time_;
  st.credit = credit_;
  st.next_step_time = next_step_time_;
  st.max_speed = max_speed_;
  st.max_speed2 = max_speed2_;
  st.counters = counters_;
  st.generator = gen_.state();
  for (const PendingPair& p : pending_) st.pending.insert(st.pending.end(), {p.a, p.b, p.i, p.k});
  st.pending_next = pending_next_;
  st.pending_filled = pending_filled_;
  st.block_max_speed2 = block_max_speed2_;
  st.block_credit = block_credit_;
  if (scattered_any_) st.slice_counts.assign(slice_count_.begin(), slice_count_.end());
  st.step_start = step_start_;
  st.remix_time = remix_time_;
  st.whole_step = whole_step_;
  st.step_acceptance = step_acceptance_;
  st.step_events_start = step_events_start_;
  st.step_candidates_start = step_candidates_start_;
  st.step_planned_candidates = step_planned_candidates_;
  st.probe = static_cast<int>(probe_);
  st.probe_time = probe_time_;
  st.probe_events = probe_events_;
  st.probe_candidates = probe_candidates_;
  st.block_lowrank = block_lowrank_ ? 1 : 0;
  st.framed = framed_;
  st.frame_scale = frame_scale_;
  st.frame_shear = frame_shear_;
  st.moments = moments_;
  return st;
}

double time_at_rest(double t_target) {
  // (a gas at rest is no state of a run: particles::restore refuses one; bounds forged to zero remain)
  if (std::isinf(t_target))
    throw std::runtime_error("collide: every speed bound is zero, so no collision can come and the event target is "
                             "never reached (a state no run makes: a damaged checkpoint?)");
  return t_target;
}

void Collider::restore(const State& st) {
  if (st.max_speed.size() != s_ || st.max_speed2.size() != s_ || st.pending.size() != 4 * lookahead ||
      st.pending_next >= lookahead || st.counters.pair_events.size() != counters_.pair_events.size())
    throw std::invalid_argument("collide: the saved state does not fit this collider");
  // What every run keeps: time from 0, a credit (the time since the last candidate) within it, bounds >= 0;
  // up to round-off (before a first candidate the credit sums the cuts' lengths, credit + (t_stop - time),
  // which can round one step above t_stop; available - n dt a few steps below 0).
  const double slack = 1e-9 * st.time;  // (each cut adds an ulp or so: a million cuts before a first candidate)
  const auto within_time = [&](double credit) { return credit >= -slack && credit <= st.time + slack; };
  const auto non_negative = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return x >= 0.0; });
  };
  if (!(st.time >= 0.0) || !within_time(st.credit) || !std::all_of(st.block_credit.begin(), st.block_credit.end(), within_time))
    throw std::invalid_argument("collide: the saved time or credit is negative, or a credit exceeds the time");
  if (!(st.next_step_time >= 0.0) || !non_negative(st.max_speed) || !non_negative(st.max_speed2) ||
      !non_negative(st.block_max_speed2))
    throw std::invalid_argument("collide: a saved step time or speed bound is negative");
  time_ = st.time;
  credit_ = st.credit;
  next_step_time_ = st.next_step_time;
  max_speed_ = st.max_speed;
  max_speed2_ = st.max_speed2;
  counters_ = st.counters;
  gen_.set_state(st.generator);
  raised_.clear();
  if (st.block_max_speed2.size() != block_max_speed2_.size() || st.block_credit.size() != block_credit_.size())
    throw std::invalid_argument("collide: the saved state has other blocks than this collider");
  block_max_speed2_ = st.block_max_speed2;
  block_credit_ = st.block_credit;
  if (scattered_any_) {  // this step's slices of the scattered species (the particles are in that order)
    if (st.slice_counts.size() != slice_count_.size())
      throw std::invalid_argument("collide: the saved state has no slices of the scattered species");
    for (std::size_t q = 0; q < slice_count_.size(); ++q) {
      if (!scattered_[q % s_] && st.slice_counts[q] != slice_count_[q])
        throw std::invalid_argument("collide: the saved state has other slices than this collider");
      slice_count_[q] = static_cast<std::size_t>(st.slice_counts[q]);
    }
    for (std::size_t k = 0; k < s_; ++k) {
      std::size_t total = 0;
      for (std::size_t q = k; q < slice_count_.size(); q += s_) total += slice_count_[q];
      if (total != sys_.count[k]) throw std::invalid_argument("collide: the saved slices do not add up to the species' count");
    }
    set_slices();
  }
  step_start_ = st.step_start;
  remix_time_ = st.remix_time;
  whole_step_ = st.whole_step;
  step_acceptance_ = st.step_acceptance;
  step_events_start_ = st.step_events_start;
  step_candidates_start_ = st.step_candidates_start;
  if (!(st.step_planned_candidates >= 0.0) || std::isinf(st.step_planned_candidates))
    throw std::invalid_argument("collide: the saved state's planned candidates of its step are not a count");
  step_planned_candidates_ = st.step_planned_candidates;
  if (st.probe < 0 || st.probe > 2) throw std::invalid_argument("collide: the saved state's probe is not 0, 1 or 2");
  if (st.probe == 1 && !(st.probe_time > st.step_start && st.probe_time <= st.next_step_time))
    throw std::invalid_argument("collide: the saved state's pending probe is not inside its step");
  if (st.probe == 2 && (st.probe_events > st.probe_candidates || st.step_events_start > st.counters.events ||
                        st.probe_events > st.counters.events - st.step_events_start))
    throw std::invalid_argument("collide: the saved state's probe has more events than its candidates or its step");
  probe_ = static_cast<Probe>(st.probe);
  probe_time_ = st.probe_time;
  probe_events_ = st.probe_events;
  probe_candidates_ = st.probe_candidates;
  framed_ = st.framed;
  frame_scale_ = st.frame_scale;
  frame_inverse_scale_ = 1.0 / frame_scale_;
  frame_shear_ = st.frame_shear;
  speed_factor_ = framed_ ? frame_norm(frame_scale_, frame_shear_) : 1.0;
  moments_ = st.moments;
  // The step's block sampler: as saved, or (a checkpoint written before it was saved) the scheme's,
  // which the code that wrote it ran; the next step chooses, as after any change of sampler.
  block_lowrank_ = st.block_lowrank >= 0 ? st.block_lowrank == 1 : lowrank_blocks();
  // What the last rebuild or raise computed (header of State); with blocks each block sets its own.
  if (counters_.steps > 0 && block_first_.empty()) rebuild_bounds();
  if (counters_.steps > 0 && !block_first_.empty() && whole_step_) set_whole_gas_bound();
  if (counters_.steps > 0 && !block_first_.empty() && !whole_step_ && framed_) rebuild_bounds();  // as advance_blocks
  for (std::size_t c = 0; c < lookahead; ++c)
    pending_[c] = {st.pending[4 * c], st.pending[4 * c + 1], st.pending[4 * c + 2], st.pending[4 * c + 3]};
  pending_next_ = st.pending_next;
  pending_filled_ = st.pending_filled;
}


void Collider::save(state::Record& r) const {
  const State s = state();
  r.put("collider/time", s.time);
  r.put("collider/credit", s.credit);
  r.put("collider/next_step_time", s.next_step_time);
  r.put("collider/max_speed", s.max_speed);
  r.put("collider/max_speed2", s.max_speed2);
  r.put_integer("collider/events", s.counters.events);
  r.put_integer("collider/candidates", s.counters.candidates);
  r.put_integer("collider/steps", s.counters.steps);
  r.put_integer("collider/overshoots", s.counters.overshoots);
  r.put("collider/step_sum", s.counters.step_sum);
  r.put("collider/dissipated", s.counters.dissipated);
  r.put("collider/pair_events", s.counters.pair_events);
  r.put("collider/transfer", std::vector<double>(s.counters.transfer.begin(), s.counters.transfer.end()));
  r.put("collider/generator", std::vector<std::uint64_t>(std::begin(s.generator.s), std::end(s.generator.s)));
  r.put("collider/generator_spare", s.generator.spare);
  r.put_integer("collider/generator_has_spare", s.generator.has_spare);
  r.put("collider/pending", std::vector<std::uint64_t>(s.pending.begin(), s.pending.end()));
  r.put_integer("collider/pending_next", s.pending_next);
  r.put_integer("collider/pending_filled", s.pending_filled);
  r.put("collider/block_max_speed2", s.block_max_speed2);
  r.put("collider/block_credit", s.block_credit);
  if (!s.slice_counts.empty()) r.put("collider/slice_counts", s.slice_counts);
  r.put("collider/step_start", s.step_start);
  r.put("collider/remix_time", s.remix_time);
  r.put("collider/step_acceptance", s.step_acceptance);
  r.put_integer("collider/whole_step", s.whole_step);
  r.put_integer("collider/step_events_start", s.step_events_start);
  r.put_integer("collider/step_candidates_start", s.step_candidates_start);
  r.put("collider/step_planned_candidates", s.step_planned_candidates);
  r.put_integer("collider/probe", static_cast<std::uint64_t>(s.probe));
  r.put("collider/probe_time", s.probe_time);
  r.put_integer("collider/probe_events", s.probe_events);
  r.put_integer("collider/probe_candidates", s.probe_candidates);
  // (the step's block sampler: 0 `majorant`, 1 `lowrank`, 2 unknown, i.e. the scheme's)
  r.put_integer("collider/block_sampler", s.block_lowrank < 0 ? 2 : static_cast<std::uint64_t>(s.block_lowrank));
  r.put_integer("collider/framed", s.framed);
  r.put("collider/frame_scale", s.frame_scale);
  r.put("collider/frame_shear", s.frame_shear);
  r.put("collider/moments", std::vector<double>(s.moments.begin(), s.moments.end()));
}

void Collider::restore(const state::Record& r) {
  State s;
  s.time = r.real("collider/time");
  s.credit = r.real("collider/credit");
  s.next_step_time = r.real("collider/next_step_time");
  s.max_speed = r.array("collider/max_speed", s_);
  s.max_speed2 = r.array("collider/max_speed2", s_);
  s.counters.events = r.integer("collider/events");
  s.counters.candidates = r.integer("collider/candidates");
  s.counters.steps = r.integer("collider/steps");
  s.counters.overshoots = r.integer("collider/overshoots");
  s.counters.step_sum = r.real("collider/step_sum");
  s.counters.dissipated = r.real("collider/dissipated");
  s.counters.pair_events = r.integer_array("collider/pair_events");
  const auto& transfer = r.array("collider/transfer", 6);
  std::copy(transfer.begin(), transfer.end(), s.counters.transfer.begin());
  const auto& generator = r.integer_array("collider/generator", 4);
  std::copy(generator.begin(), generator.end(), std::begin(s.generator.s));
  s.generator.spare = r.real("collider/generator_spare");
  s.generator.has_spare = r.flag("collider/generator_has_spare");
  const auto& pending = r.integer_array("collider/pending", 4 * lookahead);
  for (std::size_t q = 0; q < pending.size(); ++q)  // particles a, b and species i, k of each
    if (pending[q] >= (q % 4 < 2 ? sys_.size() : s_))
      throw state::StateError("a drawn-ahead candidate names a particle or species that does not exist");
  s.pending.assign(pending.begin(), pending.end());
  s.pending_next = r.integer("collider/pending_next");
  s.pending_filled = r.flag("collider/pending_filled");
  s.block_max_speed2 = r.array("collider/block_max_speed2");
  s.block_credit = r.array("collider/block_credit");
  if (s.block_credit.size() != block_credit_.size())  // (the count follows from N, S and block_size alone)
    throw state::StateMismatch("it holds " + std::to_string(s.block_credit.size()) + " cache blocks where this build makes " +
                               std::to_string(block_credit_.size()) + " of the same gas (its rule for the blocks of lowrank mixtures of more than 128 " +
                               "species differs): resume it with the build that wrote it");
  if (r.has_integers("collider/slice_counts")) s.slice_counts = r.integer_array("collider/slice_counts");
  s.step_start = r.real("collider/step_start");
  // (written since 2026-11-30; before, every step but the whole-gas ones remixed: its step's start)
  s.remix_time = r.has("collider/remix_time") ? r.real("collider/remix_time") : s.step_start;
  s.step_acceptance = r.real("collider/step_acceptance");
  s.whole_step = r.flag("collider/whole_step");
  s.step_events_start = r.integer("collider/step_events_start");
  s.step_candidates_start = r.integer("collider/step_candidates_start");
  // (written since 2026-12-02; before, 0: the last step judged long or short by its candidates)
  s.step_planned_candidates = r.has("collider/step_planned_candidates") ? r.real("collider/step_planned_candidates") : 0.0;
  // (written since 2026-11-30; before, no step had a probe)
  if (r.has_integers("collider/probe")) {
    const std::uint64_t probe = r.integer("collider/probe");
    if (probe > 2) throw state::StateError("'collider/probe' is " + std::to_string(probe) + ", not 0, 1 or 2");
    s.probe = static_cast<int>(probe);
    s.probe_time = r.real("collider/probe_time");
    s.probe_events = r.integer("collider/probe_events");
    s.probe_candidates = r.integer("collider/probe_candidates");
  }
  const std::uint64_t sampler = r.integer("collider/block_sampler");
  if (sampler > 2) throw state::StateError("'collider/block_sampler' is " + std::to_string(sampler) + ", not 0, 1 or 2");
  s.block_lowrank = sampler == 2 ? -1 : static_cast<int>(sampler);
  s.framed = r.flag("collider/framed");
  s.frame_scale = r.real("collider/frame_scale");
  s.frame_shear = r.real("collider/frame_shear");
  if (!(s.frame_scale > 0.0)) throw state::StateError("the velocity frame is damaged");
  const auto& moments = r.array("collider/moments", 4);
  std::copy(moments.begin(), moments.end(), s.moments.begin());
  restore(s);
}

void Collider::set_shear(double rate) {
  if (scheme_ != Scheme::pairs || !tables_)
    throw std::invalid_argument("collide: the shifted relative velocity of shear flow needs the 'pairs' scheme");
  shear_rate_ = rate;
  contact_.resize(s_ * s_);
  for (std::size_t i = 0; i < s_; ++i)
    for (std::size_t j = 0; j < s_; ++j) contact_[i * s_ + j] = mix_.contact_distance(i, j);
  if (rate_ > 0.0) rebuild_bounds();
}

void Collider::set_frame(double scale, double shear) {
  if (!std::visit([](const auto& r) { return std::decay_t<decltype(r)>::frames; }, rule_) || sys_.tracks_displacements())
    throw std::logic_error("collide: a frame needs constant restitution and no displacements");
  if (!(scale > 0.0) || !std::isfinite(scale) || !std::isfinite(shear))
    throw std::logic_error("collide: the frame's scale must be positive and finite");
  if (!framed_) {
    moments_ = {};
    for (std::size_t i = 0; i < sys_.size(); ++i) {
      add_moments(moments_, sys_.v[i], mix_.mass[s_ > 1 ? sys_.species[i] : 0]);
    }
    framed_ = true;
  }
  frame_scale_ = scale;
  frame_inverse_scale_ = 1.0 / scale;
  frame_shear_ = shear;
  speed_factor_ = frame_norm(scale, shear);
  if (rate_ > 0.0) rebuild_bounds();
}

void Collider::reset_frame(const std::array<double, 4>& moments, const std::vector<double>& max_speed2,
                           bool block_bounds_set) {
  framed_ = true;  // (a rule without frames runs its unframed loops in this identity frame: collide_kernels.cpp)
  frame_scale_ = 1.0;
  frame_inverse_scale_ = 1.0;
  frame_shear_ = 0.0;
  speed_factor_ = 1.0;
  moments_ = moments;
  set_max_speeds(max_speed2);
  // In blocks: each block's exact bound again (the velocities were all replaced), unless map_blocks kept them.
  if (block_bounds_set) return;
  for (std::size_t j = 0; j + 1 < block_first_.size(); ++j) set_block_max_speed2(j, block_max_speed2_.data() + j * s_);
}

bool Collider::advance(double t_target, std::uint64_t event_target, bool exact_events, std::uint64_t event_limit,
                       bool to_step_end) {
  if (!block_first_.empty()) return advance_blocks(t_target, event_target, exact_events, event_limit, to_step_end);
  event_target = std::min(event_target, event_limit);  // without blocks every target is met exactly
  while (time_ < t_target) {
    if (counters_.events >= event_target) return true;
    if (time_ >= next_step_time_) {
      if (stop_requested()) return false;
      recompute_max_speeds();
      rebuild_bounds();
      if (rate_ <= 0.0) {  // all particles at rest: nothing can ever collide
        time_ = time_at_rest(t_target);
        return false;
      }
      // dt = step_fraction / nu_max, nu_max = 2 R / N (header)
      const double step = step_fraction_ * static_cast<double>(sys_.size()) / (2.0 * rate_);
      next_step_time_ = time_ + step;
      ++counters_.steps;
      counters_.step_sum += step;
    }
    const double t_stop = std::min(t_target, next_step_time_);
    const int stop = run_loop(scheme_, t_stop, event_target);
    if (stop_requested()) return false;  // (the loop may have ended inside a step: run_substep)
    if (stop == static_cast<int>(Stop::bound_raised)) {
      if (scheme_ == Scheme::lowrank) {
        raise_lowrank_rows();
      } else {
        rebuild_bounds();
      }
    }
    if (stop == static_cast<int>(Stop::reached_events)) return true;
  }
  return false;
}

}  // namespace gdsmc::collide
