#include "dsmc/agg_frag.hpp"
#include "dsmc/event_margin.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "dsmc/rules.hpp"
#include "model/species.hpp"

namespace gdsmc::agg_frag {

namespace {

using particles::Vec3;

/// This thread's number in the OpenMP team (0 outside one, or without OpenMP).
int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
/// The first cluster after cluster i of a list that starts at or past the next multiple of `bytes` from
/// the list's start: a copy that stops there may release the pages before that multiple whole.
std::size_t next_release_point(std::size_t i, std::size_t bytes) {
  const std::size_t boundary = (i * sizeof(Vec3) / bytes + 1) * bytes;
  return (boundary + sizeof(Vec3) - 1) / sizeof(Vec3);
}

/// The threads of this OpenMP team (1 outside one): OpenMP may give fewer than asked for (OMP_DYNAMIC,
/// OMP_THREAD_LIMIT), so work is split by this, not by the request.
std::uint32_t team_size() {
#ifdef _OPENMP
  return static_cast<std::uint32_t>(omp_get_num_threads());
#else
  return 1;
#endif
}

/// Two unit vectors: a uniform on the sphere and b uniform among the unit vectors perpendicular to a.
template <class Gen>
void perpendicular_pair(Gen& gen, Vec3& a, Vec3& b) {
  rng::unit_vector(gen, a.x, a.y, a.z);
  for (;;) {
    Vec3 r;
    rng::unit_vector(gen, r.x, r.y, r.z);
    const double along = r.x * a.x + r.y * a.y + r.z * a.z;
    Vec3 p{r.x - along * a.x, r.y - along * a.y, r.z - along * a.z};
    const double norm2 = p.x * p.x + p.y * p.y + p.z * p.z;
    if (norm2 < 1e-12) continue;  // r (anti)parallel to a: draw again (the direction is uniform either way)
    const double inv = 1.0 / std::sqrt(norm2);
    b = {p.x * inv, p.y * inv, p.z * inv};
    return;
  }
}

}  // namespace

Gas::Gas(const Model& model, std::size_t monomers, double temperature, particles::InitialDistribution distribution,
         rng::Xoshiro256pp initial, rng::Xoshiro256pp collisions, double step_fraction,
         const particles::SetUpCheck& check)
    : model_(model),
      initial_monomers_(monomers),
      volume_(static_cast<double>(monomers - 1) / model.monomer_density),
      step_fraction_(step_fraction),
      gen_(collisions) {
  if (monomers < 2) throw std::invalid_argument("agg_frag::Gas: at least 2 monomers are needed");
  const species::Mixture monomer = species::make_mixture(
      {model.monomer_mass}, {model.monomer_diameter}, {model.monomer_density},
      species::PairMatrix(1, model.restitution), false);
  particles::System sys = particles::make_system(monomer, {monomers}, {temperature}, distribution, initial, check);
  grow_to(1);
  // Exactly N_0 monomers, copied in chunks of 2 MiB whose pages are returned as they go (held about once:
  // header, "Memory").
  decltype(sys.species)().swap(sys.species);  // (one species: not needed, and freed before the copy)
  ClusterList& list = lists_[1];
  list.resize(monomers);
  constexpr std::size_t release_bytes = std::size_t{1} << 21;  // (whole huge pages of sys.v: not split)
  const char* const base = reinterpret_cast<const char*>(sys.v.data());
  const char* released = base;
  for (std::size_t start = 0; start < monomers;) {
    const std::size_t stop = std::min(next_release_point(start, release_bytes), monomers);
    std::copy(sys.v.begin() + static_cast<std::ptrdiff_t>(start), sys.v.begin() + static_cast<std::ptrdiff_t>(stop),
              list.begin() + static_cast<std::ptrdiff_t>(start));
    const char* done = base + stop * sizeof(Vec3) / release_bytes * release_bytes;
    if (done > released) released = particles::release_pages(released, done);
    start = stop;
  }
  clusters_ = monomers;
  recompute_bounds();
  rebuild_sampler();
  start_step();
}

Gas::Gas(const Model& model, const std::vector<std::uint32_t>& sizes, const std::vector<particles::Vec3>& velocities,
         rng::Xoshiro256pp collisions, double step_fraction)
    : model_(model), volume_(0.0), step_fraction_(step_fraction), gen_(collisions) {
  for (auto k : sizes) initial_monomers_ += k;
  if (sizes.size() != velocities.size() || initial_monomers_ < 2 || std::count(sizes.begin(), sizes.end(), 0u))
    throw std::invalid_argument("agg_frag::Gas: sizes and velocities must match, sizes >= 1, >= 2 monomers");
  volume_ = static_cast<double>(initial_monomers_ - 1) / model.monomer_density;
  for (std::size_t c = 0; c < sizes.size(); ++c) add(sizes[c], velocities[c]);
  recompute_bounds();
  rebuild_sampler();
  start_step();
}

void Gas::grow_to(std::size_t size) {
  if (size <= capacity_) return;
  std::size_t capacity = std::max<std::size_t>(capacity_, 16);
  while (capacity < size) capacity *= 2;
  capacity = std::max(std::min(capacity, std::max<std::size_t>(initial_monomers_, 1)), size);
  lists_.resize(capacity + 1);
  max_speed_.resize(capacity + 1, 0.0);
  diameter_.resize(capacity + 1, 0.0);
  set_diameters(capacity_ + 1, capacity);
  capacity_ = capacity;
  rebuild_sampler();  // at the new size: O(K), amortised by the doubling
}

void Gas::set_diameters(std::size_t first, std::size_t last) {
  for (std::size_t k = first; k <= last; ++k)
    diameter_[k] = std::cbrt(static_cast<double>(k)) * model_.monomer_diameter;  // sigma_k = k^(1/3) sigma_1
}

void Gas::rebuild_sampler() {
  std::vector<segment_tree::LowRankSampler<3>::Vector> rows(capacity_), columns(capacity_);
  for (std::size_t k = 1; k <= capacity_; ++k) {
    const auto f = segment_tree::hard_sphere_factors(static_cast<double>(lists_[k].size()), diameter_[k],
                                                     max_speed_[k], volume_);
    rows[k - 1] = f.row;
    columns[k - 1] = f.column;
  }
  sampler_ = segment_tree::LowRankSampler<3>(capacity_);
  sampler_.assign(rows, columns);
}

void Gas::update_size(std::uint32_t size) {
  const auto f = segment_tree::hard_sphere_factors(static_cast<double>(lists_[size].size()), diameter_[size],
                                                   max_speed_[size], volume_);
  sampler_.set_row(size - 1, f.row);
  sampler_.set_column(size - 1, f.column);
}

void Gas::add(std::uint32_t size, const Vec3& v) {
  grow_to(size);
  auto& list = lists_[size];
  if (list.empty()) max_speed_[size] = 0.0;  // a size that reappears starts a bound of its own
  list.push_back(v);
  ++clusters_;
  largest_reached_ = std::max<std::size_t>(largest_reached_, size);
  touched_.push_back(size);
  raise_bound(size, v);
}

void Gas::remove(Cluster c) {
  auto& list = lists_[c.size];
  list[c.place] = list.back();
  list.pop_back();
  --clusters_;
  if (list.empty()) max_speed_[c.size] = 0.0;
  touched_.push_back(c.size);
}

void Gas::remove_pair(Cluster a, Cluster b) {
  // In one list, the later place first: removing it cannot move the other.
  if (a.size == b.size && a.place < b.place) std::swap(a, b);
  remove(a);
  remove(b);
}

void Gas::raise_bound(std::uint32_t size, const Vec3& v) {
  const double speed2 = v.x * v.x + v.y * v.y + v.z * v.z;
  double& w = max_speed_[size];
  if (speed2 > w * w) {
    w = std::sqrt(speed2);
    // sqrt can round below the true speed: nudge up so that w >= |v| holds exactly
    if (w * w < speed2) w = std::nextafter(w, INFINITY);
    touched_.push_back(size);
  }
}

void Gas::recompute_bounds() {
  // O(N + sizes present), list by list; only sizes whose bound changes touch the trees. Empty
  // sizes keep w = 0 (remove), so the capacity K never enters the cost beyond one pass over the
  // list headers. A list that has shrunk to under a quarter of its capacity is trimmed here, once
  // per step, so that the memory follows the population.
  present_.clear();
  for (std::size_t k = 1; k <= capacity_; ++k) {
    auto& list = lists_[k];
    if (list.empty()) {
      if (list.capacity() > 0) ClusterList().swap(list);
      continue;
    }
    if (list.capacity() > 4 * list.size() + 64) ClusterList(list.begin(), list.end()).swap(list);
    // (a long list on the threads of the blocks, in parts: the largest of the parts' largest is the same number)
    [[maybe_unused]] const int threads = list.size() >= (std::size_t{1} << 16) ? block_threads_ : 1;
    double w2 = 0.0;
#ifdef _OPENMP
#pragma omp parallel for num_threads(threads) if (threads > 1) reduction(max : w2) schedule(static)
#endif
    for (std::size_t i = 0; i < list.size(); ++i) w2 = std::max(w2, list[i].x * list[i].x + list[i].y * list[i].y + list[i].z * list[i].z);
    double w = std::sqrt(w2);
    if (w * w < w2) w = std::nextafter(w, INFINITY);  // w >= |v| exactly
    if (w != max_speed_[k]) {
      max_speed_[k] = w;
      update_size(static_cast<std::uint32_t>(k));
    }
  }
  touched_.clear();
}

void Gas::start_step() {
  // A step is step_fraction majorant mean free times: nu_max = 2 R/N candidates per cluster.
  const double rate = sampler_.total();
  const double dt = rate > 0.0 ? step_fraction_ * static_cast<double>(clusters_) / (2.0 * rate) : INFINITY;
  next_step_time_ = time_ + dt;
  counters_.steps += 1;
  counters_.step_sum += dt;
}

Event Gas::collide(Cluster a, Cluster b) {
  Event event;
  const std::uint32_t k = a.size, j = b.size;
  const double m_k = mass(k), m_j = mass(j), total = m_k + m_j;
  const double reduced = m_k * m_j / total;
  const Vec3 va = lists_[k][a.place], vb = lists_[j][b.place];
  const double gx = va.x - vb.x, gy = va.y - vb.y, gz = va.z - vb.z;
  const double g2 = gx * gx + gy * gy + gz * gz;
  const Vec3 centre{(m_k * va.x + m_j * vb.x) / total, (m_k * va.y + m_j * vb.y) / total,
                    (m_k * va.z + m_j * vb.z) / total};
  event.impact_energy = 0.5 * reduced * g2;
  counters_.events += 1;
  if (sticks(model_, event.impact_energy)) {  // one cluster of k + j monomers moving with V
    event.outcome = Outcome::aggregation;
    remove_pair(a, b);
    add(k + j, centre);
    counters_.aggregations += 1;
    counters_.dissipated += event.impact_energy;
  } else {
    double ex = 0.0, ey = 0.0, ez = 1.0;
    const double g = std::sqrt(g2);
    if (g > 0.0) {
      while (!rules::hemisphere_normal(gen_, gx, gy, gz, g, ex, ey, ez)) {
      }
    }
    event.ex = ex, event.ey = ey, event.ez = ez;
    const double g_dot_e = gx * ex + gy * ey + gz * ez;
    event.normal_energy = 0.5 * reduced * g_dot_e * g_dot_e;
    if (shatters(model_, k, j, event.normal_energy)) {
      event.outcome = Outcome::fragmentation;
      const std::uint32_t fragments = k + j;
      // u = sqrt(k j) eps_f |g| / K: K m_1 u^2 / 2 = eps_f^2 E_imp (\ref af_corrections "docs/agg-frag.md")
      const double u = std::sqrt(static_cast<double>(k) * static_cast<double>(j)) * model_.fragment_restitution * g /
                       static_cast<double>(fragments);
      remove_pair(a, b);
      auto place = [&](const Vec3& d) { add(1, {centre.x + u * d.x, centre.y + u * d.y, centre.z + u * d.z}); };
      std::uint32_t left = fragments;
      if (left % 2 == 1) {  // the equilateral triple a, -a/2 + (sqrt3/2) b, -a/2 - (sqrt3/2) b
        Vec3 d1, d2;
        perpendicular_pair(gen_, d1, d2);
        const double h = 0.5 * std::sqrt(3.0);
        place(d1);
        place({-0.5 * d1.x + h * d2.x, -0.5 * d1.y + h * d2.y, -0.5 * d1.z + h * d2.z});
        place({-0.5 * d1.x - h * d2.x, -0.5 * d1.y - h * d2.y, -0.5 * d1.z - h * d2.z});
        left -= 3;
      }
      for (; left > 0; left -= 2) {  // a random unit vector and its opposite
        Vec3 d;
        rng::unit_vector(gen_, d.x, d.y, d.z);
        place(d);
        place({-d.x, -d.y, -d.z});
      }
      counters_.fragmentations += 1;
      const double eps = model_.fragment_restitution;
      counters_.dissipated += (1.0 - eps * eps) * event.impact_energy;
    } else {  // bounce: the smooth rule (rules.hpp, \ref cm_rule "docs/collision-model.md") with the monomer restitution
      event.outcome = Outcome::bounce;
      Vec3& wa = lists_[k][a.place];
      Vec3& wb = lists_[j][b.place];
      const auto pair = rules::SmoothRule::make_pair(model_.restitution, m_k, m_j);
      counters_.dissipated += rules::SmoothRule::collide(wa, wb, pair, {ex, ey, ez, g_dot_e, ex, ey, ez}).loss;
      raise_bound(k, wa);
      raise_bound(j, wb);
    }
  }
  // The sampler follows every size whose count or bound changed (each at most a few times).
  std::sort(touched_.begin(), touched_.end());
  touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
  for (std::uint32_t size : touched_) update_size(size);
  touched_.clear();
  return event;
}

// ---------------------------------------------------------------------------------------------
// Cache blocks (header, "Cache blocks"; \ref af_blocks "docs/agg-frag.md")
// ---------------------------------------------------------------------------------------------

void Gas::use_blocks(std::size_t block_size, int threads) {
  block_size_ = block_size;
  block_threads_ = std::max(threads, 1);
}

std::size_t Gas::blocks() const {
  if (block_size_ == 0 || clusters_ < 2 * block_size_) return 1;
  return clusters_ / block_size_;
}

double Gas::block_step_end() const {
  const double rate = sampler_.total();
  if (blocks() == 1 || !(rate > 0.0)) return time_;
  // block_steps step_fraction majorant mean free times (N/(2R) each), at most max_block_step_candidates
  // (the blocks notice a Ctrl-C every 2^16 of their candidates: advance())
  const double dt = std::min(block_steps * step_fraction_ * static_cast<double>(clusters_) / (2.0 * rate),
                             max_block_step_candidates / rate);
  return time_ + dt;
}

double Gas::target_step_candidates(std::uint64_t events_left) const {
  // Header, "Cache blocks": C candidates are expected to bring p C events, p twice the run's events per
  // candidate once it has made min_events_for_acceptance events, else 1 (events never exceed candidates);
  // p C is the largest that may not reach the events left (event_margin.hpp).
  double acceptance = 1.0;
  if (counters_.events >= min_events_for_acceptance)
    acceptance = std::min(1.0, 2.0 * static_cast<double>(counters_.events) / static_cast<double>(counters_.candidates));
  return event_margin::largest_safe_mean(static_cast<double>(events_left)) / acceptance;
}

double Gas::blocked_step_end(double t_target, std::uint64_t event_target) const {
  const double rate = sampler_.total();
  if (blocks() == 1 || !(rate > 0.0) || counters_.events >= event_target) return -1.0;
  const double free_time = static_cast<double>(clusters_) / (2.0 * rate);  // majorant mean free time
  double end = std::min(block_step_end(), t_target);
  // Towards an event target: a step whose events stay below it with margins (target_step_candidates).
  if (event_target != UINT64_MAX)
    end = std::min(end, time_ + target_step_candidates(event_target - counters_.events) / rate);
  // A step shorter than half a mean free time runs on the whole gas (a deal costs O(N)).
  return end - time_ >= 0.5 * free_time ? end : -1.0;
}

void Gas::reset_as_block(const Gas& whole) {
  model_ = whole.model_;
  stop_flag_ = whole.stop_flag_;  // a block stops early too; the gathered gas is then only discarded
  step_fraction_ = whole.step_fraction_;
  volume_ = whole.volume_;  // until the block's own is known (blocked_step)
  if (lists_.size() < whole.capacity_ + 1) {
    lists_.resize(whole.capacity_ + 1);
    max_speed_.resize(whole.capacity_ + 1, 0.0);
    diameter_.resize(whole.capacity_ + 1, 0.0);
    set_diameters(capacity_ + 1, whole.capacity_);
    capacity_ = whole.capacity_;
  }
  for (std::size_t k = 1; k <= capacity_; ++k) {
    lists_[k].clear();
    max_speed_[k] = 0.0;
  }
  if (sampler_.size() != capacity_) rebuild_sampler();  // recompute_bounds() updates its rows
  clusters_ = 0;
  initial_monomers_ = 0;
  largest_reached_ = 1;
  time_ = whole.time_;
  credit_ = 0.0;
  next_step_time_ = whole.time_;
  counters_ = Counters{};
  touched_.clear();
}

void Gas::draw_labels() {
  // The partition: labels of K - N mod K blocks of N div K and N mod K of one more, shuffled
  // (Fisher-Yates with the gas's own stream): every partition with these block sizes equally likely.
  const std::size_t n = clusters_, k_blocks = blocks();
  labels_.resize(n);
  const std::size_t q = n / k_blocks, r = n % k_blocks;
  std::size_t at = 0;
  for (std::size_t b = 0; b < k_blocks; ++b)
    for (std::size_t i = 0, size = q + (b < r ? 1 : 0); i < size; ++i) labels_[at++] = static_cast<std::uint32_t>(b);
  for (std::size_t i = n - 1; i > 0; --i) std::swap(labels_[i], labels_[gen_.below(i + 1)]);
}

void Gas::deal_blocks() {
  const std::size_t n = clusters_, k_blocks = blocks();
  draw_labels();
  if (blocks_.size() < k_blocks) blocks_.resize(k_blocks, Gas(model_));
  for (std::size_t b = 0; b < k_blocks; ++b) blocks_[b].reset_as_block(*this);
  // Deal: the clusters size by size, each list in order, to the block of their label (size k's labels
  // are labels_[first[k] ...]). The gas's order [0, N) is cut into one part per thread; the clusters of
  // size k that a part sends to block b take the places after those that the parts before it send
  // there (counted first), so that every block list holds its clusters in the gas's order, on any
  // number of threads. The clusters are held about once, not twice (header, "Memory"): every block
  // list is sized at its count (its pages not yet touched: particles::FillLaterArray) and reserved at
  // its count plus an eighth (room for the step's new clusters; the only allocation, so that nothing
  // throws while copying), and each part returns the pages of the gas's lists it has copied to the
  // system as it goes (every 64 KiB, or every 2 MiB in a list of 2 MiB or more, which allocate_bytes
  // gives huge pages: not split), the lists freed at the end.
  std::vector<std::size_t> first(capacity_ + 2, 0);
  for (std::size_t k = 1; k <= capacity_; ++k) first[k + 1] = first[k] + lists_[k].size();
  std::vector<std::uint32_t> present;  // the sizes present
  for (std::size_t k = 1; k <= capacity_; ++k)
    if (!lists_[k].empty()) present.push_back(static_cast<std::uint32_t>(k));
  const std::size_t sizes = present.size();
  const int threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(block_threads_), k_blocks));
  // part x size present x block: counts, then the part's first places (for the threads OpenMP gives, at most these)
  std::vector<std::size_t> place(static_cast<std::size_t>(threads) * sizes * k_blocks, 0);
  std::vector<Vec3*> to(static_cast<std::size_t>(threads) * k_blocks);  // each part's next place in each block
  std::vector<std::exception_ptr> failure(static_cast<std::size_t>(threads));
  bool failed = false;
