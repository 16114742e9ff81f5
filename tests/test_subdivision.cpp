// The subdivision schemes end to end through the pipeline's stream output: watertight edges (welded
// on exact bits), exactness where the scheme is exact, stencil tables per topology combination, and
// clear errors for faces a scheme cannot take.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include "shaders_cpp/cage/cage_generators.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/topology_combinations.h"
#include "shaders_cpp/render/subd_model.h"
#include "shaders_cpp/subdiv/limit_fit.h"
#include "shaders_cpp/subdiv/patch_eval.h"
#include "shaders_cpp/render/patch_eval_lanes.h"
#include "shaders_cpp/subdiv/patch_stencils.h"
#include "shaders_cpp/subdiv/pn_patch.h"
#include "test_data.h"
#include "tools/verify/weld_check.h"
#include "weld_support.h"

using namespace tessera;
using tessera::test::check_watertight;
using tessera::test::data;
using tessera::test::kVaryingFactors;
using tessera::test::VaryingFactors;

namespace {

struct Weld {
  verify::WeldReport report;
  // With normals tracked: points whose position bits an earlier point had, and those of them whose
  // normal bits differ from that point's.
  std::uint64_t shared_points = 0, normal_mismatches = 0;
};

// Welds the model's DS output on exact position bits; with `track_normals`, also compares the normal
// bits of points that share a position (the cheaper plain weld serves the large cages).
Weld weld_model(const SubdModel& m, const SubdFactors& f, ts::Partitioning p, bool track_normals) {
  DeviceOptions o;
  o.threads = 2;
  Device device(o);
  verify::WeldChecker w;
  Weld out;
  using Bits = std::array<std::uint32_t, 3>;
  std::map<Bits, Bits> normal_at;  // position bits -> the first normal bits seen there
  const DrawResult r = stream_subd(device, m, f, p, [&](const PatchOutput<SurfaceSample>& patch, const PatchGroup&) {
    for (std::size_t i = 0; i + 2 < patch.indices.size(); i += 3)
      w.add_triangle(patch.points[patch.indices[i]].position, patch.points[patch.indices[i + 1]].position,
                     patch.points[patch.indices[i + 2]].position);
    if (!track_normals) return;
    for (const SurfaceSample& s : patch.points) {
      const auto [it, added] = normal_at.emplace(std::bit_cast<Bits>(s.position), std::bit_cast<Bits>(s.normal));
      if (added) continue;
      ++out.shared_points;
      if (it->second != std::bit_cast<Bits>(s.normal)) ++out.normal_mismatches;
    }
  });
  REQUIRE(r.ok());
  out.report = w.report();
  return out;
}

verify::WeldReport weld(const SubdModel& m, const SubdFactors& f, ts::Partitioning p) {
  return weld_model(m, f, p, false).report;
}
verify::WeldReport weld(const SubdModel& m, float factor, float vary, ts::Partitioning p) {
  SubdFactors f;
  f.factor = factor;
  f.vary = vary;
  return weld(m, f, p);
}

// A rig of one node with one morph target, whose delta at each cage vertex is `delta(position)`.
std::shared_ptr<CageRig> morph_rig(const Cage& cage, const std::function<glm::vec3(const glm::vec3&)>& delta) {
  auto rig = std::make_shared<CageRig>();
  rig->nodes.resize(1);
  rig->node_order = {0};
  rig->instances = {RigInstance{0, -1, 0, 1}};
  rig->bind_positions = cage.positions;
  rig->vertex_instance.assign(cage.positions.size(), 0);
  std::vector<glm::vec3> deltas;
  for (const glm::vec3& p : cage.positions) deltas.push_back(delta(p));
  rig->target_deltas = {deltas};
  return rig;
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
    obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + 6) + " " +
           std::to_string(a + 6) + "\n";
  }
  return parse_obj_cage(obj, "hexagonal_prism");
}

// A closed quad-triangle cage: a cube whose bottom is split into two triangles and whose top is a
// four-triangle pyramid cap; corners where triangles and quads meet, valence 3 and 4, an all-triangle
// vertex.
const char* const kMixedCube = R"(v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
v 0 0 1.5
f 1 4 3
f 1 3 2
f 5 6 9
f 6 7 9
f 7 8 9
f 8 5 9
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

SubdModel mixed_cube(Scheme s) { return make_subd_model(parse_obj_cage(kMixedCube, "mixed_cube.obj"), s); }

// Face f's patch evaluated at a location of its own domain, through SubdVS, SubdHS and SubdDS as the
// pipeline calls them.
struct PatchEvaluator {
  const SubdModel& m;
  // `sub`: the fan triangle of a face of more than four sides.
  SurfaceSample operator()(int face, DomainLocation loc, int sub = 0) const {
    for (const PatchGroup* g : {&m.patches.quads, &m.patches.tris})
      for (std::size_t id = 0; id < g->size(); ++id) {
        if (g->patches[id].face != face || g->patches[id].sub != sub) continue;
        const bool tri = g->domain == ts::Domain::tri;
        const SubdVS vs = m.vertex_shader();
        std::vector<SubdVertex> in;
        for (int k = 0; k < g->control_points; ++k) {
          const std::uint32_t v = g->indices[id * std::size_t(g->control_points) + std::size_t(k)];
          in.push_back(vs(m.cage.positions[v], v));
        }
        const SubdHS hs{g->patches, m.patches.tables, SubdFactors{}, tri};
        std::vector<SubdControlPoint> cps;
        for (int i = 0; i < SubdHS::kOutputControlPoints; ++i)
          cps.push_back(hs.control_point(in, i, std::uint32_t(id)));
        const SubdDS ds{g->patches, m.limit.get(), m.cage.tags.left_handed, tri};
        return ds(SubdPatchConstants{}, cps, loc, std::uint32_t(id));
      }
    FAIL("no patch for face " << face);
    return {};
  }
  // The location at fraction t of patch edge k (patch corner k -> k + 1) of a face with n corners.
  static DomainLocation on_edge(int n, int k, float t) {
    if (n == 3) {
      switch (k) {
        case 0: return {t, 0.0f, 1.0f - t};
        case 1: return {1.0f - t, t, 0.0f};
        default: return {0.0f, 1.0f - t, t};
      }
    }
    switch (k) {
      case 0: return {t, 0.0f, 0.0f};
      case 1: return {1.0f, t, 0.0f};
      case 2: return {1.0f - t, 1.0f, 0.0f};
      default: return {0.0f, 1.0f - t, 0.0f};
    }
  }
  // Patch edge k of face f and whether it runs a -> b (else b -> a); -1 if the face has no such edge.
  std::pair<int, bool> patch_edge(int face, int a, int b) const {
    const int n = m.topology->face_size(face);
    int rotation = 0;
    for (const PatchGroup* g : {&m.patches.quads, &m.patches.tris})
      for (const SubdPatch& p : g->patches)
        if (p.face == face) rotation = p.rotation;
    for (int k = 0; k < n; ++k) {
      const int x = m.cage.face_vertex(face, (k + rotation) % n), y = m.cage.face_vertex(face, (k + 1 + rotation) % n);
      if (x == a && y == b) return {k, true};
      if (x == b && y == a) return {k, false};
    }
    return {-1, false};
  }
};

