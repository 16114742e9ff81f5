// Texture2D: creation, mip chains and D3D11 sampling against hand-computed values. Texel values are
// chosen so that most expected results are exact in float; the rest use Approx with a stated margin.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "pipeline/texture.h"

using namespace tessera;

namespace {

Texture2D make(int width, int height, int channels, std::vector<float> texels, bool build_mips = true) {
  std::string error;
  std::optional<Texture2D> t = Texture2D::create(width, height, channels, std::move(texels), build_mips, &error);
  INFO(error);
  REQUIRE(t.has_value());
  return *t;
}

// 4x4, one channel, texel (x, y) = 4y + x. Level 1 = 2x2 block averages {2.5, 4.5, 10.5, 12.5},
// level 2 = 7.5.
Texture2D ramp4x4() {
  std::vector<float> v(16);
  for (int i = 0; i < 16; ++i) v[static_cast<std::size_t>(i)] = static_cast<float>(i);
  return make(4, 4, 1, std::move(v));
}

Sampler sampler(Filter f, AddressMode u = AddressMode::clamp, AddressMode v = AddressMode::clamp) {
  Sampler s;
  s.filter = f;
  s.address_u = u;
  s.address_v = v;
  return s;
}

bool all_finite(glm::vec4 c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(c.w);
}

}  // namespace

TEST_CASE("texture: create rejects bad sizes, channel counts and texel counts", "[texture]") {
  struct Bad {
    int w, h, c;
    std::size_t count;
    const char* message_part;
  };
  const Bad cases[] = {
      {0, 4, 1, 0, "width"},
      {-3, 4, 1, 12, "width"},
      {32769, 1, 1, 32769, "width"},
      {4, 0, 1, 0, "height"},
      {4, -1, 1, 4, "height"},
      {1, 40000, 1, 40000, "height"},
      {2, 2, 0, 0, "channels"},
      {2, 2, 5, 20, "channels"},
      {2, 2, 1, 3, "needs 4 floats, got 3"},
      {3, 5, 4, 61, "needs 60 floats"},
  };
  for (const Bad& b : cases) {
    std::string error;
    const auto t = Texture2D::create(b.w, b.h, b.c, std::vector<float>(b.count, 1.0f), true, &error);
    INFO(b.w << "x" << b.h << "x" << b.c << " with " << b.count << " floats: " << error);
    CHECK_FALSE(t.has_value());
    CHECK(error.find(b.message_part) != std::string::npos);
    CHECK(error.find('\n') == std::string::npos);
  }
  // A null error pointer is allowed.
  CHECK_FALSE(Texture2D::create(0, 1, 1, {}, false, nullptr).has_value());

  // The largest size is accepted, and NaN/Inf texels are kept as they are.
  CHECK(Texture2D::create(32768, 1, 1, std::vector<float>(32768, 0.0f), true, nullptr).has_value());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const Texture2D t = make(2, 1, 1, {nan, inf}, false);
  CHECK(std::isnan(t.load(0, 0, 0).x));
  CHECK(t.load(0, 1, 0).x == inf);
}

TEST_CASE("texture: sizes, levels and bytes", "[texture]") {
  const Texture2D t = ramp4x4();
  CHECK(t.levels() == 3);
  CHECK(t.channels() == 1);
  CHECK(t.width(0) == 4);
  CHECK(t.width(1) == 2);
  CHECK(t.height(2) == 1);
  CHECK(t.width(3) == 0);  // out of range
  CHECK(t.width(-1) == 0);
  CHECK(t.bytes() == (16 + 4 + 1) * sizeof(float));

  const Texture2D odd = make(5, 3, 2, std::vector<float>(30, 0.0f));
  CHECK(odd.levels() == 3);  // 5x3 -> 2x1 -> 1x1
  CHECK(odd.width(1) == 2);
  CHECK(odd.height(1) == 1);
  CHECK(odd.bytes() == (15 + 2 + 1) * 2 * sizeof(float));

  const Texture2D tall = make(1, 8, 1, std::vector<float>(8, 0.0f));
  CHECK(tall.levels() == 4);  // 1x8 -> 1x4 -> 1x2 -> 1x1
  CHECK(tall.width(3) == 1);
  CHECK(tall.height(2) == 2);

  const Texture2D single = make(4, 4, 1, std::vector<float>(16, 0.0f), false);
  CHECK(single.levels() == 1);
  CHECK(single.bytes() == 16 * sizeof(float));
}

