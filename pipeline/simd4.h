// Four float lanes for the 2x2-quad code (raster_tile.h, quad pixel shaders).
//
// Why a wrapper: GCC does not reliably SLP-vectorize the four-pixel loops once they are unrolled
// into a quad's many small arrays, and each pixel's chain (1/w, attributes, then the shader's sqrt and
// division) is long. With SSE2 (every x86-64) each operation is one packed instruction; elsewhere
// the scalar fallback runs the same four operations lane by lane.
//
// Every operation is a single IEEE-754 operation per lane (add, sub, mul, div, sqrt are correctly
// rounded in both forms), no FMA is formed, and min/max keep std::min/std::max's operand order
// (including which operand a NaN yields), so the packed and scalar forms give identical bits.
#pragma once

#include <array>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#if defined(__SSE4_1__)
#include <smmintrin.h>
#endif
#else
#include <cmath>
#endif

namespace tessera::simd {

#if defined(__SSE2__)

struct F4 {
  __m128 v;
  static F4 splat(float x) { return {_mm_set1_ps(x)}; }
  static F4 lanes(float a, float b, float c, float d) { return {_mm_setr_ps(a, b, c, d)}; }
  static F4 load(const std::array<float, 4>& a) { return {_mm_loadu_ps(a.data())}; }
  void store(std::array<float, 4>& a) const { _mm_storeu_ps(a.data(), v); }
  static F4 load_at(const float* p) { return {_mm_loadu_ps(p)}; }  // p[0..3]
  void store_at(float* p) const { _mm_storeu_ps(p, v); }
  // A 2x2 block of a row-major image: lanes {r0[0], r0[1], r1[0], r1[1]}.
  static F4 load_pairs(const float* r0, const float* r1) {
    return {_mm_loadh_pi(_mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(r0)),
                         reinterpret_cast<const __m64*>(r1))};
  }
  void store_pairs(float* r0, float* r1) const {
    _mm_storel_pi(reinterpret_cast<__m64*>(r0), v);
    _mm_storeh_pi(reinterpret_cast<__m64*>(r1), v);
  }
  friend F4 operator+(F4 a, F4 b) { return {_mm_add_ps(a.v, b.v)}; }
  friend F4 operator-(F4 a, F4 b) { return {_mm_sub_ps(a.v, b.v)}; }
  friend F4 operator*(F4 a, F4 b) { return {_mm_mul_ps(a.v, b.v)}; }
  friend F4 operator/(F4 a, F4 b) { return {_mm_div_ps(a.v, b.v)}; }
  friend F4 operator-(F4 a) { return {_mm_xor_ps(a.v, _mm_set1_ps(-0.0f))}; }  // flips the sign bit, as -x
};
inline F4 sqrt(F4 a) { return {_mm_sqrt_ps(a.v)}; }
// Lane-wise a * b modulo 2^32: SSE4.1's pmulld where the build has it (a host build), else from SSE2's
// 32x32->64-bit unsigned multiplies (the low 32 bits of a product do not depend on signedness).
inline __m128i mullo32(__m128i a, __m128i b) {
#if defined(__SSE4_1__)
  return _mm_mullo_epi32(a, b);
#else
  const __m128i even = _mm_mul_epu32(a, b);
  const __m128i odd = _mm_mul_epu32(_mm_srli_epi64(a, 32), _mm_srli_epi64(b, 32));
  return _mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
                            _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0)));
#endif
}
// Four 32-bit integer lanes, arithmetic modulo 2^32 as the instructions wrap: primitive setup's
// integer steps (edge functions of one triangle, one edge per lane), written once as templates over
// the lane type (primitive_setup.h) for I4 and for simd8.h's I8. Comparisons give lane masks: all
// ones where true.
struct I4 {
  __m128i v;
  I4() = default;
  explicit I4(__m128i x) : v(x) {}
  explicit I4(std::int32_t x) : v(_mm_set1_epi32(x)) {}
  friend I4 operator+(I4 a, I4 b) { return I4(_mm_add_epi32(a.v, b.v)); }
  friend I4 operator-(I4 a, I4 b) { return I4(_mm_sub_epi32(a.v, b.v)); }
  friend I4 operator*(I4 a, I4 b) { return I4(mullo32(a.v, b.v)); }
  friend I4 operator&(I4 a, I4 b) { return I4(_mm_and_si128(a.v, b.v)); }
  friend I4 operator|(I4 a, I4 b) { return I4(_mm_or_si128(a.v, b.v)); }
  friend I4 operator~(I4 a) { return I4(_mm_xor_si128(a.v, _mm_set1_epi32(-1))); }
};
inline I4 less(I4 a, I4 b) { return I4(_mm_cmplt_epi32(a.v, b.v)); }
inline I4 equal(I4 a, I4 b) { return I4(_mm_cmpeq_epi32(a.v, b.v)); }
inline I4 greater(I4 a, I4 b) { return I4(_mm_cmpgt_epi32(a.v, b.v)); }

