// Multisampling by D3D11's rules: coverage per sample at the standard positions (with the top-left
// rule), depth per sample, one pixel shader invocation per pixel, a box-filter resolve.
#include <algorithm>
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "pipeline/sample_pattern.h"
#include "pipeline_support.h"

namespace tessera {
namespace {

using test::clip_vertex;
using V1 = ClipVertex<1>;

// A constant colour; counts its invocations per pixel.
struct FlatPS {
  glm::vec4 color{1.0f};
  std::vector<int>* counts = nullptr;
  int width = 0;
  glm::vec4 operator()(const PixelInput<1>& in) const {
    if (counts) ++(*counts)[std::size_t(int(in.position.y)) * std::size_t(width) + std::size_t(int(in.position.x))];
    return color;
  }
};

// The clip vertex at window position (x, y) of a size x size target (exact for a power-of-two size).
V1 window_vertex(double x, double y, int size, float z = 0.5f) {
  const double half = size / 2.0;
  return clip_vertex<1>(float(x / half - 1.0), float(1.0 - y / half), z, 1.0f);
}

void draw_into(Framebuffer& fb, const std::vector<V1>& vertices, const std::vector<std::uint32_t>& indices, int threads,
               glm::vec4 color = glm::vec4(1.0f), std::vector<int>* counts = nullptr) {
  Device device(DeviceOptions{threads, 16});
  MeshDraw<V1, test::ClipPassVS<1>, FlatPS> d;
  d.vertices = vertices;
  d.indices = indices;
  d.ps = {color, counts, fb.width()};
  d.rasterizer.cull = CullMode::none;
  d.depth.func = CompareFunc::less;
  d.viewport = test::full_viewport(fb.width(), fb.height());
  REQUIRE(device.draw(d, fb).ok());
}

Framebuffer make_target(int size, int samples) {
  std::string error;
  auto fb = Framebuffer::create(size, size, ColorFormat::rgba8_unorm, &error, samples);
  REQUIRE(fb);
  fb->clear(glm::vec4(0, 0, 0, 1), 1.0f);
  return std::move(*fb);
}

Framebuffer draw(const std::vector<V1>& vertices, const std::vector<std::uint32_t>& indices, int size, int samples,
                 int threads, std::vector<int>* counts = nullptr) {
  Framebuffer fb = make_target(size, samples);
  draw_into(fb, vertices, indices, threads, glm::vec4(1.0f), counts);
  return fb;
}

}  // namespace

TEST_CASE("msaa: the standard patterns lie inside the pixel, distinct, D3D11's first positions", "[raster][msaa]") {
  for (int n : {1, 2, 4, 8, 16}) {
    const auto p = standard_sample_pattern(n);
    REQUIRE(int(p.size()) == n);
    for (std::size_t i = 0; i < p.size(); ++i) {
      CHECK(p[i].x >= -8);
      CHECK(p[i].x <= 7);
      CHECK(p[i].y >= -8);
      CHECK(p[i].y <= 7);
      for (std::size_t j = 0; j < i; ++j) CHECK((p[i].x != p[j].x || p[i].y != p[j].y));
    }
  }
  CHECK(standard_sample_pattern(4)[0].x == -2);
  CHECK(standard_sample_pattern(4)[0].y == -6);
  CHECK(standard_sample_pattern(16)[12].x == -8);  // the one sample on the pixel's left boundary
  CHECK_FALSE(valid_sample_count(3));
  std::string error;
  CHECK_FALSE(Framebuffer::create(8, 8, ColorFormat::rgba8_unorm, &error, 32));
  CHECK(error.find("sample count 32") != std::string::npos);
}

TEST_CASE("msaa: a rectangle's pixels resolve to the fraction of samples inside it, top-left rule included",
          "[raster][msaa]") {
  const int size = 64;
  // Edges on sample positions of some pixels (x0 = 10.5 + 2/16, on sample 0 of the 4x pattern's
  // column), others between them: a sample on the left or top edge is inside, on the right or bottom
  // edge outside.
  const double x0 = 10.5 + 2.0 / 16, x1 = 41.25 + 3.0 / 256, y0 = 7.0 + 6.0 / 16 + 0.5, y1 = 30.5 + 6.0 / 16;
  const std::vector<V1> v = {window_vertex(x0, y0, size), window_vertex(x1, y0, size), window_vertex(x1, y1, size),
                             window_vertex(x0, y1, size)};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
  for (int samples : {2, 4, 8, 16}) {
    const auto pattern = standard_sample_pattern(samples);
    std::vector<int> counts(std::size_t(size * size), 0);
    const Framebuffer fb = draw(v, idx, size, samples, 2, &counts).resolve();
    int wrong = 0, shaded_wrong = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        int inside = 0;
        for (const SampleOffset& o : pattern) {
          const double sx = x + 0.5 + o.x / 16.0, sy = y + 0.5 + o.y / 16.0;
          inside += sx >= x0 && sx < x1 && sy >= y0 && sy < y1;
        }
        const int expected = (255 * inside + samples / 2) / samples;
        wrong += int(std::lround(fb.color(x, y).r * 255.0f)) != expected;
        // The pixel shader runs once per pixel with a covered sample, per triangle that covers one.
        const int n = counts[std::size_t(y * size + x)];
        shaded_wrong += inside > 0 ? (n < 1 || n > 2) : n != 0;
      }
    INFO(samples << " samples");
    CHECK(wrong == 0);
    CHECK(shaded_wrong == 0);
  }
}

