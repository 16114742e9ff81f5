// Reference renders: byte-stable output files, the camera's up vector and turntables,
// the bounding box analyze reports, render --json, progress on stderr.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <glm/glm.hpp>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "test_data.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
const std::string kFrog = test::data("sdk-cages/monsterfrog_mapped_00.obj");
const std::string kMap = test::data("sdk-cages/monsterfrog.dds");

fs::path temp_dir(const std::string& name) {
  const fs::path dir = test::cli_temp_dir() / name;
  fs::create_directories(dir);
  return dir;
}

test::CliResult run_ok(const std::string& args) {
  const test::CliResult r = test::run_cli(args);
  INFO(args << "\n" << r.err);
  REQUIRE(r.exit_code == 0);
  return r;
}

// Pixels whose RGB differ, of an image pair of equal size.
std::size_t differing_pixels(const std::string& a, const std::string& b) {
  OIIO::ImageBuf ia(a), ib(b);
  REQUIRE(ia.read(0, 0, true, OIIO::TypeDesc::UINT8));
  REQUIRE(ib.read(0, 0, true, OIIO::TypeDesc::UINT8));
  REQUIRE(ia.spec().width == ib.spec().width);
  REQUIRE(ia.spec().height == ib.spec().height);
  std::size_t n = 0;
  const int w = ia.spec().width, h = ia.spec().height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        if (ia.getchannel(x, y, 0, c) != ib.getchannel(x, y, 0, c)) {
          ++n;
          break;
        }
  return n;
}

// Pixels that are not the background (the top-left pixel's colour).
std::size_t foreground_pixels(const std::string& path) {
  OIIO::ImageBuf img(path);
  REQUIRE(img.read(0, 0, true, OIIO::TypeDesc::UINT8));
  std::size_t n = 0;
  const int w = img.spec().width, h = img.spec().height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        if (img.getchannel(x, y, 0, c) != img.getchannel(0, 0, 0, c)) {
          ++n;
          break;
        }
  return n;
}

}  // namespace

TEST_CASE("Every output file is the same bytes for the same input on 1 and 3 threads", "[cli][outputs]") {
  const fs::path dir = temp_dir("stable");
  const std::string common =
      " --factor 6 --resolution 200x120 --displacement " + kMap + " --displacement-channel A --displacement-scale 0.5";
  for (const char* ext : {"png", "exr", "tif"}) {
    std::string first;
    for (int threads : {1, 3}) {
      const std::string n = std::to_string(threads);
      const fs::path image = dir / (std::string("f").append(n).append(".").append(ext));
      const fs::path stats = dir / (std::string("s").append(n).append(".json"));
      run_ok("-q render " + kFrog + common + " --threads " + std::to_string(threads) + " -o " + image.string() +
             " --stats " + stats.string());
      const std::string bytes = test::slurp(image) + test::slurp(stats);
      if (first.empty())
        first = bytes;
      else
        CHECK(bytes == first);  // the EXR's capDate and the TIFF's DateTime carry no clock
    }
  }
  // A second run later gives the same EXR (it held the time of writing before).
  run_ok("-q render " + kFrog + common + " -o " + (dir / "again.exr").string());
  CHECK(test::slurp(dir / "again.exr") == test::slurp(dir / "f1.exr"));
  // The statistics file holds counts, not times or memory (those are in --json).
  const auto stats = nlohmann::json::parse(test::slurp(dir / "s1.json"));
  CHECK_FALSE(stats.contains("times"));
  CHECK_FALSE(stats.contains("memory"));
  CHECK(stats["statistics"]["HSInvocations"] == 1292);
  // PLY and GLB from tessellate, and a diff image.
  for (const char* ext : {"ply", "glb"}) {
    run_ok("-q tessellate " + kFrog + " --factor 3 --threads 1 -o " + (dir / "a.").string() + ext);
    run_ok("-q tessellate " + kFrog + " --factor 3 --threads 3 -o " + (dir / "b.").string() + ext);
    CHECK(test::slurp(dir / ("a." + std::string(ext))) == test::slurp(dir / ("b." + std::string(ext))));
  }
  for (const char* name : {"d1.exr", "d2.exr"})
    test::run_cli("diff " + (dir / "f1.png").string() + " " + (dir / "again.exr").string() + " -o " +
                  (dir / name).string());
  CHECK(test::slurp(dir / "d1.exr") == test::slurp(dir / "d2.exr"));
}

