// 16.16 fixed point as the D3D11 tessellator defines it (D3D11.3 spec §11.7.11.3, §11.7.14).
//
// Every factor is converted float -> fixed exactly once, with round-to-nearest-even at bit 16,
// using integer operations on the float's bits only. After that all geometry is integer
// arithmetic, and the final fixed -> float step is exact, so every domain coordinate is a
// multiple of 2^-16 in [0, 1]. Positions come from a table of reciprocals round(2^16/n), not from
// a division: that is what makes integer spacing off i/n by up to 12 ulp16, and why an
// implementation that divides in float cannot be bit-exact.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

namespace tessera::ts {

// Unsigned 16.16; the reference calls this FXP.
using Fxp = std::uint32_t;

inline constexpr int kFxpFractionBits = 16;
inline constexpr Fxp kFxpFractionMask = 0x0000FFFFu;
inline constexpr Fxp kFxpIntegerMask = 0x7FFF0000u;
inline constexpr Fxp kFxpOne = 1u << kFxpFractionBits;
inline constexpr Fxp kFxpOneHalf = 0x8000u;
inline constexpr Fxp kFxpOneThird = 0x5555u;
inline constexpr Fxp kFxpTwoThirds = 0xAAAAu;

// The largest tessellation factor any partitioning allows; also the reciprocal table's size - 1.
inline constexpr int kMaxTessFactor = 64;

// round(2^16 / n) for n in 1..64; entry 0 is never read.
inline constexpr std::array<Fxp, kMaxTessFactor + 1> kFixedReciprocal = [] {
  std::array<Fxp, kMaxTessFactor + 1> table{};
  table[0] = 0xFFFFFFFFu;
  for (Fxp n = 1; n <= kMaxTessFactor; ++n) table[n] = (kFxpOne + n / 2) / n;
  return table;
}();
static_assert(kFixedReciprocal[6] == 0x2AAB && kFixedReciprocal[7] == 0x2492 && kFixedReciprocal[9] == 0x1C72 &&
              kFixedReciprocal[53] == 0x4D5 && kFixedReciprocal[64] == 0x400);

// float -> unsigned 15.16 fixed point with round-to-nearest-even, on the float's bits alone:
// NaN -> 0, negative -> 0, >= 2^15 -> all ones, below 2^-17 -> 0.
constexpr Fxp float_to_fixed(float input) {
  constexpr std::int32_t kMantissaBits = 23;
  constexpr std::int32_t kExponentBias = 127;
  constexpr std::uint32_t kHiddenBit = 1u << kMantissaBits;
  constexpr std::uint32_t kMantissaMask = kHiddenBit - 1;
  constexpr std::uint32_t kExponentMask = 0xFFu << kMantissaBits;
  constexpr std::uint32_t kSignBit = 0x80000000u;
  constexpr int kIntegerBits = 15;
  // 2^15 - 2^-16 would need 31 significant bits; the first float that overflows is 2^15.
  constexpr std::uint32_t kFirstTooLarge = std::uint32_t(kExponentBias + kIntegerBits) << kMantissaBits;

  const std::uint32_t bits = std::bit_cast<std::uint32_t>(input);
  const std::int32_t exponent = std::int32_t((bits & kExponentMask) >> kMantissaBits) - kExponentBias;
  const bool negative = (bits & kSignBit) != 0;
  if ((bits & kExponentMask) == kExponentMask && (bits & kMantissaMask) != 0) return 0;  // NaN
  if (negative) return 0;  // unsigned format: every negative value (and -0) clamps to 0
  if (bits >= kFirstTooLarge) return 0xFFFFFFFFu;
  if (exponent < -kFxpFractionBits - 1) return 0;  // below 2^-17 rounds to 0 even before ties
  std::uint32_t mantissa = (bits & kMantissaMask) | kHiddenBit;
  const std::int32_t extra_bits = kMantissaBits - kFxpFractionBits - exponent;
  if (extra_bits <= 0) return mantissa << -extra_bits;
  const std::uint32_t lsb = 1u << extra_bits;  // the last bit kept
  const std::uint32_t half = lsb >> 1;
  // Round to nearest, ties to even: add half unless it is an exact tie on an even result.
  if ((mantissa & lsb) != 0 || (mantissa & (lsb - 1)) > half) mantissa += half;
  return mantissa >> extra_bits;
}
static_assert(float_to_fixed(1.0f) == kFxpOne && float_to_fixed(-0.0f) == 0 && float_to_fixed(0.5f) == 0x8000);
static_assert(float_to_fixed(3.0f + 1.0f / 131072.0f) == 3 * kFxpOne);      // tie -> even
static_assert(float_to_fixed(3.0f + 3.0f / 131072.0f) == 3 * kFxpOne + 2);  // tie -> even, upwards

// Exact: both terms are representable and their sum has at most 24 significant bits for values <= 1.
constexpr float fixed_to_float(Fxp x) {
  return float(x >> kFxpFractionBits) + float(x & kFxpFractionMask) / float(kFxpOne);
}

constexpr Fxp fxp_floor(Fxp x) { return x & kFxpIntegerMask; }
constexpr Fxp fxp_ceil(Fxp x) { return (x & kFxpFractionMask) ? (x & kFxpIntegerMask) + kFxpOne : x; }

}  // namespace tessera::ts
