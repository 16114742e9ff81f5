// Per-domain point generation and connectivity (internal). Each takes processed factors that are
// neither culled nor minimal and appends to `out`, which the caller has cleared.
#pragma once

#include <algorithm>

#include "tessellator/tessellator.h"

namespace tessera::ts::detail {

void quad_generate_points(const ProcessedFactors& p, std::vector<DomainPoint>& points);
void quad_generate_connectivity(const ProcessedFactors& p, bool ccw, std::vector<std::uint32_t>& indices);
void tri_generate_points(const ProcessedFactors& p, std::vector<DomainPoint>& points);
void tri_generate_connectivity(const ProcessedFactors& p, bool ccw, std::vector<std::uint32_t>& indices);
void isoline_generate(const ProcessedFactors& p, OutputPrimitive output, Pattern& out);

inline DomainPoint make_point(Fxp u, Fxp v) { return {fixed_to_float(u), fixed_to_float(v)}; }

// The quad domain's connectivity rings: the outer ring, then one per inner ring down to the centre
// (an even axis's centre row counts as a ring).
inline int quad_rings(const ProcessedFactors& p) {
  return std::min((p.inside[0].num_points + 1) >> 1, (p.inside[1].num_points + 1) >> 1);
}

// The strip of quads an odd narrower inside axis leaves in the middle of a quad patch (the spec's
// "Z"), running along u or v; quads = 0 when the rings end in a centre row instead.
struct QuadMiddleStrip {
  int quads = 0;
  bool along_u = false;
};
inline QuadMiddleStrip quad_middle_strip(const ProcessedFactors& p) {
  const int nu = p.inside[0].num_points, nv = p.inside[1].num_points;
  if (nu > nv && p.inside[1].parity == Parity::odd)
    return {(((nu >> 1) - (nv >> 1)) << 1) + (p.inside[0].parity == Parity::even ? 2 : 1), true};
  if (nv >= nu && p.inside[0].parity == Parity::odd)
    return {(((nv >> 1) - (nu >> 1)) << 1) + (p.inside[1].parity == Parity::even ? 2 : 1), false};
  return {};
}

}  // namespace tessera::ts::detail
