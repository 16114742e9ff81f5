// glTF cages: the reader against the OBJ sources, poses against closed forms, watertightness in every
// pose, the CLI end to end (render, tessellate --format glb, --frames, material maps) and bad input.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <numbers>
#include <sstream>

#include "cli_runner.h"
#include "shaders_cpp/animation/animation_sampler.h"
#include "shaders_cpp/cage/bounding_box.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/gltf/gltf_cage.h"
#include "test_data.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using test::data;
using test::run_cli;
using Json = nlohmann::json;

const std::string kFrogObj = data("sdk-cages/monsterfrog_mapped_00.obj");
const std::string kFrogMap = data("sdk-cages/monsterfrog.dds");
const std::string kFrog = data("gltf-cages/frog.gltf");
const std::string kSkinned = data("gltf-cages/frog-skinned.gltf");
const std::string kMorph = data("gltf-cages/frog-morph.gltf");

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8 | (unsigned char)bytes[i + 2];
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = (unsigned char)bytes[i] << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8;
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

template <class T>
void append(std::string& buf, const T& v) {
  buf.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// A glTF 2.0 document of `cage` written independently of the reader: vertex i < N is cage vertex i
// (with its first corner's UV), extra (vertex, UV) pairs after, FB_ngon_encoding fans rotated where two
// would start on one index. UVs are stored as float(1 - v) computed in float, as the OBJ path flips
// them, so the two inputs give the same texture coordinates bit for bit.
Json gltf_of(const Cage& c) {
  std::vector<std::pair<int, int>> verts;  // (cage vertex, uv index)
  std::map<std::pair<int, int>, int> index;
  for (int v = 0; v < c.vertex_count(); ++v) verts.push_back({v, -1});
  std::vector<std::vector<int>> faces;
  for (int f = 0; f < c.face_count(); ++f) {
    std::vector<int> face;
    for (int k = 0; k < c.face_sizes[std::size_t(f)]; ++k) {
      const int v = c.face_vertex(f, k),
                t = c.has_uvs() ? c.face_uvs[std::size_t(c.face_offsets[std::size_t(f)] + k)] : 0;
      if (verts[std::size_t(v)].second < 0) verts[std::size_t(v)].second = t;
      const auto key = std::make_pair(v, t);
      if (verts[std::size_t(v)].second == t) {
        face.push_back(v);
      } else {
        auto [it, inserted] = index.emplace(key, int(verts.size()));
        if (inserted) verts.push_back(key);
        face.push_back(it->second);
      }
    }
    faces.push_back(face);
  }
  Json rotated = Json::array();
  std::string buf;
  for (const auto& [v, t] : verts) append(buf, c.positions[std::size_t(v)]);
  const std::size_t uv_offset = buf.size();
  for (const auto& [v, t] : verts) {
    const glm::vec2 uv = c.has_uvs() ? c.uvs[std::size_t(std::max(t, 0))] : glm::vec2(0.0f);
    append(buf, uv.x), append(buf, 1.0f - uv.y);
  }
  const std::size_t index_offset = buf.size();
  std::uint32_t count = 0;
  int previous = -1;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::vector<int> face = faces[f];
    if (face[0] == previous) {
      std::rotate(face.begin(), face.begin() + 1, face.end());
      rotated.push_back({int(f), 1});
    }
    previous = face[0];
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      for (const int i : {face[0], face[k], face[k + 1]}) append(buf, std::uint32_t(i));
      count += 3;
    }
  }
  const std::size_t n = verts.size();
  Json j;
  j["asset"] = {{"version", "2.0"}};
  j["extensionsUsed"] = {"FB_ngon_encoding"};
  j["scene"] = 0;
  j["scenes"] = {{{"nodes", {0}}}};
  j["nodes"] = {{{"mesh", 0}}};
  j["buffers"] = {{{"byteLength", buf.size()}, {"uri", "data:application/octet-stream;base64," + base64(buf)}}};
  j["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", uv_offset}},
                      {{"buffer", 0}, {"byteOffset", uv_offset}, {"byteLength", index_offset - uv_offset}},
                      {{"buffer", 0}, {"byteOffset", index_offset}, {"byteLength", buf.size() - index_offset}}};
  j["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
                    {{"bufferView", 1}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}},
                    {{"bufferView", 2}, {"componentType", 5125}, {"count", count}, {"type", "SCALAR"}}};
  Json prim = {{"attributes", {{"POSITION", 0}}},
               {"indices", 2},
               {"mode", 4},
               {"extensions", {{"FB_ngon_encoding", Json::object()}}},
               {"extras", {{"rotatedFaces", rotated}}}};
  if (c.has_uvs()) prim["attributes"]["TEXCOORD_0"] = 1;
  j["meshes"] = {{{"primitives", {prim}}}};
  return j;
}

void write_json(const fs::path& p, const Json& j) { std::ofstream(p) << j.dump(); }

