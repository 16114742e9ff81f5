// Eight float lanes for batch shader code (a batch domain shader's points), where the work per lane is
// long and the same for every lane.
//
// With AVX (an x86-64-v3 or -v4 build: TESSERA_ISA in CMakeLists.txt) each operation is one 256-bit
// instruction; without it, F8 is two F4s (simd4.h), so code written over F8 compiles and gives the same
// bits in every build. Each operation is one IEEE-754 operation per lane (add, sub, mul, div and sqrt
// are correctly rounded in every form), and no FMA is formed.
#pragma once

#include <array>
#include <cstdint>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "pipeline/simd4.h"

namespace tessera::simd {

#if defined(__AVX__)

struct F8 {
  __m256 v;
  static F8 splat(float x) { return {_mm256_set1_ps(x)}; }
  // Eight values in lanes 0..7, as F4::lanes. Lanes built from values in registers (or read one by one)
  // take this or join(), not load() of an array just filled lane by lane: a load that spans several
  // stores is not forwarded from the store buffer and waits for them to reach the cache.
  static F8 lanes(float a, float b, float c, float d, float e, float f, float g, float h) {
    return {_mm256_setr_ps(a, b, c, d, e, f, g, h)};
  }
  static F8 load(const std::array<float, 8>& a) { return {_mm256_loadu_ps(a.data())}; }
  void store(std::array<float, 8>& a) const { _mm256_storeu_ps(a.data(), v); }
  friend F8 operator+(F8 a, F8 b) { return {_mm256_add_ps(a.v, b.v)}; }
  friend F8 operator-(F8 a, F8 b) { return {_mm256_sub_ps(a.v, b.v)}; }
  friend F8 operator*(F8 a, F8 b) { return {_mm256_mul_ps(a.v, b.v)}; }
  friend F8 operator/(F8 a, F8 b) { return {_mm256_div_ps(a.v, b.v)}; }
  friend F8 operator-(F8 a) { return {_mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f))}; }  // flips the sign bit, as -x
};
inline F8 sqrt(F8 a) { return {_mm256_sqrt_ps(a.v)}; }
// Eight lanes from two halves (lanes 0..3 from lo), for values that arrive four at a time (F8::lanes).
inline F8 join(F4 lo, F4 hi) { return {_mm256_set_m128(hi.v, lo.v)}; }

#if defined(__AVX2__)
// Eight 32-bit integer lanes (AVX2), as simd4.h's I4: the eight-lane triangle setup
// (triangle_list_setup.h) runs primitive setup's integer steps over eight triangles with it.
struct I8 {
  __m256i v;
  I8() = default;
  explicit I8(__m256i x) : v(x) {}
  explicit I8(std::int32_t x) : v(_mm256_set1_epi32(x)) {}
  friend I8 operator+(I8 a, I8 b) { return I8(_mm256_add_epi32(a.v, b.v)); }
  friend I8 operator-(I8 a, I8 b) { return I8(_mm256_sub_epi32(a.v, b.v)); }
  friend I8 operator*(I8 a, I8 b) { return I8(_mm256_mullo_epi32(a.v, b.v)); }
  friend I8 operator&(I8 a, I8 b) { return I8(_mm256_and_si256(a.v, b.v)); }
  friend I8 operator|(I8 a, I8 b) { return I8(_mm256_or_si256(a.v, b.v)); }
  friend I8 operator~(I8 a) { return I8(_mm256_xor_si256(a.v, _mm256_set1_epi32(-1))); }
  friend I8 operator>>(I8 a, int bits) { return I8(_mm256_srai_epi32(a.v, bits)); }  // arithmetic, as for int32
};
inline I8 less(I8 a, I8 b) { return I8(_mm256_cmpgt_epi32(b.v, a.v)); }
inline I8 equal(I8 a, I8 b) { return I8(_mm256_cmpeq_epi32(a.v, b.v)); }
inline I8 greater(I8 a, I8 b) { return I8(_mm256_cmpgt_epi32(a.v, b.v)); }
inline I8 max(I8 a, I8 b) { return I8(_mm256_max_epi32(a.v, b.v)); }
inline I8 min(I8 a, I8 b) { return I8(_mm256_min_epi32(a.v, b.v)); }
#endif

#else

struct F8 {
  F4 lo, hi;  // lanes 0..3, 4..7
  static F8 splat(float x) { return {F4::splat(x), F4::splat(x)}; }
  static F8 lanes(float a, float b, float c, float d, float e, float f, float g, float h) {
    return {F4::lanes(a, b, c, d), F4::lanes(e, f, g, h)};
  }
  static F8 load(const std::array<float, 8>& a) { return {F4::load_at(a.data()), F4::load_at(a.data() + 4)}; }
  void store(std::array<float, 8>& a) const {
    lo.store_at(a.data());
    hi.store_at(a.data() + 4);
  }
  friend F8 operator+(F8 a, F8 b) { return {a.lo + b.lo, a.hi + b.hi}; }
  friend F8 operator-(F8 a, F8 b) { return {a.lo - b.lo, a.hi - b.hi}; }
  friend F8 operator*(F8 a, F8 b) { return {a.lo * b.lo, a.hi * b.hi}; }
  friend F8 operator/(F8 a, F8 b) { return {a.lo / b.lo, a.hi / b.hi}; }
  friend F8 operator-(F8 a) { return {-a.lo, -a.hi}; }
};
inline F8 sqrt(F8 a) { return {sqrt(a.lo), sqrt(a.hi)}; }
inline F8 join(F4 lo, F4 hi) { return {lo, hi}; }

#endif

}  // namespace tessera::simd
