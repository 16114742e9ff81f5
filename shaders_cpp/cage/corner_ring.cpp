#include "shaders_cpp/cage/corner_ring.h"

#include <algorithm>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"

namespace tessera {

CornerRing gather_corner_ring(const Cage& cage, const Topology& t, int face, int k) {
  const int h = t.face_offset(face) + k;
  const int v = t.origin(h);
  const auto ring = t.ring(v);
  CornerRing r;
  r.center = v;
  r.boundary = t.is_boundary_vertex(v);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const int g = ring[i];
    r.edges.push_back(t.destination(g));
    const int f = t.face(g), n = t.face_size(f), c = t.corner(g);
    std::vector<int> others;
    for (int m = 2; m + 1 < n; ++m) others.push_back(cage.face_vertex(f, (c + m) % n));
    r.face_others.push_back(std::move(others));
    if (g == h) r.slot = int(i);
  }
  if (r.boundary) {
    r.edges.push_back(t.origin(t.prev(ring.back())));
  } else {
    std::rotate(r.edges.begin(), r.edges.begin() + r.slot, r.edges.end());
    std::rotate(r.face_others.begin(), r.face_others.begin() + r.slot, r.face_others.end());
    r.slot = 0;
  }
  r.sharp_corner = t.corner_sharpness(v) >= kSharpnessInfinite ||
                   (r.boundary && r.valence() == 2 && cage.tags.boundary == BoundaryInterpolation::edge_and_corner);
  return r;
}

}  // namespace tessera
