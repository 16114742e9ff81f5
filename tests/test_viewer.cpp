// tessera view: settings from requests, frames that equal `tessera render`'s bytes,
// picking against an independent id buffer, and the HTTP API's answers to good and bad requests.
// The page itself is tested in headless Chromium (viewer_browser_test.py).
#include <httplib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <thread>

#include <catch2/catch.hpp>

#include "cli_runner.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/render/displaced_render.h"
#include "test_data.h"
#include "tools/scene/model_options.h"
#include "tools/viewer/viewer_server.h"
#include "tools/viewer/viewer_session.h"
#include "tools/viewer/viewer_settings.h"

namespace tessera::viewer {

using namespace scene;
namespace {

namespace fs = std::filesystem;

RenderSettings frog(bool displaced) {
  RenderSettings s;
  s.cage = test::data("sdk-cages/monsterfrog_mapped_00.obj");
  s.lod.cull = PatchCullMode::all;  // render's default
  s.camera.width = 320;
  s.camera.height = 180;
  s.threads = 2;
  if (displaced) {
    s.displacement.map = test::data("sdk-cages/monsterfrog.dds");
    s.displacement.channel.assign(1, 'A');
  }
  return s;
}

// What `tessera render` writes for render_arguments(s).
std::string rendered(const RenderSettings& s, const std::string& name) {
  const fs::path out = test::cli_temp_dir() / name;
  const std::vector<std::string> words = render_arguments(s, out.string());
  const test::CliResult r = test::run_cli("-q " + shell_words(words));
  INFO(shell_words(words) << "\n" << r.err);
  REQUIRE(r.exit_code == 0);
  return test::slurp(out);
}

// A session served on 127.0.0.1 (an ephemeral port) for the test's lifetime, and a client of it.
struct ServedSession {
  ViewerSession session;
  ViewerServer server{session};
  int port = server.bind("127.0.0.1", 0);
  std::thread serving{[this] { server.serve(); }};
  httplib::Client client{"127.0.0.1", port};
  explicit ServedSession(const RenderSettings& s) : session(s) { client.set_read_timeout(120, 0); }
  ~ServedSession() {
    server.stop();
    serving.join();
  }
};

}  // namespace

TEST_CASE("viewer settings: requests name render's options, paths, repeats and absurd sizes are refused",
          "[viewer]") {
  const RenderSettings base = frog(false);
  const RenderSettings s = settings_from_query(base, {{"factor", "12.5"},
                                                      {"view", "factors"},
                                                      {"camera-position", "-3,2,40"},
                                                      {"lod", "screen"},
                                                      {"edge-pixels", "6"},
                                                      {"scheme", "acc"},
                                                      {"x", "4"},
                                                      {"format", "png"}});
  CHECK(s.factor == 12.5f);
  CHECK(s.view == ViewKind::factors);
  CHECK(s.camera.eye == glm::vec3(-3, 2, 40));  // a leading '-' is a value, not an option
  CHECK(s.lod.mode == LodMode::screen);
  CHECK(s.lod.edge_pixels == 6.0f);
  CHECK(s.scheme == Scheme::acc);
  CHECK(s.lod.cull == PatchCullMode::all);  // untouched settings keep the base's
  CHECK(s.cage == base.cage);
  // An empty camera setting goes back to the framing camera.
  RenderSettings moved = base;
  moved.camera.eye = glm::vec3(1, 2, 3);
  CHECK(!settings_from_query(moved, {{"camera-position", ""}}).camera.eye);

  const auto refused = [&](const QueryParams& q, const std::string& expected) {
    try {
      settings_from_query(base, q);
      FAIL("accepted");
    } catch (const RequestError& e) {
      const std::string m = e.what();
      INFO(m);
      CHECK(m.find(expected) != std::string::npos);
      CHECK(m.find('\n') == std::string::npos);
    }
  };
  refused({{"cage", "/etc/passwd"}}, "'cage' is not a setting");
  refused({{"displacement", "/etc/passwd"}}, "'displacement' is not a setting");
  refused({{"factors-per-edge", "/tmp/x"}}, "is not a setting");
  refused({{"threads", "64"}}, "is not a setting");
  refused({{"factor", "8"}, {"factor", "9"}}, "given twice");
  refused({{"factor", ""}}, "an empty value");
  refused({{"factor", "eight"}}, "factor");
  refused({{"resolution", "100000x100000"}}, "--resolution: 100000x100000 is outside 1..16384");
  refused({{"resolution", "5000x5000"}}, "more than the viewer draws");
  // Values are read when the request is, by the command line's readers, with their messages.
  refused({{"scheme", "loop"}}, "--scheme: 'loop' is not one of flat, bspline, acc, gregory, exact, pn");
  refused({{"view", "x-ray"}}, "--view: 'x-ray' is not one of shaded, wireframe");
  refused({{"camera-up", "0,0,0"}}, "--camera-up: 0,0,0 has no direction");
  refused({{"camera-position", "1,2"}}, "--camera-position: expected x,y,z");
  refused({{"resolution", "0x10"}}, "--resolution: 0x10 is outside 1..16384");
  refused({{std::string(5000, 'a'), "1"}}, "...' is not a setting");

  // The command holds what differs from render's defaults, and reads back as the same settings.
  const std::vector<std::string> words = render_arguments(s, "out.png");
  CHECK(words.front() == "render");
  CHECK(std::find(words.begin(), words.end(), "--factor") != words.end());
  CHECK(std::find(words.begin(), words.end(), "--partitioning") == words.end());  // at its default
  CHECK(std::find(words.begin(), words.end(), "--threads") == words.end());       // any count gives the bytes
  CHECK(shell_words({"a b", "it's", "plain-1,2"}) == "'a b' 'it'\\''s' plain-1,2");
}

TEST_CASE("viewer frames are the bytes tessera render writes, as settings change back and forth", "[viewer]") {
  // One session through changes that reconfigure a kept scene (camera, LOD with a displacement's
  // trilinear sampling, view) and that load another (scheme, displacement scale): each frame equals a
  // fresh `tessera render` of the reproducing command.
  ViewerSession session(frog(true));
  const RenderSettings base = session.base();
  const std::vector<QueryParams> steps = {
      {},
      {{"lod", "screen"}, {"edge-pixels", "6"}, {"camera-position", "10,5,60"}},
      {{"camera-position", "10,5,60"}},  // back to uniform: the map's trilinear sampling is off again
      {{"scheme", "acc"}, {"view", "factors"}, {"factor", "5"}},
      {{"displacement-scale", "0.5"}, {"view", "patch-type"}},
      {},
  };
  std::vector<std::string> frames;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const RenderSettings s = settings_from_query(base, steps[i]);
    const auto f = session.frame(s, FrameFormat::png);
    REQUIRE(f);
    CHECK(f->content_type == "image/png");
    CHECK(f->summary["triangles"].get<std::uint64_t>() > 0);
    INFO("step " << i);
    CHECK(f->bytes == rendered(s, "viewer-step-" + std::to_string(i) + ".png"));
    frames.push_back(f->bytes);
  }
  CHECK(frames.front() == frames.back());
  CHECK(frames[0] != frames[1]);
  // A frame nobody wants any more is not drawn.
  CHECK_FALSE(session.frame(base, FrameFormat::png, [] { return false; }));
  // JPEG for a moving camera.
  const auto jpeg = session.frame(base, FrameFormat::jpeg);
  REQUIRE(jpeg);
  CHECK(jpeg->bytes.substr(0, 2) == "\xff\xd8");
}