// Along every interior cage edge, both patches at t = i/16: counts positions that are not
// bit-identical, and returns the largest angle between the two patches' normals (radians).
double max_normal_jump_across_edges(const SubdModel& m, std::uint64_t& mismatched_positions) {
  const PatchEvaluator eval{m};
  const Topology& t = *m.topology;
  double worst = 0;
  auto compare = [&](const SurfaceSample& p0, const SurfaceSample& p1) {
    using Bits = std::array<std::uint32_t, 3>;
    if (std::bit_cast<Bits>(p0.position) != std::bit_cast<Bits>(p1.position)) ++mismatched_positions;
    // atan2 of |n0 x n1| and n0 . n1 in double: acos would stop at 5e-4 (one float ulp below 1).
    const glm::dvec3 n0(p0.normal), n1(p1.normal);
    worst = std::max(worst, std::atan2(glm::length(glm::cross(n0, n1)), glm::dot(n0, n1)));
  };
  for (int e = 0; e < t.edge_count(); ++e) {
    if (t.is_boundary_edge(e)) continue;
    const auto [h0, h1] = t.edge_half_edges(e);
    const int a = t.origin(h0), b = t.destination(h0);
    const int f0 = t.face(h0), f1 = t.face(h1);
    const auto [k0, fwd0] = eval.patch_edge(f0, a, b);
    const auto [k1, fwd1] = eval.patch_edge(f1, a, b);
    REQUIRE(k0 >= 0);
    REQUIRE(k1 >= 0);
    // A face of more than four sides: its edge k is the outer edge (v = 0) of fan triangle k.
    auto at = [&](int f, int k, float x) {
      const int n = t.face_size(f);
      return n > 4 ? eval(f, PatchEvaluator::on_edge(3, 0, x), k) : eval(f, PatchEvaluator::on_edge(n, k, x));
    };
    for (int i = 0; i <= 16; ++i) {
      const float s = float(i) / 16.0f;  // from a toward b
      compare(at(f0, k0, fwd0 ? s : 1.0f - s), at(f1, k1, fwd1 ? s : 1.0f - s));
    }
  }
  // The spokes of n-gon fans: vertex k -> centre is fan k's u = 0 edge and fan k-1's w = 0 edge.
  for (int f = 0; f < t.face_count(); ++f) {
    const int n = t.face_size(f);
    if (n <= 4) continue;
    for (int k = 0; k < n; ++k)
      for (int i = 0; i <= 16; ++i) {
        const float s = float(i) / 16.0f;  // from vertex k toward the centre
        compare(eval(f, DomainLocation{0.0f, s, 1.0f - s}, k),
                eval(f, DomainLocation{1.0f - s, s, 0.0f}, (k + n - 1) % n));
      }
  }
  return worst;
}

}  // namespace

TEST_CASE("Subdivision schemes are watertight on closed cages at integer and fractional factors varying per edge",
          "[subd]") {
  const char* cages[] = {"osd-shapes/catmark_cube.obj",         "osd-shapes/catmark_torus.obj",
                         "osd-shapes/catmark_toroidal_tet.obj", "osd-shapes/catmark_lefthanded.obj",
                         "sdk-cages/monsterfrog_mapped_00.obj", "sdk-cages/guy3.obj"};
  for (const char* cage : cages)
    for (Scheme s : {Scheme::bspline, Scheme::acc, Scheme::gregory, Scheme::exact, Scheme::pn}) {
      const SubdModel m = load_subd_model(data(cage), s);
      for (const VaryingFactors c : kVaryingFactors) {
        INFO(cage << " " << to_string(s) << " " << ts::to_string(c.partitioning));
        check_watertight(weld(m, c.factor, c.vary, c.partitioning));
      }
    }
}

TEST_CASE("Faces beside high-valence vertices: the control-point pre-pass, watertight to the bit", "[subd]") {
  // Poles of valence 24: a pole quad's 1-ring has 54 points, more than an IA patch's 32. Those 48 faces
  // are precomputed; the faces around them are ordinary patches, and the edges between the two kinds
  // must weld on exact bits.
  for (Scheme s : {Scheme::bspline, Scheme::acc, Scheme::gregory}) {
    const SubdModel m = make_subd_model(sphere_cage(24, 6, 1.0f), s);
    INFO(to_string(s));
    REQUIRE(m.patches.precomputed.size() == 48);
    CHECK(m.patches.quads.control_points <= kMaxPatchControlPoints);
    CHECK(m.precomputed.size() == std::size_t(m.patches.precomputed_rows));
    int precomputed = 0;
    for (const SubdPatch& p : m.patches.quads.patches) precomputed += p.precomputed >= 0;
    CHECK(precomputed == 48);
    for (const VaryingFactors c : kVaryingFactors) {
      INFO(ts::to_string(c.partitioning));
      check_watertight(weld(m, c.factor, c.vary, c.partitioning));
    }
  }
  // Posed: a morph target that bulges one pole and a rotation. The pre-pass follows the pose (the
  // precomputed patches would part from their posed neighbours if it kept the rest pose's points).
  {
    SubdModel m = make_subd_model(sphere_cage(24, 6, 1.0f), Scheme::gregory);
    m.rig =
        morph_rig(m.cage, [](const glm::vec3& p) { return glm::vec3(0.1f * p.x * p.y, 0.2f * p.z * p.z, 0.3f * p.x); });
    const std::vector<glm::vec3> rest = m.precomputed;
    RigPose pose;
    pose.instance_matrices = {glm::mat4(glm::vec4(0.8f, 0.6f, 0.0f, 0.0f), glm::vec4(-0.6f, 0.8f, 0.0f, 0.0f),
                                        glm::vec4(0.0f, 0.0f, 1.0f, 0.0f), glm::vec4(0.1f, 0.2f, 0.3f, 1.0f))};
    pose.joint_matrices.resize(1);
    pose.target_weights = {0.7f};
    set_pose(m, pose);
    CHECK(m.precomputed != rest);
    for (const VaryingFactors c : kVaryingFactors) {
      INFO("posed " << ts::to_string(c.partitioning));
      check_watertight(weld(m, c.factor, c.vary, c.partitioning));
    }
  }
  // catmark_pole64: a valence-64 vertex among triangles, on an open disc;
  // catmark_bishop: valences 16 to 24 among triangles and creases, open at its base. Both are open
  // only where the cage is: the border's segments, as many as the exact limit's.
  for (const char* cage : {"osd-shapes/catmark_pole64.obj", "osd-shapes/catmark_bishop.obj"}) {
    const verify::WeldReport border =
        weld(load_subd_model(data(cage), Scheme::exact), 2.6f, 1.3f, ts::Partitioning::fractional_even);
    REQUIRE(border.open_edges > 0);
    for (Scheme s : {Scheme::bspline, Scheme::gregory}) {
      INFO(cage << " " << to_string(s));
      const SubdModel m = load_subd_model(data(cage), s);
      CHECK(!m.patches.precomputed.empty());
      const verify::WeldReport r = weld(m, 2.6f, 1.3f, ts::Partitioning::fractional_even);
      CHECK(r.nonmanifold_edges == 0);
      CHECK(r.degenerate_triangles == 0);
      CHECK(r.open_edges == border.open_edges);
    }
  }
}

