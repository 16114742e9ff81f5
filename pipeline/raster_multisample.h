// A triangle on a multisampled target: coverage and depth per sample of the standard pattern, shading
// per pixel.
#pragma once

#include <cstdint>
#include <span>

#include "pipeline/pixel_shading.h"
#include "pipeline/sample_pattern.h"
#include "pipeline/triangle_coverage.h"

namespace tessera::detail {

// The covered samples of a quad: bit k of covered[s] is sample s of pixel k (k = 0 (x, y), 1 (x + 1, y),
// 2 (x, y + 1), 3 (x + 1, y + 1)).
struct SampleCoverage {
  unsigned covered[16] = {};
  unsigned any = 0;  // the union over samples
};

// The pixels of the quad at (qx, qy) (bit k as in SampleCoverage) inside the box [x_begin, x_end] x
// [y_begin, y_end].
inline unsigned quad_in_box(int qx, int qy, int x_begin, int x_end, int y_begin, int y_end) {
  unsigned box = 0xFu;
  if (qx < x_begin) box &= 0xAu;
  if (qx + 1 > x_end) box &= 0x5u;
  if (qy < y_begin) box &= 0xCu;
  if (qy + 1 > y_end) box &= 0x3u;
  return box;
}

// The pixel shader on the pixels `lanes` of a multisampled quad, at their centres (dxk, dyk: their
// offsets from the primitive's origin), seeing the centre's depth clamped to the viewport's range.
template <std::size_t N, class Ps>
[[gnu::always_inline]] inline QuadColor shade_quad_centres(const ScreenPrimitive<N>& p, int qx, int qy, simd::F4 dxk,
                                                           simd::F4 dyk, unsigned lanes, const Ps& ps,
                                                           const RasterContext& rc) {
  using simd::F4;
  QuadInput<N> q;
  const F4 zc = (F4::splat(p.z[0]) + F4::splat(p.z[1]) * dxk) + F4::splat(p.z[2]) * dyk;
  simd::min(simd::max(zc, F4::splat(rc.min_depth)), F4::splat(rc.max_depth)).store(q.z);
  QuadColor color;
  shade_quad_pixels<N>(p, qx, qy, dxk, dyk, lanes, ps, q, color);
  return color;
}

// The largest box, in quads, rasterize_multisample_small takes. Up to 16 quads its test of every
// quad costs less than the 8x8 blocks' grids and regrouping (at factor 16 the torus's triangles at
// 1080p are about 2 pixels; with 4 quads, 23 % of its 4x raster went to the blocks).
inline constexpr int kSmallBoxQuads = 16;

#if defined(__AVX2__)
// A multisampled quad's samples in lanes of eight, as the target stores them (framebuffer.h: sample s of
// pixel k at 4 s + k, two samples per vector): each lane's pixel offset in the quad and its sample's
// offset from the pixel centre, in pixels (the same floats as shade_multisample_quad's per-sample
// arithmetic).
// The same offsets in subpixels for the edge functions, the pixel's (0 or kSubpixelOne) plus the
// sample's (1/16 pixel times 16, as rasterize_multisample_edges32's offsets), as 16-bit pairs (x, y):
// one _mm256_madd_epi16 with an edge's (-dy, dx) gives each lane's change of that edge from the quad's
// top-left pixel centre (at most 384 times a 16-bit step: exact in 32 bits).
struct SampleLanes {
  alignas(32) float kx[8], ky[8];
  alignas(32) float ox[64], oy[64];
  alignas(32) std::int16_t xy[128];  // lane j: xy[2 j] = x, xy[2 j + 1] = y
};
constexpr SampleLanes make_sample_lanes(std::span<const SampleOffset> pattern) {
  SampleLanes l{};
  for (int i = 0; i < 8; ++i) l.kx[i] = float(i & 1), l.ky[i] = float((i >> 1) & 1);
  for (std::size_t s = 0; s < pattern.size(); ++s)
    for (std::size_t k = 0; k < 4; ++k) {
      const std::size_t j = 4 * s + k;
      l.ox[j] = float(pattern[s].x) * (1.0f / 16.0f);
      l.oy[j] = float(pattern[s].y) * (1.0f / 16.0f);
      l.xy[2 * j] = std::int16_t(int(k & 1) * kSubpixelOne + 16 * pattern[s].x);
      l.xy[2 * j + 1] = std::int16_t(int(k >> 1) * kSubpixelOne + 16 * pattern[s].y);
    }
  return l;
}
inline constexpr SampleLanes kSampleLanes2 = make_sample_lanes(kSamples2), kSampleLanes4 = make_sample_lanes(kSamples4),
                             kSampleLanes8 = make_sample_lanes(kSamples8),
                             kSampleLanes16 = make_sample_lanes(kSamples16);
inline const SampleLanes& sample_lanes(int samples) {
  return samples == 2 ? kSampleLanes2 : samples == 4 ? kSampleLanes4 : samples == 8 ? kSampleLanes8 : kSampleLanes16;
}

// depth_pass_mask on eight lanes: bit i for lane i.
template <CompareFunc kDepthFunc>
[[gnu::always_inline]] inline unsigned depth_pass_mask8(__m256 z, __m256 stored) {
  switch (kDepthFunc) {
    case CompareFunc::never: return 0;
    case CompareFunc::less: return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(z, stored, _CMP_LT_OS)));
    case CompareFunc::equal: return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(z, stored, _CMP_EQ_OQ)));
    case CompareFunc::less_equal: return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(z, stored, _CMP_LE_OS)));
    case CompareFunc::greater: return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(stored, z, _CMP_LT_OS)));
    case CompareFunc::not_equal: return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(z, stored, _CMP_NEQ_UQ)));
    case CompareFunc::greater_equal: return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(stored, z, _CMP_LE_OS)));
    case CompareFunc::always: return 0xFFu;
  }
  return 0;
}

