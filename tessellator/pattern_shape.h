// The shape of a pattern's triangles in the domain, summarised for proofs about every triangle at once
// (the pipeline's back-patch test, pipeline/patch_orientation.h).
//
// Contract
// - For a triangle pattern (triangle_cw or triangle_ccw output) whose triangles all have non-zero
//   signed area in (u, v) and one sign, `consistent` is true and `orientation` is that sign (+1 for
//   triangle_cw patterns, as tessellator.h states, -1 for triangle_ccw). Otherwise (points, lines, a
//   degenerate or inverted triangle) `consistent` is false and no other field means anything.
// - For each triangle (a, b, c) take the edge vectors d1 = b - a = (s1, t1) and d2 = c - a = (s2, t2),
//   twice its area D = |s1 t2 - t1 s2| and the L1 lengths l1 = |s1| + |t1|, l2 = |s2| + |t2|. The fields
//   are upper bounds, over the pattern's triangles, of
//     cubic     l1 l2 (l1 + l2) / D   (shrinks as the triangle's size: 2h for legs h along u and v)
//     quartic   l1^2 l2^2 / D         (as the size squared)
//     perimeter (l1 + l2) / D         (grows as 1 / size)
//     product   l1 l2 / D             (bounded by the triangle's shape)
//     inverse   1 / D
//   each for the corner `a` (one of the triangle's three; rotations keep the orientation) that makes
//   `cubic` smallest. A bound in (u, v) is also one for (v, u) and for 1 - u or 1 - v.
// - Computed in double from the float points: differences and products are exact, quotients are
//   rounded up by a relative 2^-40.
#pragma once

#include "tessellator/tessellator.h"

namespace tessera::ts {

struct PatternShape {
  bool consistent = false;
  int orientation = 0;
  double cubic = 0, quartic = 0, perimeter = 0, product = 0, inverse = 0;
};

PatternShape pattern_shape(const Pattern& pattern);

}  // namespace tessera::ts