#ifdef _OPENMP
#pragma omp parallel num_threads(threads) if (threads > 1)
#endif
  {
    const auto t = static_cast<std::size_t>(thread_index());
    const std::size_t team = team_size();
    const std::size_t lo = n * t / team, hi = n * (t + 1) / team;  // this thread's part
    std::size_t* mine = place.data() + t * sizes * k_blocks;
    for (std::size_t s = 0; s < sizes; ++s) {
      const std::size_t k = present[s];
      std::size_t* count = mine + s * k_blocks;
      for (std::size_t i = std::max(lo, first[k]); i < std::min(hi, first[k + 1]); ++i) ++count[labels_[i]];
    }
#ifdef _OPENMP
#pragma omp barrier
#endif
    for (std::size_t b = t; b < k_blocks; b += team) {
      try {
        size_block_lists(b, team, present, place.data());
      } catch (...) {
        failure[t] = std::current_exception();  // (an exception must not leave an OpenMP region)
#ifdef _OPENMP
#pragma omp atomic write
#endif
        failed = true;
      }
    }
#ifdef _OPENMP
#pragma omp barrier
#endif
    bool stop = false;
#ifdef _OPENMP
#pragma omp atomic read
#endif
    stop = failed;
    if (!stop) deal_part(first, present, mine, to.data() + t * k_blocks, lo, hi);  // (allocates nothing: cannot throw)
  }
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
  for (std::size_t k = 1; k <= capacity_; ++k) ClusterList().swap(lists_[k]);
}

