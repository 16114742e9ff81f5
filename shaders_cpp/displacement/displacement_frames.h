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
//   edges (flat: those edges themselves); the normal is normalize(T0 x T1). (The flat frames reach the
//   owner's corners, which a flat IA patch does not hold: make_displacement refuses flat and pn.)
// Each stencil only reaches the 1-rings of the element's vertices, which every patch containing the
// element has in its IA patch. A patch writes its stencils over its ring positions (the weights rounded
// once from double); the hull shader sums each one over the patch's ring in `SubdPatch::order`
// (ascending global vertex index), skipping zero weights, in double, and rounds once (as SubdHS does),
// so both sides get identical bits.
//
// Storage (the talk's memory point: this must stay small next to the mesh it replaces): written in
// ring positions, an element's stencils depend only on the local structure of the patch and the owner,
// so most patches repeat a few contents. They are grouped in units, one per patch edge (its 8 stencils)
// and one per patch corner (its 2), and each distinct unit content is stored once; a patch keeps the
// index of its 8 units. A stored stencil is a 32-bit mask of the ring positions it reaches and its
// nonzero weights in ascending ring position (the weight of position j is at the popcount of the mask
// below j), so the sum runs in the patch's own global order whatever patch shares the unit.
//
// Contract: quad patches (as watertight_uv.h), rings of at most 32 positions (kMaxPatchControlPoints);
// a precomputed patch (a larger ring) keeps its 40 stencils over cage vertices instead, summed by the
// control-point pre-pass in the same order and arithmetic.
// Per patch 40 stencils: edge k (patch edge k, corner k -> k+1) at 8k .. 8k+7 (along 0..3, cross 0..3,
// in the OWNER's direction and parameter), corner k's two tangents at 32 + 2k, 33 + 2k; `exact` patches
// get empty stencils (no terms). A vertex appearing twice in a ring is read at its first position.
// Throws CageError if a stencil reaches a vertex outside the patch's ring (an internal error: it cannot
// happen for the schemes' all-quad neighbourhoods).
#pragma once

#include <cstdint>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/subdiv/subd_patches.h"
#include "shaders_cpp/cage/topology.h"

namespace tessera {

inline constexpr int kFrameStencils = 40;

struct PatchFrames {
  // Patch p's stencil r is stored stencil  units[8 p + r / 8] + r % 8  for r < 32 (edge units), and
  // units[8 p + 4 + (r - 32) / 2] + r % 2  for the corners.
  std::vector<std::uint32_t> units;   // per patch 8: the first stored stencil of edge units 0..3, corner units 0..3
  std::vector<std::uint32_t> masks;   // per stored stencil: bit j = ring position j has a nonzero weight
  std::vector<std::uint32_t> starts;  // per stored stencil: its first weight in `weights`
  std::vector<float> weights;         // per stored stencil, its nonzero weights by ascending ring position
  int unit_count = 0;                 // distinct units (edge and corner)
  // Precomputed patches (a 1-ring over 32 points, subd_patches.h): their 40 stencils over cage vertices,
  // summed before the draw (precompute_rows); patch p's stencil r is row precomputed_first[p] + r of
  // that sum (-1: an ordinary patch). Their units hold empty stencils.
  std::vector<PrecomputedPatch> precomputed;
  std::vector<std::int32_t> precomputed_first;  // per patch

  std::uint32_t stencil(std::size_t patch, int r) const {
    return r < 32 ? units[8 * patch + std::size_t(r / 8)] + std::uint32_t(r % 8)
                  : units[8 * patch + 4 + std::size_t((r - 32) / 2)] + std::uint32_t(r % 2);
  }
  std::size_t bytes() const {
    return (units.size() + masks.size() + starts.size()) * sizeof(std::uint32_t) + weights.size() * sizeof(float);
  }
};

PatchFrames build_patch_frames(const Cage& cage, const Topology& topology, const PatchGroup& group, Scheme scheme);

}  // namespace tessera
