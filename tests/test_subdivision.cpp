// The subdivision schemes end to end through the pipeline's stream output: watertight edges (welded
// on exact bits), exactness where the scheme is exact, stencil tables per topology combination, and
// clear errors for faces a scheme cannot take.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "cage_obj.h"
#include "subd_model.h"
#include "topology_combinations.h"
#include "weld_check.h"

using namespace tessera;

namespace {

std::string data(const std::string& name) { return std::string(TESSERA_TEST_DATA_DIR) + "/" + name; }

struct Weld {
  cli::WeldReport report;
  std::uint64_t normal_mismatches = 0;  // points with the same position bits but different normal bits
};

Weld weld_with_normals(const SubdModel& m, const SubdFactors& f, ts::Partitioning p, int threads = 2) {
  DeviceOptions o;
  o.threads = threads;
  Device device(o);
  cli::WeldChecker w;
  Weld out;
  std::unordered_map<std::uint64_t, std::vector<std::array<std::uint32_t, 6>>> seen;  // by position hash
  const auto bits = [](const SurfaceSample& s) {
    return std::array<std::uint32_t, 6>{std::bit_cast<std::uint32_t>(s.position.x), std::bit_cast<std::uint32_t>(s.position.y),
                                        std::bit_cast<std::uint32_t>(s.position.z), std::bit_cast<std::uint32_t>(s.normal.x),
                                        std::bit_cast<std::uint32_t>(s.normal.y), std::bit_cast<std::uint32_t>(s.normal.z)};
  };
  const DrawResult r = stream_subd(device, m, f, p, [&](const PatchOutput<SurfaceSample>& patch, const PatchGroup&) {
    for (std::size_t i = 0; i + 2 < patch.indices.size(); i += 3)
      w.add_triangle(patch.points[patch.indices[i]].position, patch.points[patch.indices[i + 1]].position,
                     patch.points[patch.indices[i + 2]].position);
    for (const SurfaceSample& s : patch.points) {
      const auto b = bits(s);
      auto& bucket = seen[(std::uint64_t(b[0]) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(b[1]) << 21) ^ b[2]];
      bool placed = false;
      for (const auto& other : bucket)
        if (std::equal(b.begin(), b.begin() + 3, other.begin())) {
          if (!std::equal(b.begin() + 3, b.end(), other.begin() + 3)) ++out.normal_mismatches;
          placed = true;
          break;
        }
      if (!placed) bucket.push_back(b);
    }
  });
  REQUIRE(r.ok());
  out.report = w.report();
  return out;
}

cli::WeldReport weld(const SubdModel& m, float factor, float vary, ts::Partitioning p, int threads = 2) {
  SubdFactors f;
  f.factor = factor;
  f.vary = vary;
  return weld_with_normals(m, f, p, threads).report;
}

// A pentagonal pyramid (a pentagon among triangles) and a hexagonal prism (hexagons among quads).
Cage pentagonal_pyramid() {
  std::string obj;
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * 3.14159265358979323846 * k / 5;
    obj += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  obj += "v 0.1 -0.05 1.3\nf 5 4 3 2 1\n";
  for (int k = 0; k < 5; ++k) obj += "f " + std::to_string(k + 1) + " " + std::to_string((k + 1) % 5 + 1) + " 6\n";
  return parse_obj_cage(obj, "pentagonal_pyramid");
}

Cage hexagonal_prism() {
  std::string obj;
  for (int z = 0; z < 2; ++z)
    for (int k = 0; k < 6; ++k) {
      const double a = 2 * 3.14159265358979323846 * k / 6, r = z ? 0.8 : 1.0;
      obj += "v " + std::to_string(r * std::cos(a)) + " " + std::to_string(r * std::sin(a) + 0.1 * k) + " " +
             std::to_string(z * 1.5) + "\n";
    }
  obj += "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\n";
  for (int k = 0; k < 6; ++k) {
    const int a = k + 1, b = (k + 1) % 6 + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + 6) + " " + std::to_string(a + 6) + "\n";
  }
  return parse_obj_cage(obj, "hexagonal_prism");
}

}  // namespace

TEST_CASE("Subdivision schemes are watertight on closed cages at integer and fractional factors varying per edge",
          "[subd]") {
  const char* cages[] = {"osd-shapes/catmark_cube.obj", "osd-shapes/catmark_torus.obj", "osd-shapes/catmark_toroidal_tet.obj",
                         "osd-shapes/catmark_lefthanded.obj", "sdk-cages/monsterfrog_mapped_00.obj", "sdk-cages/guy3.obj"};
  for (const char* cage : cages)
    for (Scheme s : {Scheme::bspline, Scheme::acc, Scheme::gregory, Scheme::exact}) {
      const SubdModel m = load_subd_model(data(cage), s);
      struct Case {
        ts::Partitioning p;
        float factor, vary;
      };
      for (const Case c : {Case{ts::Partitioning::integer, 3.0f, 1.0f}, Case{ts::Partitioning::fractional_odd, 2.3f, 1.7f},
                           Case{ts::Partitioning::fractional_even, 2.6f, 1.3f}}) {
        INFO(cage << " " << to_string(s) << " " << ts::to_string(c.p));
        const auto r = weld(m, c.factor, c.vary, c.p);
        CHECK(r.closed_manifold());
        CHECK(r.boundary_edges == 0);
        CHECK(r.nonmanifold_edges == 0);
        CHECK(r.degenerate_triangles == 0);
      }
    }
}

