// Crack detection the way the brief defines watertight: weld the tessellated triangles on the exact
// bit patterns of their vertex positions; then every edge must be used by two triangles, once in each
// direction. An edge used once is open: on the surface's own border (a cage boundary, the rim of a hole,
// the edge of a patch whose neighbour draws nothing) it is where the surface ends; anywhere else it is a
// crack. The caller names the border: the points that lie on each domain curve its patches share (a cage
// edge) and how many patches drew that curve; an open edge whose two ends lie on one curve drawn by
// fewer than two patches is a border edge. Without that information every open edge is a crack. A curve
// the caller names a fin (a non-manifold edge of the cage, drawn by every face on it) may carry edges of
// more than two triangles: up to the patches that drew it, they are the cage's own, not a fault.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

namespace tessera::verify {

struct WeldReport {
  std::uint64_t triangles = 0;
  std::uint64_t welded_vertices = 0;
  std::uint64_t degenerate_triangles = 0;  // two corners welded together: left out of the edge count
  std::uint64_t edges = 0;
  std::uint64_t open_edges = 0;         // used by one triangle: border_edges + crack_edges
  std::uint64_t border_edges = 0;       // open, on the surface's own border
  std::uint64_t crack_edges = 0;        // open anywhere else
  std::uint64_t nonmanifold_edges = 0;  // used by more than two triangles, or twice the same way
  std::uint64_t cage_nonmanifold_edges = 0;  // such edges along a fin: the cage's own (not counted above)
  // No cracks and no non-manifold edges: the surface may still have a border.
  bool watertight() const { return crack_edges == 0 && nonmanifold_edges == 0 && triangles > 0; }
  // Watertight with no border either: a closed, consistently oriented 2-manifold.
  bool closed_manifold() const { return watertight() && open_edges == 0; }
  // "watertight: ..." or "NOT watertight: ...", with the counts.
  std::string summary() const;
};

// An edge the weld found open (used once) or non-manifold, by its welded end points.
enum class WeldEdgeKind { crack, border, nonmanifold, cage_nonmanifold };
struct WeldEdge {
  glm::vec3 a{0.0f}, b{0.0f};
  WeldEdgeKind kind = WeldEdgeKind::crack;
};

class WeldChecker {
 public:
  void add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);
  // Point `p` lies on domain curve `curve` (any key the caller chooses, such as a cage edge's).
  void add_curve_point(const glm::vec3& p, std::int64_t curve);
  // One more patch drew `curve`.
  void add_curve_use(std::int64_t curve);
  // `curve` is a fin: a non-manifold edge of the cage (idempotent).
  void add_fin(std::int64_t curve);
  WeldReport report() const;
  // The edges report() counts as open or non-manifold, in welded-vertex order (deterministic).
  std::vector<WeldEdge> bad_edges() const;

 private:
  std::uint32_t weld(const glm::vec3& p);
  std::unordered_map<std::uint64_t, std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>>> buckets_;
  std::uint32_t next_id_ = 0;
  std::vector<glm::vec3> positions_;  // by welded id
  // Directed edge (a, b) -> uses; keyed by a << 32 | b.
  std::unordered_map<std::uint64_t, std::uint32_t> directed_;
  std::uint64_t triangles_ = 0, degenerate_ = 0;
  std::vector<std::pair<std::uint32_t, std::int64_t>> curve_points_;  // (welded id, curve)
  std::unordered_map<std::int64_t, std::uint32_t> curve_uses_;
  std::vector<std::int64_t> fins_;  // sorted, unique
  // Each undirected edge's kind (open, border or not), by its directed key; calls `visit(key, kind)`.
  template <class Visit>
  void classify(Visit&& visit) const;
};

// Adds a patch's triangles (a stream-output PatchOutput: `points` with a `position`, `indices` three per
// triangle) to the weld.
template <class PatchOut>
void add_patch_triangles(WeldChecker& weld, const PatchOut& p) {
  for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3)
    weld.add_triangle(p.points[p.indices[i]].position, p.points[p.indices[i + 1]].position,
                      p.points[p.indices[i + 2]].position);
}

}  // namespace tessera::verify