// All ones in lane i where bit i of `bits` (0..255) is set.
[[gnu::always_inline]] inline __m256i lane_mask8(unsigned bits) {
  const __m256i select = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(bits)), select), select);
}

// shade_multisample_quad for a quad inside an RGBA8 target: two samples (eight depths, eight colours)
// per vector, tested and written with one compare and one blend each, instead of sample by sample (the
// same values: each lane's depth is the same expression, and the colours are the same conversion).
// `covered[h]`: bit i for lane i of vector h (sample 2 h + i / 4, pixel i % 4).
template <std::size_t N, class Ps, CompareFunc kDepthFunc>
[[gnu::always_inline]] inline std::uint64_t shade_multisample_quad8(const ScreenPrimitive<N>& p, int qx, int qy,
                                                                    const unsigned* covered, int samples, const Ps& ps,
                                                                    const RasterContext& rc, Framebuffer& fb) {
  using simd::F4;
  const SampleLanes& lanes = sample_lanes(samples);
  const Framebuffer::QuadSite site = fb.quad_site(qx, qy);
  float* depth = fb.quad_samples_depth(site);
  std::uint8_t* color = fb.quad_samples_rgba8(site);
  const float fx = float(qx) + 0.5f - p.origin_x, fy = float(qy) + 0.5f - p.origin_y;
  const __m256 px = _mm256_add_ps(_mm256_set1_ps(fx), _mm256_load_ps(lanes.kx)),
               py = _mm256_add_ps(_mm256_set1_ps(fy), _mm256_load_ps(lanes.ky));
  const __m256 z0 = _mm256_set1_ps(p.z[0]), z1 = _mm256_set1_ps(p.z[1]), z2 = _mm256_set1_ps(p.z[2]);
  const __m256 min_depth = _mm256_set1_ps(rc.min_depth), max_depth = _mm256_set1_ps(rc.max_depth);
  const int vectors = samples / 2;
  __m256 z[8], stored[8];
  unsigned passed[8], any = 0;
  for (int h = 0; h < vectors; ++h) {
    // No branch on the coverage: the micro-triangles' patterns are unpredictable, and a vector
    // without a covered lane costs less to test than a mispredicted skip.
    // passed[h] is stored once: stored as a copy of covered[h] and then masked, the copies became one
    // call to memcpy, with every vector register spilled around it.
    const __m256 x = _mm256_add_ps(px, _mm256_load_ps(lanes.ox + 8 * h)),
                 y = _mm256_add_ps(py, _mm256_load_ps(lanes.oy + 8 * h));
    const __m256 zs = _mm256_add_ps(_mm256_add_ps(z0, _mm256_mul_ps(z1, x)), _mm256_mul_ps(z2, y));
    z[h] = _mm256_min_ps(max_depth, _mm256_max_ps(min_depth, zs));  // simd::min(simd::max(zs, lo), hi)
    stored[h] = rc.depth.test ? _mm256_loadu_ps(depth + 8 * h) : z[h];
    const unsigned pass = rc.depth.test ? covered[h] & depth_pass_mask8<kDepthFunc>(z[h], stored[h]) : covered[h];
    passed[h] = pass;
    any |= (pass | (pass >> 4)) & 0xFu;
  }
  if (!any) return 0;
  const F4 dxk = F4::splat(fx) + F4::lanes(0.0f, 1.0f, 0.0f, 1.0f),
           dyk = F4::splat(fy) + F4::lanes(0.0f, 0.0f, 1.0f, 1.0f);
  const QuadColor shaded = shade_quad_centres<N>(p, qx, qy, dxk, dyk, any, ps, rc);
  const __m128i rgba = Framebuffer::quad_to_rgba8(shaded.c);
  const __m256i both = _mm256_set_m128i(rgba, rgba);  // the quad's four pixels for two samples
  const bool write_depth = rc.depth.test && rc.depth.write;
  for (int h = 0; h < vectors; ++h) {
    // A masked store: the colours are written without being read first (a blend with the loaded
    // line waited on that load, 7 % of the 4x raster's samples).
    const __m256i m = lane_mask8(passed[h]);
    _mm256_maskstore_epi32(reinterpret_cast<int*>(color + 32 * h), m, both);
    if (write_depth) _mm256_storeu_ps(depth + 8 * h, _mm256_blendv_ps(stored[h], z[h], _mm256_castsi256_ps(m)));
  }
  return kQuadLanes[any];
}
#endif

