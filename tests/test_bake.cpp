// `tessera bake` (shaders_cpp/bake/): texel sites invert the UV layout; a map baked from the displaced
// frog's own tessellation re-renders the same surface (dual parameterisation and ray casting, vector
// and scalar), measured at the same domain points; maps are the same bytes for any thread count; bad
// inputs get one line.
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "cli_runner.h"
#include "shaders_cpp/bake/dense_mesh.h"
#include "shaders_cpp/bake/map_writer.h"
#include "shaders_cpp/bake/texel_sites.h"
#include "shaders_cpp/displacement/displacement_map.h"
#include "test_data.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
const std::string kData = TESSERA_TEST_DATA_DIR;
const std::string kFrog = kData + "/sdk-cages/monsterfrog_mapped_00.obj";
const std::string kFrogMap = kData + "/sdk-cages/monsterfrog.dds";

struct Distance {
  double max = 0, rms = 0;  // relative to the bounding box diagonal of `a`
};

// Two tessellations of one cage at one factor write the same domain points in the same order.
Distance surface_distance(const std::string& a_path, const std::string& b_path) {
  const DenseMesh a = load_dense_mesh(a_path), b = load_dense_mesh(b_path);
  REQUIRE(a.positions.size() == b.positions.size());
  REQUIRE(a.face == b.face);
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const auto& p : a.positions) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
  const double diagonal = glm::length(hi - lo);
  Distance d;
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    const double e = glm::length(glm::dvec3(a.positions[i]) - glm::dvec3(b.positions[i]));
    d.max = std::max(d.max, e), d.rms += e * e;
  }
  d.rms = std::sqrt(d.rms / double(a.positions.size()));
  d.max /= diagonal, d.rms /= diagonal;
  return d;
}

std::string slurp_binary(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("bake: texel sites invert the bilinear UV layout", "[bake]") {
  PatchTexcoords a, b;
  a.interior = {glm::vec2(0.1f, 0.1f), glm::vec2(0.5f, 0.15f), glm::vec2(0.45f, 0.6f), glm::vec2(0.05f, 0.5f)};
  b.interior = {glm::vec2(0.5f, 0.15f), glm::vec2(0.9f, 0.1f), glm::vec2(0.95f, 0.55f), glm::vec2(0.45f, 0.6f)};
  const std::vector<PatchTexcoords> patches = {a, b};
  const int w = 64, h = 48;
  const auto sites = texel_sites(patches, w, h);
  int covered[2] = {0, 0};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const TexelSite& s = sites[std::size_t(y * w + x)];
      if (s.patch < 0) continue;
      ++covered[s.patch];
      const glm::vec2 uv = bilerp_uv(patches[std::size_t(s.patch)].interior, s.u, s.v);
      CHECK(std::abs(uv.x - (float(x) + 0.5f) / float(w)) < 1e-5f);
      CHECK(std::abs(uv.y - (float(y) + 0.5f) / float(h)) < 1e-5f);
    }
  // Both quads cover about their area in texels; texels outside both are uncovered.
  CHECK(covered[0] > 300);
  CHECK(covered[1] > 300);
  CHECK(sites[0].patch == -1);
  float u, v;
  CHECK_FALSE(invert_bilinear(a.interior, glm::dvec2(0.9, 0.9), u, v));
}

TEST_CASE("bake: 16-bit maps store their range and decode at load, a malformed encoding is refused", "[bake]") {
  const fs::path dir = test::cli_temp_dir() / "bake-stored";
  fs::create_directories(dir);
  const std::vector<float> values = {-0.25f, 0.5f, 1.75f, 0.0f};
  for (const char* ext : {".png", ".tif"}) {
    const std::string path = (dir / (std::string("d") + ext)).string();
    REQUIRE(write_baked_map(path, 2, 2, {"Y"}, values, {}, true).empty());
    const DisplacementMap m = DisplacementMap::load(path);
    for (int i = 0; i < 4; ++i) CHECK(std::abs(m.texture().load(0, i % 2, i / 2).x - values[std::size_t(i)]) < 1e-4f);
    // Without the stored range a value outside [0, 1] cannot go to a 16-bit file.
    CHECK(write_baked_map(path, 2, 2, {"Y"}, values).find("holds values in [0, 1]") != std::string::npos);
  }
  const std::string bad = (dir / "bad.png").string();
  REQUIRE(write_baked_map(bad, 2, 2, {"Y"}, std::vector<float>{0, 0.5f, 1, 1},
                          {{"ImageDescription", decode_description(2, 1) + "x"}})
              .empty());
  CHECK_THROWS_WITH(DisplacementMap::load(bad), Catch::Contains("is not a valid stored encoding"));
}