TEST_CASE("a kept scene keeps its factors file's table: a camera change reads no file", "[viewer]") {
  // The frog's first face's first edge at factor 3, the rest at --factor.
  const fs::path file = test::cli_temp_dir() / "viewer-factors.txt";
  const Cage cage = load_obj_cage(test::data("sdk-cages/monsterfrog_mapped_00.obj"));
  const std::string line =
      std::to_string(cage.face_vertex(0, 0)) + " " + std::to_string(cage.face_vertex(0, 1)) + " 3\n";
  const auto write = [&] { std::ofstream(file) << line; };
  write();
  RenderSettings base = frog(false);
  base.factors_file = file.string();
  ViewerSession session(base);
  REQUIRE(session.frame(base, FrameFormat::png));
  fs::remove(file);
  const RenderSettings moved = settings_from_query(base, {{"camera-position", "10,5,60"}});
  const auto f = session.frame(moved, FrameFormat::png);  // would fail on a re-read of the missing file
  REQUIRE(f);
  write();
  CHECK(f->bytes == rendered(moved, "viewer-factors-file.png"));
}

TEST_CASE("viewer info lists every scheme the Scheme enum has", "[viewer]") {
  ViewerSession session(frog(false));
  const Json info = session.info();
  std::vector<std::string> names;
  for (const auto& s : info["schemes"]) names.push_back(s.get<std::string>());
  REQUIRE(names.size() == std::size_t(kSchemeCount));
  for (int k = 0; k < kSchemeCount; ++k) CHECK(parse_scheme(names[std::size_t(k)]) == Scheme(k));
  CHECK(names.front() == "flat");
}

