#include "shaders_cpp/bake/texel_sites.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace tessera {

bool invert_bilinear(const std::array<glm::vec2, 4>& corners, glm::dvec2 uv, float& u, float& v) {
  const glm::dvec2 a(corners[0]), b(corners[1]), c(corners[2]), d(corners[3]);
  // P(s, t) = a + (b - a) s + (d - a) t + (a - b + c - d) s t
  const glm::dvec2 e = b - a, f = d - a, g = a - b + c - d;
  double s = 0.5, t = 0.5;
  for (int i = 0; i < 32; ++i) {
    const glm::dvec2 r = a + e * s + f * t + g * (s * t) - uv;
    const glm::dvec2 ds = e + g * t, dt = f + g * s;
    const double det = ds.x * dt.y - ds.y * dt.x;
    if (det == 0.0 || !std::isfinite(det)) return false;
    const double step_s = (r.x * dt.y - r.y * dt.x) / det, step_t = (ds.x * r.y - ds.y * r.x) / det;
    s -= step_s, t -= step_t;
    if (std::abs(step_s) < 1e-12 && std::abs(step_t) < 1e-12) break;
    if (!(std::abs(s) < 8.0 && std::abs(t) < 8.0)) return false;  // diverging: the point is far outside
  }
  const glm::dvec2 r = a + e * s + f * t + g * (s * t) - uv;
  if (!(std::abs(r.x) < 1e-9 && std::abs(r.y) < 1e-9)) return false;
  constexpr double kTolerance = 1e-6;
  if (s < -kTolerance || s > 1.0 + kTolerance || t < -kTolerance || t > 1.0 + kTolerance) return false;
  u = float(std::clamp(s, 0.0, 1.0)), v = float(std::clamp(t, 0.0, 1.0));
  return true;
}

std::vector<TexelSite> texel_sites(std::span<const PatchTexcoords> patches, int w, int h) {
  std::vector<TexelSite> sites(std::size_t(w) * std::size_t(h));
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const auto& c = patches[p].interior;
    glm::vec2 lo = c[0], hi = c[0];
    for (const glm::vec2& q : c) lo = glm::min(lo, q), hi = glm::max(hi, q);
    // Texels whose centres may lie in the quad: x + 0.5 in [lo.x w, hi.x w].
    const int x0 = std::max(0, int(std::floor(double(lo.x) * w - 0.5))),
              x1 = std::min(w - 1, int(std::ceil(double(hi.x) * w - 0.5)));
    const int y0 = std::max(0, int(std::floor(double(lo.y) * h - 0.5))),
              y1 = std::min(h - 1, int(std::ceil(double(hi.y) * h - 0.5)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        TexelSite& site = sites[std::size_t(y) * std::size_t(w) + std::size_t(x)];
        if (site.patch >= 0) continue;
        float u, v;
        if (invert_bilinear(c, glm::dvec2((x + 0.5) / w, (y + 0.5) / h), u, v)) site = {std::int32_t(p), u, v};
      }
  }
  return sites;
}

}  // namespace tessera
