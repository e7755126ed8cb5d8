#include "dsmc/agg_frag.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dsmc/collide.hpp"
#include "dsmc/species.hpp"

namespace gdsmc::agg_frag {

namespace {

using particles::Vec3;

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
         rng::Xoshiro256pp initial, rng::Xoshiro256pp collisions, double step_fraction)
    : model_(model),
      initial_monomers_(monomers),
      volume_(static_cast<double>(monomers - 1) / model.monomer_density),
      step_fraction_(step_fraction),
      gen_(collisions) {
  if (monomers < 2) throw std::invalid_argument("agg_frag::Gas: at least 2 monomers are needed");
  const species::Mixture monomer = species::make_mixture(
      {model.monomer_mass}, {model.monomer_diameter}, {model.monomer_density},
      species::PairMatrix(1, model.restitution), false);
  particles::System sys = particles::make_system(monomer, {monomers}, {temperature}, distribution, initial);
  v_ = std::move(sys.v);
  v_.reserve(monomers);
  size_.reserve(monomers);
  slot_.reserve(monomers);
  grow_to(1);
  members_[1].reserve(monomers);
  for (std::size_t c = 0; c < monomers; ++c) {
    size_.push_back(1);
    slot_.push_back(0);
    add_member(c, 1);
  }
  recompute_bounds();
  rebuild_sampler();
  start_step();
}

Gas::Gas(const Model& model, const std::vector<std::uint32_t>& sizes, const std::vector<Vec3>& velocities,
         rng::Xoshiro256pp collisions, double step_fraction)
    : model_(model), initial_monomers_(0), volume_(0.0), step_fraction_(step_fraction), gen_(collisions) {
  std::size_t largest = 1;
  for (auto k : sizes) {
    initial_monomers_ += k;
    largest = std::max<std::size_t>(largest, k);
  }
  if (sizes.size() != velocities.size() || initial_monomers_ < 2 || std::count(sizes.begin(), sizes.end(), 0u))
    throw std::invalid_argument("agg_frag::Gas: sizes and velocities must match, sizes >= 1, >= 2 monomers");
  volume_ = static_cast<double>(initial_monomers_ - 1) / model.monomer_density;
  v_.reserve(initial_monomers_);
  size_.reserve(initial_monomers_);
  slot_.reserve(initial_monomers_);
  grow_to(largest);
  for (std::size_t c = 0; c < sizes.size(); ++c) append_cluster(velocities[c], sizes[c]);
  largest_reached_ = largest;
  recompute_bounds();
  rebuild_sampler();
  start_step();
}

void Gas::grow_to(std::size_t size) {
  if (size <= capacity_) return;
  std::size_t capacity = std::max<std::size_t>(capacity_, 16);
  while (capacity < size) capacity *= 2;
  capacity = std::max(std::min(capacity, std::max<std::size_t>(initial_monomers_, 1)), size);
  members_.resize(capacity + 1);
  max_speed_.resize(capacity + 1, 0.0);
  diameter_.resize(capacity + 1, 0.0);
  for (std::size_t k = capacity_ + 1; k <= capacity; ++k)
    diameter_[k] = std::cbrt(static_cast<double>(k)) * model_.monomer_diameter;  // sigma_k = k^(1/3) sigma_1
  capacity_ = capacity;
  rebuild_sampler();  // at the new size: O(K), amortised by the doubling
}

void Gas::rebuild_sampler() {
  std::vector<segment_tree::LowRankSampler<3>::Vector> rows(capacity_), columns(capacity_);
  for (std::size_t k = 1; k <= capacity_; ++k) {
    const auto f = segment_tree::hard_sphere_factors(static_cast<double>(members_[k].size()), diameter_[k],
                                                     max_speed_[k], volume_);
    rows[k - 1] = f.row;
    columns[k - 1] = f.column;
  }
  sampler_ = segment_tree::LowRankSampler<3>(capacity_);
  sampler_.assign(rows, columns);
}

void Gas::update_size(std::uint32_t size) {
  const auto f = segment_tree::hard_sphere_factors(static_cast<double>(members_[size].size()), diameter_[size],
                                                   max_speed_[size], volume_);
  sampler_.set_row(size - 1, f.row);
  sampler_.set_column(size - 1, f.column);
}

void Gas::add_member(std::size_t cluster, std::uint32_t size) {
  grow_to(size);
  auto& list = members_[size];
  if (list.empty()) max_speed_[size] = 0.0;  // a size that reappears starts a bound of its own
  size_[cluster] = size;
  slot_[cluster] = static_cast<std::uint32_t>(list.size());
  list.push_back(static_cast<std::uint32_t>(cluster));
  largest_reached_ = std::max<std::size_t>(largest_reached_, size);
  touched_.push_back(size);
}

void Gas::remove_member(std::size_t cluster) {
  const std::uint32_t size = size_[cluster];
  auto& list = members_[size];
  const std::uint32_t place = slot_[cluster];
  const std::uint32_t last = list.back();
  list[place] = last;
  slot_[last] = place;
  list.pop_back();
  if (list.empty()) max_speed_[size] = 0.0;
  touched_.push_back(size);
}

std::size_t Gas::remove_cluster(std::size_t c) {
  const std::size_t last = v_.size() - 1;
  if (c != last) {
    v_[c] = v_[last];
    size_[c] = size_[last];
    slot_[c] = slot_[last];
    members_[size_[c]][slot_[c]] = static_cast<std::uint32_t>(c);
  }
  v_.pop_back();
  size_.pop_back();
  slot_.pop_back();
  return last;
}

std::size_t Gas::append_cluster(const Vec3& v, std::uint32_t size) {
  const std::size_t c = v_.size();
  v_.push_back(v);
  size_.push_back(size);
  slot_.push_back(0);
  add_member(c, size);
  return c;
}

void Gas::raise_bound(std::size_t cluster) {
  const Vec3& v = v_[cluster];
  const double speed2 = v.x * v.x + v.y * v.y + v.z * v.z;
  double& w = max_speed_[size_[cluster]];
  if (speed2 > w * w) {
    w = std::sqrt(speed2);
    // sqrt can round below the true speed: nudge up so that w >= |v| holds exactly
    if (w * w < speed2) w = std::nextafter(w, INFINITY);
    touched_.push_back(size_[cluster]);
  }
}

void Gas::recompute_bounds() {
  // O(N + sizes present): the largest speed of each size present, in scratch_ (squared), found in
  // one pass over the clusters; only sizes whose bound changes touch the trees. Empty sizes keep
  // w = 0 (remove_member), so the capacity K never enters the cost: a gas of a few large
  // clusters must not pay for every size it once had.
  if (scratch_.size() < capacity_ + 1) scratch_.assign(capacity_ + 1, -1.0);
  present_.clear();
  for (std::size_t c = 0; c < v_.size(); ++c) {
    const Vec3& v = v_[c];
    const double speed2 = v.x * v.x + v.y * v.y + v.z * v.z;
    double& w2 = scratch_[size_[c]];
    if (w2 < 0.0) {
      w2 = speed2;
      present_.push_back(size_[c]);
    } else if (speed2 > w2) {
      w2 = speed2;
    }
  }
  std::sort(present_.begin(), present_.end());  // the trees are updated in one order in every run
  for (std::uint32_t k : present_) {
    double w = std::sqrt(scratch_[k]);
    if (w * w < scratch_[k]) w = std::nextafter(w, INFINITY);  // w >= |v| exactly
    scratch_[k] = -1.0;
    if (w != max_speed_[k]) {
      max_speed_[k] = w;
      update_size(k);
    }
  }
  touched_.clear();
}

void Gas::start_step() {
  // A step is step_fraction majorant mean free times: nu_max = 2 R/N candidates per cluster.
  const double rate = sampler_.total();
  const double dt = rate > 0.0 ? step_fraction_ * static_cast<double>(v_.size()) / (2.0 * rate) : INFINITY;
  next_step_time_ = time_ + dt;
  counters_.steps += 1;
  counters_.step_sum += dt;
}

Event Gas::collide(std::size_t a, std::size_t b) {
  Event event;
  const std::uint32_t k = size_[a], j = size_[b];
  const double m_k = mass(k), m_j = mass(j), total = m_k + m_j;
  const double reduced = m_k * m_j / total;
  const Vec3 va = v_[a], vb = v_[b];
  const double gx = va.x - vb.x, gy = va.y - vb.y, gz = va.z - vb.z;
  const double g2 = gx * gx + gy * gy + gz * gz;
  const Vec3 centre{(m_k * va.x + m_j * vb.x) / total, (m_k * va.y + m_j * vb.y) / total,
                    (m_k * va.z + m_j * vb.z) / total};
  event.impact_energy = 0.5 * reduced * g2;
  counters_.events += 1;
  if (sticks(model_, event.impact_energy)) {  // one cluster of k + j monomers moving with V
    event.outcome = Outcome::aggregation;
    remove_member(b);
    const std::size_t moved = remove_cluster(b);  // a is still listed, so a move of a is recorded
    if (moved == a) a = b;                        // a was the last cluster: it now lives where b was
    remove_member(a);
    v_[a] = centre;
    add_member(a, k + j);
    raise_bound(a);
    counters_.aggregations += 1;
    counters_.dissipated += event.impact_energy;
  } else {
    double ex = 0.0, ey = 0.0, ez = 1.0;
    const double g = std::sqrt(g2);
    if (g > 0.0) {
      while (!collide::hemisphere_normal(gen_, gx, gy, gz, g, ex, ey, ez)) {
      }
    }
    event.ex = ex, event.ey = ey, event.ez = ez;
    const double g_dot_e = gx * ex + gy * ey + gz * ez;
    event.normal_energy = 0.5 * reduced * g_dot_e * g_dot_e;
    if (shatters(model_, k, j, event.normal_energy)) {
      event.outcome = Outcome::fragmentation;
      const std::uint32_t fragments = k + j;
      // u = sqrt(k j) eps_f |g| / K: K m_1 u^2 / 2 = eps_f^2 E_imp (ERRATA §12)
      const double u = std::sqrt(static_cast<double>(k) * static_cast<double>(j)) * model_.fragment_restitution * g /
                       static_cast<double>(fragments);
      remove_member(a);
      remove_member(b);
      std::size_t placed = 0;
      auto place = [&](const Vec3& d) {
        const Vec3 w{centre.x + u * d.x, centre.y + u * d.y, centre.z + u * d.z};
        std::size_t c;
        if (placed == 0) {
          c = a;
          v_[c] = w;
          add_member(c, 1);
        } else if (placed == 1) {
          c = b;
          v_[c] = w;
          add_member(c, 1);
        } else {
          c = append_cluster(w, 1);
        }
        raise_bound(c);
        ++placed;
      };
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
    } else {  // bounce: ERRATA §1 with the monomer restitution
      event.outcome = Outcome::bounce;
      const double alpha = model_.restitution;
      const double impulse = (1.0 + alpha) * g_dot_e;
      const double da = (m_j / total) * impulse, db = (m_k / total) * impulse;
      v_[a] = {va.x - da * ex, va.y - da * ey, va.z - da * ez};
      v_[b] = {vb.x + db * ex, vb.y + db * ey, vb.z + db * ez};
      raise_bound(a);
      raise_bound(b);
      counters_.dissipated += (1.0 - alpha * alpha) * event.normal_energy;
    }
  }
  // The sampler follows every size whose count or bound changed (each at most a few times).
  std::sort(touched_.begin(), touched_.end());
  touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
  for (std::uint32_t size : touched_) update_size(size);
  touched_.clear();
  return event;
}

bool Gas::advance(double t_target, std::uint64_t event_target) {
  if (counters_.events >= event_target) return true;
  for (;;) {
    if (time_ >= next_step_time_) {  // exact bounds again (they only rise within a step)
      recompute_bounds();
      start_step();
    }
    const double rate = sampler_.total();
    // One cluster left (R > 0 still: its self pair, always rejected): nothing can collide.
    if (v_.size() < 2 || !(rate > 0.0)) {
      time_ = std::max(time_, t_target);
      return false;
    }
    // The next candidate comes 1/R after the last one, R the current rate (ERRATA §12).
    // (0 when a rise of R made the next candidate overdue: it comes now)
    const double wait = std::max(0.0, 1.0 / rate - credit_);
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
    const auto [row, column] = sampler_.sample(gen_);
    const std::uint32_t i = static_cast<std::uint32_t>(row + 1), k = static_cast<std::uint32_t>(column + 1);
    const auto& list_i = members_[i];
    const auto& list_k = members_[k];
    const std::size_t a = list_i[gen_.below(list_i.size())];
    const std::size_t b = list_k[gen_.below(list_k.size())];
    if (a == b) continue;
    const Vec3& va = v_[a];
    const Vec3& vb = v_[b];
    const double gx = va.x - vb.x, gy = va.y - vb.y, gz = va.z - vb.z;
    const double g2 = gx * gx + gy * gy + gz * gz;
    // accept with |g| / (w_i + w_k), compared squared
    const double threshold = gen_.uniform() * (max_speed_[i] + max_speed_[k]);
    if (threshold * threshold >= g2) continue;
    collide(a, b);
    if (counters_.events >= event_target) return true;
  }
}

Vec3 Gas::momentum() const {
  Vec3 p{0.0, 0.0, 0.0};
  for (std::size_t c = 0; c < v_.size(); ++c) {
    const double m = mass(size_[c]);
    p.x += m * v_[c].x;
    p.y += m * v_[c].y;
    p.z += m * v_[c].z;
  }
  return p;
}

double Gas::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t c = 0; c < v_.size(); ++c)
    e += 0.5 * mass(size_[c]) * (v_[c].x * v_[c].x + v_[c].y * v_[c].y + v_[c].z * v_[c].z);
  return e;
}

