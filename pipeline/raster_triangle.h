// A triangle on a single-sampled target: D3D11's rules. A centre on an edge is covered only if the
// edge is a top or left edge (the top-left rule), so a mesh of triangles sharing edges covers every
// pixel exactly once. Small boxes are covered as a grid and shaded quad by quad; larger ones walk the
// edge functions (triangle_coverage.h).
#pragma once

#include <cstdint>

#include "pipeline/pixel_shading.h"
#include "pipeline/primitive_setup.h"
#include "pipeline/triangle_coverage.h"

namespace tessera::detail {

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

}  // namespace tessera::detail
