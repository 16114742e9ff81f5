// Back-patch culling (shaders_cpp/lod/back_patch_cull.h, pipeline/patch_orientation.h): the pattern
// shape terms, every triangle of a patch proven to face away does face away on screen, and culling
// never changes a pixel -- over shapes, schemes, partitionings and cameras that orbit, graze and
// enter the models.
#include <cmath>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

#include "shaders_cpp/cage/bounding_box.h"
#include "shaders_cpp/debug/debug_render.h"
#include "shaders_cpp/lod/back_patch_cull.h"
#include "shaders_cpp/render/displaced_render.h"
#include "shaders_cpp/render/subd_render.h"
#include "tessellator/pattern_shape.h"
#include "test_data.h"

namespace tessera {
namespace {

const std::string kFrog = test::data("sdk-cages/monsterfrog_mapped_00.obj");
const std::string kFrogMap = test::data("sdk-cages/monsterfrog.dds");

// Cameras around a cage: an orbit at two distances, a grazing one and one inside it.
std::vector<SubdCamera> cameras(const Cage& cage, int w, int h) {
  const Box3 box = bounding_box(cage.positions);
  const glm::vec3 centre = box.centre();
  const float radius = 0.5f * glm::length(box.hi - box.lo);
  std::vector<SubdCamera> out;
  for (int k = 0; k < 4; ++k) {
    const float a = 0.4f + 1.57f * float(k);
    const glm::vec3 dir(std::cos(a), 0.35f * float(k % 3) - 0.3f, std::sin(a));
    const float d = radius * (k % 2 == 0 ? 2.2f : 1.3f);
    out.push_back(frame_cage(cage, w, h, 40.0f, centre + glm::normalize(dir) * d, centre));
  }
  out.push_back(frame_cage(cage, w, h, 50.0f, centre + glm::vec3(0.0f, 0.9f * radius, 0.1f * radius),
                           centre + glm::vec3(radius, 0.0f, 0.0f)));                  // grazing
  out.push_back(frame_cage(cage, w, h, 70.0f, centre, centre + glm::vec3(0, 0, 1)));  // inside
  return out;
}

SubdFactors uniform_factor(float factor) {
  SubdFactors f;
  f.factor = factor;
  return f;
}

PatchCull cull_for(const SubdModel& m, const SubdCamera& camera, int w, int h, bool back) {
  PatchCull c;
  if (back) c.back = BackPatchCull(camera.view_projection, w, h, subd_culled_screen_sign(m));
  return c;
}

}  // namespace

TEST_CASE("Pattern shape: one orientation, the terms of a uniform grid, nothing for other outputs", "[backface]") {
  for (const int k : {1, 2, 5, 16}) {
    ts::Pattern p;
    const float f = float(k);
    ts::tessellate_quad(ts::Partitioning::integer, ts::OutputPrimitive::triangle_cw, ts::QuadFactors{f, f, f, f, f, f},
                        p);
    const ts::PatternShape s = ts::pattern_shape(p);
    INFO("factor " << k);
    REQUIRE(s.consistent);
    CHECK(s.orientation == 1);
    // Legs of 1/k along u and v (in 16.16 fixed point): D = 1/k^2; the best corner is the right
    // angle (cubic 2/k).
    CHECK(s.inverse == Approx(double(k * k)).epsilon(1e-4));
    CHECK(s.cubic == Approx(2.0 / k).epsilon(1e-4));
    CHECK(s.product == Approx(1.0).epsilon(1e-4));
    ts::tessellate_quad(ts::Partitioning::integer, ts::OutputPrimitive::triangle_ccw, ts::QuadFactors{f, f, f, f, f, f},
                        p);
    CHECK(ts::pattern_shape(p).orientation == -1);
  }
  ts::Pattern p;
  ts::tessellate_quad(ts::Partitioning::fractional_odd, ts::OutputPrimitive::triangle_cw,
                      ts::QuadFactors{3.01f, 7.5f, 1.0f, 20.0f, 4.2f, 9.9f}, p);
  const ts::PatternShape s = ts::pattern_shape(p);
  CHECK(s.consistent);
  CHECK(s.cubic > 0.0);  // transition rings: skinnier triangles than the grid's
  ts::tessellate_quad(ts::Partitioning::integer, ts::OutputPrimitive::point, ts::QuadFactors{4, 4, 4, 4, 4, 4}, p);
  CHECK_FALSE(ts::pattern_shape(p).consistent);
  CHECK(max_edge_segments(1.0f) >= 2);
  CHECK(max_edge_segments(7.2f) >= 9);  // fractional_odd: 9 segments
  CHECK(max_edge_segments(64.0f) == 64);
  CHECK(max_edge_segments(NAN) == 64);
}

TEST_CASE("Every triangle of a patch proven to face away faces away on screen", "[backface]") {
  Device device(DeviceOptions{});
  const int w = 320, h = 240;
  std::uint64_t proven = 0, triangles = 0, wrong = 0;
  for (const auto& [path, scheme] : {std::pair{kFrog, Scheme::acc}, std::pair{kFrog, Scheme::bspline},
                                     std::pair{test::data("osd-shapes/catmark_car.obj"), Scheme::acc},
                                     std::pair{test::data("osd-shapes/bilinear_nonplanar.obj"), Scheme::flat}}) {
    const SubdModel m = load_subd_model(path, scheme);
    const int culled_sign = subd_culled_screen_sign(m);
    const std::vector<SubdCamera> views = cameras(m.cage, w, h);
    for (std::size_t vi = 0; vi < views.size(); ++vi) {
      const SubdCamera& camera = views[vi];
      if (test::kSanitized && vi % 2 == 0) continue;  // half the cameras, the inside one among them (test_data.h)
      for (const auto partitioning : {ts::Partitioning::integer, ts::Partitioning::fractional_odd}) {
        for (const float factor : {3.0f, 9.5f, 40.0f}) {
          if (test::kSanitized && factor > 10.0f) continue;
          const SubdFactors f = uniform_factor(factor);
          const PatchCull cull = cull_for(m, camera, w, h, true);
          const PatchTables tables =
              build_patch_tables(m, nullptr, f, cull, partitioning, DicingCamera{camera.eye, 1.0f});
          const DrawResult r = stream_subd(device, m, f, cull, partitioning, [&](const auto& out, const PatchGroup& g) {
            if (!tables.of(g.domain)[out.patch_id].faces_away) return;
            ++proven;
            // Window-space orientation (y down, clockwise positive) of each triangle, in double from
            // the float clip positions the rasterizer would get.
            for (std::size_t i = 0; i + 2 < out.indices.size(); i += 3) {
              glm::dvec2 s[3];
              for (int k = 0; k < 3; ++k) {
                const glm::vec4 c =
                    clip_position(camera.view_projection, 0.0f, out.points[out.indices[i + std::size_t(k)]].position);
                s[k] = glm::dvec2(double(c.x) / double(c.w), -double(c.y) / double(c.w));
              }
              const double area = (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
              ++triangles;
              if ((area > 0 ? 1 : area < 0 ? -1 : 0) != culled_sign) ++wrong;
            }
          });
          REQUIRE(r.ok());
        }
      }
    }
  }
  CHECK(wrong == 0);
  CHECK(proven > 100);
  CHECK(triangles > 10000);
}

TEST_CASE("Back-patch culling never changes a pixel: shapes, schemes, views, cameras through the model", "[backface]") {
  Device device(DeviceOptions{});
  const int w = 240, h = 180;
  std::uint64_t skipped = 0;
  for (const auto& [path, scheme] :
       {std::pair{kFrog, Scheme::acc}, std::pair{kFrog, Scheme::gregory}, std::pair{kFrog, Scheme::pn},
        std::pair{test::data("osd-shapes/catmark_car.obj"), Scheme::bspline},
        std::pair{test::data("osd-shapes/bilinear_nonplanar.obj"), Scheme::flat}}) {
    const SubdModel m = load_subd_model(path, scheme);
    const std::vector<SubdCamera> views = cameras(m.cage, w, h);
    for (std::size_t vi = 0; vi < views.size(); ++vi) {
      const SubdCamera& camera = views[vi];
      if (test::kSanitized && vi % 2 == 0) continue;  // half the cameras, the inside one among them (test_data.h)
      for (const SubdView view : {SubdView::shaded, SubdView::wire_on_shaded}) {
        for (const float factor : {4.0f, 17.3f}) {
          if (test::kSanitized && factor > 10.0f) continue;
          auto image = [&](bool back, std::uint64_t& away) {
            auto fb = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, nullptr);
            REQUIRE(fb);
            fb->clear(glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), 1.0f);
            const DrawResult r = render_subd(device, m, uniform_factor(factor), cull_for(m, camera, w, h, back),
                                             ts::Partitioning::fractional_odd, view, camera, *fb);
            REQUIRE(r.ok());
            away = r.report.patches_back_culled;
            return fb->color_bytes();
          };
          std::uint64_t away = 0, none = 0;
          const auto with = image(true, away);
          const auto without = image(false, none);
          INFO(path << " " << to_string(scheme) << " eye " << camera.eye.x << "," << camera.eye.y << "," << camera.eye.z
                    << " view " << int(view) << " factor " << factor);
          CHECK(none == 0);
          CHECK(with == without);
          skipped += away;
        }
      }
    }
  }
  CHECK(skipped > 200);
}

