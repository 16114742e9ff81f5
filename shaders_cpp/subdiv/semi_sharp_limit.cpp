#include "shaders_cpp/subdiv/semi_sharp_limit.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"

namespace tessera {

namespace {

enum class VertexRule { smooth, crease, corner };

VertexRule rule_of(double corner, const std::vector<double>& sharp) {
  const auto tagged = std::count_if(sharp.begin(), sharp.end(), [](double s) { return s > 0.0; });
  if (corner > 0.0 || tagged >= 3) return VertexRule::corner;
  return tagged == 2 ? VertexRule::crease : VertexRule::smooth;
}

}  // namespace

std::optional<Stencil> semi_sharp_limit_position(const Cage& cage, const Topology& t, int v) {
  // Chaikin creasing relaxes an edge by its neighbours' sharpness, outside the vertex's own ring.
  if (t.is_boundary_vertex(v) || cage.tags.crease_method != CreaseMethod::uniform) return std::nullopt;
  const auto half_edges = t.ring(v);  // outgoing, counter-clockwise; face i lies between edges i and i + 1
  const int n = int(half_edges.size());
  if (n < 3) return std::nullopt;
  std::vector<int> ring(half_edges.begin(), half_edges.end());
  // Every face computes this vertex's point: start at the lowest neighbour so the sums run in one order.
  const auto first =
      std::min_element(ring.begin(), ring.end(), [&](int a, int b) { return t.destination(a) < t.destination(b); });
  std::rotate(ring.begin(), first, ring.end());
  double corner = t.corner_sharpness(v);
  std::vector<double> sharp(static_cast<std::size_t>(n));
  double most = corner;
  for (int i = 0; i < n; ++i) {
    sharp[std::size_t(i)] = t.edge_sharpness(t.edge(ring[std::size_t(i)]));
    most = std::max(most, sharp[std::size_t(i)]);
  }
  if (!(most > 0.0) || most >= kSharpnessInfinite) return std::nullopt;

  const auto at = [n](int i) { return std::size_t(((i % n) + n) % n); };
  Stencil c = Stencil::vertex(v);
  std::vector<Stencil> e(static_cast<std::size_t>(n)), d(static_cast<std::size_t>(n)), fp(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) e[at(i)] = Stencil::vertex(t.destination(ring[at(i)]));
  bool quads = false;  // after the first step the ring is all quads (c, e_i, d_i, e_{i+1})
  for (int step = 0; most > 0.0 && step < 16; ++step) {
    for (int i = 0; i < n; ++i) {
      Stencil f;
      if (quads) {
        f.add(c, 0.25).add(e[at(i)], 0.25).add(d[at(i)], 0.25).add(e[at(i + 1)], 0.25);
      } else {
        const int face = t.face(ring[at(i)]), m = t.face_size(face);
        for (int k = 0; k < m; ++k) f.add_vertex(cage.face_vertex(face, k), 1.0 / m);
      }
      fp[at(i)] = f;
    }
    std::vector<Stencil> ep(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      Stencil mid;
      mid.add(c, 0.5).add(e[at(i)], 0.5);
      const double s = sharp[at(i)];
      if (s >= 1.0) {
        ep[at(i)] = mid;
        continue;
      }
      Stencil smooth;
      smooth.add(c, 0.25).add(e[at(i)], 0.25).add(fp[at(i - 1)], 0.25).add(fp[at(i)], 0.25);
      ep[at(i)] = s > 0.0 ? Stencil{}.add(smooth, 1.0 - s).add(mid, s) : smooth;
    }
    std::vector<double> child(sharp.size());
    for (std::size_t i = 0; i < sharp.size(); ++i) child[i] = std::max(0.0, sharp[i] - 1.0);
    const double child_corner = std::max(0.0, corner - 1.0);
    const auto point = [&](VertexRule r, const std::vector<double>& s) {
      if (r == VertexRule::corner) return c;
      if (r == VertexRule::crease) {
        Stencil p = 0.75 * c;
        for (int i = 0; i < n; ++i)
          if (s[at(i)] > 0.0) p.add(e[at(i)], 0.125);
        return p;
      }
      Stencil p;
      for (int i = 0; i < n; ++i) p.add(fp[at(i)], 1.0 / n).add(c, 1.0 / n).add(e[at(i)], 1.0 / n);
      return p.add(c, double(n - 3)).scale(1.0 / n);
    };
    const VertexRule parent_rule = rule_of(corner, sharp), child_rule = rule_of(child_corner, child);
    Stencil next = point(parent_rule, sharp);
    if (child_rule != parent_rule) {
      double sum = 0.0;
      int count = 0;
      if (corner > 0.0 && child_corner <= 0.0) sum += corner, ++count;
      for (std::size_t i = 0; i < sharp.size(); ++i)
        if (sharp[i] > 0.0 && child[i] <= 0.0) sum += sharp[i], ++count;
      const double w = count > 0 ? std::min(1.0, sum / count) : 0.0;
      next = Stencil{}.add(next, w).add(point(child_rule, child), 1.0 - w);
    }
    c = next;
    e = ep;
    d = fp;
    quads = true;
    sharp = child;
    corner = child_corner;
    most = corner;
    for (const double s : sharp) most = std::max(most, s);
  }
  // Smooth now: the all-quad limit mask (n^2 c + 4 sum e + sum d) / (n (n + 5)).
  Stencil p = double(n) * n * c;
  for (int i = 0; i < n; ++i) p.add(e[at(i)], 4.0).add(d[at(i)], 1.0);
  return p.scale(1.0 / (double(n) * (n + 5)));
}

}  // namespace tessera
