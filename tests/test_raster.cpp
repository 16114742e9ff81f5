// The rasterizer against D3D11's rules: fill-rule coverage, clipping, perspective-correct interpolation,
// depth functions, lines and points.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "pipeline/texture.h"
#include "pipeline_support.h"
#include "shaders_cpp/image_io/image_file.h"

using namespace tessera;
using namespace tessera::test;

namespace {

using V1 = ClipVertex<1>;

// A (cols x rows) grid of quads, each split into two triangles along an alternating diagonal, with
// inner vertices jittered by sub-pixel amounts; `z_of_x` gives clip z from NDC x (w = 1).
struct Grid {
  std::vector<V1> vertices;
  std::vector<std::uint32_t> indices;
};

Grid jittered_grid(int cols, int rows, float x0, float x1, float y0, float y1, std::uint32_t seed,
                   float (*z_of_x)(float)) {
  Rng rng(seed);
  Grid g;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= cols; ++i) {
      float x = x0 + (x1 - x0) * float(i) / float(cols), y = y0 + (y1 - y0) * float(j) / float(rows);
      if (i > 0 && i < cols) x += float(rng.uniform(-0.3, 0.3)) * (x1 - x0) / float(cols);
      if (j > 0 && j < rows) y += float(rng.uniform(-0.3, 0.3)) * (y1 - y0) / float(rows);
      g.vertices.push_back(clip_vertex<1>(x, y, z_of_x(x), 1.0f));
    }
  const auto at = [&](int i, int j) { return std::uint32_t(j * (cols + 1) + i); };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const auto a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if ((i + j) % 2) {
        g.indices.insert(g.indices.end(), {a, b, c, a, c, d});
      } else {
        g.indices.insert(g.indices.end(), {a, b, d, b, c, d});
      }
    }
  return g;
}

std::vector<int> draw_counting(Device& device, const Grid& g, int w, int h, CullMode cull = CullMode::none) {
  std::vector<int> counts(std::size_t(w) * std::size_t(h), 0);
  auto fb = make_target(w, h);
  MeshDraw<V1, ClipPassVS<1>, CountingPS<1>> d;
  d.vertices = g.vertices;
  d.indices = g.indices;
  d.ps = {&counts, w};
  d.rasterizer.cull = cull;
  d.depth.test = false;
  d.viewport = full_viewport(w, h);
  const DrawResult r = device.draw(d, fb);
  REQUIRE(r.ok());
  return counts;
}

// The clip vertex (w = 1) whose window position on a size x size target is (x, y) in 16.8 fixed point
// exactly: NDC = window * 2 / size - 1 is exact for a power-of-two size.
V1 snapped_vertex(std::int32_t x, std::int32_t y, int size) {
  const float half = float(size) / 2.0f;
  return clip_vertex<1>(float(x) / float(kSubpixelOne) / half - 1.0f, 1.0f - float(y) / float(kSubpixelOne) / half,
                        0.5f, 1.0f);
}

// Adds 1 to `counts` (size x size) at every pixel whose centre the triangle (16.8 vertices, either
// winding) covers by the one-centre edge test; returns how many.
int add_exact_coverage(std::int32_t (&sx)[3], std::int32_t (&sy)[3], int size, std::vector<int>& counts) {
  // covers_centre wants positive area (clockwise on screen, y down).
  const std::int64_t area =
      std::int64_t(sx[1] - sx[0]) * (sy[2] - sy[0]) - std::int64_t(sx[2] - sx[0]) * (sy[1] - sy[0]);
  if (area == 0) return 0;
  if (area < 0) std::swap(sx[1], sx[2]), std::swap(sy[1], sy[2]);
  int pixels = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      if (detail::covers_centre(sx, sy, x, y)) ++counts[std::size_t(y) * std::size_t(size) + std::size_t(x)], ++pixels;
  return pixels;
}