// Depth test, one pixel shader call and the writes of one quad whose covered samples are `c`.
template <std::size_t N, class Ps, CompareFunc kDepthFunc>
[[gnu::always_inline]] inline std::uint64_t shade_multisample_quad(const ScreenPrimitive<N>& p, int qx, int qy,
                                                                   const SampleCoverage& c,
                                                                   std::span<const SampleOffset> pattern, const Ps& ps,
                                                                   const RasterContext& rc, Framebuffer& fb) {
  using simd::F4;
  const int samples = int(pattern.size());
  const bool inside = fb.quad_inside(qx, qy);
#if defined(__AVX2__)
  if (inside && samples > 1 && fb.format() == ColorFormat::rgba8_unorm) {
    unsigned covered[8];
    for (int h = 0; h < samples / 2; ++h) covered[h] = c.covered[2 * h] | (c.covered[2 * h + 1] << 4);
    return shade_multisample_quad8<N, Ps, kDepthFunc>(p, qx, qy, covered, samples, ps, rc, fb);
  }
#endif
  const Framebuffer::QuadSite site = fb.quad_site(qx, qy);
  const float fx = float(qx) + 0.5f - p.origin_x, fy = float(qy) + 0.5f - p.origin_y;
  const F4 dxk = F4::splat(fx) + F4::lanes(0.0f, 1.0f, 0.0f, 1.0f),
           dyk = F4::splat(fy) + F4::lanes(0.0f, 0.0f, 1.0f, 1.0f);
  // Depth at each sample, tested against that sample's stored depth.
  F4 z[16], stored[16];
  unsigned passed[16], any = 0;
  for (int s = 0; s < samples; ++s) {
    passed[s] = c.covered[s];
    if (!c.covered[s]) continue;
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
          const float st = (c.covered[s] >> k) & 1u ? fb.sample_depth(qx + (k & 1), qy + (k >> 1), s) : 0.0f;
          pass_bits |= unsigned(depth_passes(kDepthFunc, zl[std::size_t(k)], st)) << k;
        }
      }
      passed[s] &= pass_bits;
    }
    any |= passed[s];
  }
  if (!any) return 0;
  const QuadColor color = shade_quad_centres<N>(p, qx, qy, dxk, dyk, any, ps, rc);
#if defined(__SSE2__)
  // One conversion of the shaded colours for every sample it goes to.
  const bool packed = inside && fb.format() == ColorFormat::rgba8_unorm;
  const __m128i px = packed ? Framebuffer::quad_to_rgba8(color.c) : _mm_setzero_si128();
