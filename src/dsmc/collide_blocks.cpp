// The cache blocks of the collider (collide.hpp "Blocks", "Mixtures in blocks", "Threads inside one replica"): the
// blocks, their remix, their steps and their bounds, the workers that run them on threads.
#include "dsmc/collide.hpp"
#include "dsmc/event_margin.hpp"

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

using event_margin::may_reach;  // near an exact event target with blocks (header "Blocks")

namespace {
/// The largest element of the arrays a particle carries (particles.hpp System::for_each_array): the
/// element size the remix's workspaces are sized for (deal.hpp).
std::size_t largest_element(const particles::System& sys) {
  std::size_t element = 0;
  sys.for_each_array([&](const char*, const auto& a) { element = std::max(element, sizeof(a[0])); });
  return element;
}

/// The largest |v|^2 of `count` particles from `v` (0 for none): a slice's exact bound.
inline double slice_max_speed2(const particles::Vec3* v, std::size_t count) {
  double max2 = 0.0;
  for (std::size_t i = 0; i < count; ++i) max2 = std::max(max2, v[i].x * v[i].x + v[i].y * v[i].y + v[i].z * v[i].z);
  return max2;
}
}  // namespace

void Collider::use_blocks(std::size_t block_size, const particles::SetUpCheck& check) {
  block_first_.clear();
  scattered_.assign(s_, 0);
  scattered_any_ = false;
  const std::size_t n = sys_.size();
  const bool one = s_ == 1 && scheme_ != Scheme::pairs;
  const bool mixture = s_ > 1 && scheme_ != Scheme::pairs && s_ <= block_species_limit && tables_;
  // More than separable_above species with `lowrank`: the separable draw, for a rule with the projection
  // (header "Mixtures in blocks").
  // (a mixture of at most block_species_limit species whose K x S tables would exceed N entries keeps the
  // factored draw in blocks of block_size)
  const std::size_t separable_count = s_ > separable_above && scheme_ == Scheme::lowrank && kernels_ && block_size > 0
                                          ? separable_block_count(s_, n, block_size)
                                          : 0;
  const bool separable = separable_count >= 2 && (!mixture || s_ * (n / block_size) <= n);
  if (block_size == 0 || !(one || mixture || separable) || n < 2 * block_size) return;
  if (counters_.steps > 0) throw std::logic_error("collide: use_blocks() after the run has started");
  const std::size_t blocks = separable ? separable_count : n / block_size;
  // A mixture's species with at least min_slice particles a block is dealt in equal slices, a rarer
  // one scattered, each particle to a uniformly random block (header "Mixtures in blocks").
  separable_blocks_ = separable;
  for (std::size_t k = 0; k < s_ && (mixture || separable); ++k) {
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
  // (the K x S arrays row by row: at 1e5 species they hold millions of entries; the set-up looks at the
  // interrupt every set_up_stride / min_slice species, each of which draws fewer than min_slice K blocks:
  // at most set_up_stride K draws between two looks, in practice 1024 N / S: 4e4 for 4e6 particles of 1e5 species)
  for (std::size_t j = 0; j < blocks; ++j)
    for (std::size_t k = 0; k < s_; ++k)
      if (!scattered_[k]) slice_count_[j * s_ + k] = (sys_.count[k] - j + blocks - 1) / blocks;
  for (std::size_t k = 0; k < s_; ++k) {
    if (k % (particles::set_up_stride / min_slice) == 0 && check) check();
    if (scattered_[k]) {
      for (std::size_t i = 0; i < sys_.count[k]; ++i) ++slice_count_[gen_.below(blocks) * s_ + k];
    }
  }
  set_slices();
  block_max_speed2_.assign(blocks * s_, 0.0);
  block_credit_.assign(blocks, 0.0);
  // The remix's scratch memory (deal.hpp), for the largest species and the largest particle array.
  remix_workspace_ = {};
  species_workspaces_ = {};  // (deal_species sizes them at the first remix on several threads)
  const std::size_t element = largest_element(sys_);  // (deal_in_place grows it)
  for (std::size_t k = 0; k < s_; ++k)
    if (!scattered_[k]) remix_workspace_.reserve(sys_.count[k], blocks, element, threads_);
}

std::size_t Collider::separable_block_count(std::size_t species, std::size_t n, std::size_t block_size) {
  // Each visit of a block builds six tables of about S cells, so that blocks of fewer than
  // separable_particles_per_species S particles spend more on their tables than on their candidates: K =
  // N div block_size, at most N div (separable_particles_per_species S) but at least separable_min_blocks;
  // the blocks' K x S tables (slices, bounds) hold at most about N entries each (K <= N div S); with more
  // than separable_species_limit species, blocks of at most separable_block_limit particles on average (so
  // that the P species present fit the tables' 16-bit outcomes), while S K <= 2 N. 0: no blocks.
  if (species == 0 || block_size == 0) return 0;
  std::size_t blocks = std::min(n / block_size, std::max(separable_min_blocks, n / (separable_particles_per_species * species)));
  if (species * blocks > n) blocks = n / species;
  if (species > separable_species_limit)
    blocks = std::max(blocks, (n + separable_block_limit - 1) / separable_block_limit);
  return species * blocks <= 2 * n ? blocks : 0;
}

void Collider::set_slices() {
  // Species k's slices lie in its own range in block order: slice j starts after the counts of blocks < j.
  // (block by block, so that the K x S arrays are written in order: at 1e5 species they do not fit a cache)
  const std::size_t blocks = block_first_.size() - 1;
  std::vector<std::size_t> next(sys_.first.begin(), sys_.first.end());  // species k's next slice
  for (std::size_t j = 0; j < blocks; ++j) {
    const std::size_t* count = slice_count_.data() + j * s_;
    std::size_t* first = slice_first_.data() + j * s_;
    std::size_t* cum = slice_cum_.data() + j * (s_ + 1);
    for (std::size_t k = 0; k < s_; ++k) {
      first[k] = next[k];
      next[k] += count[k];
      cum[k + 1] = cum[k] + count[k];
    }
    block_first_[j + 1] = block_first_[j] + cum[s_];
  }
}

void Collider::scatter_species() {
  // Each particle of a scattered species to a uniformly random block, independently (header "Mixtures in
  // blocks"): its particles in a uniformly random order, then cut into slices of multinomial counts
  // (deal.hpp). The draws, species after species, are those of one scatter after another; the
  // transpositions, at random within each species' range, wait on memory, so they run on the block
  // threads. (every array a particle carries, the same transpositions: particles.hpp System::for_each_array)
  const std::size_t blocks = block_first_.size() - 1;
  std::vector<std::size_t> chunk, first;  // a chunk's species and the first of each one's partners
  for (std::size_t k = 0; k < s_;) {
    chunk.clear(), first.clear();
    std::size_t partners = 0;
    for (; k < s_ && (chunk.empty() || !scattered_[k] || partners + sys_.count[k] <= scatter_chunk); ++k)
      if (scattered_[k]) {
        chunk.push_back(k), first.push_back(partners);
        partners += sys_.count[k] > 0 ? sys_.count[k] - 1 : 0;
      }
    if (scatter_partners_.size() < partners) scatter_partners_.resize(std::max(partners, std::min(scatter_chunk, sys_.size())));
    rng::Xoshiro256pp gen = gen_;  // (in registers)
    for (std::size_t c = 0; c < chunk.size(); ++c)
      deal::scatter_draws(gen, sys_.count[chunk[c]], blocks, slice_count_.data() + chunk[c], s_,
                          scatter_partners_.data() + first[c]);
    gen_ = gen;
    const auto n_chunk = static_cast<std::ptrdiff_t>(chunk.size());
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 8) if (threads_ > 1 && partners >= 4096)
    for (std::ptrdiff_t c = 0; c < n_chunk; ++c) {
      const std::size_t k = chunk[static_cast<std::size_t>(c)], start = sys_.first[k];
      const std::uint32_t* partner = scatter_partners_.data() + first[static_cast<std::size_t>(c)];
      sys_.for_each_array([&](const char*, auto& a) {
        deal::scatter_moves(sys_.count[k], partner, [&](std::size_t i, std::size_t q) { std::swap(a[start + i], a[start + q]); });
      });
    }
  }
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
  deal_species(offset);
  if (!scattered_any_) return;
  scatter_species();
  set_slices();
}