TEST_CASE("texture: point sampling at texel centres and edges", "[texture]") {
  const Texture2D t = ramp4x4();
  const Sampler s = sampler(Filter::point);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const glm::vec2 centre((static_cast<float>(x) + 0.5f) / 4.0f, (static_cast<float>(y) + 0.5f) / 4.0f);
      CHECK(t.sample_level(s, centre, 0.0f).x == static_cast<float>(4 * y + x));
    }
  // An edge between texels belongs to the texel on its right/below: floor(u * size).
  CHECK(t.sample_level(s, {0.25f, 0.0f}, 0.0f).x == 1.0f);
  CHECK(t.sample_level(s, {0.2499f, 0.0f}, 0.0f).x == 0.0f);
  CHECK(t.sample_level(s, {0.0f, 0.5f}, 0.0f).x == 8.0f);
  CHECK(t.sample_level(s, {0.0f, 0.4999f}, 0.0f).x == 4.0f);
  CHECK(t.sample_level(s, {1.0f, 1.0f}, 0.0f).x == 15.0f);  // u = 1 is texel 4, clamped to 3
  // The whole result: R plus the defaults for G, B, A.
  CHECK(t.sample_level(s, {0.6f, 0.1f}, 0.0f) == glm::vec4(2.0f, 0.0f, 0.0f, 1.0f));
}

TEST_CASE("texture: bilinear at texel centres, halfway and quarter points", "[texture]") {
  // 2x2: a b / c d with a = 0, b = 1, c = 2, d = 4.
  const Texture2D t = make(2, 2, 1, {0.0f, 1.0f, 2.0f, 4.0f}, false);
  const Sampler s = sampler(Filter::bilinear);
  CHECK(t.sample_level(s, {0.25f, 0.25f}, 0.0f).x == 0.0f);  // centre of a
  CHECK(t.sample_level(s, {0.75f, 0.75f}, 0.0f).x == 4.0f);  // centre of d
  CHECK(t.sample_level(s, {0.5f, 0.25f}, 0.0f).x == 0.5f);   // halfway a-b
  CHECK(t.sample_level(s, {0.25f, 0.5f}, 0.0f).x == 1.0f);   // halfway a-c
  CHECK(t.sample_level(s, {0.5f, 0.5f}, 0.0f).x == 1.75f);   // (0 + 1 + 2 + 4) / 4
  // u = 0.375: x = 0.375 * 2 - 0.5 = 0.25. Top row 0 * 0.75 + 1 * 0.25 = 0.25.
  CHECK(t.sample_level(s, {0.375f, 0.25f}, 0.0f).x == 0.25f);
  // Both quarter: top 0.25, bottom 2 * 0.75 + 4 * 0.25 = 2.5; 0.25 * 0.75 + 2.5 * 0.25 = 0.8125.
  CHECK(t.sample_level(s, {0.375f, 0.375f}, 0.0f).x == 0.8125f);
  // Three quarters from a towards d: x = y = 0.75. Top = 0 * 0.25 + 1 * 0.75 = 0.75,
  // bottom = 2 * 0.25 + 4 * 0.75 = 3.5, result 0.75 * 0.25 + 3.5 * 0.75 = 2.8125.
  CHECK(t.sample_level(s, {0.625f, 0.625f}, 0.0f).x == 2.8125f);

  // Odd 3x5, texel (x, y) = 10y + x.
  std::vector<float> v;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 3; ++x) v.push_back(static_cast<float>(10 * y + x));
  const Texture2D odd = make(3, 5, 1, std::move(v));
  CHECK(odd.sample_level(s, {0.5f, 0.5f}, 0.0f).x == 21.0f);  // centre of texel (1, 2)
  // v = 0.6: y = 3 - 0.5 = 2.5, halfway rows 2 and 3: (21 + 31) / 2.
  CHECK(odd.sample_level(s, {0.5f, 0.6f}, 0.0f).x == Approx(26.0f).margin(1e-5));
  // u = 1/3: x = 0.5, halfway columns 0 and 1 of row 0.
  CHECK(odd.sample_level(s, {1.0f / 3.0f, 0.1f}, 0.0f).x == Approx(0.5f).margin(1e-5));
  // Wrap on the odd width: u = 0 is halfway between texel 2 (wrapped -1) and texel 0 of row 0.
  const Sampler w = sampler(Filter::bilinear, AddressMode::wrap, AddressMode::clamp);
  CHECK(odd.sample_level(w, {0.0f, 0.1f}, 0.0f).x == 1.0f);  // (2 + 0) / 2
  CHECK(odd.sample_level(s, {0.0f, 0.1f}, 0.0f).x == 0.0f);  // clamp: texel 0 twice
}