TEST_CASE("viewer frames of an animated glTF follow the time setting", "[viewer]") {
  RenderSettings s;
  s.cage = test::data("gltf-cages/frog-skinned.gltf");
  s.lod.cull = PatchCullMode::all;
  s.camera.width = 240;
  s.camera.height = 160;
  ViewerSession session(s);
  const Json info = session.info();
  CHECK(info["animated"] == true);
  REQUIRE(info["animations"].size() >= 1);
  const RenderSettings later = settings_from_query(session.base(), {{"time", "0.5"}});
  const auto a = session.frame(later, FrameFormat::png), b = session.frame(session.base(), FrameFormat::png);
  REQUIRE(a);
  REQUIRE(b);
  CHECK(a->bytes != b->bytes);
  CHECK(a->bytes == rendered(later, "viewer-time.png"));
}

TEST_CASE("viewer picks name the patch an independent id buffer has under the pixel", "[viewer]") {
  // The test's own id buffer: the displaced draw with a pixel shader that writes SV_PrimitiveID + 1.
  const RenderSettings base = frog(true);
  ViewerSession session(base);
  const int w = 320, h = 180;
  SubdModel model = load_subd_model(base.cage, Scheme::gregory);
  DisplacementOptions o;
  o.map = base.displacement.map;
  o.channel.assign(1, 'A');
  const Displacement d = make_displacement(model, o);
  SubdFactors factors;
  factors.factor = 8.0f;
  // The session's framing camera (the same bits: the JSON holds each float's shortest exact text).
  const Json info = session.info();
  const auto vec = [](const Json& v) { return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>()); };
  const SubdCamera camera =
      frame_cage(model.cage, w, h, 35.0f, vec(info["camera"]["position"]), vec(info["camera"]["target"]));
  Device device(DeviceOptions{2});
  std::string error;
  auto ids = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error);
  REQUIRE(ids);
  ids->clear(glm::vec4(0.0f), 1.0f);
  struct IdPS {
    glm::vec4 operator()(const PixelInput<kDisplacedAttributes>& in) const {
      const std::uint32_t id = in.primitive_id + 1;
      return glm::vec4(float(id & 255u), float((id >> 8) & 255u), float((id >> 16) & 255u), 255.0f) / 255.0f;
    }
  };
  REQUIRE(with_displaced_group(
              model, d, factors, PatchCull{}, ts::Partitioning::integer,
              [&](const PatchGroup& g, const TessellatorState& ts, const DisplacedHS& hs, const DisplacedDS& ds) {
                const SubdPassState st = subd_pass_state(model, *ids, false);
                const DisplacedProjectDS<DisplacedDS> project{ds, camera.view_projection, 0.0f};
                return draw_group_pass(device, model, g, ts, hs, project, IdPS{}, st, *ids);
              })
              .ok());
  // Over a grid of pixels: the same patch, or background in both.
  std::size_t hits = 0, agree = 0, background = 0;
  const auto& patches = model.patches.quads.patches;
  for (int y = 3; y < h; y += 12)
    for (int x = 5; x < w; x += 12) {
      const auto& c = ids->color_bytes();
      const std::size_t i = (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4;
      const std::uint32_t id = c[i] | (std::uint32_t(c[i + 1]) << 8) | (std::uint32_t(c[i + 2]) << 16);
      const Json j = session.pick(base, x, y);
      if (id == 0) {
        background += j["patch"].is_null() ? 1 : 0;
        CHECK(j["patch"].is_null());
        continue;
      }
      ++hits;
      REQUIRE_FALSE(j["patch"].is_null());
      agree += j["patch"]["face"] == patches[id - 1].face ? 1 : 0;
      CHECK(j["patch"]["face"] == patches[id - 1].face);
    }
  CHECK(hits >= 40);  // (50 of the 405 grid pixels land on the frog)
  CHECK(background > 50);
  CHECK(agree == hits);
  // Outside the frame: the caller's error.
  CHECK_THROWS_AS(session.pick(base, w, 0), RequestError);
  CHECK_THROWS_AS(session.pick(base, -1, 0), RequestError);
}

