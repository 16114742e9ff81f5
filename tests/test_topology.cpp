// Half-edge topology and topology combinations: conventions and invariants on every valid shipped cage,
// one-line validation errors (hand-made cages and OpenSubdiv's non-manifold shapes), and combination
// counts on known meshes.
#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "test_data.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/cage/topology_combinations.h"

namespace fs = std::filesystem;
using namespace tessera;
using tessera::test::data;

namespace {

std::vector<fs::path> all_cages() {
  std::vector<fs::path> files;
  for (const char* folder : {"osd-shapes", "sdk-cages"})
    for (const auto& e : fs::directory_iterator(fs::path(TESSERA_TEST_DATA_DIR) / folder))
      if (e.path().extension() == ".obj") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// The shapes with non-manifold places, and the first place `analyze` names. OpenSubdiv accepts them;
// the cage reader splits them into manifold pieces joined by infinitely sharp edges and corners.
const std::map<std::string, std::string> kNonManifold = {
    {"catmark_fan.obj", "non-manifold vertex 9 (0-based): 7 faces (0, 1, 3, 6, 7, 10, 11) in 3 fans; keeps the crease rule"},
    {"catmark_nonman_edge100.obj", "non-manifold edge between vertices 200 and 201 (0-based): 100 faces (0, 1, 2, 3, 4, 5, 6, 7, ..., 99)"},
    {"catmark_nonman_edges.obj", "non-manifold vertex 9 (0-based): 7 faces (0, 1, 3, 6, 7, 10, 11) in 3 fans"},
    {"catmark_nonman_quadpole8.obj", "face 1 uses vertex 4 (0-based) more than once"},
    {"catmark_nonman_quadpole64.obj", "face 1 uses vertex 4 (0-based) more than once"},
    {"catmark_nonman_quadpole360.obj", "face 1 uses vertex 4 (0-based) more than once"},
    {"catmark_nonman_verts.obj", "non-manifold vertex 1 (0-based): 3 faces (0, 1, 2) in 2 fans; drawn as an infinitely sharp corner"},
    {"catmark_val2_nonman.obj", "non-manifold edge between vertices 0 and 1 (0-based): 4 faces (0, 1, 2, 3); drawn infinitely sharp"},
    {"loop_nonman_edge100.obj", "non-manifold edge between vertices 100 and 101 (0-based): 100 faces"},
    {"loop_nonman_edges.obj", "non-manifold vertex 7 (0-based): 4 faces (0, 1, 10, 17) in 3 fans"},
    {"loop_nonman_verts.obj", "non-manifold vertex 1 (0-based): 4 faces (0, 1, 2, 3) in 2 fans"},
    // Not named non-manifold, but they are: two quads meeting at one vertex only (a bowtie), and
    // four triangles on one edge.
    {"catmark_gregory_test4.obj", "non-manifold vertex 4 (0-based): 2 faces (0, 1) in 2 fans"},
    {"loop_val2_interior.obj", "non-manifold vertex 2 (0-based): 4 faces (0, 1, 2, 3) in 3 fans"},
};


std::string topology_error(const Cage& c) {
  try {
    (void)Topology(c);
  } catch (const CageError& e) {
    return e.what();
  }
  return "";
}

void check_invariants(const Cage& c, const Topology& t) {
  REQUIRE(t.face_count() == c.face_count());
  REQUIRE(t.half_edge_count() == int(c.face_vertices.size()));
  int boundary_half_edges = 0;
  for (int h = 0; h < t.half_edge_count(); ++h) {
    const int f = t.face(h), k = t.corner(h);
    REQUIRE(h == c.face_offsets[f] + k);
    REQUIRE(t.origin(h) == c.face_vertex(f, k));
    REQUIRE(t.destination(h) == c.face_vertex(f, (k + 1) % c.face_sizes[f]));
    REQUIRE(t.next(t.prev(h)) == h);
    REQUIRE(t.face(t.next(h)) == f);
    REQUIRE(t.corner_of(f, t.origin(h)) == k);
    if (t.twin(h) < 0) {
      ++boundary_half_edges;
      REQUIRE(t.is_boundary_edge(t.edge(h)));
      continue;
    }
    REQUIRE(t.twin(t.twin(h)) == h);
    REQUIRE(t.origin(t.twin(h)) == t.destination(h));
    REQUIRE(t.edge(t.twin(h)) == t.edge(h));
  }
  // Edges in first-use order.
  int prev_first = -1;
  for (int e = 0; e < t.edge_count(); ++e) {
    const auto [h0, h1] = t.edge_half_edges(e);
    REQUIRE(h0 > prev_first);
    REQUIRE(t.edge(h0) == e);
    if (h1 >= 0) REQUIRE((h1 > h0 && t.twin(h0) == h1));
    prev_first = h0;
  }
  // Rings: every half-edge once, counter-clockwise steps, boundary rings from boundary to boundary.
  std::vector<int> seen(std::size_t(t.half_edge_count()), 0);
  long long valence_sum = 0;
  for (int v = 0; v < t.vertex_count(); ++v) {
    const auto ring = t.ring(v);
    REQUIRE(int(ring.size()) == t.vertex_face_count(v));
    if (ring.empty()) {
      REQUIRE(t.is_isolated(v));
      continue;
    }
    for (std::size_t i = 0; i < ring.size(); ++i) {
      REQUIRE(t.origin(ring[i]) == v);
      ++seen[ring[i]];
      if (i + 1 < ring.size()) REQUIRE(ring[i + 1] == t.twin(t.prev(ring[i])));
    }
    const int after_last = t.twin(t.prev(ring.back()));
    if (t.is_boundary_vertex(v)) {
      REQUIRE(t.twin(ring.front()) < 0);
      REQUIRE(after_last < 0);
      REQUIRE(t.valence(v) == int(ring.size()) + 1);
    } else {
      REQUIRE(after_last == ring.front());
      REQUIRE(t.valence(v) == int(ring.size()));
    }
    valence_sum += t.valence(v);
  }
  REQUIRE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  REQUIRE(valence_sum == 2LL * t.edge_count());
  REQUIRE(t.edge_count() * 2 - boundary_half_edges == t.half_edge_count());
}

int euler(const Topology& t) {
  return t.vertex_count() - int(t.isolated_vertices().size()) - t.edge_count() + t.face_count();
}

}  // namespace

TEST_CASE("Topology invariants hold on every cage, the non-manifold ones split", "[topology][data]") {
  int valid = 0, split = 0;
  for (const auto& path : all_cages()) {
    INFO(path.string());
    const Cage c = load_obj_cage(path.string());
    const auto nm = kNonManifold.find(path.filename().string());
    if (nm != kNonManifold.end()) {
      REQUIRE_FALSE(c.non_manifold.empty());
      CHECK(c.non_manifold.front().rfind(nm->second, 0) == 0);
      int copies = 0;
      for (int v = 0; v < c.vertex_count(); ++v) copies += c.source_vertex(v) != v;
      CHECK(copies > 0);
      ++split;
    } else {
      CHECK(c.non_manifold.empty());
    }
    CHECK(topology_error(c).empty());
    const Topology t(c);
    check_invariants(c, t);
    const TopologyCombinations combos = analyze_combinations(t);
    int faces = 0;
    for (const Combination& k : combos.combinations) faces += k.count;
    CHECK(faces == t.face_count() - int(c.tags.holes.size()));
    ++valid;
  }
  CHECK(split == int(kNonManifold.size()));
  CHECK(valid == 129);  // 121 OpenSubdiv shapes + 8 SDK cages
}

TEST_CASE("Topology: Euler characteristic of closed and open cages", "[topology]") {
  const std::vector<std::pair<std::string, int>> cases = {{"osd-shapes/catmark_cube.obj", 2},
                                                          {"osd-shapes/catmark_torus.obj", 0},
                                                          {"osd-shapes/catmark_toroidal_tet.obj", -4},
                                                          {"osd-shapes/catmark_pyramid.obj", 2},
                                                          {"osd-shapes/catmark_pole8.obj", 1},
                                                          {"osd-shapes/catmark_lefthanded.obj", 2},
                                                          {"sdk-cages/shipquads.obj", -2},
                                                          {"sdk-cages/monsterfrog_mapped_00.obj", 16}};
  for (const auto& [file, chi] : cases) {
    INFO(file);
    const Topology t(load_obj_cage(data(file)));
    CHECK(euler(t) == chi);
  }
  const Topology cube(load_obj_cage(data("osd-shapes/catmark_cube.obj")));
  CHECK((cube.vertex_count() == 8 && cube.edge_count() == 12 && cube.face_count() == 6));
  for (int e = 0; e < cube.edge_count(); ++e) CHECK_FALSE(cube.is_boundary_edge(e));
}

TEST_CASE("Topology: rings turn counter-clockwise seen from outside", "[topology]") {
  // The cube is centred at the origin, so a vertex's outward normal points along its position.
  const Cage c = load_obj_cage(data("osd-shapes/catmark_cube.obj"));
  const Topology t(c);
  for (int v = 0; v < t.vertex_count(); ++v) {
    const auto ring = t.ring(v);
    REQUIRE(ring.size() == 3);
    const glm::vec3 p = c.positions[v];
    for (std::size_t i = 0; i < 3; ++i) {
      const glm::vec3 a = c.positions[t.destination(ring[i])] - p,
                      b = c.positions[t.destination(ring[(i + 1) % 3])] - p;
      CHECK(glm::dot(glm::cross(a, b), p) > 0);
    }
  }
  // A boundary vertex of a flat grid (z up): the ring starts on the boundary edge and turns
  // counter-clockwise about +z.
  const Cage g = parse_obj_cage("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n", "grid");
  const Topology tg(g);
  REQUIRE(tg.is_boundary_vertex(1));
  REQUIRE(tg.valence(1) == 3);
  const auto ring = tg.ring(1);
  REQUIRE(ring.size() == 2);
  CHECK(tg.destination(ring[0]) == 2);  // the boundary edge 1 -> 2, face 1
  CHECK(tg.destination(ring[1]) == 4);  // then 1 -> 4 in face 0
  CHECK(tg.destination(tg.prev(ring[1])) == 1);
  CHECK(tg.origin(tg.prev(ring[1])) == 0);  // and the fan ends on the boundary edge 0 -> 1
}

TEST_CASE("Topology: validation errors name the element", "[topology][errors]") {
  auto cage = [](std::vector<int> sizes, std::vector<int> verts, int nv) {
    Cage c;
    c.name = "hand.obj";
    c.positions.assign(std::size_t(nv), glm::vec3(0));
    c.face_sizes = sizes;
    int o = 0;
    for (int n : sizes) c.face_offsets.push_back(o), o += n;
    c.face_vertices = verts;
    return c;
  };
  CHECK(topology_error(cage({3}, {0, 1, 5}, 3)) ==
        "hand.obj: face 0 has vertex 5 (0-based), but the cage has 3 vertices");
  CHECK(topology_error(cage({3}, {0, 1, -1}, 3)) ==
        "hand.obj: face 0 has vertex -1 (0-based), but the cage has 3 vertices");
  CHECK(topology_error(cage({2}, {0, 1}, 3)) == "hand.obj: face 0 has 2 vertices; a face needs at least 3");
  CHECK(topology_error(cage({4}, {0, 1, 2, 1}, 3)) ==
        "hand.obj: face 0 is degenerate: it uses vertex 1 (0-based) twice");
  CHECK(topology_error(cage({3, 3, 3}, {0, 1, 2, 1, 0, 3, 0, 1, 4}, 5)) ==
        "hand.obj: non-manifold edge between vertices 0 and 1 (0-based): used by 3 faces (0, 1, 2); an edge may have "
        "at most two");
  CHECK(topology_error(cage({3, 3}, {0, 1, 2, 0, 1, 3}, 4)) ==
        "hand.obj: faces 0 and 1 both use the edge from vertex 0 to 1 (0-based) in the same direction (inconsistent "
        "orientation)");
  // Two triangles meeting at vertex 0 only (a bowtie).
  CHECK(topology_error(cage({3, 3}, {0, 1, 2, 0, 3, 4}, 5)) ==
        "hand.obj: non-manifold vertex 0 (0-based): its 2 faces form more than one fan");
  // Two closed fans at vertex 0: two tetrahedra sharing only that vertex.
  CHECK(topology_error(cage({3, 3, 3, 3, 3, 3, 3, 3},
                            {0, 2, 1, 0, 3, 2, 0, 1, 3, 1, 2, 3, 0, 5, 4, 0, 6, 5, 0, 4, 6, 4, 5, 6}, 7)) ==
        "hand.obj: non-manifold vertex 0 (0-based): its 6 faces form more than one fan");
  Cage holes = cage({3}, {0, 1, 2}, 3);
  holes.tags.holes = {1};
  CHECK(topology_error(holes) == "hand.obj: hole names face 1, but the cage has 1 faces");
  Cage sharp = cage({3}, {0, 1, 2}, 3);
  sharp.tags.corners = {{0, -1.0f}};
  CHECK(topology_error(sharp).rfind("hand.obj: corner at vertex 0 has sharpness -1", 0) == 0);

  // Fallbacks: warnings, not errors.
  Cage lenient = cage({3}, {0, 1, 2}, 5);
  lenient.tags.creases = {{0, 1, 2.0f}, {3, 4, 1.0f}};
  const Topology t(lenient);
  CHECK(t.isolated_vertices() == std::vector<int>{3, 4});
  CHECK(t.valence(3) == 0);
  CHECK(t.ring(3).empty());
  REQUIRE(t.warnings().size() == 2);
  CHECK(t.warnings()[0] == "hand.obj: 2 isolated vertices (used by no face; ignored), first 3 (0-based)");
  CHECK(t.warnings()[1] == "hand.obj: 1 creases name two vertices that share no edge (ignored), first 3-4");
  CHECK(t.edge_sharpness(t.edge(0)) == 2.0f);
  CHECK((t.has_sharpness_at(0) && t.has_sharpness_at(1) && !t.has_sharpness_at(2)));
}

TEST_CASE("Topology: OpenSubdiv tags become per-edge and per-vertex sharpness", "[topology][tags]") {
  const Cage c = load_obj_cage(data("osd-shapes/catmark_cube_corner4.obj"));
  const Topology t(c);
  REQUIRE(c.tags.corners.size() == 1);
  CHECK(t.corner_sharpness(c.tags.corners[0].vertex) == c.tags.corners[0].sharpness);
  const Cage cr = load_obj_cage(data("osd-shapes/catmark_cube_creases0.obj"));
  const Topology tc(cr);
  int creased = 0;
  for (int e = 0; e < tc.edge_count(); ++e) creased += tc.edge_sharpness(e) > 0;
  CHECK(creased == int(cr.tags.creases.size()));
}

TEST_CASE("Combinations: the cube has one, the torus is all regular", "[topology][combinations]") {
  const TopologyCombinations cube = analyze_combinations(Topology(load_obj_cage(data("osd-shapes/catmark_cube.obj"))));
  REQUIRE(cube.combinations.size() == 1);
  CHECK(cube.combinations[0].text == "3 3 3 3");
  CHECK(cube.combinations[0].count == 6);
  CHECK(cube.combinations[0].faces == std::vector<int>{0, 1, 2, 3, 4, 5});
  CHECK((cube.stats.patches == 6 && cube.stats.quads == 6 && cube.stats.regular == 0 && cube.stats.boundary == 0));

  const TopologyCombinations torus =
      analyze_combinations(Topology(load_obj_cage(data("osd-shapes/catmark_torus.obj"))));
  REQUIRE(torus.combinations.size() == 1);
  CHECK(torus.combinations[0].text == "4 4 4 4");
  CHECK(torus.combinations[0].patch_class == PatchClass::regular);
  CHECK(torus.stats.regular == 32);

  // A 3x3 grid: the centre face is regular, the other 8 are regular boundary patches.
  const TopologyCombinations tent = analyze_combinations(Topology(load_obj_cage(data("osd-shapes/catmark_tent.obj"))));
  CHECK((tent.stats.regular == 1 && tent.stats.boundary == 8 && tent.stats.regular_boundary == 8));
  CHECK(tent.combinations.size() == 3);  // centre, edge, corner

  // Holes get no combination; triangles are marked with a leading 0.
  const Topology holes(load_obj_cage(data("osd-shapes/catmark_hole_test1.obj")));
  const TopologyCombinations h = analyze_combinations(holes);
  CHECK(h.face_combination[1] == -1);
  CHECK(h.face_class[1] == PatchClass::hole);
  CHECK(h.stats.patches == 5);
  const TopologyCombinations pyramid =
      analyze_combinations(Topology(load_obj_cage(data("osd-shapes/catmark_pyramid.obj"))));
  CHECK((pyramid.stats.triangles == 4 && pyramid.stats.quads == 1));
  bool tri_text = false;
  for (const Combination& k : pyramid.combinations) tri_text |= k.face_size == 3 && k.text.rfind("0 ", 0) == 0;
  CHECK(tri_text);
}

TEST_CASE("Combinations: the monster frog", "[topology][combinations][data]") {
  const Cage frog = load_obj_cage(data("sdk-cages/monsterfrog_mapped_00.obj"));
  const Topology t(frog);
  const TopologyCombinations k = analyze_combinations(t);
  CHECK((t.vertex_count() == 1308 && t.edge_count() == 2584 && t.face_count() == 1292));
  int max_valence = 0;
  for (int v = 0; v < t.vertex_count(); ++v) max_valence = std::max(max_valence, t.valence(v));
  CHECK(max_valence == 7);
  CHECK(k.stats.patches == 1292);
  CHECK(k.stats.quads == 1292);
  CHECK(k.stats.regular == 528);
  CHECK(k.stats.boundary == 0);
  CHECK(k.combinations.size() == 34);
}

TEST_CASE("Combinations do not depend on which corner a face starts at", "[topology][combinations]") {
  for (const char* file :
       {"sdk-cages/monsterfrog_mapped_00.obj", "osd-shapes/catmark_nonquads.obj", "osd-shapes/catmark_car.obj"}) {
    INFO(file);
    const Cage c = load_obj_cage(data(file));
    Cage rotated = c;
    for (int f = 0; f < c.face_count(); ++f) {
      const int n = c.face_sizes[f], shift = f % n;
      for (int k = 0; k < n; ++k) rotated.face_vertices[c.face_offsets[f] + k] = c.face_vertex(f, (k + shift) % n);
    }
    const Topology ta(c), tb(rotated);
    const TopologyCombinations a = analyze_combinations(ta), b = analyze_combinations(tb);
    REQUIRE(a.combinations.size() == b.combinations.size());
    for (int f = 0; f < c.face_count(); ++f) {
      if (a.face_combination[f] < 0) continue;
      const Combination& x = a.combinations[a.face_combination[f]];
      const Combination& y = b.combinations[b.face_combination[f]];
      CHECK(x.key == y.key);
      CHECK(x.count == y.count);
      CHECK(combination_text(ta, f, a.face_rotation[f]) == combination_text(tb, f, b.face_rotation[f]));
    }
  }
}
