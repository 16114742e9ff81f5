// Eight float lanes for batch shader code (a batch domain shader's points), where the work per lane is
// long and the same for every lane.
//
// With AVX (a TESSERA_ISA=host build on an x86-64-v3 machine) each operation is one 256-bit
// instruction; without it, F8 is two F4s (simd4.h), so code written over F8 compiles and gives the same
// bits in every build. Each operation is one IEEE-754 operation per lane (add, sub, mul, div and sqrt
// are correctly rounded in every form), and no FMA is formed.
#pragma once

#include <array>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "pipeline/simd4.h"

namespace tessera::simd {

#if defined(__AVX__)

struct F8 {
  __m256 v;
  static F8 splat(float x) { return {_mm256_set1_ps(x)}; }
  static F8 load(const std::array<float, 8>& a) { return {_mm256_loadu_ps(a.data())}; }
  void store(std::array<float, 8>& a) const { _mm256_storeu_ps(a.data(), v); }
  friend F8 operator+(F8 a, F8 b) { return {_mm256_add_ps(a.v, b.v)}; }
  friend F8 operator-(F8 a, F8 b) { return {_mm256_sub_ps(a.v, b.v)}; }
  friend F8 operator*(F8 a, F8 b) { return {_mm256_mul_ps(a.v, b.v)}; }
  friend F8 operator/(F8 a, F8 b) { return {_mm256_div_ps(a.v, b.v)}; }
  friend F8 operator-(F8 a) { return {_mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f))}; }  // flips the sign bit, as -x
};
inline F8 sqrt(F8 a) { return {_mm256_sqrt_ps(a.v)}; }

#else

struct F8 {
  F4 lo, hi;  // lanes 0..3, 4..7
  static F8 splat(float x) { return {F4::splat(x), F4::splat(x)}; }
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

#endif

}  // namespace tessera::simd