float flat_z(float) { return 0.5f; }
// z < 0 (in front of the near plane) for NDC x < -0.2: the left part is clipped away.
float tilted_z(float x) { return 0.5f * (x + 0.2f); }

}  // namespace

TEST_CASE("raster: a jittered mesh covers every pixel exactly once (top-left rule)", "[raster]") {
  Device device(DeviceOptions{2, 16});
  for (std::uint32_t seed = 1; seed <= 4; ++seed) {
    // Rows and columns of quads whose vertices fall on arbitrary sub-pixel positions, shared diagonals.
    const Grid g = jittered_grid(13, 9, -1.0f, 1.0f, -1.0f, 1.0f, seed, flat_z);
    const auto counts = draw_counting(device, g, 97, 61);
    int zero = 0, multiple = 0;
    for (int c : counts) zero += c == 0, multiple += c > 1;
    INFO("seed " << seed << ": " << zero << " pixels missed, " << multiple << " shaded more than once");
    CHECK(zero == 0);
    CHECK(multiple == 0);
  }
}

TEST_CASE("raster: exact edge and corner ties obey the top-left rule", "[raster]") {
  // Vertices exactly on pixel centres: the centre on a shared edge belongs to one triangle only.
  Device device(DeviceOptions{1, 16});
  Grid g;
  const int w = 16, h = 16;
  auto ndc = [&](float px, float py) { return clip_vertex<1>(px / w * 2 - 1, 1 - py / h * 2, 0.5f, 1); };
  // Pixel centres at (k + 0.5); a fan of 8 triangles around the centre (8.5, 8.5) of a square.
  const float c = 8.5f;
  const float ring[8][2] = {{2.5f, 2.5f},   {c, 2.5f},  {14.5f, 2.5f}, {14.5f, c},
                            {14.5f, 14.5f}, {c, 14.5f}, {2.5f, 14.5f}, {2.5f, c}};
  g.vertices.push_back(ndc(c, c));
  for (auto& p : ring) g.vertices.push_back(ndc(p[0], p[1]));
  for (std::uint32_t k = 0; k < 8; ++k) g.indices.insert(g.indices.end(), {0, 1 + k, 1 + (k + 1) % 8});
  const auto counts = draw_counting(device, g, w, h);
  int covered = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int n = counts[std::size_t(y * w + x)];
      CHECK(n <= 1);
      covered += n;
    }
  // Centres in [2.5, 14.5) on both axes under the top-left rule: columns and rows 2..13 -> 12 x 12.
  CHECK(covered == 144);
  CHECK(counts[8 * w + 8] == 1);    // the shared centre vertex: exactly one of eight triangles
  CHECK(counts[2 * w + 2] == 1);    // top-left corner: on a top and a left edge
  CHECK(counts[14 * w + 14] == 0);  // bottom-right corner: on a bottom and a right edge
}

TEST_CASE("raster: triangles clipped by the guard band still tile exactly once", "[raster][clip]") {
  // Outer vertices lie far beyond the guard band (|x| up to 5000 viewport half-widths), so the
  // border triangles are clipped in clip space; the inner seams must not open or overlap.
  Device device(DeviceOptions{2, 16});
  const Grid g = jittered_grid(5, 5, -5000.0f, 5000.0f, -3000.0f, 3000.0f, 11, flat_z);
  const auto counts = draw_counting(device, g, 64, 48);
  int zero = 0, multiple = 0;
  for (int c : counts) zero += c == 0, multiple += c > 1;
  CHECK(zero == 0);
  CHECK(multiple == 0);
}

TEST_CASE("raster: near-plane clipping cuts the mesh without seams", "[raster][clip]") {
  Device device(DeviceOptions{2, 16});
  const int w = 80, h = 40;
  const Grid g = jittered_grid(7, 5, -1.5f, 1.5f, -1.5f, 1.5f, 5, tilted_z);
  const auto counts = draw_counting(device, g, w, h);
  int wrong = 0, in_front = 0, behind = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float ndc_x = (float(x) + 0.5f) / float(w) * 2 - 1;
      const int n = counts[std::size_t(y * w + x)];
      if (n > 1) ++wrong;
      const float z = tilted_z(ndc_x);
      if (z > 0.02f) {
        in_front += n == 1;
        if (n != 1) ++wrong;
      } else if (z < -0.02f) {
        behind += n == 0;
        if (n != 0) ++wrong;
      }
    }
  CHECK(wrong == 0);
  CHECK(in_front > 0);
  CHECK(behind > 0);
}

