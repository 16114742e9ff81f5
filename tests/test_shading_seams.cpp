// Shading across UV seams: in a render of the displaced frog, the colour step between two
// neighbouring pixels of two faces that meet on a UV seam is measured against the step between pixels
// of two faces that meet on an ordinary edge. A seam the asset does not have shows as a larger step.
// Measured in levels of 255, as the mean excess of the step across an edge over the steps beside it:
// with chart padding, own-chart shading and seam blending (displaced_model.h) the seams are within 2
// levels of ordinary edges (auto 3.4 against 2.0, derived 1.9 against 0.7); without, 11.4 against
// 2.0 and 5.6 against 0.8.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <catch2/catch.hpp>

#include "cli_runner.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/render/displaced_model.h"
#include "shaders_cpp/render/displaced_render.h"
#include "test_data.h"

namespace tessera {
namespace {

// The patch under each pixel: its index + 1 in the colour's first three bytes (0: background).
struct PatchIdPS {
  glm::vec4 operator()(const PixelInput<kDisplacedAttributes>& in) const {
    const std::uint32_t id = in.primitive_id + 1;
    return glm::vec4(float(id & 255u), float((id >> 8) & 255u), float((id >> 16) & 255u), 255.0f) / 255.0f;
  }
};

struct SeamSteps {
  // The mean excess of the colour step across an edge (max over RGB, 0..255) over the larger of the
  // steps beside it.
  double seam = 0, ordinary = 0;
  std::size_t seam_pairs = 0, ordinary_pairs = 0;
};

SeamSteps measure(const std::string& normal_map, bool fixed) {
  const Scheme scheme = Scheme::gregory;
  SubdModel model = load_subd_model(test::data("sdk-cages/monsterfrog_mapped_00.obj"), scheme);
  DisplacementOptions o;
  o.map = test::data("sdk-cages/monsterfrog.dds");
  o.channel.assign(1, 'A');  // (assigning a literal trips GCC 12's -Wrestrict false positive here)
  o.normal_map = normal_map;
  o.own_chart_shading = o.pad_charts = o.seam_blending = fixed;
  const Displacement d = make_displacement(model, o);
  SubdFactors factors;
  factors.factor = 12.0f;
  const int w = 640, h = 480;
  const SubdCamera camera = frame_cage(model.cage, w, h, 35.0f, std::nullopt, std::nullopt);
  Device device(DeviceOptions{2});
  std::string error;
  auto shaded = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error);
  auto ids = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error);
  shaded->clear(glm::vec4(0, 0, 0, 1), 1.0f);
  ids->clear(glm::vec4(0, 0, 0, 0), 1.0f);
  REQUIRE(
      render_displaced(device, model, d, factors, PatchCull{}, ts::Partitioning::integer, SubdView::shaded, camera, *shaded).ok());
  const DrawResult r = with_displaced_group(
      model, d, factors, PatchCull{}, ts::Partitioning::integer,
      [&](const PatchGroup& g, const TessellatorState& ts, const DisplacedHS& hs, const DisplacedDS& ds) {
        const SubdPassState st = subd_pass_state(model, *ids, false);
        const DisplacedProjectDS<DisplacedDS> project{ds, camera.view_projection, 0.0f};
        return draw_group_pass(device, model, g, ts, hs, project, PatchIdPS{}, st, *ids);
      });
  REQUIRE(r.ok());

