// A clear written tile by tile (Framebuffer::clear_by_tiles, Device::clear): every pixel a reader sees
// has the bytes of an immediate clear, whether a draw entered its tile, the resolve wrote it from the
// clear values, or finish_clear wrote it.
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "pipeline_support.h"

namespace tessera {
namespace {

using test::clip_vertex;
using V1 = ClipVertex<1>;

struct FlatPS {
  glm::vec4 operator()(const PixelInput<1>& in) const { return glm::vec4(in.attributes[0], 0.25f, 0.75f, 1.0f); }
};

// Random triangles in the target's top-left third, so that most tiles are entered by no draw.
std::vector<V1> corner_triangles(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> x(0.0f, float(width) / 3.0f), y(0.0f, float(height) / 3.0f), z(0.1f, 0.9f),
      a(0.0f, 1.0f);
  std::vector<V1> v;
  for (int i = 0; i < 60; ++i) {
    const float px = x(rng), py = y(rng);
    V1 p = clip_vertex<1>(px / float(width) * 2.0f - 1.0f, 1.0f - py / float(height) * 2.0f, z(rng), 1.0f);
    p.attributes[0] = a(rng);
    v.push_back(p);
  }
  return v;
}

void draw_with(Device& device, Framebuffer& fb, const std::vector<V1>& vertices) {
  std::vector<std::uint32_t> indices(vertices.size());
  for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = std::uint32_t(i);
  MeshDraw<V1, test::ClipPassVS<1>, FlatPS> d;
  d.vertices = vertices;
  d.indices = indices;
  d.rasterizer.cull = CullMode::none;
  d.depth.func = CompareFunc::less;
  d.viewport = test::full_viewport(fb.width(), fb.height());
  REQUIRE(device.draw(d, fb).ok());
}

Framebuffer target(int w, int h, ColorFormat f, int samples) {
  std::string error;
  auto fb = Framebuffer::create(w, h, f, &error, samples);
  REQUIRE(fb);
  fb->clear(glm::vec4(0.9f, 0.1f, 0.5f, 0.3f), 0.125f);  // bytes that the clears below must replace
  return std::move(*fb);
}

}  // namespace

TEST_CASE("tile clear: a frame cleared by tiles has the bytes of one cleared at once", "[raster][msaa]") {
  // Odd sizes (a last partial tile, and on multisampled targets quads padding the last row and
  // column), every sample count and both formats, two tile sizes; the draw enters only some tiles.
  const glm::vec4 color(0.2f, 0.4f, 0.6f, 0.8f);
  for (const int samples : {1, 2, 4, 8, 16})
    for (const ColorFormat f : {ColorFormat::rgba8_unorm, ColorFormat::rgba32_float})
      for (const int tile : {8, 64}) {
        INFO(samples << " samples, format " << int(f) << ", tile " << tile);
        const int w = 157, h = 91;
        const std::vector<V1> triangles = corner_triangles(w, h, unsigned(samples * 7 + tile));
        Device device(DeviceOptions{3, tile});
        Framebuffer at_once = target(w, h, f, samples), by_tiles = target(w, h, f, samples);
        at_once.clear(color, 0.25f);
        draw_with(device, at_once, triangles);
        // Device::clear clears a multisampled target by tiles, a single-sampled one at once.
        if (samples > 1)
          device.clear(by_tiles, color, 0.25f);
        else
          by_tiles.clear_by_tiles(color, 0.25f, tile);
        REQUIRE(by_tiles.pending_clear_tile_size() == tile);
        draw_with(device, by_tiles, triangles);
        CHECK(by_tiles.pending_clear_tile_size() == tile);  // a draw writes only the tiles it enters
        if (samples > 1) {
          // The resolve writes the tiles no draw entered from the clear values, without their samples.
          Framebuffer expected = target(w, h, f, 1), got = target(w, h, f, 1);
          device.resolve(at_once, expected);
          device.resolve(by_tiles, got);
          CHECK(got.color_bytes() == expected.color_bytes());
          CHECK(got.depth_values() == expected.depth_values());
          const Framebuffer serial = by_tiles.resolve();
          CHECK(serial.color_bytes() == expected.color_bytes());
          CHECK(serial.depth_values() == expected.depth_values());
          // The colour alone: the same colour bytes, the target's depth as it was (or, with a clear
          // pending on it, that clear's), and a new target's depth as created.
          Framebuffer color_only = target(w, h, f, 1);
          const std::vector<float> depth_before = color_only.depth_values();
          device.resolve(by_tiles, color_only, ResolvedPlanes::color);
          CHECK(color_only.color_bytes() == expected.color_bytes());
          CHECK(color_only.depth_values() == depth_before);
          Framebuffer pending_out = target(w, h, f, 1);
          pending_out.clear_by_tiles(glm::vec4(0.5f), 0.75f, tile);
          device.resolve(at_once, pending_out, ResolvedPlanes::color);
          CHECK(pending_out.pending_clear_tile_size() == 0);
          CHECK(pending_out.color_bytes() == expected.color_bytes());
          CHECK(pending_out.depth_values() == std::vector<float>(depth_before.size(), 0.75f));
          const Framebuffer serial_color = by_tiles.resolve(ResolvedPlanes::color);
          CHECK(serial_color.color_bytes() == expected.color_bytes());
          CHECK(serial_color.depth_values() == std::vector<float>(depth_before.size(), 1.0f));
        }
        device.finish_clear(by_tiles);
        CHECK(by_tiles.pending_clear_tile_size() == 0);
        CHECK(by_tiles.color_bytes() == at_once.color_bytes());
        CHECK(by_tiles.depth_values() == at_once.depth_values());
      }
}

TEST_CASE("tile clear: a draw on a device of another tile size writes the pending clear first", "[raster]") {
  const int w = 130, h = 70;
  const glm::vec4 color(0.0f, 0.5f, 1.0f, 1.0f);
  const std::vector<V1> triangles = corner_triangles(w, h, 11u);
  for (const int samples : {1, 4}) {
    const Device clears(DeviceOptions{2, 16});
    Device draws(DeviceOptions{2, 64});
    Framebuffer at_once = target(w, h, ColorFormat::rgba8_unorm, samples),
                by_tiles = target(w, h, ColorFormat::rgba8_unorm, samples);
    at_once.clear(color, 1.0f);
    draw_with(draws, at_once, triangles);
    by_tiles.clear_by_tiles(color, 1.0f, clears.options().tile_size);
    draw_with(draws, by_tiles, triangles);
    // The 16-pixel grid's clear was written whole before the 64-pixel tiles were drawn.
    CHECK(by_tiles.pending_clear_tile_size() == 0);
    CHECK(by_tiles.color_bytes() == at_once.color_bytes());
    CHECK(by_tiles.depth_values() == at_once.depth_values());
  }
}

TEST_CASE("tile clear: Device::clear leaves a clear pending on multisampled targets only", "[raster]") {
  Device device(DeviceOptions{2, 32});
  for (const int samples : {1, 2, 4, 8, 16}) {
    Framebuffer fb = target(70, 50, ColorFormat::rgba8_unorm, samples);
    device.clear(fb, glm::vec4(0.5f), 0.5f);
    CHECK(fb.pending_clear_tile_size() == (samples > 1 ? 32 : 0));
    device.finish_clear(fb);
    CHECK(fb.pending_clear_tile_size() == 0);
    int wrong = 0;
    for (int y = 0; y < 50; ++y)
      for (int x = 0; x < 70; ++x)
        for (int s = 0; s < samples; ++s) wrong += fb.sample_depth(x, y, s) != 0.5f;
    CHECK(wrong == 0);
  }
}

TEST_CASE("tile clear: whole-buffer readers and row clears refuse a target with a clear pending", "[raster]") {
  Framebuffer fb = target(40, 30, ColorFormat::rgba8_unorm, 4);
  fb.clear_by_tiles(glm::vec4(1.0f), 1.0f, 16);
  CHECK_THROWS_AS(fb.color_bytes(), std::logic_error);
  CHECK_THROWS_AS(fb.depth_values(), std::logic_error);
  CHECK_THROWS_AS(fb.clear_rows(0, 2, glm::vec4(0.0f), 0.5f), std::logic_error);
  CHECK_THROWS_AS(fb.clear_by_tiles(glm::vec4(1.0f), 1.0f, 7), std::logic_error);
  fb.finish_clear();
  CHECK(fb.color_bytes().size() == std::size_t(40 * 30 * 4 * 4));
  int wrong = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x)
      for (int s = 0; s < 4; ++s) wrong += fb.sample_depth(x, y, s) != 1.0f;
  CHECK(wrong == 0);
  // clear() replaces a pending clear: no tile keeps the older one.
  fb.clear_by_tiles(glm::vec4(1.0f), 0.75f, 16);
  fb.clear(glm::vec4(0.0f), 0.5f);
  CHECK(fb.pending_clear_tile_size() == 0);
  wrong = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) wrong += fb.sample_depth(x, y, 3) != 0.5f;
  CHECK(wrong == 0);
}