TEST_CASE("raster: clipping interpolates shared edges bit-identically", "[raster][clip]") {
  // Two triangles share the edge (a, b) and walk it in opposite directions; both clip it at the near plane.
  const GuardBand g{4, 4};
  ClipVertex<2> a, b, c, d;
  a.position = {-0.3f, 0.1f, -0.7f, 1.3f};
  a.attributes = {0.1f, 0.7f};
  b.position = {0.4f, -0.2f, 0.9f, 1.1f};
  b.attributes = {0.9f, 0.3f};
  c.position = {0.5f, 0.6f, 0.4f, 1.0f};
  d.position = {-0.6f, -0.5f, 0.6f, 1.2f};
  ClipPolygon<2> p1, p2;
  p1.v = {a, b, c};
  p1.count = 3;
  p2.v = {b, a, d};
  p2.count = 3;
  clip_polygon(p1, 1u << kNear, g);
  clip_polygon(p2, 1u << kNear, g);
  REQUIRE(p1.count == 4);
  REQUIRE(p2.count == 4);
  // The new vertex on edge (a, b) lies on z = 0 and is the same bits in both polygons.
  auto on_plane = [](const ClipPolygon<2>& p) {
    std::vector<ClipVertex<2>> r;
    for (int i = 0; i < p.count; ++i)
      if (p.v[i].position.z == 0.0f) r.push_back(p.v[i]);
    return r;
  };
  const auto n1 = on_plane(p1), n2 = on_plane(p2);
  REQUIRE(n1.size() == 2);
  REQUIRE(n2.size() == 2);
  bool shared = false;
  for (const auto& x : n1)
    for (const auto& y : n2)
      shared |= std::memcmp(&x.position, &y.position, sizeof(glm::vec4)) == 0 &&
                std::memcmp(x.attributes.data(), y.attributes.data(), 8) == 0;
  CHECK(shared);
  for (int i = 0; i < p1.count; ++i) CHECK(p1.v[i].position.z >= 0.0f);
}

TEST_CASE("raster: attributes are interpolated perspective-correctly", "[raster]") {
  // A plane receding in depth: vertex s in {0, 1} at x = 2s - 1 (clip) with w = 1 + 3s. On screen,
  // x_ndc = (2s - 1) / (1 + 3s), so the exact attribute is s = (1 + x_ndc) / (2 - 3 x_ndc).
  Device device(DeviceOptions{2, 16});
  const int w = 128, h = 8;
  std::vector<V1> v;
  for (int s = 0; s <= 1; ++s)
    for (int t = 0; t <= 1; ++t) {
      const float ws = 1.0f + 3.0f * float(s);
      V1 x = clip_vertex<1>((2.0f * float(s) - 1.0f), (2.0f * float(t) - 1.0f) * ws, 0.5f, ws);
      x.attributes[0] = float(s);
      v.push_back(x);
    }
  const std::vector<std::uint32_t> idx = {0, 2, 3, 0, 3, 1};
  std::vector<int> counts(std::size_t(w) * h, 0);
  auto fb = make_target(w, h, ColorFormat::rgba32_float);
  MeshDraw<V1, ClipPassVS<1>, CountingPS<1>> d;
  d.vertices = v;
  d.indices = idx;
  d.ps = {&counts, w};
  d.rasterizer.cull = CullMode::none;
  d.viewport = full_viewport(w, h);
  REQUIRE(device.draw(d, fb).ok());
  double worst = 0, worst_linear = 0;
  int checked = 0;
  for (int x = 0; x < w; ++x) {
    if (counts[std::size_t((h / 2) * w + x)] != 1) continue;  // outside the quad (it ends at x_ndc = 0.25)
    ++checked;
    const double ndc = (x + 0.5) / w * 2 - 1;
    const double exact = (1 + ndc) / (2 - 3 * ndc);
    const double got = fb.color(x, h / 2).r;
    worst = std::max(worst, std::abs(got - exact));
    worst_linear = std::max(worst_linear, std::abs((1 + ndc) / 2 - exact));
  }
  CHECK(checked > w / 2);
  CHECK(worst < 2e-5);
  CHECK(worst_linear > 0.1);  // screen-linear interpolation would be far off: the case is discriminating
}

