// The memory model (memory_model.h) against counts derived independently, the synthetic cage
// generator, and the OBJ writer's round trip.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <glm/geometric.hpp>

#include "test_data.h"
#include "shaders_cpp/cage/cage_generators.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "tools/measure/memory_model.h"
#include "shaders_cpp/subdiv/subd_patches.h"
#include "shaders_cpp/cage/topology.h"

using namespace tessera;
using namespace tessera::measure;
using tessera::test::data;

namespace {

std::uint32_t bits(float x) { return std::bit_cast<std::uint32_t>(x); }

std::uint64_t mip_texels(std::uint64_t side) {
  std::uint64_t n = 0;
  for (; side >= 1; side /= 2) n += side * side;
  return n;
}

}  // namespace

TEST_CASE("torus_cage is a closed all-valence-4 quad cage with one UV seam loop each way", "[memory]") {
  const Cage c = torus_cage(12, 5, 2.0f, 0.5f);
  const Topology t(c);
  CHECK(t.vertex_count() == 60);
  CHECK(t.face_count() == 60);
  CHECK(t.edge_count() == 120);
  for (int v = 0; v < t.vertex_count(); ++v) {
    CHECK(t.valence(v) == 4);
    CHECK_FALSE(t.is_boundary_vertex(v));
  }
  const auto seams = uv_seam_edges(c, t);
  CHECK(std::count(seams.begin(), seams.end(), true) == 12 + 5);
  // Counter-clockwise from outside: the first face's normal points away from the torus axis.
  const glm::vec3 a = c.positions[std::size_t(c.face_vertex(0, 0))], b = c.positions[std::size_t(c.face_vertex(0, 1))],
                  d = c.positions[std::size_t(c.face_vertex(0, 3))];
  const glm::vec3 n = glm::cross(b - a, d - a);
  CHECK(glm::dot(n, glm::vec3(a.x, a.y, 0.0f)) > 0.0f);
  CHECK_THROWS_AS(torus_cage(2, 5, 2.0f, 0.5f), std::invalid_argument);
  CHECK_THROWS_AS(torus_cage(12, 5, 1.0f, 1.5f), std::invalid_argument);
}

TEST_CASE("format_obj_cage reads back to the same cage, bit for bit", "[memory][cage]") {
  Cage c = torus_cage(7, 4, 1.0f, 0.3f);
  c.tags.creases.push_back({0, 1, 2.5f});
  c.tags.corners.push_back({3, 10.0f});
  c.tags.holes.push_back(5);
  c.tags.boundary = BoundaryInterpolation::edge_and_corner;
  const Cage r = parse_obj_cage(format_obj_cage(c), "roundtrip.obj");
  REQUIRE(r.positions.size() == c.positions.size());
  for (std::size_t i = 0; i < c.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) CHECK(bits(r.positions[i][k]) == bits(c.positions[i][k]));
  REQUIRE(r.uvs.size() == c.uvs.size());
  for (std::size_t i = 0; i < c.uvs.size(); ++i)
    for (int k = 0; k < 2; ++k) CHECK(bits(r.uvs[i][k]) == bits(c.uvs[i][k]));
  CHECK(r.face_sizes == c.face_sizes);
  CHECK(r.face_vertices == c.face_vertices);
  CHECK(r.face_uvs == c.face_uvs);
  REQUIRE(r.tags.creases.size() == 1);
  CHECK(r.tags.creases[0].sharpness == 2.5f);
  REQUIRE(r.tags.corners.size() == 1);
  CHECK(r.tags.corners[0].vertex == 3);
  CHECK(r.tags.holes == c.tags.holes);
  CHECK(r.tags.boundary == BoundaryInterpolation::edge_and_corner);
}

TEST_CASE("memory_table counts the pre-tessellated torus as its unwrapped grid", "[memory]") {
  // Split on its two UV seams, a torus of A x B quads tessellated at level L is exactly the planar
  // grid of (A L + 1) x (B L + 1) vertices and 2 A B L^2 triangles: an independent count.
  const int A = 8, B = 4;
  const Cage c = torus_cage(A, B, 1.0f, 0.4f);
  const Topology t(c);
  const SubdPatches p = build_patches(c, t, Scheme::gregory);
  MemoryModelOptions o;
  o.levels = {1, 2, 5, 8, 64};
  const MemoryTable m = memory_table(c, t, p, o);
  REQUIRE(m.levels.size() == o.levels.size());
  CHECK(m.faces == A * B);
  CHECK(m.uv_area == Approx(1.0));
  for (const MemoryLevel& l : m.levels) {
    const std::uint64_t L = std::uint64_t(l.level);
    CHECK(l.mesh_vertices == (A * L + 1) * (B * L + 1));
    CHECK(l.mesh_triangles == 2 * A * B * L * L);
    CHECK(l.mesh_bytes() == l.mesh_vertices * 32 + l.mesh_triangles * 12);
    // One texel per generated vertex: side L * sqrt(32), rounded up.
    const std::uint64_t side = std::uint64_t(std::ceil(double(L) * std::sqrt(32.0)));
    CHECK(std::uint64_t(l.needed_map_side) == side);
    CHECK(l.map_width == l.needed_map_side);
    CHECK(l.map_bytes == mip_texels(side) * 4);
    CHECK(l.tessera_bytes == m.cage_bytes + m.patch_bytes + l.map_bytes);
  }
  // The mesh grows as L^2, Tessera's fixed part does not.
  CHECK(m.levels[4].mesh_bytes() > 60 * m.levels[3].mesh_bytes());
  CHECK(m.cage_bytes == 32 * 12 + 45 * 8 + (128 + 128 + 64) * 4);
}

