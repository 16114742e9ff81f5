// Placing points along one edge (internal to the tessellator).
//
// An edge with factor f has its points mirrored about the midpoint: only one half is computed and
// the other is 1 - x, which is what makes shared edges bit-identical whichever patch computes
// them. A fractional factor lies between a "floor" and a "ceil" tessellation of the half-edge;
// the one point that exists only in the ceil tessellation (the split point, chosen by the ruler
// function so that splits happen in a stable order) slides from its parent as the fraction grows.
#pragma once

#include "tessellator/tessellator.h"

namespace tessera::ts::detail {

// The reference's ComputeTessFactorContext + NumPointsForTessFactor, with the parity explicit.
EdgeContext make_edge_context(Fxp factor, Parity parity);

// Location in 16.16 of point `point` (0 .. num_points-1) along an edge (the reference's PlacePointIn1D).
Fxp place_point(const EdgeContext& edge, int point);

}  // namespace tessera::ts::detail
