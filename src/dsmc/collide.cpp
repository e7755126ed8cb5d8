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

namespace {
enum class Stop { reached_time, bound_raised, reached_events };
/// Near an exact event target with blocks (header "Blocks"): whether a step expected to bring mu
/// events could reach the `remaining` ones, with 10 % and 8 standard deviations and 16 to spare.
bool may_reach(double mu, double remaining) { return 1.1 * mu + 8.0 * std::sqrt(mu) + 16.0 > remaining; }
}

Scheme parse_scheme(const std::string& name) {
  if (name == "majorant") return Scheme::majorant;
  if (name == "pairs") return Scheme::pairs;
  if (name == "lowrank") return Scheme::lowrank;
  throw std::invalid_argument("unknown scheme '" + name + "'");
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
    if (const auto* smooth = std::get_if<rules::SmoothRule>(&rule_))
      for (std::size_t k = 0; k < s_; ++k)
        for (std::size_t j = 0; j < s_; ++j)
          pair_kernel_.push_back({smooth->pair(k, j), s_ <= pair_event_limit
                                                         ? static_cast<std::uint32_t>(std::min(k, j) * s_ + std::max(k, j))
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

void Collider::set_lowrank_row(std::size_t k) {
  // A_ik = pi sigma_ik^2 chi_max w_i N_i N_k / V in rank-3 form (segment_tree.hpp, \ref sch_lowrank_decomposition "docs/schemes.md")
  auto f = segment_tree::hard_sphere_factors(static_cast<double>(sys_.count[k]), mix_.diameter[k],
                                             max_speed_[k] * speed_factor_, lowrank_volume_);
  for (double& x : f.row) x *= chi_max_;
  lowrank_.set_row(k, f.row);
  // v_k depends on N_k and sigma_k only: set once, then sampled from alias tables (segment_tree.hpp).
  if (!lowrank_columns_set_) lowrank_.set_column(k, f.column);
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
    for (std::size_t k = 0; k < s_; ++k) set_lowrank_row(k);
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
  st.whole_step = whole_step_;
  st.step_acceptance = step_acceptance_;
  st.step_events_start = step_events_start_;
  st.step_candidates_start = step_candidates_start_;
  st.block_lowrank = block_lowrank_ ? 1 : 0;
  st.framed = framed_;
  st.frame_scale = frame_scale_;
  st.frame_shear = frame_shear_;
  st.moments = moments_;
  return st;
}

void Collider::restore(const State& st) {
  if (st.max_speed.size() != s_ || st.max_speed2.size() != s_ || st.pending.size() != 4 * lookahead ||
      st.pending_next >= lookahead || (!counters_.pair_events.empty() && st.counters.pair_events.size() != s_ * s_))
    throw std::invalid_argument("collide: the saved state does not fit this collider");
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
  whole_step_ = st.whole_step;
  step_acceptance_ = st.step_acceptance;
  step_events_start_ = st.step_events_start;
  step_candidates_start_ = st.step_candidates_start;
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
  r.put("collider/step_acceptance", s.step_acceptance);
  r.put_integer("collider/whole_step", s.whole_step);
  r.put_integer("collider/step_events_start", s.step_events_start);
  r.put_integer("collider/step_candidates_start", s.step_candidates_start);
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
  if (r.has_integers("collider/slice_counts")) s.slice_counts = r.integer_array("collider/slice_counts");
  s.step_start = r.real("collider/step_start");
  s.step_acceptance = r.real("collider/step_acceptance");
  s.whole_step = r.flag("collider/whole_step");
  s.step_events_start = r.integer("collider/step_events_start");
  s.step_candidates_start = r.integer("collider/step_candidates_start");
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

void Collider::use_blocks(std::size_t block_size) {
  block_first_.clear();
  scattered_.assign(s_, 0);
  scattered_any_ = false;
  const std::size_t n = sys_.size();
  const bool one = s_ == 1 && scheme_ != Scheme::pairs;
  const bool mixture = s_ > 1 && scheme_ != Scheme::pairs && s_ <= block_species_limit && tables_;
  if (block_size == 0 || !(one || mixture) || n < 2 * block_size) return;
  if (counters_.steps > 0) throw std::logic_error("collide: use_blocks() after the run has started");
  const std::size_t blocks = n / block_size;
  // A mixture's species with at least min_slice particles a block is dealt in equal slices, a rarer
  // one scattered, each particle to a uniformly random block (header "Mixtures in blocks").
  for (std::size_t k = 0; k < s_ && mixture; ++k) {
    scattered_[k] = sys_.count[k] < min_slice * blocks;
    scattered_any_ = scattered_any_ || scattered_[k];
  }
  // Collisions per particle a blocked step aims at (header "Blocks", "Step length"): sqrt(2 / gamma),
  // gamma = max (1 - alpha_kj^2)/3 the fraction of the energy that one collision per particle
  // dissipates at most (docs/schemes.md, "Cache blocks"), at most block_step_collisions_max.
  // (a rule whose alpha depends on the impact speed has no such bound: block_steps mean free times)
  const std::optional<double> loss = std::visit([](const auto& r) { return r.largest_loss_fraction(); }, rule_);
  const double cooling = loss.value_or(0.0);
  block_step_collisions_ = !loss ? 0.0
                           : cooling > 2.0 / (block_step_collisions_max * block_step_collisions_max)
                               ? std::sqrt(2.0 / cooling)
                               : block_step_collisions_max;
  // Block j holds the particles dealt to it by remix(): ceil((N_k - j)/blocks) of a dealt species k;
  // a scattered species' counts are drawn here for the first step (its particles' order is the
  // initial one, independent of their velocities) and at every remix.
  block_first_.assign(blocks + 1, 0);
  slice_first_.assign(blocks * s_, 0);
  slice_cum_.assign(blocks * (s_ + 1), 0);
  slice_count_.assign(blocks * s_, 0);
  for (std::size_t k = 0; k < s_; ++k)
    for (std::size_t j = 0; j < blocks && !scattered_[k]; ++j)
      slice_count_[j * s_ + k] = (sys_.count[k] - j + blocks - 1) / blocks;
  for (std::size_t k = 0; k < s_; ++k)
    if (scattered_[k]) {
      for (std::size_t i = 0; i < sys_.count[k]; ++i) ++slice_count_[gen_.below(blocks) * s_ + k];
    }
  set_slices();
  block_max_speed2_.assign(blocks * s_, 0.0);
  block_credit_.assign(blocks, 0.0);
  // The remix's scratch memory (deal.hpp), for the largest species and the largest particle array.
  remix_workspace_ = {};
  std::size_t element = 0;  // (the largest element of the arrays a particle carries; deal_in_place grows it)
  sys_.for_each_array([&](const char*, const auto& a) { element = std::max(element, sizeof(a[0])); });
  for (std::size_t k = 0; k < s_; ++k)
    if (!scattered_[k]) remix_workspace_.reserve(sys_.count[k], blocks, element, threads_);
}

void Collider::set_slices() {
  // Species k's slices lie in its own range in block order: slice j starts after the counts of blocks < j.
  const std::size_t blocks = block_first_.size() - 1;
  for (std::size_t k = 0; k < s_; ++k) {
    std::size_t first = sys_.first[k];
    for (std::size_t j = 0; j < blocks; ++j) {
      slice_first_[j * s_ + k] = first;
      slice_cum_[j * (s_ + 1) + k + 1] = slice_cum_[j * (s_ + 1) + k] + slice_count_[j * s_ + k];
      first += slice_count_[j * s_ + k];
    }
  }
  for (std::size_t j = 0; j < blocks; ++j) block_first_[j + 1] = block_first_[j] + slice_cum_[j * (s_ + 1) + s_];
}

void Collider::scatter(std::size_t k) {
  // Each particle of species k to a uniformly random block, independently (header "Mixtures in blocks"):
  // the particles in a uniformly random order, then cut into slices of multinomial counts (deal.hpp).
  // (every array a particle carries, the same transpositions: particles.hpp System::for_each_array)
  const std::size_t first = sys_.first[k];
  deal::scatter(gen_, sys_.count[k], block_first_.size() - 1, slice_count_.data() + k, s_,
                [&](std::size_t i, std::size_t q) {
                  sys_.for_each_array([&](const char*, auto& a) { std::swap(a[first + i], a[first + q]); });
                });
}

void Collider::remix() {
  // Deal the particles, from a random starting point, round the blocks like cards: old index
  // (offset + i) mod N goes to block i mod K, slot i div K. Each new block takes every K-th particle
  // of every old block, so no two particles stay together unless K divides their distance (header).
  // In place (deal.hpp: the same permutation as dealing into a second array, for any thread count).
  const std::size_t n = sys_.size(), blocks = block_first_.size() - 1;
  if (s_ == 1) {
    const std::size_t offset = gen_.below(n);
    // (every array a particle carries: particles.hpp System::for_each_array)
    sys_.for_each_array(
        [&](const char*, auto& a) { deal::deal_in_place(a.data(), n, blocks, offset, remix_workspace_, threads_); });
    return;  // one species: the species array is all zeros and does not move
  }
  // A mixture: each species is dealt round its own slices, within its own range, so the species
  // array never changes and every block keeps its share of every species (slice j of species k
  // starts at first_k + j q_k + min(j, r_k), q_k = N_k div K, r_k = N_k mod K: deal.hpp's blocks).
  // A scattered species is shuffled and cut anew (scatter).
  std::vector<std::size_t> offset(s_);
  for (std::size_t k = 0; k < s_; ++k)
    if (!scattered_[k]) offset[k] = gen_.below(sys_.count[k]);
  sys_.for_each_array([&](const char*, auto& a) {
    for (std::size_t k = 0; k < s_; ++k)
      if (!scattered_[k])
        deal::deal_in_place(a.data() + sys_.first[k], sys_.count[k], blocks, offset[k], remix_workspace_, threads_);
  });
  if (!scattered_any_) return;
  for (std::size_t k = 0; k < s_; ++k)
    if (scattered_[k]) scatter(k);
  set_slices();
}

void Collider::set_block_max_speed2(std::size_t j, double* out) {
  for (std::size_t k = 0; k < s_; ++k) {
    double max2 = 0.0;
    const std::size_t first = slice_first_[j * s_ + k];
    const std::size_t end = first + slice_cum_[j * (s_ + 1) + k + 1] - slice_cum_[j * (s_ + 1) + k];
    for (std::size_t i = first; i < end; ++i) {
      const particles::Vec3& v = sys_.v[i];
      max2 = std::max(max2, v.x * v.x + v.y * v.y + v.z * v.z);
    }
    out[k] = max2;
  }
}

double Collider::mixture_bound(const double* max_speed2, const std::size_t* cum) const {
  // B = max_kj pi sigma_kj^2 chi_kj (vmax_k + vmax_j) (as rebuild_bounds, over the given speeds), over
  // the pairs a block can draw when its counts are given
  if (s_ > block_species_limit) throw std::logic_error("collide: mixture_bound() beyond block_species_limit species");
  std::array<std::uint32_t, block_species_limit> present;
  std::array<double, block_species_limit> speed;
  std::size_t count = 0;
  for (std::size_t k = 0; k < s_; ++k)
    if (cum == nullptr || cum[k + 1] > cum[k]) {
      present[count] = static_cast<std::uint32_t>(k);
      speed[count++] = std::sqrt(max_speed2[k]);
    }
  double bound = 0.0;
  for (std::size_t a = 0; a < count; ++a)
    for (std::size_t b = a; b < count; ++b)
      bound = std::max(bound, cross_section_[present[a] * s_ + present[b]] * (speed[a] + speed[b]));
  return bound;
}

bool Collider::choose_block_lowrank() const {
  // Both samplers are exact in a block (header "Mixtures in blocks"): a majorant sets only how many
  // candidates a collision takes, not the process. The one whose candidates cost less in all: R (the
  // same speed bounds, the same frame factor on both sides) times the cost of a candidate, a `lowrank`
  // one lowrank_candidate_cost times a `majorant` one (docs/schemes.md, "The cheaper sampler").
  // Viscoelastic mixtures run the general loops, which follow the scheme.
  if (block_first_.empty() || s_ == 1) return false;
  if (!kernels_) return lowrank_blocks();
  if (block_sampler_ != BlockSampler::cheaper) return block_sampler_ == BlockSampler::lowrank;
  return lowrank_candidate_cost * block_candidate_rate(true) < block_candidate_rate(false);
}

double Collider::lowrank_block_rate(const double* max_speed2) const {
  // set_block_lowrank's R_b = sum_ik pi sigma_ik^2 chi_ik w_i N_bi N_bk n/(N_b - 1) with the gas's counts:
  // one species gives N n pi sigma^2 chi w, the majorant's N n B/2 with B = 2 pi sigma^2 chi w.
  const double n_total = static_cast<double>(sys_.size());
  const double per_volume = mix_.total_density() / (n_total - 1.0);
  double rate = 0.0;
  for (std::size_t i = 0; i < s_; ++i) {
    const double row = std::sqrt(max_speed2[i]) * static_cast<double>(sys_.count[i]) * per_volume;
    for (std::size_t k = 0; k < s_; ++k) rate += cross_section_[i * s_ + k] * row * static_cast<double>(sys_.count[k]);
  }
  return rate;
}

void Collider::set_whole_gas_bound() {
  // The whole gas as one block (a step near an exact event target, header "Blocks"): B = 2 pi sigma^2
  // chi vmax over all particles, R = N n B / 2.
  range_first_ = 0;
  range_count_ = sys_.size();
  if (s_ > 1) {  // a mixture (majorant): the bound of rebuild_bounds over the species' vmax
    rebuild_bounds();
    return;
  }
  bound_ = 2.0 * cross_section_[0] * max_speed_[0] * speed_factor_;  // speed_factor_: 1 without a frame
  rate_ = 0.5 * static_cast<double>(sys_.size()) * mix_.total_density() * bound_;
}

double Collider::block_step_length(double rate, bool acceptance_unknown) const {
  // Header "Blocks", "Step length": block_steps majorant mean free times N/(2R), or as many as make
  // block_step_collisions_ collisions per particle at the last step's acceptance (one mean free time
  // brings `acceptance` collisions per particle), at most max_block_step_candidates candidates, when
  // that is more; times step_fraction.
  // The first step, which the simulation's chunks cannot bound yet (they take the last step's rate),
  // is at most max_block_step_candidates as well.
  const double n_total = static_cast<double>(sys_.size());
  const double short_step = block_steps * step_fraction_ * n_total / (2.0 * rate);
  if (counters_.steps == 0) return std::min(short_step, max_block_step_candidates / rate);
  if (framed_ || acceptance_unknown || block_step_collisions_ <= 0.0 || step_acceptance_ <= 0.0) return short_step;
  const double long_step = block_step_collisions_ / step_acceptance_ * step_fraction_ * n_total / (2.0 * rate);
  return std::max(short_step, std::min(long_step, max_block_step_candidates / rate));
}

bool Collider::advance_blocks(double t_target, std::uint64_t event_target, bool exact_events,
                              std::uint64_t event_limit, bool to_step_end) {
  const double entry_time = time_;
  // The target met exactly: the exact one, else the hard limit beyond a soft one.
  const std::uint64_t exact_target = exact_events ? std::min(event_target, event_limit) : event_limit;
  const std::uint64_t any_target = std::min(event_target, event_limit);
  const std::size_t blocks = block_first_.size() - 1;
  const double n_total = static_cast<double>(sys_.size());
  const double n = mix_.total_density();
  const double cross_section = cross_section_[0];  // one species: the tables always exist
  // An exact target given inside a blocked step (which was sized without it): the step ends here,
  // where every block is at time_, unless the rest of it surely stays below the target: its events at
  // the step's rate so far (which only falls within a step), that rate taken from the events so far
  // plus 8 standard deviations and 16 (few events bound it loosely, so that a step only begun ends),
  // plus the margins below. The next step then takes acceptance 1 (its last step was short).
  if (exact_target != UINT64_MAX && counters_.steps > 0 && !whole_step_ && time_ > step_start_ &&
      time_ < next_step_time_ && counters_.events < exact_target) {
    const double remaining = static_cast<double>(exact_target - counters_.events);
    const double so_far = static_cast<double>(counters_.events - step_events_start_);
    const double rest = (so_far + 8.0 * std::sqrt(so_far) + 16.0) / (time_ - step_start_) * (next_step_time_ - time_);
    if (may_reach(rest, remaining)) {
      counters_.step_sum -= next_step_time_ - time_;  // (the step is as long as it ran: mean_step())
      next_step_time_ = time_;
    }
  }
  while (time_ < t_target) {
    if (time_ >= next_step_time_) {
      // Events are checked between steps only: all blocks are then at the same time.
      if (counters_.events >= any_target) return true;
      if (to_step_end && time_ > entry_time) return false;  // one step (or the rest of one) done
      if (counters_.steps > 0) {  // the acceptance of the step that ended, for the next decision
        const auto candidates = counters_.candidates - step_candidates_start_;
        if (candidates > 0)
          step_acceptance_ = static_cast<double>(counters_.events - step_events_start_) / static_cast<double>(candidates);
      }
      if (whole_step_)  // the whole gas's bound covers every block until their first visit
        for (std::size_t j = 0; j < blocks; ++j)
          for (std::size_t k = 0; k < s_; ++k) block_max_speed2_[j * s_ + k] = max_speed2_[k];
      if (counters_.steps == 0)
        for (std::size_t j = 0; j < blocks; ++j) set_block_max_speed2(j, block_max_speed2_.data() + j * s_);
      // The step from the largest block bounds so far, an upper bound of the gas's vmax_k (the blocks'
      // bounds are recomputed when visited): dt = block_step_length().
      for (std::size_t k = 0; k < s_; ++k) {
        double global = 0.0;
        for (std::size_t j = 0; j < blocks; ++j) global = std::max(global, block_max_speed2_[j * s_ + k]);
        max_speed2_[k] = global;
        max_speed_[k] = std::sqrt(global);
      }
      // In a frame the stage loop sizes its stages by candidate_rate(): R of these bounds, as a
      // restored collider computes it (restore()).
      if (framed_) rebuild_bounds();
      double rate = (s_ == 1 ? 0.5 * n_total * n * 2.0 * cross_section * max_speed_[0]
                             : 0.5 * n_total * n * mixture_bound(max_speed2_.data())) *
                    speed_factor_;  // 1 without a frame
      if (lowrank_blocks()) rebuild_bounds();  // the low-rank majorant's own total over these vmax_k (rate_)
      // The blocks' sampler for this step (header "Mixtures in blocks", "The cheaper sampler"), chosen
      // here once for all blocks, so that R, the last step's acceptance and the output do not depend on
      // the threads. The last step's acceptance is that of the sampler it ran: a whole-gas step runs the
      // scheme's own; when this step's differs, the acceptance belongs to another majorant (with R
      // several times another's: 1.8 for 20 species), so that this step judges its events near a target
      // from the last step's events per unit time (below) and is block_steps long
      // (Collide.CheaperSamplerMeetsEventTargetsExactly).
      const bool was_lowrank = whole_step_ ? lowrank_blocks() : block_lowrank_;
      block_lowrank_ = choose_block_lowrank();
      const bool sampler_changed = counters_.steps > 0 && block_lowrank_ != was_lowrank;
      if (block_lowrank_)  // the unblocked `lowrank` total (chi_max >= chi_ik) bounds the blocks' own
        rate = lowrank_blocks() ? rate_ : lowrank_block_rate(max_speed2_.data()) * speed_factor_;
      if (rate <= 0.0) {
        time_ = t_target;
        return false;
      }
      double step = block_step_length(rate, sampler_changed);
      // Near an exact event target (header "Blocks"): a blocked step is shortened so that its events
      // (its candidates R dt times the last step's acceptance, plus 10 % and 8 standard deviations)
      // stay below those left; the first step, with no acceptance measured yet, takes acceptance 1,
      // which bounds it (every candidate an event). When that leaves less than N/64 events for it (or
      // 4 blocks' worth, N 4/K, when that is less), the step runs instead on the whole gas, which stops at
      // the target itself, and is made about 1.5 times as long as the events left need. N/64: a
      // shortened blocked step costs a remix and a pass for the bounds (about 5 ns a particle), a
      // whole-gas event about 0.15 us more than a blocked one (the velocities out of the cache), which
      // break even near N/30 events; the shortened steps bring the events left down about tenfold each.
      // A step longer than block_steps mean free times (block_step_length) is taken only while an
      // exact target is out of its reach: within a long step the acceptance falls (the gas cools, bounds
      // are raised), so its mean underestimates the next step's, and a step after a long one takes
      // acceptance 1 (a bound) instead; the approach runs steps of block_steps as before.
      whole_step_ = false;
      if (exact_target != UINT64_MAX) {
        const double remaining = static_cast<double>(exact_target - counters_.events);
        // (and a step after one of fewer than min(N/64, 4 N/K) candidates, e.g. one ended early by a
        // target given inside it, whose acceptance is too uncertain: also acceptance 1)
        const double short_candidates = block_steps * step_fraction_ * n_total / 2.0;
        const auto last_candidates = static_cast<double>(counters_.candidates - step_candidates_start_);
        const bool after_long = last_candidates > 1.01 * short_candidates;
        const double fewest = std::min(n_total / 64.0, 4.0 * n_total / static_cast<double>(blocks));
        const bool too_few = last_candidates < fewest;
        // After a change of sampler (or a whole-gas step of the other one) the last step's acceptance is
        // another majorant's: its events per unit time instead, which do not depend on the majorant (and
        // only fall as the gas cools), over this step's R. (Acceptance 1 there made the whole-gas steps
        // before a target cover a third of the events left each: a collision-driven binary `lowrank` run
        // whose blocks run `majorant` took 1.5-2 times as long.)
        const double last_elapsed = time_ - step_start_;
        const double changed_acceptance =
            last_elapsed > 0.0
                ? std::min(1.0, static_cast<double>(counters_.events - step_events_start_) / last_elapsed / rate)
                : 1.0;
        const double acceptance = step_acceptance_ > 0.0 && !after_long && !too_few
                                      ? (sampler_changed ? changed_acceptance : step_acceptance_)
                                      : 1.0;
        if (may_reach(acceptance * rate * step, remaining)) step = std::min(step, short_candidates / rate);  // (never longer)
        const double expected = acceptance * rate * step;
        if (may_reach(expected, remaining)) {
          // the largest mu with 1.1 mu + 8 sqrt(mu) + 16 <= remaining (a quadratic in sqrt(mu))
          const double root = (-8.0 + std::sqrt(std::max(0.0, 64.0 - 4.4 * (16.0 - remaining)))) / 2.2;
          const double fits = root > 0.0 ? root * root : 0.0;
          if (fits >= fewest) {
            step *= fits / expected;
          } else {
            whole_step_ = true;
            step *= std::min(1.0, 1.5 * remaining / expected);
          }
        }
      }
      if (whole_step_) {
        recompute_max_speeds();  // exact, O(N): the bound of the whole gas
        set_whole_gas_bound();
        credit_ = 0.0;
        pending_filled_ = false;
      } else if (counters_.steps > 0) {
        remix();
      }
      step_events_start_ = counters_.events;
      step_candidates_start_ = counters_.candidates;
      step_start_ = time_;
      next_step_time_ = time_ + step;
      ++counters_.steps;
      counters_.step_sum += step;
    }
    if (whole_step_) {
      const double t_stop = std::min(t_target, next_step_time_);
      const bool lowrank = lowrank_blocks();
      const int stop = run_loop(lowrank ? Scheme::lowrank : Scheme::majorant, t_stop, any_target);
      if (stop == static_cast<int>(Stop::bound_raised)) {
        raised_.clear();
        set_whole_gas_bound();
      }
      if (stop == static_cast<int>(Stop::reached_events)) return true;
      continue;
    }
    const double t_stop = std::min(t_target, next_step_time_);
    run_blocks_pass(time_, t_stop);
    time_ = t_stop;
  }
  range_first_ = 0;
  range_count_ = sys_.size();
  return false;
}

void Collider::use_threads(int threads) {
  threads_ = std::max(1, threads);
  workers_.clear();  // made again, as many as threads, at the next pass
}

void Collider::make_workers() {
  // A worker is a copy of this collider's tables and blocks, without the remix's scratch memory (which
  // only the master uses) and without workers of its own (workers_ is empty while the copies are made).
  workers_.clear();
  auto remix_workspace = std::move(remix_workspace_);
  remix_workspace_ = {};
  std::vector<Collider> made;
  made.reserve(static_cast<std::size_t>(threads_));
  for (int t = 0; t < threads_; ++t) made.push_back(*this);
  remix_workspace_ = std::move(remix_workspace);
  workers_ = std::move(made);
  block_counters_.assign(block_first_.size() - 1, counters_);
}

void Collider::run_block(Collider& master, std::size_t j, double t_start, double t_stop, bool first_visit,
                         std::uint64_t key) {
  gen_ = rng::Xoshiro256pp::substream(key, j);  // keyed by (seed, replica, pass, block): header "Threads"
  counters_.events = counters_.candidates = counters_.overshoots = 0;
  counters_.largest_acceptance = counters_.dissipated = 0.0;
  std::fill(counters_.pair_events.begin(), counters_.pair_events.end(), 0);
  whole_step_ = false;
  current_block_ = j;
  range_first_ = block_first_[j];
  range_count_ = block_first_[j + 1] - block_first_[j];
  pending_filled_ = false;  // the drawn-ahead pairs belong to another block
  block_speed2_ = master.block_max_speed2_.data() + j * s_;
  // The whole gas's frame (header, "Frame"): G from the master; this block's change of Q kept apart.
  framed_ = master.framed_;
  frame_scale_ = master.frame_scale_;
  frame_inverse_scale_ = master.frame_inverse_scale_;
  frame_shear_ = master.frame_shear_;
  speed_factor_ = master.speed_factor_;
  if (framed_) moments_ = {};
  // First visit in this step: the block's exact bound, read in order (which also brings the block
  // into the cache before its random reads).
  if (first_visit) set_block_max_speed2(j, block_speed2_);
  time_ = t_start;
  credit_ = master.block_credit_[j];
  const double n = mix_.total_density();
  const bool lowrank = master.block_lowrank_;  // the step's sampler (advance_blocks: choose_block_lowrank)
  for (;;) {
    if (lowrank) {
      set_block_lowrank(n);
    } else {
      // A block of N_b particles at the gas's density n: R_b = N_b n B_b / 2 (as R, header "Blocks").
      // (a mixture: B_b = max_kj pi sigma_kj^2 chi_kj (vmax_bk + vmax_bj) over the block's slices)
      // (in a frame every relative speed bound times ||G||: header "Frame")
      bound_ = (s_ == 1 ? 2.0 * cross_section_[0] * std::sqrt(block_speed2_[0])
                        : mixture_bound(block_speed2_, slice_cum_.data() + j * (s_ + 1))) *
               speed_factor_;
      rate_ = 0.5 * static_cast<double>(range_count_) * n * bound_;
    }
    if (rate_ <= 0.0) break;
    if (kernels_) {  // the block kernels of a rule with the projection (rules.hpp): raised bounds handled inside
      std::visit([&](const auto& rule) { run_block_kernel(rule, lowrank, t_stop); }, rule_);
      break;
    }
    const int stop = run_loop(lowrank ? Scheme::lowrank : Scheme::majorant, t_stop, UINT64_MAX);
    if (stop != static_cast<int>(Stop::bound_raised)) break;
  }
  master.block_credit_[j] = rate_ > 0.0 ? credit_ : 0.0;
  if (framed_) master.block_moments_[j] = moments_;
  Counters& out = master.block_counters_[j];
  out.events = counters_.events;
  out.candidates = counters_.candidates;
  out.overshoots = counters_.overshoots;
  out.largest_acceptance = counters_.largest_acceptance;
  out.dissipated = counters_.dissipated;
  std::copy(counters_.pair_events.begin(), counters_.pair_events.end(), out.pair_events.begin());
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

void Collider::set_block_lowrank(double n) {
  // The block's own A_ik (header "Mixtures in blocks"): the rank-3 hard-sphere majorant of its slices,
  // N_k the slice's count and V = (N_b - 1)/n, so that each pair's rate is pi sigma_ik^2 chi_ik |g|
  // n/(N_b - 1) as in the majorant blocks; vmax_k the block's. Columns as well as rows: the slices'
  // counts differ between blocks.
  // With at most block_species_limit species the entries are few: each is computed exactly, with
  // chi_ik itself instead of chi_max (the rank-3 form needs one chi for all pairs), A_ik = pi
  // sigma_ik^2 chi_ik w_i N_i N_k / V (the form of segment_tree.hpp's hard_sphere_factors with chi_ik),
  // a candidate then accepted with |g| / (w_i + w_k) (run_lowrank); a pair is drawn from their alias
  // table (one uniform) rather than by the trees' descents. Only the P species present in the block
  // (a scattered species may have no particle there) enter the kernel's table: P^2 pairs.
  const std::size_t* cum = slice_cum_.data() + current_block_ * (s_ + 1);
  lowrank_volume_ = static_cast<double>(range_count_ - 1) / n;
  for (std::size_t k = 0; k < s_; ++k) max_speed_[k] = std::sqrt(block_speed2_[k]);
  pending_filled_ = false;  // drawn from the old A_ik: redraw (header, "Look-ahead")
  if (!kernels_) {  // run_lowrank's draw, over all S^2 pairs
    pair_weights_.resize(s_ * s_);
    rate_ = 0.0;
    for (std::size_t i = 0; i < s_; ++i)
      for (std::size_t k = 0; k < s_; ++k) {
        const auto count_i = static_cast<double>(cum[i + 1] - cum[i]), count_k = static_cast<double>(cum[k + 1] - cum[k]);
        pair_weights_[i * s_ + k] = cross_section_[i * s_ + k] * max_speed_[i] * count_i * count_k / lowrank_volume_;
        rate_ += pair_weights_[i * s_ + k];
      }
    if (rate_ > 0.0) pair_alias_.build(pair_weights_);
    return;
  }
  // The mixture kernel's one-word draw (header "Mixtures in blocks"): an alias table over P = 2^m
  // cells, the pairs of the present species followed by zero weights (never drawn: Vose's construction
  // sends them to their alias), so that the cell is m uniform bits of the word.
  std::array<std::uint32_t, block_species_limit> present;
  std::size_t p = 0;
  for (std::size_t k = 0; k < s_; ++k)
    if (cum[k + 1] > cum[k]) present[p++] = static_cast<std::uint32_t>(k);
  const std::size_t pairs = p * p;
  pair_weights_.resize(pairs);
  rate_ = 0.0;
  for (std::size_t a = 0; a < p; ++a)
    for (std::size_t b = 0; b < p; ++b) {
      const std::size_t i = present[a], k = present[b];
      const auto count_i = static_cast<double>(cum[i + 1] - cum[i]), count_k = static_cast<double>(cum[k + 1] - cum[k]);
      // (in a frame every w_i times ||G||: header "Frame"; speed_factor_ is 1 without one)
      pair_weights_[a * p + b] =
          cross_section_[i * s_ + k] * (max_speed_[i] * speed_factor_) * count_i * count_k / lowrank_volume_;
      rate_ += pair_weights_[a * p + b];
    }
  if (!(rate_ > 0.0)) return;
  unsigned bits = 1;  // at least two cells (one species present: its pair and a zero weight), r >> 64 being undefined
  while ((std::size_t{1} << bits) < pairs) ++bits;
  lowrank_cell_bits_ = bits;
  pair_weights_.resize(std::size_t{1} << bits, 0.0);
  pair_alias_.build(pair_weights_);
  pair_weights_.resize(pairs);
  const double coin_scale = std::ldexp(1.0, 16 - static_cast<int>(bits));  // 2^c, c = 16 - m coin bits
  lowrank_cells_.resize(std::size_t{1} << bits);
  for (std::size_t c = 0; c < lowrank_cells_.size(); ++c) {
    // Keep cell c with probability t: with U = (q + V)/2^c (q the c coin bits, V uniform), U < t iff
    // q < floor(t 2^c), or q = floor(t 2^c) and V < t 2^c - floor(t 2^c) (both exact in doubles).
    const double scaled = pair_alias_.threshold[c] * coin_scale;
    const double whole = std::floor(scaled);
    const auto other = static_cast<std::uint32_t>(pair_alias_.alias[c]);
    lowrank_cells_[c] = {scaled - whole, static_cast<std::uint32_t>(whole),
                         c < pairs ? static_cast<std::uint32_t>(c) : other, other};
  }
  lowrank_outcomes_.resize(pairs);
  const std::size_t* slice = slice_first_.data() + current_block_ * s_;
  // Every slice of the block below 2^24 (the one-word draw); else every candidate's reject is 2^24.
  bool narrow = true;
  for (std::size_t i = 0; i < s_; ++i) narrow = narrow && cum[i + 1] - cum[i] < (std::size_t{1} << 24);
  for (std::size_t a = 0; a < p; ++a)
    for (std::size_t b = 0; b < p; ++b) {
      const std::size_t i = present[a], k = present[b];
      const auto count_i = static_cast<std::uint32_t>(cum[i + 1] - cum[i]);
      const auto count_k = static_cast<std::uint32_t>(cum[k + 1] - cum[k]);
      // Lemire's multiply-shift in 24 bits (Lemire 2019, as rng::Xoshiro256pp::below_pair): x n >> 24 is
      // uniform on [0, n) once the x with x n mod 2^24 < 2^24 mod n are rejected.
      lowrank_outcomes_[a * p + b] = {static_cast<std::uint32_t>(slice[i]), count_i, static_cast<std::uint32_t>(slice[k]),
                                      count_k, narrow ? (1u << 24) % count_i : 1u << 24,
                                      narrow ? (1u << 24) % count_k : 1u << 24, static_cast<std::uint32_t>(i * s_ + k)};
      pair_limit_[i * s_ + k] = (max_speed_[i] + max_speed_[k]) * speed_factor_;  // (pairs of absent species: never drawn)
    }
}

void Collider::run_blocks_pass(double t_start, double t_stop) {
  if (workers_.size() != static_cast<std::size_t>(threads_)) make_workers();
  const std::size_t blocks = block_first_.size() - 1;
  if (scattered_any_)  // the slices of this step's remix (the workers are copies made earlier)
    for (Collider& w : workers_) {
      w.slice_first_ = slice_first_;
      w.slice_cum_ = slice_cum_;
      w.block_first_ = block_first_;
    }
  const std::uint64_t key = gen_();  // this pass's key (header "Threads")
  if (framed_) block_moments_.assign(blocks, std::array<double, 4>{});
  const bool first_visit = t_start == step_start_;
  std::vector<std::exception_ptr> failure(blocks);  // exceptions must not leave an OpenMP region
  const auto n_blocks = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1) if (threads_ > 1)
  for (std::ptrdiff_t j = 0; j < n_blocks; ++j) {
#ifdef _OPENMP
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
#else
    const std::size_t t = 0;
#endif
    try {
      workers_[t].run_block(*this, static_cast<std::size_t>(j), t_start, t_stop, first_visit, key);
    } catch (...) {
      failure[static_cast<std::size_t>(j)] = std::current_exception();
    }
  }
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
  // The blocks' counts in block order: the same sums for any number of threads.
  for (std::size_t j = 0; j < blocks; ++j) {
    const Counters& c = block_counters_[j];
    counters_.events += c.events;
    counters_.candidates += c.candidates;
    counters_.overshoots += c.overshoots;
    counters_.largest_acceptance = std::max(counters_.largest_acceptance, c.largest_acceptance);
    counters_.dissipated += c.dissipated;
    for (std::size_t p = 0; p < c.pair_events.size(); ++p) counters_.pair_events[p] += c.pair_events[p];
    if (framed_)
      for (std::size_t q = 0; q < 4; ++q) moments_[q] += block_moments_[j][q];
  }
  time_ = t_stop;
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

void Collider::reset_frame(const std::array<double, 4>& moments, const std::vector<double>& max_speed2) {
  framed_ = true;
  frame_scale_ = 1.0;
  frame_inverse_scale_ = 1.0;
  frame_shear_ = 0.0;
  speed_factor_ = 1.0;
  moments_ = moments;
  set_max_speeds(max_speed2);
  // In blocks: each block's exact bound again (the velocities were all replaced).
  for (std::size_t j = 0; j + 1 < block_first_.size(); ++j) set_block_max_speed2(j, block_max_speed2_.data() + j * s_);
}

bool Collider::advance(double t_target, std::uint64_t event_target, bool exact_events, std::uint64_t event_limit,
                       bool to_step_end) {
  if (!block_first_.empty()) return advance_blocks(t_target, event_target, exact_events, event_limit, to_step_end);
  event_target = std::min(event_target, event_limit);  // without blocks every target is met exactly
  while (time_ < t_target) {
    if (counters_.events >= event_target) return true;
    if (time_ >= next_step_time_) {
      recompute_max_speeds();
      rebuild_bounds();
      if (rate_ <= 0.0) {  // all particles at rest: nothing can ever collide
        time_ = t_target;
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
    if (stop == static_cast<int>(Stop::bound_raised)) {
      if (scheme_ == Scheme::lowrank) {  // O(log M) per raised species, not a rebuild
        for (std::size_t k : raised_) set_lowrank_row(k);
        raised_.clear();
        rate_ = lowrank_.total();
        pending_filled_ = false;  // drawn from the old A_ik: redraw (header, "Look-ahead")
      } else {
        rebuild_bounds();
      }
    }
    if (stop == static_cast<int>(Stop::reached_events)) return true;
  }
  return false;
}

// Candidates of one sub-step at a fixed rate: candidate c (0-based) happens at
// time_ - credit_ + (c + 1)/R; what is left of the sub-step is carried in credit_.
// `try_candidate(a, b, t)` draws one candidate at time t and, when it is accepted, collides and counts it,
// sets the two particles and returns true. A template, so each scheme's loop is inlined whole.
template <class TryCandidate>
int Collider::run_substep(double t_stop, std::uint64_t event_target, TryCandidate&& try_candidate) {
  const double dt_candidate = 1.0 / rate_;
  const double available = credit_ + (t_stop - time_);
  const auto n_candidates = static_cast<std::uint64_t>(available * rate_);
  const double t0 = time_ - credit_;
  for (std::uint64_t c = 0; c < n_candidates; ++c) {
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
  const std::size_t* cum = sliced ? slice_cum_.data() + current_block_ * (s_ + 1) : nullptr;
  const std::size_t* slice = sliced ? slice_first_.data() + current_block_ * s_ : nullptr;
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
  const std::size_t* cum = sliced ? slice_cum_.data() + current_block_ * (s_ + 1) : nullptr;
  const std::size_t* slice = sliced ? slice_first_.data() + current_block_ * s_ : nullptr;
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

}  // namespace gdsmc::collide
