// Scene files (tools/scene/scene_file.h, docs/scene.schema.json): a printed scene renders the bytes its
// command line does, settings survive a round trip bit for bit, paths resolve against the scene file,
// the schema and the reader agree field for field, and bad scenes get one line naming file and field.
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>
#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_data.h"
#include "tools/scene/common.h"
#include "tools/scene/scene_file.h"
#include "tools/scene/scene_render.h"
#include "tools/scene/view_legend.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
const std::string kFrog = test::data("sdk-cages/monsterfrog_mapped_00.obj");
const fs::path kSchema = fs::path(TESSERA_TEST_DATA_DIR).parent_path().parent_path() / "docs" / "scene.schema.json";

fs::path write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("A printed scene renders the same bytes as its command line", "[scene][cli]") {
  const fs::path dir = test::cli_temp_dir() / "scene-print";
  fs::create_directories(dir / "scenes");
  const std::string line = kFrog +
                           " --scheme acc --lod screen --edge-pixels 6 --partitioning fractional_odd --camera-position "
                           "48.1,15,66 --camera-target -3,-2.5,2 --fov 31.5 --resolution 240x135 --view factors "
                           "--displacement " +
                           test::data("sdk-cages/monsterfrog.dds") +
                           " --displacement-channel A --displacement-scale 1.2 --displacement-bias -0.6";
  REQUIRE(test::run_cli("render " + line + " -o " + (dir / "direct.png").string()).exit_code == 0);
  REQUIRE(test::run_cli("render " + line + " --print-scene " + (dir / "scenes/frog.json").string()).exit_code == 0);
  const auto scene = nlohmann::json::parse(test::slurp(dir / "scenes/frog.json"));
  CHECK(scene["asset"].get<std::string>().rfind("../", 0) == 0);  // relative to the scene's directory
  CHECK(scene["lod"]["edge_pixels"] == 6.0);
  CHECK(scene["view"] == "factors");
  // From another working directory, and with another thread count: the same bytes.
  REQUIRE(test::run_cli("render --scene " + (dir / "scenes/frog.json").string() + " --threads 1 -o " +
                        (dir / "scene.png").string())
              .exit_code == 0);
  CHECK(test::slurp(dir / "scene.png") == test::slurp(dir / "direct.png"));
  // Printing to stdout gives absolute paths and renders nothing.
  const auto out = test::run_cli("render " + line + " --print-scene -");
  REQUIRE(out.exit_code == 0);
  CHECK(fs::path(nlohmann::json::parse(out.out)["asset"].get<std::string>()).is_absolute());
}

TEST_CASE("A printed scene holds the framed camera, and renders the same bytes", "[scene][cli]") {
  // Without --camera-position and --camera-target the framing places the camera; the printed scene
  // writes where it went, so the scene no longer depends on the framing heuristic.
  const fs::path dir = test::cli_temp_dir() / "scene-framed";
  fs::create_directories(dir);
  const std::string line = kFrog + " --factor 3 --resolution 160x90";
  REQUIRE(test::run_cli("render " + line + " -o " + (dir / "direct.png").string()).exit_code == 0);
  REQUIRE(test::run_cli("render " + line + " --print-scene " + (dir / "frog.json").string()).exit_code == 0);
  const auto scene = nlohmann::json::parse(test::slurp(dir / "frog.json"));
  REQUIRE(scene["camera"].contains("position"));
  REQUIRE(scene["camera"].contains("target"));
  REQUIRE(scene["camera"].contains("up"));
  REQUIRE(test::run_cli("render --scene " + (dir / "frog.json").string() + " -o " + (dir / "scene.png").string())
              .exit_code == 0);
  CHECK(test::slurp(dir / "scene.png") == test::slurp(dir / "direct.png"));
}

