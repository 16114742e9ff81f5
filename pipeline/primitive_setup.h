// Primitive assembly's back half: clip-space primitives in, screen-space primitives binned to tiles out.
//
// For each triangle of snapped vertices (setup_vertex.h): NaN rejection, trivial rejection against the
// view volume, guard-band clipping (clipper.h) of the rare triangle that needs it, back/front culling
// on the snapped signed area, the pixel bounding box clipped to viewport, scissor and render target,
// edge functions and small-box coverage, plane equations, and binning by the box (tile_bins.h).
// Everything here is a pure function of its inputs, so any thread produces the same bytes.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "pipeline/clipper.h"
#include "pipeline/screen_primitive.h"
#include "pipeline/setup_context.h"
#include "pipeline/setup_vertex.h"
#include "pipeline/simd4.h"
#include "pipeline/tile_bins.h"

namespace tessera {

namespace detail {

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

template <std::size_t N>
void copy_vertex(const SetupVertex<N>& v, ScreenPrimitive<N>& out, int slot) {
  out.xy.x[slot] = v.x;
  out.xy.y[slot] = v.y;
  out.z[slot] = v.z;
  out.inv_w[slot] = v.inv_w;
  out.attributes[slot] = v.clip.attributes;
}

template <std::size_t N>
void setup_line_window(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& a, const SetupVertex<N>& b,
                       std::uint32_t primitive_id) {
  ScreenPrimitive<N> p;
  p.kind = PrimitiveKind::line;
  p.primitive_id = primitive_id;
  copy_vertex(a, p, 0);
  copy_vertex(b, p, 1);
  // A line may light the pixel its end point lies in; widen the box by half a pixel.
  const std::int32_t h = kSubpixelOne / 2;
  if (!finish_box(c, p, std::min(p.xy.x[0], p.xy.x[1]) - h, std::max(p.xy.x[0], p.xy.x[1]) + h,
                  std::min(p.xy.y[0], p.xy.y[1]) - h, std::max(p.xy.y[0], p.xy.y[1]) + h))
    return;
  bin(c.tiles, chunk, p);
}

// The steps of setup_snapped_triangle. Each is inlined into it: they run once per triangle, and at
// high factors nearly every triangle is a few pixels.

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

// A plane equation's x and y slopes from its values at the three vertices, vertex 1 and 2 lying at
// (x1, y1) and (x2, y2) pixels from vertex 0. One template for every lane type, so both setups run
// the same expression: F is simd::F4 for four values of one triangle (set_triangle_planes) and
// simd::F8 for one value of eight triangles (setup_triangle_list).
template <class F>
struct PlaneSlopes {
  F x, y;
};
template <class F>
[[gnu::always_inline]] inline PlaneSlopes<F> plane_slopes(F a0, F a1, F a2, F x1, F y1, F x2, F y2, F inv_area) {
  const F d1 = a1 - a0, d2 = a2 - a0;
  return {(d1 * y2 - d2 * y1) * inv_area, (d2 * x1 - d1 * x2) * inv_area};
}

// Plane equations from the snapped positions, in pixels: z, 1/w and each attribute / w at vertex 0
// and their x and y slopes (ScreenPrimitive's planes).
template <std::size_t N>
[[gnu::always_inline]] inline void set_triangle_planes(ScreenPrimitive<N>& p, const SetupVertex<N>* const (&v)[3],
                                                       const std::int32_t (&vx)[3], const std::int32_t (&vy)[3]) {
  const float inv_sub = 1.0f / float(kSubpixelOne);
  const float x1 = float(vx[1] - vx[0]) * inv_sub, y1 = float(vy[1] - vy[0]) * inv_sub;
  const float x2 = float(vx[2] - vx[0]) * inv_sub, y2 = float(vy[2] - vy[0]) * inv_sub;
  const float inv_area = 1.0f / (x1 * y2 - x2 * y1);
  // For z, 1/w and each attribute / w: the value at vertex 0 and its x and y slopes, four values at a
  // time in lanes, each lane the scalar expression
  //   (a0, ((a1 - a0) * y2 - (a2 - a0) * y1) * inv_area, ((a2 - a0) * x1 - (a1 - a0) * x2) * inv_area).
  // (The values come straight from the vertices' plane_values: assembling them here lane by lane and
  // loading them as vectors stalls on store forwarding.)
  constexpr std::size_t kGroups = (N + 5) / 4;
  const float* value[3] = {v[0]->plane_values.data(), v[1]->plane_values.data(), v[2]->plane_values.data()};
  std::array<float, 4 * kGroups> slope_x, slope_y;
  {
    using simd::F4;
    const F4 fx1 = F4::splat(x1), fy1 = F4::splat(y1), fx2 = F4::splat(x2), fy2 = F4::splat(y2);
    const F4 fia = F4::splat(inv_area);
    for (std::size_t g = 0; g < kGroups; ++g) {
      const F4 a0 = F4::load_at(&value[0][4 * g]), a1 = F4::load_at(&value[1][4 * g]),
               a2 = F4::load_at(&value[2][4 * g]);
      const PlaneSlopes<F4> s = plane_slopes(a0, a1, a2, fx1, fy1, fx2, fy2, fia);
      s.x.store_at(&slope_x[4 * g]);
      s.y.store_at(&slope_y[4 * g]);
    }
  }
  p.origin_x = float(vx[0]) * inv_sub;
  p.origin_y = float(vy[0]) * inv_sub;
  p.z = {value[0][0], slope_x[0], slope_y[0]};
  p.inv_w = {value[0][1], slope_x[1], slope_y[1]};
  for (std::size_t k = 0; k < N; ++k) {
    p.attributes[0][k] = value[0][2 + k];
    p.attributes[1][k] = slope_x[2 + k];
    p.attributes[2][k] = slope_y[2 + k];
  }
}

// setup_snapped_triangle on a multisampled target: the box of the pixels whose samples the triangle's
// box may reach (samples lie within half a pixel of their pixel's centre), the vertices kept for the
// rasterizer's per-sample edge tests, no pixel-centre rejection. Out of line: single-sampled draws never
// take it.
template <std::size_t N>
[[gnu::noinline]] void setup_multisample_triangle(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& a,
                                                  const SetupVertex<N>& b, const SetupVertex<N>& d,
                                                  std::uint32_t primitive_id) {
  // Signed area and culling as setup_snapped_triangle decides them.
  const std::int64_t area = std::int64_t(b.x - a.x) * (d.y - a.y) - std::int64_t(d.x - a.x) * (b.y - a.y);
  if (area == 0) return;
  const bool front = (area > 0) != c.front_ccw;
  if ((c.cull == CullMode::back && !front) || (c.cull == CullMode::front && front)) return;
  const std::int32_t lx = std::min(std::min(a.x, b.x), d.x), hx = std::max(std::max(a.x, b.x), d.x);
  const std::int32_t ly = std::min(std::min(a.y, b.y), d.y), hy = std::max(std::max(a.y, b.y), d.y);
  const std::int32_t h = kSubpixelOne / 2;
  const PixelBox<> box = clipped_pixel_box(c, lx - h, hx + h, ly - h, hy + h);
  if (box.empty()) return;
  const SetupVertex<N>* const v[3] = {&a, area > 0 ? &b : &d, area > 0 ? &d : &b};
  const std::int32_t vx[3] = {v[0]->x, v[1]->x, v[2]->x}, vy[3] = {v[0]->y, v[1]->y, v[2]->y};
  ScreenPrimitive<N>& p = chunk.append_primitive();
  p.kind = PrimitiveKind::triangle;
  p.min_x = box.min_x, p.max_x = box.max_x, p.min_y = box.min_y, p.max_y = box.max_y;
  for (int i = 0; i < 3; ++i) {
    p.xy.x[i] = vx[i];
    p.xy.y[i] = vy[i];
  }
  p.edges32 = false;
  p.box_coverage = 0;
  set_triangle_planes(p, v, vx, vy);
  p.front_face = front;
  p.primitive_id = primitive_id;
  // Binned with push_back, not bin_last: a new call site of the hot path's emplace_back made GCC stop
  // inlining it into setup_triangle_list (a call per triangle of every single-sampled draw).
  const std::uint32_t index = static_cast<std::uint32_t>(chunk.primitive_count - 1);
  const TileGrid& g = c.tiles;
  for (int ty = g.tile_of(p.min_y); ty <= g.tile_of(p.max_y); ++ty)
    for (int tx = g.tile_of(p.min_x); tx <= g.tile_of(p.max_x); ++tx)
      chunk.entries.push_back({std::uint32_t(ty * g.columns + tx), index});
}

// A triangle whose three vertices are snapped: culling, bounding box, edges and coverage, planes,
// binning. `a`, `b`, `d` are in the primitive's order.
template <std::size_t N>
[[gnu::always_inline]] inline void setup_snapped_triangle(const SetupContext& c, ChunkBuffer<N>& chunk,
                                                          const SetupVertex<N>& a, const SetupVertex<N>& b,
                                                          const SetupVertex<N>& d, std::uint32_t primitive_id) {
  const std::int64_t area = std::int64_t(b.x - a.x) * (d.y - a.y) - std::int64_t(d.x - a.x) * (b.y - a.y);
  if (area == 0) return;  // degenerate after snapping: covers nothing
  // Positive area is clockwise on screen (y down).
  const bool front = (area > 0) != c.front_ccw;
  if ((c.cull == CullMode::back && !front) || (c.cull == CullMode::front && front)) return;
  // The box test comes before the primitive is built: most micro-triangles stop here.
  const std::int32_t lx = std::min(std::min(a.x, b.x), d.x), hx = std::max(std::max(a.x, b.x), d.x);
  const std::int32_t ly = std::min(std::min(a.y, b.y), d.y), hy = std::max(std::max(a.y, b.y), d.y);
  const PixelBox<> box = clipped_pixel_box(c, lx, hx, ly, hy);
  if (box.empty()) return;
  // Stored with positive area: swap the last two vertices of a counter-clockwise triangle.
  const SetupVertex<N>* const v[3] = {&a, area > 0 ? &b : &d, area > 0 ? &d : &b};
  const std::int32_t vx[3] = {v[0]->x, v[1]->x, v[2]->x}, vy[3] = {v[0]->y, v[1]->y, v[2]->y};
  const bool edges32 = hx - lx <= kEdges32MaxExtent && hy - ly <= kEdges32MaxExtent;
  const bool small_box = box.max_x - box.min_x <= kSmallBoxPixels - 1 && box.max_y - box.min_y <= kSmallBoxPixels - 1;
  SetupEdges32 edges;
  bool covers = true;
  if (edges32) {
    edges = setup_edges32<N>(v, vx, vy, box, small_box);
    covers = !small_box || edges.box_coverage != 0;
  } else if (small_box) {
    covers = false;
    for (std::int32_t py = box.min_y; py <= box.max_y && !covers; ++py)
      for (std::int32_t px = box.min_x; px <= box.max_x && !covers; ++px) covers = covers_centre(vx, vy, px, py);
  }
  // A box of at most 4x4 pixel centres (kSmallBoxPixels; nearly every triangle at high factors) whose
  // centres the triangle does not cover (tested exactly, as the rasterizer will) is dropped before its
  // planes are built and it is binned. The image and the PS invocations cannot change; only the work does.
  if (!covers) return;
  // Built in place; every field the rasterizer reads of a triangle is written.
  ScreenPrimitive<N>& p = chunk.append_primitive();
  p.kind = PrimitiveKind::triangle;
  p.min_x = box.min_x, p.max_x = box.max_x, p.min_y = box.min_y, p.max_y = box.max_y;
  if (edges32) {
    store_edges32(p, edges);
  } else {
    for (int i = 0; i < 3; ++i) {
      p.xy.x[i] = vx[i];
      p.xy.y[i] = vy[i];
    }
  }
  p.edges32 = edges32;
  p.box_coverage = edges.box_coverage;
  set_triangle_planes(p, v, vx, vy);
  p.front_face = front;
  p.primitive_id = primitive_id;
  bin_last(c.tiles, chunk);
}

// setup_triangle's path for a triangle that needs clipping (or is drawn as wireframe): clipped to a
// fan, each piece set up as setup_snapped_triangle does.
template <std::size_t N>
[[gnu::noinline]] void setup_clipped_triangle(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& v0,
                                              const SetupVertex<N>& v1, const SetupVertex<N>& v2, unsigned needs,
                                              std::uint32_t primitive_id) {
  ClipPolygon<N> poly;
  poly.v[0] = v0.clip, poly.v[1] = v1.clip, poly.v[2] = v2.clip;
  poly.count = 3;
  if (needs) clip_polygon(poly, needs, c.guard);
  SetupVertex<N> s[std::tuple_size_v<decltype(poly.v)>];
  for (int k = 0; k < poly.count; ++k) s[k] = make_setup_vertex(c, poly.v[k], true);
  for (int k = 1; k + 1 < poly.count; ++k) {
    ++chunk.statistics.CPrimitives;
    if (c.fill == FillMode::wireframe) {
      // Only the polygon's own edges: the fan's inner diagonals are not drawn.
      const SetupVertex<N>* t[3] = {&s[0], &s[k], &s[k + 1]};
      for (int e = 0; e < 3; ++e) {
        const bool inner = (e == 0 && k > 1) || (e == 2 && k + 2 < poly.count);
        if (!inner) setup_line_window(c, chunk, *t[e], *t[(e + 1) % 3], primitive_id);
      }
      continue;
    }
    if (c.samples > 1)
      setup_multisample_triangle(c, chunk, s[0], s[k], s[k + 1], primitive_id);
    else
      setup_snapped_triangle(c, chunk, s[0], s[k], s[k + 1], primitive_id);
  }
}

}  // namespace detail

// Triangle: counts one CInvocation and a CPrimitive per emitted triangle; appends to `chunk`. Inlined
// into the caller's loop over a pattern's triangles; the rare clipping path is a call.
template <std::size_t N>
[[gnu::always_inline]] inline void setup_triangle(const SetupContext& c, ChunkBuffer<N>& chunk,
                                                  const SetupVertex<N>& v0, const SetupVertex<N>& v1,
                                                  const SetupVertex<N>& v2, std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  // D3D11 discards primitives with a NaN or infinite position coordinate.
  if (!v0.finite || !v1.finite || !v2.finite) return;
  if (v0.view_code & v1.view_code & v2.view_code) return;  // wholly outside one plane of the view volume
  const unsigned needs = v0.clip_code | v1.clip_code | v2.clip_code;
  // Multisampled targets take the out-of-line path too (setup_multisample_triangle).
  if (needs == 0 && c.fill == FillMode::solid && c.samples == 1) {
    ++chunk.statistics.CPrimitives;
    detail::setup_snapped_triangle(c, chunk, v0, v1, v2, primitive_id);
    return;
  }
  detail::setup_clipped_triangle(c, chunk, v0, v1, v2, needs, primitive_id);
}

template <std::size_t N>
void setup_line(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& a, const SetupVertex<N>& b,
                std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  if (!a.finite || !b.finite) return;
  if (a.view_code & b.view_code) return;
  const unsigned needs = a.clip_code | b.clip_code;
  if (needs == 0) {
    ++chunk.statistics.CPrimitives;
    detail::setup_line_window(c, chunk, a, b, primitive_id);
    return;
  }
  ClipVertex<N> ca = a.clip, cb = b.clip;
  if (!clip_segment(ca, cb, needs, c.guard)) return;
  ++chunk.statistics.CPrimitives;
  detail::setup_line_window(c, chunk, make_setup_vertex(c, ca, true), make_setup_vertex(c, cb, true), primitive_id);
}

template <std::size_t N>
void setup_point(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& a, std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  if (!a.finite || a.view_code) return;
  ++chunk.statistics.CPrimitives;
  ScreenPrimitive<N> p;
  p.kind = PrimitiveKind::point;
  p.primitive_id = primitive_id;
  detail::copy_vertex(a, p, 0);
  // A point lights the one pixel it lies in.
  const std::int32_t px = p.xy.x[0] >> kSubpixelBits, py = p.xy.y[0] >> kSubpixelBits;
  p.min_x = std::max(px, c.clip_min_x), p.max_x = std::min(px, c.clip_max_x);
  p.min_y = std::max(py, c.clip_min_y), p.max_y = std::min(py, c.clip_max_y);
  if (p.min_x > p.max_x || p.min_y > p.max_y) return;
  detail::bin(c.tiles, chunk, p);
}

}  // namespace tessera
