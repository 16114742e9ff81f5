// Back-patch culling: a hull shader may prove that every triangle its patch will produce faces one
// way on screen; when the rasterizer would cull every one of them, the pipeline skips the patch before
// its domain shader runs. An extension of D3D11 that changes no pixel, only work.
//
// Contract
// - A hull shader opts in by giving its PatchConstants a member `OrientationBound orientation`. The
//   shader claims: for every triangle (a, b, c) of a pattern, with d1 = b - a = (s1, t1),
//   d2 = c - a = (s2, t2) in the domain, the screen-space signed area (window space, y down, positive =
//   clockwise) of the rasterized triangle -- after the domain shader's rounding, projection, snapping
//   and any clipping -- has the sign  `screen_sign` * sign(s1 t2 - t1 s2)  whenever
//       floor - cubic * k_cubic - quartic * k_quartic - perimeter * k_perimeter
//             - product * k_product - inverse * k_inverse  >  0
//   with the pattern's shape terms (tessellator/pattern_shape.h). Everything geometric (the surface,
//   the camera, rounding) is the shader's to bound; the pipeline only combines the bound with the
//   pattern and the rasterizer state. `screen_sign` 0 (the default) claims nothing.
// - The pipeline skips a patch only when the claim holds for its pattern and the rasterizer culls
//   every triangle of that orientation: solid fill (wireframe edges are drawn unculled) and a cull mode
//   that removes them. A skipped patch adds no DS invocation and no primitive to the statistics;
//   DrawReport::patches_back_culled counts it.
#pragma once

#include <cstdint>

#include "pipeline/setup_context.h"
#include "tessellator/pattern_shape.h"

namespace tessera {

struct OrientationBound {
  std::int8_t screen_sign = 0;
  double floor = 0, k_cubic = 0, k_quartic = 0, k_perimeter = 0, k_product = 0, k_inverse = 0;

  // The claim's condition without the pattern (every shape term is >= 0): a bound that fails here
  // fails for every pattern, and the pipeline skips computing the shape.
  bool may_hold() const { return screen_sign != 0 && floor > 0; }
  bool holds(const ts::PatternShape& s) const {
    if (screen_sign == 0 || !s.consistent) return false;
    const double slack = floor - s.cubic * k_cubic - s.quartic * k_quartic - s.perimeter * k_perimeter -
                         s.product * k_product - s.inverse * k_inverse;
    return slack > 0;
  }
};

// The screen orientation of every triangle of a pattern under a bound that holds: +1 clockwise.
inline int pattern_screen_sign(const OrientationBound& b, const ts::PatternShape& s) {
  return int(b.screen_sign) * s.orientation;
}

// Whether the rasterizer culls every triangle of triangles with this screen orientation.
inline bool rasterizer_culls(const SetupContext& c, int screen_sign) {
  if (c.fill != FillMode::solid || screen_sign == 0) return false;
  const bool front = (screen_sign > 0) != c.front_ccw;  // as setup_snapped_triangle decides
  return (c.cull == CullMode::back && !front) || (c.cull == CullMode::front && front);
}

namespace detail {
template <class PC>
concept HasOrientationBound = requires(const PC& pc) {
  { pc.orientation } -> std::convertible_to<OrientationBound>;
};
}  // namespace detail

}  // namespace tessera