TEST_CASE("raster: depth comparison functions and depth write", "[raster][depth]") {
  // Two full-screen triangles: first at depth 0.5 (red), then at `second_z` (green).
  Device device(DeviceOptions{1, 16});
  auto run = [&](CompareFunc f, float second_z, bool write) {
    auto fb = make_target(8, 8);
    auto tri = [&](float z, float g) {
      std::vector<ClipVertex<3>> v = {clip_vertex<3>(-1, -1, z, 1), clip_vertex<3>(-1, 3, z, 1),
                                      clip_vertex<3>(3, -1, z, 1)};
      for (auto& x : v) x.attributes = {1.0f - g, g, 0.0f};
      return v;
    };
    const std::vector<std::uint32_t> idx = {0, 1, 2};
    std::vector<int> counts(64, 0);
    for (int pass = 0; pass < 2; ++pass) {
      const auto v = tri(pass == 0 ? 0.5f : second_z, pass == 0 ? 0.0f : 1.0f);
      MeshDraw<ClipVertex<3>, ClipPassVS<3>, CountingPS<3>> d;
      d.vertices = v;
      d.indices = idx;
      d.ps = {&counts, 8};
      d.rasterizer.cull = CullMode::none;
      d.depth = {true, pass == 0 || write, pass == 0 ? CompareFunc::always : f};
      d.viewport = full_viewport(8, 8);
      REQUIRE(device.draw(d, fb).ok());
    }
    return std::pair{fb.color(3, 3).g > 0.5f, fb.depth(3, 3)};
  };
  struct Case {
    CompareFunc f;
    float z;
    bool green;
  } cases[] = {{CompareFunc::never, 0.2f, false},        {CompareFunc::always, 0.8f, true},
               {CompareFunc::less, 0.2f, true},          {CompareFunc::less, 0.5f, false},
               {CompareFunc::less_equal, 0.5f, true},    {CompareFunc::less_equal, 0.6f, false},
               {CompareFunc::greater, 0.8f, true},       {CompareFunc::greater, 0.5f, false},
               {CompareFunc::greater_equal, 0.5f, true}, {CompareFunc::equal, 0.5f, true},
               {CompareFunc::equal, 0.25f, false},       {CompareFunc::not_equal, 0.25f, true},
               {CompareFunc::not_equal, 0.5f, false}};
  for (const auto& c : cases) {
    INFO(to_string(c.f) << " with " << c.z);
    const auto [green, depth] = run(c.f, c.z, true);
    CHECK(green == c.green);
    CHECK(depth == (c.green ? c.z : 0.5f));
  }
  const auto [green, depth] = run(CompareFunc::less, 0.2f, false);
  CHECK(green);
  CHECK(depth == 0.5f);  // depth write off: the stored depth is unchanged
}

