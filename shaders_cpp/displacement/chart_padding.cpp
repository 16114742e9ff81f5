#include "shaders_cpp/displacement/chart_padding.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tessera {

namespace {

// Marks the texels whose centres lie in triangle (a, b, c), in texel units (edges included).
void cover_triangle(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, int w, int h, std::vector<std::uint8_t>& covered) {
  const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  if (!(std::abs(area) > 0.0)) return;  // degenerate (or NaN): no interior to cover
  const double s = area > 0.0 ? 1.0 : -1.0;
  const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}) - 0.5))),
            x1 = std::min(w - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}) - 0.5))),
            y1 = std::min(h - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
  const auto inside = [&](glm::dvec2 p, glm::dvec2 q, glm::dvec2 r) {
    return s * ((q.x - p.x) * (r.y - p.y) - (r.x - p.x) * (q.y - p.y)) >= 0.0;
  };
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const glm::dvec2 r(x + 0.5, y + 0.5);
      if (inside(a, b, r) && inside(b, c, r) && inside(c, a, r))
        covered[std::size_t(y) * std::size_t(w) + std::size_t(x)] = 1;
    }
}

}  // namespace

std::vector<std::uint8_t> chart_coverage(std::span<const PatchTexcoords> patches, int w, int h, int erode) {
  std::vector<std::uint8_t> covered(std::size_t(w) * std::size_t(h), 0);
  const glm::dvec2 scale(w, h);
  for (const PatchTexcoords& p : patches) {
    const auto& c = p.interior;
    const glm::dvec2 q0 = glm::dvec2(c[0]) * scale, q1 = glm::dvec2(c[1]) * scale, q2 = glm::dvec2(c[2]) * scale,
                     q3 = glm::dvec2(c[3]) * scale;
    // Both diagonals' triangles: the bilinear patch lies inside their union for any quad shape.
    cover_triangle(q0, q1, q2, w, h, covered);
    cover_triangle(q0, q2, q3, w, h, covered);
    cover_triangle(q0, q1, q3, w, h, covered);
    cover_triangle(q1, q2, q3, w, h, covered);
  }
  // Erosion: a texel stays covered only if its 8 neighbours are (clamped at the image's border).
  for (int e = 0; e < erode; ++e) {
    std::vector<std::uint8_t> next(covered);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
            if (!covered[std::size_t(yy) * std::size_t(w) + std::size_t(xx)])
              next[std::size_t(y) * std::size_t(w) + std::size_t(x)] = 0;
          }
    covered.swap(next);
  }
  return covered;
}

void pad_charts(std::vector<float>& texels, int w, int h, int channels, const std::vector<std::uint8_t>& covered) {
  const std::size_t n = std::size_t(w) * std::size_t(h);
  // 0: empty, 1: filled (a chart's, or an earlier ring's), 2: in the current ring.
  std::vector<std::uint8_t> state(covered.begin(), covered.end());
  const auto for_neighbours = [&](std::size_t i, auto&& visit) {
    const int x = int(i % std::size_t(w)), y = int(i / std::size_t(w));
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || x + dx < 0 || x + dx >= w || y + dy < 0 || y + dy >= h) continue;
        visit(std::size_t(y + dy) * std::size_t(w) + std::size_t(x + dx));
      }
  };
  std::vector<std::size_t> ring;
  for (std::size_t i = 0; i < n; ++i) {
    if (state[i] != 0) continue;
    bool next_to_chart = false;
    for_neighbours(i, [&](std::size_t j) { next_to_chart |= state[j] == 1; });
    if (next_to_chart) ring.push_back(i);
  }
  std::vector<float> values;
  const std::size_t ch = std::size_t(channels);
  while (!ring.empty()) {
    for (std::size_t i : ring) state[i] = 2;
    values.assign(ring.size() * ch, 0.0f);
    for (std::size_t r = 0; r < ring.size(); ++r) {
      int count = 0;
      for_neighbours(ring[r], [&](std::size_t j) {
        if (state[j] != 1) return;
        for (std::size_t k = 0; k < ch; ++k) values[r * ch + k] += texels[j * ch + k];
        ++count;
      });
      for (std::size_t k = 0; k < ch; ++k) values[r * ch + k] /= float(count);
    }
    std::vector<std::size_t> next;
    for (std::size_t r = 0; r < ring.size(); ++r) {
      for (std::size_t k = 0; k < ch; ++k) texels[ring[r] * ch + k] = values[r * ch + k];
      state[ring[r]] = 1;
    }
    for (std::size_t i : ring)
      for_neighbours(i, [&](std::size_t j) {
        if (state[j] == 0) state[j] = 3, next.push_back(j);  // 3: queued for the next ring
      });
    std::sort(next.begin(), next.end());  // a fixed order, whatever the order of discovery
    ring.swap(next);
  }
}

}  // namespace tessera
