#include "shaders_cpp/cage/boundary_rule.h"

namespace tessera {

std::vector<bool> faces_without_surface(const Cage& cage, const Topology& t) {
  std::vector<bool> none(std::size_t(t.face_count()), false);
  if (cage.tags.boundary != BoundaryInterpolation::none) return none;
  for (int v = 0; v < t.vertex_count(); ++v) {
    if (!t.is_boundary_vertex(v)) continue;
    // A boundary vertex's ring starts at its outgoing boundary half-edge and ends at the face whose
    // incoming half-edge lies on the other boundary edge (topology.h).
    const std::span<const int> ring = t.ring(v);
    const int out = t.edge(ring.front()), in = t.edge(t.prev(ring.back()));
    const bool soft = t.edge_sharpness(out) < kSharpnessInfinite || t.edge_sharpness(in) < kSharpnessInfinite;
    if (!soft) continue;
    for (const int h : ring) none[std::size_t(t.face(h))] = true;
  }
  return none;
}

}  // namespace tessera
