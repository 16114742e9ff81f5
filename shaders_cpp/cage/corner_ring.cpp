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

CornerRing gather_creased_corner_ring(const Cage& cage, const Topology& t, int face, int k, float* vertex_sharpness) {
  CornerRing whole = gather_corner_ring(cage, t, face, k);
  const int v = whole.center;
  if (vertex_sharpness) *vertex_sharpness = 0.0f;
  if (!t.has_sharpness_at(v)) return whole;
  // The sharp edges of the ring, by edge index (a boundary ring's first and last edge are sharp).
  const auto ring = t.ring(v);
  const int edges = whole.valence(), faces = whole.face_count();
  std::vector<char> sharp(std::size_t(edges), 0);
  int count = 0, inner = 0;
  double inner_sum = 0.0;
  // The ring as gathered: an interior one is rotated so the face is at 0; ring[] is not.
  const int turn = whole.boundary ? 0 : [&] {
    const int h = t.face_offset(face) + k;
    for (std::size_t i = 0; i < ring.size(); ++i)
      if (ring[i] == h) return int(i);
    return 0;
  }();
  for (int i = 0; i < edges; ++i) {
    float s = 0.0f;
    if (whole.boundary && (i == 0 || i == edges - 1)) {
      s = kSharpnessInfinite;
    } else {
      s = t.edge_sharpness(t.edge(ring[std::size_t((i + turn) % int(ring.size()))]));
      if (s < kCutSharpness) continue;
      ++inner, inner_sum += double(std::min(s, kSharpnessInfinite));
    }
    sharp[std::size_t(i)] = 1, ++count;
  }
  const float corner = t.corner_sharpness(v);
  if (vertex_sharpness)
    *vertex_sharpness = corner >= kCutSharpness ? corner : inner > 0 ? float(inner_sum / inner) : 0.0f;
  whole.sharp_corner = whole.sharp_corner || count >= 3 || corner >= kCutSharpness;
  if (count < 2 || inner == 0) return whole;  // a dart, or a boundary with no crease: its whole ring
  // The wedge: from the last sharp edge at or before the face's edge (slot) to the first after it.
  const int slot = whole.slot;
  auto wrap = [&](int i) { return whole.boundary ? i : ((i % edges) + edges) % edges; };
  int a = slot;
  while (!sharp[std::size_t(wrap(a))]) --a;
  int b = slot + 1;
  while (!sharp[std::size_t(wrap(b))]) ++b;
  CornerRing w;
  w.center = v;
  w.boundary = true;
  w.sharp_corner = whole.sharp_corner;
  for (int i = a; i <= b; ++i) w.edges.push_back(whole.edges[std::size_t(wrap(i))]);
  for (int i = a; i < b; ++i) w.face_others.push_back(whole.face_others[std::size_t(wrap(i) % faces)]);
  w.slot = slot - a;
  return w;
}

}  // namespace tessera