TEST_CASE("Gregory, bspline and pn are watertight on closed quad-triangle cages at factors varying per edge",
          "[subd]") {
  // catmark_pyramid (4 triangles on a quad), catmark_smoothtris0 (80 triangles, two valence-20 poles; a
  // vertex at x = -0, whose corners must weld with +0), loop_cube and loop_tetrahedron (all triangles)
  // and the mixed cube above (triangles and quads around one vertex).
  auto check = [](const SubdModel& m, const std::string& name) {
    REQUIRE(m.patches.tris.size() > 0);
    for (const VaryingFactors c : kVaryingFactors) {
      INFO(name << " " << to_string(m.patches.scheme) << " " << ts::to_string(c.partitioning));
      check_watertight(weld(m, c.factor, c.vary, c.partitioning));
    }
  };
  for (Scheme s : {Scheme::gregory, Scheme::bspline, Scheme::pn, Scheme::exact}) {
    for (const char* cage : {"osd-shapes/catmark_pyramid.obj", "osd-shapes/catmark_smoothtris0.obj",
                             "osd-shapes/loop_cube.obj", "osd-shapes/loop_tetrahedron.obj"})
      check(load_subd_model(data(cage), s), cage);
    check(mixed_cube(s), "mixed cube");
  }
}

TEST_CASE("Triangular Gregory face points make the surface G1 across triangle-quad and triangle-triangle edges",
          "[subd]") {
  // The face points are derived from the condition that the cross-boundary derivatives of the two
  // patches on an edge add up to 2 c(t) T(t) (patch_stencils.cpp), so the normals of the two patches
  // agree all along every edge of a closed untagged cage, up to float round-off. The quad rule on a
  // triangle (F = E + (k1 + r) / 3) breaks this by degrees.
  for (const bool mixed : {false, true}) {
    const SubdModel m =
        mixed ? mixed_cube(Scheme::gregory) : load_subd_model(data("osd-shapes/catmark_pyramid.obj"), Scheme::gregory);
    INFO((mixed ? "mixed cube" : "pyramid"));
    std::uint64_t mismatched = 0;
    const double jump = max_normal_jump_across_edges(m, mismatched);
    CHECK(mismatched == 0);
    CHECK(jump < 1e-5);  // radians; measured 7e-7 and 5e-7, the quad rule gives 0.049 and 0.023
  }
  // n-gon fans: along the spokes (the same condition with c = 1 at a corner and cos(2 pi / n) at the
  // centre) and along the cage edges (the fan's cross derivative is the mean of the neighbour's quad
  // view and the edge's own derivative).
  for (const Cage& cage :
       {load_obj_cage(data("ngon-cages/dodecahedron.obj")), hexagonal_prism(), pentagonal_pyramid()}) {
    const SubdModel m = make_subd_model(cage, Scheme::gregory);
    INFO(m.cage.name);
    std::uint64_t mismatched = 0;
    const double jump = max_normal_jump_across_edges(m, mismatched);
    CHECK(mismatched == 0);
    CHECK(jump < 1e-5);
  }
}

TEST_CASE("Gregory triangles stay close to the exact limit surface", "[subd]") {
  // The mixed cube at factor 7, parametric distance (the tri domain against the limit surface's own
  // triangle parametrization, limit_surface.h) relative to the bounding-box diagonal, triangles only.
  const SubdModel m = mixed_cube(Scheme::gregory);
  const LimitSurface exact = LimitSurface::create(m.cage);
  const double diagonal = exact.bounding_box_diagonal();
  Device device(DeviceOptions{});
  SubdFactors f;
  f.factor = 7;
  double sum2 = 0, max_d = 0, angle = 0;
  std::size_t n = 0;
  stream_subd(device, m, f, ts::Partitioning::integer, [&](const PatchOutput<SurfaceSample>& out, const PatchGroup& g) {
    if (g.domain != ts::Domain::tri) return;
    for (const SurfaceSample& p : out.points) {
      const SurfacePoint e = exact.evaluate_triangle(g.patches[out.patch_id].face, p.u, p.v, (1.0f - p.u) - p.v);
      const double d = glm::length(p.position - e.position);
      sum2 += d * d;
      max_d = std::max(max_d, d);
      angle += std::acos(std::clamp(double(glm::dot(p.normal, e.normal)), -1.0, 1.0));
      ++n;
    }
  });
  REQUIRE(n > 0);
  INFO("rms " << std::sqrt(sum2 / double(n)) / diagonal << " max " << max_d / diagonal << " mean angle "
              << angle / double(n));
  CHECK(std::sqrt(sum2 / double(n)) / diagonal < 1e-2);
  CHECK(max_d / diagonal < 2.5e-2);
  CHECK(angle / double(n) < 0.075);  // radians, 4.3 degrees
}