void Collider::deal_species(const std::vector<std::size_t>& offset) {
  // A species of N/(4 threads) particles or more is dealt on all threads, one after another; the others
  // one species per thread, each with a workspace of its own: a deal on all threads of a species of few
  // particles is mostly the threads' meeting, and with many species the deal of each would run on one
  // thread while the others wait. deal_in_place gives the same bytes on any number of threads.
  const std::size_t n = sys_.size(), blocks = block_first_.size() - 1;
  const auto threads = static_cast<std::size_t>(threads_);
  const auto small = [&](std::size_t k) { return !scattered_[k] && threads > 1 && 4 * threads * sys_.count[k] < n; };
  std::vector<std::size_t> apart;  // the species dealt one per thread (two at least, else none)
  for (std::size_t k = 0; k < s_; ++k)
    if (small(k)) apart.push_back(k);
  if (apart.size() < 2) apart.clear();
  for (std::size_t k = 0; k < s_; ++k)
    if (!scattered_[k] && (apart.empty() || !small(k)))
      sys_.for_each_array([&](const char*, auto& a) {
        deal::deal_in_place(a.data() + sys_.first[k], sys_.count[k], blocks, offset[k], remix_workspace_, threads_);
      });
  if (apart.empty()) return;
  // (every workspace sized before the threads start: nothing in the parallel region allocates)
  species_workspaces_.resize(static_cast<std::size_t>(threads_));
  const std::size_t element = largest_element(sys_);
  for (deal::Workspace& w : species_workspaces_)
    for (std::size_t k : apart) w.reserve(sys_.count[k], blocks, element, 1);
  std::vector<std::exception_ptr> failure(apart.size());  // exceptions must not leave an OpenMP region
  const auto n_apart = static_cast<std::ptrdiff_t>(apart.size());
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1)
  for (std::ptrdiff_t q = 0; q < n_apart; ++q) {
#ifdef _OPENMP
    deal::Workspace& workspace = species_workspaces_[static_cast<std::size_t>(omp_get_thread_num())];
#else
    deal::Workspace& workspace = species_workspaces_[0];
#endif
    const std::size_t k = apart[static_cast<std::size_t>(q)];
    try {
      sys_.for_each_array([&](const char*, auto& a) {
        deal::deal_in_place(a.data() + sys_.first[k], sys_.count[k], blocks, offset[k], workspace, 1);
      });
    } catch (...) {
      failure[static_cast<std::size_t>(q)] = std::current_exception();
    }
  }
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
}

void Collider::set_block_max_speed2(std::size_t j, double* out) {
  const std::size_t* slice = slice_first_of(j);
  const std::size_t* cum = slice_cum_of(j);
  for (std::size_t k = 0; k < s_; ++k) out[k] = slice_max_speed2(sys_.v.data() + slice[k], cum[k + 1] - cum[k]);
}

Collider::BlockPass Collider::map_blocks(double s, double sc, const particles::Vec3& b) {
  if (block_first_.empty()) throw std::logic_error("collide: map_blocks() without blocks");
  const std::size_t blocks = block_first_.size() - 1;
  std::vector<FramePassSums> part(blocks);
  std::vector<std::size_t> visited_in(blocks, 0);
  const auto n_blocks = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for num_threads(threads_) schedule(static) if (threads_ > 1)
  for (std::ptrdiff_t jj = 0; jj < n_blocks; ++jj) {
    const auto j = static_cast<std::size_t>(jj);
    const std::size_t* slice = slice_first_of(j);
    const std::size_t* cum = slice_cum_of(j);
    for (std::size_t k = 0; k < s_; ++k) {
      const std::size_t count = cum[k + 1] - cum[k];
      block_max_speed2_[j * s_ + k] = map_velocities(sys_.v.data() + slice[k], count, mix_.mass[k], s, sc, b, part[j]);
      visited_in[j] += count;
    }
  }
  BlockPass out;
  out.max_speed2.assign(s_, 0.0);
  std::size_t visited = 0;
  for (std::size_t j = 0; j < blocks; ++j) {  // in block order: the same sums on any number of threads
    const FramePassSums& p = part[j];
    visited += visited_in[j];
    out.mass += p.mass;
    out.momentum.x += p.momentum[0], out.momentum.y += p.momentum[1], out.momentum.z += p.momentum[2];
    for (std::size_t q = 0; q < 4; ++q) out.moments[q] += p.moments[q];
    for (std::size_t k = 0; k < s_; ++k) out.max_speed2[k] = std::max(out.max_speed2[k], block_max_speed2_[j * s_ + k]);
  }
  if (visited != sys_.size()) throw std::logic_error("collide: map_blocks() did not visit every particle once");
  return out;
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
  if (!kernels_ || separable_blocks_) return lowrank_blocks();
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
  if (acceptance_unknown || block_step_collisions_ <= 0.0 || step_acceptance_ <= 0.0) return short_step;
  const double long_step = block_step_collisions_ / step_acceptance_ * step_fraction_ * n_total / (2.0 * rate);
  return std::max(short_step, std::min(long_step, max_block_step_candidates / rate));
}