void Gas::size_block_lists(std::size_t b, std::size_t parts, const std::vector<std::uint32_t>& present,
                           std::size_t* place) {
  const std::size_t k_blocks = blocks(), sizes = present.size();
  for (std::size_t s = 0; s < sizes; ++s) {
    std::size_t total = 0;  // the parts' first places: the counts of the parts before
    for (std::size_t p = 0; p < parts; ++p) {
      std::size_t& at = place[(p * sizes + s) * k_blocks + b];
      const std::size_t count = at;
      at = total;
      total += count;
    }
    if (total == 0) continue;
    auto& list = blocks_[b].lists_[present[s]];
    list.reserve(total + total / 8);
    list.resize(total);
    blocks_[b].initial_monomers_ += present[s] * total;
  }
}

void Gas::deal_part(const std::vector<std::size_t>& first, const std::vector<std::uint32_t>& present,
                    const std::size_t* place, Vec3** to, std::size_t lo, std::size_t hi) {
  const std::size_t k_blocks = blocks();
  for (std::size_t s = 0; s < present.size(); ++s) {
    const std::size_t k = present[s];
    const std::size_t begin = std::max(lo, first[k]), end = std::min(hi, first[k + 1]);
    if (begin >= end) continue;
    for (std::size_t b = 0; b < k_blocks; ++b) to[b] = blocks_[b].lists_[k].data() + place[s * k_blocks + b];
    const ClusterList& list = lists_[k];
    const std::size_t release_bytes =
        list.capacity() * sizeof(Vec3) >= (std::size_t{1} << 21) ? std::size_t{1} << 21 : std::size_t{1} << 16;
    // (whole multiples of release_bytes from the list's start, so that a huge page goes whole or not at all;
    // the pages before the part's first multiple, and a page it shares with the next part, go with the list)
    const auto base = reinterpret_cast<std::uintptr_t>(list.data());
    const std::size_t part_begin = begin - first[k], part_end = end - first[k];
    const char* released = reinterpret_cast<const char*>(
        base + (part_begin * sizeof(Vec3) + release_bytes - 1) / release_bytes * release_bytes);
    const std::uint32_t* label = labels_.data() + first[k];
    for (std::size_t start = part_begin; start < part_end;) {
      const std::size_t stop = std::min(next_release_point(start, release_bytes), part_end);
      for (std::size_t i = start; i < stop; ++i) *to[label[i]]++ = list[i];
      const char* done = reinterpret_cast<const char*>(base + (stop * sizeof(Vec3)) / release_bytes * release_bytes);
      if (done > released) released = particles::release_pages(released, done);
      start = stop;
    }
  }
}

