// The neighbourhood of one corner of a patch face, in the vocabulary of Loop & Schaefer's masks: the
// corner vertex p, its edge neighbours e_i counter-clockwise (seen from outside), and between e_i and
// e_{i+1} a face whose remaining vertices are listed (one, d_i, for a quad; none for a triangle).
//
// Contract: for the patch face itself, faces[slot] is the face, e_slot is the next corner of the face
// (the edge corner -> corner+1) and e_{slot+1} the previous corner. An interior ring has n edges and n
// faces and is rotated so slot == 0; a boundary ring has n edges and n-1 faces and starts at a boundary
// edge (e_0 and e_{n-1} are the boundary neighbours).
#pragma once

#include <vector>

namespace tessera {

struct CornerRing {
  int center = -1;
  bool boundary = false;
  bool sharp_corner = false;                  // interpolated: a tagged corner, or a valence-2 boundary corner
  std::vector<int> edges;                     // e_0 .. e_{n-1}
  std::vector<std::vector<int>> face_others;  // per face i: its vertices strictly between e_i and e_{i+1}
  int slot = 0;

  int valence() const { return static_cast<int>(edges.size()); }
  int face_count() const { return static_cast<int>(face_others.size()); }
  bool all_quads() const {
    for (const auto& f : face_others)
      if (f.size() != 1) return false;
    return true;
  }
  // e_i with i taken modulo the valence (interior rings are cyclic).
  int e(int i) const {
    const int n = valence();
    return edges[std::size_t(((i % n) + n) % n)];
  }
  // d_i of an all-quad interior ring, i modulo the valence.
  int d(int i) const {
    const int n = face_count();
    return face_others[std::size_t(((i % n) + n) % n)][0];
  }
};

}  // namespace tessera

namespace tessera {

struct Cage;
class Topology;

// The ring of corner k of face f. A vertex is a sharp corner when its corner sharpness is infinite, or
// when it is a valence-2 boundary vertex and the cage interpolates boundary corners.
CornerRing gather_corner_ring(const Cage& cage, const Topology& topology, int face, int k);

// Creases and corner tags below this sharpness relax within the first subdivision step: the per-face
// schemes draw them smooth.
inline constexpr float kCutSharpness = 1.0f;

// The ring of corner k of face f with the cage's creases cut open: every edge of sharpness at least
// kCutSharpness taken as infinitely sharp. Where the vertex has two or more such edges (a boundary's edges count),
// the ring is the wedge of faces between the sharp edges on either side of the face, as a boundary
// ring starting at the first of them; with three or more it is also a sharp corner (Catmull-Clark's
// crease and corner rules, which on each side of a crease are the boundary rules). A dart (one sharp
// edge, inside) keeps its whole ring. `vertex_sharpness`, when given, receives the sharpness the
// crease rule would use at the vertex: its corner tag's, or else the mean of its sharp inner edges'
// (0 when the ring is not cut).
CornerRing gather_creased_corner_ring(const Cage& cage, const Topology& topology, int face, int k,
                                      float* vertex_sharpness = nullptr);

}  // namespace tessera
