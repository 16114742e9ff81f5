// Frustum culling of whole patches, from a conservative bound, in the hull shader: a culled patch
// gets zero tessellation factors, which D3D11 (and ts::process_factors) takes as "cull the patch".
//
// Contract: outside(points, count) is true only when every point within `growth` of the convex hull
// of the given points lies strictly outside one clip plane of `view_projection` (D3D's clip volume
// -w <= x, y <= w, 0 <= z <= w, with z moved by -z_bias * w as clip_position() does). Every patch
// kind Tessera draws lies in the convex hull of its control points (Bezier and Gregory points, PN
// points, or for `exact` the 1-ring of the face, whose limit surface is a convex combination of it),
// and the displaced surface lies within the displacement bound of it; the clipper would then reject
// every triangle of the patch, so culling it never changes a pixel. Each plane is tested as a linear
// function of the world position, so the test holds for points behind the eye too.
//
// The growth also covers rounding: the domain shader's float evaluation may leave the exact hull by
// a few ulps of the coordinates, so the bound is grown by 2^-12 of the points' largest coordinate.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>

#include <glm/glm.hpp>

#include "shaders_cpp/cage/bounding_box.h"

namespace tessera {

// --cull: no test, one of them, or both (the frustum test here, the back-patch test of
// back_patch_cull.h); neither can change a pixel.
enum class PatchCullMode : std::uint8_t { none, frustum, backface, all };
std::optional<PatchCullMode> parse_patch_cull_mode(std::string_view name);
const char* to_string(PatchCullMode m);
inline bool culls_frustum(PatchCullMode m) { return m == PatchCullMode::frustum || m == PatchCullMode::all; }
inline bool culls_backface(PatchCullMode m) { return m == PatchCullMode::backface || m == PatchCullMode::all; }

// D3D's clip volume (-w <= x, y <= w, 0 <= z <= w, z moved by -z_bias * w as clip_position() does) as six
// planes, each a linear function of the world position (x, y, z, 1) that is >= 0 inside, in double;
// `w` is the clip-space w row.
struct ClipPlanes {
  std::array<glm::dvec4, 6> planes;
  glm::dvec4 w;
};
inline ClipPlanes clip_planes(const glm::mat4& view_projection, float z_bias) {
  std::array<glm::dvec4, 4> row;
  for (int i = 0; i < 4; ++i)
    row[std::size_t(i)] =
        glm::dvec4(view_projection[0][i], view_projection[1][i], view_projection[2][i], view_projection[3][i]);
  row[2] -= double(z_bias) * row[3];
  return {{row[3] + row[0], row[3] - row[0], row[3] + row[1], row[3] - row[1], row[2], row[3] - row[2]}, row[3]};
}

struct FrustumCull {
  bool enabled = false;
  glm::mat4 view_projection{1.0f};
  float z_bias = 0.0f;
  float growth = 0.0f;  // the displacement bound, object units

  template <class PointAt>
  bool outside(int count, PointAt&& point_at) const {
    if (!enabled || count <= 0) return false;
    // In double: no rounding question in the test.
    const std::array<glm::dvec4, 6> planes = clip_planes(view_projection, z_bias).planes;
    double extent = 0.0;
    for (int i = 0; i < count; ++i) {
      const glm::vec3 p = point_at(i);
      extent = std::max({extent, std::abs(double(p.x)), std::abs(double(p.y)), std::abs(double(p.z))});
    }
    if (!std::isfinite(extent)) return false;  // NaN control points: the pipeline's own rules apply
    const double grow = double(growth) + extent * 0x1p-12 + 0x1p-20;
    for (const glm::dvec4& plane : planes) {
      const double reach = grow * glm::length(glm::dvec3(plane));
      bool all_out = true;
      for (int i = 0; i < count && all_out; ++i) {
        const glm::dvec3 p(point_at(i));
        all_out = glm::dot(glm::dvec3(plane), p) + plane.w + reach < 0.0;
      }
      if (all_out) return true;
    }
    return false;
  }
};

}  // namespace tessera
