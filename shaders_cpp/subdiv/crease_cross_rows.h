// The cross-derivative rows of a patch's averaged edges (SubdPatch::averaged_edges): along a semi-sharp
// crease, and along a smooth edge with a tag at one end between two fitted faces, the domain shader
// gives a point on the edge a normal from the neighbour's inward derivative as well as the patch's own.
//
// A semi-sharp crease's exact limit is smooth on the crease line itself (one normal, about the mean of
// the two sides') and creased a band of width 2^-s away, so the line takes the mean of the two patches'
// normals. A smooth edge at a tag bends within a fraction of the face (a corner tag's cone), which no
// bicubic follows, so it takes the limit's own derivative into the neighbour. Positions are untouched.
//
// Contract: the rows are those the neighbour's own patch has (the same crease blend), or the exact
// limit's derivative into it where it is fitted (FittedFaces), so both faces see one edge.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/fitted_faces.h"
#include "shaders_cpp/subdiv/stencil.h"

namespace tessera::subdiv {

// The Gregory stencils of a triangle or quad from its corner 0, blended at its creases as its own patch
// is, each built once: the rows a neighbour reads its cross derivative from, and the quad rows a polar
// triangle and an acc quad read across an edge.
class NeighbourRows {
 public:
  NeighbourRows(const Cage& cage, const Topology& t, const std::vector<std::optional<Stencil>>& semi_sharp)
      : cage_(cage), t_(t), semi_sharp_(semi_sharp) {}
  const std::vector<Stencil>& of(int face);

 private:
  const Cage& cage_;
  const Topology& t_;
  const std::vector<std::optional<Stencil>>& semi_sharp_;
  std::map<int, std::vector<Stencil>> rows_;
};

struct CrossRows {
  std::vector<Stencil> rows;  // kCrossRows rows from our corner k; empty: not an averaged edge
  bool limit = false;         // the limit's own derivative into the neighbour (SubdPatch::limit_edges)
};

// The kCrossRows rows of patch edge k of face f (n sides; patch corner k is face corner k + rot) when
// the edge is a semi-sharp crease between f and a triangle or quad, or a smooth edge at a tag whose
// neighbour is fitted; empty otherwise.
CrossRows neighbour_cross_rows(const Topology& t, int f, int n, int rot, int k, NeighbourRows& rows,
                               const FittedFaces& fitted);

}  // namespace tessera::subdiv
