// View-dependent LOD and frustum patch culling (shaders_cpp/lod): the factor rules, watertightness
// under view-dependent factors (welded on exact bits), and culling that never changes a pixel.
#include <bit>
#include <cmath>

#include <catch2/catch.hpp>

#include "shaders_cpp/cage/bounding_box.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/lod/edge_lod.h"
#include "shaders_cpp/lod/frustum_cull.h"
#include "shaders_cpp/lod/subd_factors.h"
#include "shaders_cpp/render/displaced_render.h"
#include "shaders_cpp/render/subd_render.h"
#include "test_data.h"
#include "weld_support.h"

namespace tessera {
namespace {

const std::string kFrog = test::data("sdk-cages/monsterfrog_mapped_00.obj");
const std::string kFrogMap = test::data("sdk-cages/monsterfrog.dds");

LodSettings screen_lod(glm::vec3 eye, float edge_pixels = 8.0f, float bound = 0.0f) {
  LodSettings s;
  s.mode = LodMode::screen;
  s.edge_pixels = edge_pixels;
  s.bound = bound;
  s.camera.eye = eye;
  s.camera.pixels_per_unit = pixels_per_unit(1080, 35.0f);
  return s;
}

// The camera of an inside-the-frog view: it cuts through the surface, so patches lie behind, beside
// and in front of it.
SubdCamera near_camera(const Cage& cage, int w, int h) {
  return frame_cage(cage, w, h, 35.0f, glm::vec3(20, 5, 12), glm::vec3(-3, -2.5f, 2));
}

template <class Stream>
verify::WeldReport weld(Stream&& stream) {
  verify::WeldChecker w;
  const DrawResult r = stream([&](const auto& out, const PatchGroup&) { verify::add_patch_triangles(w, out); });
  REQUIRE(r.ok());
  return w.report();
}

}  // namespace

TEST_CASE("Edge LOD: symmetric in the end points, clamped to [1, 64], falling with distance", "[lod]") {
  const glm::vec3 a(0.1f, 0.7f, -0.3f), b(1.3f, -0.2f, 0.45f);
  for (const LodMode mode : {LodMode::distance, LodMode::screen}) {
    LodSettings s = screen_lod(glm::vec3(3, 2, 9));
    s.mode = mode;
    s.factor = 12.0f;
    s.lod_distance = 5.0f;
    const float f = edge_lod_factor(a, b, s);
    CHECK(std::bit_cast<std::uint32_t>(f) == std::bit_cast<std::uint32_t>(edge_lod_factor(b, a, s)));
    CHECK(f >= 1.0f);
    CHECK(f <= 64.0f);
    // Twice as far: half the factor (distance is 1/d; screen 1/sqrt(d^2 - r^2), about 1/d for r << d).
    const glm::vec3 mid = 0.5f * (a + b);
    LodSettings far = s;
    far.camera.eye = mid + 2.0f * (s.camera.eye - mid);
    CHECK(edge_lod_factor(a, b, far) == Approx(f / 2.0f).epsilon(mode == LodMode::screen ? 1e-2 : 1e-5));
    // Very far: 1; inside the sphere or at the midpoint: 64.
    far.camera.eye = mid + 1e6f * (s.camera.eye - mid);
    CHECK(edge_lod_factor(a, b, far) == 1.0f);
    far.camera.eye = mid;
    CHECK(edge_lod_factor(a, b, far) == 64.0f);
  }
  // Screen: the sphere's projected diameter over the target pixels; a displacement bound grows it.
  LodSettings s = screen_lod(glm::vec3(0, 0, 40), 4.0f);
  const glm::vec3 p0(-1, 0, 0), p1(1, 0, 0);
  CHECK(edge_lod_factor(p0, p1, s) == Approx(2.0 * s.camera.pixels_per_unit / std::sqrt(1600.0 - 1.0) / 4.0));
  s.bound = 0.5f;
  CHECK(edge_lod_factor(p0, p1, s) == Approx(3.0 * s.camera.pixels_per_unit / std::sqrt(1600.0 - 2.25) / 4.0));
  // Continuous into the sphere: just outside it the factor is already 64.
  s.camera.eye = glm::vec3(0, 0, 1.5001f);
  CHECK(edge_lod_factor(p0, p1, s) == 64.0f);
  CHECK(parse_lod_mode("screen") == LodMode::screen);
  CHECK_FALSE(parse_lod_mode("bogus"));
}

TEST_CASE("Screen LOD keeps the frog watertight on exact bits: every scheme, partitioning and camera", "[lod]") {
  Device device(DeviceOptions{});
  const std::array<glm::vec3, 2> eyes = {glm::vec3(20, 5, 12), glm::vec3(120, 40, 170)};
  for (const Scheme scheme : {Scheme::gregory, Scheme::exact, Scheme::pn, Scheme::flat}) {
    const SubdModel m = load_subd_model(kFrog, scheme);
    for (const glm::vec3 eye : eyes)
      for (const auto p : {ts::Partitioning::integer, ts::Partitioning::pow2, ts::Partitioning::fractional_odd,
                           ts::Partitioning::fractional_even}) {
        // Sanitized: the near eye, one integer and one fractional spacing (test_data.h; the same code paths).
        if (test::kSanitized &&
            (eye != eyes[0] || p == ts::Partitioning::pow2 || p == ts::Partitioning::fractional_even))
          continue;
        INFO(to_string(scheme) << " " << ts::to_string(p) << " eye " << eye.x);
        SubdFactors f;
        f.per_edge = edge_lod_factors(m.positions(), *m.topology, screen_lod(eye, 16.0f));
        const auto r = weld([&](auto&& sink) { return stream_subd(device, m, f, p, sink); });
        CHECK(r.closed_manifold());
        CHECK(r.open_edges == 0);
        CHECK(r.nonmanifold_edges == 0);
      }
  }
  // Displaced, with the map's bound in the spheres.
  for (const Scheme scheme : {Scheme::acc, Scheme::exact}) {
    const SubdModel m = load_subd_model(kFrog, scheme);
    Displacement d = make_displacement(
        m, DisplacementOptions{.map = kFrogMap, .channel = std::string("A"), .scale = 1.2f, .bias = -0.6f});
    // |1.2 a - 0.6| is at most 0.6; the frog's alpha spans most of [0, 1].
    CHECK(d.bound > 0.5f);
    CHECK(d.bound <= 0.6f);
    SubdFactors f;
    f.per_edge = edge_lod_factors(m.positions(), *m.topology, screen_lod(eyes[0], 16.0f, d.bound));
    d.trilinear = true;  // as the CLI samples under view-dependent LOD
    const auto r =
        weld([&](auto&& sink) { return stream_displaced(device, m, d, f, ts::Partitioning::fractional_odd, sink); });
    CHECK(r.closed_manifold());
  }
}

TEST_CASE("fractional_odd inside factors near 1 are lifted so no ring lands on, or folds along, the patch edges",
          "[lod]") {
  // Edge factors at 1 and barely above it (as screen LOD makes them where it clamps) average to inside
  // factors within 2^-16 of 1; without the raise these weld open.
  const SubdModel m = load_subd_model(test::data("osd-shapes/catmark_cube.obj"), Scheme::gregory);
  Device device(DeviceOptions{});
  const std::array<float, 6> near_one = {1.0f, 1.0f + 0x1p-23f, 1.0f + 0x1p-17f, 1.0f + 0x1p-14f, 1.0f + 0x1p-11f,
                                         1.5f};
  int runs = 0;
  for (std::size_t seed = 0; seed < 36; ++seed) {
    auto table = std::make_shared<EdgeFactorTable>();
    int e = 0;
    for (int h = 0; h < m.topology->half_edge_count(); ++h) {
      const std::int64_t key = cage_edge_key(m.topology->origin(h), m.topology->destination(h));
      if (!table->contains(key)) (*table)[key] = near_one[(seed * 7 + std::size_t(e++) * (seed + 1)) % 6];
    }
    SubdFactors f;
    f.per_edge = table;
    for (const auto p : {ts::Partitioning::fractional_odd, ts::Partitioning::fractional_even}) {
      const auto r = weld([&](auto&& sink) { return stream_subd(device, m, f, p, sink); });
      INFO("seed " << seed << " " << ts::to_string(p));
      CHECK(r.closed_manifold());
      ++runs;
    }
  }
  auto lifted = [](float a, float b) {
    TessFactors f;
    f.inside = {a, b};
    SubdHS::lift_inside_factors(f);
    return f.inside;
  };
  CHECK(lifted(1.0f + 0x1p-20f, 3.0f) == std::array<float, 2>{1.0f + 0x1p-10f, 3.0f});
  CHECK(lifted(1.0f, 1.0f + 0x1p-8f) == std::array<float, 2>{1.0f + 0x1p-10f, 1.0f + 0x1p-8f});
  CHECK(lifted(1.0f, 1.0f) == std::array<float, 2>{1.0f, 1.0f});
  CHECK(lifted(3.25f, 0.5f) == std::array<float, 2>{3.25f, 0.5f});
  CHECK(runs == 72);
}

TEST_CASE("Frustum culling removes patches and never changes a pixel, displaced, with cameras inside the frog",
          "[lod]") {
  Device device(DeviceOptions{});
  const int w = 320, h = 180;
  for (const Scheme scheme : {Scheme::gregory, Scheme::exact}) {
    const SubdModel m = load_subd_model(kFrog, scheme);
    const Displacement d = make_displacement(
        m, DisplacementOptions{.map = kFrogMap, .channel = std::string("A"), .scale = 1.2f, .bias = -0.6f});
    for (const SubdCamera& camera :
         {near_camera(m.cage, w, h),
          frame_cage(m.cage, w, h, 35.0f, glm::vec3(2, 1, 30), glm::vec3(2, 1, -10)),  // from inside, looking through
          frame_cage(m.cage, w, h, 60.0f, glm::vec3(-25, 3, -4), glm::vec3(-10, 0, 0))}) {
      for (const SubdView view : {SubdView::shaded, SubdView::wire_on_shaded}) {
        auto image = [&](bool cull, std::uint64_t& culled) {
          auto fb = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, nullptr);
          REQUIRE(fb);
          fb->clear(glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), 1.0f);
          SubdFactors f;
          f.factor = 5.0f;
          PatchCull c;
          c.frustum.enabled = cull;
          c.frustum.view_projection = camera.view_projection;
          c.frustum.growth = d.bound;
          const DrawResult r =
              render_displaced(device, m, d, f, c, ts::Partitioning::fractional_odd, view, camera, *fb);
          REQUIRE(r.ok());
          culled = r.report.patches_culled;
          return fb->color_bytes();
        };
        std::uint64_t culled = 0, none = 0;
        const auto with = image(true, culled);
        const auto without = image(false, none);
        INFO(to_string(scheme) << " eye " << camera.eye.x << " view " << int(view));
        CHECK(none == 0);
        CHECK(culled > 0);
        CHECK(with == without);
      }
    }
  }
}