TEST_CASE("raster: back and front culling follow the winding on screen", "[raster]") {
  Device device(DeviceOptions{1, 16});
  Grid g;
  // Clockwise on screen (y down) = front by default: (-1,1) -> (1,1) -> (-1,-1) in NDC.
  g.vertices = {clip_vertex<1>(-1, 1, 0.5f, 1), clip_vertex<1>(1, 1, 0.5f, 1), clip_vertex<1>(-1, -1, 0.5f, 1)};
  g.indices = {0, 1, 2};
  auto total = [](const std::vector<int>& c) {
    int n = 0;
    for (int x : c) n += x;
    return n;
  };
  CHECK(total(draw_counting(device, g, 16, 16, CullMode::back)) > 0);
  CHECK(total(draw_counting(device, g, 16, 16, CullMode::front)) == 0);
  g.indices = {0, 2, 1};
  CHECK(total(draw_counting(device, g, 16, 16, CullMode::back)) == 0);
  CHECK(total(draw_counting(device, g, 16, 16, CullMode::front)) > 0);
}

TEST_CASE("raster: scissor and viewport limit the written pixels", "[raster]") {
  Device device(DeviceOptions{2, 16});
  const Grid g = jittered_grid(2, 2, -1, 1, -1, 1, 3, flat_z);
  std::vector<int> counts(40 * 30, 0);
  auto fb = make_target(40, 30);
  MeshDraw<V1, ClipPassVS<1>, CountingPS<1>> d;
  d.vertices = g.vertices;
  d.indices = g.indices;
  d.ps = {&counts, 40};
  d.rasterizer.cull = CullMode::none;
  d.rasterizer.scissor = ScissorRect{5, 4, 17, 20};
  d.viewport = {2, 3, 30, 20, 0, 1};
  REQUIRE(device.draw(d, fb).ok());
  int inside = 0, outside = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const int n = counts[std::size_t(y * 40 + x)];
      const bool in = x >= 5 && x < 17 && y >= 4 && y < 20;  // the scissor lies within the viewport here
      (in ? inside : outside) += n;
      if (in) CHECK(n == 1);
    }
  CHECK(inside == 12 * 16);
  CHECK(outside == 0);
}

namespace {

// Samples a texture with the derivatives of attributes 0 and 1 (HLSL Sample in a pixel shader).
struct TexturePS {
  const Texture2D* texture = nullptr;
  glm::vec4 operator()(const PixelInput<2>& in) const {
    const Sampler s{Filter::trilinear, AddressMode::wrap, AddressMode::wrap};
    return texture->sample_grad(s, {in.attributes[0], in.attributes[1]}, {in.ddx(0), in.ddx(1)},
                                {in.ddy(0), in.ddy(1)});
  }
};

}  // namespace

TEST_CASE("raster: pixel-shader derivatives select the mip level, float targets write EXR", "[raster][texture]") {
  // A 64x64 one-texel checkerboard: level 0 is 0/1, every coarser level is 0.5.
  std::vector<float> texels(64 * 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) texels[std::size_t(y * 64 + x)] = float((x + y) % 2);
  std::string error;
  const auto tex = Texture2D::create(64, 64, 1, texels, true, &error);
  REQUIRE(tex);
  Device device(DeviceOptions{2, 16});
  for (float texels_per_pixel : {1.0f, 4.0f}) {
    const int w = 32, h = 32;
    // uv spans texels_per_pixel * 32 texels across the 32-pixel target: ddx(u) = texels_per_pixel / 64.
    const float span = texels_per_pixel * 32.0f / 64.0f;
    std::vector<ClipVertex<2>> v = {clip_vertex<2>(-1, 1, 0.5f, 1), clip_vertex<2>(3, 1, 0.5f, 1),
                                    clip_vertex<2>(-1, -3, 0.5f, 1)};
    v[0].attributes = {0, 0};
    v[1].attributes = {2 * span, 0};
    v[2].attributes = {0, 2 * span};
    const std::vector<std::uint32_t> idx = {0, 1, 2};
    auto fb = make_target(w, h, ColorFormat::rgba32_float);
    MeshDraw<ClipVertex<2>, ClipPassVS<2>, TexturePS> d;
    d.vertices = v;
    d.indices = idx;
    d.ps = {&*tex};
    d.rasterizer.cull = CullMode::none;
    d.viewport = full_viewport(w, h);
    REQUIRE(device.draw(d, fb).ok());
    INFO("texels per pixel " << texels_per_pixel);
    if (texels_per_pixel == 1.0f) {
      // lod 0: each pixel centre sits on a texel centre, so the checkerboard comes through exactly.
      CHECK(fb.color(4, 7).r == 1.0f);
      CHECK(fb.color(5, 7).r == 0.0f);
    } else {
      CHECK(fb.color(4, 7).r == Approx(0.5f));  // lod 2: the averaged level
      CHECK(fb.color(5, 7).r == Approx(0.5f));
      const std::string path = (std::filesystem::temp_directory_path() / "tessera-test-lod.exr").string();
      REQUIRE(write_color(fb, {path}).empty());
      auto in = OIIO::ImageInput::open(path);
      REQUIRE(in);
      std::vector<float> px(std::size_t(w) * h * 4);
      REQUIRE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, px.data()));
      CHECK(px[(7 * std::size_t(w) + 4) * 4] == Approx(0.5f));
      in->close();
      std::filesystem::remove(path);
    }
  }
}

