// The Catmull-Clark limit at the centre of a face of n >= 5 sides, as stencils over the cage: what the
// per-face schemes need to draw such a face as a fan of n triangles meeting at its centre
// (patch_stencils.h, gregory_fan_stencils).
//
// One Catmull-Clark step turns the face into n quads around its face point c, a vertex of valence n
// whose ring is all quads: edge neighbours m_i (the edge points of face edges i, corner i -> i+1) and
// far neighbours v'_{i+1} (the vertex points of the face's corners). The limit masks of an all-quad
// ring then give the position, and the tangent along each refined edge c -> m_i (Loop & Schaefer's
// mask, per unit of a sub-quad's parameter, as limit_masks.h scales its tangents).
//
// Conventions (Catmull-Clark with uniform creasing, one step):
// - m_i: (v_i + v_{i+1} + c + f_i) / 4 with f_i the centroid of the face across the edge; the edge's
//   midpoint on a boundary edge; a tagged edge of sharpness s blends toward the midpoint by min(s, 1).
// - v'_i: the smooth vertex rule (Q + 2 R + (n - 3) v) / n; (e_a + 6 v + e_b) / 8 on a boundary or between
//   two tagged edges; v itself at a sharp corner (three or more tagged edges, a corner tag, or a
//   boundary corner the cage interpolates); tags below sharpness 1 blend toward the smooth rule.
// Exact for the first step, so the position is the limit's to round-off wherever the face's ring is
// smooth after one step.
#pragma once

#include <vector>

#include "shaders_cpp/subdiv/stencil.h"

namespace tessera {

struct Cage;
class Topology;

struct FaceCentre {
  Stencil position;
  std::vector<Stencil> tangents;  // [i]: the limit tangent at the centre along c -> m_i (face edge i)
};

// Face f must have at least 3 sides, no hole, and manifold edges (the per-face schemes' contract).
FaceCentre face_centre_limit(const Cage& cage, const Topology& topology, int face);

}  // namespace tessera
