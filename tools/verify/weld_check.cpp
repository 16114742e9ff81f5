#include "tools/verify/weld_check.h"

#include <algorithm>
#include <bit>
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

WeldReport WeldChecker::report() const {
  WeldReport r;
  r.triangles = triangles_;
  r.degenerate_triangles = degenerate_;
  r.welded_vertices = next_id_;
  for (const auto& [key, uses] : directed_) {
    const std::uint32_t a = std::uint32_t(key >> 32), b = std::uint32_t(key);
    const auto it = directed_.find(std::uint64_t(b) << 32 | a);
    const std::uint32_t back = it == directed_.end() ? 0 : it->second;
    // Count each undirected edge once, from its smaller end (or from the only direction present).
    if (back != 0 && a > b) continue;
    ++r.edges;
    if (uses > 1 || back > 1)
      ++r.nonmanifold_edges;
    else if (back == 0)
      ++r.boundary_edges;
  }
  return r;
}

std::vector<WeldEdge> WeldChecker::bad_edges() const {
  std::vector<std::pair<std::uint64_t, bool>> bad;
  for (const auto& [key, uses] : directed_) {
    const std::uint32_t a = std::uint32_t(key >> 32), b = std::uint32_t(key);
    const auto it = directed_.find(std::uint64_t(b) << 32 | a);
    const std::uint32_t back = it == directed_.end() ? 0 : it->second;
    if (back != 0 && a > b) continue;
    if (uses > 1 || back > 1)
      bad.emplace_back(key, true);
    else if (back == 0)
      bad.emplace_back(key, false);
  }
  std::sort(bad.begin(), bad.end());
  std::vector<WeldEdge> out;
  for (const auto& [key, nonmanifold] : bad)
    out.push_back({positions_[std::size_t(key >> 32)], positions_[std::size_t(std::uint32_t(key))], nonmanifold});
  return out;
}

std::string WeldReport::summary() const {
  std::ostringstream s;
  s << (closed_manifold() ? "watertight" : "NOT watertight") << ": " << triangles << " triangles, " << welded_vertices
    << " welded vertices, " << edges << " edges, " << boundary_edges << " open edges, " << nonmanifold_edges
    << " non-manifold edges, " << degenerate_triangles << " degenerate triangles";
  return s.str();
}

}  // namespace tessera::verify