TEST_CASE("Displaced patches make no orientation claim, the left-handed rule follows the rasterizer", "[backface]") {
  const SubdModel m = load_subd_model(kFrog, Scheme::acc);
  const Displacement d = make_displacement(
      m, DisplacementOptions{.map = kFrogMap, .channel = std::string("A"), .scale = 1.2f, .bias = -0.6f});
  Device device(DeviceOptions{});
  const int w = 240, h = 180;
  const SubdCamera camera = frame_cage(m.cage, w, h, 35.0f, std::nullopt, std::nullopt);
  const SubdFactors f = uniform_factor(12.0f);
  const PatchCull cull = cull_for(m, camera, w, h, true);
  auto fb = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, nullptr);
  REQUIRE(fb);
  const DrawResult displaced =
      render_displaced(device, m, d, f, cull, ts::Partitioning::integer, SubdView::shaded, camera, *fb);
  REQUIRE(displaced.ok());
  CHECK(displaced.report.patches_back_culled == 0);
  const DrawResult plain = render_subd(device, m, f, cull, ts::Partitioning::integer, SubdView::shaded, camera, *fb);
  REQUIRE(plain.ok());
  CHECK(plain.report.patches_back_culled > 0);
  // A right-handed cage culls back faces: clockwise on screen with front_counter_clockwise.
  CHECK(subd_culled_screen_sign(m) == 1);
  CHECK_FALSE(BackPatchCull().enabled());
  CHECK_FALSE(BackPatchCull(glm::mat4(0.0f), w, h, 1).enabled());  // singular projection
}

