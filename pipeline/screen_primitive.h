// The record setup writes and the rasterizer reads: a primitive in window space (16.8 fixed point
// positions or 32-bit edge functions, plane equations, the covered pixel box), and the constants that
// bound it. Plain data; setup (primitive_setup.h, triangle_list_setup.h) fills it, raster_tile.h
// consumes it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace tessera {

inline constexpr int kSubpixelBits = 8;
inline constexpr int kSubpixelOne = 1 << kSubpixelBits;

enum class PrimitiveKind : std::uint8_t { triangle, line, point };

// A primitive in window space, ready to rasterize. Triangles are stored with positive signed area
// (vertices 1 and 2 swapped if needed), so edge functions are >= 0 inside.
//
// Lines and points keep per-vertex values in z, inv_w and attributes. Triangles keep plane equations
// there instead, computed once at setup: value(x, y) = [0] + [1] * (x - origin_x) + [2] * (y - origin_y)
// in pixels, for window depth, for 1/w, and for each attribute divided by w (perspective-correct
// interpolation divides the attribute plane by the 1/w plane per pixel).
//
// A triangle whose vertex box is small enough that every edge-function value the rasterizer evaluates
// fits in 32 bits (`edges32`, kEdges32MaxExtent; nearly all of them) keeps its edge functions, set up
// once here rather than per tile, in place of its vertices (the rasterizer needs nothing else of them,
// and the record stays as small as it was: setup writes and the rasterizer reads it through memory).
// Other triangles keep their vertices; the rasterizer sets their edges up in 64-bit integers.
struct VertexPositions {
  std::array<std::int32_t, 3> x, y;  // 16.8 fixed-point window coordinates
};
// Edge i runs from vertex i to vertex i + 1 (top-left bias included); its value at the centre of pixel
// (min_x, min_y) is ref[i], and it changes by -dy[i] * 256 per pixel right and dx[i] * 256 per pixel down
// (dx, dy: vertex i + 1 minus vertex i, at most kEdges32MaxExtent in magnitude).
struct SmallTriangleEdges {
  std::array<std::int16_t, 4> dx, dy;  // [3] unused: dx and dy are one 16-byte store from setup's lanes
  std::array<std::int32_t, 3> ref;
  // Edge i's steps for one pixel right and one pixel down, and its value at the centre of pixel
  // (min_x + ox, min_y + oy), modulo 2^32: exact wherever the rasterizer evaluates it.
  std::int32_t step_x(int i) const { return -std::int32_t(dy[std::size_t(i)]) * kSubpixelOne; }
  std::int32_t step_y(int i) const { return std::int32_t(dx[std::size_t(i)]) * kSubpixelOne; }
  std::int32_t value_at(int i, int ox, int oy) const {
    return std::int32_t(std::uint32_t(ref[std::size_t(i)]) + std::uint32_t(step_x(i)) * std::uint32_t(ox) +
                        std::uint32_t(step_y(i)) * std::uint32_t(oy));
  }
};
template <std::size_t N>
struct ScreenPrimitive {
  union {
    VertexPositions xy{};      // lines, points, triangles without edges32
    SmallTriangleEdges edges;  // triangles with edges32
  };
  std::array<float, 3> z{};                          // window depth (viewport-mapped), or its plane
  std::array<float, 3> inv_w{};                      // 1/w, or its plane
  std::array<std::array<float, N>, 3> attributes{};  // per vertex, or planes: attributes[j][a] = coefficient j of a
  float origin_x = 0, origin_y = 0;                  // triangles: where the planes are anchored (vertex 0), in pixels
  std::int32_t min_x = 0, min_y = 0, max_x = -1, max_y = -1;  // covered pixel box, inclusive
  std::uint32_t primitive_id = 0;
  PrimitiveKind kind = PrimitiveKind::triangle;
  bool front_face = true;
  bool edges32 = false;
  // Triangles whose box holds at most 4x4 pixel centres (nearly all of them from factor 16 up): bit
  // dx + 8 * dy is set when pixel (min_x + dx, min_y + dy) lies in the box and is covered, as setup
  // found when it tested those centres; the rasterizer shades these pixels without walking edges. 0
  // otherwise (setup drops a small-box triangle that covers nothing). Rows are 8 bits apart, as the
  // rasterizer's quad grid (BoxQuads) lays them out, so it only shifts them into place.
  std::uint32_t box_coverage = 0;
};

// The largest vertex box extent (16.8 units, either axis) of a triangle whose edge functions the
// rasterizer evaluates in 32-bit lanes. Every pixel centre it evaluates lies at most one pixel (256)
// outside the box (a quad's lane beside the first or last covered centre), so
// |edge| <= ext_y * (ext_x + 256) + ext_x * (ext_y + 256) + 1 < 2^31.
inline constexpr std::int32_t kEdges32MaxExtent = 32767 - 256;

// The largest pixel box (either side) whose covered centres setup finds and keeps in the record
// (ScreenPrimitive::box_coverage).
inline constexpr std::int32_t kSmallBoxPixels = 4;

}  // namespace tessera
