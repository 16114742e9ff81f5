// Factor processing: culling, clamping, rounding, parity, conversion to 16.16, and the minimal
// case (D3D11.3 §11.7.10-11.7.12). Afterwards everything is integer arithmetic.
#include <cmath>

#include "tessellator/d3d_float.h"
#include "tessellator/edge_context.h"
#include "tessellator/tessellator.h"

namespace tessera::ts {
namespace {

// 2^-16, the smallest fixed-point fraction.
constexpr float kEpsilon = 1.0f / 65536.0f;
// A factor above this still converts to more than 1.0 in 16.16 (1 + 2^-17 itself ties to 1.0).
constexpr float kMinOddPlusHalfEpsilon = kMinOddTessFactor + kEpsilon / 2;

// Integer and pow2 are the same to hardware (§11.7.7.1): both round up to an integer.
bool rounds_to_integer(Partitioning p) { return p == Partitioning::integer || p == Partitioning::pow2; }

struct Bounds {
  float lower, upper;
};

Bounds clamp_bounds(Partitioning p) {
  switch (p) {
    case Partitioning::fractional_even: return {kMinEvenTessFactor, kMaxEvenTessFactor};
    case Partitioning::fractional_odd: return {kMinOddTessFactor, kMaxOddTessFactor};
    case Partitioning::integer:
    case Partitioning::pow2: break;
  }
  return {kMinOddTessFactor, kMaxEvenTessFactor};
}

Parity partitioning_parity(Partitioning p) { return p == Partitioning::fractional_odd ? Parity::odd : Parity::even; }

bool is_even(float clamped) { return (static_cast<int>(clamped) & 1) == 0; }

float clamp_and_round(float x, Bounds b, Partitioning p) {
  x = d3d_clamp(x, b.lower, b.upper);  // NaN -> lower bound
  return rounds_to_integer(p) ? std::ceil(x) : x;
}

Parity edge_parity(float factor, Partitioning p) {
  if (!rounds_to_integer(p)) return partitioning_parity(p);
  return is_even(factor) ? Parity::even : Parity::odd;
}

// An inside factor of exactly 1 is treated as even (2 segments), so a ring still forms.
Parity inside_parity(float factor, Partitioning p) {
  if (!rounds_to_integer(p)) return partitioning_parity(p);
  return (is_even(factor) || factor == 1.0f) ? Parity::even : Parity::odd;
}

EdgeContext context(float factor, Parity parity, int min_points = 0) {
  EdgeContext c = detail::make_edge_context(float_to_fixed(factor), parity);
  if (c.num_points < min_points) c.num_points = min_points;
  return c;
}

// Inside factors need at least one inner ring (odd) or centre (even); when an inside factor of 1
// meets larger edges this gives degenerate transition regions, as in the reference.
int min_inside_points(Parity parity) { return parity == Parity::odd ? 4 : 3; }

}  // namespace

ProcessedFactors process_quad_factors(Partitioning partitioning, const QuadFactors& f) {
  ProcessedFactors r;
  r.domain = Domain::quad;
  if (!(f.Ueq0 > 0) || !(f.Veq0 > 0) || !(f.Ueq1 > 0) || !(f.Veq1 > 0)) {  // NaN fails > 0 too
    r.culled = true;
    return r;
  }
  const Bounds b = clamp_bounds(partitioning);
  const std::array<float, 4> outside = {
      clamp_and_round(f.Ueq0, b, partitioning), clamp_and_round(f.Veq0, b, partitioning),
      clamp_and_round(f.Ueq1, b, partitioning), clamp_and_round(f.Veq1, b, partitioning)};
  Bounds inside_bounds = b;
  if (partitioning == Partitioning::fractional_odd) {
    // If anything will tessellate beyond 1, force the inside above 1 so a "picture frame" ring
    // exists. The raw inside factors are tested, not the clamped ones.
    bool any_above_one = f.insideU > kMinOddPlusHalfEpsilon || f.insideV > kMinOddPlusHalfEpsilon;
    for (float x : outside) any_above_one = any_above_one || x > kMinOddPlusHalfEpsilon;
    if (any_above_one) inside_bounds.lower = kMinOddTessFactor + kEpsilon;
  }
  const std::array<float, 2> inside = {clamp_and_round(f.insideU, inside_bounds, partitioning),
                                       clamp_and_round(f.insideV, inside_bounds, partitioning)};

  bool all_one = true;
  for (std::size_t e = 0; e < 4; ++e) {
    r.outside[e].factor = float_to_fixed(outside[e]);
    r.outside[e].parity = edge_parity(outside[e], partitioning);
    all_one = all_one && r.outside[e].factor == kFxpOne;
  }
  for (std::size_t a = 0; a < 2; ++a) {
    r.inside[a].factor = float_to_fixed(inside[a]);
    r.inside[a].parity = inside_parity(inside[a], partitioning);
    all_one = all_one && r.inside[a].factor == kFxpOne;
  }
  if (all_one && partitioning != Partitioning::fractional_even) {
    r.minimal = true;
    return r;
  }
  for (std::size_t e = 0; e < 4; ++e) r.outside[e] = context(outside[e], r.outside[e].parity);
  for (std::size_t a = 0; a < 2; ++a)
    r.inside[a] = context(inside[a], r.inside[a].parity, min_inside_points(r.inside[a].parity));
  return r;
}

ProcessedFactors process_tri_factors(Partitioning partitioning, const TriFactors& f) {
  ProcessedFactors r;
  r.domain = Domain::tri;
  if (!(f.Ueq0 > 0) || !(f.Veq0 > 0) || !(f.Weq0 > 0)) {
    r.culled = true;
    return r;
  }
  const Bounds b = clamp_bounds(partitioning);
  const std::array<float, 3> outside = {clamp_and_round(f.Ueq0, b, partitioning),
                                        clamp_and_round(f.Veq0, b, partitioning),
                                        clamp_and_round(f.Weq0, b, partitioning)};
  Bounds inside_bounds = b;
  if (partitioning == Partitioning::fractional_odd) {
    // Unlike quads, only the edges are tested: there is a single inside factor.
    bool any_above_one = false;
    for (float x : outside) any_above_one = any_above_one || x > kMinOddPlusHalfEpsilon;
    if (any_above_one) inside_bounds.lower = kMinOddTessFactor + kEpsilon;
  }
  const float inside = clamp_and_round(f.inside, inside_bounds, partitioning);

  bool all_one = true;
  for (std::size_t e = 0; e < 3; ++e) {
    r.outside[e].factor = float_to_fixed(outside[e]);
    r.outside[e].parity = edge_parity(outside[e], partitioning);
    all_one = all_one && r.outside[e].factor == kFxpOne;
  }
  r.inside[0].factor = float_to_fixed(inside);
  r.inside[0].parity = inside_parity(inside, partitioning);
  all_one = all_one && r.inside[0].factor == kFxpOne;
  if (all_one && partitioning != Partitioning::fractional_even) {
    r.minimal = true;
    return r;
  }
  for (std::size_t e = 0; e < 3; ++e) r.outside[e] = context(outside[e], r.outside[e].parity);
  r.inside[0] = context(inside, r.inside[0].parity, min_inside_points(r.inside[0].parity));
  return r;
}

ProcessedFactors process_isoline_factors(Partitioning partitioning, const IsolineFactors& f) {
  ProcessedFactors r;
  r.domain = Domain::isoline;
  if (!(f.density > 0) || !(f.detail > 0)) {
    r.culled = true;
    return r;
  }
  // Detail follows the partitioning (no picture frame: there is no inside); density is always
  // integer-partitioned.
  const float detail = clamp_and_round(f.detail, clamp_bounds(partitioning), partitioning);
  const float density = std::ceil(d3d_clamp(f.density, kMinIsolineDensity, kMaxIsolineDensity));
  r.outside[0] = context(density, is_even(density) ? Parity::even : Parity::odd);
  r.outside[1] = context(detail, edge_parity(detail, partitioning));
  return r;
}

ProcessedFactors process_factors(Partitioning partitioning, const FactorSet& f) {
  const auto& x = f.values;
  switch (f.domain) {
    case Domain::quad: return process_quad_factors(partitioning, {x[0], x[1], x[2], x[3], x[4], x[5]});
    case Domain::tri: return process_tri_factors(partitioning, {x[0], x[1], x[2], x[3]});
    case Domain::isoline: break;
  }
  return process_isoline_factors(partitioning, {x[0], x[1]});
}

}  // namespace tessera::ts
