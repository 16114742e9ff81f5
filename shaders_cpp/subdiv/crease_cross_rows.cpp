#include "shaders_cpp/subdiv/crease_cross_rows.h"

#include "shaders_cpp/cage/corner_ring.h"
#include "shaders_cpp/subdiv/crease_blend.h"
#include "shaders_cpp/subdiv/patch_stencils.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera::subdiv {
namespace {

std::vector<Stencil> face_gregory_stencils(const Cage& cage, const Topology& t, int g,
                                           const std::vector<std::optional<Stencil>>& semi_sharp) {
  const int m = t.face_size(g);
  bool creased = false;
  for (int k = 0; k < m; ++k) creased |= t.has_sharpness_at(cage.face_vertex(g, k));
  auto build = [&]<std::size_t N>(std::array<CornerRing, N>& c, auto&& stencils) {
    std::array<CornerRing, N> cut;
    std::array<double, N> w{};
    for (std::size_t k = 0; k < N; ++k) {
      c[k] = gather_corner_ring(cage, t, g, int(k));
      float sharpness = 0.0f;
      if (creased) cut[k] = gather_creased_corner_ring(cage, t, g, int(k), &sharpness);
      w[k] = crease_weight(sharpness);
    }
    std::vector<Stencil> s = stencils(c);
    if (!creased) return s;
    std::vector<Stencil> blended = blend_by_corner(s, stencils(cut), w, false);
    for (std::size_t k = 0; k < N; ++k) {
      const int v = cage.face_vertex(g, int(k));
      exact_corner(blended, s, t, v, semi_sharp[std::size_t(v)], 5 * k, {5 * k + 1, 5 * k + 2});
    }
    return blended;
  };
  if (m == 3) {
    std::array<CornerRing, 3> c;
    return build(c, [](const std::array<CornerRing, 3>& r) { return gregory_triangle_stencils(r); });
  }
  std::array<CornerRing, 4> c;
  return build(c, [](const std::array<CornerRing, 4>& r) { return gregory_quad_stencils(r); });
}

}  // namespace

const std::vector<Stencil>& NeighbourRows::of(int face) {
  auto it = rows_.find(face);
  if (it != rows_.end()) return it->second;
  std::vector<Stencil> rows = face_gregory_stencils(cage_, t_, face, semi_sharp_);
  return rows_.emplace(face, std::move(rows)).first->second;
}

// The neighbour g traverses the edge from its corner j (our corner k + 1) to j + 1 (our corner k); its
// inward cross derivative there, in its Gregory points (P, E+, E-, F+, F- at 5 j), is the cubic
// 3 (E-_j - P_j), d (F+_j - E+_j), d (F-_{j+1} - E-_{j+1}), 3 (E+_{j+1} - P_{j+1}), d the patch degree
// across the edge (3 quad, 4 triangle; gregory_stencils' G1 condition on the quad view). Returned from
// our corner k: reversed. Where the fit has the limit's own derivative into g (a fitted face), that is
// returned instead, marked `limit`: the limit is smooth across the line, so the domain shader takes
// that normal alone.
CrossRows neighbour_cross_rows(const Topology& t, int f, int n, int rot, int k, NeighbourRows& neighbours,
                               const FittedFaces& fitted) {
  const int h = t.face_offset(f) + (k + rot) % n;
  const int twin = t.twin(h);
  const float s = t.edge_sharpness(t.edge(h));
  if (twin < 0 || s >= kSharpnessInfinite) return {};
  const bool smooth_at_tag = s == 0.0f && (t.has_sharpness_at(t.origin(h)) || t.has_sharpness_at(t.destination(h)));
  if (!(s >= kCutSharpness) && !smooth_at_tag) return {};
  const int g = t.face(twin), m = t.face_size(g);
  if ((m != 3 && m != 4) || t.is_hole(g)) return {};
  const int a = twin - t.face_offset(g), b = (a + 1) % m;
  if (const std::optional<std::array<Stencil, 4>> c = fitted.inward_derivative(g, a))
    return {{(*c)[3], (*c)[2], (*c)[1], (*c)[0]}, true};
  if (smooth_at_tag) return {};
  const std::vector<Stencil>& rows = neighbours.of(g);
  const double d = m == 3 ? 4.0 : 3.0;
  auto row = [&](int corner, int r) -> const Stencil& { return rows[std::size_t(5 * corner + r)]; };
  auto diff = [](double scale, const Stencil& x, const Stencil& y) {
    Stencil out;
    return out.add(x, scale).add(y, -scale);
  };
  return {{diff(3.0, row(b, 1), row(b, 0)), diff(d, row(b, 4), row(b, 2)), diff(d, row(a, 3), row(a, 1)),
           diff(3.0, row(a, 2), row(a, 0))}};
}

}  // namespace tessera::subdiv