TEST_CASE("texture: wrap, clamp and mirror addressing", "[texture]") {
  // 4x1: 10 20 30 40. Mirror repeats 0 1 2 3 3 2 1 0 (period 8).
  const Texture2D t = make(4, 1, 1, {10.0f, 20.0f, 30.0f, 40.0f}, false);
  struct Case {
    float u;
    float wrap, clamp, mirror;
  };
  SECTION("point: texel floor(u * 4)") {
    const Case cases[] = {
        {-0.25f, 40.0f, 10.0f, 10.0f},  // texel -1: wrap 3, mirror 0
        {-0.6f, 20.0f, 10.0f, 30.0f},   // -2.4 -> texel -3: wrap 1, mirror 5 -> 2
        {1.25f, 20.0f, 40.0f, 30.0f},   // texel 5: wrap 1, mirror 2
        {1.6f, 30.0f, 40.0f, 20.0f},    // 6.4 -> texel 6: wrap 2, mirror 1
        {2.6f, 30.0f, 40.0f, 30.0f},    // 10.4 -> texel 10: wrap 2, mirror 10 mod 8 = 2
        {-0.9f, 10.0f, 10.0f, 40.0f},   // -3.6 -> texel -4: wrap 0, mirror 4 -> 3
    };
    for (const Case& c : cases) {
      INFO("u = " << c.u);
      CHECK(t.sample_level(sampler(Filter::point, AddressMode::wrap), {c.u, 0.5f}, 0.0f).x == c.wrap);
      CHECK(t.sample_level(sampler(Filter::point, AddressMode::clamp), {c.u, 0.5f}, 0.0f).x == c.clamp);
      CHECK(t.sample_level(sampler(Filter::point, AddressMode::mirror), {c.u, 0.5f}, 0.0f).x == c.mirror);
    }
  }
  SECTION("bilinear: x = u * 4 - 0.5, both taps addressed") {
    const Case cases[] = {
        {-0.25f, 35.0f, 10.0f, 15.0f},  // x = -1.5: taps -2, -1. wrap 2, 3; mirror 1, 0
        {1.25f, 15.0f, 40.0f, 35.0f},   // x = 4.5: taps 4, 5. wrap 0, 1; mirror 3, 2
        {0.0f, 25.0f, 10.0f, 10.0f},    // x = -0.5: taps -1, 0. wrap 3, 0; mirror 0, 0
        {1.0f, 25.0f, 40.0f, 40.0f},    // x = 3.5: taps 3, 4. wrap 3, 0; mirror 3, 3
    };
    for (const Case& c : cases) {
      INFO("u = " << c.u);
      CHECK(t.sample_level(sampler(Filter::bilinear, AddressMode::wrap), {c.u, 0.5f}, 0.0f).x == c.wrap);
      CHECK(t.sample_level(sampler(Filter::bilinear, AddressMode::clamp), {c.u, 0.5f}, 0.0f).x == c.clamp);
      CHECK(t.sample_level(sampler(Filter::bilinear, AddressMode::mirror), {c.u, 0.5f}, 0.0f).x == c.mirror);
    }
    // u = 1.6: x = 5.9, taps 5, 6 with frac 0.9. wrap: 1, 2 -> 20 * 0.1 + 30 * 0.9 = 29;
    // mirror: 2, 1 -> 30 * 0.1 + 20 * 0.9 = 21; clamp: 40.
    CHECK(t.sample_level(sampler(Filter::bilinear, AddressMode::wrap), {1.6f, 0.5f}, 0.0f).x ==
          Approx(29.0f).margin(1e-4));
    CHECK(t.sample_level(sampler(Filter::bilinear, AddressMode::mirror), {1.6f, 0.5f}, 0.0f).x ==
          Approx(21.0f).margin(1e-4));
    CHECK(t.sample_level(sampler(Filter::bilinear, AddressMode::clamp), {1.6f, 0.5f}, 0.0f).x == 40.0f);
    // u = 2.6: x = 9.9, taps 9, 10: wrap 1, 2 -> 29 again; mirror 1, 2 -> 29.
    CHECK(t.sample_level(sampler(Filter::bilinear, AddressMode::wrap), {2.6f, 0.5f}, 0.0f).x ==
          Approx(29.0f).margin(1e-4));
    CHECK(t.sample_level(sampler(Filter::bilinear, AddressMode::mirror), {2.6f, 0.5f}, 0.0f).x ==
          Approx(29.0f).margin(1e-4));
  }
  SECTION("u and v are addressed independently") {
    // 2x2: 1 2 / 3 4. u wraps, v clamps: (-0.25, -0.25) is texel (-1 -> 1, -1 -> 0) = 2.
    const Texture2D q = make(2, 2, 1, {1.0f, 2.0f, 3.0f, 4.0f}, false);
    CHECK(q.sample_level(sampler(Filter::point, AddressMode::wrap, AddressMode::clamp), {-0.25f, -0.25f}, 0.0f).x ==
          2.0f);
    CHECK(q.sample_level(sampler(Filter::point, AddressMode::clamp, AddressMode::wrap), {-0.25f, -0.25f}, 0.0f).x ==
          3.0f);
    CHECK(q.sample_level(sampler(Filter::point, AddressMode::mirror, AddressMode::wrap), {1.25f, 1.75f}, 0.0f).x ==
          4.0f);  // u: texel 2 -> mirror 1; v: texel 3 -> wrap 1
  }
}

TEST_CASE("texture: mip chain of a 4x4 texture", "[texture]") {
  const Texture2D t = ramp4x4();
  CHECK(t.load(1, 0, 0).x == 2.5f);  // (0 + 1 + 4 + 5) / 4
  CHECK(t.load(1, 1, 0).x == 4.5f);  // (2 + 3 + 6 + 7) / 4
  CHECK(t.load(1, 0, 1).x == 10.5f);
  CHECK(t.load(1, 1, 1).x == 12.5f);
  CHECK(t.load(2, 0, 0).x == 7.5f);
  // Level 0 is kept as given.
  CHECK(t.load(0, 3, 2).x == 11.0f);
  // A copy owns its storage and samples the same.
  const Texture2D copy = t;
  CHECK(copy.load(1, 1, 1).x == 12.5f);
  CHECK(copy.sample_level(Sampler{}, {0.3f, 0.7f}, 0.7f) == t.sample_level(Sampler{}, {0.3f, 0.7f}, 0.7f));
}