// std::max(a, b) is (a < b) ? b : a; maxps(b, a) is (b > a) ? b : a: the same for every input.
inline F4 max(F4 a, F4 b) { return {_mm_max_ps(b.v, a.v)}; }
// std::min(a, b) is (b < a) ? b : a; minps(b, a) is (b < a) ? b : a.
inline F4 min(F4 a, F4 b) { return {_mm_min_ps(b.v, a.v)}; }
// Comparisons as 4-bit lane masks (bit k = lane k), with C++'s operators' results for every input
// (NaN compares unordered: false, except !=).
inline unsigned less_mask(F4 a, F4 b) { return unsigned(_mm_movemask_ps(_mm_cmplt_ps(a.v, b.v))); }
inline unsigned less_equal_mask(F4 a, F4 b) { return unsigned(_mm_movemask_ps(_mm_cmple_ps(a.v, b.v))); }
inline unsigned equal_mask(F4 a, F4 b) { return unsigned(_mm_movemask_ps(_mm_cmpeq_ps(a.v, b.v))); }
inline unsigned not_equal_mask(F4 a, F4 b) { return unsigned(_mm_movemask_ps(_mm_cmpneq_ps(a.v, b.v))); }
// All ones in lane k where bit k of `mask` (0..15) is set: one load from a table, where building the
// lanes from the bits took a dozen instructions per quad.
alignas(64) inline constexpr std::int32_t kLaneMasks[16][4] = {
    {0, 0, 0, 0},   {-1, 0, 0, 0},   {0, -1, 0, 0},   {-1, -1, 0, 0},  {0, 0, -1, 0},  {-1, 0, -1, 0},
    {0, -1, -1, 0}, {-1, -1, -1, 0}, {0, 0, 0, -1},   {-1, 0, 0, -1},  {0, -1, 0, -1}, {-1, -1, 0, -1},
    {0, 0, -1, -1}, {-1, 0, -1, -1}, {0, -1, -1, -1}, {-1, -1, -1, -1}};
inline __m128i lane_mask(unsigned mask) {
  return _mm_load_si128(reinterpret_cast<const __m128i*>(kLaneMasks[mask & 0xFu]));
}
// Lane k of the result is b's where bit k of `mask` is set, else a's.
inline F4 select(unsigned mask, F4 a, F4 b) {
  const __m128 m = _mm_castsi128_ps(lane_mask(mask));
  return {_mm_or_ps(_mm_and_ps(m, b.v), _mm_andnot_ps(m, a.v))};
}

#else

struct F4 {
  std::array<float, 4> v;
  static F4 splat(float x) { return {{x, x, x, x}}; }
  static F4 lanes(float a, float b, float c, float d) { return {{a, b, c, d}}; }
  static F4 load(const std::array<float, 4>& a) { return {a}; }
  void store(std::array<float, 4>& a) const { a = v; }
  static F4 load_at(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
  void store_at(float* p) const {
    for (int k = 0; k < 4; ++k) p[k] = v[k];
  }
  static F4 load_pairs(const float* r0, const float* r1) { return {{r0[0], r0[1], r1[0], r1[1]}}; }
  void store_pairs(float* r0, float* r1) const { r0[0] = v[0], r0[1] = v[1], r1[0] = v[2], r1[1] = v[3]; }
  template <class Op>
  static F4 map(F4 a, F4 b, Op op) {
    F4 r;
    for (int k = 0; k < 4; ++k) r.v[k] = op(a.v[k], b.v[k]);
    return r;
  }
  friend F4 operator+(F4 a, F4 b) {
    return map(a, b, [](float x, float y) { return x + y; });
  }
  friend F4 operator-(F4 a, F4 b) {
    return map(a, b, [](float x, float y) { return x - y; });
  }
  friend F4 operator*(F4 a, F4 b) {
    return map(a, b, [](float x, float y) { return x * y; });
  }
  friend F4 operator/(F4 a, F4 b) {
    return map(a, b, [](float x, float y) { return x / y; });
  }
  friend F4 operator-(F4 a) {
    for (auto& x : a.v) x = -x;
    return a;
  }
};
inline F4 sqrt(F4 a) {
  for (auto& x : a.v) x = std::sqrt(x);
  return a;
}
inline F4 max(F4 a, F4 b) {
  return F4::map(a, b, [](float x, float y) { return x < y ? y : x; });
}
inline F4 min(F4 a, F4 b) {
  return F4::map(a, b, [](float x, float y) { return y < x ? y : x; });
}
template <class Op>
unsigned compare_mask(F4 a, F4 b, Op op) {
  unsigned m = 0;
  for (int k = 0; k < 4; ++k) m |= unsigned(op(a.v[k], b.v[k])) << k;
  return m;
}
inline unsigned less_mask(F4 a, F4 b) {
  return compare_mask(a, b, [](float x, float y) { return x < y; });
}
inline unsigned less_equal_mask(F4 a, F4 b) {
  return compare_mask(a, b, [](float x, float y) { return x <= y; });
}
inline unsigned equal_mask(F4 a, F4 b) {
  return compare_mask(a, b, [](float x, float y) { return x == y; });
}
inline unsigned not_equal_mask(F4 a, F4 b) {
  return compare_mask(a, b, [](float x, float y) { return x != y; });
}
inline F4 select(unsigned mask, F4 a, F4 b) {
  for (int k = 0; k < 4; ++k)
    if ((mask >> k) & 1u) a.v[k] = b.v[k];
  return a;
}

#endif

}  // namespace tessera::simd