#endif
  for (int s = 0; s < samples; ++s) {
    if (!passed[s]) continue;
    const Framebuffer::QuadSite ss = fb.sample_site(site, s);
#if defined(__SSE2__)
    if (packed)
      fb.write_quad_rgba8(ss, passed[s], px);
    else
#endif
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
  return kQuadLanes[any];
}

#if defined(__AVX2__)
// A triangle with edges32 whose box spans at most kSmallBoxQuads quads, on an RGBA8 target: each quad's
// samples tested at once in the lanes the target stores them in (two samples, eight points, per
// vector), the edge values at the quad plus each lane's pixel and sample offset: the same integers as
// the 8x8 blocks below, without their per-sample grids and the bits' regrouping per quad (about 5 % of
// the torus's 4x raster time, its micro-triangles about 2 pixels). The sample count is a template
// argument: the per-vector loops here and in the inlined quad shader unroll, and their masks and depths
// stay in registers.
template <std::size_t N, class Ps, CompareFunc kDepthFunc, int kSamples>
std::uint64_t rasterize_multisample_small(const ScreenPrimitive<N>& p, int x_begin, int x_end, int y_begin, int y_end,
                                          const Ps& ps, const RasterContext& rc, Framebuffer& fb) {
  constexpr int samples = kSamples, vectors = kSamples / 2;
  const SampleLanes& lanes = sample_lanes(samples);
  // Per edge and vector: each lane's change from the quad's top-left pixel centre, -dy x + dx y.
  __m256i lane_step[3][8];
  for (int i = 0; i < 3; ++i) {
    // -dy fits in 16 bits: setup keeps edges32 only for extents within kEdges32MaxExtent.
    const std::uint32_t pair =
        std::uint16_t(-p.edges.dy[std::size_t(i)]) | (std::uint32_t(std::uint16_t(p.edges.dx[std::size_t(i)])) << 16);
    const __m256i steps = _mm256_set1_epi32(std::int32_t(pair));
    for (int h = 0; h < vectors; ++h)
      lane_step[i][h] =
          _mm256_madd_epi16(steps, _mm256_load_si256(reinterpret_cast<const __m256i*>(lanes.xy + 16 * h)));
  }
  std::uint64_t invocations = 0;
  for (int qy = y_begin & ~1; qy <= y_end; qy += 2)
    for (int qx = x_begin & ~1; qx <= x_end; qx += 2) {
      const unsigned box = quad_in_box(qx, qy, x_begin, x_end, y_begin, y_end);
      const unsigned box8 = box | (box << 4);
      __m256i at[3];
      for (int i = 0; i < 3; ++i) at[i] = _mm256_set1_epi32(p.edges.value_at(i, qx - p.min_x, qy - p.min_y));
      unsigned covered[8], any = 0;
      for (int h = 0; h < vectors; ++h) {
        const __m256i any_negative = _mm256_or_si256(
            _mm256_or_si256(_mm256_add_epi32(at[0], lane_step[0][h]), _mm256_add_epi32(at[1], lane_step[1][h])),
            _mm256_add_epi32(at[2], lane_step[2][h]));
        covered[h] = ~unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(any_negative))) & box8;
        any |= covered[h];
      }
      if (any) invocations += shade_multisample_quad8<N, Ps, kDepthFunc>(p, qx, qy, covered, samples, ps, rc, fb);
    }
  return invocations;
}

