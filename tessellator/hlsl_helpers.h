// The HLSL helper layer: what the HLSL compiler adds to a hull shader's patch-constant function
// (the Process*TessFactors* intrinsics, D3D11.3 §10.10.1). Hardware never sees this layer; it turns
// raw edge factors and inside *scales* into the factors the fixed-function tessellator receives.
//
// - Edge factors are cleaned up (< 1 or NaN -> 1), rounded (integer: ceil; pow2: the next power
//   of two) and clamped to the partitioning's range.
// - The inside factor is a reduction (min, max or average) of the cleaned but *unrounded* edges,
//   times the scale clamped to [0, 1] (NaN -> 0), then clamped and rounded. Quads reduce all four
//   edges to one value (1 axis) or Veq0/Veq1 -> U and Ueq0/Ueq1 -> V (2 axes).
// - Anti-popping: an odd inside factor below 3 would snap the first ring ("picture frame") to the
//   edges, so it is replaced by min(3, max or average of the edges), ignoring the scale; for quads,
//   an odd axis below 3 is also raised to min(other axis, 3).
//
// Pure functions; `unrounded`, when given, receives the factors before rounding (what the
// reference's GetUnRoundedComputedTessFactors returns).
#pragma once

#include "tessellator/tessellator.h"

namespace tessera::ts::hlsl {

enum class Reduction : std::uint8_t { min, max, average };
enum class QuadReductionAxis : std::uint8_t { one_axis, two_axis };

std::string_view to_string(Reduction r);
std::optional<Reduction> parse_reduction(std::string_view s);

// Edge factor cleanup: [1, +inf), NaN -> 1.
float cleanup_edge_factor(float x);
// Inside scale cleanup: [0, 1], NaN -> 0.
float clamp_scale(float x);
// Rounding as the partitioning asks (integer: ceil; pow2: next power of two; fractional: none).
// Expects x >= 1.
float round_factor(float x, Partitioning p);
// Clamp to the partitioning's range (integer/pow2 [1, 64], fractional_odd [1, 63], fractional_even [2, 64]).
float clamp_factor(float x, Partitioning p);

// ProcessQuadTessFactors{Min,Max,Avg} (1 axis) and Process2DQuadTessFactors{Min,Max,Avg} (2 axes).
// The input's insideU/insideV are the scales.
QuadFactors process_quad(Partitioning p, Reduction r, QuadReductionAxis axis, const QuadFactors& edges_and_scales,
                         QuadFactors* unrounded = nullptr);
// ProcessTriTessFactors{Min,Max,Avg}; the input's `inside` is the scale.
TriFactors process_tri(Partitioning p, Reduction r, const TriFactors& edges_and_scale, TriFactors* unrounded = nullptr);
// ProcessIsolineTessFactors: density is always integer-rounded; detail follows the partitioning.
IsolineFactors process_isoline(Partitioning p, const IsolineFactors& f, IsolineFactors* unrounded = nullptr);

}  // namespace tessera::ts::hlsl
