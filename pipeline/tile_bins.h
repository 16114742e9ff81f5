// Binning: the screen's tile grid and a chunk's primitives binned to tiles in draw order (the unit the
// back end hands from setup to the tile rasterizers). Storage is reused from chunk to chunk.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "pipeline/screen_primitive.h"
#include "pipeline/statistics.h"

namespace tessera {

// Screen tiles: the unit of parallel rasterization.
struct TileGrid {
  int tile_size = 64;
  int columns = 0, rows = 0;
  // tile_of(p) = p / tile_size by a 32-bit multiply and a shift (setup bins every primitive, eight at a
  // time in SIMD lanes where it can; a division is slow, and AVX2 has no 64-bit lane multiply): with
  // shift = 14 + ceil(log2 tile_size) and reciprocal = floor(2^shift / tile_size) + 1, p * reciprocal / 2^shift
  // exceeds p / tile_size by less than p / 2^shift < 1 / tile_size, the gap to the next integer, for every
  // pixel p < 2^14 (kMaxRenderTargetSize); and p * reciprocal < 2^14 * (2^15 + 1) < 2^31.
  std::uint32_t reciprocal = (1u << 20) / 64 + 1;
  int shift = 20;
  void set_tile_size(int size) {
    tile_size = size;
    shift = 14;
    while ((1 << (shift - 14)) < size) ++shift;
    reciprocal = (1u << shift) / std::uint32_t(size) + 1;
  }
  int count() const { return columns * rows; }
  int tile_of(std::int32_t pixel) const { return int((std::uint32_t(pixel) * reciprocal) >> shift); }
};

// One chunk of the draw's primitives, in draw order, binned to tiles. Setup appends (tile, primitive)
// pairs; finish_bins() sorts them by tile with a stable counting sort, so each tile's list keeps draw
// order. Storage is proportional to the chunk's primitives (not to tiles x capacity), and is reused.
//
// Each buffer has cache lines of its own (alignas): threads fill neighbouring slots at the same time,
// and setup updates the counters and vector ends here per primitive; sharing a line with the next
// slot made setup run at half speed whenever two threads filled neighbours.
template <std::size_t N>
struct alignas(128) ChunkBuffer {
  // primitives[0, primitive_count) are this chunk's; the rest is storage kept from earlier chunks
  // (append_primitive() hands out slots without clearing them: setup writes every field it uses).
  std::vector<ScreenPrimitive<N>> primitives;
  std::size_t primitive_count = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> entries;  // (tile, primitive) in draw order
  std::vector<std::uint32_t> tile_start;                         // per tile: first entry in `binned`, plus an end
  std::vector<std::uint32_t> binned;                             // primitive indices grouped by tile
  std::vector<std::uint32_t> touched;                            // the tiles with a primitive, ascending (finish_bins)
  PipelineStatistics statistics;
  StageTimes times;
  std::uint64_t patches_back_culled = 0;  // patches skipped by the back-patch test (patch_orientation.h)

  void reset(int tile_count) {
    primitive_count = 0;
    entries.clear();
    binned.clear();
    touched.clear();
    tile_start.assign(std::size_t(tile_count) + 1, 0);
    statistics = {};
    times = {};
    patches_back_culled = 0;
  }
  void finish_bins() {
    const std::size_t tiles = tile_start.size() - 1;
    std::fill(tile_start.begin(), tile_start.end(), 0);
    // Both passes go run by run: setup appends entries in draw order, and consecutive primitives
    // mostly lie in one tile. A run's count and cursor stay in a register; incremented per entry in
    // memory, the tile's counter was one chain of stores and reloads (these two loops were 4 % of a
    // one-thread torus frame).
    const std::size_t n = entries.size();
    const auto run_end = [&](std::size_t i) {
      const std::uint32_t t = entries[i].first;
      std::size_t j = i + 1;
      while (j < n && entries[j].first == t) ++j;
      return j;
    };
    for (std::size_t i = 0; i < n;) {
      const std::size_t j = run_end(i);
      tile_start[entries[i].first + 1] += std::uint32_t(j - i);
      i = j;
    }
    for (std::size_t t = 0; t < tiles; ++t) tile_start[t + 1] += tile_start[t];
    binned.resize(n);
    // Fill using a running cursor per tile; tile_start is restored afterwards.
    for (std::size_t i = 0; i < n;) {
      const std::size_t j = run_end(i);
      std::uint32_t& cursor = tile_start[entries[i].first];
      std::uint32_t at = cursor;
      for (std::size_t k = i; k < j; ++k) binned[at++] = entries[k].second;
      cursor = at;
      i = j;
    }
    for (std::size_t t = tiles; t > 0; --t) tile_start[t] = tile_start[t - 1];
    tile_start[0] = 0;
    touched.clear();
    for (std::size_t t = 0; t < tiles; ++t)
      if (tile_start[t + 1] != tile_start[t]) touched.push_back(std::uint32_t(t));
  }
  // The next primitive's slot, holding whatever an earlier chunk left there.
  [[gnu::always_inline]] ScreenPrimitive<N>& append_primitive() {
    if (primitive_count == primitives.size()) primitives.resize(std::max<std::size_t>(16, 2 * primitives.size()));
    return primitives[primitive_count++];
  }
  std::span<const std::uint32_t> bin(int tile) const {
    return {binned.data() + tile_start[std::size_t(tile)], binned.data() + tile_start[std::size_t(tile) + 1]};
  }
  std::size_t capacity_bytes() const {
    return primitives.capacity() * sizeof(ScreenPrimitive<N>) + entries.capacity() * sizeof(entries[0]) +
           (tile_start.capacity() + binned.capacity() + touched.capacity()) * sizeof(std::uint32_t);
  }
};

namespace detail {

// Enters the chunk's primitive `index` in the bins of the tiles its box touches.
// Inlined into setup: it runs for every primitive, and nearly every one lies in a single tile.
template <std::size_t N>
[[gnu::always_inline]] inline void bin_primitive(const TileGrid& g, ChunkBuffer<N>& chunk, std::uint32_t index) {
  const ScreenPrimitive<N>& p = chunk.primitives[index];
  const int tx0 = g.tile_of(p.min_x), tx1 = g.tile_of(p.max_x), ty0 = g.tile_of(p.min_y), ty1 = g.tile_of(p.max_y);
  if (tx0 == tx1 && ty0 == ty1) {
    chunk.entries.emplace_back(std::uint32_t(ty0 * g.columns + tx0), index);
    return;
  }
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) chunk.entries.emplace_back(std::uint32_t(ty * g.columns + tx), index);
}
template <std::size_t N>
[[gnu::always_inline]] inline void bin_last(const TileGrid& g, ChunkBuffer<N>& chunk) {
  bin_primitive(g, chunk, static_cast<std::uint32_t>(chunk.primitive_count - 1));
}
template <std::size_t N>
void bin(const TileGrid& g, ChunkBuffer<N>& chunk, const ScreenPrimitive<N>& p) {
  chunk.append_primitive() = p;
  bin_last(g, chunk);
}

}  // namespace detail

}  // namespace tessera