bool Gas::bounds_hold() const {
  for (std::size_t c = 0; c < v_.size(); ++c) {
    const double speed2 = v_[c].x * v_[c].x + v_[c].y * v_[c].y + v_[c].z * v_[c].z;
    const double w = max_speed_[size_[c]];
    if (speed2 > w * w) return false;
  }
  return true;
}

Measurement Gas::measure() const {
  Measurement m;
  const Vec3 p = momentum();
  const double total_mass = model_.monomer_mass * static_cast<double>(initial_monomers_);
  const Vec3 u{p.x / total_mass, p.y / total_mass, p.z / total_mass};  // mean flow (zero to round-off)
  std::size_t largest = 1;
  for (std::size_t k = 1; k <= capacity_; ++k)
    if (!members_[k].empty()) largest = k;
  m.number.assign(largest, 0.0);
  m.energy.assign(largest, 0.0);
  for (std::size_t c = 0; c < v_.size(); ++c) {
    const Vec3 d{v_[c].x - u.x, v_[c].y - u.y, v_[c].z - u.z};
    const std::size_t k = size_[c];
    m.energy[k - 1] += 0.5 * mass(size_[c]) * (d.x * d.x + d.y * d.y + d.z * d.z);
  }
  for (std::size_t k = 1; k <= largest; ++k) {
    m.number[k - 1] = static_cast<double>(members_[k].size());
    m.kinetic_energy += m.energy[k - 1];
  }
  m.clusters = static_cast<double>(v_.size());
  return m;
}

