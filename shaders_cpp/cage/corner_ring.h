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

}  // namespace tessera
