// Non-manifold cages drawn as OpenSubdiv draws them: the cage is split into a manifold one whose limit
// surface is OpenSubdiv's limit surface of the original, so every scheme and the half-edge topology
// (topology.h) see only manifold cages.
//
// What OpenSubdiv (Vtr, Far::TopologyRefinerFactory) does with such places, and so what the split keeps:
// - a non-manifold edge (three or more faces, two faces using it in the same direction, a face using it
//   twice, or a degenerate edge) is infinitely sharp; an edge a face uses twice counts, from its second
//   use in that face on, as one more edge at its ends (Vtr makes it a new edge instance);
// - a non-manifold vertex (on such an edge, repeated in a face, or whose faces form more than one fan) is
//   an infinitely sharp corner, except in the middle of a non-manifold crease (exactly two non-manifold
//   edges, no boundary edge, more faces than edges), which keeps the crease rule.
// An infinitely sharp edge decouples the faces on its two sides exactly (the crease rules read only the
// edge's own vertices), so the faces around such a place can be given their own copies of its vertices:
// corners of a vertex stay one vertex while consecutive faces share a manifold edge there (two faces, in
// opposite directions), and every other group of them gets a copy at the same position. The split edges
// carry an infinite crease tag and the split vertices an infinite corner tag (the exception above aside),
// so the boundary rules treat them as OpenSubdiv does ("none" makes no hole at an infinitely sharp edge).
// Faces keep their indices and corner order (UVs and holes unchanged); vertex v keeps index v (its first
// group of corners), copies are appended in order of first use.
//
// Cost: O(face corners) after a bucket sort of the edges; a manifold cage is returned untouched.
#pragma once

#include <string>
#include <vector>

#include "shaders_cpp/cage/cage.h"

namespace tessera {

// One place OpenSubdiv's non-manifold rules apply to, for `tessera analyze` and warnings.
struct NonManifoldPlace {
  enum class Kind { edge, repeated_vertex, vertex } kind = Kind::edge;
  int v0 = -1, v1 = -1;    // the vertices (an edge's two; v1 = -1 for a vertex)
  std::vector<int> faces;  // the faces around it, in face order
  int fans = 0;            // a vertex: how many groups of its corners (copies) it became
  bool corner = false;     // a vertex: sharpened to an infinitely sharp corner
};

// One line: "non-manifold edge between vertices 8 and 9 (0-based): 3 faces (1, 6, 10); drawn
// infinitely sharp", "face 1 uses vertex 4 twice; ...", "non-manifold vertex 5: its 8 faces form 8 fans; ...".
std::string describe(const NonManifoldPlace& place);

// Splits `cage` in place as above when it has non-manifold places (it is left untouched otherwise) and
// returns them. Fills Cage::vertex_source (copy -> vertex of the original) and Cage::non_manifold, and
// adds one line to Cage::warnings. Throws CageError (one line) only when a face would still use one
// vertex twice within one fan of corners, which no manifold cage can draw.
std::vector<NonManifoldPlace> split_non_manifold(Cage& cage);

}  // namespace tessera