TEST_CASE("Scene settings survive a round trip bit for bit", "[scene]") {
  const fs::path dir = test::cli_temp_dir() / "scene-roundtrip";
  scene::RenderSettings s;
  s.cage = (dir / "assets/cage.obj").string();
  s.scheme = Scheme::pn;
  s.partitioning = ts::Partitioning::pow2;
  s.factor = 7.3f;
  s.vary = 0.1f;
  s.factors_file = (dir / "factors.txt").string();
  s.view = scene::ViewKind::density;
  s.factor_kind = scene::FactorKind::processed;
  s.camera = {640, 360, glm::vec3(0.1f, -2.3e-5f, 1e6f), glm::vec3(3, 2, 1), glm::vec3(0, 0, 1), 29.7f};
  s.lod.mode = LodMode::distance;
  s.lod.cull = PatchCullMode::backface;
  s.lod.edge_pixels = 3.3f;
  s.lod.lod_distance = 12.125f;
  s.lod.dicing_eye = glm::vec3(1.5f, 0.2f, -7.0f);
  s.threads = 3;
  s.msaa = 4;
  s.displacement = {(dir / "maps/h.exr").string(),
                    "R,G,B",
                    DisplacementSpace::object,
                    (dir / "maps/n.png").string(),
                    0.7f,
                    -0.35f,
                    scene::UvSeams::raw};
  s.asset.time = 0.25;
  s.asset.animation = "walk";
  s.source = {"Blender 3.4.1", "/home/a/bar.blend", "Bar", 12.0};  // the exporting tool's record
  const fs::path file = write(dir / "scenes/s.json", scene::scene_json(s, (dir / "scenes").string()).dump(2));
  scene::RenderSettings r = scene::read_scene(file.string());
  CHECK(fs::path(r.cage).lexically_normal() == fs::path(s.cage).lexically_normal());
  CHECK(fs::path(r.factors_file) == fs::path(s.factors_file).lexically_normal());
  CHECK(fs::path(r.displacement.map) == fs::path(s.displacement.map).lexically_normal());
  CHECK(fs::path(r.displacement.normal_map) == fs::path(s.displacement.normal_map).lexically_normal());
  // Every other setting, typed, bit for bit.
  r.cage = s.cage;
  r.factors_file = s.factors_file;
  r.displacement.map = s.displacement.map;
  r.displacement.normal_map = s.displacement.normal_map;
  CHECK(r == s);
  CHECK(r.camera.eye->y == -2.3e-5f);
  CHECK(r.lod.dicing_eye == s.lod.dicing_eye);
}

TEST_CASE("The schema and the reader agree, and --scene-schema prints the schema", "[scene][cli]") {
  const std::string text = test::slurp(kSchema);
  CHECK(test::run_cli("render --scene-schema").out == text);
  const auto schema = nlohmann::json::parse(text);
  const fs::path dir = test::cli_temp_dir() / "scene-schema";
  // Every property of the schema, at a value the schema allows, is read.
  int accepted = 0;
  for (const auto& [key, spec] : schema["properties"].items()) {
    nlohmann::json scene = {{"tessera_scene", 1}, {"asset", kFrog}};
    if (spec.contains("default"))
      scene[key] = spec["default"];
    else if (spec.contains("enum"))
      scene[key] = spec["enum"][0];
    else if (key == "factors_per_edge")
      scene[key] = "f.txt";
    else if (key == "lod")
      scene[key] = {{"mode", "screen"}, {"dicing_camera_position", {1, 2, 3}}};
    else if (key == "displacement")
      scene[key] = {{"map", "h.exr"}, {"channel", "A"}, {"normal_map", "derived"}};
    else if (key == "camera")
      scene[key] = {{"position", {1, 2, 3}}, {"target", {0, 0, 0}}, {"fov", 40}};
    else if (key == "animation" || key == "mesh")
      scene[key] = "bend";
    else if (key == "scene_index")
      scene[key] = 0;
    else if (key == "source")
      scene[key] = {{"application", "Blender 3.4.1"}, {"file", "a.blend"}, {"object", "Cube"}, {"frame", 12}};
    else if (key != "tessera_scene" && key != "asset")
      FAIL("no sample value for schema property " << key);
    const fs::path file = write(dir / ("p-" + key + ".json"), scene.dump());
    INFO(key << ": " << scene.dump());
    CHECK_NOTHROW(scene::read_scene(file.string()));
    ++accepted;
  }
  CHECK(accepted == int(schema["properties"].size()));
  // Sub-objects: every property of lod, displacement and camera is known to the reader too.
  for (const char* object : {"lod", "displacement", "camera"})
    for (const auto& [key, spec] : schema["properties"][object]["properties"].items()) {
      nlohmann::json scene = {{"tessera_scene", 1}, {"asset", kFrog}};
      nlohmann::json value = spec.contains("enum")                                       ? spec["enum"].back()
                             : key == "mode"                                             ? nlohmann::json("screen")
                             : key == "space"                                            ? nlohmann::json("object")
                             : (key == "map" || key == "channel" || key == "normal_map") ? nlohmann::json("x.exr")
                             : (key == "position" || key == "target" || key == "up" || key == "dicing_camera_position")
                                 ? nlohmann::json::array({1, 2, 3})
                                 : nlohmann::json(2.5);
      scene[object] = {{key, value}};
      if (std::string(object) == "displacement") scene[object]["map"] = "h.exr";
      const fs::path file = write(dir / (std::string(object) + "-" + key + ".json"), scene.dump());
      INFO(object << "." << key);
      CHECK_NOTHROW(scene::read_scene(file.string()));
    }
  // And a field the schema does not have is refused.
  const fs::path typo = write(dir / "typo.json", R"({"tessera_scene": 1, "asset": "a.obj", "camera": {"fav": 40}})");
  CHECK_THROWS_WITH(scene::read_scene(typo.string()), Catch::Contains("\"camera.fav\": not a scene field"));
}

