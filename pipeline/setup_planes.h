// Plane equations of a set-up triangle: z, 1/w and each attribute / w as a value at vertex 0 and
// slopes in x and y (pixels), from the snapped positions. One template for every lane type, so the
// per-triangle and the eight-triangle setup (triangle_list_setup.h) run the same expressions.
#pragma once

#include <cstddef>

#include "pipeline/screen_primitive.h"
#include "pipeline/setup_vertex.h"
#include "pipeline/simd4.h"

namespace tessera::detail {

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

}  // namespace tessera::detail