void Gas::run_block(std::size_t b, double end, std::uint64_t key, double volume_per_partner) {
  Gas& block = blocks_[b];
  std::size_t members = 0;
  for (std::size_t k = 1; k <= block.capacity_; ++k) {
    members += block.lists_[k].size();
    if (!block.lists_[k].empty()) block.largest_reached_ = k;
  }
  block.clusters_ = members;
  block.volume_ = volume_per_partner * static_cast<double>(members - 1);
  block.gen_ = rng::Xoshiro256pp::substream(key, b);
  block.recompute_bounds();
  block.rebuild_sampler();
  const double rate = block.sampler_.total();
  if (rate > 0.0) block.credit_ = block.gen_.uniform() / rate;  // a uniformly random phase (header)
  block.start_step();
  block.advance(end);
}

void Gas::gather_blocks() {
  // In block order: the lists, the counters, the largest size. Each list of the gas is sized at its
  // total (its pages not yet touched: particles::FillLaterArray), and block b's clusters of size k go
  // to the places after those of the blocks before it, copied by the thread of block b; each block
  // list is released as soon as it is copied (its pages first: a freed small array may stay in the
  // heap), so that the clusters are again held about once (header, "Memory").
  const std::size_t k_blocks = blocks();
  std::size_t largest = 1;
  for (std::size_t b = 0; b < k_blocks; ++b) largest = std::max(largest, blocks_[b].capacity_);
  grow_to(largest);
  for (std::size_t k = 1; k <= capacity_; ++k)
    if (!lists_[k].empty()) throw std::logic_error("agg_frag: a list of the gas is not empty at the gather");
  std::vector<std::size_t> place(k_blocks * (capacity_ + 1), 0);  // block x size: the block's first place
  clusters_ = 0;
  for (std::size_t k = 1; k <= capacity_; ++k) {
    std::size_t total = 0;
    for (std::size_t b = 0; b < k_blocks; ++b) {
      place[b * (capacity_ + 1) + k] = total;
      if (k <= blocks_[b].capacity_) total += blocks_[b].lists_[k].size();
    }
    lists_[k].resize(total);
    clusters_ += total;
  }
  const int threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(block_threads_), k_blocks));
  const auto n_blocks = static_cast<std::ptrdiff_t>(k_blocks);