TEST_CASE("render --json: the summary scripts read, with times and memory", "[cli]") {
  const fs::path dir = temp_dir("json");
  const auto r = run_ok("-q render " + kFrog + " --factor 4 --resolution 160x90 --json -o " + (dir / "a.png").string());
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["output"] == (dir / "a.png").string());
  CHECK(j["width"] == 160);
  CHECK(j["height"] == 90);
  CHECK(j["patches"] == 1292);
  CHECK(j["triangles"].get<std::uint64_t>() == j["statistics"]["CInvocations"].get<std::uint64_t>());
  CHECK(j["pixels_shaded"].get<std::uint64_t>() > 0);
  CHECK(j["times"]["wall_s"].get<double>() > 0);
  CHECK(j["memory"]["geometry_peak_bytes"].get<std::uint64_t>() > 0);
  CHECK(j["peak_rss_bytes"].get<std::uint64_t>() > 0);
  CHECK(j["camera"]["position"].size() == 3);
}

TEST_CASE("Camera up vector (--camera-up): z-up views, a reversed up turns the image over, degenerate ups are refused",
          "[cli][camera]") {
  const fs::path dir = temp_dir("up");
  const std::string cam = " --factor 4 --resolution 160x120 --camera-position 40,20,60 --camera-target 0,3,0 -o ";
  run_ok("-q render " + kFrog + cam + (dir / "y.png").string());
  run_ok("-q render " + kFrog + cam + (dir / "minus_y.png").string() + " --camera-up 0,-2,0");
  // Up reversed: the image turned half a turn. Compare against the y-up image rotated by 180 degrees;
  // snapping and the top-left rule are not symmetric, so a few edge pixels may differ.
  {
    OIIO::ImageBuf y((dir / "y.png").string());
    OIIO::ImageBuf turned = OIIO::ImageBufAlgo::rotate180(y);
    REQUIRE(turned.write((dir / "y_turned.png").string()));
  }
  const std::size_t fg = foreground_pixels((dir / "y.png").string());
  REQUIRE(fg > 1000);
  CHECK(differing_pixels((dir / "y_turned.png").string(), (dir / "minus_y.png").string()) < fg / 50);
  // A camera straight above the model works once up is not its view direction.
  const std::string above = " --factor 4 --resolution 160x120 --camera-position 0,90,0 --camera-target 0,0,0 -o ";
  auto r = test::run_cli("render " + kFrog + above + (dir / "above.png").string());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("looks straight along the up axis") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "above.png"));
  run_ok("-q render " + kFrog + above + (dir / "above.png").string() + " --camera-up 0,0,-1");
  CHECK(foreground_pixels((dir / "above.png").string()) > 1000);
  for (const char* bad : {"0,0,0", "nan,1,0", "1,2", "0,1e-30,0"}) {
    r = test::run_cli("render " + kFrog + " --camera-up " + bad + " -o " + (dir / "bad.png").string());
    INFO(bad << ": " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--camera-up") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(dir / "bad.png"));
  }
}

