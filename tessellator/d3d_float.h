// The float rules the D3D11 tessellator applies to factors before it converts them to fixed point
// (D3D11.3 spec §3.1, §11.7.10): denormals flush to zero in min/max, and a NaN second operand
// returns the first one, so clamp(lower, upper, NaN) lands on the lower bound.
#pragma once

#include <bit>
#include <cstdint>

namespace tessera::ts {

constexpr bool d3d_isnan(float a) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(a);
  return (bits & 0x7F800000u) == 0x7F800000u && (bits & 0x007FFFFFu) != 0;
}

// Denormals become a zero of the same sign; NaN and infinities pass through.
constexpr float d3d_flush(float a) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(a);
  if ((bits & 0x7FFFFFFFu) < 0x00800000u) return std::bit_cast<float>(bits & 0x80000000u);
  return a;
}

// IEEE 754R-style min as D3D defines it; note which operand's NaN wins: only b is tested.
constexpr float d3d_fmin(float a, float b) {
  const float fa = d3d_flush(a), fb = d3d_flush(b);
  if (d3d_isnan(fb)) return a;
  if (fa == 0 && fb == 0) return (std::bit_cast<std::uint32_t>(fa) & 0x80000000u) ? a : b;  // -0 < +0
  return fa < fb ? a : b;
}

constexpr float d3d_fmax(float a, float b) {
  const float fa = d3d_flush(a), fb = d3d_flush(b);
  if (d3d_isnan(fb)) return a;
  if (fa == 0 && fb == 0) return (std::bit_cast<std::uint32_t>(fb) & 0x80000000u) ? a : b;  // +0 > -0
  return fa >= fb ? a : b;
}

// Clamp to [lower, upper] with the operand order of the reference, so NaN -> lower.
constexpr float d3d_clamp(float x, float lower, float upper) { return d3d_fmin(upper, d3d_fmax(lower, x)); }

}  // namespace tessera::ts
