// The pixel end of rasterization, shared by every primitive rasterizer: the depth test (early, before
// the pixel shader), the pixel shader in 2x2 quads (perspective-correct attributes, helper pixels for
// derivatives) or per pixel for lines and points (no derivatives), and the output merger.
//
// Depth is interpolated linearly in screen space and clamped to the viewport's depth range;
// attributes are interpolated perspective-correctly (linear in 1/w).
#pragma once

#include <array>
#include <cstdint>

#include "pipeline/framebuffer.h"
#include "pipeline/pipeline_state.h"
#include "pipeline/screen_primitive.h"
#include "pipeline/simd4.h"
#include "pipeline/stage_io.h"

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

// One 2x2 quad of triangle `p` on a single-sampled target, at (qx, qy), whose lanes `covered` (bit k =
// pixel (qx + (k & 1), qy + (k >> 1))) are inside the triangle and the tile: early depth,
// perspective-correct attributes, the pixel shader, the output merger. Returns the pixel shader
// invocations.
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
  const Framebuffer::QuadSite site = inside ? fb.single_sample_quad_site(qx, qy) : Framebuffer::QuadSite{};
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
}  // namespace detail

}  // namespace tessera
