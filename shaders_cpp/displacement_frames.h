// Consistent normals for displacement (the talk's "control tangents along edges are not symmetric"):
// the direction a point on a cage edge or vertex is displaced along must be the same bits on every
// patch that shares it, but each patch's own du x dv there comes from its own control points.
//
// So every shared element gets one frame, defined by its owner (watertight_uv.h) and written as
// stencils over global cage vertices:
// - a cage edge: the owner face's tangent along the edge and across it (into the owner face), each a
//   cubic in the owner's edge parameter with four control vectors (8 stencils: along A0..A3, cross
//   C0..C3). acc: the tangent patches' edge rows (along degree-elevated from quadratic); gregory and
//   bspline: the derivatives of the Bezier boundary (degree-elevated) and 3 (row 1 − row 0); flat: the
//   bilinear patch's. The normal there is normalize(along x cross).
//   `exact` has no stencils (its IA patch is the face alone): its normals are owned by the limit
//   surface already, and its DS reads the owner's derivatives from the limit surface directly.
// - a cage vertex: two limit tangents (limit_masks.h) along the vertex owner face's next and previous
//   edges (flat: those edges themselves); the normal is normalize(T0 x T1).
// Each stencil only reaches the 1-rings of the element's vertices, which every patch containing the
// element has in its IA patch; a patch stores the stencils as (ring position, float weight) terms
// sorted by global vertex index, the weights rounded once from double. The hull shader sums them in
// that order in double and rounds once (as SubdHS does), so both sides get identical bits.
//
// Contract: quad patches (as watertight_uv.h). Per patch 40 stencils (empty for exact): edge k (patch edge k, corner k ->
// k+1) at 8k .. 8k+7 (along 0..3, cross 0..3, in the OWNER's direction and parameter), corner k's two
// tangents at 32 + 2k, 33 + 2k. Throws CageError if a stencil reaches a vertex outside the patch's
// ring (an internal error: it cannot happen for the schemes' all-quad neighbourhoods).
#pragma once

#include <cstdint>
#include <vector>

#include "cage.h"
#include "subd_patches.h"
#include "topology.h"

namespace tessera {

inline constexpr int kFrameStencils = 40;

struct FrameTerm {
  std::uint32_t position = 0;  // ring position in the IA patch
  float weight = 0.0f;
};

struct PatchFrames {
  std::vector<std::uint32_t> offsets;  // patch p, stencil r: terms [offsets[40 p + r], offsets[40 p + r + 1])
  std::vector<FrameTerm> terms;
  std::size_t bytes() const { return offsets.size() * sizeof(std::uint32_t) + terms.size() * sizeof(FrameTerm); }
};

PatchFrames build_patch_frames(const Cage& cage, const Topology& topology, const PatchGroup& group, Scheme scheme);

}  // namespace tessera