TEST_CASE("PN triangles and quads: planar faces stay flat and linear, corners and normals interpolate", "[subd]") {
  // A planar triangle or parallelogram with the plane's normal at every corner has straight edges
  // with points at thirds, so the PN triangle is the linear triangle (its centre rule adds nothing) and
  // the Coons interior makes the PN quad the bilinear patch.
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const std::array<glm::vec3, 3> tp{glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(3.0f, 0.5f, 2.0f),
                                    glm::vec3(1.0f, 2.0f, 2.0f)};
  const std::array<glm::vec3, 3> tn{n, n, n};
  const PNTriangle t = pn_triangle(tp, tn);
  const std::array<glm::vec3, 4> qp{glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(3.0f, 0.5f, 2.0f),
                                    glm::vec3(4.0f, 2.5f, 2.0f), glm::vec3(1.0f, 2.0f, 2.0f)};
  const std::array<glm::vec3, 4> qn{n, n, n, n};
  const PNQuad q = pn_quad(qp, qn);
  for (int i = 1; i < 8; ++i)
    for (int j = 1; i + j < 8; ++j) {
      const float u = float(i) / 8.0f, v = float(j) / 8.0f, w = (1.0f - u) - v;
      const glm::vec3 p = cubic_triangle(t.b, u, v, w).position;
      CHECK(glm::length(p - (w * tp[0] + u * tp[1] + v * tp[2])) < 1e-5f);
      CHECK(glm::length(quadratic_triangle_normal(t.n, u, v, w) - n) < 1e-6f);
      const glm::vec3 b = bezier_patch(q.b, u, v).position;
      const glm::vec3 bl = (1.0f - v) * ((1.0f - u) * qp[0] + u * qp[1]) + v * ((1.0f - u) * qp[3] + u * qp[2]);
      CHECK(glm::length(b - bl) < 1e-5f);
    }
  // Curved: corners interpolate, corner normals are the vertex normals, an edge leaves its corner in the
  // corner's tangent plane, and the centre bulges by (E - V) / 2.
  const std::array<glm::vec3, 3> cn{glm::normalize(glm::vec3(-0.3f, -0.2f, 1.0f)),
                                    glm::normalize(glm::vec3(0.4f, 0.0f, 1.0f)),
                                    glm::normalize(glm::vec3(0.0f, 0.5f, 1.0f))};
  const PNTriangle c = pn_triangle(tp, cn);
  CHECK(cubic_triangle(c.b, 0.0f, 0.0f, 1.0f).position == tp[0]);
  CHECK(cubic_triangle(c.b, 1.0f, 0.0f, 0.0f).position == tp[1]);
  CHECK(glm::length(quadratic_triangle_normal(c.n, 0.0f, 1.0f, 0.0f) - cn[2]) < 1e-6f);
  CHECK(std::abs(glm::dot(c.b[std::size_t(tri_index(3, 1, 0))] - tp[0], cn[0])) < 1e-6f);
  glm::vec3 e(0.0f);
  for (int i : {1, 2, 4, 6, 7, 8}) e += c.b[std::size_t(i)];
  e /= 6.0f;
  const glm::vec3 centre = (tp[0] + tp[1] + tp[2]) / 3.0f;
  CHECK(glm::length(c.b[std::size_t(tri_index(3, 1, 1))] - (e + 0.5f * (e - centre))) < 1e-5f);
}

TEST_CASE("pn normals are continuous to the bit: every welded point has one normal", "[subd]") {
  for (const char* cage : {"osd-shapes/catmark_pyramid.obj", "osd-shapes/catmark_cube.obj"}) {
    const SubdModel m = load_subd_model(data(cage), Scheme::pn);
    SubdFactors f;
    f.factor = 3.3f;
    f.vary = 1.0f;
    const Weld w = weld_model(m, f, ts::Partitioning::fractional_even, true);
    INFO(cage);
    CHECK(w.shared_points > 0);
    CHECK(w.normal_mismatches == 0);
  }
}

TEST_CASE("Every scheme but acc and pn draws triangles and n-gons watertight next to quads and triangles", "[subd]") {
  // An n-gon is a fan of triangles whose outer edge is the whole cage edge, tessellated with that
  // edge's factor like the neighbour's; drawing it as quad sub-patches left T-junctions here (the
  // sub-patches' half edges against the neighbour's whole edge), which this weld finds.
  std::vector<std::pair<std::string, Cage>> cages;
  for (const char* name : {"osd-shapes/catmark_pyramid.obj", "osd-shapes/catmark_gregory_test8.obj"})
    cages.emplace_back(name, load_obj_cage(data(name)));
  cages.emplace_back("pentagonal pyramid", pentagonal_pyramid());
  cages.emplace_back("hexagonal prism", hexagonal_prism());
  for (const auto& [name, cage] : cages)
    for (Scheme s : {Scheme::flat, Scheme::exact, Scheme::adaptive, Scheme::gregory, Scheme::bspline}) {
      const SubdModel m = make_subd_model(cage, s);
      for (const VaryingFactors c : {VaryingFactors{ts::Partitioning::integer, 4.0f, 0.0f}, kVaryingFactors[0],
                                     kVaryingFactors[1], kVaryingFactors[2]}) {
        INFO(name << " " << to_string(s) << " " << ts::to_string(c.partitioning) << " vary " << c.vary);
        SubdFactors f;
        f.factor = c.factor;
        f.vary = c.vary;
        const Weld w = weld_model(m, f, c.partitioning, true);
        check_watertight(w.report);
        // The exact surface is smooth: one normal per welded point (flat is faceted; the per-face schemes
        // are G1 only approximately).
        if (uses_limit_surface(s)) CHECK(w.normal_mismatches == 0);
      }
    }
}

TEST_CASE("An n-gon's fan takes its cage edges whole and shares its spokes", "[subd]") {
  for (Scheme s : {Scheme::flat, Scheme::exact, Scheme::gregory}) {
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
  for (int k = 0; k < 33; ++k)
    obj += "v " + std::to_string(std::cos(k / 5.25)) + " " + std::to_string(std::sin(k / 5.25)) + " 0\n";
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

// A pentagon whose corners have valence 8: each corner fans six triangles out to an arc, so a fan
// triangle's ring (every corner's 1-ring, which the centre reads) has all 35 points, over an IA patch's 32.
// The surface is bent (z = 0.2 x y) so that it has curvature.
Cage pentagon_among_fans() {
  constexpr int kFan = 6;
  std::string obj;
  auto vertex = [&](double x, double y) {
    obj += "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(0.2 * x * y) + "\n";
  };
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < 5; ++i) vertex(std::cos(2 * pi * i / 5), std::sin(2 * pi * i / 5));
  // Corner i's arc: kFan + 1 points from the outer point of edge i - 1 to that of edge i, at radius 2.
  // Arc point j of corner i is vertex 6 + i * kFan + j (1-based), and the last of corner i is the first
  // of corner i + 1.
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < kFan; ++j) {
      const double a = 2 * pi * (i - 0.5 + double(j) / kFan) / 5;
      vertex(2 * std::cos(a), 2 * std::sin(a));
    }
  auto arc = [&](int i, int j) { return 6 + ((i * kFan + j) % (5 * kFan)); };
  obj += "f 1 2 3 4 5\n";
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < kFan; ++j)
      obj +=
          "f " + std::to_string(i + 1) + " " + std::to_string(arc(i, j)) + " " + std::to_string(arc(i, j + 1)) + "\n";
    // The triangle between corner i, the next corner and their shared arc point.
    obj += "f " + std::to_string(i + 1) + " " + std::to_string(arc(i, kFan)) + " " + std::to_string((i + 1) % 5 + 1) +
           "\n";
  }
  return parse_obj_cage(obj, "pentagon_among_fans");
}