Gas::State Gas::state() const {
  State s;
  s.velocity.reserve(3 * v_.size());
  for (const auto& v : v_) s.velocity.insert(s.velocity.end(), {v.x, v.y, v.z});
  s.size.assign(size_.begin(), size_.end());
  s.slot.assign(slot_.begin(), slot_.end());
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
  const std::size_t n = s.size.size();
  if (s.velocity.size() != 3 * n || s.slot.size() != n || n > initial_monomers_ ||
      s.max_speed.size() != s.capacity || s.capacity > std::max<std::size_t>(initial_monomers_, 16))
    throw std::runtime_error("agg_frag checkpoint: inconsistent cluster arrays");
  // The tables at the saved capacity: the trees' sums then come out bit for bit as they were.
  members_.clear();
  max_speed_.clear();
  diameter_.clear();
  capacity_ = 0;
  grow_to(s.capacity);
  v_.resize(n);
  size_.resize(n);
  slot_.resize(n);
  std::size_t monomers = 0;
  for (std::size_t c = 0; c < n; ++c) {
    v_[c] = {s.velocity[3 * c], s.velocity[3 * c + 1], s.velocity[3 * c + 2]};
    size_[c] = static_cast<std::uint32_t>(s.size[c]);
    slot_[c] = static_cast<std::uint32_t>(s.slot[c]);
    if (size_[c] < 1 || size_[c] > capacity_) throw std::runtime_error("agg_frag checkpoint: cluster size out of range");
    monomers += size_[c];
  }
  if (monomers != initial_monomers_) throw std::runtime_error("agg_frag checkpoint: monomer count differs from the input");
  for (std::size_t c = 0; c < n; ++c) {  // the member lists in their saved order
    auto& list = members_[size_[c]];
    if (list.size() <= slot_[c]) list.resize(slot_[c] + 1, UINT32_MAX);
    list[slot_[c]] = static_cast<std::uint32_t>(c);
  }
  for (const auto& list : members_)
    for (auto c : list)
      if (c == UINT32_MAX) throw std::runtime_error("agg_frag checkpoint: member lists have holes");
  for (std::size_t k = 1; k <= capacity_; ++k) max_speed_[k] = s.max_speed[k - 1];
  rebuild_sampler();
  time_ = s.time;
  credit_ = s.credit;
  next_step_time_ = s.next_step_time;
  largest_reached_ = s.largest_reached;
  counters_ = s.counters;
  gen_.set_state(s.generator);
  touched_.clear();
}

}  // namespace gdsmc::agg_frag
