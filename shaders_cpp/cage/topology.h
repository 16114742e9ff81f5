// Half-edge topology of a Cage, built once and validated; what the subdivision schemes walk.
//
// Conventions (the schemes and their stencils depend on them):
// - Half-edge h of face f, corner k is h = cage.face_offsets[f] + k. It goes from face_vertex(f, k) to
//   face_vertex(f, (k + 1) % n), so half-edges and cage.face_vertices / cage.face_uvs share indices.
// - twin(h) is the half-edge of the other face on the same edge, going the other way; -1 on a boundary.
// - Edges (undirected) are numbered in order of first use: walking h = 0, 1, 2, ..., an edge gets the
//   next id the first time one of its half-edges is seen. edge_half_edges(e)[0] is that first half-edge.
// - ring(v) lists the half-edges leaving v, one per incident face, counter-clockwise seen from outside
//   (faces are counter-clockwise): ring[i + 1] = twin(prev(ring[i])). An interior vertex's ring is a
//   cycle (ring[0] is the outgoing half-edge of its first face in face order). A boundary vertex's ring
//   starts at its boundary outgoing half-edge (twin == -1) and ends at the face whose incoming half-edge
//   prev(ring.back()) lies on the other boundary edge; valence = ring size + 1 there.
// - Valence is the number of incident edges; vertex_face_count the number of incident faces.
// - Holes (CageTags::holes) are faces like any other here: they take part in the topology and make no
//   boundary; the schemes just make no surface for them.
//
// Validation (throws CageError, one line naming the cage and the element): vertex index out of range,
// a face with fewer than 3 corners or a repeated vertex, an edge of more than two faces (non-manifold
// edge), two faces using the same directed edge (inconsistent orientation), a vertex whose faces form more
// than one fan (non-manifold vertex), hole or tag indices out of range, a negative or non-finite sharpness.
// Fallbacks, reported in warnings() and not errors: isolated vertices (used by no face; they get valence 0
// and an empty ring), creases between two vertices that share no edge (ignored). A vertex or edge tagged
// twice keeps the last sharpness, as OpenSubdiv does.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "shaders_cpp/cage/cage.h"

namespace tessera {

// Infinitely sharp, as OpenSubdiv's Sdc::Crease::SHARPNESS_INFINITE.
inline constexpr float kSharpnessInfinite = 10.0f;

class Topology {
 public:
  // Builds and validates; throws CageError. O(number of face corners), expected.
  explicit Topology(const Cage& cage);

  int vertex_count() const { return int(ring_offsets_.size()) - 1; }
  int face_count() const { return int(face_sizes_.size()); }
  int half_edge_count() const { return int(origin_.size()); }
  int edge_count() const { return int(edge_half_edges_.size()); }

  int face_size(int f) const { return face_sizes_[f]; }
  int face_offset(int f) const { return face_offsets_[f]; }
  // The first half-edge of face f (corner 0).
  int face_half_edge(int f) const { return face_offsets_[f]; }
  bool is_hole(int f) const { return hole_[f] != 0; }

  int origin(int h) const { return origin_[h]; }
  int destination(int h) const { return origin_[next(h)]; }
  int face(int h) const { return face_[h]; }
  int corner(int h) const { return h - face_offsets_[face_[h]]; }  // k in h = face_offsets[f] + k
  int twin(int h) const { return twin_[h]; }
  int next(int h) const {
    const int f = face_[h];
    return h + 1 == face_offsets_[f] + face_sizes_[f] ? face_offsets_[f] : h + 1;
  }
  int prev(int h) const {
    const int f = face_[h];
    return h == face_offsets_[f] ? face_offsets_[f] + face_sizes_[f] - 1 : h - 1;
  }
  int edge(int h) const { return edge_[h]; }

  // The two half-edges of edge e: [0] the one seen first, [1] its twin or -1 on a boundary.
  std::array<int, 2> edge_half_edges(int e) const { return edge_half_edges_[e]; }
  bool is_boundary_edge(int e) const { return edge_half_edges_[e][1] < 0; }

  int valence(int v) const { return valence_[v]; }
  int vertex_face_count(int v) const { return ring_offsets_[v + 1] - ring_offsets_[v]; }
  bool is_boundary_vertex(int v) const { return boundary_[v] != 0; }
  bool is_isolated(int v) const { return vertex_face_count(v) == 0; }
  // Outgoing half-edges of v, counter-clockwise (see the conventions above).
  std::span<const int> ring(int v) const {
    return {ring_.data() + ring_offsets_[v], std::size_t(ring_offsets_[v + 1] - ring_offsets_[v])};
  }
  // The corner k of face f at vertex v, or -1 when v is not a vertex of f.
  int corner_of(int f, int v) const;

  // Sharpness from the tags: 0 smooth, >= kSharpnessInfinite infinitely sharp. Boundary rules
  // (CageTags::boundary) are not folded in; they are the scheme's business.
  float corner_sharpness(int v) const { return corner_sharpness_[v]; }
  float edge_sharpness(int e) const { return edge_sharpness_[e]; }
  // True when v has a corner sharpness or an incident edge with a crease sharpness.
  bool has_sharpness_at(int v) const { return sharp_at_[v] != 0; }

  // Isolated vertices and ignored tags, one line each naming the cage.
  const std::vector<std::string>& warnings() const { return warnings_; }
  const std::vector<int>& isolated_vertices() const { return isolated_; }

 private:
  // The constructor's stages, in order; each throws CageError for what it finds wrong.
  void read_faces(const Cage& cage);
  void build_edges(const Cage& cage);
  void build_rings(const std::string& name, int vertex_count);
  void read_tags(const Cage& cage);
  // The edge between vertices a and b (from their rings), or -1.
  int edge_between(int a, int b) const;

  std::vector<int> face_sizes_, face_offsets_;
  std::vector<char> hole_;
  std::vector<int> origin_, face_, twin_, edge_;
  std::vector<std::array<int, 2>> edge_half_edges_;
  std::vector<int> valence_, ring_offsets_, ring_;
  std::vector<char> boundary_, sharp_at_;
  std::vector<float> corner_sharpness_, edge_sharpness_;
  std::vector<int> isolated_;
  std::vector<std::string> warnings_;
};

// Builds the topology and throws away the result: the check cage.h's contract refers to.
void validate_cage(const Cage& cage);

// Per edge: true when the two faces on an interior edge give it different texture coordinate indices at
// either end (a UV seam). All false when the cage has no UVs. Boundary edges are not seams.
std::vector<bool> uv_seam_edges(const Cage& cage, const Topology& topology);

}  // namespace tessera