#ifdef _OPENMP
#pragma omp parallel for schedule(static, 1) num_threads(threads) if (threads > 1)
#endif
  for (std::ptrdiff_t bb = 0; bb < n_blocks; ++bb) {
    const auto b = static_cast<std::size_t>(bb);
    Gas& block = blocks_[b];
    for (std::size_t k = 1; k <= block.capacity_; ++k) {
      auto& from = block.lists_[k];
      if (!from.empty()) {
        std::copy(from.begin(), from.end(), lists_[k].begin() + static_cast<std::ptrdiff_t>(place[b * (capacity_ + 1) + k]));
        const char* data = reinterpret_cast<const char*>(from.data());
        particles::release_pages(data, data + from.capacity() * sizeof(Vec3));
      }
      if (from.capacity() > 0) ClusterList().swap(from);  // memory follows the gas
    }
  }
  for (std::size_t b = 0; b < k_blocks; ++b) {
    const Counters& c = blocks_[b].counters_;
    counters_.events += c.events;
    counters_.aggregations += c.aggregations;
    counters_.fragmentations += c.fragmentations;
    counters_.candidates += c.candidates;
    counters_.dissipated += c.dissipated;
    largest_reached_ = std::max(largest_reached_, blocks_[b].largest_reached_);
  }
}

