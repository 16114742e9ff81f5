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
#include "pipeline/sample_pattern.h"
#include "pipeline/screen_primitive.h"
#include "pipeline/setup_context.h"
#include "pipeline/setup_edges.h"
#include "pipeline/setup_planes.h"
#include "pipeline/setup_vertex.h"
#include "pipeline/simd4.h"
#include "pipeline/tile_bins.h"

namespace tessera {

namespace detail {

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

// setup_snapped_triangle on a multisampled target: the box of the pixels whose samples the triangle's
// box may reach (sample_reach: at most half a pixel from their pixel's centre), the edges (or the
// vertices of a large triangle) kept for the rasterizer's per-sample edge tests, no pixel-centre
// rejection. Out of line: single-sampled draws never take it.
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
  const SampleReach r = sample_reach(c.samples);  // in 1/16 pixel: 16 subpixels
  const PixelBox<> box =
      clipped_pixel_box(c, lx - 16 * r.max_x, hx - 16 * r.min_x, ly - 16 * r.max_y, hy - 16 * r.min_y);
  if (box.empty()) return;
  const SetupVertex<N>* const v[3] = {&a, area > 0 ? &b : &d, area > 0 ? &d : &b};
  const std::int32_t vx[3] = {v[0]->x, v[1]->x, v[2]->x}, vy[3] = {v[0]->y, v[1]->y, v[2]->y};
  ScreenPrimitive<N>& p = chunk.append_primitive();
  p.kind = PrimitiveKind::triangle;
  p.min_x = box.min_x, p.max_x = box.max_x, p.min_y = box.min_y, p.max_y = box.max_y;
  // AVX2 builds keep the edges of a triangle small enough in 32 bits, as the lanes of
  // setup_triangle_list do: every sample point lies within a pixel of the vertex box (kEdges32MaxExtent).
#if defined(__AVX2__)
  const bool edges32 = hx - lx <= kEdges32MaxExtent && hy - ly <= kEdges32MaxExtent;
#else
  const bool edges32 = false;
#endif
  if (edges32) {
    store_edges32(p, setup_edges32<N>(v, vx, vy, box, false));
  } else {
    for (int i = 0; i < 3; ++i) {
      p.xy.x[i] = vx[i];
      p.xy.y[i] = vy[i];
    }
  }
  p.edges32 = edges32;
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
