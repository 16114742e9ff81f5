// Lines and points. Lines: one pixel per step along the major axis at pixel centres, the segment
// half-open at its end (so strips do not light shared end points twice) -- D3D11's aliased line rule
// without the diamond-exit refinements at end points. Points: the one pixel the point lies in. Both
// light every sample of the pixels they light on a multisampled target; their pixel shader sees zero
// derivatives.
#pragma once

#include <cstdint>

#include "pipeline/pixel_shading.h"
#include "pipeline/setup_edges.h"

namespace tessera {

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

}  // namespace tessera