TEST_CASE("texture: mip chain of odd sizes is an area-weighted box", "[texture]") {
  SECTION("5 -> 2 -> 1: (2a + 2b + c) / 5 and (c + 2d + 2e) / 5") {
    // 1x5 (vertical) and 5x1 (horizontal), values 0 5 10 15 20.
    const std::vector<float> v{0.0f, 5.0f, 10.0f, 15.0f, 20.0f};
    const Texture2D column = make(1, 5, 1, v);
    const Texture2D row = make(5, 1, 1, v);
    for (const Texture2D* t : {&column, &row}) {
      REQUIRE(t->levels() == 3);
      const glm::vec4 second = t == &column ? t->load(1, 0, 1) : t->load(1, 1, 0);
      CHECK(t->load(1, 0, 0).x == 4.0f);  // (0 + 10 + 10) / 5
      CHECK(second.x == 16.0f);           // (10 + 30 + 40) / 5
      CHECK(t->load(2, 0, 0).x == 10.0f);
    }
  }
  SECTION("7 -> 3 -> 1: (3a + 3b + c) / 7, (2c + 3d + 2e) / 7, (e + 3f + 3g) / 7") {
    const Texture2D t = make(7, 1, 1, {0.0f, 7.0f, 14.0f, 21.0f, 28.0f, 35.0f, 42.0f});
    REQUIRE(t.levels() == 3);
    CHECK(t.load(1, 0, 0).x == 5.0f);   // (0 + 21 + 14) / 7
    CHECK(t.load(1, 1, 0).x == 21.0f);  // (28 + 63 + 56) / 7
    CHECK(t.load(1, 2, 0).x == 37.0f);  // (28 + 105 + 126) / 7
    CHECK(t.load(2, 0, 0).x == 21.0f);  // (5 + 21 + 37) / 3, the mean of level 0
  }
  SECTION("5x3 -> 2x1 -> 1x1, two channels") {
    // Texel (x, y): R = 10y + x, G = 1. Rows reduce to 10y + 0.8 and 10y + 3.2
    // ((2x0 + 2x1 + x2) / 5 and (x2 + 2x3 + 2x4) / 5), then the three rows average to 10.8 and 13.2.
    std::vector<float> v;
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 5; ++x) {
        v.push_back(static_cast<float>(10 * y + x));
        v.push_back(1.0f);
      }
    const Texture2D t = make(5, 3, 2, std::move(v));
    CHECK(t.load(1, 0, 0).x == Approx(10.8f).margin(1e-5));
    CHECK(t.load(1, 1, 0).x == Approx(13.2f).margin(1e-5));
    CHECK(t.load(1, 0, 0).y == 1.0f);  // a constant channel stays exactly constant
    CHECK(t.load(2, 0, 0).x == Approx(12.0f).margin(1e-5));
    CHECK(t.load(2, 0, 0).y == 1.0f);
  }
}

TEST_CASE("texture: point and bilinear use the nearest mip level", "[texture]") {
  const Texture2D t = ramp4x4();  // at uv (0.1, 0.1): level 0 -> 0, level 1 -> 2.5, level 2 -> 7.5
  const Sampler s = sampler(Filter::point);
  const glm::vec2 uv(0.1f, 0.1f);
  CHECK(t.sample_level(s, uv, -3.0f).x == 0.0f);
  CHECK(t.sample_level(s, uv, 0.49f).x == 0.0f);
  CHECK(t.sample_level(s, uv, 0.5f).x == 2.5f);  // floor(0.5 + 0.5) = 1
  CHECK(t.sample_level(s, uv, 1.49f).x == 2.5f);
  CHECK(t.sample_level(s, uv, 1.5f).x == 7.5f);
  CHECK(t.sample_level(s, uv, 7.0f).x == 7.5f);  // clamped to the last level
  // Bilinear at (0.125, 0.125): level 0 is texel 0's centre (0); on level 1 both taps clamp to
  // texel 0 (2.5); level 2 is 7.5. No blending between levels.
  const Sampler b = sampler(Filter::bilinear);
  const glm::vec2 corner(0.125f, 0.125f);
  CHECK(t.sample_level(b, corner, 0.4f).x == 0.0f);
  CHECK(t.sample_level(b, corner, 0.6f).x == 2.5f);
  CHECK(t.sample_level(b, corner, 1.4f).x == 2.5f);
  CHECK(t.sample_level(b, corner, 1.6f).x == 7.5f);
  // Halfway between level 1's texels 0 and 1 (2.5, 4.5) on their row.
  CHECK(t.sample_level(b, {0.5f, 0.25f}, 1.0f).x == 3.5f);
}

