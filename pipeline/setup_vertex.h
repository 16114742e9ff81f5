// The vertex transform before primitive setup: a clip-space vertex's outcodes, perspective division,
// viewport transform and snapping to 16.8 fixed point (D3D11's 8 bits of sub-pixel precision), done
// once per vertex (per domain point) and shared by every primitive that uses it; four at a time in
// SIMD lanes for a batch, with the scalar form's bits.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "pipeline/clipper.h"
#include "pipeline/screen_primitive.h"
#include "pipeline/setup_context.h"
#include "pipeline/simd4.h"

namespace tessera {

namespace detail {

inline std::int32_t snap(float window_coordinate) {
  // Round to nearest even in 1/256 pixel; the guard band bounds the magnitude below 2^23.
  return static_cast<std::int32_t>(std::nearbyint(window_coordinate * float(kSubpixelOne)));
}

}  // namespace detail

// A vertex as setup sees it: the clip-space vertex, its outcodes, and (when it lies inside the guard
// band, in front of the near plane and behind the far one) its snapped window position. Computed once
// per vertex (per domain point), then shared by every primitive that uses it.
template <std::size_t N>
struct SetupVertex {
  ClipVertex<N> clip;
  std::int32_t x = 0, y = 0;  // 16.8 window position (valid when clip_code == 0)
  float z = 0, inv_w = 0;
  // What a triangle's plane equations interpolate, computed once per vertex and laid out for SIMD loads
  // (setup_snapped_triangle): z, 1/w, each attribute times 1/w, then zeros to a multiple of 4.
  std::array<float, 4 * ((N + 5) / 4)> plane_values{};
  unsigned view_code = 0;  // outside which view-volume planes
  unsigned clip_code = 0;  // outside which clipping planes (near, far, guard band)
  bool finite = true;
};

// A snapped vertex's plane_values, from its z, 1/w and attributes.
template <std::size_t N>
void set_plane_values(SetupVertex<N>& s) {
  s.plane_values[0] = s.z;
  s.plane_values[1] = s.inv_w;
  for (std::size_t a = 0; a < N; ++a) s.plane_values[2 + a] = s.clip.attributes[a] * s.inv_w;
  for (std::size_t a = N + 2; a < s.plane_values.size(); ++a) s.plane_values[a] = 0.0f;
}

// `clipped` marks a vertex the clipper made: it lies on a clipping plane, possibly an ulp outside, and
// is projected regardless.
template <std::size_t N>
SetupVertex<N> make_setup_vertex(const SetupContext& c, const ClipVertex<N>& v, bool clipped = false) {
  SetupVertex<N> s;
  s.clip = v;
  s.finite = finite_position(v.position);
  if (!s.finite) return s;
  s.view_code = view_outcode(v.position);
  s.clip_code = clip_outcode(v.position, c.guard);
  if (s.clip_code == 0 || clipped) {
    const float inv_w = 1.0f / v.position.w;
    s.x = detail::snap(v.position.x * inv_w * c.scale_x + c.offset_x);
    s.y = detail::snap(v.position.y * inv_w * c.scale_y + c.offset_y);
    s.z = v.position.z * inv_w * c.z_scale + c.z_offset;
    s.inv_w = inv_w;
    set_plane_values(s);
  }
  return s;
}

// make_setup_vertex for many vertices (a batch domain shader's output): the same bits, with the
// outcodes, the perspective division, the viewport transform and the snapping of four vertices in SIMD
// lanes (each lane the scalar expression; cvtps2dq rounds to nearest even like std::nearbyint in the
// default rounding mode, and every value it converts lies inside the guard band).
template <std::size_t N>
void make_setup_vertices(const SetupContext& c, std::span<const ClipVertex<N>> in, std::span<SetupVertex<N>> out) {
  std::size_t i = 0;
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps(), sign = _mm_set1_ps(-0.0f);
  const __m128i exponent = _mm_set1_epi32(0x7f800000);
  const auto bit = [](__m128 mask, unsigned b) {
    return _mm_and_si128(_mm_castps_si128(mask), _mm_set1_epi32(int(1u << b)));
  };
  for (; i + 4 <= in.size(); i += 4) {
    __m128 x = _mm_loadu_ps(&in[i].position.x), y = _mm_loadu_ps(&in[i + 1].position.x);
    __m128 z = _mm_loadu_ps(&in[i + 2].position.x), w = _mm_loadu_ps(&in[i + 3].position.x);
    _MM_TRANSPOSE4_PS(x, y, z, w);  // now lane k of x, y, z, w is vertex i + k
    // finite_position: no coordinate has an all-ones exponent.
    const __m128i inf_or_nan =
        _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(x), exponent), exponent),
                                  _mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(y), exponent), exponent)),
                     _mm_or_si128(_mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(z), exponent), exponent),
                                  _mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(w), exponent), exponent)));
    const unsigned finite = ~unsigned(_mm_movemask_ps(_mm_castsi128_ps(inf_or_nan))) & 0xFu;
    // view_outcode
    const __m128 neg_w = _mm_xor_ps(w, sign);
    const __m128i view = _mm_or_si128(
        _mm_or_si128(_mm_or_si128(bit(_mm_cmplt_ps(z, zero), kNear), bit(_mm_cmplt_ps(w, z), kFar)),
                     _mm_or_si128(bit(_mm_cmplt_ps(x, neg_w), kLeft), bit(_mm_cmplt_ps(w, x), kRight))),
        _mm_or_si128(_mm_or_si128(bit(_mm_cmplt_ps(y, neg_w), kBottom), bit(_mm_cmplt_ps(w, y), kTop)),
                     _mm_andnot_si128(_mm_castps_si128(_mm_cmpgt_ps(w, zero)), _mm_set1_epi32(int(1u << kW)))));
    // clip_outcode
    const __m128 gx = _mm_mul_ps(_mm_set1_ps(c.guard.gx), w), gy = _mm_mul_ps(_mm_set1_ps(c.guard.gy), w);
    const __m128i clip = _mm_or_si128(
        _mm_or_si128(_mm_or_si128(bit(_mm_cmplt_ps(z, zero), kNear), bit(_mm_cmplt_ps(_mm_sub_ps(w, z), zero), kFar)),
                     _mm_or_si128(bit(_mm_cmplt_ps(_mm_add_ps(gx, x), zero), kLeft),
                                  bit(_mm_cmplt_ps(_mm_sub_ps(gx, x), zero), kRight))),
        _mm_or_si128(_mm_or_si128(bit(_mm_cmplt_ps(_mm_add_ps(gy, y), zero), kBottom),
                                  bit(_mm_cmplt_ps(_mm_sub_ps(gy, y), zero), kTop)),
                     bit(_mm_cmplt_ps(_mm_sub_ps(w, _mm_set1_ps(kMinClipW)), zero), kW)));
    // Projection and snapping (used only in lanes that are finite with clip code 0).
    const __m128 inv_w = _mm_div_ps(_mm_set1_ps(1.0f), w);
    const __m128 one_pixel = _mm_set1_ps(float(kSubpixelOne));
    const __m128i sx = _mm_cvtps_epi32(_mm_mul_ps(
        _mm_add_ps(_mm_mul_ps(_mm_mul_ps(x, inv_w), _mm_set1_ps(c.scale_x)), _mm_set1_ps(c.offset_x)), one_pixel));
    const __m128i sy = _mm_cvtps_epi32(_mm_mul_ps(
        _mm_add_ps(_mm_mul_ps(_mm_mul_ps(y, inv_w), _mm_set1_ps(c.scale_y)), _mm_set1_ps(c.offset_y)), one_pixel));
    const __m128 sz = _mm_add_ps(_mm_mul_ps(_mm_mul_ps(z, inv_w), _mm_set1_ps(c.z_scale)), _mm_set1_ps(c.z_offset));
    alignas(16) std::int32_t view_codes[4], clip_codes[4], xs[4], ys[4];
    alignas(16) float zs[4], inv_ws[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(view_codes), view);
    _mm_store_si128(reinterpret_cast<__m128i*>(clip_codes), clip);
    _mm_store_si128(reinterpret_cast<__m128i*>(xs), sx);
    _mm_store_si128(reinterpret_cast<__m128i*>(ys), sy);
    _mm_store_ps(zs, sz);
    _mm_store_ps(inv_ws, inv_w);
    for (int k = 0; k < 4; ++k) {
      // Every field written in place (as make_setup_vertex leaves it): assigning a value-initialised
      // SetupVertex went through a stack temporary whose copy stalled on store forwarding.
      SetupVertex<N>& s = out[i + std::size_t(k)];
      const ClipVertex<N>& v = in[i + std::size_t(k)];
      const bool is_finite = (finite >> k) & 1u;
      const bool snapped = is_finite && clip_codes[k] == 0;
      s.clip = v;
      s.finite = is_finite;
      s.view_code = is_finite ? unsigned(view_codes[k]) : 0u;
      s.clip_code = is_finite ? unsigned(clip_codes[k]) : 0u;
      s.x = snapped ? xs[k] : 0;
      s.y = snapped ? ys[k] : 0;
      s.z = snapped ? zs[k] : 0.0f;
      s.inv_w = snapped ? inv_ws[k] : 0.0f;
      if (snapped)
        set_plane_values(s);
      else
        s.plane_values.fill(0.0f);
    }
  }
#endif
  for (; i < in.size(); ++i) out[i] = make_setup_vertex<N>(c, in[i]);
}

}  // namespace tessera
