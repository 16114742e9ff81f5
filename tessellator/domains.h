// Per-domain point generation and connectivity (internal). Each takes processed factors that are
// neither culled nor minimal and appends to `out`, which the caller has cleared.
#pragma once

#include "tessellator.h"

namespace tessera::ts::detail {

void quad_generate_points(const ProcessedFactors& p, std::vector<DomainPoint>& points);
void quad_generate_connectivity(const ProcessedFactors& p, bool ccw, std::vector<std::uint32_t>& indices);
void tri_generate_points(const ProcessedFactors& p, std::vector<DomainPoint>& points);
void tri_generate_connectivity(const ProcessedFactors& p, bool ccw, std::vector<std::uint32_t>& indices);
void isoline_generate(const ProcessedFactors& p, OutputPrimitive output, Pattern& out);

inline DomainPoint make_point(Fxp u, Fxp v) { return {fixed_to_float(u), fixed_to_float(v)}; }

}  // namespace tessera::ts::detail
