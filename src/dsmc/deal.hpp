/**
 * \file deal.hpp
 * \brief The remix of cache blocks done in place: n particles dealt round k blocks like cards from a starting point.
 *
 * **The permutation** (collide.hpp, "Blocks"). Old index (offset + i) mod n goes to block i mod k,
 * slot i div k, where block j starts at first(j) = j q + min(j, r), q = n div k, r = n mod k (the
 * first r blocks hold q + 1 particles, the others q). Written out of place this is
 *   out[first(i mod k) + i div k] = in[(offset + i) mod n],   i = 0 .. n - 1,
 * which is what the collider did until issue 11, with a second copy of the particle arrays (24 bytes a
 * particle for the velocities, 32 more for tracked displacements). deal_in_place() computes the same
 * permutation in place: the same bytes end in the same places (only copies, no arithmetic on them).
 *
 * **Four stages.** Let y = in rotated by offset (y[i] = in[(offset + i) mod n]) and view y as q rows of
 * k (row a, column j holding y[a k + j]) and a last partial row of r: the dealing puts column j, top to
 * bottom, into block j. With segments of seg = min(64, q) rows, rows = q div seg row groups ("tiles"
 * of seg k elements) and slots = rows k segments, the target is a grid of slots places: place
 * t = j rows + g is [first(j) + g seg, + seg), the g-th run of seg elements of block j; what is not on
 * the grid (the last q - rows seg rows of each block and the partial row, m = n - slots seg elements in
 * all) is handled apart.
 *  1. std::rotate by offset turns the array into y.
 *  2. The m elements after the last whole tile are copied aside. Then the tiles, the last first, are
 *     transposed through a buffer, and column j of tile g (a segment of seg elements, s = g k + j) is
 *     written to grid place s. Place s starts at or after s seg, where the segment was (the grid only
 *     adds gaps), so a tile's segments land on the tile itself or on later tiles, already read: nothing
 *     unread is overwritten.
 *  3. The segments are permuted on the grid: place t = j rows + g takes the segment at place g k + j,
 *     the transposition of a rows x k matrix of segments, by following its cycles with one segment in
 *     a buffer. The cycles depend on (rows, k) only; their least places are found once (Workspace).
 *  4. The m elements aside go to first(j) + a, for their row a and column j.
 * Afterwards place j rows + g holds rows g seg .. g seg + seg - 1 of column j, and the rows past the
 * grid follow it: every element is where the dealing puts it. Stages 2 and 3 move runs of seg elements
 * (1.5 KB of velocities), so they stream through memory; each of the four stages is one pass
 * (stage 4 a small one), against the one pass of the out-of-place dealing.
 *
 * **Threads.** Stage 2 splits the tiles into one run per thread; each thread first saves the first
 * ceil(m / (seg k)) tiles of its run, the only ones that the thread before it can overwrite (a tile's
 * segments land less than m past the tile), and then proceeds as above. Stage 3 deals out whole cycles,
 * which are disjoint. Stages 1 and 4 run on one thread. Whichever thread moves an element, it ends in
 * the same place: the result does not depend on the thread count.
 *
 * **Memory** (Workspace): the m < (seg + 1) k elements aside, a tile of seg k elements per thread (and,
 * on several threads, its saved tiles, at most 2 tiles more) and 4 bytes per cycle (at most slots/2
 * cycles, slots = n div seg): about (2 seg + 1) k elements and 2 n/seg bytes, against the n elements
 * of a second array (finding the cycles once takes slots bits more for a moment). With blocks of 32768
 * particles this is below 0.15 bytes a particle on one thread (0.5 on two).
 *
 * Checked by tests/collide_test.cpp (Collide.DealInPlaceIsTheDealing: against the out-of-place
 * formula above for one species and mixtures, with and without displacements, k not dividing n, on
 * 1 to 3 threads).
 */
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gdsmc::deal {

/// Rows of a segment: the unit that stages 2 and 3 move (header).
inline constexpr std::size_t segment_rows = 64;

/// The scratch memory of deal_in_place(), kept between calls (header, "Memory").
struct Workspace {
  std::vector<unsigned char> buffer;  ///< the elements set aside; each thread's tile, saved tiles and segment
  /// The cycles of stage 3 for one shape (rows x k segments): the least place of each cycle longer
  /// than one, longest cycles first. They depend on the shape only, so they are found once.
  struct Cycles {
    std::size_t rows = 0;                ///< row groups (segments per block)
    std::size_t k = 0;                   ///< blocks
    std::vector<std::uint32_t> leaders;  ///< the least place of each cycle
  };
  std::vector<Cycles> cycles;  ///< one entry per shape met (a mixture: one per species at most)

  /// The parts of `buffer` for n elements in k blocks on `threads` threads (header, "Memory").
  struct Layout {
    std::size_t q, r, seg, rows, slots, tile, whole, aside, saved, per_thread;
  };
  static Layout layout(std::size_t n, std::size_t k, int threads) {
    Layout l{};
    l.q = n / k;
    l.r = n % k;
    l.seg = std::min(segment_rows, l.q);
    if (l.seg == 0) return l;
    l.rows = l.q / l.seg;
    l.slots = l.rows * k;
    l.tile = l.seg * k;
    l.whole = l.slots * l.seg;
    l.aside = n - l.whole;
    l.saved = (l.aside + l.tile - 1) / l.tile;  // tiles a thread's writes may reach past its own
    l.per_thread = l.tile * (1 + (threads > 1 ? l.saved : 0));
    return l;
  }
  /// Threads that stage 2 uses: each takes at least saved + 1 tiles.
  static int stage2_threads(const Layout& l, int threads) {
    return static_cast<int>(std::max<std::size_t>(1, std::min<std::size_t>(threads, l.rows / (l.saved + 1))));
  }
  /// Grows the memory to what deal_in_place() needs for n elements of `element_size` bytes in k
  /// blocks on `threads` threads.
  void reserve(std::size_t n, std::size_t k, std::size_t element_size, int threads = 1) {
    if (k < 2) return;
    const Layout l = layout(n, k, threads);
    if (l.seg == 0) return;
    const std::size_t bytes = (l.aside + static_cast<std::size_t>(std::max(1, threads)) * l.per_thread) * element_size;
    if (buffer.size() < bytes) buffer.resize(bytes);
    leaders(l.rows, k);
  }
  /// The cycles of the rows x k transposition of stage 3 (found on the first call for a shape).
  const std::vector<std::uint32_t>& leaders(std::size_t rows, std::size_t k) {
    for (const Cycles& c : cycles)
      if (c.rows == rows && c.k == k) return c.leaders;
    Cycles c{rows, k, {}};
    const std::size_t slots = rows * k;
    std::vector<std::uint64_t> done((slots + 63) / 64, 0);
    std::vector<std::pair<std::size_t, std::uint32_t>> found;  // (length, least place)
    for (std::size_t start = 0; start < slots; ++start) {
      if (done[start >> 6] >> (start & 63) & 1) continue;
      std::size_t length = 0;
      std::size_t t = start;
      do {
        done[t >> 6] |= std::uint64_t{1} << (t & 63);
        ++length;
        t = source(t, rows, k);
      } while (t != start);
      if (length > 1) found.emplace_back(length, static_cast<std::uint32_t>(start));
    }
    std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& f : found) c.leaders.push_back(f.second);
    cycles.push_back(std::move(c));
    return cycles.back().leaders;
  }
  /// Stage 3's permutation: place t = j rows + g takes the segment at place g k + j.
  static std::size_t source(std::size_t t, std::size_t rows, std::size_t k) {
    const std::size_t j = t / rows;
    return (t - j * rows) * k + j;
  }
  /// The memory held, in bytes.
  std::size_t bytes() const {
    std::size_t b = buffer.capacity();
    for (const Cycles& c : cycles) b += sizeof(Cycles) + c.leaders.capacity() * sizeof(std::uint32_t);
    return b;
  }
};