TEST_CASE("memory_table keeps the mip level of a real map that a level needs, never more than the map", "[memory]") {
  const Cage c = torus_cage(8, 4, 1.0f, 0.4f);
  const Topology t(c);
  const SubdPatches p = build_patches(c, t, Scheme::gregory);
  MemoryModelOptions o;
  o.levels = {8, 64};
  o.map = MapSize{512, 256};
  o.texel_bytes = 1;
  const MemoryTable m = memory_table(c, t, p, o);
  // Level 8 needs ceil(8 sqrt 32) = 46 texels across: the 64x32 level of the 512x256 chain and
  // everything coarser.
  CHECK(m.levels[0].needed_map_side == 46);
  CHECK(m.levels[0].map_width == 64);
  CHECK(m.levels[0].map_height == 32);
  std::uint64_t chain = 0;
  for (int w = 64, h = 32; w >= 1; w /= 2, h = std::max(1, h / 2)) chain += std::uint64_t(w) * std::uint64_t(h);
  CHECK(m.levels[0].map_bytes == chain);
  // Level 64 needs 363 and gets the whole map.
  CHECK(m.levels[1].map_width == 512);
  CHECK(m.levels[1].map_height == 256);
  o.levels = {65};
  CHECK_THROWS_AS(memory_table(c, t, p, o), std::invalid_argument);
}

TEST_CASE("memory_table on the monster frog: the mesh grows as the square of the level, the ratio with it",
          "[memory]") {
  const Cage c = load_obj_cage(data("sdk-cages/monsterfrog_mapped_00.obj"));
  const Topology t(c);
  const SubdPatches p = build_patches(c, t, Scheme::gregory);
  MemoryModelOptions o;
  o.map = MapSize{512, 512};
  const MemoryTable m = memory_table(c, t, p, o);
  REQUIRE(m.levels.size() == 4);
  CHECK(m.faces == 1292);
  CHECK(m.uv_area > 0.1);
  CHECK(m.uv_area < 1.0);
  for (std::size_t i = 0; i + 1 < m.levels.size(); ++i) {
    const double growth = double(m.levels[i + 1].mesh_bytes()) / double(m.levels[i].mesh_bytes());
    CHECK(growth > 3.5);
    CHECK(growth < 4.1);
    CHECK(m.levels[i + 1].ratio() > m.levels[i].ratio());
  }
  // All quads: L^2 * 2 triangles per face.
  CHECK(m.levels[0].mesh_triangles == 1292u * 128u);
}

TEST_CASE("memory_table counts the precomputed patches' rows and pre-pass points", "[memory]") {
  // A sphere with valence-20 poles: its 40 pole quads have 1-rings of 46 points, precomputed; the patch
  // data holds their rows over the ring and the pre-pass's 20 points per patch besides the tables.
  const Cage c = sphere_cage(20, 4, 1.0f);
  const Topology t(c);
  const SubdPatches p = build_patches(c, t, Scheme::gregory);
  REQUIRE(p.precomputed.size() == 40);
  std::uint64_t rows = 0, tables = 0;
  for (const PrecomputedPatch& q : p.precomputed)
    rows += q.weights.size() * sizeof(float) + q.vertices.size() * sizeof(int);
  for (const StencilTable& s : p.tables) tables += s.weights.size() * sizeof(float);
  const std::uint64_t records = (p.quads.size() + p.tris.size()) * sizeof(SubdPatch);
  const std::uint64_t indices = (p.quads.indices.size() + p.tris.indices.size()) * sizeof(std::uint32_t);
  MemoryModelOptions o;
  o.levels = {4};
  o.displacement_data_bytes = 0;
  const MemoryTable m = memory_table(c, t, p, o);
  CHECK(m.patch_bytes == indices + tables + records + rows + 40 * 20 * sizeof(glm::vec3));
}
