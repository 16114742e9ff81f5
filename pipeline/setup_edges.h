// Setup's fixed-point steps: edge functions on 16.8 vertices with D3D11's top-left rule as a bias,
// the pixel box whose centres a primitive may cover, and a small triangle's edges in 32-bit lanes
// with the centres of its box it covers. The rasterizer (triangle_coverage.h) walks exactly these
// functions. Pure functions of their inputs.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "pipeline/screen_primitive.h"
#include "pipeline/setup_context.h"
#include "pipeline/setup_vertex.h"
#include "pipeline/simd4.h"

namespace tessera::detail {

// Setup's integer steps are templates over the lane type I: std::int32_t for one triangle,
// simd::I4 (simd4.h) for a triangle's three edges in lanes, simd::I8 (simd8.h) for eight triangles
// in lanes (triangle_list_setup.h). Every form computes the same integers, so the two setups cannot
// drift apart.

// First and last pixel whose centre (p + 0.5) lies in [lo, hi] (16.8 fixed point).
template <class I>
I first_pixel_at_or_after(I lo) {
  // ceil((lo - 128) / 256) = floor((lo - 128 + 255) / 256); >> is floor division (arithmetic shift).
  return (lo + I(kSubpixelOne / 2 - 1)) >> kSubpixelBits;
}
template <class I>
I last_pixel_at_or_before(I hi) {
  return (hi - I(kSubpixelOne / 2)) >> kSubpixelBits;  // arithmetic shift = floor
}

// D3D11's top-left rule as an edge function's bias: 0 on a top edge (horizontal, the inside below:
// dy == 0, dx > 0) or a left edge (dy < 0), -1 elsewhere, so a centre exactly on another edge is
// outside. In lanes the comparisons are masks, and the bias is their complement.
inline std::int32_t top_left_bias(std::int32_t dx, std::int32_t dy) { return dy < 0 || (dy == 0 && dx > 0) ? 0 : -1; }
template <class I>
[[gnu::always_inline]] inline I top_left_bias(I dx, I dy) {
  const I zero(0);
  return ~(less(dy, zero) | (equal(dy, zero) & greater(dx, zero)));
}

// The edge from (x, y) to (x_next, y_next) of a triangle with positive area, in 32 bits: its
// direction and its value at the centre (cx, cy) with the top-left bias (covers_centre's edge
// function; exact for triangles within kEdges32MaxExtent, whose values all fit).
template <class I>
struct Edge32 {
  I dx, dy, ref;
};
template <class I>
[[gnu::always_inline]] inline Edge32<I> edge32(I x, I y, I x_next, I y_next, I cx, I cy) {
  const I dx = x_next - x, dy = y_next - y;
  return {dx, dy, dy * (x - cx) + dx * (cy - y) + top_left_bias(dx, dy)};
}

// Edge i of a triangle with positive area runs from vertex i to vertex i + 1; it is >= 0 on the inside
// and biased by -1 unless it is a top or left edge (D3D11's top-left rule). EdgeFunction is edge i's
// value at (cx, cy) (16.8 units) and its steps for one pixel right and down, in 64-bit integers (exact
// inside the guard band); raster_tile.h walks exactly these functions, and setup's 32-bit lanes compute
// the same values for small triangles.
struct EdgeFunction {
  std::int64_t value, step_x, step_y;
};
inline EdgeFunction edge_function(const std::int32_t* x, const std::int32_t* y, int i, std::int64_t cx,
                                  std::int64_t cy) {
  const int j = i == 2 ? 0 : i + 1;
  const std::int64_t dx = x[j] - x[i], dy = y[j] - y[i];
  return {-dy * (cx - x[i]) + dx * (cy - y[i]) + top_left_bias(std::int32_t(dx), std::int32_t(dy)), -dy * kSubpixelOne,
          dx * kSubpixelOne};
}

// The one-centre form: whether pixel (px, py)'s centre (px + 0.5, py + 0.5) is covered.
inline bool covers_centre(const std::int32_t (&x)[3], const std::int32_t (&y)[3], std::int32_t px, std::int32_t py) {
  const std::int64_t cx = std::int64_t(px) * kSubpixelOne + kSubpixelOne / 2;
  const std::int64_t cy = std::int64_t(py) * kSubpixelOne + kSubpixelOne / 2;
  std::int64_t all = 0;
  for (int i = 0; i < 3; ++i) all |= edge_function(x, y, i, cx, cy).value;
  return all >= 0;
}

// The pixel box whose centres lie in [lx, hx] x [ly, hy] (16.8), clipped to what may be written (empty when min > max).
template <class I = std::int32_t>
struct PixelBox {
  I min_x, max_x, min_y, max_y;
  bool empty() const { return min_x > max_x || min_y > max_y; }  // one triangle's box
};
template <class I>
[[gnu::always_inline]] inline PixelBox<I> clipped_pixel_box(const SetupContext& c, I lx, I hx, I ly, I hy) {
  using std::max, std::min;  // simd::max and min by argument-dependent lookup
  return {max(first_pixel_at_or_after(lx), I(c.clip_min_x)), min(last_pixel_at_or_before(hx), I(c.clip_max_x)),
          max(first_pixel_at_or_after(ly), I(c.clip_min_y)), min(last_pixel_at_or_before(hy), I(c.clip_max_y))};
}

// Clips the pixel box to what may be written; false if nothing is left.
template <std::size_t N>
bool finish_box(const SetupContext& c, ScreenPrimitive<N>& p, std::int32_t lo_x, std::int32_t hi_x, std::int32_t lo_y,
                std::int32_t hi_y) {
  const PixelBox<> b = clipped_pixel_box(c, lo_x, hi_x, lo_y, hi_y);
  p.min_x = b.min_x, p.max_x = b.max_x, p.min_y = b.min_y, p.max_y = b.max_y;
  return !b.empty();
}

// A triangle's edge functions in 32 bits (ScreenPrimitive::edges; the vertices in positive-area order),
// and for a box of at most kSmallBoxPixels^2 centres the ones it covers (box_coverage).
struct SetupEdges32 {
#if defined(__SSE2__)
  __m128i ref_lanes = _mm_setzero_si128();  // edge i's value at the box's first centre in lane i
  __m128i d_lanes = _mm_setzero_si128();    // dx of edges 0..3, then dy, in 16-bit lanes
#else
  std::uint32_t ref[4] = {};
  std::int16_t d[8] = {};  // dx of edges 0..3, then dy
#endif
  unsigned box_coverage = 0;
};
// Edge functions (covers_centre's) of a triangle small enough for 32 bits: computed modulo 2^32
// (unsigned arithmetic wraps, defined), which gives the exact values because every value used fits
// (kEdges32MaxExtent; the reference centre lies inside the vertex box).
template <std::size_t N>
[[gnu::always_inline]] inline SetupEdges32 setup_edges32([[maybe_unused]] const SetupVertex<N>* const (&v)[3],
                                                         [[maybe_unused]] const std::int32_t (&vx)[3],
                                                         [[maybe_unused]] const std::int32_t (&vy)[3],
                                                         const PixelBox<>& box, bool small_box) {
  SetupEdges32 e;
  const std::int32_t min_x = box.min_x, max_x = box.max_x, min_y = box.min_y, max_y = box.max_y;
  unsigned box_coverage = 0;
  const std::int32_t cx = min_x * kSubpixelOne + kSubpixelOne / 2, cy = min_y * kSubpixelOne + kSubpixelOne / 2;
#if defined(__SSE2__)
  // The three edges in lanes 0..2 (lane 3 repeats edge 2's direction; it is never used). A
  // SetupVertex's x and y are adjacent: one 64-bit load per vertex.
  static_assert(offsetof(SetupVertex<N>, y) == offsetof(SetupVertex<N>, x) + sizeof(std::int32_t));
  const __m128i p0 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&v[0]->x));  // x0 y0
  const __m128i p1 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&v[1]->x));
  const __m128i p2 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&v[2]->x));
  const __m128i p01 = _mm_unpacklo_epi32(p0, p1), p22 = _mm_unpacklo_epi32(p2, p2);  // x0 x1 y0 y1, x2 x2 y2 y2
  const __m128i x = _mm_unpacklo_epi64(p01, p22), y = _mm_unpackhi_epi64(p01, p22);  // x0 x1 x2 x2, y0 y1 y2 y2
  using simd::I4;
  const Edge32<I4> edges = edge32(I4(x), I4(y), I4(_mm_shuffle_epi32(x, _MM_SHUFFLE(0, 0, 2, 1))),
                                  I4(_mm_shuffle_epi32(y, _MM_SHUFFLE(0, 0, 2, 1))), I4(cx), I4(cy));
  const __m128i dx = edges.dx.v, dy = edges.dy.v, ref = edges.ref.v, zero = _mm_setzero_si128();
  const __m128i sx = _mm_slli_epi32(_mm_sub_epi32(zero, dy), kSubpixelBits), sy = _mm_slli_epi32(dx, kSubpixelBits);
  e.ref_lanes = ref;
  e.d_lanes = _mm_packs_epi32(dx, dy);  // exact: |d| <= kEdges32MaxExtent
  if (small_box) {
    // A box of at most 4x4 pixel centres: each edge at the four centres (min_x + dx, min_y + dy) of
    // a row in lanes dx; the covered centres of a row are the lanes where no edge is negative. All
    // four rows, without a branch on the box's height; centres outside the box are masked off below.
    // (AVX2 builds set up most triangles in triangle_list_setup.h; this form serves the rest.)
    unsigned found = 0;  // bit dx + 8 * dy
    // The x step times dx = 0..3 as masked adds: SSE2 has no 32-bit lane multiply (simd::mullo32
    // emulates one there with twice the instructions).
    const __m128i from1 = _mm_setr_epi32(0, -1, -1, -1), from2 = _mm_setr_epi32(0, 0, -1, -1);
    const __m128i from3 = _mm_setr_epi32(0, 0, 0, -1);
    __m128i row[3], down[3];
    const auto edge = [&](auto lane) {  // edge `lane` at the first row's centres
      constexpr int k = decltype(lane)::value, broadcast = _MM_SHUFFLE(k, k, k, k);
      const __m128i step = _mm_shuffle_epi32(sx, broadcast);
      const __m128i times_dx = _mm_add_epi32(_mm_add_epi32(_mm_and_si128(step, from1), _mm_and_si128(step, from2)),
                                             _mm_and_si128(step, from3));
      row[k] = _mm_add_epi32(_mm_shuffle_epi32(ref, broadcast), times_dx);
      down[k] = _mm_shuffle_epi32(sy, broadcast);
    };
    edge(std::integral_constant<int, 0>{});
    edge(std::integral_constant<int, 1>{});
    edge(std::integral_constant<int, 2>{});
    for (int r = 0; r < kSmallBoxPixels; ++r) {
      const __m128i any_negative = _mm_or_si128(_mm_or_si128(row[0], row[1]), row[2]);
      found |= (~unsigned(_mm_movemask_ps(_mm_castsi128_ps(any_negative))) & 0xFu) << (8 * r);
      for (int i = 0; i < 3; ++i) row[i] = _mm_add_epi32(row[i], down[i]);
    }
    const unsigned columns = ((2u << (max_x - min_x)) - 1u) * 0x01010101u;
    const unsigned rows = 0xFFFFFFFFu >> (8 * (kSmallBoxPixels - 1 - (max_y - min_y)));
    box_coverage = found & columns & rows;
  }