TEST_CASE("gregory draws an n-gon as a fan of Gregory triangles: exact centre, watertight, close to the limit",
          "[subd]") {
  // The fan's centre corner is the exact limit at the face's centre (one Catmull-Clark step, then the
  // all-quad masks), to float round-off.
  for (const Cage& cage : {hexagonal_prism(), pentagon_among_fans()}) {
    const SubdModel m = make_subd_model(cage, Scheme::gregory);
    const LimitSurface exact = LimitSurface::create(m.cage);
    Device device(DeviceOptions{});
    SubdFactors f;
    f.factor = 1;
    int centres = 0;
    stream_subd(device, m, f, ts::Partitioning::integer,
                [&](const PatchOutput<SurfaceSample>& out, const PatchGroup& g) {
                  const SubdPatch& p = g.patches[out.patch_id];
                  if (g.domain != ts::Domain::tri || m.cage.face_sizes[std::size_t(p.face)] < 5) return;
                  CHECK(p.kind == PatchKind::gregory_triangle);
                  for (std::size_t i = 0; i < out.points.size(); ++i)
                    if (out.domain[i].v == 1.0f) {
                      const glm::vec3 e = exact.evaluate_fan(p.face, p.sub, 0.0f, 1.0f, 0.0f).position;
                      INFO(m.cage.name << " face " << p.face << " fan " << p.sub);
                      CHECK(glm::length(out.points[i].position - e) < 1e-5f);
                      ++centres;
                    }
                });
    CHECK(centres == (m.cage.name == "hexagonal_prism" ? 12 : 5));
  }
  // A fan over a ring of 40 points is precomputed and still welds to its ordinary neighbours, plain,
  // creased (the crease blend keeps the P and E points the neighbours compute) and posed.
  SubdModel fans = make_subd_model(pentagon_among_fans(), Scheme::gregory);
  int precomputed = 0;
  for (const SubdPatch& p : fans.patches.tris.patches)
    precomputed += p.precomputed >= 0 && fans.cage.face_sizes[std::size_t(p.face)] == 5;
  CHECK(precomputed == 5);
  std::string creased_obj =
      "v 0 0 0\nv 1 0 0\nv 1.3 0.9 0.1\nv 0.5 1.5 0\nv -0.3 0.9 -0.1\n"
      "v 0.2 0.4 1\n"
      "f 5 4 3 2 1\nf 1 2 6\nf 2 3 6\nf 3 4 6\nf 4 5 6\nf 5 1 6\n"
      "t crease 2/1/0 1 2 10\nt crease 2/1/0 2 3 0.6\nt corner 1/1/0 3 10\n";
  const SubdModel creased = make_subd_model(parse_obj_cage(creased_obj, "creased_pentagon"), Scheme::gregory);
  for (const SubdModel* m : std::array<const SubdModel*, 2>{&fans, &creased})
    for (const VaryingFactors c : kVaryingFactors) {
      INFO(m->cage.name << " " << ts::to_string(c.partitioning));
      if (m == &fans) {
        const verify::WeldReport r = weld(*m, c.factor, c.vary, c.partitioning);
        CHECK(r.nonmanifold_edges == 0);  // an open disc: open only along its arc
        CHECK(r.degenerate_triangles == 0);
      } else {
        check_watertight(weld(*m, c.factor, c.vary, c.partitioning));
      }
    }
  {
    fans.rig = morph_rig(fans.cage,
                         [](const glm::vec3& p) { return glm::vec3(0.1f * p.x * p.y, 0.2f * p.y, 0.3f * p.x * p.x); });
    const verify::WeldReport rest = weld(fans, 3.0f, 1.0f, ts::Partitioning::fractional_odd);
    RigPose pose;
    pose.instance_matrices = {glm::mat4(1.0f)};
    pose.joint_matrices.resize(1);
    pose.target_weights = {0.8f};
    const std::vector<glm::vec3> before = fans.precomputed;
    set_pose(fans, pose);
    CHECK(fans.precomputed != before);
    const verify::WeldReport posed = weld(fans, 3.0f, 1.0f, ts::Partitioning::fractional_odd);
    CHECK(posed.nonmanifold_edges == 0);
    CHECK(posed.open_edges == rest.open_edges);
  }
  // Close to the limit: the fan's domain mapped into the face's sub-patches as the exact scheme maps it
  // (fan_location); relative to the bounding-box diagonal.
  for (const char* name : {"osd-shapes/catmark_nonquads.obj", "osd-shapes/catmark_gregory_test5.obj"}) {
    const SubdModel m = load_subd_model(data(name), Scheme::gregory);
    const LimitSurface exact = LimitSurface::create(m.cage);
    Device device(DeviceOptions{});
    SubdFactors f;
    f.factor = 9;
    double max_d = 0, angle = 0;
    std::size_t n = 0;
    stream_subd(
        device, m, f, ts::Partitioning::integer, [&](const PatchOutput<SurfaceSample>& out, const PatchGroup& g) {
          const SubdPatch& p = g.patches[out.patch_id];
          const int sides = m.cage.face_sizes[std::size_t(p.face)];
          if (sides < 5) return;
          for (std::size_t i = 0; i < out.points.size(); ++i) {
            const LimitSurface::SubPatchLocation l =
                LimitSurface::fan_location(sides, p.sub, out.domain[i].u, out.domain[i].v);
            const ReferenceSample e = exact.sample_reference(p.face, l.sub, l.s, l.t);
            max_d = std::max(max_d, glm::length(glm::dvec3(out.points[i].position) - e.position));
            angle +=
                std::acos(std::clamp(glm::dot(glm::dvec3(out.points[i].normal), glm::normalize(e.normal)), -1.0, 1.0));
            ++n;
          }
        });
    REQUIRE(n > 0);
    INFO(name << " max " << max_d / exact.bounding_box_diagonal() << " mean angle " << angle / double(n));
    // The shapes give 4.1e-3 / 1.4 degrees and 1.5e-2 / 1.9 degrees; twist-free face points would give
    // 2.1 and 3.0 degrees, over the bound.
    CHECK(max_d / exact.bounding_box_diagonal() < 2e-2);
    CHECK(angle / double(n) < 0.045);  // radians, 2.6 degrees
  }
}

