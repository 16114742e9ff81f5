#include "shaders_cpp/subdiv/limit_masks.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tessera {

namespace {

constexpr double kPi = std::numbers::pi;

Stencil centroid(const CornerRing& r, int i) {
  // Face i: p, e_i, others..., e_{i+1}.
  const auto& others = r.face_others[std::size_t(i)];
  const double w = 1.0 / double(3 + others.size());
  Stencil c;
  c.add_vertex(r.center, w).add_vertex(r.e(i), w).add_vertex(r.e(i + 1), w);
  for (int v : others) c.add_vertex(v, w);
  return c;
}

}  // namespace

Stencil far_point(const CornerRing& r, int i) {
  const int n = r.face_count();
  i = ((i % n) + n) % n;
  const auto& others = r.face_others[std::size_t(i)];
  if (others.size() == 1) return Stencil::vertex(others[0]);
  Stencil d = 4.0 * centroid(r, i);
  d.add_vertex(r.center, -1.0).add_vertex(r.e(i), -1.0).add_vertex(r.e(i + 1), -1.0);
  return d;
}

int pseudo_valence(const CornerRing& r) {
  if (!r.boundary) return r.valence();
  return r.valence() == 2 ? 4 : 2 * (r.valence() - 1);
}

Stencil limit_position(const CornerRing& ring) {
  const int n = ring.valence();
  if (ring.sharp_corner) return Stencil::vertex(ring.center);
  // Every face at the vertex computes this point, each from the ring rotated to its own face. Sums
  // of unequal weights (a triangle's and a quad's share of p) depend on their order, so an interior
  // ring is first turned to start at its lowest-index neighbour: every face adds in the same order.
  CornerRing r = ring;
  if (!r.boundary) {
    const auto first = std::min_element(r.edges.begin(), r.edges.end()) - r.edges.begin();
    std::rotate(r.edges.begin(), r.edges.begin() + first, r.edges.end());
    std::rotate(r.face_others.begin(), r.face_others.begin() + first, r.face_others.end());
    r.slot = 0;  // no longer the patch face; the position does not need it
  }
  if (r.boundary) {
    Stencil s;
    s.add_vertex(r.edges.front(), 1.0 / 6.0).add_vertex(r.center, 4.0 / 6.0).add_vertex(r.edges.back(), 1.0 / 6.0);
    return s;
  }
  if (r.all_quads()) {
    Stencil s;
    s.add_vertex(r.center, double(n) * n);
    for (int i = 0; i < n; ++i) s.add_vertex(r.e(i), 4.0).add_vertex(r.d(i), 1.0);
    return s.scale(1.0 / (double(n) * (n + 5)));
  }
  // One Catmull-Clark step turns the ring into quads around the vertex point V; then the quad mask.
  std::vector<Stencil> face_points(static_cast<std::size_t>(n)), edge_points(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) face_points[std::size_t(i)] = centroid(r, i);
  Stencil favg, ravg;
  for (int i = 0; i < n; ++i) {
    Stencil e;
    e.add_vertex(r.center, 0.25).add_vertex(r.e(i), 0.25);
    e.add(face_points[std::size_t((i + n - 1) % n)], 0.25).add(face_points[std::size_t(i)], 0.25);
    edge_points[std::size_t(i)] = e;
    favg.add(face_points[std::size_t(i)], 1.0 / n);
    ravg.add_vertex(r.center, 0.5 / n).add_vertex(r.e(i), 0.5 / n);
  }
  Stencil v = favg;
  v.add(ravg, 2.0).add_vertex(r.center, double(n - 3));
  v.scale(1.0 / n);
  Stencil s = double(n) * n * v;
  for (int i = 0; i < n; ++i) s.add(edge_points[std::size_t(i)], 4.0).add(face_points[std::size_t(i)], 1.0);
  return s.scale(1.0 / (double(n) * (n + 5)));
}

Stencil limit_tangent(const CornerRing& r, int j) {
  const int n = r.valence();
  if (r.sharp_corner) {
    Stencil t = Stencil::vertex(r.e(j));
    return t.add_vertex(r.center, -1.0);
  }
  if (r.boundary) {
    // k faces, theta = pi / k; edge j leaves at angle j * theta from the first boundary edge.
    const int k = n - 1;
    const double theta = kPi / k, c = std::cos(theta), s = std::sin(theta);
    Stencil r1;  // along the boundary, toward e_0
    r1.add_vertex(r.edges.front(), 0.5).add_vertex(r.edges.back(), -0.5);
    Stencil r0;  // across the boundary, into the surface
    const double den = 3.0 * k + c;
    r0.add_vertex(r.center, -4.0 * s / den);
    const double b = -(1.0 + 2.0 * c) * std::sqrt(1.0 + c) / (den * std::sqrt(1.0 - c));
    r0.add_vertex(r.edges.front(), b).add_vertex(r.edges.back(), b);
    for (int i = 1; i < k; ++i) r0.add_vertex(r.edges[std::size_t(i)], 4.0 * std::sin(i * theta) / den);
    for (int i = 0; i < k; ++i) r0.add(far_point(r, i), (std::sin(i * theta) + std::sin((i + 1) * theta)) / den);
    Stencil t = std::sin(j * theta) * r0;
    t.add(r1, std::cos(j * theta));
    return t;
  }
  return acc_tangent(
      n, j, [&](int i) { return Stencil::vertex(r.e(i)); }, [&](int i) { return far_point(r, i); });
}

Stencil acc_tangent(int n, int j, const std::function<Stencil(int)>& e, const std::function<Stencil(int)>& d) {
  const double cpn = std::cos(kPi / n);
  const double root = std::sqrt(4.0 + cpn * cpn);
  Stencil t;
  for (int i = 0; i < n; ++i) {
    const double alpha = (1.0 / n + cpn / (n * root)) * std::cos(2.0 * kPi * i / n);
    const double beta = (1.0 / (n * root)) * std::cos(2.0 * kPi * (i + 0.5) / n);
    t.add(e(j + i), alpha);
    t.add(d(j + i), beta);
  }
  return t;
}

}  // namespace tessera