/// Deals `data[0 .. n)` round `k` blocks from `offset` (< n), in place: afterwards
/// data[j q + min(j, r) + i div k] holds what data[(offset + i) mod n] held, j = i mod k, q = n div k,
/// r = n mod k (header, "The permutation"). `T` is trivially copyable; k >= 1. Stages 2 and 3 run on
/// up to `threads` OpenMP threads; the result is the same for any number.
template <class T>
void deal_in_place(T* data, std::size_t n, std::size_t k, std::size_t offset, Workspace& workspace, int threads = 1) {
  if (n < 2 || k < 1) return;
  if (offset != 0) std::rotate(data, data + offset, data + n);  // stage 1: y
  if (k == 1) return;
#ifdef _OPENMP
  threads = std::max(1, threads);
#else
  threads = 1;
#endif
  const Workspace::Layout l = Workspace::layout(n, k, threads);
  if (l.seg == 0) return;  // n < k: every block holds at most one element, and y is the dealing
  workspace.reserve(n, k, sizeof(T), threads);
  const std::vector<std::uint32_t>& leaders = workspace.leaders(l.rows, k);
  const std::size_t q = l.q, r = l.r, seg = l.seg, rows = l.rows, tile = l.tile, m = l.aside;
  T* const aside = reinterpret_cast<T*>(workspace.buffer.data());
  auto first = [q, r](std::size_t j) { return j * q + std::min(j, r); };
  auto place = [&](std::size_t t) {  // grid place t: block t div rows, row group t mod rows
    const std::size_t j = t / rows;
    return data + first(j) + (t - j * rows) * seg;
  };
  auto thread_buffer = [&](int p) { return aside + m + static_cast<std::size_t>(p) * l.per_thread; };
  // Stage 2: the elements after the last whole tile aside; the tiles transposed onto the grid. On
  // several threads each takes a run of tiles, last first, having saved the first `saved` tiles of
  // its run, which the thread before it may overwrite (its writes reach at most m past its run).
  std::memcpy(static_cast<void*>(aside), data + l.whole, m * sizeof(T));
  const int threads2 = Workspace::stage2_threads(l, threads);
#pragma omp parallel num_threads(threads2) if (threads2 > 1)
  {
    int p = 0;
#ifdef _OPENMP
    p = omp_get_thread_num();
#endif
    const std::size_t g_begin = rows * static_cast<std::size_t>(p) / static_cast<std::size_t>(threads2);
    const std::size_t g_end = rows * static_cast<std::size_t>(p + 1) / static_cast<std::size_t>(threads2);
    T* const buffer = thread_buffer(p);
    T* const saved = buffer + tile;
    const std::size_t n_saved = threads2 > 1 && p > 0 ? std::min(l.saved, g_end - g_begin) : 0;
    std::memcpy(static_cast<void*>(saved), data + g_begin * tile, n_saved * tile * sizeof(T));
#pragma omp barrier
    for (std::size_t g = g_end; g-- > g_begin;) {
      const T* const from = g < g_begin + n_saved ? saved + (g - g_begin) * tile : data + g * tile;
      for (std::size_t a = 0; a < seg; ++a)
        for (std::size_t j = 0; j < k; ++j) buffer[j * seg + a] = from[a * k + j];
      for (std::size_t j = 0; j < k; ++j)
        std::memcpy(static_cast<void*>(place(g * k + j)), buffer + j * seg, seg * sizeof(T));
    }
  }
  // Stage 3: place j rows + g takes the segment at place g k + j, cycle by cycle (cycles are
  // disjoint: any thread may follow any of them).
  const auto n_cycles = static_cast<std::ptrdiff_t>(leaders.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && n_cycles > 1)
  for (std::ptrdiff_t c = 0; c < n_cycles; ++c) {
    int p = 0;
#ifdef _OPENMP
    p = omp_get_thread_num();
#endif
    T* const buffer = thread_buffer(p);
    const std::size_t start = leaders[static_cast<std::size_t>(c)];
    std::memcpy(static_cast<void*>(buffer), place(start), seg * sizeof(T));
    for (std::size_t t = start;;) {
      const std::size_t from = Workspace::source(t, rows, k);
      if (from == start) {
        std::memcpy(static_cast<void*>(place(t)), buffer, seg * sizeof(T));
        break;
      }
      std::memcpy(static_cast<void*>(place(t)), place(from), seg * sizeof(T));
      t = from;
    }
  }
  // Stage 4: element whole + i of y is in row whole/k + i div k, column i mod k (whole is a multiple of k).
  for (std::size_t i = 0; i < m; ++i) data[first(i % k) + rows * seg + i / k] = aside[i];
}

}  // namespace gdsmc::deal