TEST_CASE("msaa: a jittered mesh covers every sample, on any thread count, the same bytes", "[raster][msaa]") {
  const int size = 128, cols = 11, rows = 7;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<V1> v;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= cols; ++i) {
      const bool border_x = i == 0 || i == cols, border_y = j == 0 || j == rows;
      const double x = (i + (border_x ? 0 : jitter(rng))) * size / cols - (i == 0 ? 1 : i == cols ? -1 : 0);
      const double y = (j + (border_y ? 0 : jitter(rng))) * size / rows - (j == 0 ? 1 : j == rows ? -1 : 0);
      v.push_back(window_vertex(x, y, size, float(0.2 + 0.05 * jitter(rng))));
    }
  std::vector<std::uint32_t> idx;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const auto a = std::uint32_t(j * (cols + 1) + i), b = a + 1, c = a + std::uint32_t(cols) + 2, d = c - 1;
      idx.insert(idx.end(), {a, b, c, a, c, d});
    }
  for (int samples : {4, 16}) {
    const Framebuffer one = draw(v, idx, size, samples, 1);
    const Framebuffer resolved = one.resolve();
    int holes = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) holes += resolved.color(x, y).r != 1.0f;
    CHECK(holes == 0);
    for (int threads : {2, 5}) CHECK(test::image_hash(draw(v, idx, size, samples, threads)) == test::image_hash(one));
  }
}

TEST_CASE("msaa: depth is tested per sample (an edge through a pixel in front of another surface)", "[raster][msaa]") {
  const int size = 32;
  Framebuffer fb = make_target(size, 4);
  // A far red square over everything, then a near green half-plane x < 16.3 (nearer: z 0.2 < 0.6).
  const std::vector<std::uint32_t> quad = {0, 1, 2, 0, 2, 3};
  draw_into(fb,
            {window_vertex(0, 0, size, 0.6f), window_vertex(32, 0, size, 0.6f), window_vertex(32, 32, size, 0.6f),
             window_vertex(0, 32, size, 0.6f)},
            quad, 2, glm::vec4(1, 0, 0, 1));
  const double edge = 16.5 + 1.0 / 16;  // between samples of column 16: x offsets -6, -2 left of it, 2, 6 right
  draw_into(fb,
            {window_vertex(0, 0, size, 0.2f), window_vertex(edge, 0, size, 0.2f), window_vertex(edge, 32, size, 0.2f),
             window_vertex(0, 32, size, 0.2f)},
            quad, 2, glm::vec4(0, 1, 0, 1));
  // A far surface drawn last loses every sample the near one holds.
  draw_into(fb,
            {window_vertex(0, 0, size, 0.9f), window_vertex(32, 0, size, 0.9f), window_vertex(32, 32, size, 0.9f),
             window_vertex(0, 32, size, 0.9f)},
            quad, 2, glm::vec4(0, 0, 1, 1));
  const Framebuffer r = fb.resolve();
  for (int y = 0; y < size; ++y) {
    CHECK(r.color(15, y).g == 1.0f);
    CHECK(r.color(17, y).r == 1.0f);
    // Column 16: two samples green, two red.
    CHECK(std::lround(r.color(16, y).g * 255.0f) == 128);
    CHECK(std::lround(r.color(16, y).r * 255.0f) == 128);
    CHECK(r.color(16, y).b == 0.0f);
  }
}

}  // namespace tessera