void Gas::blocked_step(double end) {
  const std::size_t n = clusters_, k_blocks = blocks();
  deal_blocks();
  const std::uint64_t key = gen_();  // the blocks' streams for this step: substream(key, b)
  // V_b = V (n_b - 1)/(N - 1): every pair's expected rate is the whole gas's (header).
  const double volume_per_partner = volume_ / static_cast<double>(n - 1);
  std::vector<std::exception_ptr> failure(k_blocks);  // exceptions must not leave an OpenMP region
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(block_threads_) if (block_threads_ > 1)
#endif
  for (std::ptrdiff_t b = 0; b < static_cast<std::ptrdiff_t>(k_blocks); ++b) {
    try {
      run_block(static_cast<std::size_t>(b), end, key, volume_per_partner);
    } catch (...) {
      failure[static_cast<std::size_t>(b)] = std::current_exception();
    }
  }
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
  gather_blocks();
  counters_.steps += 1;
  counters_.step_sum += end - time_;
  blocked_steps_ += 1;
  time_ = end;
  credit_ = 0.0;
  next_step_time_ = end;  // the next step starts now, with exact bounds
  for (std::size_t k = 1; k <= capacity_; ++k) max_speed_[k] = 0.0;
  recompute_bounds();
  rebuild_sampler();
  bounds_exact_ = true;  // advance() need not recompute them at the step that starts now
}

