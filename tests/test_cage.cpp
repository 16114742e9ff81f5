// The OBJ cage reader: every accepted form, OpenSubdiv's tags, one-line errors that name the line, and
// every shipped cage (OpenSubdiv's regression shapes, the DirectX SDK cages).
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

#include "test_data.h"
#include "shaders_cpp/cage/cage_generators.h"
#include "shaders_cpp/cage/cage_obj.h"

namespace fs = std::filesystem;
using namespace tessera;
using tessera::test::data;

namespace {

const char* kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

std::vector<fs::path> obj_files(const std::string& folder) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(TESSERA_TEST_DATA_DIR) / folder))
    if (e.path().extension() == ".obj") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// The message of the CageError that parsing `text` throws ("" when it does not throw).
std::string parse_error(const std::string& text) {
  try {
    (void)parse_obj_cage(text, "t.obj");
  } catch (const CageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("OBJ faces: v, v/vt, v/vt/vn and v//vn forms", "[cage]") {
  const Cage plain = parse_obj_cage(std::string(kSquare) + "vn 0 0 1\nf 1 2 3 4\n", "plain");
  CHECK(plain.name == "plain");
  CHECK(plain.vertex_count() == 4);
  REQUIRE(plain.face_count() == 1);
  CHECK(plain.face_sizes == std::vector<int>{4});
  CHECK(plain.face_offsets == std::vector<int>{0});
  CHECK(plain.face_vertices == std::vector<int>{0, 1, 2, 3});
  CHECK_FALSE(plain.has_uvs());
  CHECK(plain.positions[2] == glm::vec3(1, 1, 0));

  const std::string uvs = std::string(kSquare) + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";
  const Cage a = parse_obj_cage(uvs + "f 1/1 2/2 3/3 4/4\n", "a");
  const Cage b = parse_obj_cage(uvs + "f 1/1/1 2/2/1 3/3/1 4/4/1\n", "b");
  const Cage c = parse_obj_cage(uvs + "f 1//1 2//1 3//1 4//1\n", "c");
  for (const Cage* x : {&a, &b}) {
    CHECK(x->has_uvs());
    CHECK(x->face_uvs == std::vector<int>{0, 1, 2, 3});
    CHECK(x->uvs.size() == 4);
    CHECK(x->uvs[2] == glm::vec2(1, 1));
  }
  CHECK_FALSE(c.has_uvs());
  CHECK(c.face_vertices == plain.face_vertices);
}

TEST_CASE("OBJ negative indices count back from the last element read", "[cage]") {
  const Cage c = parse_obj_cage(
      std::string(kSquare) + "vt 0 0\nvt 1 0\nvt 1 1\nf -4/-3 -3/-2 -2/-1\nv 2 2 0\nvt 2 2\nf -1/-1 -3/-2 -2/-3\n",
      "neg");
  // The two triangles share vertex 2 and no edge: a non-manifold vertex, which the reader splits.
  std::vector<int> read;
  for (int v : c.face_vertices) read.push_back(c.source_vertex(v));
  CHECK(read == std::vector<int>{0, 1, 2, 4, 2, 3});
  CHECK(c.non_manifold.size() == 1);
  CHECK(c.face_uvs == std::vector<int>{0, 1, 2, 3, 2, 1});
}

TEST_CASE("OBJ continuation lines, comments, CRLF and ignored statements", "[cage]") {
  const Cage c = parse_obj_cage(
      "# a comment\r\nmtllib x.mtl\r\no thing\r\ng group\r\ns 1\r\nusemtl m\r\n"
      "v 0 0 0 # trailing comment\r\nv 1 0 0\r\nv \\\r\n 1 1 0\r\nv 0 1 0 1\r\n\r\n"
      "f 1 2 \\\n3 \\\n 4\n",
      "cont");
  CHECK(c.vertex_count() == 4);
  CHECK(c.positions[2] == glm::vec3(1, 1, 0));
  CHECK(c.face_vertices == std::vector<int>{0, 1, 2, 3});
  CHECK(c.warnings.empty());
}

TEST_CASE("OBJ tags: creases, corners, holes and the boundary options", "[cage][tags]") {
  const std::string grid = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n";
  const Cage c = parse_obj_cage(grid +
                                    "t crease 2/1/0 1 4 2.5\n"
                                    "t crease 4/2/0 0 1 1 2 1.0 10\n"
                                    "t crease 4/1/0 3 4 4 5 3\n"
                                    "t corner 2/1/0 0 2 4\n"
                                    "t corner 1/1/0 5 0.5\n"
                                    "t hole 1/0/0 1\n"
                                    "t interpolateboundary 1/0/0 1\n"
                                    "t creasemethod 0/0/1 chaikin\n"
                                    "t smoothtriangles 0/0/1 smooth\n"
                                    "t facevaryinginterpolateboundary 1/0/0 3\n"
                                    "t facevaryingpropagatecorners 1/0/0 1\n",
                                "tags");
  const auto& t = c.tags;
  REQUIRE(t.creases.size() == 5);
  CHECK((t.creases[0].v0 == 1 && t.creases[0].v1 == 4 && t.creases[0].sharpness == 2.5f));
  CHECK((t.creases[1].v0 == 0 && t.creases[1].v1 == 1 && t.creases[1].sharpness == 1.0f));
  CHECK((t.creases[2].v0 == 1 && t.creases[2].v1 == 2 && t.creases[2].sharpness == 10.0f));
  CHECK((t.creases[3].sharpness == 3.0f && t.creases[4].v0 == 4 && t.creases[4].sharpness == 3.0f));
  REQUIRE(t.corners.size() == 3);
  CHECK((t.corners[0].vertex == 0 && t.corners[0].sharpness == 4.0f && t.corners[1].vertex == 2 &&
         t.corners[2].sharpness == 0.5f));
  CHECK(t.holes == std::vector<int>{1});
  CHECK(t.boundary == BoundaryInterpolation::edge_and_corner);
  CHECK(t.crease_method == CreaseMethod::chaikin);
  CHECK(t.smooth_triangles);
  CHECK(t.fvar_boundary == 3);
  CHECK(t.fvar_propagate_corners);
  CHECK(c.warnings.empty());

  // Defaults, and the other two boundary modes.
  const Cage d = parse_obj_cage(grid, "defaults");
  CHECK(d.tags.boundary == BoundaryInterpolation::edge_only);
  CHECK(d.tags.crease_method == CreaseMethod::uniform);
  CHECK_FALSE(d.tags.smooth_triangles);
  CHECK(d.tags.fvar_boundary == 1);
  CHECK(parse_obj_cage(grid + "t interpolateboundary 1/0/0 0\n", "x").tags.boundary == BoundaryInterpolation::none);
  CHECK(parse_obj_cage(grid + "t interpolateboundary 1/0/0 2\n", "x").tags.boundary ==
        BoundaryInterpolation::edge_only);
}

TEST_CASE("OBJ unknown tags and statements are ignored with a warning naming the line", "[cage][tags]") {
  const Cage c = parse_obj_cage(
      std::string(kSquare) + "f 1 2 3 4\nt vertexedit 4/2/3 1 0 1 0 0.5 1 add P value\nl 1 2\n", "hedit.obj");
  REQUIRE(c.warnings.size() == 2);
  CHECK(c.warnings[0] == "hedit.obj:6: tag 'vertexedit' is not supported; ignored");
  CHECK(c.warnings[1].find("hedit.obj:7: statement 'l'") == 0);
}

TEST_CASE("OBJ malformed input: one line naming the file, line and element", "[cage][errors]") {
  const std::string sq = kSquare;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "t.obj: no faces (empty cage)"},
      {sq, "t.obj: no faces"},
      {"v 0 0 x\nf 1 1 1\n", "t.obj:1: bad number 'x' in vertex"},
      {"v 0 0\n", "t.obj:1: vertex needs 3 coordinates"},
      {"v 0 nan 0\n", "t.obj:1: non-finite number 'nan' in vertex"},
      {"v 0 0 inf\n", "t.obj:1: non-finite number 'inf' in vertex"},
      {"v 0 0 1e60\n", "t.obj:1: bad number '1e60' in vertex"},
      {sq + "vt 0 nan\n", "t.obj:5: non-finite number 'nan' in texture coordinate"},
      {sq + "f 1 2\n", "t.obj:5: face 0 has 2 vertices; a face needs at least 3"},
      {sq + "f 1 2 3 4\nf 1 2 9\n", "t.obj:6: face 1 has vertex index 9, but the cage has 4 vertices"},
      {sq + "f 1 2 0\n", "t.obj:5: face 0 has vertex index 0 (OBJ indices start at 1)"},
      {sq + "f 1 2 -5\n", "t.obj:5: face 0 has relative vertex index -5, but only 4 were read so far"},
      {sq + "f 1 2 3a\n", "t.obj:5: bad integer '3a' in vertex"},
      {sq + "vt 0 0\nf 1/1 2/1 3/2\n",
       "t.obj:6: face 0 has texture coordinate index 2, but the cage has 1 texture coordinates"},
      {sq + "vt 0 0\nf 1/1 2 3/1\n", "t.obj:6: face 0 gives texture coordinates for some corners but not all"},
      {sq + "vt 0 0\nf 1/1 2/1 3/1\nf 1 3 4\n",
       "t.obj:7: face 1 has no texture coordinates, but face 0 (line 6) has them"},
      {sq + "vt 0 0\nf 1 2 3\nf 1/1 3/1 4/1\n",
       "t.obj:7: face 1 has texture coordinates, but face 0 (line 6) has none"},
      {sq + "f 1/1/1/1 2 3\n", "t.obj:5: face 0 corner '1/1/1/1' has too many '/'"},
      {sq + "f 1 2 3 4\nt crease 2/1/0 0 9 1\n", "t.obj:6: crease names vertex 9, but the cage has 4 vertices"},
      {sq + "f 1 2 3 4\nt crease 3/1/0 0 1 2 1\n", "t.obj:6: crease takes pairs of vertices"},
      {sq + "f 1 2 3 4\nt crease 2/1/0 0 1 -2\n", "t.obj:6: tag 'crease' has negative sharpness -2"},
      {sq + "f 1 2 3 4\nt crease 2/1/0 0 1\n", "t.obj:6: tag 'crease' declares 3 arguments but has 2"},
      {sq + "f 1 2 3 4\nt corner 1/1/0 4 1\n", "t.obj:6: corner names vertex 4, but the cage has 4 vertices"},
      {sq + "f 1 2 3 4\nt hole 1/0/0 1\n", "t.obj:6: hole names face 1, but the cage has 1 faces"},
      {sq + "f 1 2 3 4\nt interpolateboundary 1/0/0 7\n", "t.obj:6: interpolateboundary must be 0, 1 or 2, got 7"},
      {sq + "f 1 2 3 4\nt creasemethod 0/0/1 sharp\n",
       "t.obj:6: creasemethod must be 'normal' or 'chaikin', got 'sharp'"},
      {sq + "f 1 2 3 4\nt smoothtriangles 1/0/0 1\n",
       "t.obj:6: tag 'smoothtriangles' takes 0/0/1 arguments, got 1/0/0"},
      {sq + "f 1 2 3 4\nt hole 1/0\n", "t.obj:6: tag 'hole' has counts '1/0'"},
      {sq + "f 1 2 3 4\nt\n", "t.obj:6: tag needs a name"},
  };
  for (const auto& [text, expected] : cases) {
    INFO(text);
    const std::string message = parse_error(text);
    CHECK(message.rfind(expected, 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
  }
}

TEST_CASE("OBJ missing file: one line naming it", "[cage][errors]") {
  try {
    (void)load_obj_cage("/nonexistent/cage.obj");
    FAIL("no error");
  } catch (const CageError& e) {
    CHECK(std::string(e.what()) == "/nonexistent/cage.obj: cannot open the file");
  }
}

TEST_CASE("Every OpenSubdiv regression shape and DirectX SDK cage loads", "[cage][data]") {
  const auto shapes = obj_files("osd-shapes");
  const auto sdk = obj_files("sdk-cages");
  CHECK(shapes.size() == 121);  // the folder's 122nd file is the licence
  CHECK(sdk.size() == 8);
  int tags = 0, hedits = 0;
  for (const auto& path : shapes) {
    INFO(path.string());
    const Cage c = load_obj_cage(path.string());
    CHECK(c.face_count() > 0);
    CHECK(c.name == path.string());
    tags += !c.tags.creases.empty() || !c.tags.corners.empty() || !c.tags.holes.empty();
    // Only the hierarchical-edit shapes (their edit tags are not supported) and the non-manifold ones
    // (one line naming the places) warn.
    const bool hedit = path.filename().string().find("hedit") != std::string::npos;
    hedits += hedit;
    CHECK(c.warnings.empty() == (!hedit && c.non_manifold.empty()));
  }
  CHECK(hedits == 5);
  CHECK(tags > 40);
  for (const auto& path : sdk) {
    INFO(path.string());
    const Cage c = load_obj_cage(path.string());
    CHECK(c.face_count() > 0);
    CHECK(c.warnings.empty());
  }
}

TEST_CASE("The monster frog: counts, UVs, and a tag-heavy shape", "[cage][data]") {
  const Cage frog = load_obj_cage(data("sdk-cages/monsterfrog_mapped_00.obj"));
  CHECK(frog.vertex_count() == 1308);
  CHECK(frog.face_count() == 1292);
  CHECK(frog.has_uvs());
  CHECK(frog.uvs.size() == 1705);
  CHECK(frog.face_uvs.size() == frog.face_vertices.size());
  CHECK(std::all_of(frog.face_sizes.begin(), frog.face_sizes.end(), [](int n) { return n == 4; }));

  const Cage car = load_obj_cage(data("osd-shapes/catmark_car.obj"));
  CHECK(car.face_count() == 1575);
  CHECK(car.tags.creases.size() >= 314);
  const Cage holes = load_obj_cage(data("osd-shapes/catmark_hole_test3.obj"));
  CHECK(holes.tags.holes == std::vector<int>{15, 2, 7, 8, 9, 5, 13, 14});
}

namespace {
// The cage read both ways: in parallel chunks and whole.
void check_same_cage(const std::string& text) {
  const Cage a = parse_obj_cage(text, "t.obj", ObjParse::chunks);
  const Cage b = parse_obj_cage(text, "t.obj", ObjParse::serial);
  CHECK(a.positions == b.positions);
  CHECK(a.face_sizes == b.face_sizes);
  CHECK(a.face_offsets == b.face_offsets);
  CHECK(a.face_vertices == b.face_vertices);
  CHECK(a.uvs == b.uvs);
  CHECK(a.face_uvs == b.face_uvs);
  CHECK(a.tags.creases.size() == b.tags.creases.size());
  CHECK(a.tags.boundary == b.tags.boundary);
  CHECK(a.warnings == b.warnings);
}
// The error message of a text read both ways.
std::string error_of(const std::string& text, ObjParse how) {
  try {
    parse_obj_cage(text, "t.obj", how);
  } catch (const CageError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("OBJ text of several megabytes read in parallel chunks equals the whole text's reading", "[cage]") {
  // 32,768 quads with UVs: about 3.4 MB, three chunks.
  const std::string text = format_obj_cage(torus_cage(256, 128, 1.0f, 0.35f));
  REQUIRE(text.size() > 3'000'000);
  check_same_cage(text);
  // What only the whole text's reading handles: a tag, a relative index, an unknown statement, a
  // continued line; each in the last chunk.
  check_same_cage(text + "t interpolateboundary 1/0/0 1\nt crease 2/1/0 0 1 2.5\n");
  check_same_cage(text + "f -1/-1 -2/-2 -3/-3\n");
  check_same_cage(text + "curv 0 1\n");
  check_same_cage(text + "f 1/1 2/2 \\\n 3/3\n");
  // Errors: the same line, the same face number, however far into the text.
  // ("f 1/1 2/2 999999/3" is read in chunks: the range check after the last chunk names its line.)
  for (const std::string bad :
       {"f 1 2 999999\n", "f 1/1 2/2 999999/3\n", "v 1 2 nan\n", "f 1 2\n", "f 1 2 0\n"}) {
    const std::string e = error_of(text + bad, ObjParse::serial);
    CHECK_FALSE(e.empty());
    CHECK(error_of(text + bad, ObjParse::chunks) == e);
  }
  const std::size_t half = text.find('\n', text.size() / 2) + 1;
  const std::string middle = text.substr(0, half) + "f 1/1 2 3\n" + text.substr(half);
  CHECK(error_of(middle, ObjParse::chunks) == error_of(middle, ObjParse::serial));
}