void Collider::end_step_at_target(std::uint64_t exact_target) {
  // An exact target given inside a blocked step (which was sized without it): the step ends here,
  // where every block is at time_, unless the rest of it surely stays below the target: its events at
  // the step's rate so far (which only falls within a step), that rate taken from the events so far
  // plus 8 standard deviations and 16 (few events bound it loosely, so that a step only begun ends),
  // plus the margins below. The next step then takes approach_acceptance's estimate after a step this
  // short (1 when it had fewer than min(N/64, 4 N/K) candidates).
  if (exact_target == UINT64_MAX || counters_.steps == 0 || whole_step_ || !(time_ > step_start_) ||
      !(time_ < next_step_time_) || counters_.events >= exact_target)
    return;
  const double remaining = static_cast<double>(exact_target - counters_.events);
  const double so_far = static_cast<double>(counters_.events - step_events_start_);
  const double rest = (so_far + 8.0 * std::sqrt(so_far) + 16.0) / (time_ - step_start_) * (next_step_time_ - time_);
  if (may_reach(rest, remaining)) {
    counters_.step_sum -= next_step_time_ - time_;  // (the step is as long as it ran: mean_step())
    next_step_time_ = time_;
  }
}

double Collider::blocked_step_rate(bool& sampler_changed) {
  const std::size_t blocks = block_first_.size() - 1;
  const double n_total = static_cast<double>(sys_.size());
  const double n = mix_.total_density();
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
  // (block by block: the K x S array in order)
  std::fill(max_speed2_.begin(), max_speed2_.end(), 0.0);
  for (std::size_t j = 0; j < blocks; ++j)
    for (std::size_t k = 0; k < s_; ++k) max_speed2_[k] = std::max(max_speed2_[k], block_max_speed2_[j * s_ + k]);
  for (std::size_t k = 0; k < s_; ++k) max_speed_[k] = std::sqrt(max_speed2_[k]);
  // In a frame the stage loop sizes its stages by candidate_rate(): R of these bounds, as a
  // restored collider computes it (restore()).
  if (framed_) rebuild_bounds();
  double rate = (s_ == 1            ? 0.5 * n_total * n * 2.0 * cross_section_[0] * max_speed_[0]  // (one species: the tables always exist)
                 : separable_blocks_ ? 0.0  // (no `majorant` blocks: the separable draw's rate below)
                                     : 0.5 * n_total * n * mixture_bound(max_speed2_.data())) *
                speed_factor_;  // 1 without a frame
  if (lowrank_blocks()) rebuild_bounds();  // the low-rank majorant's own total over these vmax_k (rate_)
  // The blocks' sampler for this step (header "Mixtures in blocks", "The cheaper sampler"), chosen
  // here once for all blocks, so that R, the last step's acceptance and the output do not depend on
  // the threads. The last step's acceptance is that of the sampler it ran: a whole-gas step runs the
  // scheme's own; when this step's differs, the acceptance belongs to another majorant (with R
  // several times another's: 1.8 for 20 species), so that this step judges its events near a target
  // from the last step's events per unit time (approach_target) and is block_steps long
  // (Collide.CheaperSamplerMeetsEventTargetsExactly).
  const bool was_lowrank = whole_step_ ? lowrank_blocks() : block_lowrank_;
  block_lowrank_ = choose_block_lowrank();
  sampler_changed = counters_.steps > 0 && block_lowrank_ != was_lowrank;
  if (block_lowrank_)  // the unblocked `lowrank` total (chi_max >= chi_ik) bounds the blocks' own
    rate = separable_blocks_ ? separable_block_rate()
           : lowrank_blocks() ? rate_
                              : lowrank_block_rate(max_speed2_.data()) * speed_factor_;
  return rate;
}

double Collider::approach_target(double step, double rate, std::uint64_t exact_target, bool sampler_changed) {
  // Near an exact event target (header "Event targets"): a blocked step is shortened so that its events
  // (its candidates R dt times an acceptance, approach_acceptance, plus 10 % and 8 standard deviations)
  // stay below those left. When that leaves less than N/64 events for it (or 4 blocks' worth, N 4/K, when
  // that is less), the step runs instead on the whole gas, which stops at the target itself, and is made
  // about 1.5 times as long as the events left need (\ref sch_blocks "docs/schemes.md").
  whole_step_ = keeps_blocks_ = false;
  if (exact_target == UINT64_MAX) return step;
  const double full_step = step;
  const double remaining = static_cast<double>(exact_target - counters_.events);
  const auto [acceptance, cooling_probe] = approach_acceptance(rate, sampler_changed);
  // A step longer than block_steps mean free times (block_step_length) near the target only after a
  // probe in a gas whose events per unit time fell: its acceptance is then one step old, and within a
  // step of a heating gas (rough spheres with a hot rotation) the events per unit time rise.
  if (!cooling_probe && may_reach(acceptance * rate * step, remaining))
    step = std::min(step, short_step_candidates() / rate);  // (never longer)
  const double expected = acceptance * rate * step;
  if (!may_reach(expected, remaining)) return step;
  // the largest mu with 1.1 mu + 8 sqrt(mu) + 16 <= remaining (a quadratic in sqrt(mu))
  const double root = (-8.0 + std::sqrt(std::max(0.0, 64.0 - 4.4 * (16.0 - remaining)))) / 2.2;
  const double fits = root > 0.0 ? root * root : 0.0;
  if (fits >= fewest_block_events()) {
    // A step shortened to at most block_steps mean free times brings a fraction of a step's events: it
    // keeps the blocks of the step before (whose remix, O(N), and with many species O(N) scattered writes,
    // would cost more than its events), while it ends within two full steps' time of the last remix: with
    // samples closer than a step every step is shortened, and blocks that were never dealt again would
    // become gases of their own. (a longer one, which takes a probe, is dealt anew as a full step is)
    const double shortened = step * (fits / expected);
    keeps_blocks_ = !is_long_step(shortened * rate) && time_ + shortened - remix_time_ <= 2.0 * full_step;
    return shortened;
  }
  whole_step_ = true;
  return step * std::min(1.0, 1.5 * remaining / expected);
}