TEST_CASE("FrustumCull tests the hull grown by the bound against each clip plane", "[lod]") {
  FrustumCull c;
  c.enabled = true;  // identity: the clip volume is -1 <= x, y <= 1, 0 <= z <= 1
  const std::array<glm::vec3, 2> right = {glm::vec3(1.5f, 0, 0.5f), glm::vec3(2.0f, 0.3f, 0.2f)};
  auto at = [&](const auto& pts) { return [&pts](int i) { return pts[std::size_t(i)]; }; };
  CHECK(c.outside(2, at(right)));
  c.growth = 0.6f;  // now the grown hull reaches x = 0.9
  CHECK_FALSE(c.outside(2, at(right)));
  c.growth = 0.0f;
  const std::array<glm::vec3, 2> straddling = {glm::vec3(1.5f, 0, 0.5f), glm::vec3(-3.0f, 0, 0.5f)};
  CHECK_FALSE(c.outside(2, at(straddling)));
  const std::array<glm::vec3, 1> behind = {glm::vec3(0, 0, -0.5f)};
  CHECK(c.outside(1, at(behind)));
  c.enabled = false;
  CHECK_FALSE(c.outside(2, at(right)));
}

}  // namespace tessera

namespace tessera {

TEST_CASE("factor policy: ranges and view-dependent LOD's exclusions are FactorSettingErrors naming the option",
          "[lod]") {
  CHECK(base_factors(8.0f, 0.0f).factor == 8.0f);
  CHECK(base_factors(64.0f, 63.0f).vary == 63.0f);
  CHECK_THROWS_WITH(base_factors(0.0f, 0.0f), "--factor: 0 is not in (0, 64]");
  CHECK_THROWS_WITH(base_factors(NAN, 0.0f), "--factor: nan is not in (0, 64]");
  CHECK_THROWS_WITH(base_factors(64.5f, 0.0f), "--factor: 64.5 is not in (0, 64]");
  CHECK_THROWS_AS(base_factors(8.0f, -1.0f), FactorSettingError);
  CHECK_THROWS_AS(base_factors(8.0f, INFINITY), FactorSettingError);

  const Cage cage = load_obj_cage(kFrog);
  const Topology topology(cage);
  const LodView view{glm::vec3(0, 0, 60), glm::vec3(0.0f), glm::mat4(1.0f), 640, 360, 35.0f};
  const LodModel model{cage.positions, topology, 1, 0.0f, false};
  SubdFactors f = base_factors(8.0f, 0.0f);
  LodRequest screen{LodMode::screen, PatchCullMode::none, 8.0f, 0.0f, std::nullopt};
  PatchCull c;
  const LodSettings s = apply_lod(screen, view, model, f, c);
  CHECK(s.mode == LodMode::screen);
  REQUIRE(f.per_edge);
  CHECK(f.per_edge->size() > 0);
  CHECK_FALSE(c.frustum.enabled);
  CHECK_FALSE(c.back.enabled());

  SubdFactors varied = base_factors(8.0f, 1.0f);
  CHECK_THROWS_WITH(apply_lod(screen, view, model, varied, c),
                    "--lod screen sets every edge's factor: drop --factors-per-edge and --vary-factors");
  LodRequest uniform{LodMode::uniform, PatchCullMode::all, 6.0f, 0.0f, std::nullopt};
  SubdFactors u = base_factors(8.0f, 0.0f);
  CHECK_THROWS_AS(apply_lod(uniform, view, model, u, c), FactorSettingError);
  uniform.edge_pixels = 8.0f;
  CHECK(apply_lod(uniform, view, model, u, c).mode == LodMode::uniform);
  CHECK_FALSE(u.per_edge);
  CHECK(c.frustum.enabled);  // --cull all: the frustum test, and the back-patch test of an undisplaced model
  LodRequest bad{LodMode::screen, PatchCullMode::none, 0.1f, 0.0f, std::nullopt};
  CHECK_THROWS_WITH(apply_lod(bad, view, model, u, c), "--edge-pixels: 0.1 is not in [0.25, 4096]");
}

TEST_CASE("bounding boxes: empty until extended, glm::min and max of the points in order", "[lod]") {
  const Box3 empty = bounding_box({});
  CHECK(empty.lo.x == INFINITY);
  CHECK(empty.hi.x == -INFINITY);
  const std::vector<glm::vec3> points = {{1, -2, 3}, {-4, 5, 0.5f}, {2, 2, 2}};
  const Box3 b = bounding_box(points);
  CHECK(b.lo == glm::vec3(-4, -2, 0.5f));
  CHECK(b.hi == glm::vec3(2, 5, 3));
  CHECK(b.corner(0) == b.lo);
  CHECK(b.corner(7) == b.hi);
  CHECK(b.corner(1) == glm::vec3(2, -2, 0.5f));
  CHECK(b.centre() == glm::vec3(-1, 1.5f, 1.75f));
}

}  // namespace tessera
