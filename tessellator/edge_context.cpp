#include "tessellator/edge_context.h"

#include <bit>

namespace tessera::ts::detail {
namespace {

// Clears the most significant set bit (0 stays 0).
int remove_msb(int value) {
  if (value <= 0) return 0;
  const auto v = static_cast<unsigned>(value);
  return static_cast<int>(v & ~std::bit_floor(v));
}

}  // namespace

EdgeContext make_edge_context(Fxp factor, Parity parity) {
  const bool odd = parity == Parity::odd;
  EdgeContext c;
  c.factor = factor;
  c.parity = parity;

  // Work on half the edge. Odd factors have a middle segment, so their half is shifted by 1/2; an
  // integer factor of 1 with even parity (an inside factor of 1) is handled as if it were 2.
  Fxp half = (factor + 1) / 2;
  if (odd || half == kFxpOneHalf) half += kFxpOneHalf;
  const Fxp floor_half = fxp_floor(half);
  const Fxp ceil_half = fxp_ceil(half);
  c.half_fraction = half - floor_half;
  c.num_half_points = static_cast<int>(ceil_half >> kFxpFractionBits);

  if (ceil_half == floor_half) {
    c.split_point = c.num_half_points + 1;  // no fraction: no point is splitting; never matched
  } else if (odd) {
    c.split_point =
        floor_half == kFxpOne ? 0 : (remove_msb(static_cast<int>(floor_half >> kFxpFractionBits) - 1) << 1) + 1;
  } else {
    c.split_point = (remove_msb(static_cast<int>(floor_half >> kFxpFractionBits)) << 1) + 1;
  }

  int floor_segments = static_cast<int>((floor_half * 2) >> kFxpFractionBits);
  int ceil_segments = static_cast<int>((ceil_half * 2) >> kFxpFractionBits);
  if (odd) {
    floor_segments -= 1;
    ceil_segments -= 1;
  }
  c.inv_floor_segments = kFixedReciprocal[static_cast<std::size_t>(floor_segments)];
  c.inv_ceil_segments = kFixedReciprocal[static_cast<std::size_t>(ceil_segments)];

  // The next odd (or even) segment count >= factor, plus one: the edge's point count.
  const Fxp rounded_half = (factor + 1) / 2;
  c.num_points = odd ? static_cast<int>((fxp_ceil(kFxpOneHalf + rounded_half) * 2) >> kFxpFractionBits)
                     : static_cast<int>((fxp_ceil(rounded_half) * 2) >> kFxpFractionBits) + 1;
  return c;
}

Fxp place_point(const EdgeContext& edge, int point) {
  const bool odd = edge.parity == Parity::odd;
  bool flip = false;
  if (point >= edge.num_half_points) {  // second half: mirror, so that x and 1 - x pair up exactly
    point = (edge.num_half_points << 1) - point;
    if (odd) point -= 1;
    flip = true;
  }
  // The midpoint of an even edge is exact: 16-bit reciprocals cannot reproduce 0.5.
  if (point == edge.num_half_points) return kFxpOneHalf;

  const auto on_ceil = static_cast<Fxp>(point);
  const Fxp on_floor = point > edge.split_point ? on_ceil - 1 : on_ceil;
  // Both products are <= 0.5 in 16.16 (at most 16 bits), so the lerp below fits in 32 bits; the
  // arithmetic is unsigned 32-bit like the reference's, including the fold quirk above 6 and 30.
  const Fxp location_floor = on_floor * edge.inv_floor_segments;
  const Fxp location_ceil = on_ceil * edge.inv_ceil_segments;
  Fxp location = location_floor * (kFxpOne - edge.half_fraction) + location_ceil * edge.half_fraction;
  location = (location + kFxpOneHalf) >> kFxpFractionBits;
  return flip ? kFxpOne - location : location;
}

}  // namespace tessera::ts::detail