TEST_CASE("viewer HTTP API: frames, picks and commands, one-line 400s for bad requests, 404 elsewhere",
          "[viewer]") {
  ServedSession served(frog(false));
  httplib::Client& client = served.client;
  const auto get = [&](const std::string& path) {
    auto r = client.Get(path.c_str());
    REQUIRE(r);
    return *r;
  };
  const auto one_line_error = [&](const std::string& path, int status, const std::string& text) {
    const httplib::Response r = get(path);
    INFO(path << " -> " << r.status << " " << r.body);
    CHECK(r.status == status);
    CHECK(r.body.find(text) != std::string::npos);
    CHECK(std::count(r.body.begin(), r.body.end(), '\n') == 1);
  };
  {
    const httplib::Response page = get("/");
    CHECK(page.status == 200);
    CHECK(page.body.find("viewer.js") != std::string::npos);
    CHECK(get("/viewer.js").body.find("api/frame") != std::string::npos);
    const Json info = Json::parse(get("/api/info").body);
    CHECK(info["patches"] == 1292);
    CHECK(info["settings"]["resolution"] == "320x180");
    const httplib::Response progress = get("/api/progress");
    CHECK(progress.status == 200);
    CHECK(Json::parse(progress.body)["busy"] == false);
    CHECK(get("/viewer.js").body.find("api/progress") != std::string::npos);
  }
  const httplib::Response frame = get("/api/frame?factor=4&view=density&lod=screen");
  CHECK(frame.status == 200);
  CHECK(frame.get_header_value("Content-Type") == "image/png");
  CHECK(Json::parse(frame.get_header_value("X-Tessera-Summary"))["view"] == "density");
  const Json command = Json::parse(get("/api/command?factor=4&view=density&lod=screen").body);
  CHECK(command["command"].get<std::string>().find("--view density") != std::string::npos);
  CHECK(command["scene"]["view"] == "density");
  const Json pick = Json::parse(get("/api/pick?x=160&y=90").body);
  CHECK(pick["patch"]["face"].is_number());
  CHECK(Json::parse(get("/api/pick?x=0&y=0").body)["patch"].is_null());

  one_line_error("/api/frame?factor=nan", 400, "--factor");
  one_line_error("/api/frame?factor=-1", 400, "--factor");
  one_line_error("/api/frame?factor=1e30", 400, "--factor");
  one_line_error("/api/frame?camera-position=nan,0,0", 400, "camera");
  one_line_error("/api/frame?camera-position=0,2.884325,0.10888481", 400, "");  // at the target
  one_line_error("/api/frame?resolution=0x0", 400, "resolution");
  one_line_error("/api/frame?resolution=99999x1", 400, "--resolution: 99999x1 is outside 1..16384");
  one_line_error("/api/frame?resolution=8000x8000", 400, "more than the viewer draws");
  one_line_error("/api/frame?msaa=3", 400, "msaa");
  one_line_error("/api/frame?view=nonsense", 400, "view");
  one_line_error("/api/frame?cage=/etc/passwd", 400, "not a setting");
  one_line_error("/api/frame?format=gif", 400, "format");
  one_line_error("/api/frame?client=a", 400, "seq");
  one_line_error("/api/pick?x=1", 400, "y: missing");
  one_line_error("/api/pick?x=1&y=1e99", 400, "not an integer");
  one_line_error("/api/pick?x=100000&y=1", 400, "outside");
  one_line_error("/api/frame?factor=3&factor=4", 400, "given twice");
  one_line_error("/api/frame?time=5", 400, "is not animated");                // an OBJ cage
  one_line_error("/api/frame?factor=abc", 400, "factor: cannot read 'abc'");  // not CLI11's own words
  one_line_error("/etc/passwd", 404, "not part of the viewer");
  one_line_error("/../../etc/passwd", 404, "");
  // The server still draws after all that.
  CHECK(get("/api/frame?factor=2").status == 200);
  // A client's older frame is superseded; the table of clients is capped (256), so once 256 others
  // have asked, the server has forgotten this one and draws its old frame again.
  const std::string tiny = "/api/frame?factor=1&resolution=16x16";
  CHECK(get(tiny + "&client=old&seq=10").status == 200);
  CHECK(get(tiny + "&client=old&seq=5").status == 409);
  for (int i = 0; i < 256; ++i) REQUIRE(get(tiny + "&client=c" + std::to_string(i) + "&seq=1").status == 200);
  CHECK(get(tiny + "&client=old&seq=5").status == 200);
}

