// Catmull-Clark limit masks at a cage vertex, as stencils over its 1-ring (corner_ring.h): the limit
// position, and the limit tangent along each incident edge. Both approximation schemes (acc.h and
// gregory.h) build their corner and edge control points from these, so a point shared by two patches
// comes from the same stencil on both.
//
// Conventions
// - Interior smooth vertex: the position is exact (one Catmull-Clark step, then the all-quad mask
//   (n^2 p + 4 sum e_i + sum d_i) / (n (n + 5))), for any face sizes around it. The tangent along e_j
//   is Loop & Schaefer's ACC mask (alpha on e_i, beta on d_i); on rings with non-quad faces, d_i is
//   the face's virtual quad point 4 c_i - p - e_i - e_{i+1} (c_i its centroid).
// - Boundary vertex (boundary interpolation edge_only / edge_and_corner): the cubic B-spline of the
//   boundary polygon, (e_0 + 4 p + e_last) / 6, and the boundary tangents of Loop et al. 2009 (r0 across,
//   r1 along the boundary).
// - Sharp corner: the vertex itself, and tangents toward each neighbour (e_j - p).
// - Every tangent is scaled so that p + t/3 is the Bezier edge point of a regular (valence 4) vertex.
// - Faces other than quads in a ring act through their virtual quad point 4 c_i - p - e_i - e_{i+1}
//   (a triangle's: its centroid). One Catmull-Clark step sees a face only through its centroid, so the
//   limit position and tangents come out exact for any face sizes.
// - Bit-identical on every face that asks: the tangent along e_j is summed from edge j; the position
//   from the ring turned to start at its lowest-index neighbour.
#pragma once

#include <functional>

#include "shaders_cpp/cage/corner_ring.h"
#include "shaders_cpp/subdiv/stencil.h"

namespace tessera {

Stencil limit_position(const CornerRing& ring);
// The limit tangent at the ring's centre in the direction of edge e_j.
Stencil limit_tangent(const CornerRing& ring, int j);
// Loop & Schaefer's ACC tangent mask at an interior vertex of valence n along edge j of an all-quad ring
// (real or virtual quads): sum_i alpha_i e(j + i) + beta_i d(j + i), i = 0..n-1, where d(i) is the far
// point of the face between e(i) and e(i + 1); e and d take their index modulo n.
Stencil acc_tangent(int n, int j, const std::function<Stencil(int)>& e, const std::function<Stencil(int)>& d);
// The valence the masks use: n for interior vertices, 2 (n - 1) for boundary ones (4 at a valence-2
// boundary corner), as Castano's boundary extension of ACC.
int pseudo_valence(const CornerRing& ring);
// The face corner's "virtual quad" far point d_i (the vertex itself for a quad face).
Stencil far_point(const CornerRing& ring, int i);

}  // namespace tessera