Collider::ApproachAcceptance Collider::approach_acceptance(double rate, bool sampler_changed) const {
  // The events per candidate a step near a target expects (header "Event targets"): the last step's; 1,
  // a bound, for the first step and after one of fewer than min(N/64, 4 N/K) candidates (e.g. ended early
  // by a target given inside it), whose acceptance is too uncertain. After a change of sampler (or a
  // whole-gas step of the other one) the last step's acceptance is another majorant's: its events per
  // unit time instead, which do not depend on the majorant, over this step's R (\ref sch_blocks
  // "docs/schemes.md", "The cheaper sampler"). Within a long step the acceptance falls (the gas cools,
  // bounds are raised), so its mean underestimates the next step's: after one, the acceptance of its
  // first block_steps mean free times (its probe, at bounds as tight as the next step's) when its events
  // per unit time fell after the probe (by more than 3 standard deviations of the events after it, of which
  // at least min(N/64, 4 N/K): a noisy rate is not taken for a falling one), else 1. A step is long when
  // begun so (R dt; a whole-gas step's at the blocks' R, above its own) and run so (its candidates): one
  // begun short is judged as a short step, and when its bounds rose within it, so that it ran more
  // candidates than begun for, its acceptance is taken times their ratio, its events over the candidates
  // it was begun for (an estimate, as any short step's, never below its own acceptance).
  const auto last_candidates = static_cast<double>(counters_.candidates - step_candidates_start_);
  if (!(step_acceptance_ > 0.0) || last_candidates < fewest_block_events()) return {1.0, false};
  const double last_elapsed = time_ - step_start_;
  const auto last_events = static_cast<double>(counters_.events - step_events_start_);
  // (0 begun: an older checkpoint's step, judged by its candidates alone)
  const double planned = step_planned_candidates_ > 0.0 ? step_planned_candidates_ : last_candidates;
  if (probe_ != Probe::measured && !(is_long_step(planned) && is_long_step(last_candidates))) {
    if (!sampler_changed) return {std::min(1.0, step_acceptance_ * std::max(1.0, last_candidates / planned)), false};
    return {last_elapsed > 0.0 ? std::min(1.0, last_events / last_elapsed / rate) : 1.0, false};
  }
  if (sampler_changed || probe_ != Probe::measured || probe_events_ == 0 || !(time_ > probe_time_) ||
      !(probe_time_ > step_start_))
    return {1.0, false};
  const auto probe_events = static_cast<double>(probe_events_);
  const double events_after = last_events - probe_events;
  const double at_probe_rate = probe_events / (probe_time_ - step_start_) * (time_ - probe_time_);
  if (events_after < fewest_block_events() || !(events_after + 3.0 * std::sqrt(events_after) <= at_probe_rate))
    return {1.0, false};
  return {probe_events / static_cast<double>(probe_candidates_), true};
}

double Collider::short_step_candidates() const {
  return block_steps * step_fraction_ * static_cast<double>(sys_.size()) / 2.0;
}

bool Collider::is_long_step(double candidates) const { return candidates > 1.01 * short_step_candidates(); }

void Collider::begin_blocked_step(double step, double rate, bool exact_target) {
  if (whole_step_) {
    recompute_max_speeds();  // exact, O(N): the bound of the whole gas
    set_whole_gas_bound();
    credit_ = 0.0;
    pending_filled_ = false;
    // approach_target sized the step at the blocks' rate R; the whole gas's own R_w can be several times
    // less (the separable draw's bound W_b/sqrt(m_i) of every species): at least 1.25 of its candidates,
    // or a step for the last event could hold none (its credit starts at 0), and so would every next one.
    if (rate_ > 0.0) step = std::max(step, 1.25 / rate_);
  } else if (counters_.steps == 0 || !keeps_blocks_) {
    if (counters_.steps > 0) remix();
    remix_time_ = time_;
  }
  step_events_start_ = counters_.events;
  step_candidates_start_ = counters_.candidates;
  step_planned_candidates_ = step * rate;
  step_start_ = time_;
  next_step_time_ = time_ + step;
  // A blocked step longer than block_steps mean free times, on the way to an exact target, measures the
  // acceptance of its first ones (approach_target; run_blocks_pass).
  probe_ = exact_target && !whole_step_ && is_long_step(step * rate) ? Probe::pending : Probe::none;
  probe_time_ = probe_ == Probe::pending ? time_ + short_step_candidates() / rate : 0.0;
  probe_events_ = probe_candidates_ = 0;
  ++counters_.steps;
  counters_.step_sum += step;
}

double Collider::fewest_block_events() const {
  const double n_total = static_cast<double>(sys_.size());
  return std::min(n_total / 64.0, 4.0 * n_total / static_cast<double>(block_first_.size() - 1));
}

bool Collider::extend_whole_step(std::uint64_t exact_target) {
  // A whole-gas step that ended short of its exact target goes on (header "Blocks"), made 1.5 times as
  // long as the events left need at its own events per unit time: its bounds, only raised, still bound
  // the gas, and a new step would recompute them (O(N), and O(S) for the low-rank trees) and start
  // from the blocks' acceptance, whose guess after a short step (1) made it several times too short.
  if (!whole_step_ || exact_target == UINT64_MAX || counters_.events >= exact_target) return false;
  // (a target as far as a blocked step could go is left to the blocks: approach_target)
  if (static_cast<double>(exact_target - counters_.events) >= fewest_block_events()) return false;
  const double made = static_cast<double>(counters_.events - step_events_start_), elapsed = time_ - step_start_;
  if (!(made > 0.0 && elapsed > 0.0)) return false;  // (no events yet: a new step, of at least 1.25/R_w)
  const double more = 1.5 * static_cast<double>(exact_target - counters_.events) * elapsed / made;
  if (!(time_ + more > time_)) return false;  // (below the time's resolution: a new step)
  next_step_time_ = time_ + more;
  counters_.step_sum += more;
  return true;
}

