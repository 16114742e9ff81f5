#include "shaders_cpp/bake/parameter_locator.h"

#include <algorithm>
#include <cmath>

namespace tessera {

ParameterLocator::ParameterLocator(const DenseMesh& mesh, int faces) : mesh_(mesh), grids_(std::size_t(faces)) {
  std::vector<std::vector<std::uint32_t>> per_face(static_cast<std::size_t>(faces));
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::int32_t f = mesh.face[mesh.triangles[3 * t]];
    if (f >= faces)
      throw BakeError(mesh.name + ": vertex " + std::to_string(mesh.triangles[3 * t]) + " names face " +
                      std::to_string(f) + ", but the cage has " + std::to_string(faces) +
                      " faces (was the mesh tessellated from this cage?)");
    if (mesh.face[mesh.triangles[3 * t + 1]] != f || mesh.face[mesh.triangles[3 * t + 2]] != f) continue;
    per_face[std::size_t(f)].push_back(std::uint32_t(t));
  }
  for (std::size_t f = 0; f < per_face.size(); ++f) {
    const auto& tris = per_face[f];
    if (tris.empty()) continue;
    FaceGrid& g = grids_[f];
    g.n = std::clamp(int(std::ceil(std::sqrt(double(tris.size()) / 2.0))), 1, 64);
    const std::size_t buckets = std::size_t(g.n) * std::size_t(g.n);
    auto range = [&](std::uint32_t t, int& x0, int& x1, int& y0, int& y1) {
      glm::vec2 lo(2.0f), hi(-1.0f);
      for (int k = 0; k < 3; ++k) {
        const glm::vec2 p = mesh.face_uv[mesh.triangles[3 * std::size_t(t) + std::size_t(k)]];
        lo = glm::min(lo, p), hi = glm::max(hi, p);
      }
      constexpr float kPad = 1e-5f;
      x0 = std::clamp(int(std::floor((lo.x - kPad) * float(g.n))), 0, g.n - 1);
      x1 = std::clamp(int(std::floor((hi.x + kPad) * float(g.n))), 0, g.n - 1);
      y0 = std::clamp(int(std::floor((lo.y - kPad) * float(g.n))), 0, g.n - 1);
      y1 = std::clamp(int(std::floor((hi.y + kPad) * float(g.n))), 0, g.n - 1);
    };
    std::vector<std::uint32_t> count(buckets + 1, 0);
    for (std::uint32_t t : tris) {
      int x0, x1, y0, y1;
      range(t, x0, x1, y0, y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) ++count[std::size_t(y * g.n + x) + 1];
    }
    for (std::size_t b = 0; b < buckets; ++b) count[b + 1] += count[b];
    g.start = count;
    g.items.resize(count[buckets]);
    for (std::uint32_t t : tris) {
      int x0, x1, y0, y1;
      range(t, x0, x1, y0, y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) g.items[count[std::size_t(y * g.n + x)]++] = t;
    }
  }
}

int ParameterLocator::faces_covered() const {
  return int(std::count_if(grids_.begin(), grids_.end(), [](const FaceGrid& g) { return g.n > 0; }));
}

std::optional<DenseLocation> ParameterLocator::locate(std::uint32_t face, glm::vec2 uv) const {
  if (face >= grids_.size() || grids_[face].n == 0) return std::nullopt;
  const FaceGrid& g = grids_[face];
  const int x = std::clamp(int(std::floor(uv.x * float(g.n))), 0, g.n - 1);
  const int y = std::clamp(int(std::floor(uv.y * float(g.n))), 0, g.n - 1);
  const std::size_t b = std::size_t(y * g.n + x);
  std::optional<DenseLocation> best;
  double best_min = -1e-6;
  const glm::dvec2 p(uv);
  for (std::uint32_t i = g.start[b]; i < g.start[b + 1]; ++i) {
    const std::uint32_t t = g.items[i];
    const glm::dvec2 a(mesh_.face_uv[mesh_.triangles[3 * std::size_t(t)]]);
    const glm::dvec2 bb(mesh_.face_uv[mesh_.triangles[3 * std::size_t(t) + 1]]);
    const glm::dvec2 c(mesh_.face_uv[mesh_.triangles[3 * std::size_t(t) + 2]]);
    const double det = (bb.x - a.x) * (c.y - a.y) - (bb.y - a.y) * (c.x - a.x);
    if (det == 0.0) continue;
    const double w1 = ((p.x - a.x) * (c.y - a.y) - (p.y - a.y) * (c.x - a.x)) / det;
    const double w2 = ((bb.x - a.x) * (p.y - a.y) - (bb.y - a.y) * (p.x - a.x)) / det;
    const double w0 = 1.0 - w1 - w2;
    const double m = std::min({w0, w1, w2});
    if (m > best_min) {
      best_min = m;
      glm::dvec3 w = glm::max(glm::dvec3(w0, w1, w2), glm::dvec3(0.0));
      w /= (w.x + w.y + w.z);
      best = DenseLocation{t, w};
    }
  }
  return best;
}

}  // namespace tessera