TEST_CASE("raster: coverage equals the exact edge test on both sides of the 32-bit edge limit", "[raster]") {
  // Triangles of 100..160 pixels: below about 127 pixels of extent the rasterizer evaluates edges in
  // 32-bit lanes, above in 64-bit integers; both must give exactly the pixels the one-centre test gives.
  // Vertices lie on the 16.8 grid of a 512x512 target (NDC = window / 256 - 1 is exact), so the snapped
  // positions are known.
  constexpr int kSize = 512;
  Device device(DeviceOptions{2, 64});
  Rng rng(7);
  int small = 0, large = 0;
  for (int t = 0; t < 24; ++t) {
    const double extent = rng.uniform(100, 160);
    const double cx = rng.uniform(100, 400), cy = rng.uniform(100, 400);
    std::int32_t sx[3], sy[3];
    for (int k = 0; k < 3; ++k) {
      sx[k] = std::int32_t(std::lround((cx + rng.uniform(-0.5, 0.5) * extent) * kSubpixelOne));
      sy[k] = std::int32_t(std::lround((cy + rng.uniform(-0.5, 0.5) * extent) * kSubpixelOne));
    }
    const std::int32_t ext = std::max(std::max(sx[0], sx[1]), sx[2]) - std::min(std::min(sx[0], sx[1]), sx[2]);
    (ext <= kEdges32MaxExtent ? small : large) += 1;
    Grid g;
    for (int k = 0; k < 3; ++k) g.vertices.push_back(snapped_vertex(sx[k], sy[k], kSize));
    g.indices = {0, 1, 2};
    const std::vector<int> counts = draw_counting(device, g, kSize, kSize);
    std::vector<int> expected(counts.size(), 0);
    const int covered = add_exact_coverage(sx, sy, kSize, expected);
    int wrong = 0;
    for (std::size_t i = 0; i < counts.size(); ++i) wrong += counts[i] != expected[i];
    INFO("triangle " << t << ", extent " << ext << " (16.8 units), " << covered << " pixels");
    CHECK(wrong == 0);
  }
  CHECK(small > 0);
  CHECK(large > 0);
}

TEST_CASE("raster: Device::clear writes the bytes Framebuffer::clear writes", "[raster]") {
  Device device(DeviceOptions{2, 64});
  for (const ColorFormat f : {ColorFormat::rgba8_unorm, ColorFormat::rgba32_float}) {
    auto a = make_target(97, 61, f), b = make_target(97, 61, f);
    a.clear(glm::vec4(0.2f, 0.4f, 0.6f, 0.8f), 0.25f);
    b.clear(glm::vec4(0.9f, 0.9f, 0.9f, 0.9f), 0.75f);  // different first, so the clear must overwrite
    device.clear(b, glm::vec4(0.2f, 0.4f, 0.6f, 0.8f), 0.25f);
    device.finish_clear(b);  // no draw entered a tile: every tile is written here
    CHECK(a.color_bytes() == b.color_bytes());
    CHECK(a.depth_values() == b.depth_values());
  }
}