TEST_CASE("bench frog --compare-cull times each mode, with the same image, --cull names its modes", "[backface][cli]") {
  const auto r = test::run_cli(
      "bench frog --scheme acc --factor 12 --resolution 320x180 --frames 1 --json --compare-cull "
      "--camera-position 20,5,12 --camera-target -3,-2.5,2");
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  const auto& modes = j["cull_modes"];
  REQUIRE(modes.size() == 4);
  for (const auto& m : modes) CHECK(m["same_image"] == true);
  CHECK(modes[0]["cull"] == "none");
  CHECK(modes[0]["patches_culled"] == 0);
  CHECK(modes[0]["patches_back_culled"] == 0);
  CHECK(modes[1]["patches_culled"].get<int>() > 0);
  CHECK(modes[1]["patches_back_culled"] == 0);
  CHECK(modes[2]["patches_culled"] == 0);
  CHECK(modes[2]["patches_back_culled"].get<int>() > 0);
  CHECK(modes[3]["patches_culled"] == modes[1]["patches_culled"]);
  CHECK(modes[3]["triangles"].get<long>() < modes[1]["triangles"].get<long>());
  const auto bad = test::run_cli("bench frog --cull sideways --frames 1 --resolution 64x64");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("--cull: 'sideways' is not none, frustum, backface or all") != std::string::npos);
}

}  // namespace tessera