namespace tessera {

TEST_CASE("msaa: per-sample coverage of random small and large triangles is the 64-bit edge functions'",
          "[raster][msaa]") {
  // Setup keeps a small triangle's edges in 32 bits and the rasterizer tests each sample of 8x8 blocks
  // in lanes (raster_multisample.h); here every sample of every pixel is held against the 64-bit edge
  // functions of the snapped vertices, with D3D11's top-left rule, for triangles of 0.2 to 40 pixels
  // (vertices on the 1/256 grid, so snapping is exact), both windings, some past the target's edges.
  // Every fourth triangle has its vertices on sample points: samples then lie on its edges and on its
  // box's sides, where setup's box of reachable pixels (sample_reach) is tightest.
  const int size = 64;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-4.0, size + 4.0), spread(0.0, 1.0);
  const auto grid = [](double v) { return std::round(v * 256.0) / 256.0; };
  int covered_samples = 0;
  for (int samples : {2, 4, 8, 16}) {
    const auto pattern = standard_sample_pattern(samples);
    int wrong = 0;
    for (int t = 0; t < 60; ++t) {
      const double reach = t % 3 == 0 ? 40.0 : t % 3 == 1 ? 3.0 : 0.6;  // large, a few pixels, sub-pixel
      const double cx = pos(rng), cy = pos(rng);
      double x[3], y[3];
      for (int k = 0; k < 3; ++k) {
        x[k] = grid(cx + reach * (spread(rng) - 0.5)), y[k] = grid(cy + reach * (spread(rng) - 0.5));
        if (t % 4 == 3) {  // the nearest pixel's sample (s chosen at random), exact on the 1/256 grid
          const SampleOffset o = pattern[std::size_t(rng() % pattern.size())];
          x[k] = std::floor(x[k]) + 0.5 + o.x / 16.0, y[k] = std::floor(y[k]) + 0.5 + o.y / 16.0;
        }
      }
      Framebuffer fb = make_target(size, samples);
      draw_into(fb, {window_vertex(x[0], y[0], size), window_vertex(x[1], y[1], size), window_vertex(x[2], y[2], size)},
                {0, 1, 2}, 2);
      // The reference: positive-area order (setup's), then edge i from vertex i to i + 1 at each sample.
      std::int32_t vx[3], vy[3];
      for (int k = 0; k < 3; ++k)
        vx[k] = std::int32_t(std::lround(x[k] * 256)), vy[k] = std::int32_t(std::lround(y[k] * 256));
      const std::int64_t area =
          std::int64_t(vx[1] - vx[0]) * (vy[2] - vy[0]) - std::int64_t(vx[2] - vx[0]) * (vy[1] - vy[0]);
      if (area < 0) std::swap(vx[1], vx[2]), std::swap(vy[1], vy[2]);
      for (int py = 0; py < size; ++py)
        for (int px = 0; px < size; ++px)
          for (int s = 0; s < samples; ++s) {
            const std::int64_t sx = std::int64_t(px) * 256 + 128 + pattern[std::size_t(s)].x * 16;
            const std::int64_t sy = std::int64_t(py) * 256 + 128 + pattern[std::size_t(s)].y * 16;
            bool inside = area != 0;
            for (int i = 0; i < 3; ++i) inside = inside && detail::edge_function(vx, vy, i, sx, sy).value >= 0;
            const bool drawn = fb.sample_depth(px, py, s) == 0.5f;
            wrong += inside != drawn;
            covered_samples += inside;
          }
    }
    INFO(samples << " samples");
    CHECK(wrong == 0);
  }
  CHECK(covered_samples > 10000);  // the triangles did cover samples
}

}  // namespace tessera

namespace tessera {

TEST_CASE("msaa: an odd-sized target clears, stores and resolves every sample (its quads pad the last row and column)",
          "[raster][msaa]") {
  // A multisampled target is stored by 2x2 quads (framebuffer.h): row ranges that split a quad, and a
  // last row and column with no partner, must still reach every sample.
  for (int samples : {2, 4, 8, 16})
    for (ColorFormat format : {ColorFormat::rgba8_unorm, ColorFormat::rgba32_float}) {
      INFO(samples << " samples, format " << int(format));
      std::string error;
      auto fb = Framebuffer::create(7, 5, format, &error, samples);
      REQUIRE(fb);
      fb->clear_rows(0, 3, glm::vec4(1, 0, 0, 1), 0.25f);  // row 3 splits the second quad row
      fb->clear_rows(3, 5, glm::vec4(0, 0, 1, 1), 0.75f);
      for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
          for (int s = 0; s < samples; ++s) CHECK(fb->sample_depth(x, y, s) == (y < 3 ? 0.25f : 0.75f));
      // Distinct depths per sample: the resolve keeps each pixel's nearest.
      for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
          for (int s = 0; s < samples; ++s) fb->set_sample_depth(x, y, s, float(100 + 10 * x + y - s) / 256.0f);
      const Framebuffer resolved = fb->resolve();
      REQUIRE(resolved.samples() == 1);
      for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) {
          CHECK(resolved.depth(x, y) == float(100 + 10 * x + y - (samples - 1)) / 256.0f);
          CHECK(resolved.color(x, y) == (y < 3 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 0, 1, 1)));
        }
    }
}

}  // namespace tessera