TEST_CASE("Bad scenes: one line naming the file and the field, a non-zero exit, no output", "[scene][cli]") {
  const fs::path dir = test::cli_temp_dir() / "scene-bad";
  const std::pair<const char*, const char*> cases[] = {
      {R"({"tessera_scene": 1, "asset": "a.obj", "factr": 3})", "\"factr\": not a scene field"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "factor": "8"})", "\"factor\": expected a number"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "scheme": "loop"})", "\"scheme\": 'loop' is not one of"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "resolution": [640]})", "\"resolution\": expected [width, height]"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "camera": {"position": [1, 2]}})",
       "\"camera.position\": expected [x, y, z]"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "threads": -1})", "\"threads\": expected a count"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "msaa": 3})", "\"msaa\": expected 1, 2, 4, 8 or 16"},
      // Names and vectors go through the command line's readers, their refusals under the field's name.
      {R"({"tessera_scene": 1, "asset": "a.obj", "lod": {"mode": "far"}})", "\"lod.mode\": 'far' is not uniform"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "camera": {"up": [0, 0, 0]}})", "\"camera.up\": [0,0,0] has no"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "resolution": [20000, 10]})", "\"resolution\": [20000,10] is outside"},
      // A number past double's range (the scene fuzzer's find: nlohmann throws out_of_range, not parse_error).
      {R"({"tessera_scene": 1, "asset": "a.obj", "factor": 1e999})", "not a JSON scene (number overflow"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "displacement": {"scale": 2}})", "\"displacement.map\": missing"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "source": {"frame": "12"}})", "\"source.frame\": expected a number"},
      {R"({"tessera_scene": 1, "asset": "a.obj", "source": {"scene": 1}})", "\"source.scene\": not a scene field"},
      {R"({"tessera_scene": 2, "asset": "a.obj"})", "\"tessera_scene\": must be 1"},
      {R"({"tessera_scene": 1})", "\"asset\": missing"},
      {R"([1, 2])", "expected an object"},
      {"{\"tessera_scene\": 1,\n  \"asset\": ", "line 2"}};
  int n = 0;
  for (const auto& [text, message] : cases) {
    const fs::path file = write(dir / ("bad" + std::to_string(n++) + ".json"), text);
    const fs::path out = dir / "out.png";
    const auto r = test::run_cli("render --scene " + file.string() + " -o " + out.string());
    INFO(text);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(file.string()) != std::string::npos);
    CHECK(r.err.find(message) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(out));
  }
  // The scene and the options it sets, together: refused; a time on a static cage: refused.
  const fs::path good = write(dir / "good.json", nlohmann::json({{"tessera_scene", 1}, {"asset", kFrog}}).dump());
  const auto both = test::run_cli("render --scene " + good.string() + " --factor 3 -o " + (dir / "x.png").string());
  CHECK(both.exit_code == 2);
  CHECK(both.err.find("--factor with --scene") != std::string::npos);
  const fs::path timed =
      write(dir / "timed.json", nlohmann::json({{"tessera_scene", 1}, {"asset", kFrog}, {"time", 1.5}}).dump());
  const auto t = test::run_cli("render --scene " + timed.string() + " -o " + (dir / "x.png").string());
  CHECK(t.exit_code == 2);
  CHECK(t.err.find("not animated") != std::string::npos);
  CHECK(test::run_cli("render --scene " + (dir / "missing.json").string() + " -o x.png").exit_code == 1);
}

}  // namespace tessera