bool Gas::advance(double t_target, std::uint64_t event_target) {
  if (counters_.events >= event_target) return true;
  // The sampler's totals (R and its terms) and 1/R, computed once per change of the sampler (an
  // event, a step start) instead of once per candidate: the same values, so the same draws.
  decltype(sampler_)::Totals totals;
  double inverse_rate = 0.0;
  bool totals_valid = false;
  for (;;) {
    if (time_ >= next_step_time_) {  // exact bounds again (they only rise within a step)
      if (stop_flag_ && stop_flag_->load(std::memory_order_relaxed)) return false;
      totals_valid = false;
      if (!bounds_exact_) recompute_bounds();
      bounds_exact_ = false;
      const double end = blocked_step_end(t_target, event_target);
      if (end > time_) {
        blocked_step(end);
        if (counters_.events > event_target)
          throw std::runtime_error("agg_frag: a blocked step passed the event target (" +
                                   std::to_string(counters_.events) + " > " + std::to_string(event_target) +
                                   " collisions); run with block_size = 0 or give t_end");
        if (counters_.events == event_target) return true;
        if (time_ >= t_target) return false;
        continue;
      }
      start_step();
    }
    if (!totals_valid) {
      totals = sampler_.totals();
      inverse_rate = 1.0 / totals.sum;
      totals_valid = true;
    }
    const double rate = totals.sum;
    // One cluster left (R > 0 still: its self pair, always rejected): nothing can collide.
    if (clusters_ < 2 || !(rate > 0.0)) {
      time_ = std::max(time_, t_target);
      return false;
    }
    // The next candidate comes 1/R after the last one, R the current rate (\ref af_scheme "docs/agg-frag.md")
    // (0 when a rise of R made the next candidate overdue: it comes now).
    const double wait = std::max(0.0, inverse_rate - credit_);
    const double stop = std::min(t_target, next_step_time_);
    if (time_ + wait > stop) {
      credit_ += stop - time_;
      time_ = stop;
      if (stop >= t_target) return false;
      continue;
    }
    time_ += wait;
    credit_ = 0.0;
    counters_.candidates += 1;
    // A blocked step holds up to 2^24 candidates: an interrupt is noticed every 2^16 (a few ms) and the
    // step is abandoned (the gathered gas is only discarded); no draw depends on it.
    if ((counters_.candidates & 0xFFFFu) == 0 && stop_flag_ && stop_flag_->load(std::memory_order_relaxed)) return false;
    const auto [row, column] = sampler_.sample(gen_, totals);
    const Cluster a{static_cast<std::uint32_t>(row + 1), 0}, b0{static_cast<std::uint32_t>(column + 1), 0};
    const auto& list_a = lists_[a.size];
    const auto& list_b = lists_[b0.size];
    const Cluster ca{a.size, static_cast<std::uint32_t>(gen_.below(list_a.size()))};
    const Cluster cb{b0.size, static_cast<std::uint32_t>(gen_.below(list_b.size()))};
    if (ca.size == cb.size && ca.place == cb.place) continue;  // the same cluster twice
    const Vec3& va = list_a[ca.place];
    const Vec3& vb = list_b[cb.place];
    const double gx = va.x - vb.x, gy = va.y - vb.y, gz = va.z - vb.z;
    const double g2 = gx * gx + gy * gy + gz * gz;
    // accept with |g| / (w_i + w_k), compared squared
    const double threshold = gen_.uniform() * (max_speed_[ca.size] + max_speed_[cb.size]);
    if (threshold * threshold >= g2) continue;
    collide(ca, cb);
    totals_valid = false;  // the event changed the sampler
    if (counters_.events >= event_target) return true;
  }
}

Vec3 Gas::momentum() const {
  Vec3 p{0.0, 0.0, 0.0};
  for (std::size_t k = 1; k <= capacity_; ++k) {
    const double m = mass(k);
    for (const Vec3& v : lists_[k]) {
      p.x += m * v.x;
      p.y += m * v.y;
      p.z += m * v.z;
    }
  }
  return p;
}

double Gas::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t k = 1; k <= capacity_; ++k)
    for (const Vec3& v : lists_[k]) e += 0.5 * mass(k) * (v.x * v.x + v.y * v.y + v.z * v.z);
  return e;
}

std::size_t Gas::memory_bytes() const {
  std::size_t bytes = 0;
  for (const auto& list : lists_) bytes += list.capacity() * sizeof(Vec3) + sizeof(list);
  for (const Gas& block : blocks_) bytes += block.memory_bytes();
  bytes += labels_.capacity() * sizeof(std::uint32_t);
  bytes += (max_speed_.capacity() + diameter_.capacity()) * sizeof(double);
  bytes += 6 * 2 * capacity_ * sizeof(double);  // the sampler's six trees (2P doubles each, P < 2K)
  return bytes;
}

bool Gas::bounds_hold() const {
  for (std::size_t k = 1; k <= capacity_; ++k)
    for (const Vec3& v : lists_[k])
      if (v.x * v.x + v.y * v.y + v.z * v.z > max_speed_[k] * max_speed_[k]) return false;
  return true;
}

Measurement Gas::measure() const {
  Measurement m;
  const Vec3 p = momentum();
  const double total_mass = model_.monomer_mass * static_cast<double>(initial_monomers_);
  const Vec3 u{p.x / total_mass, p.y / total_mass, p.z / total_mass};  // mean flow (zero to round-off)
  std::size_t largest = 1;
  for (std::size_t k = 1; k <= capacity_; ++k)
    if (!lists_[k].empty()) largest = k;
  m.number.assign(largest, 0.0);
  m.energy.assign(largest, 0.0);
  for (std::size_t k = 1; k <= largest; ++k) {
    double e = 0.0;
    for (const Vec3& v : lists_[k]) {
      const Vec3 d{v.x - u.x, v.y - u.y, v.z - u.z};
      e += d.x * d.x + d.y * d.y + d.z * d.z;
    }
    m.energy[k - 1] = 0.5 * mass(k) * e;
    m.number[k - 1] = static_cast<double>(lists_[k].size());
    m.kinetic_energy += m.energy[k - 1];
  }
  m.clusters = static_cast<double>(clusters_);
  return m;
}