TEST_CASE("Flat and exact schemes draw triangles and n-gons watertight next to quads and triangles", "[subd]") {
  // An n-gon is a fan of triangles whose outer edge is the whole cage edge, tessellated with that
  // edge's factor like the neighbour's; drawing it as quad sub-patches left T-junctions here (the
  // sub-patches' half edges against the neighbour's whole edge), which this weld finds.
  std::vector<std::pair<std::string, Cage>> cages;
  for (const char* name : {"osd-shapes/catmark_pyramid.obj", "osd-shapes/catmark_gregory_test8.obj"})
    cages.emplace_back(name, load_obj_cage(data(name)));
  cages.emplace_back("pentagonal pyramid", pentagonal_pyramid());
  cages.emplace_back("hexagonal prism", hexagonal_prism());
  for (const auto& [name, cage] : cages)
    for (Scheme s : {Scheme::flat, Scheme::exact}) {
      const SubdModel m = make_subd_model(cage, s);
      struct Case {
        ts::Partitioning p;
        float factor, vary;
      };
      for (const Case c : {Case{ts::Partitioning::integer, 4.0f, 0.0f}, Case{ts::Partitioning::integer, 3.0f, 1.0f},
                           Case{ts::Partitioning::fractional_odd, 2.3f, 1.7f},
                           Case{ts::Partitioning::fractional_even, 2.6f, 1.3f}}) {
        INFO(name << " " << to_string(s) << " " << ts::to_string(c.p) << " vary " << c.vary);
        SubdFactors f;
        f.factor = c.factor;
        f.vary = c.vary;
        const Weld w = weld_with_normals(m, f, c.p);
        CHECK(w.report.closed_manifold());
        CHECK(w.report.boundary_edges == 0);
        CHECK(w.report.nonmanifold_edges == 0);
        CHECK(w.report.degenerate_triangles == 0);
        // The exact surface is smooth: one normal per welded point (flat is faceted).
        if (s == Scheme::exact) CHECK(w.normal_mismatches == 0);
      }
    }
}

TEST_CASE("An n-gon's fan takes its cage edges whole and shares its spokes", "[subd]") {
  for (Scheme s : {Scheme::flat, Scheme::exact}) {
    const SubdModel m = make_subd_model(hexagonal_prism(), s);
    REQUIRE(m.patches.tris.size() == 12);  // two hexagons, six triangles each
    REQUIRE(m.patches.quads.size() == 6);
    for (std::size_t i = 0; i < m.patches.tris.size(); ++i) {
      const SubdPatch& p = m.patches.tris.patches[i];
      const int n = 6, k = p.sub;
      CHECK(k == int(i % 6));
      const auto v = [&](int j) { return m.cage.face_vertex(p.face, (j % n + n) % n); };
      // Veq0 is cage edge k -> k+1 itself; the spokes (Ueq0 to vertex k, Weq0 to vertex k+1) name the
      // two cage edges at their vertex, in the same order from both triangles that share them.
      CHECK(p.edge_keys[1] == EdgeFactorKey{cage_edge_key(v(k), v(k + 1)), -1});
      CHECK(p.edge_keys[0] == EdgeFactorKey{cage_edge_key(v(k - 1), v(k)), cage_edge_key(v(k), v(k + 1))});
      CHECK(p.edge_keys[2] == EdgeFactorKey{cage_edge_key(v(k), v(k + 1)), cage_edge_key(v(k + 1), v(k + 2))});
      const SubdPatch& next = m.patches.tris.patches[i / 6 * 6 + (i + 1) % 6];
      CHECK(next.edge_keys[0] == p.edge_keys[2]);
    }
    // The spoke's factor is the mean of the cage edges beside it.
    SubdFactors f;
    f.per_edge = std::make_shared<std::unordered_map<std::int64_t, float>>(std::unordered_map<std::int64_t, float>{
        {cage_edge_key(m.cage.face_vertex(0, 0), m.cage.face_vertex(0, 1)), 3.0f},
        {cage_edge_key(m.cage.face_vertex(0, 1), m.cage.face_vertex(0, 2)), 6.0f}});
    CHECK(f.edge(m.patches.tris.patches[1].edge_keys[0]) == 4.5f);
    CHECK(f.edge(m.patches.tris.patches[0].edge_keys[2]) == 4.5f);
  }
  // Faces of more sides than a patch has control points are refused with one line.
  std::string obj;
  for (int k = 0; k < 33; ++k) obj += "v " + std::to_string(std::cos(k / 5.25)) + " " + std::to_string(std::sin(k / 5.25)) + " 0\n";
  obj += "f";
  for (int k = 1; k <= 33; ++k) {
    obj += ' ';
    obj += std::to_string(k);
  }
  const Cage big = parse_obj_cage(obj + "\n", "big");
  for (Scheme s : {Scheme::flat, Scheme::exact}) {
    try {
      make_subd_model(big, s);
      FAIL("no error");
    } catch (const CageError& e) {
      CHECK(std::string(e.what()) == std::string("big: face 0 has 33 sides; --scheme ") + to_string(s) +
                                         " draws faces of up to 32 (the face is the patch's control points)");
    }
  }
}