TEST_CASE("raster: tiny triangles cover exactly the centres of the exact edge test", "[raster]") {
  // Triangles of 0.2..7 pixels, one per 8x8 cell of a 256x256 target, at random sub-pixel positions: setup
  // tests boxes of at most 4x4 centres itself (dropping triangles that cover none) and sets the edges of
  // the rest up for the rasterizer (a triangle with a box of at most 4x4 centres carries the centres it
  // covers, and the rasterizer shades their quads without walking edges); every pixel must be lit
  // exactly when the one-centre test says so. Second run: the triangles straddle the 8-pixel tiles.
  constexpr int kSize = 256, kCell = 8, kCells = kSize / kCell;
  const auto [offset, tile_size] = GENERATE(std::pair{2, 64}, std::pair{6, 8});
  CAPTURE(offset, tile_size);
  Rng rng(11);
  // Pixel centres in a triangle's vertex box along one axis (detail:: as setup finds them).
  const auto centres = [](const std::int32_t(&c)[3]) {
    return detail::last_pixel_at_or_before(std::max({c[0], c[1], c[2]})) -
           detail::first_pixel_at_or_after(std::min({c[0], c[1], c[2]})) + 1;
  };
  Grid g;
  std::vector<int> expected(std::size_t(kSize) * kSize, 0);
  int lit = 0, empty = 0, small_box = 0, large_box = 0;
  for (int cy = 0; cy < kCells; ++cy)
    for (int cx = 0; cx < kCells; ++cx) {
      const double extent = rng.uniform(0.2, 7.0);
      const double ox = cx * kCell + offset + rng.uniform(0, 2), oy = cy * kCell + offset + rng.uniform(0, 2);
      std::int32_t sx[3], sy[3];  // 16.8
      for (int k = 0; k < 3; ++k) {
        sx[k] = std::int32_t(std::lround((ox + rng.uniform(0, 1) * extent) * kSubpixelOne));
        sy[k] = std::int32_t(std::lround((oy + rng.uniform(0, 1) * extent) * kSubpixelOne));
        g.indices.push_back(std::uint32_t(g.vertices.size()));
        g.vertices.push_back(snapped_vertex(sx[k], sy[k], kSize));
      }
      (std::max(centres(sx), centres(sy)) <= kSmallBoxPixels ? small_box : large_box) += 1;
      // After the vertices are drawn: it may reorder sx, sy to a positive area.
      (add_exact_coverage(sx, sy, kSize, expected) ? lit : empty) += 1;
    }
  Device device(DeviceOptions{2, tile_size});
  const std::vector<int> counts = draw_counting(device, g, kSize, kSize);
  REQUIRE(counts.size() == expected.size());
  CHECK(counts == expected);
  CHECK(lit > 100);  // both kinds occur
  CHECK(empty > 50);
  CHECK(small_box > 300);  // and both paths of the rasterizer
  CHECK(large_box > 50);
}

TEST_CASE("raster: TileGrid::tile_of is exact division for every tile size and pixel", "[raster]") {
  // Setup bins with a 32-bit multiply and shift in place of p / tile_size; the bound in TileGrid's
  // comment must hold for every size a Device accepts (even, 8..1024) and every pixel of the largest
  // render target.
  int wrong = 0, first_wrong_size = 0, first_wrong_pixel = 0;
  for (int size = 8; size <= 1024; size += 2) {
    TileGrid g;
    g.set_tile_size(size);
    for (std::int32_t p = 0; p < kMaxRenderTargetSize; ++p)
      if (g.tile_of(p) != p / size && wrong++ == 0) first_wrong_size = size, first_wrong_pixel = p;
  }
  INFO("first wrong: tile size " << first_wrong_size << ", pixel " << first_wrong_pixel);
  CHECK(wrong == 0);
}
