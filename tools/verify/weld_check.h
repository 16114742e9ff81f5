// Crack detection the way the brief defines watertight: weld the tessellated triangles on the exact
// bit patterns of their vertex positions, then every edge must be used by exactly two triangles, once
// in each direction (a closed, consistently oriented 2-manifold).
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
  std::uint64_t boundary_edges = 0;     // used by one triangle: a crack, or the cage's own boundary
  std::uint64_t nonmanifold_edges = 0;  // used by more than two triangles, or twice the same way
  bool closed_manifold() const { return boundary_edges == 0 && nonmanifold_edges == 0 && triangles > 0; }
  std::string summary() const;
};

// An edge the weld found open (used once) or non-manifold, by its welded end points.
struct WeldEdge {
  glm::vec3 a{0.0f}, b{0.0f};
  bool nonmanifold = false;
};

class WeldChecker {
 public:
  void add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);
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
