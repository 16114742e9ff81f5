// Primitive assembly's back half: clip-space primitives in, screen-space primitives binned to tiles out.
//
// For each triangle: NaN rejection, trivial rejection against the view volume, guard-band clipping
// (clipper.h), perspective division, the viewport transform, snapping to 16.8 fixed point (D3D11's
// 8 bits of sub-pixel precision), back/front culling on the snapped signed area, the pixel bounding box
// clipped to viewport, scissor and render target, and binning by that box into screen tiles.
// Everything here is a pure function of its inputs, so any thread produces the same bytes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "clipper.h"
#include "pipeline_state.h"
#include "statistics.h"

namespace tessera {

inline constexpr int kSubpixelBits = 8;
inline constexpr int kSubpixelOne = 1 << kSubpixelBits;

enum class PrimitiveKind : std::uint8_t { triangle, line, point };

// A primitive in window space, ready to rasterize. Triangles are stored with positive signed area
// (vertices 1 and 2 swapped if needed), so edge functions are >= 0 inside.
template <std::size_t N>
struct ScreenPrimitive {
  std::array<std::int32_t, 3> x{}, y{};  // 16.8 fixed-point window coordinates
  std::array<float, 3> z{};              // window depth (viewport-mapped)
  std::array<float, 3> inv_w{};          // 1/w, for perspective-correct attributes
  std::array<std::array<float, N>, 3> attributes{};
  std::int32_t min_x = 0, min_y = 0, max_x = -1, max_y = -1;  // covered pixel box, inclusive
  std::uint32_t primitive_id = 0;
  PrimitiveKind kind = PrimitiveKind::triangle;
  bool front_face = true;
};

// Screen tiles: the unit of parallel rasterization.
struct TileGrid {
  int tile_size = 64;
  int columns = 0, rows = 0;
  int count() const { return columns * rows; }
};

// What setup needs to know about the draw, computed once.
struct SetupContext {
  // Viewport transform: window = ndc * scale + offset (y flipped: D3D's y-down window space).
  float scale_x = 0, offset_x = 0, scale_y = 0, offset_y = 0, z_scale = 1, z_offset = 0;
  float min_depth = 0, max_depth = 1;
  GuardBand guard;
  // Pixels that may be written: viewport, scissor and render target intersected (inclusive).
  int clip_min_x = 0, clip_min_y = 0, clip_max_x = -1, clip_max_y = -1;
  CullMode cull = CullMode::back;
  bool front_ccw = false;
  FillMode fill = FillMode::solid;
  TileGrid tiles;
};

SetupContext make_setup_context(const Viewport& vp, const RasterizerState& rs, int target_width, int target_height,
                                int tile_size);

// One chunk of the draw's primitives, in draw order, with per-tile lists of indices into `primitives`.
template <std::size_t N>
struct ChunkBuffer {
  std::vector<ScreenPrimitive<N>> primitives;
  std::vector<std::vector<std::uint32_t>> bins;
  PipelineStatistics statistics;
  StageTimes times;