TEST_CASE("tile clear: a clear writes its colour and depth to every sample, for any run of pixels", "[raster]") {
  // Widths 1..40 give every run length of a row (the clear stores 32 bytes at a time, then the rest
  // pixel by pixel); both formats, single and multisampled, cleared at once and by tiles.
  const glm::vec4 color(0.2f, 0.4f, 0.6f, 0.8f);
  const std::uint8_t rgba8[4] = {51, 102, 153, 204};  // float_to_unorm8 of each channel
  for (const int samples : {1, 4})
    for (const ColorFormat f : {ColorFormat::rgba8_unorm, ColorFormat::rgba32_float})
      for (int w = 1; w <= 40; ++w) {
        INFO(samples << " samples, format " << int(f) << ", width " << w);
        for (const bool by_tiles : {false, true}) {
          Framebuffer fb = target(w, 3, f, samples);
          if (by_tiles) {
            fb.clear_by_tiles(color, 0.5f, 8);
            fb.finish_clear();
          } else {
            fb.clear(color, 0.5f);
          }
          const std::vector<std::uint8_t>& bytes = fb.color_bytes();
          const std::size_t pixel_bytes = f == ColorFormat::rgba8_unorm ? 4 : 16;
          bool all = true;
          for (std::size_t i = 0; i < bytes.size(); i += pixel_bytes)
            all = all && (f == ColorFormat::rgba8_unorm ? std::memcmp(&bytes[i], rgba8, 4) == 0
                                                        : std::memcmp(&bytes[i], &color[0], 16) == 0);
          CHECK(all);
          CHECK(fb.depth_values() == std::vector<float>(fb.depth_values().size(), 0.5f));
        }
      }
}

}  // namespace tessera