TEST_CASE("render --orbit N: a turntable from one load, each view the render of its camera", "[cli][camera]") {
  const fs::path dir = temp_dir("orbit");
  const std::string common =
      " --factor 4 --resolution 160x90 --displacement " + kMap + " --displacement-channel A --displacement-scale 0.5";
  const auto r = run_ok("-q render " + kFrog + common + " --orbit 4 --json -o " + (dir / "v_%d.png").string());
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["images"].size() == 4);
  std::vector<std::string> eyes;
  for (int i = 0; i < 4; ++i) {
    const auto& image = j["images"][std::size_t(i)];
    CHECK(image["output"] == (dir / ("v_" + std::to_string(i) + ".png")).string());
    REQUIRE(fs::exists(dir / ("v_" + std::to_string(i) + ".png")));
    const auto& p = image["camera"]["position"];
    const auto& t = image["camera"]["target"];
    std::ostringstream eye, target;
    eye << std::setprecision(9) << p[0].get<double>() << "," << p[1].get<double>() << "," << p[2].get<double>();
    target << std::setprecision(9) << t[0].get<double>() << "," << t[1].get<double>() << "," << t[2].get<double>();
    eyes.push_back(eye.str());
    // The same camera in one render gives the same bytes.
    run_ok("-q render " + kFrog + common + " --camera-position " + eye.str() + " --camera-target " + target.str() +
           " -o " + (dir / "single.png").string());
    CHECK(test::slurp(dir / "single.png") == test::slurp(dir / ("v_" + std::to_string(i) + ".png")));
  }
  // The views differ and stay at one height (turned about +y).
  CHECK(j["images"][0]["camera"]["position"][1] == j["images"][2]["camera"]["position"][1]);
  CHECK(test::slurp(dir / "v_0.png") != test::slurp(dir / "v_2.png"));
  // --orbit with --frames is refused; a missing frame field too.
  auto bad = test::run_cli("render " + kFrog + " --orbit 3 --frames 2 -o " + (dir / "w_%d.png").string());
  CHECK(bad.exit_code == 2);
  bad = test::run_cli("render " + kFrog + " --orbit 3 -o " + (dir / "w.png").string());
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("--orbit") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "w.png"));
}

TEST_CASE("analyze reports the control points' bounding box", "[cli]") {
  const auto r = run_ok("analyze " + kFrog + " --json");
  const auto j = nlohmann::json::parse(r.out);
  const Cage cage = load_obj_cage(kFrog);
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : cage.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  for (int a = 0; a < 3; ++a) {
    CHECK(j["bounding_box"]["min"][std::size_t(a)].get<float>() == lo[a]);
    CHECK(j["bounding_box"]["max"][std::size_t(a)].get<float>() == hi[a]);
  }
  CHECK(j["bounding_box"]["diagonal"].get<double>() == Approx(glm::length(hi - lo)).epsilon(1e-6));
  const auto text = run_ok("analyze " + kFrog);
  CHECK(text.out.find("bounding box = (") != std::string::npos);
}

TEST_CASE("Progress and -v on stderr, nothing with -q", "[cli]") {
  const fs::path dir = temp_dir("progress");
  const std::string args = " render " + kFrog + " --factor 8 --resolution 160x90 -o " + (dir / "p.png").string();
  auto r = run_ok("-v" + args);
  CHECK(r.err.find("tessera: loaded " + kFrog + ": 1308 vertices, 1292 faces") != std::string::npos);
  CHECK(r.err.find("thread-ms: IA+VS") != std::string::npos);
  CHECK(r.err.find("tessera: render done (1292/1292 patches)") != std::string::npos);  // a log's last line
  // A cage of quads and triangles draws two patch groups: the last line counts both (50 + 32).
  const auto mixed = run_ok("-v render " + test::data("osd-shapes/catmark_val2_interior.obj") +
                            " --scheme exact --resolution 32x18 -o " + (dir / "mixed.png").string());
  CHECK(mixed.err.find("tessera: render done (82 patches in 2 passes)") != std::string::npos);
  r = run_ok("-q" + args);
  CHECK(r.err.empty());
  r = run_ok(args);
  CHECK(r.err.find("loaded") == std::string::npos);  // -v only
}

}  // namespace tessera