TEST_CASE("texture: trilinear blends floor(lod) and floor(lod) + 1 by frac(lod)", "[texture]") {
  const Texture2D t = ramp4x4();
  const Sampler s = sampler(Filter::trilinear);  // clamp: at uv (0.125, 0.125) level 0 -> 0,
  const glm::vec2 uv(0.125f, 0.125f);            // level 1 -> 2.5 (both taps clamp to 0), level 2 -> 7.5
  CHECK(t.sample_level(s, uv, 0.0f).x == 0.0f);
  CHECK(t.sample_level(s, uv, 0.5f).x == 1.25f);    // 0 * 0.5 + 2.5 * 0.5
  CHECK(t.sample_level(s, uv, 0.25f).x == 0.625f);  // 0 * 0.75 + 2.5 * 0.25
  CHECK(t.sample_level(s, uv, 1.0f).x == 2.5f);
  CHECK(t.sample_level(s, uv, 1.5f).x == 5.0f);  // 2.5 * 0.5 + 7.5 * 0.5
  CHECK(t.sample_level(s, uv, 1.75f).x == 6.25f);
  CHECK(t.sample_level(s, uv, 2.0f).x == 7.5f);
  CHECK(t.sample_level(s, uv, 9.0f).x == 7.5f);
  CHECK(t.sample_level(s, uv, -1.0f).x == 0.0f);  // magnification: level 0, bilinear
  CHECK(t.sample_level(s, uv, 0.5f).w == 1.0f);   // the default alpha survives the blend exactly
}

TEST_CASE("texture: lod is clamped by min_lod and max_lod after the bias", "[texture]") {
  const Texture2D t = ramp4x4();
  const glm::vec2 uv(0.1f, 0.1f);  // point: level 0 -> 0, level 1 -> 2.5, level 2 -> 7.5
  Sampler s = sampler(Filter::point);
  s.min_lod = 1.0f;
  CHECK(t.sample_level(s, uv, 0.0f).x == 2.5f);
  CHECK(t.sample_level(s, uv, std::numeric_limits<float>::quiet_NaN()).x == 2.5f);  // NaN -> lower bound
  s.min_lod = 0.0f;
  s.max_lod = 1.0f;
  CHECK(t.sample_level(s, uv, 5.0f).x == 2.5f);
  CHECK(t.sample_level(s, uv, std::numeric_limits<float>::infinity()).x == 2.5f);
  s.max_lod = 1000.0f;
  s.mip_lod_bias = 2.0f;
  CHECK(t.sample_level(s, uv, 0.0f).x == 7.5f);
  s.mip_lod_bias = -5.0f;
  CHECK(t.sample_level(s, uv, 2.0f).x == 0.0f);
  s.mip_lod_bias = 0.0f;
  s.min_lod = 2.0f;  // min_lod > max_lod: max_lod wins
  s.max_lod = 1.0f;
  CHECK(t.sample_level(s, uv, 0.0f).x == 2.5f);
  // Trilinear between the clamped bounds.
  Sampler tri = sampler(Filter::trilinear);
  tri.min_lod = 0.5f;
  CHECK(t.sample_level(tri, {0.125f, 0.125f}, 0.0f).x == 1.25f);
  tri.min_lod = 0.0f;
  tri.max_lod = 1.5f;
  CHECK(t.sample_level(tri, {0.125f, 0.125f}, 2.0f).x == 5.0f);
}

TEST_CASE("texture: sample_grad picks the level from derivatives", "[texture]") {
  const Texture2D t = ramp4x4();
  const Sampler s = sampler(Filter::point);
  const glm::vec2 uv(0.1f, 0.1f);
  // |ddx * size| = 4 texels per pixel -> lod 2.
  CHECK(t.sample_grad(s, uv, {4.0f / 4.0f, 0.0f}, {0.0f, 0.0f}).x == 7.5f);
  CHECK(t.sample_grad(s, uv, {2.0f / 4.0f, 0.0f}, {0.0f, 0.0f}).x == 2.5f);  // lod 1
  CHECK(t.sample_grad(s, uv, {0.25f, 0.0f}, {0.0f, 1.0f}).x == 7.5f);        // the larger (ddy) wins
  CHECK(t.sample_grad(s, uv, {0.0f, 0.0f}, {0.0f, 0.0f}).x == 0.0f);         // lod -inf -> 0
  CHECK(t.sample_grad(s, uv, {0.25f, 0.0f}, {0.0f, 0.25f}).x == 0.0f);       // one texel per pixel -> lod 0
  // A diagonal derivative of (1, 1) texels has length sqrt(2): lod 0.5, blended by trilinear.
  CHECK(t.sample_grad(sampler(Filter::trilinear), {0.125f, 0.125f}, {0.25f, 0.25f}, {0.0f, 0.0f}).x == 1.25f);
  // The bias applies on top of the derivative lod.
  Sampler biased = s;
  biased.mip_lod_bias = 1.0f;
  CHECK(t.sample_grad(biased, uv, {0.25f, 0.0f}, {0.0f, 0.0f}).x == 2.5f);

  // Non-square: 8x2 scales u derivatives by 8 and v derivatives by 2.
  std::vector<float> v(16);
  for (int i = 0; i < 16; ++i) v[static_cast<std::size_t>(i)] = static_cast<float>(i);
  const Texture2D wide = make(8, 2, 1, std::move(v));  // 8x2 -> 4x1 -> 2x1 -> 1x1
  REQUIRE(wide.levels() == 4);
  const float level1 = wide.load(1, 0, 0).x;  // (0 + 1 + 8 + 9) / 4 = 4.5
  CHECK(level1 == 4.5f);
  CHECK(wide.sample_grad(s, {0.01f, 0.1f}, {0.0f, 0.5f}, {0.0f, 0.0f}).x == 0.0f);     // 1 texel -> lod 0
  CHECK(wide.sample_grad(s, {0.01f, 0.1f}, {0.25f, 0.0f}, {0.0f, 0.0f}).x == level1);  // 2 texels -> lod 1
}