#else
  std::uint32_t edge_sx[4] = {}, edge_sy[4] = {};
  for (int i = 0; i < 3; ++i) {
    const int j = i == 2 ? 0 : i + 1;
    const std::int32_t dx = vx[j] - vx[i], dy = vy[j] - vy[i];
    const std::uint32_t bias = std::uint32_t(top_left_bias(dx, dy));
    e.ref[i] = std::uint32_t(dy) * std::uint32_t(vx[i] - cx) + std::uint32_t(dx) * std::uint32_t(cy - vy[i]) + bias;
    edge_sx[i] = std::uint32_t(-dy) * kSubpixelOne;
    edge_sy[i] = std::uint32_t(dx) * kSubpixelOne;
    e.d[i] = std::int16_t(dx), e.d[4 + i] = std::int16_t(dy);
  }
  if (small_box) {
    for (std::int32_t py = 0; py <= max_y - min_y; ++py)
      for (std::int32_t px = 0; px <= max_x - min_x; ++px) {
        std::uint32_t all = 0;
        for (int i = 0; i < 3; ++i) all |= e.ref[i] + edge_sx[i] * std::uint32_t(px) + edge_sy[i] * std::uint32_t(py);
        if (std::int32_t(all) >= 0) box_coverage |= 1u << (px + 8 * py);
      }
  }
#endif
  e.box_coverage = box_coverage;
  return e;
}

// The edges into the record, straight from the lanes: reading back a vector store in pieces stalls
// store forwarding.
template <std::size_t N>
[[gnu::always_inline]] inline void store_edges32(ScreenPrimitive<N>& p, const SetupEdges32& e) {
#if defined(__SSE2__)
  static_assert(offsetof(SmallTriangleEdges, dy) == offsetof(SmallTriangleEdges, dx) + 8);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p.edges.dx.data()), e.d_lanes);
  _mm_storel_epi64(reinterpret_cast<__m128i*>(p.edges.ref.data()), e.ref_lanes);
  p.edges.ref[2] = _mm_cvtsi128_si32(_mm_shuffle_epi32(e.ref_lanes, _MM_SHUFFLE(2, 2, 2, 2)));
#else
  for (int i = 0; i < 3; ++i) {
    p.edges.ref[i] = std::int32_t(e.ref[i]);
    p.edges.dx[i] = e.d[i];
    p.edges.dy[i] = e.d[4 + i];
  }
#endif
}

}  // namespace tessera::detail