Gas::State Gas::state() const {
  State s;
  s.velocity.reserve(3 * clusters_);
  s.count.resize(capacity_);
  for (std::size_t k = 1; k <= capacity_; ++k) {
    s.count[k - 1] = lists_[k].size();
    for (const Vec3& v : lists_[k]) s.velocity.insert(s.velocity.end(), {v.x, v.y, v.z});
  }
  s.max_speed.assign(max_speed_.begin() + 1, max_speed_.end());
  s.time = time_;
  s.credit = credit_;
  s.next_step_time = next_step_time_;
  s.capacity = capacity_;
  s.largest_reached = largest_reached_;
  s.counters = counters_;
  s.generator = gen_.state();
  return s;
}

void Gas::restore(const State& s) {
  std::size_t clusters = 0, monomers = 0;
  if (s.count.size() != s.capacity || s.max_speed.size() != s.capacity ||
      s.capacity > std::max<std::size_t>(initial_monomers_, 16))
    throw std::runtime_error("agg_frag checkpoint: inconsistent cluster tables");
  for (std::size_t k = 1; k <= s.capacity; ++k) {
    clusters += s.count[k - 1];
    monomers += k * s.count[k - 1];
  }
  if (monomers != initial_monomers_ || s.velocity.size() != 3 * clusters)
    throw std::runtime_error("agg_frag checkpoint: the monomer count differs from the input");
  // The tables at the saved capacity: the trees' sums then come out bit for bit as they were.
  lists_.clear();
  max_speed_.clear();
  diameter_.clear();
  capacity_ = 0;
  grow_to(s.capacity);
  std::size_t at = 0;
  for (std::size_t k = 1; k <= capacity_; ++k) {
    auto& list = lists_[k];
    list.resize(s.count[k - 1]);
    for (Vec3& v : list) {
      v = {s.velocity[at], s.velocity[at + 1], s.velocity[at + 2]};
      at += 3;
    }
    max_speed_[k] = s.max_speed[k - 1];
  }
  clusters_ = clusters;
  rebuild_sampler();
  time_ = s.time;
  credit_ = s.credit;
  next_step_time_ = s.next_step_time;
  largest_reached_ = s.largest_reached;
  counters_ = s.counters;
  gen_.set_state(s.generator);
  touched_.clear();
  bounds_exact_ = false;
}

void Gas::save(state::Record& r) const {
  const State s = state();
  r.put("clusters/velocity", s.velocity);
  r.put("clusters/count", s.count);
  r.put("clusters/max_speed", s.max_speed);
  r.put("clusters/time", s.time);
  r.put("clusters/credit", s.credit);
  r.put("clusters/next_step_time", s.next_step_time);
  r.put("clusters/step_sum", s.counters.step_sum);
  r.put("clusters/dissipated", s.counters.dissipated);
  r.put("clusters/generator", std::vector<std::uint64_t>(std::begin(s.generator.s), std::end(s.generator.s)));
  r.put("clusters/generator_spare", s.generator.spare);
  r.put_integer("clusters/generator_has_spare", s.generator.has_spare);
  r.put_integer("clusters/events", s.counters.events);
  r.put_integer("clusters/aggregations", s.counters.aggregations);
  r.put_integer("clusters/fragmentations", s.counters.fragmentations);
  r.put_integer("clusters/candidates", s.counters.candidates);
  r.put_integer("clusters/steps", s.counters.steps);
  r.put_integer("clusters/capacity", s.capacity);
  r.put_integer("clusters/largest_reached", s.largest_reached);
}

void Gas::restore(const state::Record& r) {
  State s;
  s.velocity = r.array("clusters/velocity");
  s.count = r.integer_array("clusters/count");
  s.max_speed = r.array("clusters/max_speed");
  s.time = r.real("clusters/time");
  s.credit = r.real("clusters/credit");
  s.next_step_time = r.real("clusters/next_step_time");
  s.counters.step_sum = r.real("clusters/step_sum");
  s.counters.dissipated = r.real("clusters/dissipated");
  const auto& generator = r.integer_array("clusters/generator", 4);
  std::copy(generator.begin(), generator.end(), std::begin(s.generator.s));
  s.generator.spare = r.real("clusters/generator_spare");
  s.generator.has_spare = r.flag("clusters/generator_has_spare");
  s.counters.events = r.integer("clusters/events");
  s.counters.aggregations = r.integer("clusters/aggregations");
  s.counters.fragmentations = r.integer("clusters/fragmentations");
  s.counters.candidates = r.integer("clusters/candidates");
  s.counters.steps = r.integer("clusters/steps");
  s.capacity = r.integer("clusters/capacity");
  s.largest_reached = r.integer("clusters/largest_reached");
  restore(s);
}

}  // namespace gdsmc::agg_frag