namespace tessera::scene {

TEST_CASE("configure_scene redoes only what the settings change, and draws as a fresh scene", "[scene]") {
  RenderSettings s;
  s.cage = kFrog;
  s.lod.mode = LodMode::screen;
  s.lod.cull = PatchCullMode::all;
  s.camera.width = 160;
  s.camera.height = 90;
  s.threads = 2;
  s.view = ViewKind::density;  // a view with a legend: framing keeps its band (view_legend.h)
  const std::unique_ptr<PreparedScene> p = prepare_scene(s);
  REQUIRE(p->factors.per_edge);
  const auto* table = p->factors.per_edge.get();
  Device device(device_options(2));
  const auto bytes = [&](const PreparedScene& scene) { return render_scene(device, scene, false).fb->color_bytes(); };

  // A view kind alone: the LOD table stands, and the image is a fresh scene's.
  RenderSettings v = s;
  v.view = ViewKind::factors;
  configure_scene(*p, v);
  CHECK(p->factors.per_edge.get() == table);
  CHECK(p->settings.view == ViewKind::factors);
  CHECK(bytes(*p) == bytes(*prepare_scene(v)));

  // The camera: the LOD is computed again, for the new view.
  RenderSettings c = v;
  c.camera.eye = glm::vec3(10, 5, 60);
  configure_scene(*p, c);
  CHECK(p->factors.per_edge.get() != table);
  CHECK(bytes(*p) == bytes(*prepare_scene(c)));

  // After view_scene (render --orbit), the settings' camera is computed again even though its text
  // did not change.
  const auto* orbit_table = p->factors.per_edge.get();
  view_scene(*p, orbit_view(c.camera, p->model, p->view, 1, 4));
  configure_scene(*p, c);
  CHECK(p->factors.per_edge.get() != orbit_table);
  CHECK(bytes(*p) == bytes(*prepare_scene(c)));
}

TEST_CASE("A legend takes the first corner where it covers no surface, and keeps the lower left when free",
          "[scene][views]") {
  const fs::path dir = test::cli_temp_dir() / "legend-corner";
  fs::create_directories(dir);
  const glm::vec4 background(0.8f, 0.8f, 0.8f, 1.0f), surface(0.2f, 0.4f, 0.6f, 1.0f);  // exact in 8 bits
  Legend legend;
  legend.title = "a legend";
  legend.lines = {"one line of text"};
  // Returns the pixels of the written image, RGBA8, and the surface's pixels untouched or not.
  const auto draw = [&](int surface_from_row, const std::string& name) {
    std::string error;
    std::optional<Framebuffer> fb = Framebuffer::create(320, 240, ColorFormat::rgba8_unorm, &error);
    REQUIRE(fb);
    fb->clear(background, 1.0f);
    for (int y = surface_from_row; y < 240; ++y)
      for (int x = 0; x < 320; ++x) fb->set_color(x, y, surface), fb->set_depth(x, y, 0.5f);
    const std::string path = (dir / name).string();
    write_with_legend(*fb, legend, {path});
    auto in = OIIO::ImageInput::open(path);
    REQUIRE(in);
    std::vector<std::uint8_t> px(320 * 240 * 4);
    REQUIRE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
    return px;
  };
  const auto changed = [](const std::vector<std::uint8_t>& px, int y0, int y1, glm::vec4 was) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < 320; ++x)
        for (int c = 0; c < 3; ++c)
          n += px[(std::size_t(y) * 320 + std::size_t(x)) * 4 + std::size_t(c)] != std::uint8_t(was[c] * 255.0f + 0.5f);
    return n;
  };
  // The surface covers the lower half: the legend goes to the top, the surface keeps every pixel.
  const auto low = draw(120, "low.png");
  CHECK(changed(low, 120, 240, surface) == 0);
  CHECK(changed(low, 0, 120, background) > 0);
  // No surface at all: the lower left, where a legend has always been.
  const auto none = draw(240, "none.png");
  CHECK(changed(none, 0, 120, background) == 0);
  CHECK(changed(none, 120, 240, background) > 0);
}

}  // namespace tessera::scene

namespace tessera::scene {

TEST_CASE("The cage view frames the control cage as well as the surface", "[scene]") {
  // Three cubes' cages reach far beyond their rounded surfaces: framed on the surface alone, corners of
  // the cage fall outside the image the cage view draws them in.
  RenderSettings s;
  s.cage = test::data("osd-shapes/catmark_cubes_semisharp.obj");
  s.scheme = Scheme::exact;
  s.camera.width = 800;
  s.camera.height = 450;
  const auto outside = [](const PreparedScene& p) {
    int n = 0;
    for (const glm::vec3& v : p.model.positions()) {
      const glm::vec4 c = p.view.camera.view_projection * glm::vec4(v, 1.0f);
      n += std::abs(c.x) > c.w || std::abs(c.y) > c.w ? 1 : 0;
    }
    return n;
  };
  s.view = ViewKind::shaded;
  const std::unique_ptr<PreparedScene> shaded = prepare_scene(s);
  CHECK(outside(*shaded) > 0);
  s.view = ViewKind::cage;
  const std::unique_ptr<PreparedScene> cage = prepare_scene(s);
  CHECK(outside(*cage) == 0);
  // A prepared scene switched to the cage view is framed again, as a fresh one.
  configure_scene(*shaded, s);
  CHECK(shaded->view.camera.eye == cage->view.camera.eye);
}

}  // namespace tessera::scene