TEST_CASE("texture: RGBA sampling and defaults for missing channels", "[texture]") {
  const Texture2D rgba = make(2, 1, 4, {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f}, false);
  CHECK(rgba.load(0, 1, 0) == glm::vec4(5.0f, 6.0f, 7.0f, 8.0f));
  CHECK(rgba.sample_level(sampler(Filter::bilinear), {0.5f, 0.5f}, 0.0f) == glm::vec4(3.0f, 4.0f, 5.0f, 6.0f));
  CHECK(rgba.sample_level(sampler(Filter::point), {0.9f, 0.5f}, 0.0f) == glm::vec4(5.0f, 6.0f, 7.0f, 8.0f));
  // x = 0.375 * 2 - 0.5 = 0.25: 0.75 * texel 0 + 0.25 * texel 1, per channel.
  CHECK(rgba.sample_level(sampler(Filter::bilinear), {0.375f, 0.5f}, 0.0f) == glm::vec4(2.0f, 3.0f, 4.0f, 5.0f));
  const Texture2D rgba_mips = make(2, 1, 4, {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f});
  CHECK(rgba_mips.load(1, 0, 0) == glm::vec4(3.0f, 4.0f, 5.0f, 6.0f));
  CHECK(rgba_mips.sample_level(sampler(Filter::trilinear), {0.25f, 0.5f}, 0.5f) ==
        glm::vec4(2.0f, 3.0f, 4.0f, 5.0f));  // (texel 0 + level 1) / 2

  const Texture2D r = make(1, 1, 1, {0.5f});
  const Texture2D rg = make(1, 1, 2, {0.5f, 0.25f});
  const Texture2D rgb = make(1, 1, 3, {0.5f, 0.25f, 0.125f});
  CHECK(r.load(0, 0, 0) == glm::vec4(0.5f, 0.0f, 0.0f, 1.0f));
  CHECK(rg.load(0, 0, 0) == glm::vec4(0.5f, 0.25f, 0.0f, 1.0f));
  CHECK(rgb.load(0, 0, 0) == glm::vec4(0.5f, 0.25f, 0.125f, 1.0f));
  for (Filter f : {Filter::point, Filter::bilinear, Filter::trilinear}) {
    INFO(to_string(f));
    CHECK(r.sample_level(sampler(f), {0.3f, 0.6f}, 0.0f) == glm::vec4(0.5f, 0.0f, 0.0f, 1.0f));
    CHECK(rg.sample_level(sampler(f), {0.3f, 0.6f}, 0.0f) == glm::vec4(0.5f, 0.25f, 0.0f, 1.0f));
    CHECK(rgb.sample_level(sampler(f), {0.3f, 0.6f}, 0.0f) == glm::vec4(0.5f, 0.25f, 0.125f, 1.0f));
  }
  // Load outside the level or outside the chain reads zero, as D3D's ld does.
  CHECK(rgba.load(0, 2, 0) == glm::vec4(0.0f));
  CHECK(rgba.load(0, 0, -1) == glm::vec4(0.0f));
  CHECK(rgba.load(1, 0, 0) == glm::vec4(0.0f));
  CHECK(r.load(-1, 0, 0) == glm::vec4(0.0f));
}

