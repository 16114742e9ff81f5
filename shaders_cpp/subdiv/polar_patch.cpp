#include "shaders_cpp/subdiv/polar_patch.h"

#include <cmath>
#include <numbers>

namespace tessera {

std::vector<int> polar_poles(const Topology& t) {
  std::vector<int> pole(std::size_t(t.face_count()), -1);
  for (int v = 0; v < t.vertex_count(); ++v) {
    if (t.is_isolated(v) || t.is_boundary_vertex(v) || t.has_sharpness_at(v) || t.valence(v) < kPolarMinValence)
      continue;
    bool polar = true;
    for (const int h : t.ring(v)) {
      const int f = t.face(h), q = t.destination(h);
      const int across = t.twin(t.next(h));  // the ring edge Q_j -> Q_j+1, seen from the quad
      polar = polar && t.face_size(f) == 3 && !t.is_hole(f) && t.valence(q) == 4 && !t.is_boundary_vertex(q) &&
              !t.has_sharpness_at(q) && across >= 0 && t.face_size(t.face(across)) == 4 && !t.is_hole(t.face(across));
    }
    if (!polar) continue;
    for (const int h : t.ring(v)) pole[std::size_t(t.face(h))] = v;
  }
  return pole;
}

void polar_triangle_rows(std::vector<Stencil>& rows, int n, const std::vector<Stencil>& quad, int a) {
  const Stencil& p = rows[0];
  // Row 1: the B-spline control points p + T_j / (3 h) of the spokes' points m_j = p + T_j / 3, and the
  // sector's inner Bezier points (2 d_j + d_j+1) / 3, (d_j + 2 d_j+1) / 3.
  const double h = (2.0 + std::cos(2.0 * std::numbers::pi / n)) / 3.0;
  const Stencil tj = rows[1] - p, tk = rows[2] - p;  // m_j - p and m_j+1 - p
  rows[3] = p + (1.0 / (3.0 * h)) * (2.0 * tj + tk);
  rows[4] = p + (1.0 / (3.0 * h)) * (tj + 2.0 * tk);
  // Row 2 inside: the quad's inner row mirrored across the ring edge. The quad runs the edge from its
  // corner a (our corner 2) to a + 1 (our corner 1); its face point by our corner 1 belongs to that
  // edge at its corner a + 1 (F-), by our corner 2 at its corner a (F+).
  const std::size_t qa = std::size_t(5 * (a % 4)), qb = std::size_t(5 * ((a + 1) % 4));
  rows[8] = 2.0 * rows[6] - quad[qb + 4];
  rows[9] = 2.0 * rows[12] - quad[qa + 3];
  rows[13] = rows[14] = p;  // unused slots, inside the hull
}

}  // namespace tessera
