/**
 * \file deal.hpp
 * \brief The remix of cache blocks done in place: n particles dealt round k blocks like cards from a starting point.
 *
 * **The permutation** (collide.hpp, "Blocks"). Old index (offset + i) mod n goes to block i mod k,
 * slot i div k, where block j starts at first(j) = j q + min(j, r), q = n div k, r = n mod k (the
 * first r blocks hold q + 1 particles, the others q). Written out of place this is
 *   out[first(i mod k) + i div k] = in[(offset + i) mod n],   i = 0 .. n - 1,
 * which needs a second copy of the particle arrays (24 bytes a particle for the velocities, 32 more for
 * tracked displacements). deal_in_place() computes the same permutation in place: the same bytes end in
 * the same places (only copies, no arithmetic on them). Its cost and memory, measured against the
 * out-of-place dealing it replaced: \ref perf_remix "docs/performance.md".
 *
 * **Four stages.** Let y be the array read from offset round (y[i] = in[(offset + i) mod n]) and view
 * y as q rows of k (row a, column j holding y[a k + j]) and a last partial row of r: the dealing puts
 * column j, top to bottom, into block j. With segments of seg rows (q div 128, at least 1 and at most
 * 64, so that a tile is at most n/128 elements), rows = q div seg row
 * groups ("tiles" of seg k elements) and slots = rows k segments, the target is a grid of slots
 * places: place t = j rows + g is [first(j) + g seg, + seg), the g-th run of seg elements of block j.
 * What is not on the grid (the last q - rows seg rows of each block and the partial row: the
 * m = n - slots seg elements of y after its last whole tile) is handled apart.
 *  1. The m elements of y after the last whole tile are copied aside.
 *  2. Tile by tile in the order of y, a tile is copied into a buffer, transposed, and its column j
 *     (segment s = g k + j of y, for tile g) is written to grid place (s + u) mod slots,
 *     u = min(offset div seg, slots) mod slots. Place s + u starts between seg before and 2 m after
 *     the position of segment s in y (the shift u takes the rotation by offset in whole segments, the
 *     grid's gaps add at most m, the wrap round the array end at most m more), so reading the next
 *     ceil(2 m / (seg k)) + 1 tiles ahead, and saving the last tile first (the first tile's segments may
 *     land on it), nothing is overwritten before it is read. No separate pass rotates the array.
 *  3. The segments are permuted on the grid: place t = j rows + g takes segment s = g k + j from place
 *     (s + u) mod slots, by following the cycles of that permutation with one segment in a buffer.
 *     Its cycles depend on (rows, k, u); they are found in each call by one pass over the slots places
 *     (index arithmetic and one bit a place, no particle data).
 *  4. The m elements aside go to first(j) + a, for their row a and column j.
 * Afterwards place j rows + g holds rows g seg .. g seg + seg - 1 of column j, and the rows past the
 * grid follow it: every element is where the dealing puts it. Stages 2 and 3 move runs of seg elements
 * (1.5 KB of velocities), so they stream through memory: two passes over the particles against the
 * one of the out-of-place dealing.
 *
 * **Threads.** Stage 2 splits the tiles into one run per thread; each thread first saves the first
 * ceil(2 m / (seg k)) + 1 tiles and the last tile of its run, the only ones that other runs' segments
 * can land on, and then proceeds as above within its run. Stage 3 deals out whole cycles, which are
 * disjoint; a cycle longer than slots / (4 threads) places is cut into pieces of at most that length,
 * whose first segments are saved before any piece moves (the piece before ends by taking it), so that
 * the long cycle a random shift usually leaves (\ref perf_remix "docs/performance.md") does not run on
 * one thread. Stages 1 and 4 (m elements) and the search
 * for the cycles run on one thread. Whichever
 * thread moves an element, it ends in the same place: the result does not depend on the thread count.
 *
 * **Memory** (Workspace): the m < (seg + 1) k elements aside; per thread, its saved tiles, its tiles
 * read ahead and one being transposed (at most 9 tiles of seg k elements); one bit and at most 2
 * bytes (the cycles' least places) per grid place; with threads, the saved first segments of at most
 * 8 threads pieces. Against the n elements of a second array (24 or 32
 * bytes a particle), this is below 0.7 bytes a particle for blocks of 32768 particles (seg k =
 * 64 n/32768), and 0.6 more for each further thread.
 *
 * Checked by tests/collide_test.cpp (Collide.DealInPlaceIsTheDealing: against the out-of-place
 * formula above for one species and mixtures, with and without displacements, k not dividing n, on
 * 1 to 3 threads).
 *
 * **Scattering** (scatter_draws, scatter_moves; collide.hpp, "Mixtures in blocks"): a species too rare to be
 * dealt in equal slices is put in a uniformly random order (Fisher-Yates) and cut into k slices of multinomial
 * counts, so that each element goes to a uniformly random block independently of the others (any two
 * share a block with probability 1/k). The draws and the transpositions are apart, so that the
 * transpositions of several species can run on threads while the draws stay in one stream. Checked by
 * Collide.ScatterPlacesEveryParticleUniformly (each element's block and every pair's sharing of a block
 * over 60000 scatterings) and Collide.ScatterInHalvesIsScatter (the one-pass Fisher-Yates).
 */
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gdsmc::deal {

/// Rows of a segment: the unit that stages 2 and 3 move (header, "Four stages").
inline constexpr std::size_t segment_rows = 64;

/// The scratch memory of deal_in_place(), kept between calls (header, "Memory").
struct Workspace {
  std::vector<unsigned char> buffer;  ///< the elements set aside, and each thread's tiles and segment
  std::vector<std::uint64_t> done;    ///< one bit per grid place while the cycles of stage 3 are found
  std::vector<std::uint32_t> leaders; ///< the least place of each cycle of stage 3 (not cut into pieces)
  /// A piece of a long cycle of stage 3: its first place, its places, and its cycle's first piece.
  struct Piece {
    std::uint32_t first;   ///< its first grid place
    std::uint32_t length;  ///< its places
    std::uint32_t cycle;   ///< the index (in `pieces`) of its cycle's first piece
  };
  std::vector<Piece> pieces;          ///< the pieces of the long cycles, cycle by cycle in cycle order

  /// The sizes of one call: n elements in k blocks on `threads` threads (header, "Four stages").
  struct Layout {
    std::size_t q;           ///< n div k
    std::size_t r;           ///< n mod k
    std::size_t seg;         ///< rows of a segment, q div 128 within [1, segment_rows]
    std::size_t rows;        ///< row groups (tiles), q div seg
    std::size_t slots;       ///< grid places, rows k
    std::size_t tile;        ///< elements of a tile, seg k
    std::size_t whole;       ///< elements in whole tiles, slots seg
    std::size_t aside;       ///< the other elements, n - whole
    std::size_t ahead;       ///< tiles read ahead: a tile's segments land less than 2 aside past it
    std::size_t per_thread;  ///< elements of buffer a thread uses: saved and read-ahead tiles, and one
  };
  /// The layout of a call (seg = 0 when n < k).
  static Layout layout(std::size_t n, std::size_t k) {
    Layout l{};
    l.q = n / k;
    l.r = n % k;
    if (l.q == 0) return l;  // seg = 0
    l.seg = std::clamp<std::size_t>(l.q / 128, 1, segment_rows);
    l.rows = l.q / l.seg;
    l.slots = l.rows * k;
    l.tile = l.seg * k;
    l.whole = l.slots * l.seg;
    l.aside = n - l.whole;
    l.ahead = 2 * l.aside / l.tile + 1;
    l.per_thread = l.tile * (2 * l.ahead + 3);
    return l;
  }
  /// Threads that stage 2 uses: each takes a run of at least ahead + 2 tiles.
  static int stage2_threads(const Layout& l, int threads) {
    return static_cast<int>(std::max<std::size_t>(1, std::min<std::size_t>(threads, l.rows / (l.ahead + 2))));
  }
  /// Grows the memory to what deal_in_place() needs for n elements of `element_size` bytes in k
  /// blocks on `threads` threads.
  void reserve(std::size_t n, std::size_t k, std::size_t element_size, int threads = 1) {
    if (k < 2) return;
    const Layout l = layout(n, k);
    if (l.seg == 0) return;
    const std::size_t used = static_cast<std::size_t>(std::max(1, threads));
    // With threads, at most 8 threads pieces of stage 3 (pieces of slots / (4 threads) places, and
    // each long cycle's last piece shorter), each with its first segment saved.
    const std::size_t n_pieces = used > 1 ? 8 * used : 0;
    const std::size_t bytes = (l.aside + used * l.per_thread + n_pieces * l.seg) * element_size;
    if (buffer.size() < bytes) buffer.resize(bytes);
    if (done.capacity() < (l.slots + 63) / 64) done.reserve((l.slots + 63) / 64);
    if (leaders.capacity() < l.slots / 2) leaders.reserve(l.slots / 2);
    if (pieces.capacity() < n_pieces) pieces.reserve(n_pieces);
  }
  /// The memory held, in bytes.
  std::size_t bytes() const {
    return buffer.capacity() + done.capacity() * sizeof(std::uint64_t) + leaders.capacity() * sizeof(std::uint32_t) +
           pieces.capacity() * sizeof(Piece);
  }
};

namespace detail {

/// One call of deal_in_place(): its sizes and the four stages (header, "Four stages").
template <class T>
class Dealer {
 public:
  Dealer(T* data, std::size_t n, std::size_t k, std::size_t offset, Workspace& workspace, int threads)
      : data_(data), n_(n), k_(k), offset_(offset), l_(Workspace::layout(n, k)), workspace_(workspace), threads_(threads),
        // The grid places are shifted by offset div seg, so that each segment lands near where it lies (at
        // most seg before it, less than 2 aside after it); an offset in the last aside elements needs no shift.
        shift_(std::min(offset / l_.seg, l_.slots) % l_.slots),
        aside_(reinterpret_cast<T*>(workspace.buffer.data())) {}

  /// Stage 1: the elements after the last whole tile of y aside.
  void set_aside() { read_y(aside_, l_.whole, l_.aside); }
  /// Stage 2: segment s of y (column s mod k of tile s div k) to grid place (s + shift) mod slots, near
  /// where it lies in y. Each thread takes a run of tiles in order, having saved the first `ahead` and
  /// the last tile of its run (the only ones other runs' segments can land on), and reads the next
  /// `ahead` tiles of its run before a tile's segments are written.
  void transpose_tiles() {
    const int threads2 = Workspace::stage2_threads(l_, threads_);
#pragma omp parallel num_threads(threads2) if (threads2 > 1)
    {
      int p = 0;
#ifdef _OPENMP
      p = omp_get_thread_num();
#endif
      transpose_run(l_.rows * static_cast<std::size_t>(p) / static_cast<std::size_t>(threads2),
                    l_.rows * static_cast<std::size_t>(p + 1) / static_cast<std::size_t>(threads2), p);
    }
  }
  /// Stage 3: place t = j rows + g takes segment s = g k + j, now at place (s + shift) mod slots, cycle
  /// by cycle (cycles are disjoint: any thread may follow any of them); long cycles in pieces.
  void follow_cycles() {
    find_cycles();
    move_cycles();
    move_pieces();
  }
  /// Stage 4: element whole + i of y is in row whole/k + i div k, column i mod k (whole is a multiple of k).
  void place_aside() {
    for (std::size_t i = 0; i < l_.aside; ++i) data_[first(i % k_) + l_.rows * l_.seg + i / k_] = aside_[i];
  }

 private:
  std::size_t first(std::size_t j) const { return j * l_.q + std::min(j, l_.r); }
  /// Grid place t: block t div rows, row group t mod rows.
  T* place(std::size_t t) const {
    const std::size_t j = t / l_.rows;
    return data_ + first(j) + (t - j * l_.rows) * l_.seg;
  }
  /// y[i .. i + count) into `to`, y[i] = data[(offset + i) mod n].
  void read_y(T* to, std::size_t i, std::size_t count) const {
    std::size_t at = offset_ + i;
    if (at >= n_) at -= n_;
    const std::size_t part = std::min(count, n_ - at);
    std::memcpy(static_cast<void*>(to), data_ + at, part * sizeof(T));
    std::memcpy(static_cast<void*>(to + part), data_, (count - part) * sizeof(T));
  }
  /// The place whose segment moves to place t in stage 3.
  std::size_t source(std::size_t t) const {
    const std::size_t j = t / l_.rows;
    const std::size_t from = (t - j * l_.rows) * k_ + j + shift_;
    return from >= l_.slots ? from - l_.slots : from;
  }
  /// Stage 2 on tiles [g_begin, g_end), thread p's.
  void transpose_run(std::size_t g_begin, std::size_t g_end, int p) {
    const std::size_t ahead = l_.ahead, tile = l_.tile, seg = l_.seg;
    T* const saved = aside_ + l_.aside + static_cast<std::size_t>(p) * l_.per_thread;  // ahead + 1 tiles
    T* const ring = saved + (ahead + 1) * tile;                                          // ahead + 1 tiles
    T* const columns = ring + (ahead + 1) * tile;                                        // one tile
    const std::size_t n_first = std::min(ahead, g_end - g_begin);
    const bool last_apart = g_end - 1 >= g_begin + n_first;
    auto kept = [&](std::size_t g) -> T* {  // the saved copy of tile g, or nullptr
      if (g < g_begin + n_first) return saved + (g - g_begin) * tile;
      if (last_apart && g == g_end - 1) return saved + ahead * tile;
      return nullptr;
    };
    for (std::size_t g = g_begin; g < g_begin + n_first; ++g) read_y(kept(g), g * tile, tile);
    if (last_apart) read_y(kept(g_end - 1), (g_end - 1) * tile, tile);
#pragma omp barrier
    for (std::size_t g = g_begin; g < std::min(g_begin + ahead, g_end); ++g)
      if (!kept(g)) read_y(ring + g % (ahead + 1) * tile, g * tile, tile);
    for (std::size_t g = g_begin; g < g_end; ++g) {
      const std::size_t next = g + ahead;
      if (next < g_end && !kept(next)) read_y(ring + next % (ahead + 1) * tile, next * tile, tile);
      const T* const from = kept(g) ? kept(g) : ring + g % (ahead + 1) * tile;
      for (std::size_t a = 0; a < seg; ++a)
        for (std::size_t j = 0; j < k_; ++j) columns[j * seg + a] = from[a * k_ + j];
      for (std::size_t j = 0; j < k_; ++j) {
        std::size_t t = g * k_ + j + shift_;
        if (t >= l_.slots) t -= l_.slots;
        std::memcpy(static_cast<void*>(place(t)), columns + j * seg, seg * sizeof(T));
      }
    }
  }
  /// The cycles of stage 3, by one pass of index arithmetic. With more than one thread a cycle longer
  /// than `piece` places (slots / (4 threads)) is cut into pieces of at most `piece`, so that one long
  /// cycle (a random shift often leaves one holding most places) does not run on one thread.
  void find_cycles() {
    const std::size_t slots = l_.slots;
    const std::size_t piece = threads_ > 1 ? (slots + 4 * static_cast<std::size_t>(threads_) - 1) /
                                                 (4 * static_cast<std::size_t>(threads_))
                                           : slots;
    workspace_.done.assign((slots + 63) / 64, 0);
    workspace_.leaders.clear();
    workspace_.pieces.clear();
    std::uint64_t* const done = workspace_.done.data();
    for (std::size_t start = 0; start < slots; ++start) {
      if (done[start >> 6] >> (start & 63) & 1) continue;
      std::size_t t = start, length = 0;
      do {
        done[t >> 6] |= std::uint64_t{1} << (t & 63);
        t = source(t);
        ++length;
      } while (t != start);
      if (length == 1) continue;
      if (length <= piece) {
        workspace_.leaders.push_back(static_cast<std::uint32_t>(start));
        continue;
      }
      // A long cycle: its pieces' first places and lengths, in the order of the cycle.
      const std::size_t first_piece = workspace_.pieces.size();
      for (std::size_t at = 0; at < length; at += piece) {
        workspace_.pieces.push_back({static_cast<std::uint32_t>(t), static_cast<std::uint32_t>(std::min(piece, length - at)),
                                     static_cast<std::uint32_t>(first_piece)});
        for (std::size_t step = 0; step < piece && step + at < length; ++step) t = source(t);
      }
    }
  }
  /// The short cycles, each whole on one thread.
  void move_cycles() {
    const std::size_t seg = l_.seg;
    const std::uint32_t* const leaders = workspace_.leaders.data();
    const auto n_cycles = static_cast<std::ptrdiff_t>(workspace_.leaders.size());
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1) if (threads_ > 1 && n_cycles > 1)
    for (std::ptrdiff_t c = 0; c < n_cycles; ++c) {
      int p = 0;
#ifdef _OPENMP
      p = omp_get_thread_num();
#endif
      T* const buffer = aside_ + l_.aside + static_cast<std::size_t>(p) * l_.per_thread;
      const std::size_t start = leaders[c];
      std::memcpy(static_cast<void*>(buffer), place(start), seg * sizeof(T));
      for (std::size_t t = start;;) {
        const std::size_t from = source(t);
        if (from == start) {
          std::memcpy(static_cast<void*>(place(t)), buffer, seg * sizeof(T));
          break;
        }
        std::memcpy(static_cast<void*>(place(t)), place(from), seg * sizeof(T));
        t = from;
      }
    }
  }
  /// The pieces of the long cycles: each first place is saved (the piece before it in the cycle ends by
  /// taking it), then every piece moves its segments along the cycle, its last place taking the saved
  /// first segment of the next piece (of the first piece, for the cycle's last).
  void move_pieces() {
    const std::size_t seg = l_.seg;
    const auto n_pieces = static_cast<std::ptrdiff_t>(workspace_.pieces.size());
    if (n_pieces == 0) return;
    T* const saved = aside_ + l_.aside + static_cast<std::size_t>(threads_) * l_.per_thread;
    const Workspace::Piece* const pieces = workspace_.pieces.data();
#pragma omp parallel for num_threads(threads_) schedule(static) if (threads_ > 1)
    for (std::ptrdiff_t c = 0; c < n_pieces; ++c)
      std::memcpy(static_cast<void*>(saved + static_cast<std::size_t>(c) * seg), place(pieces[c].first), seg * sizeof(T));
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1) if (threads_ > 1)
    for (std::ptrdiff_t c = 0; c < n_pieces; ++c) {
      const Workspace::Piece& here = pieces[c];
      const bool last = c + 1 == n_pieces || pieces[c + 1].cycle != here.cycle;
      const std::size_t next = last ? here.cycle : static_cast<std::size_t>(c + 1);
      std::size_t t = here.first;
      for (std::size_t step = 1; step < here.length; ++step) {
        const std::size_t from = source(t);
        std::memcpy(static_cast<void*>(place(t)), place(from), seg * sizeof(T));
        t = from;
      }
      std::memcpy(static_cast<void*>(place(t)), saved + next * seg, seg * sizeof(T));
    }
  }

  T* data_;
  std::size_t n_, k_, offset_;
  Workspace::Layout l_;
  Workspace& workspace_;
  int threads_;
  std::size_t shift_;
  T* aside_;
};

}  // namespace detail

