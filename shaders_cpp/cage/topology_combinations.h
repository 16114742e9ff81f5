// Topology combinations (the talk's nvAnalyze): faces grouped by the structure of their 1-ring, so
// that work depending only on that structure (a stencil table mapping 1-ring vertices to patch control
// points) is done once per combination and applied to every face that has it.
//
// The combination key of a non-hole face f of n corners, corner k at vertex v (half-edge h = offset + k):
//   n, then per corner, in the face's order starting from the canonical corner:
//     boundary flag, number of faces around v, f's position in v's fan (0 for an interior vertex, whose
//     cyclic fan is read starting at f), the size of every face around v in ring order (ring(v),
//     topology.h) from that start, v's corner sharpness, and the crease sharpness of every edge at v in
//     the same order (bit patterns of the floats, so any sharpness difference is a different key).
//   Valence follows: number of faces, + 1 on a boundary.
// The canonical corner is the rotation r whose corner sequence (r, r+1, ...) is lexicographically
// smallest; the smallest such r when the face is symmetric. `rotation` is r: canonical corner i is the
// face's corner (i + r) % n.
//
// What the key identifies: each corner's fan (faces, their sizes, their order, tags on the edges at the
// corner) as a local, unfolded structure. Two faces with equal keys, both read from their canonical
// corner, walk identical 1-rings: same number of 1-ring vertices reached in the same order by the same
// traversal. Global coincidences (one vertex reached from two corners, as in a cube where the 1-ring of
// a face is the whole cube) are not part of the key, so stencils must be built on the unfolded 1-ring.
// Not in the key: hole flags of neighbours (holes still contribute vertices) and the cage-wide options
// (boundary interpolation, crease method), which are the same for every face.
//
// Classes (counted over non-hole faces):
// - regular: a quad whose 4 corners are interior, valence 4, with only quads around them and no
//   crease or corner sharpness at any corner: a bicubic B-spline patch.
// - boundary: a corner is on a boundary.
// - regular boundary: a boundary quad whose every corner is interior valence 4, boundary valence 3
//   (2 faces) or a boundary corner of valence 2 (1 face), only quads around, no sharpness: a B-spline
//   patch with boundary (and corner) rules.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shaders_cpp/cage/topology.h"

namespace tessera {

enum class PatchClass : std::uint8_t { hole, regular, regular_boundary, boundary, irregular };

struct Combination {
  std::vector<std::int32_t> key;  // as described above; equal keys <=> equal 1-ring structure
  std::string text;               // readable, see combination_text()
  int face_size = 0;
  bool boundary = false;                           // some corner is on a boundary
  PatchClass patch_class = PatchClass::irregular;  // the class of every face with this key
  int count = 0;                                   // faces with this key
  std::vector<int> faces;                          // all of them, ascending
};

struct CombinationStats {
  int patches = 0, triangles = 0, quads = 0, polygons = 0;  // non-hole faces, by size (polygons: > 4)
  int regular = 0, boundary = 0, regular_boundary = 0;
};

struct TopologyCombinations {
  std::vector<Combination> combinations;  // in order of the first face that has each key
  std::vector<int> face_combination;      // per face: index into combinations, -1 for a hole
  std::vector<int> face_rotation;         // per face: the canonical corner r (0 for a hole)
  // Per face: the smallest p > 0 such that reading from corner r + p gives the same key (the face's
  // rotational symmetry: 1 for a regular quad, n for a face with none; 1 for a hole). Starting at any
  // corner r + m p keeps the face's combination and its canonical rotation.
  std::vector<int> face_period;
  std::vector<PatchClass> face_class;     // per face
  CombinationStats stats;
};

// O(sum over faces of their 1-ring size). Holes get no combination.
TopologyCombinations analyze_combinations(const Topology& topology);

// The readable form, after the talk: the corner valences from the canonical corner, space separated.
// A triangle starts with 0 (the talk's mark for the missing fourth corner). A corner gets the suffix
// 'b' on a boundary, '*' when sharpness touches it, and "(s1 s2 ...)" with the sizes of the faces in its
// fan when they are not all quads (ring order: from the face for an interior vertex, from the boundary
// for a boundary one), e.g. "5 4 4 4", "0 6 6 7", "3b 3b 4 4", "4 4(4 3 4 4) 4 4*". The text leaves
// out sharpness values and a boundary face's place in its fans, so two combinations can read alike.
std::string combination_text(const Topology& topology, int face, int rotation);

}  // namespace tessera