TEST_CASE("texture: NaN, infinite and huge coordinates stay in range", "[texture]") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // Odd sizes, so wrap and mirror take the division path.
  std::vector<float> v;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 3; ++x) v.push_back(static_cast<float>(10 * y + x));
  const Texture2D t = make(3, 5, 1, std::move(v));
  const float coords[] = {nan, inf, -inf, 1e30f, -1e30f, 3.4e38f, -3.4e38f, 1e9f, -1e9f, 65536.3f, 1e-45f};
  for (Filter f : {Filter::point, Filter::bilinear, Filter::trilinear})
    for (AddressMode m : {AddressMode::wrap, AddressMode::clamp, AddressMode::mirror})
      for (float c : coords) {
        INFO(to_string(f) << " " << to_string(m) << " coordinate " << c);
        const Sampler s = sampler(f, m, m);
        const glm::vec4 a = t.sample_level(s, {c, 0.5f}, 0.0f);
        const glm::vec4 b = t.sample_level(s, {0.5f, c}, 1.3f);
        const glm::vec4 d = t.sample_grad(s, {c, c}, {c, 0.0f}, {0.0f, c});
        CHECK(all_finite(a));
        CHECK(all_finite(b));
        CHECK(all_finite(d));
        // Every result is a convex blend of texels, which lie in [0, 42].
        CHECK(a.x >= 0.0f);
        CHECK(a.x <= 42.0f);
        CHECK(d.x >= 0.0f);
        CHECK(d.x <= 42.0f);
      }
  // Point: a NaN or infinite coordinate is texel-space 0 (column or row 0); a huge finite one clamps
  // to the last column.
  CHECK(t.sample_level(sampler(Filter::point, AddressMode::wrap), {nan, 0.5f}, 0.0f).x == 20.0f);
  CHECK(t.sample_level(sampler(Filter::point, AddressMode::mirror), {0.5f, nan}, 0.0f).x == 1.0f);
  CHECK(t.sample_level(sampler(Filter::point, AddressMode::clamp), {1e30f, 0.5f}, 0.0f).x == 22.0f);
  CHECK(t.sample_level(sampler(Filter::point, AddressMode::clamp), {-inf, 0.5f}, 0.0f).x == 20.0f);
  // u = +-1e30 on a width of 4: 4e30 is a multiple of 4 in float (its ulp is 2^78), so wrap reads
  // texel 0, and bilinear's -0.5 is lost to rounding (frac 0).
  const Texture2D four = make(4, 1, 1, {10.0f, 20.0f, 30.0f, 40.0f}, false);
  CHECK(four.sample_level(sampler(Filter::point, AddressMode::wrap), {1e30f, 0.5f}, 0.0f).x == 10.0f);
  CHECK(four.sample_level(sampler(Filter::bilinear, AddressMode::wrap), {-1e30f, 0.5f}, 0.0f).x == 10.0f);
  CHECK(four.sample_level(sampler(Filter::point, AddressMode::clamp), {-1e30f, 0.5f}, 0.0f).x == 10.0f);
  CHECK(four.sample_level(sampler(Filter::point, AddressMode::clamp), {1e30f, 0.5f}, 0.0f).x == 40.0f);
}

TEST_CASE("texture: filter and address mode names round-trip", "[texture]") {
  for (Filter f : {Filter::point, Filter::bilinear, Filter::trilinear}) CHECK(parse_filter(to_string(f)) == f);
  for (AddressMode m : {AddressMode::wrap, AddressMode::clamp, AddressMode::mirror})
    CHECK(parse_address_mode(to_string(m)) == m);
  CHECK(to_string(Filter::bilinear) == "bilinear");
  CHECK(to_string(AddressMode::mirror) == "mirror");
  CHECK_FALSE(parse_filter("linear").has_value());
  CHECK_FALSE(parse_address_mode("border").has_value());
  CHECK_FALSE(parse_address_mode("").has_value());
}

TEST_CASE("texture: bilinear filtering of 3 and 4 channels gives the bits of the per-channel formula",
          "[texture][simd]") {
  // Each channel must be top * (1 - fv) + bottom * fv with top = t00 * (1 - fu) + t01 * fu (and bottom
  // likewise), in that order: the formula the one-channel lanes (sample_level4) reproduce.
  for (const int channels : {3, 4}) {
    const int w = 37, h = 23;  // odd sizes: the last texel's fourth float lies past a 3-channel level
    std::vector<float> texels(std::size_t(w * h * channels));
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = std::sin(float(i) * 0.71f) * 3.0f;
    const Texture2D t = make(w, h, channels, texels, false);
    std::uint32_t state = 99;
    auto next = [&] {
      state = state * 1664525u + 1013904223u;
      return float(state >> 8) / float(1u << 24);  // [0, 1)
    };
    int compared = 0;
    for (int round = 0; round < 2000; ++round) {
      const glm::vec2 uv(next() * 1.1f - 0.05f, next() * 1.1f - 0.05f);
      const glm::vec4 got = t.sample_level(sampler(Filter::bilinear), uv, 0.0f);
      const float x = uv.x * float(w) - 0.5f, y = uv.y * float(h) - 0.5f;
      const int i = int(std::floor(x)), j = int(std::floor(y));
      const float fu = x - float(i), fv = y - float(j);
      const auto at = [&](int a, int b, int c) {
        return texels[std::size_t(((std::clamp(b, 0, h - 1) * w) + std::clamp(a, 0, w - 1)) * channels + c)];
      };
      for (int c = 0; c < 4; ++c) {
        float expect = 1.0f;
        if (c < channels) {
          const float top = at(i, j, c) * (1.0f - fu) + at(i + 1, j, c) * fu;
          const float bottom = at(i, j + 1, c) * (1.0f - fu) + at(i + 1, j + 1, c) * fu;
          expect = top * (1.0f - fv) + bottom * fv;
        }
        INFO(channels << " channels, uv " << uv.x << ", " << uv.y << " channel " << c);
        CHECK(std::bit_cast<std::uint32_t>(got[c]) == std::bit_cast<std::uint32_t>(expect));
        ++compared;
      }
    }
    CHECK(compared == 8000);
  }
}

