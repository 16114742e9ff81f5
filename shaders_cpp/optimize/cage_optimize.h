// Cage optimization for the tessellation pipeline, after NVIDIA's mesh processing tool: the same limit
// surface, with each face's start corner rotated and faces and vertices reordered.
//
// - Fewest topology combinations. A combination's key is read from its canonical corner
//   (topology_combinations.h), but the hull shader's stencil table is indexed from the corner the face
//   starts at: as stored, faces of one combination starting at different corners need different tables.
//   Starting every face at a canonical corner leaves one table per combination (the talk's 105 -> 23 is
//   this count, after remodelling; rotation alone reaches the number of combinations).
// - Consistent adjacency. A quad's parameter runs along its edges 0 and 1 in their direction and along
//   edges 2 and 3 against it; a shared edge is consistent when both faces' parameters run the same way
//   along it (one face sees it as edge 0 or 1, the other as edge 2 or 3), as in a regular grid. Among a
//   symmetric face's canonical corners (face_period), a greedy pass in breadth-first order picks the one
//   consistent with most neighbours already placed.
// - Locality. Faces are ordered by meshoptimizer's vertex-cache optimizer over their fan triangles (each
//   face at its first triangle), vertices and texture coordinates by first use (meshoptimizer's fetch
//   remap).
// Tags follow their vertices and faces; UVs stay with their corners; positions are copied bit for bit.
//
// Contract: throws CageError (one line naming the cage) for a cage its Topology refuses. Deterministic.
#pragma once

#include <vector>

#include "shaders_cpp/cage/cage.h"

namespace tessera {

struct CageOptimizeOptions {
  bool rotate = true;        // canonical start corners, then consistent adjacency
  bool reorder = true;       // face and vertex order for locality
  unsigned cache_size = 16;  // for the vertex-cache statistics
};

struct CageOptimizeReport {
  int faces = 0;
  int combinations = 0;                     // distinct keys: the floor for the next two
  int stored_before = 0, stored_after = 0;  // distinct (key, start corner) pairs: stencil tables as stored
  int quad_edges = 0;                       // edges between two quads
  int consistent_before = 0, consistent_after = 0;
  // At the canonical corners alone (what the combination count asks for, before the choice among
  // symmetric corners): minimizing combinations can cost consistency that the input had.
  int consistent_canonical = 0;
  float acmr_before = 0, acmr_after = 0;  // fan triangles through a FIFO cache of cache_size
  float atvr_before = 0, atvr_after = 0;
};

struct OptimizedCage {
  Cage cage;
  std::vector<int> face_of;    // per new face: the old face
  std::vector<int> shift;      // per new face: new corner k is old corner (k + shift) % n
  std::vector<int> vertex_of;  // per new vertex: the old vertex
  CageOptimizeReport report;
};

OptimizedCage optimize_cage(const Cage& cage, const CageOptimizeOptions& options = {});

}  // namespace tessera
