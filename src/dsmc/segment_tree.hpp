/**
 * \file segment_tree.hpp
 * \brief Segment trees for choosing the species pair of a candidate collision in O(log M) when there
 *        are M (up to thousands of) species: the data structure of the low-rank scheme of Bodrova and Osinsky 2024, \ref sch_lowrank "docs/schemes.md".
 *
 * **What it is for** (Bodrova and Osinsky 2024, sec. II B, eqs 12-14; \ref cm_pair_rate "docs/collision-model.md", \ref sch_lowrank_decomposition "docs/schemes.md"). In the continuous-time
 * scheme a candidate is an ordered species pair (i, k) drawn with probability C_ik / R, then a
 * particle of each species, accepted with the ratio of the true rate to the majorant. Drawing (i, k)
 * from an M x M table costs O(M^2) per update; but the majorant is a sum of a few separable terms,
 *   C_ik = sum_{r=1..Rank} u_i^(r) v_k^(r),   R = sum_{i,k} C_ik = sum_r (sum_i u_i^(r)) (sum_k v_k^(r)),
 * and a pair is drawn exactly by picking the term r with probability
 * (sum_i u_i^(r))(sum_k v_k^(r)) / R, then i with probability u_i^(r) / sum_i u_i^(r) and,
 * independently, k with probability v_k^(r) / sum_k v_k^(r) (Bodrova and Osinsky 2024, text after eq. (14), \ref sch_segment_trees "docs/schemes.md"). One
 * SumTree per vector u^(r) and v^(r) keeps those sums and samples from them in O(log M); when the
 * count N_i or the largest speed of species i changes, its row and column are reset in
 * O(Rank log M).
 *
 * **The hard-sphere decomposition** (hard_sphere_factors). Convention of \ref cm_pair_rate "docs/collision-model.md" as used by
 * collide.hpp: one unordered pair collides at pi sigma_ik^2 |g| / V (chi = 1; see below). With
 * w_i = max_j |v_i^j| the largest speed in species i, |g| <= w_i + w_k, so the unordered particle
 * pair {a in i, b in k} gets candidates at pi sigma_ik^2 (w_i + w_k) / V. Split it evenly over the
 * two ordered pairs (a, b), (b, a) and sum over ordered particle pairs (the self pairs a = b of
 * i = k included, and rejected when drawn): by the symmetry of that sum,
 *   R = sum_{i,k} N_i N_k pi sigma_ik^2 (w_i + w_k) / (2V) = sum_{i,k} A_ik,
 *   A_ik = pi sigma_ik^2 w_i N_i N_k / V                                      (\ref sch_lowrank_decomposition "docs/schemes.md", Bodrova and Osinsky 2024, eq. (12))
 * so the (asymmetric) A is the C to sample: the unordered species pair {i, k} is drawn with
 * probability (A_ik + A_ki) / R, the candidate rate of the pair {a, b} is pi sigma_ik^2 (w_i + w_k) / V,
 * and accepting with |g| / (w_i + w_k) leaves the collision rate pi sigma_ik^2 |g| / V. With
 * sigma_ik^2 = (sigma_i^2 + 2 sigma_i sigma_k + sigma_k^2) / 4 (Bodrova and Osinsky 2024, eq. (13), \ref sch_lowrank_decomposition "docs/schemes.md"), A has rank 3:
 *   u_i = (pi w_i N_i / (4V)) (sigma_i^2, 2 sigma_i, 1),   v_k = N_k (1, sigma_k, sigma_k^2)  (eq 14, \ref sch_lowrank_decomposition "docs/schemes.md").
 * With the other convention of \ref cm_pair_rate "docs/collision-model.md" (e uniform on the sphere, accept |g.e| / (w_i + w_k)) the
 * candidate rate doubles: R = 2 sum A_ik, same sampling. For the Enskog gas chi_ik is not separable:
 * multiply R by a bound chi_max >= chi_ik and accept with an extra factor chi_ik / chi_max.
 *
 * **Round-off.** Internal nodes are always recomputed from their two children (never updated by
 * adding a difference), so every stored sum is the exact pairwise sum of the current leaves up to
 * round-off of order log2(M) eps, whatever the number of updates. find() never returns an index of
 * zero weight, even when the target lands on a boundary or past the total through round-off.
 *
 * Units: those of the weights. Checked by tests/segment_tree_test.cpp.
 */
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gdsmc::segment_tree {

/// Sums of non-negative weights over [0, M) with point update and weighted sampling, O(log M) each.
///
/// Layout: a flat array of 2P doubles, P the smallest power of two >= M; node 1 is the root, node n
/// has children 2n and 2n + 1, leaf i is node P + i, and the padding leaves M..P-1 hold 0.
class SumTree {
 public:
  /// M leaves, all of weight 0.
  explicit SumTree(std::size_t size = 0) { resize(size); }

  /// Replaces all weights (and the size, to weights.size()); O(M). Throws std::invalid_argument
  /// if a weight is negative or not finite (the tree is then left all zero).
  void assign(const std::vector<double>& weights) {
    if (weights.size() != size_) resize(weights.size());
    for (std::size_t i = 0; i < size_; ++i) {
      if (!valid(weights[i])) {
        std::fill(tree_.begin(), tree_.end(), 0.0);
        throw_invalid(i, weights[i]);
      }
      tree_[leaves_ + i] = weights[i];
    }
    std::fill(tree_.begin() + static_cast<std::ptrdiff_t>(leaves_ + size_), tree_.end(), 0.0);
    for (std::size_t n = leaves_ - 1; n >= 1; --n) tree_[n] = tree_[2 * n] + tree_[2 * n + 1];
  }

  /// Sets weight `index` and recomputes the log2(P) sums above it from their children.
  /// Throws std::out_of_range for index >= size(), std::invalid_argument for a negative or
  /// non-finite weight.
  [[gnu::always_inline]] void set(std::size_t index, double weight) {
    if (index >= size_) throw_out_of_range(index);
    if (!valid(weight)) throw_invalid(index, weight);
    std::size_t n = leaves_ + index;
    tree_[n] = weight;
    for (n >>= 1; n >= 1; n >>= 1) tree_[n] = tree_[2 * n] + tree_[2 * n + 1];
  }

  /// The weight of leaf `index`.
  double weight(std::size_t index) const { return tree_[leaves_ + index]; }
  /// Sum of all weights (the root).
  double total() const { return tree_[1]; }
  /// Number of leaves M.
  std::size_t size() const { return size_; }

  /// The index i with prefix(i) <= u < prefix(i + 1), prefix(i) the sum of weights 0..i-1, for u in
  /// [0, total()). Never returns an index of zero weight: u < 0 (or NaN) is read as 0, and u >= total()
  /// (a boundary, or round-off) gives the last index of positive weight. Throws std::domain_error if
  /// total() is not positive. O(log M), no allocation.
  [[gnu::always_inline]] std::size_t find(double u) const {
    if (!(tree_[1] > 0.0)) throw_all_zero();
    if (!(u >= 0.0)) u = 0.0;
    // Leaf 0 without the descent (agg_frag's monomers, its most frequent draw): every left sum on the
    // path to leaf 0 is a floating-point sum of non-negative terms that include w_0, so never below
    // w_0, and u < w_0 takes the descent left at every level: the same index as the loop below.
    if (u < tree_[leaves_]) return 0;
    std::size_t n = 1;
    // Invariant: tree_[n] > 0. Go left when u falls there or when the right subtree is empty; the
    // parent is the exact sum left + right, so if right == 0 then left == parent > 0. Going right
    // only when right > 0, the invariant holds down to the leaf.
    while (n < leaves_) {
      const std::size_t left = 2 * n;
      const double left_sum = tree_[left];
      if (u < left_sum || !(tree_[left + 1] > 0.0)) {
        n = left;
      } else {
        u -= left_sum;
        n = left + 1;
      }
    }
    return n - leaves_;
  }

 private:
  static bool valid(double w) { return w >= 0.0 && std::isfinite(w); }
  // (The throws out of line: set() and find() are inlined into the samplers' loops.)
  [[noreturn]] void throw_out_of_range(std::size_t index) const {
    throw std::out_of_range("segment_tree::SumTree::set: index " + std::to_string(index) + " >= size " +
                            std::to_string(size_));
  }
  [[noreturn]] static void throw_all_zero() {
    throw std::domain_error("segment_tree::SumTree::find: all weights are zero");
  }
  [[noreturn]] static void throw_invalid(std::size_t index, double w) {
    throw std::invalid_argument("segment_tree::SumTree: weight " + std::to_string(index) + " = " +
                                std::to_string(w) + " must be finite and >= 0");
  }
  void resize(std::size_t size) {
    size_ = size;
    leaves_ = 1;
    while (leaves_ < size_) leaves_ *= 2;
    tree_.assign(2 * leaves_, 0.0);
  }

  std::size_t size_ = 0;    ///< M
  std::size_t leaves_ = 1;  ///< P, a power of two >= max(M, 1)
  std::vector<double> tree_;
};

/// Walker's alias table (Vose's construction): k with probability w_k / sum w from one uniform, in
/// O(1) with two memory reads; built in O(n). Used for LowRankSampler's frozen columns and for the
/// species pairs of a mixture's block (collide.hpp, "Mixtures in blocks").
struct AliasTable {
  std::vector<double> threshold;   ///< probability of keeping cell k rather than its alias
  std::vector<std::size_t> alias;  ///< the other index of cell k
  std::vector<double> scaled;        ///< build()'s scratch: n w_k / sum w
  std::vector<std::uint32_t> small;  ///< build()'s scratch: the cells below 1 (a stack)
  std::vector<std::uint32_t> large;  ///< build()'s scratch: the cells at or above 1 (a stack)
  /// Builds the table of weights `w` (each finite and >= 0, fewer than 2^32); all zero leaves it empty of draws.
  void build(const std::vector<double>& w) {
    threshold.resize(w.size());
    alias.resize(w.size());
    if (!build_cells(w, [&](std::size_t k, double t, std::size_t a) { threshold[k] = t, alias[k] = a; }))
      threshold.assign(w.size(), 0.0), alias.assign(w.size(), 0);
  }
  /// Vose's construction of the table of `w` (as build()), each cell k handed to `cell(k, threshold_k,
  /// alias_k)` once, in the order the construction settles them, instead of being stored; false (and no
  /// cell) when every weight is zero. The blocks turn the cells into their own tables at each visit
  /// (collide.hpp, "Mixtures in blocks"): no intermediate table, nor its clearing. The weights from
  /// `used` on are zero (the blocks' tables are padded to 2^m cells): they are not read.
  template <class Cell>
  bool build_cells(const std::vector<double>& w, Cell&& cell, std::size_t used = SIZE_MAX) {
    const std::size_t n = w.size();
    used = std::min(used, n);
    double total = 0.0;
    for (std::size_t k = 0; k < used; ++k) total += w[k];  // (adding the zeros after would not change it)
    if (!(total > 0.0)) return false;
    scaled.resize(n);  // (the scratch arrays kept between builds: the blocks rebuild their tables often)
    small.resize(n), large.resize(n);
    std::size_t smalls = 0, larges = 0;  // the stacks' heights
    for (std::size_t k = 0; k < used; ++k) {
      scaled[k] = w[k] * static_cast<double>(n) / total;
      const bool below = scaled[k] < 1.0;  // (both written, one kept: no branch on the weights)
      small[smalls] = large[larges] = static_cast<std::uint32_t>(k);
      smalls += below, larges += !below;
    }
    for (std::size_t k = used; k < n; ++k) {  // (a zero weight: 0 n/total, below 1)
      scaled[k] = 0.0;
      small[smalls++] = static_cast<std::uint32_t>(k);
    }
    // Each small cell takes its alias from the top large one, l, whose level drops by what the cell
    // lacks; below 1 it becomes small itself. (l's level in a register: through memory each step waited
    // on the last one's store)
    if (smalls > 0 && larges > 0) {
      std::size_t l = large[larges - 1];
      double level = scaled[l];
      for (;;) {
        const std::size_t s = small[--smalls];
        const double kept = scaled[s];
        cell(s, kept, l);
        level -= 1.0 - kept;
        if (level < 1.0) {
          scaled[l] = level;
          --larges;
          small[smalls++] = static_cast<std::uint32_t>(l);
          if (larges == 0) break;
          l = large[larges - 1];
          level = scaled[l];
        } else if (smalls == 0) {
          scaled[l] = level;
          break;
        }
      }
    }
    // What is left is 1 up to round-off: keep it; a zero weight left over (round-off emptied
    // `large` first) points to a column of positive weight, so it is never drawn.
    std::size_t positive = 0;
    while (!(w[positive] > 0.0)) ++positive;
    for (std::size_t q = 0; q < larges; ++q) cell(large[q], 1.0, large[q]);
    for (std::size_t q = 0; q < smalls; ++q) {
      const std::size_t k = small[q];
      cell(k, w[k] > 0.0 ? 1.0 : 0.0, w[k] > 0.0 ? k : positive);
    }
    return true;
  }
  /// The index drawn by a uniform `u` in [0, 1).
  std::size_t sample(double u) const {
    const double x = u * static_cast<double>(threshold.size());
    const auto k = std::min(static_cast<std::size_t>(x), threshold.size() - 1);
    return x - static_cast<double>(k) < threshold[k] ? k : alias[k];
  }
};

/// The rank-`Rank` majorant matrix C_ik = sum_r u_i^(r) v_k^(r) over M species: its total
/// R = sum_{i,k} C_ik, the update of one species' row u_i or column v_k in O(Rank log M), and the
/// draw of a pair (i, k) with probability C_ik / R in O(Rank + log M).
template <std::size_t Rank>
class LowRankSampler {
  static_assert(Rank >= 1, "LowRankSampler needs at least one term");

 public:
  using Vector = std::array<double, Rank>;  ///< one row u_i or column v_k: its Rank terms

  /// M species, all rows and columns zero.
  explicit LowRankSampler(std::size_t size = 0) : size_(size) {
    for (auto& t : u_) t = SumTree(size);
    for (auto& t : v_) t = SumTree(size);
  }

  /// Replaces every row and column (rows[i] = u_i, columns[k] = v_k, equal lengths M); O(Rank M).
  void assign(const std::vector<Vector>& rows, const std::vector<Vector>& columns) {
    columns_frozen_ = false;
    if (rows.size() != columns.size())
      throw std::invalid_argument("segment_tree::LowRankSampler::assign: " +
                                  std::to_string(rows.size()) + " rows but " +
                                  std::to_string(columns.size()) + " columns");
    size_ = rows.size();
    std::vector<double> w(size_);
    for (std::size_t r = 0; r < Rank; ++r) {
      for (std::size_t i = 0; i < size_; ++i) w[i] = rows[i][r];
      u_[r].assign(w);
      for (std::size_t k = 0; k < size_; ++k) w[k] = columns[k][r];
      v_[r].assign(w);
    }
  }

  /// Sets every row u_i (rows.size() == size()) in O(Rank M), each tree summed once from its leaves:
  /// the same sums as set_row for each i (a node's sum is its children's, however they were set).
  void set_rows(const std::vector<Vector>& rows) {
    if (rows.size() != size_)
      throw std::invalid_argument("segment_tree::LowRankSampler::set_rows: " + std::to_string(rows.size()) +
                                  " rows for " + std::to_string(size_) + " species");
    std::vector<double> w(size_);
    for (std::size_t r = 0; r < Rank; ++r) {
      for (std::size_t i = 0; i < size_; ++i) w[i] = rows[i][r];
      u_[r].assign(w);
    }
  }
  /// Sets u_i^(r), r = 1..Rank, of species i (each finite and >= 0).
  void set_row(std::size_t i, const Vector& u_i) {
    for (std::size_t r = 0; r < Rank; ++r) u_[r].set(i, u_i[r]);
  }
  /// Sets v_k^(r), r = 1..Rank, of species k (each finite and >= 0).
  void set_column(std::size_t k, const Vector& v_k) {
    columns_frozen_ = false;
    for (std::size_t r = 0; r < Rank; ++r) v_[r].set(k, v_k[r]);
  }

  /// u_i^(r), r = 1..Rank.
  Vector row(std::size_t i) const {
    Vector out{};
    for (std::size_t r = 0; r < Rank; ++r) out[r] = u_[r].weight(i);
    return out;
  }
  /// v_k^(r), r = 1..Rank.
  Vector column(std::size_t k) const {
    Vector out{};
    for (std::size_t r = 0; r < Rank; ++r) out[r] = v_[r].weight(k);
    return out;
  }
  /// C_ik = sum_r u_i^(r) v_k^(r).
  double entry(std::size_t i, std::size_t k) const {
    double c = 0.0;
    for (std::size_t r = 0; r < Rank; ++r) c += u_[r].weight(i) * v_[r].weight(k);
    return c;
  }
  /// (sum_i u_i^(r)) (sum_k v_k^(r)): the share of term r in the total.
  double term_total(std::size_t r) const { return u_[r].total() * v_[r].total(); }
  /// R = sum_{i,k} C_ik = sum_r (sum_i u_i^(r)) (sum_k v_k^(r)), from the trees' roots; O(Rank).
  double total() const { return totals().sum; }
  /// Number of species M.
  std::size_t size() const { return size_; }

  /// Draws (i, k) with probability C_ik / R from two uniforms gen.uniform() in [0, 1): the first
  /// picks the term r and, rescaled to what is left of it within that term, the row i; the second
  /// picks the column k. Never returns i with u_i^(r) = 0 or k with v_k^(r) = 0 for the term used,
  /// so never a pair with C_ik = 0. Throws std::domain_error if R is not positive.
  template <class Gen>
  std::pair<std::size_t, std::size_t> sample(Gen& gen) const {
    return sample(gen, totals());
  }

  /// The term totals sum_i u_i^(r) sum_k v_k^(r) and R (what totals() returns).
  struct Totals {
    std::array<double, Rank> term{};  ///< the term totals
    double sum = 0.0;                 ///< R = total()
    std::size_t last_positive = Rank;  ///< the last term of positive total (Rank: none)
  };
  /// The term totals and R, as sample() and total() use them (total() is totals().sum): a caller that
  /// draws many pairs between updates computes them once and passes them to sample(gen, totals).
  Totals totals() const {
    Totals t;
    for (std::size_t r = 0; r < Rank; ++r) {
      t.term[r] = term_total(r);
      t.sum += t.term[r];
      if (t.term[r] > 0.0) t.last_positive = r;
    }
    return t;
  }

  /// sample(gen) with the totals of the current rows and columns given (totals() since the last update).
  template <class Gen>
  std::pair<std::size_t, std::size_t> sample(Gen& gen, const Totals& totals) const {
    const auto& term = totals.term;
    const double sum = totals.sum;
    const std::size_t last_positive = totals.last_positive;
    if (last_positive == Rank)
      throw std::domain_error("segment_tree::LowRankSampler::sample: total majorant is zero");
    double x = gen.uniform() * sum;  // in [0, R)
    std::size_t r = 0;
    while (r < last_positive && !(x < term[r])) {  // a term of zero weight is never picked
      x -= term[r];
      ++r;
    }
    // Conditionally on r, x / term[r] is uniform on [0, 1): reuse it for the row. Round-off that
    // leaves x at or past term[r] lands on the last positive leaf (SumTree::find).
    const std::size_t i = u_[r].find(x / v_[r].total());
    const std::size_t k = columns_frozen_ ? column_alias_[r].sample(gen.uniform())
                                          : v_[r].find(gen.uniform() * v_[r].total());
    return {i, k};
  }

  /// Declares the columns settled: sample() then draws k from Walker alias tables, O(1) with two
  /// memory reads instead of a tree descent (with thousands of species the descent's cache misses
  /// dominate a candidate's cost). Any later set_column()/assign() returns to the trees until
  /// freeze_columns() is called again.
  void freeze_columns() {
    for (std::size_t r = 0; r < Rank; ++r) {
      std::vector<double> w(size_);
      for (std::size_t k = 0; k < size_; ++k) w[k] = v_[r].weight(k);
      column_alias_[r].build(w);
    }
    columns_frozen_ = true;
  }

 private:
  std::size_t size_ = 0;
  std::array<SumTree, Rank> u_;  ///< u^(r), one tree per term
  std::array<SumTree, Rank> v_;  ///< v^(r)
  std::array<AliasTable, Rank> column_alias_;
  bool columns_frozen_ = false;
};

/// Row u_i and column v_k of species i of the rank-3 hard-sphere majorant A_ik of Bodrova and Osinsky 2024, eqs. (12)-(14), \ref sch_lowrank_decomposition "docs/schemes.md"
/// (\ref cm_pair_rate "docs/collision-model.md", \ref sch_lowrank "docs/schemes.md"; derivation in the file comment):
///   A_ik = pi sigma_ik^2 w_i N_i N_k / V = sum_r u_i^(r) v_k^(r),
///   u_i = (pi w_i N_i / (4V)) (sigma_i^2, 2 sigma_i, 1),   v_i = N_i (1, sigma_i, sigma_i^2),
/// with N_i the count, sigma_i the diameter, w_i = max_j |v_i^j| and V the volume. With the
/// convention of collide.hpp (accept with |g| / (w_i + w_k)) the candidate rate is R = sum A_ik.
struct HardSphereFactors {
  std::array<double, 3> row;     ///< u_i
  std::array<double, 3> column;  ///< v_i
};
/// The HardSphereFactors of a species with `count` particles, `diameter`, bound `max_speed` = w_i,
/// in the simulated volume `volume`.
inline HardSphereFactors hard_sphere_factors(double count, double diameter, double max_speed,
                                             double volume) {
  const double a = std::numbers::pi * max_speed * count / (4.0 * volume);
  return {{a * diameter * diameter, a * 2.0 * diameter, a},
          {count, count * diameter, count * diameter * diameter}};
}

}  // namespace gdsmc::segment_tree