  // Faces meeting on each cage edge, and whether the edge is a UV seam.
  const Topology& t = *model.topology;
  const std::vector<bool> seams = uv_seam_edges(model.cage, t);
  std::map<std::pair<int, int>, bool> edge_between;
  for (int e = 0; e < t.edge_count(); ++e) {
    if (t.is_boundary_edge(e)) continue;
    const auto he = t.edge_half_edges(e);
    int a = t.face(he[0]), b = t.face(he[1]);
    if (a > b) std::swap(a, b);
    edge_between[{a, b}] = seams[std::size_t(e)];
  }
  const auto& patches = model.patches.quads.patches;
  const auto face_at = [&](int x, int y) {
    const auto& c = ids->color_bytes();
    const std::size_t i = (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4;
    const std::uint32_t id = c[i] | (std::uint32_t(c[i + 1]) << 8) | (std::uint32_t(c[i + 2]) << 16);
    return id == 0 ? -1 : patches[id - 1].face;
  };
  const auto step = [&](int x0, int y0, int x1, int y1) {
    const auto& c = shaded->color_bytes();
    const std::size_t i = (std::size_t(y0) * std::size_t(w) + std::size_t(x0)) * 4;
    const std::size_t j = (std::size_t(y1) * std::size_t(w) + std::size_t(x1)) * 4;
    int m = 0;
    for (int k = 0; k < 3; ++k) m = std::max(m, std::abs(int(c[i + std::size_t(k)]) - int(c[j + std::size_t(k)])));
    return m;
  };
  // A pair (x, y) -> (x + dx, y + dy) crossing from face a to face b is held against its two neighbouring
  // pairs in the same direction, each inside one face: a discontinuity is a step larger than the
  // shading's own gradient beside it.
  SeamSteps s;
  for (int y = 1; y + 2 < h; ++y)
    for (int x = 1; x + 2 < w; ++x)
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        int a = face_at(x, y), b = face_at(x + dx, y + dy);
        if (a < 0 || b < 0 || a == b) continue;
        if (face_at(x - dx, y - dy) != a || face_at(x + 2 * dx, y + 2 * dy) != b) continue;
        const int before = step(x - dx, y - dy, x, y), after = step(x + dx, y + dy, x + 2 * dx, y + 2 * dy);
        const double excess = std::max(0, step(x, y, x + dx, y + dy) - std::max(before, after));
        if (a > b) std::swap(a, b);
        const auto e = edge_between.find({a, b});
        if (e == edge_between.end()) continue;  // faces meeting at a vertex only
        (e->second ? s.seam : s.ordinary) += excess;
        ++(e->second ? s.seam_pairs : s.ordinary_pairs);
      }
  s.seam /= double(std::max<std::size_t>(1, s.seam_pairs));
  s.ordinary /= double(std::max<std::size_t>(1, s.ordinary_pairs));
  return s;
}

}  // namespace

TEST_CASE("Shading seams: the step across a UV seam is within 2 levels of an ordinary edge's, in both normal modes",
          "[displacement][seams]") {
  for (const char* mode : {"auto", "derived"}) {
    const SeamSteps after = measure(mode, true);
    const SeamSteps before = measure(mode, false);  // the map as the file holds it, the shading of before
    INFO(mode << ": seam step " << after.seam << " over " << after.seam_pairs << " pairs, ordinary " << after.ordinary
              << " over " << after.ordinary_pairs << "; before: seam " << before.seam << ", ordinary "
              << before.ordinary);
    REQUIRE(after.seam_pairs > 500);
    REQUIRE(after.ordinary_pairs > 5000);
    CHECK(after.seam - after.ordinary <= 2.0);
    // The bound fails where seams are shaded from texels of neither side (UvSeams::raw).
    CHECK(before.seam - before.ordinary > 2.0);
    CHECK(after.seam <= 0.5 * before.seam);
  }
}

TEST_CASE("UV seams from the CLI (--uv-seams blend|raw): raw is the render of before, a bad value is one line",
          "[seams][cli]") {
  const auto dir = test::cli_temp_dir() / "uv-seams";
  std::filesystem::create_directories(dir);
  const std::string base = "render " + test::data("sdk-cages/monsterfrog_mapped_00.obj") + " --displacement " +
                           test::data("sdk-cages/monsterfrog.dds") +
                           " --displacement-channel A --factor 6 --resolution 320x240 -q --uv-seams ";
  const auto blend = test::run_cli(base + "blend -o " + (dir / "blend.png").string());
  const auto raw = test::run_cli(base + "raw -o " + (dir / "raw.png").string());
  const auto dflt = test::run_cli(base.substr(0, base.size() - std::string("--uv-seams ").size()) + "-o " +
                                  (dir / "default.png").string());
  REQUIRE(blend.exit_code == 0);
  REQUIRE(raw.exit_code == 0);
  REQUIRE(dflt.exit_code == 0);
  CHECK(test::slurp(dir / "default.png") == test::slurp(dir / "blend.png"));
  CHECK(test::slurp(dir / "raw.png") != test::slurp(dir / "blend.png"));
  const auto bad = test::run_cli(base + "smooth -o " + (dir / "bad.png").string());
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("--uv-seams: 'smooth' is not blend or raw") != std::string::npos);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK_FALSE(std::filesystem::exists(dir / "bad.png"));
}

}  // namespace tessera