// A triangle with edges32 (setup kept its 32-bit edge functions; the box is small enough that every
// sample of it fits, kEdges32MaxExtent) in blocks of 8x8 pixels from quad-aligned corners: each sample's
// coverage of a block is grid_coverage with the edges moved by the sample's offset, an exact integer
// (offset in 1/16 pixel times 16 subpixel units times dx or dy). The same integers as the 64-bit edge
// functions at the same points, so the same samples are covered.
template <std::size_t N, class Ps, CompareFunc kDepthFunc>
std::uint64_t rasterize_multisample_edges32(const ScreenPrimitive<N>& p, int x_begin, int x_end, int y_begin, int y_end,
                                            std::span<const SampleOffset> pattern, const Ps& ps,
                                            const RasterContext& rc, Framebuffer& fb) {
  const int samples = int(pattern.size());
  std::int32_t offset[16][3];  // sample s's edge i, minus its pixel centre's
  for (int s = 0; s < samples; ++s)
    for (int i = 0; i < 3; ++i)
      offset[s][i] = -std::int32_t(p.edges.dy[std::size_t(i)]) * (16 * pattern[std::size_t(s)].x) +
                     std::int32_t(p.edges.dx[std::size_t(i)]) * (16 * pattern[std::size_t(s)].y);
  std::uint64_t invocations = 0;
  for (int by = y_begin & ~1; by <= y_end; by += 8)
    for (int bx = x_begin & ~1; bx <= x_end; bx += 8) {
      BoxQuads keep(~std::uint64_t(0));
      keep.keep(x_begin - bx, x_end + 1 - bx, y_begin - by, y_end + 1 - by);
      const int rows = std::min(8, y_end + 1 - by);
      std::uint64_t grid[16];
      std::uint64_t any = 0;
      for (int s = 0; s < samples; ++s) {
        grid[s] = grid_coverage(p.edges, bx - p.min_x, by - p.min_y, rows, offset[s]) & keep.grid;
        any |= grid[s];
      }
      BoxQuads quads(any);
      int i = 0, j = 0;
      SampleCoverage c;
      while (quads.next(i, j, c.any)) {
        const int shift = 16 * j + 2 * i;
        for (int s = 0; s < samples; ++s) {
          const std::uint64_t pair = grid[s] >> shift;
          c.covered[s] = unsigned(pair & 3u) | unsigned((pair >> 6) & 0xCu);
        }
        invocations += shade_multisample_quad<N, Ps, kDepthFunc>(p, bx + 2 * i, by + 2 * j, c, pattern, ps, rc, fb);
      }
    }
  return invocations;
}
#endif

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
  const int x_begin = std::max(p.min_x, tx0), x_end = std::min(p.max_x, tx1 - 1);
  const int y_begin = std::max(p.min_y, ty0), y_end = std::min(p.max_y, ty1 - 1);
  if (x_begin > x_end || y_begin > y_end) return 0;
  const std::span<const SampleOffset> pattern = standard_sample_pattern(fb.samples());
#if defined(__AVX2__)
  // Only AVX2 builds' setup keeps a multisampled triangle's edges32 (triangle_list_setup.h).
  if (p.edges32 && fb.format() == ColorFormat::rgba8_unorm && x_end + 1 < fb.width() && y_end + 1 < fb.height() &&
      ((x_end >> 1) - (x_begin >> 1) + 1) * ((y_end >> 1) - (y_begin >> 1) + 1) <= kSmallBoxQuads) {
    switch (pattern.size()) {
      case 2: return rasterize_multisample_small<N, Ps, kDepthFunc, 2>(p, x_begin, x_end, y_begin, y_end, ps, rc, fb);
      case 4: return rasterize_multisample_small<N, Ps, kDepthFunc, 4>(p, x_begin, x_end, y_begin, y_end, ps, rc, fb);
      case 8: return rasterize_multisample_small<N, Ps, kDepthFunc, 8>(p, x_begin, x_end, y_begin, y_end, ps, rc, fb);
      default: return rasterize_multisample_small<N, Ps, kDepthFunc, 16>(p, x_begin, x_end, y_begin, y_end, ps, rc, fb);
    }
  }
  if (p.edges32)
    return rasterize_multisample_edges32<N, Ps, kDepthFunc>(p, x_begin, x_end, y_begin, y_end, pattern, ps, rc, fb);
#endif
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
    for (int qx = qx0; qx <= x_end; qx += 2) {
      const unsigned mask = quad_in_box(qx, qy, x_begin, x_end, y_begin, y_end);
      const std::int64_t dqx = qx - qx0, dqy = qy - qy0;
      SampleCoverage c;
      for (int s = 0; s < samples; ++s) {
        unsigned covered = 0;
        for (int k = 0; k < 4; ++k) {
          const std::int64_t dx = dqx + (k & 1), dy = dqy + (k >> 1);
          covered |= unsigned(((e0[s][0] + dx * sx[0] + dy * sy[0]) | (e0[s][1] + dx * sx[1] + dy * sy[1]) |
                               (e0[s][2] + dx * sx[2] + dy * sy[2])) >= 0)
                     << k;
        }
        c.covered[s] = covered & mask;
        c.any |= c.covered[s];
      }
      if (c.any) invocations += shade_multisample_quad<N, Ps, kDepthFunc>(p, qx, qy, c, pattern, ps, rc, fb);
    }
  }
  return invocations;
}

}  // namespace tessera::detail
