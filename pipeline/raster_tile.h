// Rasterization of one screen tile: D3D11's rules for triangles, lines and points, then early depth,
// the pixel shader in 2x2 quads, and the output merger.
//
// Triangles: edge functions on 16.8 fixed-point vertices evaluated exactly in 64-bit integers at pixel
// centres (x + 0.5, y + 0.5); a centre on an edge is covered only if the edge is a top or left edge
// (D3D11's top-left rule), so a mesh of triangles sharing edges covers every pixel exactly once.
// Depth is interpolated linearly in screen space and clamped to the viewport's depth range;
// attributes are interpolated perspective-correctly (linear in 1/w).
// Multisampled targets: rasterize_triangle_multisample (coverage and depth per sample, shading per
// pixel); lines and points light every sample of the pixels they light.
// Lines: one pixel per step along the major axis at pixel centres, the segment half-open at its end
// (so strips do not light shared end points twice) — D3D11's aliased line rule without the
// diamond-exit refinements at end points. Points: the one pixel the point lies in.
//
// A tile is owned by one thread; it processes its primitives in draw order, so results do not depend
// on the thread count.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "pipeline/framebuffer.h"
#include "pipeline/primitive_setup.h"
#include "pipeline/sample_pattern.h"
#include "pipeline/simd4.h"

