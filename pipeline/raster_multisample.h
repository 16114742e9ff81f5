// A triangle on a multisampled target: coverage and depth per sample of the standard pattern, shading
// per pixel.
#pragma once

#include <cstdint>

#include "pipeline/pixel_shading.h"
#include "pipeline/sample_pattern.h"
#include "pipeline/triangle_coverage.h"

namespace tessera::detail {

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

}  // namespace tessera::detail