TEST_CASE("On open cages with n-gons the only open edges are the cage's boundary", "[subd]") {
  // Integer partitioning: a cage edge of factor F is ceil(F) segments, on each side.
  for (const char* cage : {"osd-shapes/catmark_nonquads.obj", "osd-shapes/catmark_gregory_test2.obj",
                           "osd-shapes/catmark_gregory_test5.obj", "osd-shapes/catmark_val2_foldover.obj"})
    for (Scheme s : {Scheme::flat, Scheme::exact, Scheme::gregory}) {
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
          expected +=
              std::uint64_t(std::ceil(f.edge(cage_edge_key(m.topology->origin(h), m.topology->destination(h)))));
        }
      REQUIRE(expected > 0);
      const verify::WeldReport r = weld(m, f, ts::Partitioning::integer);
      CHECK(r.open_edges == expected);
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
    CHECK(r.open_edges == std::uint64_t(5 * boundary));
    CHECK(r.nonmanifold_edges == 0);
  }
}

TEST_CASE("The weld check sees a crack: one vertex moved by one ulp opens its edges", "[subd]") {
  verify::WeldChecker ok, cracked;
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
  CHECK(r.open_edges == 4);
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
    stream_subd(device, m, f, ts::Partitioning::integer,
                [&](const PatchOutput<SurfaceSample>& out, const PatchGroup& g) {
                  for (const SurfaceSample& p : out.points) {
                    const SurfacePoint e = exact.limit->evaluate(g.patches[out.patch_id].face, 0, p.u, p.v);
                    max_d = std::max(max_d, double(glm::length(p.position - e.position)));
                    max_angle = std::max(max_angle, double(std::acos(std::min(1.0f, glm::dot(p.normal, e.normal)))));
                  }
                });
    INFO(to_string(s));
    CHECK(max_d < 1e-5);      // the torus is about 3.4 across: float round-off
    CHECK(max_angle < 1e-3);  // radians
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
    stream_subd(device, m, f, ts::Partitioning::integer,
                [&](const PatchOutput<SurfaceSample>& out, const PatchGroup& g) {
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
  struct Case {
    const char* cage;
    Scheme scheme;
  };
  for (const Case c : {Case{"sdk-cages/monsterfrog_mapped_00.obj", Scheme::acc},
                       Case{"sdk-cages/monsterfrog_mapped_00.obj", Scheme::pn},
                       Case{"osd-shapes/catmark_smoothtris0.obj", Scheme::gregory}}) {
    INFO(c.cage << " " << to_string(c.scheme));
    const SubdModel m = load_subd_model(data(c.cage), c.scheme);
    auto digest = [&](int threads) {
      DeviceOptions o;
      o.threads = threads;
      o.chunk_primitives = threads == 1 ? 16384 : 777;
      Device device(o);
      std::uint64_t h = 1469598103934665603ull;
      SubdFactors f;
      f.factor = 3.5f;
      f.vary = 1.0f;
      stream_subd(device, m, f, ts::Partitioning::fractional_odd,
                  [&](const PatchOutput<SurfaceSample>& out, const PatchGroup&) {
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
  // Pentagons: pn takes triangles and quads only, acc quads only.
  for (Scheme s : {Scheme::acc, Scheme::pn}) {
    INFO(to_string(s));
    try {
      load_subd_model(data("osd-shapes/catmark_gregory_test2.obj"), s);
      FAIL("no error");
    } catch (const CageError& e) {
      const std::string m = e.what();
      CHECK(m.find("catmark_gregory_test2.obj: face") != std::string::npos);
      if (s == Scheme::pn) {
        CHECK(m.find("has 5 sides") != std::string::npos);
        CHECK(m.find("triangles and quads only") != std::string::npos);
      } else {  // a quad beside the pentagon comes first
        CHECK(m.find("--scheme acc") != std::string::npos);
        CHECK(m.find("quad") != std::string::npos);
      }
      CHECK(m.find('\n') == std::string::npos);
    }
  }
}

TEST_CASE("Exact draws only the faces OpenSubdiv gives a surface: boundary faces under interpolateboundary none",
          "[subd]") {
  // catmark_edgenone: `t interpolateboundary 0`, so its boundary faces have no limit surface; drawing
  // them used to fail with "face 0 has no surface". Every face with a surface is drawn exactly once,
  // and the drawn region's only open edges are its own boundary (welded on exact bits).
  const SubdModel m = load_subd_model(data("osd-shapes/catmark_edgenone.obj"), Scheme::exact);
  REQUIRE(m.cage.tags.boundary == BoundaryInterpolation::none);
  std::vector<int> drawn(std::size_t(m.cage.face_count()), 0);
  for (const SubdPatch& p : m.patches.quads.patches) ++drawn[std::size_t(p.face)];
  for (const SubdPatch& p : m.patches.tris.patches) ++drawn[std::size_t(p.face)];
  int with_surface = 0;
  for (int f = 0; f < m.cage.face_count(); ++f) {
    const int expected =
        m.limit->has_surface(f) ? m.limit->sub_patch_count(f) == 1 ? 1 : m.cage.face_sizes[std::size_t(f)] : 0;
    CHECK(drawn[std::size_t(f)] == expected);
    with_surface += m.limit->has_surface(f);
  }
  CHECK(with_surface > 0);
  CHECK(with_surface < m.cage.face_count());
  CHECK(m.patches.holes == m.cage.face_count() - with_surface);
  // Open edges of the drawn region: cage edges with exactly one drawn face, 3 segments each at factor 3.
  const Topology& t = *m.topology;
  int region_boundary = 0;
  for (int e = 0; e < t.edge_count(); ++e) {
    const auto [h0, h1] = t.edge_half_edges(e);
    region_boundary += (drawn[std::size_t(t.face(h0))] > 0) != (h1 >= 0 && drawn[std::size_t(t.face(h1))] > 0);
  }
  const auto r = weld(m, 3.0f, 0.0f, ts::Partitioning::integer);
  CHECK(r.open_edges == std::uint64_t(3 * region_boundary));
  CHECK(r.nonmanifold_edges == 0);
  CHECK(r.degenerate_triangles == 0);
}

TEST_CASE("limit fit: on regular faces the fitted Gregory points are the B-spline patch's", "[subd]") {
  // A least-squares fit to the limit reproduces it where a bicubic can: the torus's faces are all
  // regular, so the fitted edge and face points must be the masks' (the B-spline patch's Bezier points)
  // to round-off, as stencils, weight for weight. A fit that sampled the wrong place, mixed up the
  // rotation or the Gregory layout, or solved the normal equations wrongly fails this.
  const Cage cage = torus_cage(8, 6, 2.0f, 0.7f);
  const Topology t(cage);
  const LimitStencils limit(cage);
  auto same = [](const Stencil& a, const Stencil& b) {
    std::map<int, double> d;
    for (const auto& [v, w] : a.terms) d[v] += w;
    for (const auto& [v, w] : b.terms) d[v] -= w;
    double worst = 0.0;
    for (const auto& [v, w] : d) worst = std::max(worst, std::abs(w));
    return worst;
  };
  for (const int f : {0, 13, 40})
    for (const int rotation : {0, 1, 3}) {
      std::array<CornerRing, 4> rings;
      for (int k = 0; k < 4; ++k) rings[std::size_t(k)] = gather_corner_ring(cage, t, f, (k + rotation) % 4);
      const std::vector<Stencil> masks = gregory_quad_stencils(rings);
      std::vector<Stencil> fitted = masks;
      for (std::size_t k = 0; k < 4; ++k) fitted[5 * k + 3] = fitted[5 * k + 4] = Stencil{};
      REQUIRE(fit_face_points(limit, f, rotation, fitted));
      for (std::size_t r = 0; r < 20; ++r) {
        INFO("face " << f << " rotation " << rotation << " row " << r);
        CHECK(same(fitted[r], masks[r]) < 1e-9);
      }
      // Patch edge 0 is face edge `rotation`: its two Bezier points beside patch corners 0 and 1.
      const std::optional<EdgePoints> e = fit_edge_points(limit, f, rotation, masks[0], masks[5]);
      REQUIRE(e);
      CHECK(same(e->near_a, masks[1]) < 1e-9);
      CHECK(same(e->near_b, masks[7]) < 1e-9);
    }
}

TEST_CASE("polar triangles: a bicubic with a collapsed row, its edges the Gregory triangle's bits", "[subd]") {
  // Random points in the 15 slots: on the three edges the polar patch is the Gregory triangle's cubic,
  // bit for bit (what its neighbours compute); inside it is the bicubic b(s, t), s = v / (u + v),
  // t = u + v, and its derivatives the chain rule's (checked against central differences).
  std::array<glm::vec3, 15> g;
  std::uint32_t seed = 12345u;
  auto next = [&] {
    seed = seed * 1664525u + 1013904223u;
    return float(seed >> 8) / float(1u << 24) - 0.5f;
  };
  for (glm::vec3& p : g) p = {next(), next(), next()};
  for (int i = 0; i <= 16; ++i) {
    const float t = float(i) / 16.0f;
    for (const auto& [u, v] : {std::pair{t, 0.0f}, std::pair{1.0f - t, t}, std::pair{0.0f, t}}) {
      const float w = (1.0f - u) - v;
      CHECK(polar_triangle(g, u, v, w).position == gregory_triangle(g, u, v, w).position);
    }
  }
  // The pole: every s gives the pole's point.
  CHECK(polar_triangle(g, 0.0f, 0.0f, 1.0f).position == g[0]);
  const std::array<glm::vec3, 16> b = {g[0], g[0], g[0], g[0],  g[1], g[3], g[4],  g[2],
                                       g[7], g[8], g[9], g[11], g[5], g[6], g[12], g[10]};
  for (int i = 1; i < 8; ++i)
    for (int j = 1; i + j < 8; ++j) {
      const float u = float(i) / 8.0f, v = float(j) / 8.0f, w = (1.0f - u) - v;
      const PatchPoint p = polar_triangle(g, u, v, w);
      CHECK(glm::length(p.position - bezier_patch(b, v / (u + v), u + v).position) < 1e-6f);
      constexpr float h = 1.0f / 1024.0f;
      const glm::vec3 du =
          (polar_triangle(g, u + h, v, w - h).position - polar_triangle(g, u - h, v, w + h).position) / (2.0f * h);
      const glm::vec3 dv =
          (polar_triangle(g, u, v + h, w - h).position - polar_triangle(g, u, v - h, w + h).position) / (2.0f * h);
      CHECK(glm::length(p.du - du) < 2e-3f * (1.0f + glm::length(du)));
      CHECK(glm::length(p.dv - dv) < 2e-3f * (1.0f + glm::length(dv)));
    }
}

TEST_CASE("polar configurations: gregory and bspline draw their triangles as polar patches, watertight to the bit",
          "[subd]") {
  // A latitude-longitude sphere: valence 5 stays Gregory triangles (kPolarMinValence), 8 and 32 (a
  // 1-ring of over 32 points: precomputed) become polar; an all-quad pole has no triangles.
  auto polar_count = [](const SubdModel& m) {
    int polar = 0;
    for (const SubdPatch& p : m.patches.tris.patches) polar += p.kind == PatchKind::polar_triangle;
    return polar;
  };
  CHECK(polar_count(make_subd_model(sphere_cage(5, 6, 1.0f, true), Scheme::gregory)) == 0);
  CHECK(polar_count(make_subd_model(sphere_cage(8, 6, 1.0f), Scheme::gregory)) == 0);
  CHECK(polar_count(load_subd_model(data("osd-shapes/catmark_pole8.obj"), Scheme::gregory)) == 8);
  // A tag at the pole or on a spoke keeps the Gregory triangles (the creased construction).
  Cage tagged = sphere_cage(8, 6, 1.0f, true);
  tagged.tags.creases.push_back({tagged.vertex_count() - 2, 0, 2.0f});  // a spoke of the south pole
  CHECK(polar_count(make_subd_model(tagged, Scheme::gregory)) == 8);    // the north pole's
  for (const int n : {8, 32})
    for (Scheme s : {Scheme::gregory, Scheme::bspline}) {
      const SubdModel m = make_subd_model(sphere_cage(n, 6, 1.0f, true), s);
      INFO(n << " " << to_string(s));
      CHECK(polar_count(m) == 2 * n);
      CHECK(m.patches.precomputed.empty() == (n < 32));
      for (const VaryingFactors c : kVaryingFactors) {
        INFO(ts::to_string(c.partitioning));
        check_watertight(weld(m, c.factor, c.vary, c.partitioning));
      }
    }
  // Posed by a morph target: the polar rows follow the pose, as every stencil does.
  SubdModel m = make_subd_model(sphere_cage(12, 6, 1.0f, true), Scheme::gregory);
  m.rig =
      morph_rig(m.cage, [](const glm::vec3& p) { return glm::vec3(0.3f * p.y * p.y, 0.1f * p.x, 0.2f * p.z * p.x); });
  RigPose pose;
  pose.instance_matrices = {glm::mat4(1.0f)};
  pose.joint_matrices.resize(1);
  pose.target_weights = {0.8f};
  set_pose(m, pose);
  for (const VaryingFactors c : kVaryingFactors) check_watertight(weld(m, c.factor, c.vary, c.partitioning));
  // One tangent plane at the pole: every sector's normal a step from it (the domain shader's normal at
  // the pole itself) within a degree of the sphere's axis.
  const SubdModel sphere = make_subd_model(sphere_cage(16, 6, 1.0f, true), Scheme::gregory);
  Device device(DeviceOptions{});
  SubdFactors f;
  f.factor = 4;
  int poles = 0;
  stream_subd(device, sphere, f, ts::Partitioning::integer,
              [&](const PatchOutput<SurfaceSample>& out, const PatchGroup& g) {
                if (g.patches[out.patch_id].kind != PatchKind::polar_triangle) return;
                for (std::size_t i = 0; i < out.points.size(); ++i) {
                  const SurfaceSample& s = out.points[i];
                  if (out.domain[i].u != 0.0f || out.domain[i].v != 0.0f) continue;
                  INFO(s.position.x << " " << s.position.y << " " << s.position.z);
                  CHECK(std::abs(s.normal.y) > std::cos(std::numbers::pi_v<float> / 180.0f));
                  CHECK(s.normal.y * s.position.y > 0.0f);  // outward
                  ++poles;
                }
              });
  CHECK(poles == 2 * 16);
}

TEST_CASE("PatchLanes evaluates ACC, Gregory and triangular Gregory patches with the scalar functions' bits",
          "[subd][lanes]") {
  // Control points from a fixed generator, well away from any symmetry; locations: a factor-23 grid
  // (interior, the four edges, the corners) and a short last group, in an order that mixes them.
  std::uint32_t state = 12345u;
  const auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) * 4.0f - 2.0f;
  };
  const auto point = [&] { return glm::vec3(next(), next(), next()); };
  std::array<glm::vec3, 16> b;
  std::array<glm::vec3, 12> du, dv;
  std::array<glm::vec3, 20> g;
  for (auto& p : b) p = point();
  for (auto& p : du) p = point();
  for (auto& p : dv) p = point();
  for (auto& p : g) p = point();
  std::vector<float> u, v;
  for (int j = 0; j <= 23; ++j)
    for (int i = 0; i <= 23; ++i) u.push_back(float(i) / 23.0f), v.push_back(float((j * 7) % 24) / 23.0f);
  u.push_back(1.0f), v.push_back(0.0f);  // 577 locations: the last group has one
  const auto same = [](const glm::vec3& a, const glm::vec3& e) {
    return std::bit_cast<std::array<std::uint32_t, 3>>(a) == std::bit_cast<std::array<std::uint32_t, 3>>(e);
  };
  std::vector<PatchPoint> lanes(u.size());
  PatchLanes::acc(b, du, dv, u, v, lanes);
  std::size_t acc_wrong = 0, gregory_wrong = 0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    PatchPoint e = bezier_patch(b, u[i], v[i]);
    acc_tangents(du, dv, u[i], v[i], e.du, e.dv);
    acc_wrong += !(same(lanes[i].position, e.position) && same(lanes[i].du, e.du) && same(lanes[i].dv, e.dv));
  }
  PatchLanes::gregory(g, u, v, lanes);
  for (std::size_t i = 0; i < u.size(); ++i) {
    const PatchPoint e = bezier_patch(gregory_to_bezier(g, u[i], v[i]), u[i], v[i]);
    gregory_wrong += !(same(lanes[i].position, e.position) && same(lanes[i].du, e.du) && same(lanes[i].dv, e.dv));
  }
  CHECK(acc_wrong == 0);
  CHECK(gregory_wrong == 0);

  // The triangular Gregory patch on the tri domain: its three edges (w exactly 0 on the third), the
  // corners, the interior.
  std::array<glm::vec3, 15> gt;
  for (auto& p : gt) p = point();
  std::vector<float> tu, tv, tw;
  for (int j = 0; j <= 23; ++j)
    for (int i = 0; i + j <= 23; ++i) {
      tu.push_back(float(i) / 23.0f), tv.push_back(float(j) / 23.0f);
      tw.push_back(i + j == 23 ? 0.0f : 1.0f - tu.back() - tv.back());
    }
  std::vector<PatchPoint> tri(tu.size());
  PatchLanes::gregory_triangle(gt, tu, tv, tw, tri);
  std::size_t triangle_wrong = 0;
  for (std::size_t i = 0; i < tu.size(); ++i) {
    const PatchPoint e = gregory_triangle(gt, tu[i], tv[i], tw[i]);
    triangle_wrong += !(same(tri[i].position, e.position) && same(tri[i].du, e.du) && same(tri[i].dv, e.dv));
  }
  CHECK(tu.size() % 8 != 0);  // a short last group
  CHECK(triangle_wrong == 0);
}

#include <set>

#include "shaders_cpp/render/surface_framing.h"
#include "test_data.h"

TEST_CASE("Framing's surface points are the point set the stream draws, each shared point once", "[subd]") {
  using namespace tessera;
  // Quads, triangles and n-gon fans, creases, the exact and adaptive limit, a small wrapping torus.
  struct Case {
    std::string path;
    Scheme scheme;
  };
  const std::vector<Case> cases = {{test::data("sdk-cages/monsterfrog_mapped_00.obj"), Scheme::gregory},
                                   {test::data("osd-shapes/catmark_nonquads.obj"), Scheme::gregory},
                                   {test::data("osd-shapes/catmark_cube_creases1.obj"), Scheme::exact},
                                   {test::data("osd-shapes/catmark_single_crease.obj"), Scheme::adaptive},
                                   {test::data("osd-shapes/catmark_pyramid.obj"), Scheme::bspline}};
  const auto bits = [](const glm::vec3& p) {
    return std::array<std::uint32_t, 3>{std::bit_cast<std::uint32_t>(p.x), std::bit_cast<std::uint32_t>(p.y),
                                        std::bit_cast<std::uint32_t>(p.z)};
  };
  for (const Case& c : cases) {
    INFO(c.path << " " << to_string(c.scheme));
    const SubdModel m = load_subd_model(c.path, c.scheme);
    const std::size_t patches = m.patches.quads.size() + m.patches.tris.size();
    const float factor =
        float(std::clamp(std::floor(std::sqrt(double(kFramingPoints) / double(patches))) - 1.0, 2.0, 8.0));
    Device device(DeviceOptions{.threads = 2});
    std::set<std::array<std::uint32_t, 3>> streamed;
    std::size_t drawn = 0;
    REQUIRE(stream_subd(device, m, base_factors(factor, 0.0f), ts::Partitioning::integer,
                        [&](const PatchOutput<SurfaceSample>& p, const PatchGroup&) {
                          for (const SurfaceSample& s : p.points) streamed.insert(bits(s.position)), ++drawn;
                        })
                .ok());
    const std::vector<glm::vec3> points = surface_points(m);
    std::set<std::array<std::uint32_t, 3>> framed;
    for (const glm::vec3& p : points) framed.insert(bits(p));
    CHECK(framed == streamed);
    CHECK(points.size() < drawn);
  }
}
