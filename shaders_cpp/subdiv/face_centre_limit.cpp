#include "shaders_cpp/subdiv/face_centre_limit.h"

#include <algorithm>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/limit_masks.h"

namespace tessera {

namespace {

Stencil centroid(const Cage& cage, const Topology& t, int f) {
  const int n = t.face_size(f);
  Stencil c;
  for (int k = 0; k < n; ++k) c.add_vertex(cage.face_vertex(f, k), 1.0 / n);
  return c;
}

// (1 - s) a + s b with s clamped to [0, 1]: a tag's blend between the smooth and the sharp rule.
Stencil blend(const Stencil& smooth, const Stencil& sharp, double s) {
  if (s <= 0.0) return smooth;
  if (s >= 1.0) return sharp;
  Stencil out;
  return out.add(smooth, 1.0 - s).add(sharp, s);
}

// The vertex point of cage vertex v after one Catmull-Clark step.
Stencil vertex_point(const Cage& cage, const Topology& t, int v) {
  const auto ring = t.ring(v);  // outgoing half-edges, one per face
  if (t.corner_sharpness(v) >= kSharpnessInfinite) return Stencil::vertex(v);
  if (t.is_boundary_vertex(v)) {
    if (ring.size() == 1 && cage.tags.boundary == BoundaryInterpolation::edge_and_corner) return Stencil::vertex(v);
    Stencil s;
    s.add_vertex(t.destination(ring.front()), 1.0 / 8.0).add_vertex(v, 6.0 / 8.0);
    return s.add_vertex(t.origin(t.prev(ring.back())), 1.0 / 8.0);
  }
  const int n = int(ring.size());
  Stencil q, r;
  std::vector<int> tagged;
  double tag_sum = 0.0;
  for (const int g : ring) {
    q.add(centroid(cage, t, t.face(g)), 1.0 / n);
    r.add_vertex(v, 0.5 / n).add_vertex(t.destination(g), 0.5 / n);
    if (const float s = t.edge_sharpness(t.edge(g)); s > 0.0f) tagged.push_back(t.destination(g)), tag_sum += s;
  }
  Stencil smooth = q;
  smooth.add(r, 2.0).add_vertex(v, double(n - 3)).scale(1.0 / n);
  const double corner = t.corner_sharpness(v);
  if (corner > 0.0 || tagged.size() >= 3)
    return blend(smooth, Stencil::vertex(v), std::max(corner, tagged.empty() ? 0.0 : tag_sum / double(tagged.size())));
  if (tagged.size() == 2) {
    Stencil crease;
    crease.add_vertex(tagged[0], 1.0 / 8.0).add_vertex(v, 6.0 / 8.0).add_vertex(tagged[1], 1.0 / 8.0);
    return blend(smooth, crease, tag_sum / 2.0);
  }
  return smooth;
}

}  // namespace

FaceCentre face_centre_limit(const Cage& cage, const Topology& t, int f) {
  const int n = t.face_size(f);
  const Stencil c = centroid(cage, t, f);
  std::vector<Stencil> m(static_cast<std::size_t>(n)), d(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const int h = t.face_offset(f) + i;
    const int a = t.origin(h), b = t.destination(h);
    Stencil mid;
    mid.add_vertex(a, 0.5).add_vertex(b, 0.5);
    if (t.twin(h) < 0) {
      m[std::size_t(i)] = mid;
    } else {
      Stencil smooth;
      smooth.add_vertex(a, 0.25).add_vertex(b, 0.25).add(c, 0.25).add(centroid(cage, t, t.face(t.twin(h))), 0.25);
      m[std::size_t(i)] = blend(smooth, mid, t.edge_sharpness(t.edge(h)));
    }
    // The sub-quad between m_i and m_{i+1} has the vertex point of corner i + 1 opposite the centre.
    d[std::size_t(i)] = vertex_point(cage, t, t.destination(h));
  }
  FaceCentre out;
  out.position = double(n) * n * c;
  for (int i = 0; i < n; ++i) out.position.add(m[std::size_t(i)], 4.0).add(d[std::size_t(i)], 1.0);
  out.position.scale(1.0 / (double(n) * (n + 5)));
  // The ACC tangent mask on the all-quad ring (limit_masks.h), from edge j.
  auto at = [n](const std::vector<Stencil>& v) { return [&v, n](int i) { return v[std::size_t(i % n)]; }; };
  for (int j = 0; j < n; ++j) out.tangents.push_back(acc_tangent(n, j, at(m), at(d)));
  return out;
}

}  // namespace tessera