TEST_CASE("bake: the displaced frog baked from its own tessellation re-renders the same surface", "[bake][cli]") {
  const fs::path dir = test::cli_temp_dir() / "bake-round-trip";
  fs::create_directories(dir);
  const std::string dense = (dir / "dense.ply").string();
  REQUIRE(test::run_cli("tessellate " + kFrog + " --factor 8 --displacement " + kFrogMap +
                        " --displacement-channel A -o " + dense)
              .exit_code == 0);
  struct Case {
    const char* name;  // a name ending in -png bakes a 16-bit PNG, else an EXR
    std::string bake, render;
    double max, rms;  // the bounds it must meet, relative to the diagonal
  };
  // Measured (factor 8, 512x512): dual vector tangent max 1.4e-3 rms 6.5e-5; scalar 1.2e-3 / 5.9e-5;
  // object space 1.3e-2 / 2.3e-3 (the renderer's mip filtering averages vectors whose direction turns);
  // ray casting, nearest 1.4e-2 / 1.7e-3 (scalar, or a tangent-space vector: the same hits), outward
  // 6.2e-3 / 5.2e-4 (hits on folded layers in creases).
  const Case cases[] = {
      {"dual-vector-tangent", "--kind vector", "--displacement-channel RGB", 3e-3, 1.5e-4},
      // 16-bit PNG: the range is stored in the file and decoded at load (decode_description).
      {"dual-vector-png", "--kind vector", "--displacement-channel RGB", 3e-3, 1.5e-4},
      {"dual-vector-object", "--kind vector --space object", "--displacement-channel RGB --displacement-space object",
       3e-2, 5e-3},
      {"dual-scalar", "--kind scalar", "", 3e-3, 1.5e-4},
      {"raycast-scalar", "--method raycast --kind scalar --max-distance 1", "", 3e-2, 3.5e-3},
      {"raycast-vector", "--method raycast --max-distance 1", "--displacement-channel RGB", 3e-2, 3.5e-3},
      {"raycast-outward", "--method raycast --kind scalar --max-distance 1 --prefer outward", "", 1.5e-2, 1.2e-3},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string name = c.name, ext = name.ends_with("-png") ? ".png" : ".exr";
    // Sanitized: one ray-casting bake stands for the three (test_data.h; the same caster and writer).
    if (test::kSanitized && (name == "raycast-vector" || name == "raycast-outward")) continue;
    const std::string map = (dir / (name + ext)).string();
    const std::string back = (dir / (std::string(c.name) + ".ply")).string();
    const auto r = test::run_cli("bake " + kFrog + " --dense " + dense + " --resolution 512 " + c.bake + " -o " + map);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    REQUIRE(test::run_cli("tessellate " + kFrog + " --factor 8 --displacement " + map + " " + c.render + " -o " + back)
                .exit_code == 0);
    const Distance d = surface_distance(dense, back);
    INFO("max " << d.max << " rms " << d.rms);
    CHECK(d.max < c.max);
    CHECK(d.rms < c.rms);
  }
  // Without the map, the base surface is far from the dense one: the bounds above say something.
  const std::string plain = (dir / "plain.ply").string();
  REQUIRE(test::run_cli("tessellate " + kFrog + " --factor 8 -o " + plain).exit_code == 0);
  CHECK(surface_distance(dense, plain).rms > 5e-3);
}

TEST_CASE("bake: every map is the same bytes for 1 and 3 threads", "[bake][cli][determinism]") {
  const fs::path dir = test::cli_temp_dir() / "bake-threads";
  fs::create_directories(dir);
  const std::string dense = (dir / "dense.ply").string();
  REQUIRE(test::run_cli("tessellate " + kFrog + " --factor 4 --displacement " + kFrogMap +
                        " --displacement-channel A -o " + dense)
              .exit_code == 0);
  for (const char* method : {"dual", "raycast"}) {
    INFO(method);
    std::string bytes[2];
    for (int i = 0; i < 2; ++i) {
      const fs::path out = dir / (std::string(method) + std::to_string(i));
      const auto r = test::run_cli("bake " + kFrog + " --dense " + dense + " --resolution 128 --method " + method +
                                   " --threads " + (i == 0 ? "1" : "3") + " -o " + out.string() + ".exr --normal-map " +
                                   out.string() + "-n.png --ao " + out.string() + "-ao.exr --ao-rays 8");
      INFO(r.err);
      REQUIRE(r.exit_code == 0);
      bytes[i] = slurp_binary(out.string() + ".exr") + slurp_binary(out.string() + "-n.png") +
                 slurp_binary(out.string() + "-ao.exr");
    }
    CHECK(bytes[0].size() > 1000);
    CHECK(bytes[0] == bytes[1]);
  }
}

TEST_CASE("bake: bad input gets one line naming the file", "[bake][cli]") {
  const fs::path dir = test::cli_temp_dir() / "bake-bad";
  fs::create_directories(dir);
  const std::string truncated = (dir / "cut.ply").string();
  std::ofstream(truncated) << "ply\nformat binary_little_endian 1.0\nelement vertex 10\nproperty float x\n"
                              "property float y\nproperty float z\nelement face 1\nproperty list uchar int "
                              "vertex_indices\nend_header\nabc";
  const std::string huge = (dir / "huge.ply").string();
  std::ofstream(huge) << "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n";
  const std::string plain_obj = kData + "/sdk-cages/cube.obj";
  const std::string out = (dir / "out.exr").string();
  const std::pair<std::string, std::string> cases[] = {
      {"bake " + kFrog + " --dense " + (dir / "missing.ply").string() + " -o " + out, "missing.ply: no such file"},
      {"bake " + kFrog + " --dense " + truncated + " -o " + out, "cut.ply: vertex 0: the file ends early"},
      {"bake " + kFrog + " --dense " + huge + " -o " + out, "claims 99999999999 entries"},
      {"bake " + kFrog + " --dense " + plain_obj + " --method dual -o " + out, "--method dual needs"},
      {"bake " + kFrog + " --dense " + plain_obj + " -o " + (dir / "out.jpg").string(),
       "write maps as .exr, .tif or .png"},
      {"bake " + kFrog + " --dense " + plain_obj + " --resolution 0 -o " + out, "--resolution"},
      {"bake " + kFrog + " --dense " + plain_obj + " --max-distance nan -o " + out, "--max-distance"},
      {"bake " + kFrog + " --dense " + plain_obj + " --kind scalar --space object -o " + out, "has no space"},
      {"bake " + kFrog + " --dense " + kFrog + " -o " + kFrog + ".exr --ao " + kFrog + ".exr", "name one file"},
  };
  for (const auto& [args, expected] : cases) {
    const auto r = test::run_cli(args);
    INFO(args << "\n" << r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find(expected) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  CHECK_FALSE(fs::exists(out));
}

}  // namespace tessera
