#include "tools/verify/weld_check.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <optional>
#include <sstream>

namespace tessera::verify {

std::uint32_t WeldChecker::weld(const glm::vec3& p) {
  const std::array<std::uint32_t, 3> bits{std::bit_cast<std::uint32_t>(p.x), std::bit_cast<std::uint32_t>(p.y),
                                          std::bit_cast<std::uint32_t>(p.z)};
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint32_t b : bits) h = (h ^ b) * 1099511628211ull;
  auto& bucket = buckets_[h];
  for (const auto& [key, id] : bucket)
    if (key == bits) return id;
  bucket.emplace_back(bits, next_id_);
  positions_.push_back(p);
  return next_id_++;
}

void WeldChecker::add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  ++triangles_;
  const std::uint32_t ia = weld(a), ib = weld(b), ic = weld(c);
  if (ia == ib || ib == ic || ic == ia) {
    ++degenerate_;
    return;
  }
  auto add = [&](std::uint32_t x, std::uint32_t y) { ++directed_[std::uint64_t(x) << 32 | y]; };
  add(ia, ib);
  add(ib, ic);
  add(ic, ia);
}

void WeldChecker::add_curve_point(const glm::vec3& p, std::int64_t curve) { curve_points_.emplace_back(weld(p), curve); }

void WeldChecker::add_curve_use(std::int64_t curve) { ++curve_uses_[curve]; }

void WeldChecker::add_fin(std::int64_t curve) {
  const auto at = std::lower_bound(fins_.begin(), fins_.end(), curve);
  if (at == fins_.end() || *at != curve) fins_.insert(at, curve);
}

template <class Visit>
void WeldChecker::classify(Visit&& visit) const {
  std::vector<std::pair<std::uint32_t, std::int64_t>> on(curve_points_);
  std::sort(on.begin(), on.end());
  on.erase(std::unique(on.begin(), on.end()), on.end());
  const auto curves_of = [&](std::uint32_t id) {
    const auto lo = std::lower_bound(on.begin(), on.end(), std::pair<std::uint32_t, std::int64_t>(id, INT64_MIN));
    auto hi = lo;
    while (hi != on.end() && hi->first == id) ++hi;
    return std::pair(lo, hi);
  };
  // Both ends on one curve that fewer than two patches drew: the edge runs along the surface's border.
  const auto on_border = [&](std::uint32_t a, std::uint32_t b) {
    const auto [a0, a1] = curves_of(a);
    const auto [b0, b1] = curves_of(b);
    for (auto i = a0; i != a1; ++i)
      for (auto j = b0; j != b1; ++j)
        if (i->second == j->second) {
          const auto uses = curve_uses_.find(i->second);
          if (uses == curve_uses_.end() || uses->second < 2) return true;
        }
    return false;
  };
  // Both ends on one fin that at least `triangles` patches drew: one of the cage's non-manifold edges.
  const auto on_fin = [&](std::uint32_t a, std::uint32_t b, std::uint32_t triangles) {
    const auto [a0, a1] = curves_of(a);
    const auto [b0, b1] = curves_of(b);
    for (auto i = a0; i != a1; ++i)
      for (auto j = b0; j != b1; ++j)
        if (i->second == j->second && std::binary_search(fins_.begin(), fins_.end(), i->second)) {
          const auto uses = curve_uses_.find(i->second);
          if (uses != curve_uses_.end() && uses->second >= triangles) return true;
        }
    return false;
  };
  for (const auto& [key, uses] : directed_) {
    const std::uint32_t a = std::uint32_t(key >> 32), b = std::uint32_t(key);
    const auto it = directed_.find(std::uint64_t(b) << 32 | a);
    const std::uint32_t back = it == directed_.end() ? 0 : it->second;
    // Each undirected edge once, from its smaller end (or from the only direction present).
    if (back != 0 && a > b) continue;
    if (uses > 1 || back > 1)
      visit(key, std::optional<WeldEdgeKind>(on_fin(a, b, uses + back) ? WeldEdgeKind::cage_nonmanifold
                                                                       : WeldEdgeKind::nonmanifold));
    else if (back == 0)
      visit(key, std::optional<WeldEdgeKind>(on_border(a, b) ? WeldEdgeKind::border : WeldEdgeKind::crack));
    else
      visit(key, std::optional<WeldEdgeKind>());
  }
}

WeldReport WeldChecker::report() const {
  WeldReport r;
  r.triangles = triangles_;
  r.degenerate_triangles = degenerate_;
  r.welded_vertices = next_id_;
  classify([&](std::uint64_t, std::optional<WeldEdgeKind> kind) {
    ++r.edges;
    if (!kind) return;
    if (*kind == WeldEdgeKind::nonmanifold || *kind == WeldEdgeKind::cage_nonmanifold) {
      ++(*kind == WeldEdgeKind::nonmanifold ? r.nonmanifold_edges : r.cage_nonmanifold_edges);
      return;
    }
    ++r.open_edges;
    ++(*kind == WeldEdgeKind::border ? r.border_edges : r.crack_edges);
  });
  return r;
}

std::vector<WeldEdge> WeldChecker::bad_edges() const {
  std::vector<std::pair<std::uint64_t, WeldEdgeKind>> bad;
  classify([&](std::uint64_t key, std::optional<WeldEdgeKind> kind) {
    if (kind) bad.emplace_back(key, *kind);
  });
  std::sort(bad.begin(), bad.end());
  std::vector<WeldEdge> out;
  for (const auto& [key, kind] : bad)
    out.push_back({positions_[std::size_t(key >> 32)], positions_[std::size_t(std::uint32_t(key))], kind});
  return out;
}

std::string WeldReport::summary() const {
  std::ostringstream s;
  s << (watertight() ? "watertight" : "NOT watertight") << ": " << triangles << " triangles, " << welded_vertices
    << " welded vertices, " << edges << " edges, " << crack_edges << " crack edges, " << nonmanifold_edges
    << " non-manifold edges, " << border_edges << " border edges (the surface's own), ";
  if (cage_nonmanifold_edges > 0) s << cage_nonmanifold_edges << " non-manifold edges of the cage's own, ";
  s << degenerate_triangles << " degenerate triangles";
  return s.str();
}

}  // namespace tessera::verify