  void reset(int tile_count) {
    primitives.clear();
    if (bins.size() != std::size_t(tile_count)) bins.assign(std::size_t(tile_count), {});
    for (auto& b : bins) b.clear();
    statistics = {};
    times = {};
  }
  std::size_t capacity_bytes() const {
    std::size_t b = primitives.capacity() * sizeof(ScreenPrimitive<N>) + bins.capacity() * sizeof(bins[0]);
    for (const auto& bin : bins) b += bin.capacity() * sizeof(std::uint32_t);
    return b;
  }
};

namespace detail {

inline std::int32_t snap(float window_coordinate) {
  // Round to nearest even in 1/256 pixel; the guard band bounds the magnitude below 2^23.
  return static_cast<std::int32_t>(std::nearbyint(window_coordinate * float(kSubpixelOne)));
}

// First and last pixel whose centre (p + 0.5) lies in [lo, hi] (16.8 fixed point).
inline std::int32_t first_pixel_at_or_after(std::int32_t lo) {
  // ceil((lo - 128) / 256) with floor division semantics for negatives.
  const std::int32_t t = lo - kSubpixelOne / 2;
  return t >= 0 ? (t + kSubpixelOne - 1) >> kSubpixelBits : -((-t) >> kSubpixelBits);
}
inline std::int32_t last_pixel_at_or_before(std::int32_t hi) {
  return (hi - kSubpixelOne / 2) >> kSubpixelBits;  // arithmetic shift = floor
}

template <std::size_t N>
void to_window(const SetupContext& c, const ClipVertex<N>& v, ScreenPrimitive<N>& out, int slot) {
  const float inv_w = 1.0f / v.position.w;
  const float nx = v.position.x * inv_w, ny = v.position.y * inv_w, nz = v.position.z * inv_w;
  out.x[slot] = snap(nx * c.scale_x + c.offset_x);
  out.y[slot] = snap(ny * c.scale_y + c.offset_y);
  out.z[slot] = nz * c.z_scale + c.z_offset;
  out.inv_w[slot] = inv_w;
  out.attributes[slot] = v.attributes;
}

template <std::size_t N>
void bin(const SetupContext& c, ChunkBuffer<N>& chunk, const ScreenPrimitive<N>& p) {
  const auto index = static_cast<std::uint32_t>(chunk.primitives.size());
  chunk.primitives.push_back(p);
  const int ts = c.tiles.tile_size;
  const int tx0 = p.min_x / ts, tx1 = p.max_x / ts, ty0 = p.min_y / ts, ty1 = p.max_y / ts;
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) chunk.bins[std::size_t(ty * c.tiles.columns + tx)].push_back(index);
}

// Clips the pixel box to what may be written; false if nothing is left.
template <std::size_t N>
bool finish_box(const SetupContext& c, ScreenPrimitive<N>& p, std::int32_t lo_x, std::int32_t hi_x, std::int32_t lo_y,
                std::int32_t hi_y) {
  p.min_x = std::max(first_pixel_at_or_after(lo_x), c.clip_min_x);
  p.max_x = std::min(last_pixel_at_or_before(hi_x), c.clip_max_x);
  p.min_y = std::max(first_pixel_at_or_after(lo_y), c.clip_min_y);
  p.max_y = std::min(last_pixel_at_or_before(hi_y), c.clip_max_y);
  return p.min_x <= p.max_x && p.min_y <= p.max_y;
}

template <std::size_t N>
void setup_line_window(const SetupContext& c, ChunkBuffer<N>& chunk, const ClipVertex<N>& a, const ClipVertex<N>& b,
                       std::uint32_t primitive_id) {
  ScreenPrimitive<N> p;
  p.kind = PrimitiveKind::line;
  p.primitive_id = primitive_id;
  to_window(c, a, p, 0);
  to_window(c, b, p, 1);
  p.x[2] = p.x[1], p.y[2] = p.y[1];
  // A line may light the pixel its end point lies in; widen the box by half a pixel.
  const std::int32_t h = kSubpixelOne / 2;
  if (!finish_box(c, p, std::min(p.x[0], p.x[1]) - h, std::max(p.x[0], p.x[1]) + h, std::min(p.y[0], p.y[1]) - h,
                  std::max(p.y[0], p.y[1]) + h))
    return;
  bin(c, chunk, p);
}

}  // namespace detail

