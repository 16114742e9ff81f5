// The exact Catmull-Clark limit position at a cage vertex whose tags are semi-sharp, as a stencil over
// its 1-ring: what the per-face schemes put at such a patch corner instead of a blend of the smooth and
// the sharp corner, which is off by up to a fifth of an edge (catmark_cube_corner1: 0.17 of a 2.8 edge).
//
// A tag of sharpness s keeps its sharp rule for floor(s) Catmull-Clark steps and blends for the
// fraction after (uniform creasing, OpenSubdiv's default): after ceil(s) steps the vertex is smooth.
// The vertex's own ring is closed under refinement (its edge and face points depend on its 1-ring only),
// so the steps run on the ring alone, in stencils over the cage, and the all-quad limit mask ends them.
// Rules: edge points (v + e + f_a + f_b) / 4, the midpoint on a sharp edge, blended by s below 1; vertex
// points smooth (Q + 2 R + (n - 3) v) / n, crease (e_a + 6 v + e_b) / 8 between two sharp edges, corner v
// (a corner tag or three or more sharp edges); where the rule changes from one step to the next, the
// parent's rule point weighs the mean sharpness of what relaxes (OpenSubdiv's fractional weight).
//
// Contract: an interior manifold vertex with a finite positive tag (its corner or an incident edge);
// nullopt otherwise (untagged, infinitely sharp, boundary, or Chaikin creasing, whose relaxation reads
// the neighbouring edges' sharpness). Computed once per vertex, from its ring
// turned to start at its lowest neighbour, so every face reads the same bits.
#pragma once

#include <optional>

#include "shaders_cpp/subdiv/stencil.h"

namespace tessera {

struct Cage;
class Topology;

std::optional<Stencil> semi_sharp_limit_position(const Cage& cage, const Topology& topology, int vertex);

}  // namespace tessera