// The frog posed in closed form (the asset README's rules), in double: skin = rotation about z by the
// bend angle at time t, around joint_bend's rest position, blended by each vertex's weight.
std::vector<glm::dvec3> skinned_frog_closed_form(const CageRig& rig, double t) {
  const double keys[] = {0, 15, 30, 15, 0};
  const double s = std::clamp(t, 0.0, 2.0) / 0.5;
  const int k = std::min(int(s), 3);
  const double degrees = keys[k] + (s - k) * (keys[k + 1] - keys[k]);
  const double a = degrees * std::numbers::pi / 180.0;
  const glm::dvec3 pivot = rig.nodes[1].translation + rig.nodes[2].translation;  // root, then its child
  std::vector<glm::dvec3> out;
  for (std::size_t v = 0; v < rig.bind_positions.size(); ++v) {
    const glm::dvec3 p(rig.bind_positions[v]), d = p - pivot;
    const glm::dvec3 r(std::cos(a) * d.x - std::sin(a) * d.y, std::sin(a) * d.x + std::cos(a) * d.y, d.z);
    const double w = rig.weights[v][1];
    out.push_back((1.0 - w) * p + w * (pivot + r));
  }
  return out;
}

double bbox_diagonal(const std::vector<glm::vec3>& p) {
  const Box3 box = bounding_box(p);
  return glm::length(glm::dvec3(box.hi - box.lo));
}

}  // namespace

TEST_CASE("glTF: the frog cage reads back to the OBJ's vertices, faces and UVs, bit for bit", "[gltf]") {
  const Cage obj = load_obj_cage(kFrogObj);
  const GltfCage g = load_gltf_cage(kFrog);
  CHECK(g.gltf_vertices == 1705);
  REQUIRE(g.cage.vertex_count() == obj.vertex_count());
  for (int v = 0; v < obj.vertex_count(); ++v)
    REQUIRE(std::bit_cast<glm::uvec3>(g.cage.positions[std::size_t(v)]) ==
            std::bit_cast<glm::uvec3>(obj.positions[std::size_t(v)]));
  CHECK(g.cage.face_sizes == obj.face_sizes);
  CHECK(g.cage.face_vertices == obj.face_vertices);  // rotatedFaces undone: the same start corners
  REQUIRE(g.cage.has_uvs());
  CHECK(g.cage.uv_v_down);
  for (std::size_t c = 0; c < obj.face_uvs.size(); ++c) {
    const glm::vec2 a = obj.uvs[std::size_t(obj.face_uvs[c])], b = g.cage.uvs[std::size_t(g.cage.face_uvs[c])];
    REQUIRE(a.x == b.x);
    REQUIRE(std::abs((1.0f - a.y) - b.y) <= 6e-8f);  // the file holds 1 - v rounded once
  }
  CHECK(g.rig == nullptr);  // nothing moves

  // The pyramid: triangles and a quad from one fan-encoded primitive.
  const GltfCage p = load_gltf_cage(data("gltf-cages/pyramid.gltf"));
  const Cage po = load_obj_cage(data("osd-shapes/catmark_pyramid.obj"));
  CHECK(p.cage.face_sizes == po.face_sizes);
  CHECK(p.cage.face_vertices == po.face_vertices);
}