TEST_CASE("texture: sample_grad4 gives the bits of four sample_grad calls", "[texture][simd]") {
  // A pixel's four central-difference taps (DisplacedPS): derivatives from zero (lod -inf) to past the
  // last level, and between levels (the trilinear blend), on a one-channel map and a four-channel one.
  std::vector<float> one(128 * 64), four(16 * 16 * 4);
  for (std::size_t i = 0; i < one.size(); ++i) one[i] = std::sin(float(i) * 0.13f);
  for (std::size_t i = 0; i < four.size(); ++i) four[i] = std::cos(float(i) * 0.29f);
  const Texture2D textures[] = {make(128, 64, 1, one), make(16, 16, 4, four)};
  std::uint32_t state = 777;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);  // [0, 1)
  };
  int compared = 0, blended = 0;
  for (const Texture2D& t : textures)
    for (const Filter f : {Filter::bilinear, Filter::trilinear})
      for (int round = 0; round < 300; ++round) {
        const Sampler s = sampler(f, AddressMode::clamp, AddressMode::clamp);
        const float scale = std::ldexp(1.0f, round % 12 - 10);  // 1/1024 .. 2 of the map per pixel
        const glm::vec2 ddx = round % 50 == 0 ? glm::vec2(0.0f) : glm::vec2(next(), next() - 0.5f) * scale;
        const glm::vec2 ddy = glm::vec2(next() - 0.5f, next()) * scale;
        const glm::vec2 uv(next() * 1.2f - 0.1f, next() * 1.2f - 0.1f);
        const float du = 1.0f / float(t.width()), dv = 1.0f / float(t.height());
        const std::array<glm::vec2, 4> taps = {uv + glm::vec2(du, 0.0f), uv - glm::vec2(du, 0.0f),
                                               uv + glm::vec2(0.0f, dv), uv - glm::vec2(0.0f, dv)};
        std::array<glm::vec4, 4> batch;
        t.sample_grad4(s, taps, ddx, ddy, batch);
        const float lod = t.grad_lod(ddx, ddy);
        if (lod > 0.0f && lod < float(t.levels() - 1) && lod != std::floor(lod)) ++blended;
        for (std::size_t k = 0; k < 4; ++k) {
          const glm::vec4 single = t.sample_grad(s, taps[k], ddx, ddy);
          INFO("uv " << taps[k].x << ", " << taps[k].y << " lod " << lod);
          CHECK(std::memcmp(&single, &batch[k], sizeof single) == 0);
          ++compared;
        }
      }
  CHECK(compared == 2 * 2 * 300 * 4);
  CHECK(blended > 100);  // the trilinear lanes' blend was exercised
}

TEST_CASE("texture: sample_level4 gives the bits of four sample_level calls", "[texture][simd]") {
  // Coordinates inside, outside (every addressing mode), on texel edges and non-finite; one and four
  // channels (the SIMD paths and the fallback), each filter.
  std::vector<float> one(64 * 32), four(16 * 8 * 4);
  for (std::size_t i = 0; i < one.size(); ++i) one[i] = std::sin(float(i) * 0.37f);
  for (std::size_t i = 0; i < four.size(); ++i) four[i] = std::cos(float(i) * 0.11f);
  const Texture2D textures[] = {make(64, 32, 1, one), make(16, 8, 4, four)};
  const float specials[] = {0.0f,
                            1.0f,
                            -1.0f,
                            0.5f / 64.0f,
                            3e9f,
                            -3e9f,
                            std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity()};
  std::uint32_t state = 12345;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) * 5.0f - 2.0f;  // [-2, 3)
  };
  int compared = 0;
  for (const Texture2D& t : textures)
    for (const Filter f : {Filter::point, Filter::bilinear, Filter::trilinear})
      for (const AddressMode m : {AddressMode::wrap, AddressMode::clamp, AddressMode::mirror})
        for (const float lod : {0.0f, 0.3f, 1.0f, 1.75f, 2.5f, 40.0f, -1.0f}) {
          const Sampler s = sampler(f, m, m);
          for (int round = 0; round < 40; ++round) {
            std::array<glm::vec2, 4> uv;
            for (std::size_t k = 0; k < 4; ++k) {
              uv[k] = {next(), next()};
              if (round % 5 == 0) uv[k].x = specials[(std::size_t(round) + k) % std::size(specials)];
              // All four lanes inside the texture (nearly always with both taps inside too): the lane
              // path that computes the taps without addressing.
              if (round % 5 == 1 || round % 5 == 2) uv[k] = (uv[k] + 2.0f) / 5.0f;
            }
            std::array<glm::vec4, 4> batch;
            t.sample_level4(s, uv, lod, batch);
            for (std::size_t k = 0; k < 4; ++k) {
              const glm::vec4 single = t.sample_level(s, uv[k], lod);
              INFO("uv " << uv[k].x << ", " << uv[k].y << " lod " << lod);
              CHECK(std::memcmp(&single, &batch[k], sizeof single) == 0);
              ++compared;
            }
          }
        }
  CHECK(compared == 2 * 3 * 3 * 7 * 40 * 4);
}
