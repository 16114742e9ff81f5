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

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
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
  friend F4 operator+(F4 a, F4 b) { return {_mm_add_ps(a.v, b.v)}; }
  friend F4 operator-(F4 a, F4 b) { return {_mm_sub_ps(a.v, b.v)}; }
  friend F4 operator*(F4 a, F4 b) { return {_mm_mul_ps(a.v, b.v)}; }
  friend F4 operator/(F4 a, F4 b) { return {_mm_div_ps(a.v, b.v)}; }
  friend F4 operator-(F4 a) { return {_mm_xor_ps(a.v, _mm_set1_ps(-0.0f))}; }  // flips the sign bit, as -x
};
inline F4 sqrt(F4 a) { return {_mm_sqrt_ps(a.v)}; }
// std::max(a, b) is (a < b) ? b : a; maxps(b, a) is (b > a) ? b : a: the same for every input.
inline F4 max(F4 a, F4 b) { return {_mm_max_ps(b.v, a.v)}; }
// std::min(a, b) is (b < a) ? b : a; minps(b, a) is (b < a) ? b : a.
inline F4 min(F4 a, F4 b) { return {_mm_min_ps(b.v, a.v)}; }

#else

struct F4 {
  std::array<float, 4> v;
  static F4 splat(float x) { return {{x, x, x, x}}; }
  static F4 lanes(float a, float b, float c, float d) { return {{a, b, c, d}}; }
  static F4 load(const std::array<float, 4>& a) { return {a}; }
  void store(std::array<float, 4>& a) const { a = v; }
  template <class Op>
  static F4 map(F4 a, F4 b, Op op) {
    F4 r;
    for (int k = 0; k < 4; ++k) r.v[k] = op(a.v[k], b.v[k]);
    return r;
  }
  friend F4 operator+(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x + y; }); }
  friend F4 operator-(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x - y; }); }
  friend F4 operator*(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x * y; }); }
  friend F4 operator/(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x / y; }); }
  friend F4 operator-(F4 a) {
    for (auto& x : a.v) x = -x;
    return a;
  }
};
inline F4 sqrt(F4 a) {
  for (auto& x : a.v) x = std::sqrt(x);
  return a;
}
inline F4 max(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return x < y ? y : x; }); }
inline F4 min(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return y < x ? y : x; }); }

#endif

}  // namespace tessera::simd