TEST_CASE("glTF: a damaged file is refused in one short line naming it, without its base64", "[gltf][cli]") {
  const fs::path dir = test::cli_temp_dir() / "gltf-damaged";
  fs::create_directories(dir);
  std::string text;
  {
    std::ifstream in(kFrog, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  // Cut in the middle of the buffer's data URI (the file ends there), and a URI cut short in valid JSON.
  const fs::path cut = dir / "cut.gltf", short_uri = dir / "short.gltf";
  std::ofstream(cut, std::ios::binary) << text.substr(0, text.size() / 2);
  nlohmann::json j = nlohmann::json::parse(text);
  const std::string uri = j["buffers"][0]["uri"].get<std::string>();
  j["buffers"][0]["uri"] = uri.substr(0, uri.size() / 2);
  std::ofstream(short_uri) << j.dump();
  for (const auto& [f, said] : {std::pair(cut, std::string(": not a readable glTF 2.0 file (")),
                                std::pair(short_uri, std::string(": buffers[0]: its base64 data URI is cut short ("))}) {
    const auto r = run_cli("render " + f.string() + " --resolution 32x32 -o " + (dir / "x.png").string());
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(f.string() + said) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.size() < 300);
    CHECK(r.err.find("base64,") == std::string::npos);  // the payload is not quoted
  }
}

TEST_CASE("glTF: a triangle mesh without FB_ngon_encoding is a triangle cage, welded on exact bits", "[gltf]") {
  // Khronos' Box: 24 vertices (split by normals), 12 triangles, under a rotating node.
  const GltfCage box = load_gltf_cage(data("gltf-samples/Box.gltf"));
  CHECK(box.gltf_vertices == 24);
  CHECK(box.cage.vertex_count() == 8);
  CHECK(box.cage.face_count() == 12);
  CHECK(std::all_of(box.cage.face_sizes.begin(), box.cage.face_sizes.end(), [](int n) { return n == 3; }));
  const Topology t(box.cage);  // a closed, consistently oriented triangle cage
  for (int e = 0; e < t.edge_count(); ++e) CHECK(!t.is_boundary_edge(e));
  const auto r = run_cli("render " + data("gltf-samples/Box.gltf") + " --scheme gregory --resolution 160x120 -o " +
                         (test::cli_temp_dir() / "box.png").string());
  CHECK(r.exit_code == 0);
}

TEST_CASE("glTF: OBJ and glTF inputs of one cage render and tessellate to the same bytes", "[gltf][cli]") {
  const fs::path dir = test::cli_temp_dir();
  for (const std::string scheme : {"gregory", "pn", "exact"}) {
    const auto a =
        run_cli("render " + kFrog + " --scheme " + scheme + " --resolution 480x270 -o " + (dir / "g.png").string());
    const auto b =
        run_cli("render " + kFrogObj + " --scheme " + scheme + " --resolution 480x270 -o " + (dir / "o.png").string());
    REQUIRE(a.exit_code == 0);
    REQUIRE(b.exit_code == 0);
    CHECK(bytes_of(dir / "g.png") == bytes_of(dir / "o.png"));
  }
  // Displaced: a glTF whose UVs are float(1 - v) as the OBJ path computes them gives the same bytes.
  write_json(dir / "frog-float-uv.gltf", gltf_of(load_obj_cage(kFrogObj)));
  const std::string maps = " --displacement " + kFrogMap + " --displacement-channel A --resolution 480x270";
  REQUIRE(
      run_cli("render " + (dir / "frog-float-uv.gltf").string() + maps + " -o " + (dir / "g.png").string()).exit_code ==
      0);
  REQUIRE(run_cli("render " + kFrogObj + maps + " -o " + (dir / "o.png").string()).exit_code == 0);
  CHECK(bytes_of(dir / "g.png") == bytes_of(dir / "o.png"));

  // tessellate --format glb: the same surface, and a file our own reader (tinygltf) accepts.
  REQUIRE(run_cli("tessellate " + kFrog + " --factor 3 -o " + (dir / "g.glb").string()).exit_code == 0);
  REQUIRE(run_cli("tessellate " + kFrogObj + " --factor 3 --format glb -o " + (dir / "o.bin").string()).exit_code == 0);
  CHECK(bytes_of(dir / "g.glb") == bytes_of(dir / "o.bin"));
  const GltfCage out = load_gltf_cage((dir / "g.glb").string());
  CHECK(out.cage.face_count() == 1292 * 18);  // factor 3: 18 triangles per quad
  const auto w = run_cli("tessellate " + (dir / "g.glb").string() + " --scheme flat --factor 1 --check-watertight");
  CHECK(w.exit_code == 0);
  CHECK(w.out.find(" 0 crack edges") != std::string::npos);
}

TEST_CASE("glTF: skins and morph targets pose the cage as their closed forms say", "[gltf]") {
  const GltfCage g = load_gltf_cage(kSkinned);
  REQUIRE(g.rig);
  const CageRig& rig = *g.rig;
  REQUIRE(rig.animations.size() == 1);
  CHECK(rig.animations[0].end == 2.0f);
  const double diagonal = bbox_diagonal(g.cage.positions);
  for (const double t : {0.0, 0.3, 1.0, 1.6, 2.0, 5.0}) {
    const std::vector<glm::vec3> posed = pose_positions(rig, pose_at(rig, 0, t));
    const std::vector<glm::dvec3> expected = skinned_frog_closed_form(rig, t);
    double worst = 0.0;
    for (std::size_t v = 0; v < posed.size(); ++v)
      worst = std::max(worst, glm::length(glm::dvec3(posed[v]) - expected[v]));
    INFO("t = " << t);
    CHECK(worst <= 2e-6 * diagonal);
  }
  // The bend moves the far end by about 13 units at t = 1 (the asset's README).
  const std::vector<glm::vec3> bent = pose_positions(rig, pose_at(rig, 0, 1.0));
  double moved = 0.0;
  for (std::size_t v = 0; v < bent.size(); ++v)
    moved = std::max(moved, double(glm::length(bent[v] - g.cage.positions[v])));
  CHECK(moved == Approx(13.18).margin(0.01));

  const GltfCage m = load_gltf_cage(kMorph);
  REQUIRE(m.rig);
  REQUIRE(m.rig->target_count() == 1);
  for (const double t : {0.25, 1.0, 1.5}) {
    const double weight = t <= 1.0 ? t : 2.0 - t;
    const std::vector<glm::vec3> posed = pose_positions(*m.rig, pose_at(*m.rig, 0, t));
    double worst = 0.0;
    for (std::size_t v = 0; v < posed.size(); ++v) {
      const glm::dvec3 e = glm::dvec3(m.rig->bind_positions[v]) + weight * glm::dvec3(m.rig->target_deltas[0][v]);
      worst = std::max(worst, glm::length(glm::dvec3(posed[v]) - e));
    }
    CHECK(worst <= 1e-6 * diagonal);
  }
}

TEST_CASE("glTF: STEP, LINEAR and CUBICSPLINE samplers follow the spec", "[gltf]") {
  CageRig rig;
  rig.nodes.resize(1);
  rig.node_order = {0};
  Animation a;
  AnimationChannel ch;
  ch.node = 0, ch.path = AnimationPath::translation, ch.width = 3;
  ch.times = {1.0f, 3.0f};
  ch.values = {0, 0, 0, 4, 8, -2};
  ch.interpolation = Interpolation::step;
  a.channels = {ch};
  rig.animations = {a};
  CHECK(animate_nodes(rig, 0, 2.9)[0].translation == glm::dvec3(0.0));
  CHECK(animate_nodes(rig, 0, 3.5)[0].translation == glm::dvec3(4, 8, -2));
  rig.animations[0].channels[0].interpolation = Interpolation::linear;
  CHECK(animate_nodes(rig, 0, 2.0)[0].translation == glm::dvec3(2, 4, -1));
  CHECK(animate_nodes(rig, 0, 0.0)[0].translation == glm::dvec3(0.0));  // before the first key
  // Cubic: keys (in, value, out); zero tangents give the smoothstep between the values.
  AnimationChannel& c = rig.animations[0].channels[0];
  c.interpolation = Interpolation::cubic_spline;
  c.values = {0, 0, 0, 0, 0, 0, 0, 0, 0, /* key 1 */ 0, 0, 0, 4, 8, -2, 0, 0, 0};
  const glm::dvec3 mid = animate_nodes(rig, 0, 1.5)[0].translation;  // s = 0.25: 3s^2 - 2s^3 = 0.15625
  CHECK(mid.x == Approx(4 * 0.15625));
  // An out-tangent of key 0 bends the curve: d = 2 s, out = (1, 0, 0) adds d (s^3 - 2 s^2 + s) = 0.28125.
  c.values[6] = 1.0f;
  CHECK(animate_nodes(rig, 0, 1.5)[0].translation.x == Approx(4 * 0.15625 + 2 * (0.015625 - 0.125 + 0.25)));
  // Rotation LINEAR is a slerp along the shorter arc: halfway between 0 and 90 degrees about z is 45.
  AnimationChannel r;
  r.node = 0, r.path = AnimationPath::rotation, r.width = 4, r.interpolation = Interpolation::linear;
  r.times = {0.0f, 1.0f};
  const float h = std::sqrt(0.5f);
  r.values = {0, 0, 0, 1, 0, 0, h, h};
  rig.animations[0].channels = {r};
  const glm::dquat q = animate_nodes(rig, 0, 0.5)[0].rotation;
  CHECK(q.z == Approx(std::sin(std::numbers::pi / 8)));
  CHECK(q.w == Approx(std::cos(std::numbers::pi / 8)));
  r.values = {0, 0, 0, 1, 0, 0, -h, -h};  // the same rotation, negated: still the short way
  rig.animations[0].channels = {r};
  CHECK(std::abs(animate_nodes(rig, 0, 0.5)[0].rotation.z) == Approx(std::sin(std::numbers::pi / 8)));
}

TEST_CASE("glTF: the skinned, displaced frog is watertight in every pose, the same bytes on any thread count",
          "[gltf][cli]") {
  const std::string maps = " --displacement " + kFrogMap + " --displacement-channel A";
  for (const char* t : {"0.2", "1", "1.7"})
    for (const char* scheme : {"gregory", "exact", "adaptive"}) {
      // Sanitized: one pose per scheme (test_data.h), each scheme's posing path still runs.
      if (test::kSanitized && std::string(t) != (std::string(scheme) == "gregory" ? "0.2"
                                                 : scheme[1] == 'x'               ? "1"
                                                                                  : "1.7"))
        continue;
      const auto r = run_cli(std::string("tessellate ") + kSkinned + " --time " + t + " --scheme " + scheme +
                             " --factor 5 --partitioning fractional_odd --check-watertight" + maps);
      INFO(t << " " << scheme << ": " << r.out << r.err);
      CHECK(r.exit_code == 0);
      CHECK(r.out.find(" 0 crack edges, 0 non-manifold edges") != std::string::npos);
    }
  const auto m = run_cli("tessellate " + kMorph +
                         " --time 0.7 --lod screen --camera-position 10,30,60 "
                         "--partitioning fractional_even --check-watertight" +
                         maps);
  CHECK(m.exit_code == 0);
  const fs::path dir = test::cli_temp_dir();
  std::string first;
  for (const char* threads : {"1", "2", "16"}) {
    const auto r = run_cli(std::string("render ") + kSkinned + " --time 0.8 --lod screen --resolution 400x300" + maps +
                           " --threads " + threads + " -o " + (dir / "t.png").string());
    REQUIRE(r.exit_code == 0);
    const std::string bytes = bytes_of(dir / "t.png");
    if (first.empty()) first = bytes;
    CHECK(bytes == first);
  }
}

TEST_CASE("glTF: a posed frame equals the same pose written as OBJ, within float round-off", "[gltf][cli]") {
  const GltfCage g = load_gltf_cage(kSkinned);
  Cage posed = g.cage;
  const std::vector<glm::dvec3> expected = skinned_frog_closed_form(*g.rig, 1.0);
  for (std::size_t v = 0; v < expected.size(); ++v) posed.positions[v] = glm::vec3(expected[v]);
  const fs::path dir = test::cli_temp_dir();
  std::ofstream(dir / "posed.obj") << format_obj_cage(posed);
  REQUIRE(
      run_cli("tessellate " + (dir / "posed.obj").string() + " --factor 4 -o " + (dir / "a.glb").string()).exit_code ==
      0);
  REQUIRE(run_cli("tessellate " + kSkinned + " --time 1 --factor 4 -o " + (dir / "b.glb").string()).exit_code == 0);
  const GltfCage a = load_gltf_cage((dir / "a.glb").string()), b = load_gltf_cage((dir / "b.glb").string());
  REQUIRE(a.cage.vertex_count() == b.cage.vertex_count());
  REQUIRE(a.cage.face_vertices == b.cage.face_vertices);
  double worst = 0.0;
  for (int v = 0; v < a.cage.vertex_count(); ++v)
    worst = std::max(worst, double(glm::length(a.cage.positions[std::size_t(v)] - b.cage.positions[std::size_t(v)])));
  CHECK(worst <= 2e-6 * bbox_diagonal(a.cage.positions));
}

TEST_CASE("glTF: render --frames writes a sequence whose frames equal single renders", "[gltf][cli]") {
  const fs::path dir = test::cli_temp_dir() / "frames";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto r = run_cli("render " + kSkinned + " --frames 3 --fps 2 --resolution 320x180 --json -o " +
                         (dir / "f_%03d.png").string());
  REQUIRE(r.exit_code == 0);
  CHECK(fs::exists(dir / "f_000.png"));
  CHECK(fs::exists(dir / "f_002.png"));
  // The sequence keeps the camera that framed its first pose: a single render with that camera.
  const auto camera = nlohmann::json::parse(r.out)["images"][1]["camera"];
  const auto vec = [](const nlohmann::json& v) {
    std::ostringstream s;
    s << std::setprecision(9) << v[0].get<double>() << "," << v[1].get<double>() << "," << v[2].get<double>();
    return s.str();
  };
  REQUIRE(run_cli("render " + kSkinned + " --time 0.5 --resolution 320x180 --camera-position " +
                  vec(camera["position"]) + " --camera-target " + vec(camera["target"]) + " -o " +
                  (dir / "one.png").string())
              .exit_code == 0);
  CHECK(bytes_of(dir / "f_001.png") == bytes_of(dir / "one.png"));
  CHECK(bytes_of(dir / "f_000.png") != bytes_of(dir / "f_001.png"));
  CHECK(
      run_cli("render " + kSkinned + " --frames 1 --resolution 32x18 -o " + (dir / "one_%d.png").string()).exit_code ==
      0);
  CHECK(fs::exists(dir / "one_0.png"));
  // Refused before anything is written: a static asset, a path without a frame field.
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto s = run_cli("render " + kFrog + " --frames 3 -o " + (dir / "f_%d.png").string());
  CHECK(s.exit_code == 2);
  CHECK(s.err.find("not animated") != std::string::npos);
  const auto p = run_cli("render " + kSkinned + " --frames 3 -o " + (dir / "f.png").string());
  CHECK(p.exit_code == 2);
  CHECK(p.err.find("%04d") != std::string::npos);
  CHECK(fs::is_empty(dir));
}

TEST_CASE("glTF: material maps (external and embedded) displace as the same map given on the command line",
          "[gltf][cli]") {
  const fs::path dir = test::cli_temp_dir() / "material";
  fs::create_directories(dir);
  // A small height map (R) with a ramp and a bump, written as PNG.
  const int n = 64;
  std::vector<std::uint8_t> px(std::size_t(n * n));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      px[std::size_t(y * n + x)] = std::uint8_t((x * 3 + y * 2 + ((x / 8 + y / 8) % 2) * 60) % 256);
  {
    auto out = OIIO::ImageOutput::create((dir / "height.png").string());
    REQUIRE(out);
    REQUIRE(out->open((dir / "height.png").string(), OIIO::ImageSpec(n, n, 1, OIIO::TypeDesc::UINT8)));
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
    out->close();
  }
  Json j = gltf_of(load_obj_cage(kFrogObj));
  j["meshes"][0]["primitives"][0]["material"] = 0;
  j["materials"] = {{{"extensions",
                      {{"KHR_materials_displacement",
                        {{"displacementGeometryTexture", {{"index", 0}}},
                         {"displacementGeometryFactor", 2.5},
                         {"displacementGeometryOffset", -1.0}}}}}}};
  j["textures"] = {{{"source", 0}}};
  j["images"] = {{{"uri", "height.png"}}};
  write_json(dir / "external.gltf", j);
  j["images"] = {{{"uri", "data:image/png;base64," + base64(bytes_of(dir / "height.png"))}, {"mimeType", "image/png"}}};
  write_json(dir / "embedded.gltf", j);
  const std::string opts = " --resolution 320x180 --normal-map derived";
  const auto cli = run_cli("render " + kFrogObj + opts + " --displacement " + (dir / "height.png").string() +
                           " --displacement-channel R --displacement-scale 2.5 --displacement-bias -1 -o " +
                           (dir / "cli.png").string());
  REQUIRE(cli.exit_code == 0);
  for (const char* name : {"external", "embedded"}) {
    const auto r = run_cli("render " + (dir / (std::string(name) + ".gltf")).string() + opts + " -o " +
                           (dir / (std::string(name) + ".png")).string());
    INFO(name << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(bytes_of(dir / (std::string(name) + ".png")) == bytes_of(dir / "cli.png"));
  }
  // --displacement none turns the material's map off; --displacement-scale replaces its factor.
  REQUIRE(run_cli("render " + (dir / "external.gltf").string() + opts + " --displacement none -o " +
                  (dir / "none.png").string())
              .exit_code == 2);
  REQUIRE(run_cli("render " + (dir / "external.gltf").string() + " --resolution 320x180 --displacement none -o " +
                  (dir / "none.png").string())
              .exit_code == 0);
  REQUIRE(run_cli("render " + kFrogObj + " --resolution 320x180 -o " + (dir / "plain.png").string()).exit_code == 0);
  CHECK(bytes_of(dir / "none.png") == bytes_of(dir / "plain.png"));
  // A missing image is an error naming it.
  j["images"] = {{{"uri", "missing.png"}}};
  write_json(dir / "missing.gltf", j);
  const auto m =
      run_cli("render " + (dir / "missing.gltf").string() + " --resolution 64x64 -o " + (dir / "x.png").string());
  CHECK(m.exit_code == 1);
  CHECK(m.err.find("missing.png") != std::string::npos);
  CHECK(m.err.find("material 0") != std::string::npos);
}

TEST_CASE("glTF: bad files get one line naming the file and the element, never a crash", "[gltf][cli]") {
  const fs::path dir = test::cli_temp_dir() / "bad";
  fs::create_directories(dir);
  const Json good = gltf_of(load_obj_cage(data("osd-shapes/catmark_cube.obj")));
  struct Case {
    std::string name, expect;
    std::function<void(Json&)> edit;
  };
  const std::vector<Case> cases = {
      {"truncated", "not a readable glTF", nullptr},
      {"missing-buffer", "nowhere.bin", [](Json& j) { j["buffers"][0]["uri"] = "nowhere.bin"; }},
      {"index-range", "index 2 is 3, but POSITION has 3 elements",
       [](Json& j) { j["accessors"][0]["count"] = 3, j["accessors"][1]["count"] = 3; }},
      {"count-mismatch", "TEXCOORD_0 and POSITION have different counts",
       [](Json& j) { j["accessors"][1]["count"] = 3; }},
      {"accessor-past-end", "reads past the end", [](Json& j) { j["accessors"][1]["byteOffset"] = 48; }},
      {"no-triangles", "no triangles", [](Json& j) { j["meshes"][0]["primitives"][0]["mode"] = 0; }},
      {"required-extension", "requires KHR_draco_mesh_compression",
       [](Json& j) { j["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }},
      {"bad-node", "node 0: child 7 does not exist", [](Json& j) { j["nodes"][0]["children"] = {7}; }},
      {"nan-scale", "not finite",
       [](Json& j) {
         j["nodes"][0]["scale"] = {1e308, 1e308, 1e308};
       }},
  };
  for (const Case& c : cases) {
    const fs::path p = dir / (c.name + ".gltf");
    if (c.edit) {
      Json j = good;
      c.edit(j);
      write_json(p, j);
    } else {
      std::ofstream(p) << good.dump().substr(0, 200);
    }
    const auto r = run_cli("render " + p.string() + " --resolution 64x64 -o " + (dir / "x.png").string());
    INFO(c.name << ": " << r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(p.string()) != std::string::npos);
    CHECK(r.err.find(c.expect) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(!fs::exists(dir / "x.png"));
  }
  // A NaN position (written as raw bits into the buffer) names the accessor.
  {
    Cage cube = load_obj_cage(data("osd-shapes/catmark_cube.obj"));
    cube.positions[3].y = std::numeric_limits<float>::quiet_NaN();
    write_json(dir / "nan.gltf", gltf_of(cube));
    const auto r = run_cli("tessellate " + (dir / "nan.gltf").string() + " --check-watertight");
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("accessor 0 (POSITION)") != std::string::npos);
    CHECK(r.err.find("element 3 is not finite") != std::string::npos);
  }
  // Options that do not apply, or name nothing.
  CHECK(run_cli("render " + kFrogObj + " --mesh frog -o " + (dir / "x.png").string()).exit_code == 2);
  const auto mesh = run_cli("render " + kFrog + " --mesh nothing -o " + (dir / "x.png").string());
  CHECK(mesh.exit_code == 1);
  CHECK(mesh.err.find("no mesh or node named 'nothing'") != std::string::npos);
  const auto anim = run_cli("render " + kSkinned + " --animation walk -o " + (dir / "x.png").string());
  CHECK(anim.exit_code == 2);
  CHECK(anim.err.find("0 (bend)") != std::string::npos);
  CHECK(run_cli("render " + kFrog + " --time 1 -o " + (dir / "x.png").string()).exit_code == 2);
  CHECK(run_cli("render " + kSkinned + " --time nan -o " + (dir / "x.png").string()).exit_code == 2);
  CHECK(!fs::exists(dir / "x.png"));
}

TEST_CASE("glTF: skin weights that do not sum to one are normalised with a warning, joints beyond the skin fail",
          "[gltf]") {
  const fs::path dir = test::cli_temp_dir();
  Json j = Json::parse(bytes_of(kSkinned));
  // Scale the weights accessor's data: rewrite it as normalised unsigned bytes summing to 200 %.
  const int weights = j["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"];
  const int count = j["accessors"][weights]["count"];
  std::string buf;
  for (int i = 0; i < count; ++i) append(buf, std::array<std::uint8_t, 4>{255, 255, 0, 0});
  const int view = int(j["bufferViews"].size());
  j["buffers"].push_back({{"byteLength", buf.size()}, {"uri", "data:application/octet-stream;base64," + base64(buf)}});
  j["bufferViews"].push_back({{"buffer", int(j["buffers"].size()) - 1}, {"byteLength", buf.size()}});
  j["accessors"].push_back(
      {{"bufferView", view}, {"componentType", 5121}, {"normalized", true}, {"count", count}, {"type", "VEC4"}});
  j["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = int(j["accessors"].size()) - 1;
  write_json(dir / "heavy.gltf", j);
  const GltfCage g = load_gltf_cage((dir / "heavy.gltf").string());
  REQUIRE(g.rig);
  CHECK(g.rig->weights[0][0] == 0.5f);
  CHECK(g.rig->weights[0][1] == 0.5f);
  REQUIRE(!g.cage.warnings.empty());
  CHECK(g.cage.warnings[0].find("do not sum to 1; normalised") != std::string::npos);
  const auto r =
      run_cli("render " + (dir / "heavy.gltf").string() + " --resolution 64x64 -o " + (dir / "h.png").string());
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("warning:") != std::string::npos);

  j["skins"][0]["joints"] = {1};  // the file's joints index 0 and 1
  j["skins"][0].erase("inverseBindMatrices");
  write_json(dir / "joints.gltf", j);
  CHECK_THROWS_WITH(load_gltf_cage((dir / "joints.gltf").string()),
                    Catch::Contains("names joint 1, but skin 0 has 1 joints"));
}

}  // namespace tessera

namespace tessera {

TEST_CASE("glTF: accuracy, scene files and external buffers work on posed assets", "[gltf][cli]") {
  const fs::path dir = test::cli_temp_dir() / "posed";
  fs::create_directories(dir);
  // accuracy compares the posed surface with the exact limit of the posed cage.
  const auto a = run_cli("accuracy " + kSkinned + " --time 1 --factor 6 --json");
  REQUIRE(a.exit_code == 0);
  const Json acc = Json::parse(a.out);
  CHECK(acc["max_relative"].get<double>() < 0.01);
  // A scene file naming the asset, its animation and a time renders what the command line does.
  write_json(
      dir / "scene.json",
      {{"tessera_scene", 1}, {"asset", kSkinned}, {"time", 0.75}, {"animation", "bend"}, {"resolution", {320, 180}}});
  REQUIRE(run_cli("render --scene " + (dir / "scene.json").string() + " -o " + (dir / "s.png").string()).exit_code ==
          0);
  REQUIRE(
      run_cli("render " + kSkinned + " --time 0.75 --resolution 320x180 -o " + (dir / "c.png").string()).exit_code ==
      0);
  CHECK(bytes_of(dir / "s.png") == bytes_of(dir / "c.png"));
  const auto printed = run_cli("render " + kSkinned + " --time 0.75 --animation 0 --print-scene -");
  REQUIRE(printed.exit_code == 0);
  CHECK(Json::parse(printed.out)["time"] == 0.75);
  CHECK(Json::parse(printed.out)["animation"] == "0");
  // The same cube with its buffer in an external file (a URI with an escaped space).
  Json j = gltf_of(load_obj_cage(data("osd-shapes/catmark_cube.obj")));
  const std::string uri = j["buffers"][0]["uri"];
  std::string raw;
  {
    // Decode our own base64 back to bytes.
    const std::string b64 = uri.substr(uri.find(',') + 1);
    auto value = [](char c) -> int {
      if (c >= 'A' && c <= 'Z') return c - 'A';
      if (c >= 'a' && c <= 'z') return c - 'a' + 26;
      if (c >= '0' && c <= '9') return c - '0' + 52;
      return c == '+' ? 62 : 63;
    };
    for (std::size_t i = 0; i + 3 < b64.size(); i += 4) {
      const int n = value(b64[i]) << 18 | value(b64[i + 1]) << 12 | (b64[i + 2] == '=' ? 0 : value(b64[i + 2]) << 6) |
                    (b64[i + 3] == '=' ? 0 : value(b64[i + 3]));
      raw += char(n >> 16);
      if (b64[i + 2] != '=') raw += char((n >> 8) & 255);
      if (b64[i + 3] != '=') raw += char(n & 255);
    }
  }
  std::ofstream(dir / "cube data.bin", std::ios::binary) << raw;
  j["buffers"][0]["uri"] = "cube%20data.bin";
  write_json(dir / "cube-external.gltf", j);
  const GltfCage external = load_gltf_cage((dir / "cube-external.gltf").string());
  const Cage obj = load_obj_cage(data("osd-shapes/catmark_cube.obj"));
  CHECK(external.cage.positions == obj.positions);
  CHECK(external.cage.face_vertices == obj.face_vertices);
}

TEST_CASE("glTF: eight influences through JOINTS_1 and WEIGHTS_1 skin as the sum of both sets", "[gltf]") {
  // The skinned frog with its two influences moved into the second set (JOINTS_1/WEIGHTS_1), the
  // first set zero: the same pose, to the bit (influences are summed in order and zeros are skipped).
  Json j = Json::parse(bytes_of(kSkinned));
  Json& attributes = j["meshes"][0]["primitives"][0]["attributes"];
  const int count = j["accessors"][int(attributes["POSITION"])]["count"];
  std::string joints, weights;
  for (int i = 0; i < count; ++i) {
    append(joints, std::array<std::uint8_t, 4>{0, 0, 0, 0});
    append(weights, std::array<float, 4>{0, 0, 0, 0});
  }
  j["buffers"].push_back({{"byteLength", joints.size() + weights.size()},
                          {"uri", "data:application/octet-stream;base64," + base64(joints + weights)}});
  const int buffer = int(j["buffers"].size()) - 1, view = int(j["bufferViews"].size());
  j["bufferViews"].push_back({{"buffer", buffer}, {"byteLength", joints.size()}});
  j["bufferViews"].push_back({{"buffer", buffer}, {"byteOffset", joints.size()}, {"byteLength", weights.size()}});
  const int first = int(j["accessors"].size());
  j["accessors"].push_back({{"bufferView", view}, {"componentType", 5121}, {"count", count}, {"type", "VEC4"}});
  j["accessors"].push_back({{"bufferView", view + 1}, {"componentType", 5126}, {"count", count}, {"type", "VEC4"}});
  attributes["JOINTS_1"] = attributes["JOINTS_0"];
  attributes["WEIGHTS_1"] = attributes["WEIGHTS_0"];
  attributes["JOINTS_0"] = first;
  attributes["WEIGHTS_0"] = first + 1;
  const fs::path path = test::cli_temp_dir() / "eight.gltf";
  write_json(path, j);
  const GltfCage a = load_gltf_cage(kSkinned), b = load_gltf_cage(path.string());
  REQUIRE(b.rig);
  CHECK(b.rig->weights[100][5] == a.rig->weights[100][1]);
  const auto pa = pose_positions(*a.rig, pose_at(*a.rig, 0, 1.0)), pb = pose_positions(*b.rig, pose_at(*b.rig, 0, 1.0));
  CHECK(pa == pb);
}

}  // namespace tessera

namespace tessera {

TEST_CASE("SimpleMorph at t = 1.5 under gregory has no dark sliver: corners with one face get a normal",
          "[gltf][cli]") {
  // The morph poses the triangle (0,0,0), (1,0,0), (1,2,0) at t = 1.5. Each corner is a vertex with one
  // face, whose two patch edges leave along the one boundary tangent: the derivatives there are
  // parallel and their cross product was round-off, pointing away at the right angle's corner (a
  // dark sliver, 180 degrees against the exact limit). The pose was not at fault: the same triangle as
  // a static OBJ draws the same bytes. Now the normal there is the patch's a step inside it.
  const fs::path dir = test::cli_temp_dir() / "morph-fold";
  fs::create_directories(dir);
  const std::string morph = test::data("gltf-samples/SimpleMorph.gltf");
  const std::string camera = " --resolution 320x180 --camera-position 0.5,0.9,4 --camera-target 0.5,0.9,0 -o ";
  {
    std::ofstream obj(dir / "posed.obj");
    obj << "v 0 0 0\nv 1 0 0\nv 1 2 0\nf 1 2 3\n";
  }
  REQUIRE(run_cli("-q render " + morph + " --time 1.5" + camera + (dir / "morph.png").string()).exit_code == 0);
  REQUIRE(run_cli("-q render " + (dir / "posed.obj").string() + camera + (dir / "posed.png").string()).exit_code == 0);
  CHECK(bytes_of(dir / "morph.png") == bytes_of(dir / "posed.png"));
  for (const char* scheme : {"gregory", "bspline"}) {
    const auto accuracy =
        run_cli("accuracy " + (dir / "posed.obj").string() + " --scheme " + scheme + " --factor 16 --json");
    REQUIRE(accuracy.exit_code == 0);
    INFO(scheme);
    CHECK(nlohmann::json::parse(accuracy.out)["max_normal_degrees"].get<double>() < 1.0);  // was 180
  }
}

}  // namespace tessera
