// Which pixels a triangle covers: its three edge functions (16.8 fixed-point vertices, evaluated
// exactly at pixel centres x + 0.5, y + 0.5, with D3D11's top-left rule as the setup's bias), in
// 64-bit integers for any triangle in the guard band, or in the lanes of 32-bit vectors for small
// ones (kEdges32MaxExtent, primitive_setup.h), walked quad by quad or as one 8x8 grid of bits.
#pragma once

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "pipeline/primitive_setup.h"

namespace tessera::detail {

// The three edge functions of a triangle at the four pixels of a quad, stepped quad by quad. Edge i
// at pixel k of the quad: k = 0 (x, y), 1 (x + 1, y), 2 (x, y + 1), 3 (x + 1, y + 1). `e0` is the value
// at the first quad's top-left pixel, `sx`/`sy` the steps for one pixel right/down.
//
// Edges64 holds them in 64-bit integers: exact for any triangle inside the guard band.
struct Edges64 {
  std::int64_t row[3], e[3], sx[3], sy[3];
  Edges64(const std::int64_t (&e0)[3], const std::int64_t (&step_x)[3], const std::int64_t (&step_y)[3]) {
    for (int i = 0; i < 3; ++i) row[i] = e[i] = e0[i], sx[i] = step_x[i], sy[i] = step_y[i];
  }
  void start_row() { e[0] = row[0], e[1] = row[1], e[2] = row[2]; }
  void next_quad() { e[0] += 2 * sx[0], e[1] += 2 * sx[1], e[2] += 2 * sx[2]; }
  void next_row() { row[0] += 2 * sy[0], row[1] += 2 * sy[1], row[2] += 2 * sy[2]; }
  // Bit k: pixel k is inside all three edges (all values >= 0).
  unsigned covered() const {
    unsigned c = 0;
    for (int k = 0; k < 4; ++k) {
      const std::int64_t dx = (k & 1) ? 1 : 0, dy = (k >> 1);
      c |= unsigned(((e[0] + dx * sx[0] + dy * sy[0]) | (e[1] + dx * sx[1] + dy * sy[1]) |
                     (e[2] + dx * sx[2] + dy * sy[2])) >= 0)
           << k;
    }
    return c;
  }
};

#if defined(__SSE2__)
// Edges32 holds the four pixels' values of each edge in the lanes of one 32-bit vector, for triangles
// small enough that every value it evaluates fits (kEdges32MaxExtent, primitive_setup.h): then the
// values are the exact integers Edges64 computes, and coverage is three ORs and a sign mask. Steps wrap
// modulo 2^32 (defined for vector adds); a value past the last quad or row may wrap but is never used.
struct Edges32 {
  __m128i row[3], e[3], step_x2[3], step_y2[3];
  Edges32(const std::int32_t (&e0)[3], const std::int32_t (&sx)[3], const std::int32_t (&sy)[3]) {
    for (int i = 0; i < 3; ++i) {
      const std::int32_t x = sx[i], y = sy[i];
      row[i] = _mm_add_epi32(_mm_set1_epi32(e0[i]),
                             _mm_setr_epi32(0, x, y, std::int32_t(std::uint32_t(x) + std::uint32_t(y))));
      e[i] = row[i];
      step_x2[i] = _mm_set1_epi32(2 * x);
      step_y2[i] = _mm_set1_epi32(2 * y);
    }
  }
  void start_row() { e[0] = row[0], e[1] = row[1], e[2] = row[2]; }
  void next_quad() {
    for (int i = 0; i < 3; ++i) e[i] = _mm_add_epi32(e[i], step_x2[i]);
  }
  void next_row() {
    for (int i = 0; i < 3; ++i) row[i] = _mm_add_epi32(row[i], step_y2[i]);
  }
  unsigned covered() const {
    const __m128i any_negative = _mm_or_si128(_mm_or_si128(e[0], e[1]), e[2]);
    return ~unsigned(_mm_movemask_ps(_mm_castsi128_ps(any_negative))) & 0xFu;
  }
};
#endif

// Walks the quads of [x_begin, x_end] x [y_begin, y_end] (quads aligned to even pixels, starting at
// (qx0, qy0)); pixels of a quad outside the range are masked out (bit k = pixel k).
template <class Edges, class Shade>
std::uint64_t walk_quads(Edges edges, int qx0, int qy0, int x_begin, int x_end, int y_begin, int y_end, Shade&& shade) {
  std::uint64_t invocations = 0;
  for (int qy = qy0; qy <= y_end; qy += 2, edges.next_row()) {
    unsigned row_mask = 0xF;
    if (qy < y_begin) row_mask &= 0xC;
    if (qy + 1 > y_end) row_mask &= 0x3;
    edges.start_row();
    for (int qx = qx0; qx <= x_end; qx += 2, edges.next_quad()) {
      unsigned mask = row_mask;
      if (qx < x_begin) mask &= 0xA;
      if (qx + 1 > x_end) mask &= 0x5;
      const unsigned covered = edges.covered() & mask;
      if (covered) invocations += shade(qx, qy, covered);
    }
  }
  return invocations;
}

// The covered pixels of a triangle in a box of at most 8x8 pixels from its quad-aligned corner
// (origin_x, origin_y) = (min_x & ~1, min_y & ~1), on a grid of 8-bit rows: pixel (origin_x + c, origin_y + r)
// is bit 8r + c, and quad (i, j) is bits 2i, 2i + 1 of rows 2j and 2j + 1.
struct BoxQuads {
  std::uint64_t grid = 0;
  explicit BoxQuads(std::uint64_t g) : grid(g) {}
  // From box_coverage (setup found which of the at most 4x4 pixel centres of the box the triangle
  // covers): shifted by the box's offset from the corner, so its pixels lie in the grid's 3x3 quads.
  BoxQuads(std::uint32_t coverage, int min_x, int min_y)
      : grid(std::uint64_t(coverage) << ((min_x & 1) + 8 * (min_y & 1))) {}
  // Keeps the pixels of columns [c0, c1) and rows [r0, r1) of the grid (each bound clamped to 0..8).
  [[gnu::always_inline]] void keep(int c0, int c1, int r0, int r1) {
    c0 = std::clamp(c0, 0, 8), c1 = std::clamp(c1, 0, 8), r0 = std::clamp(r0, 0, 8), r1 = std::clamp(r1, 0, 8);
    if (c0 >= c1 || r0 >= r1) {
      grid = 0;
      return;
    }
    const std::uint64_t columns = ((1u << c1) - 1u) & ~((1u << c0) - 1u);
    const std::uint64_t below_r1 = r1 == 8 ? ~std::uint64_t(0) : (std::uint64_t(1) << (8 * r1)) - 1u;
    grid &= below_r1 & ~((std::uint64_t(1) << (8 * r0)) - 1u) & (columns * 0x0101010101010101u);
  }
  // Takes the quad of the lowest remaining pixel: its (i, j) and lanes (bit k = pixel (2i + (k & 1),
  // 2j + (k >> 1))), removing its pixels from the grid. False when none is left.
  bool next(int& i, int& j, unsigned& lanes) {
    if (!grid) return false;
    const int bit = std::countr_zero(grid);
    i = (bit & 7) >> 1, j = bit >> 4;
    const int shift = 16 * j + 2 * i;
    const std::uint64_t pair = grid >> shift;
    lanes = unsigned(pair & 3u) | unsigned((pair >> 6) & 0xCu);
    grid &= ~(std::uint64_t(0x0303) << shift);
    return true;
  }
};

#if defined(__AVX2__)
// The centres covered by a triangle with edges32 among the grid's first `rows` rows (BoxQuads' layout,
// corner (origin_x, origin_y)): each edge at a row's eight centres in the lanes of one vector, the
// rows stepped down by adds. Centres up to eight pixels past the box may wrap modulo 2^32; the caller
// keeps only the box's pixels, whose values are exact (kEdges32MaxExtent). `offset`, when given, moves
// the points from the centres by a sample's offset: offset[i] is edge i's change (raster_multisample.h).
[[gnu::always_inline]] inline std::uint64_t grid_coverage(const SmallTriangleEdges& edges, int origin_x_from_min,
                                                          int origin_y_from_min, int rows,
                                                          const std::int32_t* offset = nullptr) {
  const __m256i columns = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  __m256i e[3], down[3];
  for (int i = 0; i < 3; ++i) {
    std::uint32_t at = std::uint32_t(edges.value_at(i, origin_x_from_min, origin_y_from_min));
    if (offset) at += std::uint32_t(offset[i]);
    e[i] = _mm256_add_epi32(_mm256_set1_epi32(std::int32_t(at)),
                            _mm256_mullo_epi32(_mm256_set1_epi32(edges.step_x(i)), columns));
    down[i] = _mm256_set1_epi32(edges.step_y(i));
  }
  std::uint64_t grid = 0;
  for (int r = 0; r < rows; ++r) {
    const __m256i any_negative = _mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]);
    grid |= std::uint64_t(~unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(any_negative))) & 0xFFu) << (8 * r);
    for (int i = 0; i < 3; ++i) e[i] = _mm256_add_epi32(e[i], down[i]);
  }
  return grid;
}
#endif

}  // namespace tessera::detail