TEST_CASE("viewer: settings the asset refuses are a one-line 422 with the CLI's reason, not a 500", "[viewer]") {
  // pn patches carry no 1-ring, so the displaced frog cannot be drawn with them: the request is well
  // formed and the asset refuses it.
  ServedSession served(frog(true));
  httplib::Client& client = served.client;
  const auto r = client.Get("/api/frame?scheme=pn&resolution=32x32");
  REQUIRE(r);
  INFO(r->body);
  CHECK(r->status == 422);
  CHECK(r->body.find("--scheme pn cannot be displaced") != std::string::npos);
  CHECK(std::count(r->body.begin(), r->body.end(), '\n') == 1);
  const auto ok = client.Get("/api/frame?scheme=acc&resolution=32x32");  // the server still draws
  REQUIRE(ok);
  CHECK(ok->status == 200);
  // The page is offered only the schemes that draw this asset; the others come with their reason.
  const auto i = client.Get("/api/info");
  REQUIRE(i);
  const Json info = Json::parse(i->body);
  std::vector<std::string> names;
  for (const auto& s : info["schemes"]) names.push_back(s.get<std::string>());
  CHECK(std::find(names.begin(), names.end(), "pn") == names.end());
  CHECK(std::find(names.begin(), names.end(), "flat") == names.end());
  CHECK(std::find(names.begin(), names.end(), "gregory") != names.end());
  CHECK(info["schemes_refused"]["pn"].get<std::string>().find("cannot be displaced") != std::string::npos);
}

TEST_CASE("viewer info leaves out the schemes an n-gon cage refuses", "[viewer]") {
  // The dodecahedron's pentagons: acc takes quads only and pn triangles and quads only.
  RenderSettings s;
  s.cage = test::data("ngon-cages/dodecahedron.obj");
  ViewerSession session(s);
  const Json info = session.info();
  std::vector<std::string> names;
  for (const auto& n : info["schemes"]) names.push_back(n.get<std::string>());
  CHECK(names == std::vector<std::string>{"flat", "bspline", "gregory", "exact", "adaptive"});
  CHECK(info["schemes_refused"]["acc"].get<std::string>().find("5 sides") != std::string::npos);
  CHECK(info["schemes_refused"].contains("pn"));
}

TEST_CASE("tessera view: bad ports and addresses, and --scene with settings, fail in one line",
          "[viewer][cli]") {
  const std::string cage = test::data("sdk-cages/monsterfrog_mapped_00.obj");
  const test::CliResult port = test::run_cli("view " + cage + " --port 70000");
  CHECK(port.exit_code == 2);
  CHECK(port.err.find("--port") != std::string::npos);
  const test::CliResult bind = test::run_cli("view " + cage + " --bind 203.0.113.7 --port 0");
  CHECK(bind.exit_code == 1);
  CHECK(bind.err.find("cannot listen") != std::string::npos);
  const test::CliResult bad = test::run_cli("view " + cage + " --factor nan --port 0");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("--factor") != std::string::npos);
  const test::CliResult scene = test::run_cli("view --scene " + std::string(TESSERA_GOLDEN_DIR) +
                                              "/suites/scenes/frog-pn-factors.json --factor 3");
  CHECK(scene.exit_code == 2);
  CHECK(scene.err.find("--factor with --scene") != std::string::npos);
  for (const auto* r : {&port, &bind, &bad, &scene}) CHECK(std::count(r->err.begin(), r->err.end(), '\n') == 1);
}

TEST_CASE("viewer progress names the steps of each load of the asset, and is idle between frames", "[viewer]") {
  ViewerSession session(frog(false));
  Json p = session.progress();
  CHECK(p["busy"] == false);
  CHECK(p["loads"] == 1);
  const auto steps = [&] { return session.progress()["last_load"].get<std::vector<std::string>>(); };
  const std::vector<std::string> first = steps();
  REQUIRE(first.size() >= 3);
  CHECK(first[0] == "reading");
  CHECK(std::find(first.begin(), first.end(), "patches") != first.end());
  // A camera change reconfigures the kept scene: no load.
  RenderSettings s = session.base();
  s.camera.eye = glm::vec3(10, 5, 60);
  REQUIRE(session.frame(s, FrameFormat::png));
  CHECK(session.progress()["loads"] == 1);
  // Another scheme loads the asset again; exact builds the limit surface.
  s.scheme = Scheme::exact;
  REQUIRE(session.frame(s, FrameFormat::png));
  p = session.progress();
  CHECK(p["busy"] == false);
  CHECK(p["loads"] == 2);
  const std::vector<std::string> second = steps();
  CHECK(std::find(second.begin(), second.end(), "limit surface") != second.end());
}

}  // namespace tessera::viewer