TEST_CASE("On open cages with n-gons the only open edges are the cage's boundary", "[subd]") {
  // Integer partitioning: a cage edge of factor F is ceil(F) segments, on each side.
  for (const char* cage : {"osd-shapes/catmark_nonquads.obj", "osd-shapes/catmark_gregory_test2.obj",
                           "osd-shapes/catmark_gregory_test5.obj", "osd-shapes/catmark_val2_foldover.obj"})
    for (Scheme s : {Scheme::flat, Scheme::exact}) {
      // val2_foldover's cage folds faces onto each other: drawn flat, points of different faces coincide
      // to the bit, and the weld joins them (non-manifold edges that are no crack).
      if (s == Scheme::flat && std::string(cage).find("foldover") != std::string::npos) continue;
      INFO(cage << " " << to_string(s));
      const SubdModel m = load_subd_model(data(cage), s);
      SubdFactors f;
      f.factor = 2.0f;
      f.vary = 1.5f;
      std::uint64_t expected = 0;
      for (int e = 0; e < m.topology->edge_count(); ++e)
        if (m.topology->is_boundary_edge(e)) {
          const int h = m.topology->edge_half_edges(e)[0];
          expected += std::uint64_t(std::ceil(f.edge(cage_edge_key(m.topology->origin(h), m.topology->destination(h)))));
        }
      REQUIRE(expected > 0);
      const cli::WeldReport r = weld_with_normals(m, f, ts::Partitioning::integer).report;
      CHECK(r.boundary_edges == expected);
      CHECK(r.nonmanifold_edges == 0);
      CHECK(r.degenerate_triangles == 0);
    }
}

TEST_CASE("On an open cage the only open edges are the cage's boundary, factor segments each", "[subd]") {
  for (Scheme s : {Scheme::flat, Scheme::acc, Scheme::gregory, Scheme::exact}) {
    const SubdModel m = load_subd_model(data("osd-shapes/catmark_tent.obj"), s);
    int boundary = 0;
    for (int e = 0; e < m.topology->edge_count(); ++e) boundary += m.topology->is_boundary_edge(e) ? 1 : 0;
    REQUIRE(boundary > 0);
    const auto r = weld(m, 5.0f, 0.0f, ts::Partitioning::integer);
    INFO(to_string(s));
    CHECK(r.boundary_edges == std::uint64_t(5 * boundary));
    CHECK(r.nonmanifold_edges == 0);
  }
}

TEST_CASE("The weld check sees a crack: one vertex moved by one ulp opens its edges", "[subd]") {
  cli::WeldChecker ok, cracked;
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  // A tetrahedron, consistently oriented.
  for (auto* w : {&ok, &cracked}) {
    w->add_triangle(a, c, b);
    w->add_triangle(a, b, d);
    w->add_triangle(b, c, d);
  }
  ok.add_triangle(c, a, d);
  cracked.add_triangle(c, a, glm::vec3(0, 0, std::nextafter(1.0f, 2.0f)));
  CHECK(ok.report().closed_manifold());
  const auto r = cracked.report();
  CHECK_FALSE(r.closed_manifold());
  CHECK(r.boundary_edges == 4);
}

