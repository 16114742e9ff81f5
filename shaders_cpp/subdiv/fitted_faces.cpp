#include "shaders_cpp/subdiv/fitted_faces.h"

#include <algorithm>
#include <cmath>

namespace tessera::subdiv {
namespace {

// The limit on an edge, and its derivatives there, read the faces at the edge's two vertices only: the
// vertices of those faces, sorted.
std::vector<int> edge_neighbourhood(const Cage& cage, const Topology& t, int a, int b) {
  std::vector<int> near;
  for (const int v : {a, b})
    for (const int h : t.ring(v)) {
      const int fh = t.face(h);
      for (int c = 0; c < t.face_size(fh); ++c) near.push_back(cage.face_vertex(fh, c));
    }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  return near;
}

// Drops a fitted stencil's terms outside `near`, so that the rows fit both faces' rings; false when a
// dropped weight is not negligible.
bool restrict_to(const std::vector<int>& near, Stencil& s) {
  double dropped = 0.0;
  std::erase_if(s.terms, [&](const std::pair<int, double>& term) {
    if (std::binary_search(near.begin(), near.end(), term.first)) return false;
    dropped = std::max(dropped, std::abs(term.second));
    return true;
  });
  return dropped < kNegligibleFitWeight;
}

}  // namespace

FittedFaces::FittedFaces(const Cage& cage, const Topology& t, Scheme scheme, std::span<const char> refit)
    : cage_(cage), t_(t), fitted_(std::size_t(t.face_count()), 0) {
  for (int f = 0; f < t.face_count(); ++f) {
    const int m = t.face_size(f);
    const bool tagged = fits_limit(cage, t, scheme, f);
    const bool forced = !refit.empty() && refit[std::size_t(f)] && !t.is_hole(f) && (m == 3 || m == 4) &&
                        (scheme == Scheme::gregory || scheme == Scheme::bspline || scheme == Scheme::acc);
    if (!forced && !tagged) continue;
    fitted_[std::size_t(f)] = 1;
    refit_count_ += forced && !tagged;
    for (int k = 0; k < m; ++k) {
      const int a = cage.face_vertex(f, k), b = cage.face_vertex(f, (k + 1) % m);
      if (forced || t.has_sharpness_at(a) || t.has_sharpness_at(b) || t.is_boundary_vertex(a) ||
          t.is_boundary_vertex(b))
        edge_owner_.try_emplace(cage_edge_key(a, b), f);
    }
  }
  if (!edge_owner_.empty()) limit_ = std::make_unique<LimitStencils>(cage);
  fit_points_ = fitted_;
  for (int f = 0; f < t.face_count() && limit_; ++f) {
    const int m = t.face_size(f);
    if (t.is_hole(f) || (m != 3 && m != 4)) continue;
    for (int k = 0; k < m; ++k)
      if (edge_owner_.contains(cage_edge_key(cage.face_vertex(f, k), cage.face_vertex(f, (k + 1) % m))))
        fit_points_[std::size_t(f)] = 1;
  }
}

// The exact limit at a tagged vertex from Bfr (the masks' corner is exact for uniform creasing,
// semi_sharp_limit.h, but not for Chaikin's rule).
void FittedFaces::fit_corner(std::vector<Stencil>& rows, int v, std::size_t p_row) {
  if (!limit_ || !t_.has_sharpness_at(v)) return;
  auto it = corners_.find(v);
  if (it == corners_.end()) {
    std::optional<Stencil> p;
    int g = -1;
    for (const int h : t_.ring(v))
      if (fitted_[std::size_t(t_.face(h))] && (g < 0 || t_.face(h) < g)) g = t_.face(h);
    if (g >= 0) p = limit_at_corner(*limit_, g, t_.corner_of(g, v));
    if (p && !restrict_to(edge_neighbourhood(cage_, t_, v, v), *p)) p.reset();
    it = corners_.emplace(v, std::move(p)).first;
  }
  if (it->second) rows[p_row] = *it->second;
}

void FittedFaces::fit_edge(std::vector<Stencil>& rows, int va, int vb, std::size_t pa, std::size_t pb,
                           std::size_t ea, std::size_t eb) {
  const std::int64_t key = cage_edge_key(va, vb);
  const auto owner = edge_owner_.find(key);
  if (owner == edge_owner_.end()) return;
  auto it = edges_.find(key);
  if (it == edges_.end()) {
    FittedEdge e;
    const int g = owner->second, m = t_.face_size(g);
    for (int j = 0; j < m; ++j) {
      const int x = cage_.face_vertex(g, j), y = cage_.face_vertex(g, (j + 1) % m);
      if (cage_edge_key(x, y) != key) continue;
      const Stencil& px = x == va ? rows[pa] : rows[pb];
      const Stencil& py = x == va ? rows[pb] : rows[pa];
      if (std::optional<EdgePoints> fit = fit_edge_points(*limit_, g, j, px, py)) {
        const std::vector<int> near = edge_neighbourhood(cage_, t_, x, y);
        if (restrict_to(near, fit->near_a) && restrict_to(near, fit->near_b))
          e.ok = true, e.a = x, e.points = std::move(*fit);
      }
      break;
    }
    it = edges_.emplace(key, std::move(e)).first;
  }
  if (!it->second.ok) return;
  const bool forward = it->second.a == va;
  rows[ea] = forward ? it->second.points.near_a : it->second.points.near_b;
  rows[eb] = forward ? it->second.points.near_b : it->second.points.near_a;
}

std::optional<std::array<Stencil, 4>> FittedFaces::inward_derivative(int g, int e) const {
  if (!limit_ || !fitted_[std::size_t(g)]) return std::nullopt;
  std::optional<std::array<Stencil, 4>> c = fit_inward_derivative(*limit_, g, e);
  if (!c) return std::nullopt;
  const std::vector<int> near =
      edge_neighbourhood(cage_, t_, cage_.face_vertex(g, e), cage_.face_vertex(g, (e + 1) % t_.face_size(g)));
  for (Stencil& r : *c)
    if (!restrict_to(near, r)) return std::nullopt;
  return c;
}

}  // namespace tessera::subdiv