namespace tessera {

struct RasterContext {
  DepthState depth;
  float min_depth = 0, max_depth = 1;
};

namespace detail {

// Lines and points are not shaded in 2x2 quads: their pixel shader sees zero derivatives.
template <std::size_t N>
inline constexpr std::array<float, N> kNoDerivatives{};

template <std::size_t N>
PixelInput<N> quadless_pixel_input(std::uint32_t primitive_id) {
  PixelInput<N> in;
  in.primitive_id = primitive_id;
  in.ddx_attributes = &kNoDerivatives<N>;
  in.ddy_attributes = &kNoDerivatives<N>;
  return in;
}

// Writes one shaded pixel after the depth test passed.
template <std::size_t N, class Ps>
inline void shade(const Ps& ps, const RasterContext& rc, Framebuffer& fb, int x, int y, PixelInput<N>& in) {
  in.position.x = float(x) + 0.5f;
  in.position.y = float(y) + 0.5f;
  const glm::vec4 color = ps(static_cast<const PixelInput<N>&>(in));
  fb.set_color(x, y, color);
  if (rc.depth.test && rc.depth.write) fb.set_depth(x, y, in.position.z);
}

inline bool depth_test(const RasterContext& rc, const Framebuffer& fb, int x, int y, float z) {
  return !rc.depth.test || depth_passes(rc.depth.func, z, fb.depth(x, y));
}

}  // namespace detail

namespace detail {

inline constexpr std::uint8_t kQuadLanes[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};  // popcount

// Lanes of a quad where `z kDepthFunc stored` holds, as depth_passes() decides per pixel.
template <CompareFunc kDepthFunc>
unsigned depth_pass_mask(simd::F4 z, simd::F4 stored) {
  switch (kDepthFunc) {
    case CompareFunc::never: return 0;
    case CompareFunc::less: return simd::less_mask(z, stored);
    case CompareFunc::equal: return simd::equal_mask(z, stored);
    case CompareFunc::less_equal: return simd::less_equal_mask(z, stored);
    case CompareFunc::greater: return simd::less_mask(stored, z);
    case CompareFunc::not_equal: return simd::not_equal_mask(z, stored);
    case CompareFunc::greater_equal: return simd::less_equal_mask(stored, z);
    case CompareFunc::always: return 0xF;
  }
  return 0;
}

// The pixel shader on the lanes `passed` of a quad whose q.z is set: perspective-correct attributes at
// the four pixel centres (helpers included, for derivatives), then the shader, into `color`. dxk and
// dyk are the centres' offsets from the primitive's origin. Shared by the single-sampled and the
// multisampled quad (inlined: the same instructions as written in place).
template <std::size_t N, class Ps>
[[gnu::always_inline]] inline void shade_quad_pixels(const ScreenPrimitive<N>& p, int qx, int qy, simd::F4 dxk,
                                                     simd::F4 dyk, unsigned passed, const Ps& ps, QuadInput<N>& q,
                                                     QuadColor& color) {
  using simd::F4;
  // Perspective-correct attributes at all four pixels (helpers included, for derivatives), in
  // lanes: q.attributes[a][k].
  const F4 inv_w = (F4::splat(p.inv_w[0]) + F4::splat(p.inv_w[1]) * dxk) + F4::splat(p.inv_w[2]) * dyk;
  inv_w.store(q.inv_w);
  const F4 w = F4::splat(1.0f) / inv_w;
  for (std::size_t a = 0; a < N; ++a)
    (((F4::splat(p.attributes[0][a]) + F4::splat(p.attributes[1][a]) * dxk) + F4::splat(p.attributes[2][a]) * dyk) * w)
        .store(q.attributes[a]);
  // float(qx + 1) + 0.5f is float(qx) + 1.5f: both exact for any pixel coordinate.
  (F4::splat(float(qx)) + F4::lanes(0.5f, 1.5f, 0.5f, 1.5f)).store(q.x);
  (F4::splat(float(qy)) + F4::lanes(0.5f, 0.5f, 1.5f, 1.5f)).store(q.y);
  if constexpr (QuadPixelShader<Ps, N>) {
    q.front_face = p.front_face;
    q.primitive_id = p.primitive_id;
    q.mask = passed;
    ps.shade_quad(static_cast<const QuadInput<N>&>(q), color);
  } else {
    // Coarse derivatives: along the quad's top row and down its left column (QuadInput::ddx/ddy
    // compute the same for quad shaders; a test compares the two forms).
    std::array<float, N> ddx, ddy;
    for (std::size_t a = 0; a < N; ++a) {
      ddx[a] = q.attributes[a][1] - q.attributes[a][0];
      ddy[a] = q.attributes[a][2] - q.attributes[a][0];
    }
    PixelInput<N> in;
    in.front_face = p.front_face;
    in.primitive_id = p.primitive_id;
    in.ddx_attributes = &ddx;
    in.ddy_attributes = &ddy;
    for (int k = 0; k < 4; ++k) {
      if (!(passed & (1u << k))) continue;
      for (std::size_t a = 0; a < N; ++a) in.attributes[a] = q.attributes[a][k];
      in.position = glm::vec4(q.x[k], q.y[k], q.z[k], q.inv_w[k]);
      const glm::vec4 c = ps(static_cast<const PixelInput<N>&>(in));
      for (int ch = 0; ch < 4; ++ch) color.c[std::size_t(ch)][k] = c[ch];
    }
  }
}

// One 2x2 quad of triangle `p` at (qx, qy) whose lanes `covered` (bit k = pixel (qx + (k & 1),
// qy + (k >> 1))) are inside the triangle and the tile: early depth, perspective-correct attributes,
// the pixel shader, the output merger. Returns the pixel shader invocations.
//
// Inlined into the loop over a small box's quads, which shades nearly every quad at high factors (an
// out-of-line call there made the loop save and restore its registers around every quad); the edge
// walks call shade_triangle_quad_call.
template <std::size_t N, class Ps, CompareFunc kDepthFunc>
[[gnu::always_inline]] inline unsigned shade_triangle_quad(const ScreenPrimitive<N>& p, int qx, int qy,
                                                           unsigned covered, const Ps& ps, const RasterContext& rc,
                                                           Framebuffer& fb) {
  // Planes evaluated at the four pixel centres, four lanes at once (simd4.h: the same bits as scalar).
  using simd::F4;
  const float fx = float(qx) + 0.5f - p.origin_x, fy = float(qy) + 0.5f - p.origin_y;
  // fx + 0 is fx (a difference is never -0), so one add with constant lanes gives fx and fx + 1.0f.
  const F4 dxk = F4::splat(fx) + F4::lanes(0.0f, 1.0f, 0.0f, 1.0f),
           dyk = F4::splat(fy) + F4::lanes(0.0f, 0.0f, 1.0f, 1.0f);
  QuadInput<N> q;
  const F4 zq = (F4::splat(p.z[0]) + F4::splat(p.z[1]) * dxk) + F4::splat(p.z[2]) * dyk;
  const F4 z = simd::min(simd::max(zq, F4::splat(rc.min_depth)), F4::splat(rc.max_depth));
  z.store(q.z);

  // Early depth for the whole quad without a branch per pixel. A quad inside the target reads its
  // four depths at once (its other lanes are in the same tile, so owned by this thread); one that
  // hangs over the target's last row or column reads only its covered pixels.
  const bool inside = fb.quad_inside(qx, qy);
  const Framebuffer::QuadSite site = inside ? fb.quad_site(qx, qy) : Framebuffer::QuadSite{};
  unsigned passed = covered;
  F4 stored = F4::splat(0.0f);
  if (rc.depth.test) {
    unsigned pass_bits = 0;
    if (inside) {
      stored = fb.depth_quad(site);
      pass_bits = depth_pass_mask<kDepthFunc>(z, stored);
    } else {
      for (int k = 0; k < 4; ++k) {
        const float s = (covered >> k) & 1u ? fb.depth(qx + (k & 1), qy + (k >> 1)) : 0.0f;
        pass_bits |= unsigned(depth_passes(kDepthFunc, q.z[k], s)) << k;
      }
    }
    passed &= pass_bits;
    if (!passed) return 0;
  }

  QuadColor color;
  shade_quad_pixels<N>(p, qx, qy, dxk, dyk, passed, ps, q, color);
  if (inside)
    fb.write_quad(site, passed, color.c);
  else
    fb.write_quad(qx, qy, passed, color.c);
  if (rc.depth.test && rc.depth.write) {
    if (inside) {
      fb.set_depth_quad(site, simd::select(passed, stored, z));
    } else {
      for (int k = 0; k < 4; ++k)
        if (passed & (1u << k)) fb.set_depth(qx + (k & 1), qy + (k >> 1), q.z[k]);
    }
  }
  return kQuadLanes[passed];
}

template <std::size_t N, class Ps, CompareFunc kDepthFunc>
[[gnu::noinline]] unsigned shade_triangle_quad_call(const ScreenPrimitive<N>& p, int qx, int qy, unsigned covered,
                                                    const Ps& ps, const RasterContext& rc, Framebuffer& fb) {
  return shade_triangle_quad<N, Ps, kDepthFunc>(p, qx, qy, covered, ps, rc, fb);
}

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
  void keep(int c0, int c1, int r0, int r1) {
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
// keeps only the box's pixels, whose values are exact (kEdges32MaxExtent).
inline std::uint64_t grid_coverage(const SmallTriangleEdges& edges, int origin_x_from_min, int origin_y_from_min,
                                   int rows) {
  const __m256i columns = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  __m256i e[3], down[3];
  for (int i = 0; i < 3; ++i) {
    e[i] = _mm256_add_epi32(_mm256_set1_epi32(edges.value_at(i, origin_x_from_min, origin_y_from_min)),
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

// Triangles that rasterize_triangle_with cannot take as a grid (boxes past 8x8 pixels, edges in 64 bits,
// or past 4x4 in builds without AVX2): the quads of [x_begin, x_end] x [y_begin, y_end] found by walking
// the edge functions. Out of line: few triangles take it at high factors.
template <std::size_t N, class Ps, CompareFunc kDepthFunc>
[[gnu::noinline]] std::uint64_t rasterize_triangle_walk(const ScreenPrimitive<N>& p, int x_begin, int x_end,
                                                        int y_begin, int y_end, const Ps& ps, const RasterContext& rc,
                                                        Framebuffer& fb) {
  const int qx0 = x_begin & ~1, qy0 = y_begin & ~1;  // 2x2 quads are aligned to even pixels
  auto shade = [&](int qx, int qy, unsigned covered) {
    return shade_triangle_quad_call<N, Ps, kDepthFunc>(p, qx, qy, covered, ps, rc, fb);
  };
#if defined(__SSE2__)
  if (p.edges32) {
    // Setup's edge functions moved from (min_x, min_y) to the first quad, modulo 2^32 (exact: the
    // value fits, primitive_setup.h).
    std::int32_t e0[3], sx[3], sy[3];
    for (int i = 0; i < 3; ++i)
      sx[i] = p.edges.step_x(i), sy[i] = p.edges.step_y(i), e0[i] = p.edges.value_at(i, qx0 - p.min_x, qy0 - p.min_y);
    return walk_quads(Edges32(e0, sx, sy), qx0, qy0, x_begin, x_end, y_begin, y_end, shade);
  }
#endif
  const std::int64_t px0 = std::int64_t(qx0) * kSubpixelOne + kSubpixelOne / 2;
  const std::int64_t py0 = std::int64_t(qy0) * kSubpixelOne + kSubpixelOne / 2;

  // Edge i runs from vertex i to vertex i+1: zero on that edge, positive towards the third vertex
  // (primitive_setup.h's edge_function).
  std::int64_t e0[3], sx[3], sy[3];
  for (int i = 0; i < 3; ++i) {
    const EdgeFunction e = edge_function(p.xy.x.data(), p.xy.y.data(), i, px0, py0);
    e0[i] = e.value, sx[i] = e.step_x, sy[i] = e.step_y;
  }
  return walk_quads(Edges64(e0, sx, sy), qx0, qy0, x_begin, x_end, y_begin, y_end, shade);
}

// Rasterizes triangle `p` inside the tile [tx0, tx1) x [ty0, ty1); returns pixel shader invocations.
template <std::size_t N, class Ps, CompareFunc kDepthFunc>
std::uint64_t rasterize_triangle_with(const ScreenPrimitive<N>& p, int tx0, int ty0, int tx1, int ty1, const Ps& ps,
                                      const RasterContext& rc, Framebuffer& fb) {
  const int x_begin = std::max(p.min_x, tx0), x_end = std::min(p.max_x, tx1 - 1);
  const int y_begin = std::max(p.min_y, ty0), y_end = std::min(p.max_y, ty1 - 1);
  if (x_begin > x_end || y_begin > y_end) return 0;
  // The covered pixels as a grid of quads (BoxQuads) where that is cheap, shaded quad by quad below: the
  // centres setup found in a small box, or (AVX2) the centres of a box of at most 8x8 pixels from its
  // quad-aligned corner, evaluated here eight at a time (about one triangle in eight at factor 16).
  // Other triangles walk their edges quad by quad. A triangle's quads do not overlap, so their order
  // does not change the image; tiles are aligned to quads.
  const int ox = p.min_x & ~1, oy = p.min_y & ~1;
  const bool clipped_by_tile = x_begin != p.min_x || x_end != p.max_x || y_begin != p.min_y || y_end != p.max_y;
  BoxQuads box(0);
  if (p.box_coverage) {
    box = BoxQuads(p.box_coverage, p.min_x, p.min_y);
    if (clipped_by_tile) box.keep(x_begin - ox, x_end + 1 - ox, y_begin - oy, y_end + 1 - oy);
  }
#if defined(__AVX2__)
  else if (p.edges32 && p.max_x - ox < 8 && p.max_y - oy < 8) {
    box = BoxQuads(grid_coverage(p.edges, ox - p.min_x, oy - p.min_y, p.max_y - oy + 1));
    box.keep(x_begin - ox, x_end + 1 - ox, y_begin - oy, y_end + 1 - oy);
  }
#endif
  else {
    return rasterize_triangle_walk<N, Ps, kDepthFunc>(p, x_begin, x_end, y_begin, y_end, ps, rc, fb);
  }
  std::uint64_t invocations = 0;
  int i = 0, j = 0;
  unsigned covered = 0;
  while (box.next(i, j, covered))
    invocations += shade_triangle_quad<N, Ps, kDepthFunc>(p, ox + 2 * i, oy + 2 * j, covered, ps, rc, fb);
  return invocations;
}

}  // namespace detail

template <std::size_t N, class Ps>
std::uint64_t rasterize_line(const ScreenPrimitive<N>& p, int tx0, int ty0, int tx1, int ty1, const Ps& ps,
                             const RasterContext& rc, Framebuffer& fb) {
  const std::int64_t dx = p.xy.x[1] - p.xy.x[0], dy = p.xy.y[1] - p.xy.y[0];
  if (dx == 0 && dy == 0) return 0;
  const bool x_major = (dx < 0 ? -dx : dx) >= (dy < 0 ? -dy : dy);
  // Steps along the major axis at pixel centres in the half-open span [start, end) of the segment.
  const std::int32_t a_lo = x_major ? std::min(p.xy.x[0], p.xy.x[1]) : std::min(p.xy.y[0], p.xy.y[1]);
  const std::int32_t a_hi = x_major ? std::max(p.xy.x[0], p.xy.x[1]) : std::max(p.xy.y[0], p.xy.y[1]);
  int first = detail::first_pixel_at_or_after(a_lo), last = detail::last_pixel_at_or_before(a_hi - 1);
  const int lo_major = x_major ? std::max(tx0, p.min_x) : std::max(ty0, p.min_y);
  const int hi_major = x_major ? std::min(tx1 - 1, p.max_x) : std::min(ty1 - 1, p.max_y);
  first = std::max(first, lo_major);
  last = std::min(last, hi_major);

  std::uint64_t invocations = 0;
  PixelInput<N> in = detail::quadless_pixel_input<N>(p.primitive_id);
  const float major_start = float(x_major ? p.xy.x[0] : p.xy.y[0]);
  const float major_delta = float(x_major ? dx : dy);
  for (int m = first; m <= last; ++m) {
    const float centre = float(m) * float(kSubpixelOne) + float(kSubpixelOne / 2);
    const float t = (centre - major_start) / major_delta;
    const float minor = float(x_major ? p.xy.y[0] : p.xy.x[0]) + t * float(x_major ? dy : dx);
    const int n = static_cast<int>(std::floor(minor / float(kSubpixelOne)));
    const int x = x_major ? m : n, y = x_major ? n : m;
    if (x < std::max(tx0, p.min_x) || x > std::min(tx1 - 1, p.max_x) || y < std::max(ty0, p.min_y) ||
        y > std::min(ty1 - 1, p.max_y))
      continue;
    float z = (1.0f - t) * p.z[0] + t * p.z[1];
    z = std::min(std::max(z, rc.min_depth), rc.max_depth);
    if (!detail::depth_test(rc, fb, x, y, z)) continue;
    const float f0 = (1.0f - t) * p.inv_w[0], f1 = t * p.inv_w[1];
    const float s = f0 + f1, r = 1.0f / s;
    for (std::size_t a = 0; a < N; ++a) in.attributes[a] = (f0 * p.attributes[0][a] + f1 * p.attributes[1][a]) * r;
    in.position.z = z;
    in.position.w = s;
    detail::shade<N>(ps, rc, fb, x, y, in);
    ++invocations;
  }
  return invocations;
}

template <std::size_t N, class Ps>
std::uint64_t rasterize_point(const ScreenPrimitive<N>& p, int tx0, int ty0, int tx1, int ty1, const Ps& ps,
                              const RasterContext& rc, Framebuffer& fb) {
  const int x = p.min_x, y = p.min_y;
  if (x < tx0 || x >= tx1 || y < ty0 || y >= ty1) return 0;
  const float z = std::min(std::max(p.z[0], rc.min_depth), rc.max_depth);
  if (!detail::depth_test(rc, fb, x, y, z)) return 0;
  PixelInput<N> in = detail::quadless_pixel_input<N>(p.primitive_id);
  in.attributes = p.attributes[0];
  in.position.z = z;
  in.position.w = p.inv_w[0];
  detail::shade<N>(ps, rc, fb, x, y, in);
  return 1;
}

namespace detail {

// A triangle on a multisampled target (D3D11's multisample rasterization): coverage by each sample of
// the standard pattern (sample_pattern.h) with the same exact edge functions and top-left rule as a
// pixel centre, depth interpolated and tested per sample, the pixel shader once per 2x2 quad for the
// pixels with any sample passing, at the pixel centres (attributes are not centroid-interpolated: a
// centre outside the triangle extrapolates, as D3D's default interpolation does), and its colour
// written to the samples that passed. Out of line: single-sampled draws never take it.
template <std::size_t N, class Ps, CompareFunc kDepthFunc>
[[gnu::noinline]] std::uint64_t rasterize_triangle_multisample(const ScreenPrimitive<N>& p, int tx0, int ty0, int tx1,
                                                               int ty1, const Ps& ps, const RasterContext& rc,
                                                               Framebuffer& fb) {
  using simd::F4;
  const int x_begin = std::max(p.min_x, tx0), x_end = std::min(p.max_x, tx1 - 1);
  const int y_begin = std::max(p.min_y, ty0), y_end = std::min(p.max_y, ty1 - 1);
  if (x_begin > x_end || y_begin > y_end) return 0;
  const std::span<const SampleOffset> pattern = standard_sample_pattern(fb.samples());
  const int samples = int(pattern.size());
  const int qx0 = x_begin & ~1, qy0 = y_begin & ~1;
  // Each sample's edge values at the first quad's top-left pixel; the steps are the same for all.
  std::int64_t e0[16][3] = {}, sx[3] = {}, sy[3] = {};
  for (int s = 0; s < samples; ++s)
    for (int i = 0; i < 3; ++i) {
      const std::int64_t cx = std::int64_t(qx0) * kSubpixelOne + kSubpixelOne / 2 + pattern[std::size_t(s)].x * 16;
      const std::int64_t cy = std::int64_t(qy0) * kSubpixelOne + kSubpixelOne / 2 + pattern[std::size_t(s)].y * 16;
      const EdgeFunction e = edge_function(p.xy.x.data(), p.xy.y.data(), i, cx, cy);
      e0[s][i] = e.value, sx[i] = e.step_x, sy[i] = e.step_y;
    }
  std::uint64_t invocations = 0;
  for (int qy = qy0; qy <= y_end; qy += 2) {
    unsigned row_mask = 0xF;
    if (qy < y_begin) row_mask &= 0xC;
    if (qy + 1 > y_end) row_mask &= 0x3;
    for (int qx = qx0; qx <= x_end; qx += 2) {
      unsigned mask = row_mask;
      if (qx < x_begin) mask &= 0xA;
      if (qx + 1 > x_end) mask &= 0x5;
      const std::int64_t dqx = qx - qx0, dqy = qy - qy0;
      unsigned covered[16], any_covered = 0;
      for (int s = 0; s < samples; ++s) {
        unsigned c = 0;
        for (int k = 0; k < 4; ++k) {
          const std::int64_t dx = dqx + (k & 1), dy = dqy + (k >> 1);
          c |= unsigned(((e0[s][0] + dx * sx[0] + dy * sy[0]) | (e0[s][1] + dx * sx[1] + dy * sy[1]) |
                         (e0[s][2] + dx * sx[2] + dy * sy[2])) >= 0)
               << k;
        }
        covered[s] = c & mask;
        any_covered |= covered[s];
      }
      if (!any_covered) continue;
      const bool inside = fb.quad_inside(qx, qy);
      const Framebuffer::QuadSite site = fb.quad_site(qx, qy);
      const float fx = float(qx) + 0.5f - p.origin_x, fy = float(qy) + 0.5f - p.origin_y;
      const F4 dxk = F4::splat(fx) + F4::lanes(0.0f, 1.0f, 0.0f, 1.0f),
               dyk = F4::splat(fy) + F4::lanes(0.0f, 0.0f, 1.0f, 1.0f);
      // Depth at each sample, tested against that sample's plane.
      F4 z[16], stored[16];
      unsigned passed[16], any = 0;
      for (int s = 0; s < samples; ++s) {
        passed[s] = covered[s];
        if (!covered[s]) continue;
        const float ox = float(pattern[std::size_t(s)].x) * (1.0f / 16.0f),
                    oy = float(pattern[std::size_t(s)].y) * (1.0f / 16.0f);
        const F4 zs =
            (F4::splat(p.z[0]) + F4::splat(p.z[1]) * (dxk + F4::splat(ox))) + F4::splat(p.z[2]) * (dyk + F4::splat(oy));
        z[s] = simd::min(simd::max(zs, F4::splat(rc.min_depth)), F4::splat(rc.max_depth));
        if (rc.depth.test) {
          unsigned pass_bits = 0;
          if (inside) {
            stored[s] = fb.depth_quad(fb.sample_site(site, s));
            pass_bits = depth_pass_mask<kDepthFunc>(z[s], stored[s]);
          } else {
            std::array<float, 4> zl;
            z[s].store(zl);
            for (int k = 0; k < 4; ++k) {
              const float st = (covered[s] >> k) & 1u ? fb.sample_depth(qx + (k & 1), qy + (k >> 1), s) : 0.0f;
              pass_bits |= unsigned(depth_passes(kDepthFunc, zl[std::size_t(k)], st)) << k;
            }
          }
          passed[s] &= pass_bits;
        }
        any |= passed[s];
      }
      if (!any) continue;
      QuadInput<N> q;
      const F4 zc = (F4::splat(p.z[0]) + F4::splat(p.z[1]) * dxk) + F4::splat(p.z[2]) * dyk;
      simd::min(simd::max(zc, F4::splat(rc.min_depth)), F4::splat(rc.max_depth)).store(q.z);
      QuadColor color;
      shade_quad_pixels<N>(p, qx, qy, dxk, dyk, any, ps, q, color);
      invocations += kQuadLanes[any];
      for (int s = 0; s < samples; ++s) {
        if (!passed[s]) continue;
        const Framebuffer::QuadSite ss = fb.sample_site(site, s);
        fb.write_quad(ss, inside, passed[s], color.c);
        if (rc.depth.test && rc.depth.write) {
          if (inside) {
            fb.set_depth_quad(ss, simd::select(passed[s], stored[s], z[s]));
          } else {
            std::array<float, 4> zl;
            z[s].store(zl);
            for (int k = 0; k < 4; ++k)
              if (passed[s] & (1u << k)) fb.set_sample_depth(qx + (k & 1), qy + (k >> 1), s, zl[std::size_t(k)]);
          }
        }
      }
    }
  }
  return invocations;
}

template <std::size_t N, class Ps, CompareFunc kDepthFunc, bool kMultisampled, class ForEach>
std::uint64_t rasterize_tile_with(const ForEach& for_each_primitive, int tx0, int ty0, int tx1, int ty1, const Ps& ps,
                                  const RasterContext& rc, Framebuffer& fb) {
  std::uint64_t invocations = 0;
  for_each_primitive([&](const ScreenPrimitive<N>& p) {
    switch (p.kind) {
      case PrimitiveKind::triangle:
        if constexpr (kMultisampled)
          invocations += rasterize_triangle_multisample<N, Ps, kDepthFunc>(p, tx0, ty0, tx1, ty1, ps, rc, fb);
        else
          invocations += rasterize_triangle_with<N, Ps, kDepthFunc>(p, tx0, ty0, tx1, ty1, ps, rc, fb);
        break;
      case PrimitiveKind::line: invocations += rasterize_line<N>(p, tx0, ty0, tx1, ty1, ps, rc, fb); break;
      case PrimitiveKind::point: invocations += rasterize_point<N>(p, tx0, ty0, tx1, ty1, ps, rc, fb); break;
    }
  });
  return invocations;
}

}  // namespace detail

// Rasterizes primitives, in draw order, inside the tile [tx0, tx1) x [ty0, ty1), which only this thread
// writes: for_each_primitive(visit) calls visit(const ScreenPrimitive<N>&) for each of them. Returns
// the pixel shader invocations. The depth function is chosen once per tile, as a template argument,
// so the per-pixel test compiles to one comparison.
template <std::size_t N, class Ps, class ForEach>
std::uint64_t rasterize_tile(const ForEach& for_each_primitive, int tx0, int ty0, int tx1, int ty1, const Ps& ps,
                             const RasterContext& rc, Framebuffer& fb) {
  // The sample count too is chosen once per tile: the single-sampled loop has no multisample branch.
  const bool multisampled = fb.samples() > 1;
  const auto with = [&](auto func) {
    return multisampled ? detail::rasterize_tile_with<N, Ps, decltype(func)::value, true>(for_each_primitive, tx0, ty0,
                                                                                          tx1, ty1, ps, rc, fb)
                        : detail::rasterize_tile_with<N, Ps, decltype(func)::value, false>(for_each_primitive, tx0, ty0,
                                                                                           tx1, ty1, ps, rc, fb);
  };
  using F = CompareFunc;
  switch (rc.depth.func) {
    case F::never: return with(std::integral_constant<F, F::never>{});
    case F::less: return with(std::integral_constant<F, F::less>{});
    case F::equal: return with(std::integral_constant<F, F::equal>{});
    case F::less_equal: return with(std::integral_constant<F, F::less_equal>{});
    case F::greater: return with(std::integral_constant<F, F::greater>{});
    case F::not_equal: return with(std::integral_constant<F, F::not_equal>{});
    case F::greater_equal: return with(std::integral_constant<F, F::greater_equal>{});
    case F::always: return with(std::integral_constant<F, F::always>{});
  }
  return 0;
}

}  // namespace tessera