// Triangle: counts one CInvocation and a CPrimitive per emitted triangle; appends to `chunk`.
template <std::size_t N>
void setup_triangle(const SetupContext& c, ChunkBuffer<N>& chunk, const ClipVertex<N>& v0, const ClipVertex<N>& v1,
                    const ClipVertex<N>& v2, std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  // D3D11 discards primitives with a NaN or infinite position coordinate.
  if (!finite_position(v0.position) || !finite_position(v1.position) || !finite_position(v2.position)) return;
  if (view_outcode(v0.position) & view_outcode(v1.position) & view_outcode(v2.position)) return;

  ClipPolygon<N> poly;
  const unsigned needs = clip_outcode(v0.position, c.guard) | clip_outcode(v1.position, c.guard) |
                         clip_outcode(v2.position, c.guard);
  poly.v[0] = v0, poly.v[1] = v1, poly.v[2] = v2;
  poly.count = 3;
  if (needs) clip_polygon(poly, needs, c.guard);

  for (int k = 1; k + 1 < poly.count; ++k) {
    ++chunk.statistics.CPrimitives;
    if (c.fill == FillMode::wireframe) {
      // Only the triangle's own edges: for a clipped polygon, the fan's inner diagonals are not drawn.
      const ClipVertex<N>* t[3] = {&poly.v[0], &poly.v[k], &poly.v[k + 1]};
      for (int e = 0; e < 3; ++e) {
        const bool inner = (e == 0 && k > 1) || (e == 2 && k + 2 < poly.count);
        if (!inner) detail::setup_line_window(c, chunk, *t[e], *t[(e + 1) % 3], primitive_id);
      }
      continue;
    }
    ScreenPrimitive<N> p;
    p.primitive_id = primitive_id;
    detail::to_window(c, poly.v[0], p, 0);
    detail::to_window(c, poly.v[k], p, 1);
    detail::to_window(c, poly.v[k + 1], p, 2);
    const std::int64_t area = std::int64_t(p.x[1] - p.x[0]) * (p.y[2] - p.y[0]) -
                              std::int64_t(p.x[2] - p.x[0]) * (p.y[1] - p.y[0]);
    if (area == 0) continue;  // degenerate after snapping: covers nothing
    // Positive area is clockwise on screen (y down).
    p.front_face = (area > 0) != c.front_ccw;
    if ((c.cull == CullMode::back && !p.front_face) || (c.cull == CullMode::front && p.front_face)) continue;
    if (area < 0) {
      std::swap(p.x[1], p.x[2]);
      std::swap(p.y[1], p.y[2]);
      std::swap(p.z[1], p.z[2]);
      std::swap(p.inv_w[1], p.inv_w[2]);
      std::swap(p.attributes[1], p.attributes[2]);
    }
    const auto [lx, hx] = std::minmax({p.x[0], p.x[1], p.x[2]});
    const auto [ly, hy] = std::minmax({p.y[0], p.y[1], p.y[2]});
    if (!detail::finish_box(c, p, lx, hx, ly, hy)) continue;  // no pixel centre inside the box
    detail::bin(c, chunk, p);
  }
}

template <std::size_t N>
void setup_line(const SetupContext& c, ChunkBuffer<N>& chunk, ClipVertex<N> a, ClipVertex<N> b,
                std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  if (!finite_position(a.position) || !finite_position(b.position)) return;
  if (view_outcode(a.position) & view_outcode(b.position)) return;
  const unsigned needs = clip_outcode(a.position, c.guard) | clip_outcode(b.position, c.guard);
  if (needs && !clip_segment(a, b, needs, c.guard)) return;
  ++chunk.statistics.CPrimitives;
  detail::setup_line_window(c, chunk, a, b, primitive_id);
}

template <std::size_t N>
void setup_point(const SetupContext& c, ChunkBuffer<N>& chunk, const ClipVertex<N>& a, std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  if (!finite_position(a.position) || view_outcode(a.position)) return;
  ++chunk.statistics.CPrimitives;
  ScreenPrimitive<N> p;
  p.kind = PrimitiveKind::point;
  p.primitive_id = primitive_id;
  detail::to_window(c, a, p, 0);
  // A point lights the one pixel it lies in.
  const std::int32_t px = p.x[0] >> kSubpixelBits, py = p.y[0] >> kSubpixelBits;
  p.min_x = std::max(px, c.clip_min_x), p.max_x = std::min(px, c.clip_max_x);
  p.min_y = std::max(py, c.clip_min_y), p.max_y = std::min(py, c.clip_max_y);
  if (p.min_x > p.max_x || p.min_y > p.max_y) return;
  detail::bin(c, chunk, p);
}

}  // namespace tessera