TEST_CASE("Regular faces are the B-spline patch: bspline, acc and gregory match the exact limit on the torus",
          "[subd]") {
  const SubdModel exact = load_subd_model(data("osd-shapes/catmark_torus.obj"), Scheme::exact);
  for (Scheme s : {Scheme::bspline, Scheme::acc, Scheme::gregory}) {
    const SubdModel m = load_subd_model(data("osd-shapes/catmark_torus.obj"), s);
    CHECK(m.patches.fallback_faces == 0);
    Device device(DeviceOptions{});
    SubdFactors f;
    f.factor = 7;
    double max_d = 0, max_angle = 0;
    stream_subd(device, m, f, ts::Partitioning::integer, [&](const PatchOutput<SurfaceSample>& out, const PatchGroup& g) {
      for (const SurfaceSample& p : out.points) {
        const SurfacePoint e = exact.limit->evaluate(g.patches[out.patch_id].face, 0, p.u, p.v);
        max_d = std::max(max_d, double(glm::length(p.position - e.position)));
        max_angle = std::max(max_angle, double(std::acos(std::min(1.0f, glm::dot(p.normal, e.normal)))));
      }
    });
    INFO(to_string(s));
    CHECK(max_d < 1e-5);        // the torus is about 3.4 across: float round-off
    CHECK(max_angle < 1e-3);    // radians
  }
}

TEST_CASE("Approximations stay close to the limit on the monster frog", "[subd]") {
  // Measured: acc rms 2.8e-4, gregory 2.4e-4 of the bounding-box diagonal; a wrong mask is 1e-2 or worse.
  const SubdModel exact = load_subd_model(data("sdk-cages/monsterfrog_mapped_00.obj"), Scheme::exact);
  const double diagonal = exact.limit->bounding_box_diagonal();
  for (Scheme s : {Scheme::acc, Scheme::gregory}) {
    const SubdModel m = load_subd_model(data("sdk-cages/monsterfrog_mapped_00.obj"), s);
    Device device(DeviceOptions{});
    SubdFactors f;
    f.factor = 5;
    double sum2 = 0, mean_angle = 0;
    std::size_t n = 0;
    stream_subd(device, m, f, ts::Partitioning::integer, [&](const PatchOutput<SurfaceSample>& out, const PatchGroup& g) {
      for (const SurfaceSample& p : out.points) {
        const SurfacePoint e = exact.limit->evaluate(g.patches[out.patch_id].face, 0, p.u, p.v);
        const double d = glm::length(p.position - e.position);
        sum2 += d * d;
        mean_angle += std::acos(std::min(1.0, double(glm::dot(p.normal, e.normal))));
        ++n;
      }
    });
    INFO(to_string(s));
    CHECK(std::sqrt(sum2 / double(n)) / diagonal < 1e-3);
    CHECK(mean_angle / double(n) < 0.02);  // radians, about 1 degree
  }
}

TEST_CASE("Faces of one topology combination share one stencil table", "[subd]") {
  const SubdModel cube = load_subd_model(data("osd-shapes/catmark_cube.obj"), Scheme::gregory);
  CHECK(cube.patches.tables.size() == 1);
  const SubdModel frog = load_subd_model(data("sdk-cages/monsterfrog_mapped_00.obj"), Scheme::acc);
  const auto combos = analyze_combinations(*frog.topology);
  CHECK(frog.patches.tables.size() <= combos.combinations.size());
  CHECK(frog.patches.tables.size() > 1);
  CHECK(frog.patches.quads.control_points <= 32);
}

TEST_CASE("Stream output and stencil evaluation give the same bytes for any thread count", "[subd]") {
  const SubdModel m = load_subd_model(data("sdk-cages/monsterfrog_mapped_00.obj"), Scheme::acc);
  auto digest = [&](int threads) {
    DeviceOptions o;
    o.threads = threads;
    o.chunk_primitives = threads == 1 ? 16384 : 777;
    Device device(o);
    std::uint64_t h = 1469598103934665603ull;
    SubdFactors f;
    f.factor = 3.5f;
    f.vary = 1.0f;
    stream_subd(device, m, f, ts::Partitioning::fractional_odd, [&](const PatchOutput<SurfaceSample>& out, const PatchGroup&) {
      for (const SurfaceSample& p : out.points)
        for (float x : {p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y, p.normal.z})
          h = (h ^ std::bit_cast<std::uint32_t>(x)) * 1099511628211ull;
    });
    return h;
  };
  const auto one = digest(1);
  CHECK(digest(2) == one);
  CHECK(digest(3) == one);
}

TEST_CASE("Faces a scheme cannot take give one line naming the face", "[subd]") {
  try {
    load_subd_model(data("osd-shapes/catmark_pyramid.obj"), Scheme::acc);
    FAIL("no error");
  } catch (const CageError& e) {
    const std::string m = e.what();
    CHECK(m.find("catmark_pyramid.obj: face") != std::string::npos);
    CHECK(m.find("quads only") != std::string::npos);
    CHECK(m.find('\n') == std::string::npos);
  }
  try {
    load_subd_model(data("osd-shapes/catmark_pole64.obj"), Scheme::gregory);
    FAIL("no error");
  } catch (const CageError& e) {
    CHECK(std::string(e.what()).find("face") != std::string::npos);
  }
  CHECK_THROWS_AS(load_subd_model(data("osd-shapes/catmark_nonman_edges.obj"), Scheme::gregory), CageError);
}