bool Collider::advance_blocks(double t_target, std::uint64_t event_target, bool exact_events,
                              std::uint64_t event_limit, bool to_step_end) {
  const double entry_time = time_;
  // The target met exactly: the exact one, else the hard limit beyond a soft one.
  const std::uint64_t exact_target = exact_events ? std::min(event_target, event_limit) : event_limit;
  const std::uint64_t any_target = std::min(event_target, event_limit);
  end_step_at_target(exact_target);
  while (time_ < t_target) {
    if (time_ >= next_step_time_) {
      // Events are checked between steps only: all blocks are then at the same time.
      if (counters_.events >= any_target) return true;
      if (to_step_end && time_ > entry_time) return false;  // one step (or the rest of one) done
      if (stop_requested()) return false;
      if (extend_whole_step(exact_target)) continue;
      bool sampler_changed = false;
      const double rate = blocked_step_rate(sampler_changed);
      if (rate <= 0.0) {
        time_ = time_at_rest(t_target);
        return false;
      }
      begin_blocked_step(approach_target(block_step_length(rate, sampler_changed), rate, exact_target, sampler_changed),
                         rate, exact_target != UINT64_MAX);
    }
    const double t_stop = std::min(t_target, next_step_time_);
    if (whole_step_) {
      // (a call may start inside a whole-gas step with its target already met: a sample's target equal to
      // the last one's; the loop would only stop after one more event)
      if (counters_.events >= any_target) return true;
      const int stop = run_loop(lowrank_blocks() ? Scheme::lowrank : Scheme::majorant, t_stop, any_target);
      if (stop_requested()) return false;  // (the loop may have ended inside the step: run_substep)
      if (stop == static_cast<int>(Stop::bound_raised)) {
        if (lowrank_blocks()) {
          raise_lowrank_rows();  // the raised rows only (the same sums as a rebuild: segment_tree.hpp)
        } else {
          raised_.clear();
          set_whole_gas_bound();
        }
      }
      // (a raised bound takes precedence over the target in the loop's stop: the collision that raised it
      // may have met the target, and the next loop would pass it)
      if (stop == static_cast<int>(Stop::reached_events) || counters_.events >= any_target) return true;
      continue;
    }
    run_blocks_pass(time_, t_stop);
    time_ = t_stop;
    if (stop_requested()) return false;
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
  auto species_workspaces = std::move(species_workspaces_);
  remix_workspace_ = {};
  species_workspaces_ = {};
  std::vector<Collider> made;
  made.reserve(static_cast<std::size_t>(threads_));
  // Nor what only the master holds: a worker reads the slices, bounds and credits of its master's blocks
  // (run_block), and the whole-gas sampler and the slice counts serve the master's steps and remix.
  auto slice_first = std::move(slice_first_), slice_cum = std::move(slice_cum_), slice_count = std::move(slice_count_);
  auto block_max_speed2 = std::move(block_max_speed2_), block_credit = std::move(block_credit_);
  auto lowrank = std::move(lowrank_);
  slice_first_ = slice_cum_ = slice_count_ = {};
  block_max_speed2_ = block_credit_ = {};
  lowrank_ = segment_tree::LowRankSampler<3>();
  for (int t = 0; t < threads_; ++t) made.push_back(*this);
  slice_first_ = std::move(slice_first), slice_cum_ = std::move(slice_cum), slice_count_ = std::move(slice_count);
  block_max_speed2_ = std::move(block_max_speed2), block_credit_ = std::move(block_credit);
  lowrank_ = std::move(lowrank);
  remix_workspace_ = std::move(remix_workspace);
  species_workspaces_ = std::move(species_workspaces);
  workers_ = std::move(made);
  block_counters_.assign(block_first_.size() - 1, counters_);
}

void Collider::run_block(Collider& master, std::size_t j, double t_start, double t_stop, bool first_visit,
                         std::uint64_t key, double probe) {
  gen_ = rng::Xoshiro256pp::substream(key, j);  // keyed by (seed, replica, pass, block): header "Threads"
  counters_.events = counters_.candidates = counters_.overshoots = 0;
  counters_.largest_acceptance = counters_.dissipated = 0.0;
  std::fill(counters_.pair_events.begin(), counters_.pair_events.end(), 0);
  whole_step_ = false;
  current_block_ = j;
  slice_owner_ = &master;  // the slices of the master's remix (block_slice_first, block_slice_cum)
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
  const bool lowrank = master.block_lowrank_;  // the step's sampler (advance_blocks: choose_block_lowrank)
  // First visit in this step: the block's exact bound, read in order (which also brings the block
  // into the cache before its random reads); the separable draw's in the pass that gathers its species.
  bool measure_speeds = first_visit && lowrank && separable_blocks_;
  if (first_visit && !measure_speeds) set_block_max_speed2(j, block_speed2_);
  time_ = t_start;
  credit_ = master.block_credit_[j];
  const double n = master.pass_density_;
  // (a probe inside the visit: the block runs to it, its counts noted, then on to t_stop)
  double stop = probe > t_start && probe < t_stop ? probe : t_stop;
  const auto note_probe = [&] {
    master.block_probe_[j] = {counters_.events, counters_.candidates};
    stop = t_stop;
  };
  for (;;) {
    if (lowrank) {
      set_block_lowrank(n, measure_speeds);
      measure_speeds = false;  // (a bound raised by run_loop stays raised)
    } else {
      // A block of N_b particles at the gas's density n: R_b = N_b n B_b / 2 (as R, header "Blocks").
      // (a mixture: B_b = max_kj pi sigma_kj^2 chi_kj (vmax_bk + vmax_bj) over the block's slices)
      // (in a frame every relative speed bound times ||G||: header "Frame")
      bound_ = (s_ == 1 ? 2.0 * cross_section_[0] * std::sqrt(block_speed2_[0])
                        : mixture_bound(block_speed2_, block_slice_cum())) *
               speed_factor_;
      rate_ = 0.5 * static_cast<double>(range_count_) * n * bound_;
    }
    if (rate_ <= 0.0) break;
    if (kernels_) {  // the block kernels of a rule with the projection (rules.hpp): raised bounds handled inside
      run_block_kernels(lowrank, stop);
      if (stop < t_stop) {
        note_probe();
        run_block_kernels(lowrank, stop);
      }
      break;
    }
    if (run_loop(lowrank ? Scheme::lowrank : Scheme::majorant, stop, UINT64_MAX) == static_cast<int>(Stop::bound_raised))
      continue;
    if (stop == t_stop || time_ < stop) break;  // (time_ < stop: interrupted, stop_requested)
    note_probe();
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

void Collider::set_block_lowrank(double n, bool measure_speeds) {
  // The block's own A_ik (header "Mixtures in blocks"): the rank-3 hard-sphere majorant of its slices,
  // N_k the slice's count and V = (N_b - 1)/n, so that each pair's rate is pi sigma_ik^2 chi_ik |g|
  // n/(N_b - 1) as in the majorant blocks; vmax_k the block's. Columns as well as rows: the slices'
  // counts differ between blocks.
  // With at most block_species_limit species the entries are few: each is computed exactly, with
  // chi_ik itself instead of chi_max (the rank-3 form needs one chi for all pairs), A_ik = pi
  // sigma_ik^2 chi_ik w_i N_i N_k / V (the form of segment_tree.hpp's hard_sphere_factors with chi_ik),
  // a candidate then accepted with |g| / (w_i + w_k) (run_lowrank); a pair is drawn from their alias
  // table (one uniform) rather than by the trees' descents. Only the P species present in the block
  // (a scattered species may have no particle there) enter the kernel's tables.
  const std::size_t* cum = block_slice_cum();
  lowrank_volume_ = static_cast<double>(range_count_ - 1) / n;
  if (separable_blocks_) {  // more than separable_above species: the separable draw
    set_block_separable(cum, measure_speeds);
    return;
  }
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
  std::array<std::uint32_t, block_species_limit> present;
  std::size_t p = 0;
  for (std::size_t k = 0; k < s_; ++k)
    if (cum[k + 1] > cum[k]) present[p++] = static_cast<std::uint32_t>(k);
  // The mixture kernel's draw: one word over the P^2 pairs, or the factored draw above factor_above_
  // present species (collide.hpp, "Mixtures in blocks"; \ref sch_factored "docs/schemes.md").
  block_factored_ = p > factor_above_;
  if (block_factored_)
    set_block_factored(present.data(), p, cum);
  else
    set_block_one_word(present.data(), p, cum);
}

void Collider::set_block_one_word(const std::uint32_t* present_species, std::size_t p, const std::size_t* cum) {
  // The mixture kernel's one-word draw (header "Mixtures in blocks"): an alias table over P = 2^m
  // cells, the pairs of the present species followed by zero weights (never drawn: Vose's construction
  // sends them to their alias), so that the cell is m uniform bits of the word.
  // (present in a local array: the tables' 32-bit stores below might otherwise alias it, and the P^2
  // loops would read it again after each store, a fifth more instructions here)
  std::array<std::uint32_t, block_species_limit> present;
  std::copy_n(present_species, p, present.begin());
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
  const double coin_scale = std::ldexp(1.0, 16 - static_cast<int>(bits));  // 2^c, c = 16 - m coin bits
  lowrank_cells_.resize(std::size_t{1} << bits);
  // Keep cell c with probability t: with U = (q + V)/2^c (q the c coin bits, V uniform), U < t iff
  // q < floor(t 2^c), or q = floor(t 2^c) and V < t 2^c - floor(t 2^c) (both exact in doubles).
  // (rate_ > 0: a weight is positive, and every cell is built)
  pair_alias_.build_cells(pair_weights_, [&](std::size_t c, double threshold, std::size_t alias) {
    const double scaled = threshold * coin_scale;
    const auto whole = static_cast<std::uint32_t>(scaled);  // floor: 0 <= scaled <= 2^c (Vose's thresholds lie in [0, 1])
    const auto other = static_cast<std::uint32_t>(alias);
    lowrank_cells_[c] = {scaled - static_cast<double>(whole), whole, c < pairs ? static_cast<std::uint32_t>(c) : other,
                         other};
  });
  pair_weights_.resize(pairs);
  lowrank_outcomes_.resize(pairs);
  const std::size_t* slice = block_slice_first();
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

void Collider::set_block_factored(const std::uint32_t* present, std::size_t p, const std::size_t* cum) {
  // The factored draw (collide.hpp, "Mixtures in blocks"; \ref sch_factored "docs/schemes.md"): A_ik = w_i
  // rho_i q_k|i over the P species present. The column tables q_k|i hold no speed: built here, once per
  // visit; the rows, w_i rho_i, again at every raised bound (raise_block_factored).
  const std::size_t* slice = block_slice_first();
  // Every slice of the block below 2^24 (the 24-bit fields); else every candidate's reject is 2^24.
  bool narrow = true;
  for (std::size_t i = 0; i < s_; ++i) narrow = narrow && cum[i + 1] - cum[i] < (std::size_t{1} << 24);
  FactoredTables& f = factored_;
  f.species.resize(p);
  for (std::size_t a = 0; a < p; ++a) {
    const std::size_t i = present[a];
    const auto count = static_cast<std::uint32_t>(cum[i + 1] - cum[i]);
    f.species[a] = {static_cast<std::uint32_t>(slice[i]), count, narrow ? (1u << 24) % count : 1u << 24,
                    static_cast<std::uint32_t>(i * s_), static_cast<std::uint32_t>(i)};
  }
  unsigned bits = 1;  // at least two cells (one species present: it and a zero weight), r >> 64 being undefined
  while ((std::size_t{1} << bits) < p) ++bits;
  f.bits = bits;
  const std::size_t cells = std::size_t{1} << bits;
  f.columns.resize(p * cells);
  f.column_fraction.resize(p * cells);
  f.rho.resize(p);
  f.w.resize(p);
  pair_weights_.assign(cells, 0.0);
  for (std::size_t a = 0; a < p; ++a) {
    // Row i's columns: q_k|i proportional to pi sigma_ik^2 chi_ik N_k; rho_i = N_i sum_k (...) / V.
    const std::size_t i = present[a];
    double sum = 0.0;
    for (std::size_t b = 0; b < p; ++b) {
      const std::size_t k = present[b];
      pair_weights_[b] = cross_section_[i * s_ + k] * static_cast<double>(cum[k + 1] - cum[k]);
      sum += pair_weights_[b];
    }
    f.rho[a] = static_cast<double>(cum[i + 1] - cum[i]) * sum / lowrank_volume_;
    f.w[a] = max_speed_[i];
    fill_alias_cells(pair_weights_, p, bits, f.columns.data() + a * cells, f.column_fraction.data() + a * cells);
  }
  build_factored_rows();
}

void Collider::set_block_separable(const std::size_t* cum, bool measure_speeds) {
  // The separable draw (collide.hpp, "Mixtures in blocks"; \ref sch_separable "docs/schemes.md"): A_ik =
  // pi sigma_ik^2 chi_max w_i N_i N_k / V = sum_r u_i^(r) v_k^(r), sigma_ik^2 = (sigma_i^2 + 2 sigma_i
  // sigma_k + sigma_k^2)/4, u_i = (pi chi_max w_i N_i/(4V)) (sigma_i^2, 2 sigma_i, 1), v_k = N_k (1, sigma_k,
  // sigma_k^2) (Bodrova and Osinsky 2024, eqs. (12)-(14); segment_tree.hpp), with w_i = W_b/sqrt(m_i):
  // the term r with weight (sum_i u_i^(r)) (sum_k v_k^(r)), then i from u^(r) and k from v^(r). W_b is a
  // common factor of every u_i: no table holds a speed, and a raised W_b changes R_b only.
  const std::size_t* slice = block_slice_first();
  SeparableTables& t = separable_;
  t.species.clear();
  double energy2 = 0.0;
  bool narrow = true;  // every slice of the block below 2^24 (the 24-bit fields); else every reject is 2^24
  // (with measure_speeds, as set_block_max_speed2 in the same pass: with 1e5 species the block's slices are
  // 1e5 scattered short runs, whose walk costs about what reading them does)
  const auto gather = [&](auto measure) {
    for (std::size_t k = 0; k < s_; ++k) {
      const std::size_t count = cum[k + 1] - cum[k];
      if constexpr (decltype(measure)::value) {
        // (the slice some species ahead asked for now: each is a line of its own, and the walk's branches,
        // taken at random with one or two particles a slice, would keep the reads from overlapping)
        __builtin_prefetch(sys_.v.data() + slice[std::min(k + separable_prefetch_ahead, s_ - 1)]);
        block_speed2_[k] = slice_max_speed2(sys_.v.data() + slice[k], count);
      }
      if (count == 0) continue;
      narrow = narrow && count < (std::size_t{1} << 24);
      energy2 = std::max(energy2, mix_.mass[k] * block_speed2_[k]);
      t.species.push_back({static_cast<std::uint32_t>(slice[k]), static_cast<std::uint32_t>(count), 0,
                           static_cast<std::uint32_t>(k), 1.0 / std::sqrt(mix_.mass[k]), mix_.mass[k]});
    }
  };
  if (measure_speeds)
    gather(std::true_type{});
  else
    gather(std::false_type{});
  const std::size_t p = t.species.size();
  if (p > separable_species_limit)  // (separable_block_count: over 12 standard deviations beyond a block's mean)
    throw std::runtime_error("collide: " + std::to_string(p) + " species present in one cache block, more than the " +
                             "separable draw's " + std::to_string(separable_species_limit));
  for (SeparableSpecies& x : t.species) x.reject = narrow ? (1u << 24) % x.count : 1u << 24;
  unsigned bits = 1;  // at least two cells (one species present: it and a zero weight), r >> 64 being undefined
  while ((std::size_t{1} << bits) < p) ++bits;
  t.bits = bits;
  const std::size_t cells = std::size_t{1} << bits;
  t.rows.resize(3 * cells), t.row_fraction.resize(3 * cells);
  t.columns.resize(3 * cells), t.column_fraction.resize(3 * cells);
  double term[3];
  pair_weights_.assign(cells, 0.0);  // (the cells past the p present species stay zero: the six tables' padding)
  for (std::size_t r = 0; r < 3; ++r) {
    double row_sum = 0.0, column_sum = 0.0;
    // u^(r) / (pi chi_max W_b/(4V))
    for (std::size_t a = 0; a < p; ++a) {
      const double sigma = mix_.diameter[t.species[a].species];
      pair_weights_[a] = static_cast<double>(t.species[a].count) * t.species[a].inverse_root_mass *
                         (r == 0 ? sigma * sigma : r == 1 ? 2.0 * sigma : 1.0);
      row_sum += pair_weights_[a];
    }
    fill_alias_cells(pair_weights_, p, bits, t.rows.data() + r * cells, t.row_fraction.data() + r * cells);
    for (std::size_t a = 0; a < p; ++a) {  // v^(r)
      const double sigma = mix_.diameter[t.species[a].species];
      pair_weights_[a] = static_cast<double>(t.species[a].count) * (r == 0 ? 1.0 : r == 1 ? sigma : sigma * sigma);
      column_sum += pair_weights_[a];
    }
    fill_alias_cells(pair_weights_, p, bits, t.columns.data() + r * cells, t.column_fraction.data() + r * cells);
    term[r] = row_sum * column_sum;
  }
  const double sum = term[0] + term[1] + term[2];
  t.term0 = term[0] / sum, t.term01 = (term[0] + term[1]) / sum;
  t.energy2 = energy2;
  t.scale = std::numbers::pi * chi_max_ / (4.0 * lowrank_volume_) * sum;
  rate_ = t.scale * std::sqrt(energy2) * speed_factor_;  // (in a frame every bound times ||G||: header "Frame")
}

double Collider::separable_block_rate() const {
  // set_block_separable's R_b summed over the blocks with the gas's counts, V = (N - 1)/n, and W^2 =
  // max_k m_k vmax_k^2 (the largest of the blocks' W_b^2: the blocks' bounds make max_speed2_).
  double energy2 = 0.0, g[3] = {0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < s_; ++k) {
    const double count = static_cast<double>(sys_.count[k]), sigma = mix_.diameter[k];
    g[0] += count, g[1] += count * sigma, g[2] += count * sigma * sigma;
    energy2 = std::max(energy2, mix_.mass[k] * max_speed2_[k]);
  }
  double rows = 0.0;
  for (std::size_t k = 0; k < s_; ++k) {
    const double sigma = mix_.diameter[k];
    rows += static_cast<double>(sys_.count[k]) * (sigma * sigma * g[0] + 2.0 * sigma * g[1] + g[2]) /
            std::sqrt(mix_.mass[k]);
  }
  const double volume = static_cast<double>(sys_.size() - 1) / mix_.total_density();
  return std::numbers::pi * chi_max_ / (4.0 * volume) * rows * std::sqrt(energy2) * speed_factor_;
}

template <class Cell>
void Collider::fill_alias_cells(const std::vector<double>& w, std::size_t p, unsigned bits, Cell* out, double* fraction) {
  // Keep cell c with probability t: with U = (q + V)/2^c (q the c coin bits, V uniform), U < t iff
  // q < floor(t 2^c), or q = floor(t 2^c) and V < t 2^c - floor(t 2^c) (both exact in doubles).
  using Outcome = decltype(Cell::keep);
  const double coin_scale = std::ldexp(1.0, 32 - static_cast<int>(bits));  // 2^c, c = 32 - m coin bits
  const auto cell = [&](std::size_t c, double threshold, std::size_t alias) {
    const double scaled = threshold * coin_scale;
    const auto whole = static_cast<std::uint32_t>(scaled);  // floor: 0 <= scaled <= 2^c (Vose's thresholds lie in [0, 1])
    const auto other = static_cast<Outcome>(alias);
    out[c] = {whole, c < p ? static_cast<Outcome>(c) : other, other};
    fraction[c] = scaled - static_cast<double>(whole);
  };
  if (!pair_alias_.build_cells(w, cell, p))  // (all zero: no cell kept, each sends to outcome 0)
    for (std::size_t c = 0; c < w.size(); ++c) cell(c, 0.0, 0);
}

void Collider::build_factored_rows() {
  // Row weights w_i rho_i, their sum R_b = sum_ik A_ik (in a frame every w_i times ||G||: header "Frame";
  // speed_factor_ is 1 without one).
  FactoredTables& f = factored_;
  const std::size_t p = f.species.size();
  pair_weights_.assign(std::size_t{1} << f.bits, 0.0);
  rate_ = 0.0;
  for (std::size_t a = 0; a < p; ++a) {
    pair_weights_[a] = f.w[a] * speed_factor_ * f.rho[a];
    rate_ += pair_weights_[a];
  }
  if (!(rate_ > 0.0)) return;
  f.rows.resize(pair_weights_.size());
  f.row_fraction.resize(pair_weights_.size());
  fill_alias_cells(pair_weights_, p, f.bits, f.rows.data(), f.row_fraction.data());
}

void Collider::raise_block_factored() {
  // A raised bound (run_block_mixture): w_i anew from the block's bounds, then the rows (O(P); the
  // columns q_k|i do not depend on the speeds).
  FactoredTables& f = factored_;
  for (std::size_t a = 0; a < f.species.size(); ++a) {
    const std::uint32_t i = f.species[a].species;
    max_speed_[i] = f.w[a] = std::sqrt(block_speed2_[i]);
  }
  pending_filled_ = false;  // drawn from the old A_ik: redraw (header, "Look-ahead")
  build_factored_rows();
}

std::vector<std::size_t> Collider::visit_order(std::size_t blocks, int threads) {
  // Blocks next to each other share cache lines: a mixture's block is a slice of every species, and a
  // slice of a few particles starts and ends inside lines that its neighbours' slices share. Blocks
  // taken up one after another run at the same time on the threads, so consecutive ones are
  // ceil(K/T) apart: 0, h, 2h, .., 1, h + 1, .. (threads > 1; the order does not change any result).
  std::vector<std::size_t> order;
  order.reserve(blocks);
  const auto t = static_cast<std::size_t>(std::max(1, threads));
  const std::size_t h = (blocks + t - 1) / t;
  for (std::size_t i = 0; i < h; ++i)
    for (std::size_t r = 0; r < t; ++r)
      if (r * h + i < blocks) order.push_back(r * h + i);
  return order;
}

void Collider::run_blocks_pass(double t_start, double t_stop) {
  if (workers_.size() != static_cast<std::size_t>(threads_)) make_workers();
  const std::size_t blocks = block_first_.size() - 1;
  if (scattered_any_)  // the blocks of this step's remix (the workers are copies made earlier; slices: run_block)
    for (Collider& w : workers_) w.block_first_ = block_first_;
  const std::uint64_t key = gen_();  // this pass's key (header "Threads")
  if (framed_) block_moments_.assign(blocks, std::array<double, 4>{});
  const bool first_visit = t_start == step_start_;
  // The pass that holds a pending probe: each block's counts at probe_time_ (run_block).
  const bool probing = probe_ == Probe::pending && probe_time_ > t_start && probe_time_ < t_stop;
  if (probing) block_probe_.assign(blocks, {0, 0});
  const std::uint64_t events_before = counters_.events, candidates_before = counters_.candidates;
  std::vector<std::exception_ptr> failure(blocks);  // exceptions must not leave an OpenMP region
  const std::vector<std::size_t> order = visit_order(blocks, threads_);
  pass_density_ = mix_.total_density();
  const auto n_blocks = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1) if (threads_ > 1)
  for (std::ptrdiff_t q = 0; q < n_blocks; ++q) {
#ifdef _OPENMP
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
#else
    const std::size_t t = 0;
#endif
    const std::size_t j = order[static_cast<std::size_t>(q)];
    if (stop_requested()) continue;  // (interrupted: the run is abandoned, the blocks left are not visited)
    try {
      workers_[t].run_block(*this, j, t_start, t_stop, first_visit, key, probing ? probe_time_ : t_stop);
    } catch (...) {
      failure[j] = std::current_exception();
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
  if (probing) {  // the step's counts up to the probe: those before this pass and the blocks', in block order
    probe_ = Probe::measured;
    probe_events_ = events_before - step_events_start_;
    probe_candidates_ = candidates_before - step_candidates_start_;
    for (const auto& [events, candidates] : block_probe_) probe_events_ += events, probe_candidates_ += candidates;
  } else if (probe_ == Probe::pending && probe_time_ <= t_stop) {  // (a pass that ends at the probe)
    probe_ = Probe::measured;
    probe_events_ = counters_.events - step_events_start_;
    probe_candidates_ = counters_.candidates - step_candidates_start_;
  }
  time_ = t_stop;
}

}  // namespace gdsmc::collide