/// Deals `data[0 .. n)` round `k` blocks from `offset` (< n), in place: afterwards
/// data[j q + min(j, r) + i div k] holds what data[(offset + i) mod n] held, j = i mod k, q = n div k,
/// r = n mod k (header, "The permutation"). `T` is trivially copyable; k >= 1. Stages 2 and 3 run on
/// up to `threads` OpenMP threads; the result is the same for any number.
template <class T>
void deal_in_place(T* data, std::size_t n, std::size_t k, std::size_t offset, Workspace& workspace, int threads = 1) {
  if (n < 2 || k < 1) return;
  const Workspace::Layout l = Workspace::layout(n, k);
  if (k == 1 || l.seg == 0) {  // y itself is the dealing (one block, or at most one element a block)
    if (offset != 0) std::rotate(data, data + offset, data + n);
    return;
  }
#ifdef _OPENMP
  threads = std::max(1, threads);
#else
  threads = 1;
#endif
  workspace.reserve(n, k, sizeof(T), threads);  // (before the Dealer takes the buffer's address)
  detail::Dealer<T> dealer(data, n, k, offset, workspace, threads);
  dealer.set_aside();
  dealer.transpose_tiles();
  dealer.follow_cycles();
  dealer.place_aside();
}

/// The draws of scattering n elements over k blocks (header, "Scattering"): the partner of Fisher-Yates
/// transposition i, i = n ... 2, uniform below i, to partners[n - i] (n - 1 of them; n < 2^32), then
/// counts[j stride], j < k, the elements block j takes (each element's block uniform, independently).
/// `gen.below(m)` is uniform on [0, m).
template <class Gen>
void scatter_draws(Gen& gen, std::size_t n, std::size_t k, std::size_t* counts, std::size_t stride,
                   std::uint32_t* partners) {
  if (n > std::size_t{UINT32_MAX}) throw std::length_error("deal::scatter_draws: 2^32 elements or more");
  for (std::size_t i = n; i > 1; --i) partners[n - i] = static_cast<std::uint32_t>(gen.below(i));
  for (std::size_t j = 0; j < k; ++j) counts[j * stride] = 0;
  for (std::size_t i = 0; i < n; ++i) ++counts[gen.below(k) * stride];
}
/// The transpositions of scatter_draws' `partners` for n elements: swap(i - 1, partners[n - i]) for i = n ... 2,
/// `swap(i, q)` swapping elements i and q of every array that holds them.
template <class Swap>
void scatter_moves(std::size_t n, const std::uint32_t* partners, Swap&& swap) {
  for (std::size_t i = n; i > 1; --i) swap(i - 1, static_cast<std::size_t>(partners[n - i]));
}

}  // namespace gdsmc::deal
