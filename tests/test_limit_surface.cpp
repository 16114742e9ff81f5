// The exact limit surface (shaders_cpp/limit_surface.h): agreement with closed-form B-splines and
// OpenSubdiv's exact vertex limits, bitwise watertightness through ownership, normals, domains,
// and errors.
#include <catch2/catch.hpp>

#include <malloc.h>

#include <opensubdiv/far/primvarRefiner.h>

#include <glm/geometric.hpp>

#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "test_data.h"
#include "tools/measure/limit_accuracy.h"
#include "shaders_cpp/subdiv/limit_surface.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/subdiv/far_patches.h"
#include "shaders_cpp/subdiv/osd_refiner.h"
#include "shaders_cpp/subdiv/semi_sharp_limit.h"
#include "shaders_cpp/cage/topology.h"

using namespace tessera;
using namespace tessera::measure;
using tessera::test::data;
namespace {

// LimitSurface::create's CageError message for `c`, or "" when it takes the cage.
std::string create_error(const Cage& c) {
  try {
    LimitSurface::create(c);
  } catch (const CageError& e) {
    return e.what();
  }
  return "";
}

std::string osd_shape(const std::string& name) { return data("osd-shapes/" + name + ".obj"); }
std::string sdk_cage(const std::string& name) { return data("sdk-cages/" + name + ".obj"); }

// Tessellator-like parameter: k/n rounded to a multiple of 2^-16 (so 1 - t is exact).
float tess_param(int k, int n) { return float(std::nearbyint(double(k) / n * 65536.0) / 65536.0); }

bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return std::bit_cast<std::uint32_t>(a.x) == std::bit_cast<std::uint32_t>(b.x) &&
         std::bit_cast<std::uint32_t>(a.y) == std::bit_cast<std::uint32_t>(b.y) &&
         std::bit_cast<std::uint32_t>(a.z) == std::bit_cast<std::uint32_t>(b.z);
}

// A regular torus cage: n x m grid of quads, vertex (i,j) = i*m + j, face (i,j) has corners
// (i,j),(i+1,j),(i+1,j+1),(i,j+1) -> its (u,v) runs along i and j.
Cage grid_torus(int n, int m) {
  Cage c;
  c.name = "grid_torus";
  const double R = 3.0, r = 1.0, pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double a = 2 * pi * i / n, b = 2 * pi * j / m;
      c.positions.push_back(glm::vec3(float((R + r * std::cos(b)) * std::cos(a)),
                                      float((R + r * std::cos(b)) * std::sin(a)),
                                      float(r * std::sin(b) + 0.1 * std::sin(3 * a))));
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      c.face_offsets.push_back(int(c.face_vertices.size()));
      c.face_sizes.push_back(4);
      for (auto [di, dj] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}})
        c.face_vertices.push_back(((i + di) % n) * m + (j + dj) % m);
    }
  return c;
}

void bspline(double t, double b[4], double d[4]) {
  const double s = 1 - t;
  b[0] = s * s * s / 6;
  b[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
  b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
  b[3] = t * t * t / 6;
  d[0] = -s * s / 2;
  d[1] = (9 * t * t - 12 * t) / 6;
  d[2] = (-9 * t * t + 6 * t + 3) / 6;
  d[3] = t * t / 2;
}

// eval(face, sub, u, v, w): sub >= 0 a quad (sub-)patch, kBarycentric a triangle's barycentric domain,
// kFan - k fan triangle k.
constexpr int kBarycentric = -1, kFan = -2;

// All the ways a tessellated face can ask for the point at parameter t of its edge e (the same
// geometric point): the quad domain, both sub-patches at an n-gon edge's midpoint, a triangle's
// barycentric domain, and the fan triangle on the edge.
template <class Eval>
void edge_queries(const LimitSurface& s, int f, int e, float t, Eval&& eval) {
  const int n = s.face_size(f);
  if (n == 4) {
    const float one = 1.0f;
    switch (e) {
      case 0: eval(f, 0, t, 0.0f, -1.0f); break;
      case 1: eval(f, 0, one, t, -1.0f); break;
      case 2: eval(f, 0, one - t, one, -1.0f); break;
      default: eval(f, 0, 0.0f, one - t, -1.0f); break;
    }
    return;
  }
  if (t <= 0.5f) eval(f, e, 2.0f * t, 0.0f, -1.0f);
  if (t >= 0.5f) eval(f, (e + 1) % n, 0.0f, 2.0f * (1.0f - t), -1.0f);
  const float r = 1.0f - t;
  if (n == 3) {  // barycentric (u, v, w): corner 0 w=1, corner 1 u=1, corner 2 v=1
    if (e == 0) eval(f, kBarycentric, t, 0.0f, r);
    if (e == 1) eval(f, kBarycentric, r, t, 0.0f);
    if (e == 2) eval(f, kBarycentric, 0.0f, r, t);
  }
  eval(f, kFan - e, t, 0.0f, r);  // fan triangle e: its v = 0 edge is the cage edge
}

struct WatertightResult {
  long points = 0, mismatches = 0;
  double max_distance = 0;  // between the representations of one point, relative to the diagonal
};

// Every point of every edge (k/37 and its mirror from the other side), every vertex and every
// n-gon's internal sub-patch edges, evaluated through every face/sub-patch/domain that contains it.
WatertightResult check_watertight(const LimitSurface& s, const Cage& cage, bool owned) {
  WatertightResult res;
  const double diag = s.bounding_box_diagonal();
  std::vector<SurfacePoint> got;
  const auto eval = [&](int f, int sub, float u, float v, float w) {
    if (sub == kBarycentric) {
      got.push_back(s.evaluate_triangle(f, u, v, w));
      return;
    }
    if (sub <= kFan) {
      got.push_back(s.evaluate_fan(f, kFan - sub, u, v, w));
      return;
    }
    got.push_back(owned ? s.evaluate(f, sub, u, v) : s.evaluate_unowned(f, sub, u, v));
  };
  const auto settle = [&] {
    for (std::size_t i = 1; i < got.size(); ++i) {
      ++res.points;
      if (!same_bits(got[i].position, got[0].position) || !same_bits(got[i].normal, got[0].normal)) ++res.mismatches;
      res.max_distance = std::max(res.max_distance, double(glm::length(got[i].position - got[0].position)) / diag);
    }
    got.clear();
  };
  // Edges: collect, per undirected edge, the faces using it and their direction.
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> uses;  // (lo,hi) -> (face, edge)
  for (int f = 0; f < cage.face_count(); ++f) {
    if (!s.has_surface(f)) continue;
    const int n = cage.face_sizes[std::size_t(f)];
    for (int e = 0; e < n; ++e) {
      const int a = cage.face_vertex(f, e), b = cage.face_vertex(f, (e + 1) % n);
      uses[{std::min(a, b), std::max(a, b)}].push_back({f, e});
    }
  }
  for (const auto& [key, fs] : uses) {
    for (int k = 0; k <= 37; ++k) {
      const float t = tess_param(k, 37);  // parameter from key.first to key.second
      for (auto [f, e] : fs) {
        const bool forward = cage.face_vertex(f, e) == key.first;
        // Triangles and fans through their own paths too (only with ownership: the plain path has no
        // barycentric or fan variant, and it is compared through the sub-patches instead).
        edge_queries(s, f, e, forward ? t : 1.0f - t, [&](int ff, int sub, float u, float v, float w) {
          if (sub < 0 && !owned) return;
          eval(ff, sub, u, v, w);
        });
      }
      settle();
    }
  }
  // Internal sub-patch edges and centres of n-gons.
  for (int f = 0; f < cage.face_count(); ++f) {
    const int n = s.sub_patch_count(f);
    if (n < 3) continue;
    for (int k = 0; k < n; ++k)
      for (int i = 0; i <= 37; ++i) {
        const float t = tess_param(i, 37);
        eval(f, k, 1.0f, t, -1.0f);
        eval(f, (k + 1) % n, t, 1.0f, -1.0f);
        settle();
        if (!owned) continue;
        // The fan's spoke from vertex k to the centre, from both fan triangles on it (v = 1: the centre).
        eval(f, kFan - k, 0.0f, t, 1.0f - t);
        eval(f, kFan - (k + n - 1) % n, 1.0f - t, t, 0.0f);
        eval(f, k, t, t, -1.0f);  // the diagonal of sub-patch k
        if (i == 37) eval(f, 0, 1.0f, 1.0f, -1.0f);
        settle();
      }
  }
  return res;
}

const std::vector<std::string> kClosedShapes = {
    "catmark_cube",          "catmark_torus",         "catmark_gregory_test0", "catmark_gregory_test1",
    "catmark_gregory_test2", "catmark_gregory_test3", "catmark_gregory_test5", "catmark_gregory_test7",
    "catmark_gregory_test8", "catmark_nonquads",      "catmark_pyramid",       "catmark_cube_creases1",
    "catmark_hole_test1",    "catmark_smoothtris0",   "catmark_val2_foldover", "catmark_val2_back2back"};

}  // namespace

TEST_CASE("limit surface regular torus equals its bicubic B-spline patches", "[limit]") {
  const Cage cage = grid_torus(9, 7);
  const LimitSurface s = LimitSurface::create(cage);
  const double diag = s.bounding_box_diagonal();
  const int n = 9, m = 7;
  double worst = 0, worst_d = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int f = i * m + j;
      for (int a = 0; a <= 11; ++a)
        for (int b = 0; b <= 11; ++b) {
          const double u = a / 11.0, v = b / 11.0;
          double bu[4], du[4], bv[4], dv[4];
          bspline(u, bu, du);
          bspline(v, bv, dv);
          glm::dvec3 p(0.0), pu(0.0), pv(0.0);
          for (int x = 0; x < 4; ++x)
            for (int y = 0; y < 4; ++y) {
              const glm::dvec3 c(cage.positions[std::size_t(((i - 1 + x + n) % n) * m + (j - 1 + y + m) % m)]);
              p += bu[x] * bv[y] * c;
              pu += du[x] * bv[y] * c;
              pv += bu[x] * dv[y] * c;
            }
          const SurfacePoint q = s.evaluate(f, 0, float(u), float(v));
          worst = std::max(worst, glm::length(glm::dvec3(q.position) - p) / diag);
          worst_d = std::max(worst_d,
                             std::max(glm::length(glm::dvec3(q.du) - pu), glm::length(glm::dvec3(q.dv) - pv)) / diag);
        }
    }
  CHECK(worst < 1e-6);
  CHECK(worst_d < 1e-6);
}

TEST_CASE("limit surface corners equal PrimvarRefiner Limit", "[limit]") {
  namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;
  for (const std::string name :
       {"catmark_cube", "catmark_xord_interior", "catmark_nonquads", "catmark_pyramid", "catmark_gregory_test2"}) {
    INFO(name);
    const Cage cage = load_obj_cage(osd_shape(name));
    const LimitSurface s = LimitSurface::create(cage);
    auto refiner = subdiv::build_osd_refiner(cage);
    osd::Far::TopologyRefiner::UniformOptions uniform(1);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);
    struct P {
      glm::dvec3 p{0.0};
      void Clear() { p = glm::dvec3(0.0); }
      void AddWithWeight(const P& o, double w) { p += w * o.p; }
    };
    std::vector<P> pts(static_cast<std::size_t>(refiner->GetNumVerticesTotal())),
        limit(static_cast<std::size_t>(refiner->GetLevel(1).GetNumVertices()));
    for (int v = 0; v < cage.vertex_count(); ++v) pts[std::size_t(v)].p = glm::dvec3(cage.positions[std::size_t(v)]);
    osd::Far::PrimvarRefinerReal<double> pr(*refiner);
    P* coarse = pts.data();
    P* refined = pts.data() + cage.vertex_count();
    pr.Interpolate(1, coarse, refined);
    pr.Limit(refined, limit);
    double worst = 0;
    for (int f = 0; f < cage.face_count(); ++f) {
      const int n = cage.face_sizes[std::size_t(f)];
      for (int k = 0; k < n; ++k) {
        const int v = cage.face_vertex(f, k);
        const glm::dvec3 exact = limit[std::size_t(refiner->GetLevel(0).GetVertexChildVertex(v))].p;
        static constexpr float qu[4] = {0, 1, 1, 0}, qv[4] = {0, 0, 1, 1};
        const SurfacePoint q = n == 4 ? s.evaluate(f, 0, qu[k], qv[k]) : s.evaluate(f, k, 0.0f, 0.0f);
        worst = std::max(worst, glm::length(glm::dvec3(q.position) - exact) / s.bounding_box_diagonal());
      }
    }
    CHECK(worst < 1e-6);
    // And off the 1/8 grid: dyadic points of a level-5 uniform refinement (multiples of 1/32).
    const LimitAccuracy acc = measure_limit_accuracy(cage, s, 5);
    CHECK(acc.samples > 1000);
    CHECK(acc.max_relative() < 1e-6);
  }
}

TEST_CASE("limit surface low approximation levels are measurably inexact", "[limit]") {
  // The measurement must be able to fail: Bfr's default level 2 is far from the limit near
  // extraordinary vertices (subdiv.md §3.3: ~1e-4 of the diagonal).
  const Cage cage = load_obj_cage(osd_shape("catmark_xord_interior"));
  const LimitSurface coarse = LimitSurface::create(cage, 2), fine = LimitSurface::create(cage);
  CHECK(measure_limit_accuracy(cage, coarse, 5).max_relative() > 1e-5);
  CHECK(compare_limit_surfaces(coarse, fine, 37).max_relative() > 1e-5);
  CHECK(measure_limit_accuracy(cage, fine, 5).max_relative() < 1e-6);
}

TEST_CASE("limit surface shared edges and vertices are bitwise watertight", "[limit]") {
  std::vector<std::string> paths;
  for (const auto& n : kClosedShapes) paths.push_back(osd_shape(n));
  paths.push_back(sdk_cage("monsterfrog_mapped_00"));
  long unowned_mismatches = 0;
  for (const auto& path : paths) {
    INFO(path);
    const Cage cage = load_obj_cage(path);
    const LimitSurface s = LimitSurface::create(cage);
    const WatertightResult owned = check_watertight(s, cage, true);
    CHECK(owned.points > 0);
    CHECK(owned.mismatches == 0);
    const WatertightResult plain = check_watertight(s, cage, false);
    // Without ownership the two sides agree only to round-off (this also checks that the sub-patch
    // and barycentric parameterizations line up with the neighbours).
    CHECK(plain.max_distance < 1e-5);
    unowned_mismatches += plain.mismatches;
  }
  // ...and they do differ in the last bits, so the ownership check above can fail.
  CHECK(unowned_mismatches > 100);
}

TEST_CASE("limit surface normals are unit length and outward", "[limit]") {
  Cage cube = load_obj_cage(osd_shape("catmark_cube"));
  Cage flipped = cube;  // the same cube wound clockwise and tagged so
  for (int f = 0; f < flipped.face_count(); ++f)
    std::reverse(
        flipped.face_vertices.begin() + flipped.face_offsets[std::size_t(f)],
        flipped.face_vertices.begin() + flipped.face_offsets[std::size_t(f)] + flipped.face_sizes[std::size_t(f)]);
  flipped.tags.left_handed = true;
  for (const Cage* c : {&cube, &flipped}) {
    const LimitSurface s = LimitSurface::create(*c);
    const glm::dvec3 centre = (s.bounds_min() + s.bounds_max()) * 0.5;
    int bad = 0;
    for (int f = 0; f < s.face_count(); ++f)
      for (int i = 0; i <= 13; ++i)
        for (int j = 0; j <= 13; ++j) {
          const SurfacePoint p = s.evaluate(f, 0, tess_param(i, 13), tess_param(j, 13));
          if (std::abs(glm::length(p.normal) - 1.0f) > 1e-6f) ++bad;
          if (glm::dot(glm::dvec3(p.normal), glm::dvec3(p.position) - centre) <= 0) ++bad;
        }
    CHECK(bad == 0);
  }
  // Every normal on the frog is finite and unit, including at extraordinary vertices.
  const Cage frog = load_obj_cage(sdk_cage("monsterfrog_mapped_00"));
  const LimitSurface s = LimitSurface::create(frog);
  int bad = 0;
  for (int f = 0; f < s.face_count(); ++f)
    for (int k = 0; k < s.sub_patch_count(f); ++k)
      for (int i = 0; i <= 4; ++i)
        for (int j = 0; j <= 4; ++j)
          if (!(std::abs(glm::length(s.evaluate(f, k, tess_param(i, 4), tess_param(j, 4)).normal) - 1.0f) < 1e-6f))
            ++bad;
  CHECK(bad == 0);
}

TEST_CASE("limit surface derivatives match finite differences in every domain", "[limit]") {
  const Cage cage = load_obj_cage(osd_shape("catmark_pyramid"));  // triangles and a quad
  const Cage nonquads = load_obj_cage(osd_shape("catmark_nonquads"));
  const double h = 1e-4;
  for (const Cage* c : {&cage, &nonquads}) {
    const LimitSurface s = LimitSurface::create(*c);
    const double diag = s.bounding_box_diagonal();
    for (int f = 0; f < s.face_count(); ++f) {
      for (int k = 0; k < s.sub_patch_count(f); ++k)
        for (auto [u, v] : {std::pair{0.3, 0.6}, {0.71, 0.2}}) {
          const SurfacePoint p = s.evaluate(f, k, float(u), float(v));
          const glm::dvec3 fu =
              (s.sample_reference(f, k, u + h, v).position - s.sample_reference(f, k, u - h, v).position) / (2 * h);
          const glm::dvec3 fv =
              (s.sample_reference(f, k, u, v + h).position - s.sample_reference(f, k, u, v - h).position) / (2 * h);
          CHECK(glm::length(glm::dvec3(p.du) - fu) / diag < 1e-4);
          CHECK(glm::length(glm::dvec3(p.dv) - fv) / diag < 1e-4);
        }
      if (s.face_size(f) != 3) continue;
      // Points off the lines between sub-patches: there the derivatives of the barycentric map jump
      // (it is only C0); the surface and its normal do not (checked below).
      for (auto [u, v] : {std::pair{0.2, 0.3}, {0.5, 0.25}, {0.1, 0.8}, {0.3, 0.38}}) {
        const auto at = [&](double a, double b) {
          return glm::dvec3(s.evaluate_triangle(f, float(a), float(b), float(1 - a - b)).position);
        };
        const SurfacePoint p = s.evaluate_triangle(f, float(u), float(v), float(1 - u - v));
        const double hh = 1.0 / 1024;  // exact in float
        const glm::dvec3 fu = (at(u + hh, v) - at(u - hh, v)) / (2 * hh),
                         fv = (at(u, v + hh) - at(u, v - hh)) / (2 * hh);
        CHECK(glm::length(glm::dvec3(p.du) - fu) / diag < 1e-3);
        CHECK(glm::length(glm::dvec3(p.dv) - fv) / diag < 1e-3);
        CHECK(glm::dot(glm::cross(p.du, p.dv), p.normal) > 0);
      }
      {
        const float a = 0.3f, b = 0.35f, e = 1.0f / 4096;  // b0 = b2: the line between sub-patches 0 and 2
        const glm::vec3 n0 = s.evaluate_triangle(f, a, b - e, 1.0f - a - (b - e)).normal;
        const glm::vec3 n1 = s.evaluate_triangle(f, a, b + e, 1.0f - a - (b + e)).normal;
        CHECK(glm::length(n0 - n1) < 1e-2);
      }
      // Corners and the centroid of the barycentric domain land where the sub-patches put them.
      const auto same = [&](const SurfacePoint& a, const SurfacePoint& b) {
        return glm::length(a.position - b.position) / diag < 1e-6;
      };
      CHECK(same(s.evaluate_triangle(f, 0, 0, 1), s.evaluate(f, 0, 0, 0)));
      CHECK(same(s.evaluate_triangle(f, 1, 0, 0), s.evaluate(f, 1, 0, 0)));
      CHECK(same(s.evaluate_triangle(f, 0, 1, 0), s.evaluate(f, 2, 0, 0)));
      const float third = 1.0f / 3.0f;
      CHECK(same(s.evaluate_triangle(f, third, third, 1.0f - 2 * third), s.evaluate(f, 0, 1, 1)));
      CHECK(same(s.evaluate_triangle(f, 0.5f, 0, 0.5f), s.evaluate(f, 0, 1, 0)));
    }
  }
}

TEST_CASE("limit surface fan triangles are the sub-patches mapped piecewise affinely", "[limit]") {
  using L = LimitSurface;
  // The map itself: corners, the edge midpoint, the centre, and both spokes land exactly where the
  // contract puts them (the spoke points as the same (s, t) from both triangles).
  const auto is = [](const L::SubPatchLocation& l, int sub, double s, double t) {
    return l.sub == sub && l.s == s && l.t == t;
  };
  CHECK(is(L::fan_location(5, 2, 0.0, 0.0), 2, 0.0, 0.0));
  CHECK(is(L::fan_location(5, 2, 1.0, 0.0), 3, 0.0, 0.0));
  CHECK(is(L::fan_location(5, 4, 1.0, 0.0), 0, 0.0, 0.0));
  CHECK(is(L::fan_location(5, 2, 0.5, 0.0), 2, 1.0, 0.0));
  CHECK(is(L::fan_location(5, 2, 0.0, 1.0), 2, 1.0, 1.0));
  CHECK(is(L::fan_location(5, 2, 0.25, 0.0), 2, 0.5, 0.0));
  CHECK(is(L::fan_location(5, 2, 0.75, 0.0), 3, 0.0, 0.5));
  for (int i = 1; i < 37; ++i) {
    const double t = tess_param(i, 37), r = double(1.0f - float(t));
    CHECK(is(L::fan_location(6, 3, 0.0, t), 3, t, t));
    CHECK(is(L::fan_location(6, 2, r, t), 3, t, t));
  }
  for (const std::string name : {"catmark_nonquads", "catmark_gregory_test8", "catmark_pyramid"}) {
    INFO(name);
    const Cage cage = load_obj_cage(osd_shape(name));
    const LimitSurface s = LimitSurface::create(cage);
    const double diag = s.bounding_box_diagonal();
    int fans = 0;
    for (int f = 0; f < s.face_count(); ++f) {
      const int n = s.face_size(f);
      if (n == 4 || !s.has_surface(f)) continue;
      for (int k = 0; k < n; ++k, ++fans) {
        const auto ref = [&](double u, double v) {
          const L::SubPatchLocation l = L::fan_location(n, k, u, v);
          return s.sample_reference(f, l.sub, l.s, l.t);
        };
        // Points on both halves: the position is the sub-patch's, the derivatives those of the map.
        for (auto [u, v] : {std::pair{0.2, 0.3}, {0.1, 0.5}, {0.55, 0.2}, {0.3, 0.65}, {0.7, 0.1}}) {
          const SurfacePoint p = s.evaluate_fan(f, k, float(u), float(v), float(1 - u - v));
          CHECK(glm::length(glm::dvec3(p.position) - ref(u, v).position) / diag < 1e-6);
          const double h = 1.0 / 4096;  // both samples on the point's own half
          const glm::dvec3 fu = (ref(u + h, v).position - ref(u - h, v).position) / (2 * h);
          const glm::dvec3 fv = (ref(u, v + h).position - ref(u, v - h).position) / (2 * h);
          CHECK(glm::length(glm::dvec3(p.du) - fu) / diag < 1e-3);
          CHECK(glm::length(glm::dvec3(p.dv) - fv) / diag < 1e-3);
          CHECK(glm::dot(glm::cross(p.du, p.dv), p.normal) > 0);
          CHECK(std::abs(glm::length(p.normal) - 1.0f) < 1e-6f);
        }
        // Across the line x = 2u + v = 1, where the triangle passes from sub-patch k to k+1, the
        // position and the normal are continuous.
        const float v = 0.375f, e = 1.0f / 8192;
        const SurfacePoint a = s.evaluate_fan(f, k, (1.0f - v) / 2 - e, v, 1.0f - ((1.0f - v) / 2 - e) - v);
        const SurfacePoint b = s.evaluate_fan(f, k, (1.0f - v) / 2 + e, v, 1.0f - ((1.0f - v) / 2 + e) - v);
        CHECK(glm::length(a.position - b.position) / diag < 1e-3);
        CHECK(glm::length(a.normal - b.normal) < 1e-2);
      }
    }
    CHECK(fans > 0);
  }
  // A quad has no fan; triangles past n - 1 do not exist.
  const Cage nonquads = load_obj_cage(osd_shape("catmark_nonquads"));
  const LimitSurface s = LimitSurface::create(nonquads);
  int quad = 0, hexagon = 0;
  while (s.face_size(quad) != 4) ++quad;
  while (s.face_size(hexagon) != 6) ++hexagon;
  CHECK_THROWS_AS(s.evaluate_fan(quad, 0, 0.2f, 0.2f, 0.6f), std::out_of_range);
  CHECK_THROWS_AS(s.evaluate_fan(hexagon, 6, 0.2f, 0.2f, 0.6f), std::out_of_range);
  CHECK_NOTHROW(s.evaluate_fan(hexagon, 5, 0.2f, 0.2f, 0.6f));
}

TEST_CASE("limit surface holes and out-of-range queries are reported", "[limit]") {
  const Cage cage = load_obj_cage(osd_shape("catmark_hole_test1"));
  const LimitSurface s = LimitSurface::create(cage);
  REQUIRE(!cage.tags.holes.empty());
  for (int h : cage.tags.holes) {
    CHECK_FALSE(s.has_surface(h));
    CHECK(s.sub_patch_count(h) == 0);
    CHECK_THROWS_AS(s.evaluate(h, 0, 0.5f, 0.5f), std::out_of_range);
  }
  int good = 0;
  while (!s.has_surface(good)) ++good;
  CHECK_NOTHROW(s.evaluate(good, 0, 0.5f, 0.5f));
  CHECK_THROWS_AS(s.evaluate(-1, 0, 0.5f, 0.5f), std::out_of_range);
  CHECK_THROWS_AS(s.evaluate(s.face_count(), 0, 0.5f, 0.5f), std::out_of_range);
  CHECK_THROWS_AS(s.evaluate(good, 1, 0.5f, 0.5f), std::out_of_range);
  CHECK_THROWS_AS(s.evaluate(good, 0, 1.5f, 0.5f), std::out_of_range);
  CHECK_THROWS_AS(s.evaluate(good, 0, 0.5f, std::nanf("")), std::out_of_range);
  CHECK_THROWS_AS(s.evaluate_triangle(good, 0.2f, 0.2f, 0.6f), std::out_of_range);  // a quad
  CHECK_THROWS_AS(LimitSurface::create(cage, 0), std::invalid_argument);
  CHECK_THROWS_AS(LimitSurface::create(cage, 11), std::invalid_argument);
}

TEST_CASE("limit surface broken cages give a one-line CageError", "[limit]") {
  const Cage cube = load_obj_cage(osd_shape("catmark_cube"));
  // The cage's own validation (validate_cage, topology.h) speaks first.
  Cage bad = cube;
  bad.face_vertices[5] = 99;
  CHECK(create_error(bad).find("face 1 has vertex 99 (0-based), but the cage has 8 vertices") != std::string::npos);
  bad = cube;
  bad.face_sizes[2] = 2;
  CHECK(create_error(bad).find("face 2 has 2 vertices; a face needs at least 3") != std::string::npos);
  bad = cube;
  bad.tags.holes.push_back(6);
  CHECK(create_error(bad).find("hole names face 6, but the cage has 6 faces") != std::string::npos);
  bad = cube;
  bad.tags.corners.push_back({3, -1.0f});
  CHECK(create_error(bad).find("corner at vertex 3 has sharpness") != std::string::npos);
  bad = cube;
  bad.positions[3].x = std::nanf("");
  const std::string nan_message = create_error(bad);
  CHECK(nan_message.find(": face ") != std::string::npos);
  CHECK(nan_message.find("has no finite limit surface") != std::string::npos);
  CHECK(nan_message.find('\n') == std::string::npos);
  // Non-manifold cages are split by the reader (non_manifold.h) and then evaluate like any other; a
  // bare vertex is a warning, and the surface evaluates.
  for (const std::string name : {"catmark_nonman_edges", "catmark_nonman_verts", "catmark_val2_nonman", "catmark_fan",
                                 "catmark_gregory_test4"}) {
    INFO(name);
    const Cage c = load_obj_cage(osd_shape(name));
    CHECK_FALSE(c.non_manifold.empty());
    CHECK_NOTHROW(validate_cage(c));
    CHECK(create_error(c).empty());
  }
  {
    const LimitSurface s = LimitSurface::create(load_obj_cage(osd_shape("catmark_nonman_bareverts")));
    for (int f = 0; f < s.face_count(); ++f)
      for (int k = 0; k < s.sub_patch_count(f); ++k) CHECK(std::isfinite(s.evaluate(f, k, 0.3f, 0.6f).position.x));
  }
  // A crease on two vertices that share no edge is ignored, as the topology documents (a warning there).
  bad = cube;
  bad.tags.creases.push_back({0, 7, 2.0f});  // a diagonal, not an edge
  {
    const LimitSurface plain = LimitSurface::create(cube), diagonal = LimitSurface::create(bad);
    for (int f = 0; f < cube.face_count(); ++f)
      CHECK(same_bits(plain.evaluate(f, 0, 0.3f, 0.6f).position, diagonal.evaluate(f, 0, 0.3f, 0.6f).position));
  }
}

TEST_CASE("limit surface rejects faces and valences beyond OpenSubdiv's limits and its own", "[limit]") {
  const int limit = 65535;        // Bfr::Limits::MaxFaceSize() and MaxValence()
  std::vector<glm::vec3> circle;  // limit + 1 points on the unit circle
  for (int i = 0; i <= limit; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / (limit + 1);
    circle.push_back(glm::vec3(float(std::cos(a)), float(std::sin(a)), 0.0f));
  }
  Cage big;  // one face of 65536 corners, valid for the topology
  big.name = "big";
  big.face_sizes = {limit + 1};
  big.face_offsets = {0};
  big.positions = circle;
  for (int i = 0; i <= limit; ++i) big.face_vertices.push_back(i);
  CHECK(create_error(big) == "big: face 0 has 65536 vertices; OpenSubdiv takes at most 65535");
  Cage pole;  // a disc of 65536 triangles around vertex 0: valence 65536 there
  pole.name = "pole";
  pole.positions.push_back(glm::vec3(0.0f));
  pole.positions.insert(pole.positions.end(), circle.begin(), circle.end());
  for (int i = 0; i <= limit; ++i) {
    pole.face_sizes.push_back(3);
    pole.face_offsets.push_back(3 * i);
    for (int v : {0, 1 + i, 1 + (i + 1) % (limit + 1)}) pole.face_vertices.push_back(v);
  }
  CHECK(create_error(pole) == "pole: vertex 0 has valence 65536; OpenSubdiv takes at most 65535");
}

TEST_CASE("limit surface evaluation is thread-safe and deterministic", "[limit]") {
  const Cage frog = load_obj_cage(sdk_cage("monsterfrog_mapped_00"));
  const LimitSurface s = LimitSurface::create(frog);
  const auto digest = [&](int stride, int offset) {
    std::uint64_t h = 1469598103934665603ull;
    for (int f = offset; f < s.face_count(); f += stride)
      for (int k = 0; k < s.sub_patch_count(f); ++k)
        for (int i = 0; i <= 6; ++i)
          for (int j = 0; j <= 6; ++j) {
            const SurfacePoint p = s.evaluate(f, k, tess_param(i, 6), tess_param(j, 6));
            for (float x : {p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y, p.normal.z})
              h = (h ^ std::bit_cast<std::uint32_t>(x)) * 1099511628211ull;
          }
    return h;
  };
  std::array<std::uint64_t, 4> single{}, threaded{};
  for (int t = 0; t < 4; ++t) single[std::size_t(t)] = digest(4, t);
  std::vector<std::thread> pool;
  for (int t = 0; t < 4; ++t) pool.emplace_back([&, t] { threaded[std::size_t(t)] = digest(4, t); });
  for (auto& th : pool) th.join();
  CHECK(single == threaded);
}

// Measurements for the report: accuracy per level, creation time and memory, evaluation cost.
TEST_CASE("limit surface measurements", "[.][limit-bench]") {
  for (const std::string name : {"catmark_cube", "catmark_xord_interior"}) {
    const Cage cage = load_obj_cage(osd_shape(name));
    const LimitSurface ref = LimitSurface::create(cage, 10);
    for (int level : {2, 4, 6, 8, 10}) {
      const LimitSurface s = LimitSurface::create(cage, level);
      const LimitAccuracy a = measure_limit_accuracy(cage, s, 6);
      const LimitAccuracy b = compare_limit_surfaces(s, ref, 37);
      const LimitAccuracy c = measure_limit_accuracy(cage, s, 8);
      std::printf(
          "%-22s level %2d: vs PrimvarRefiner::Limit 1/64 grid max %.3g rms %.3g, 1/256 grid max %.3g | vs level 10 "
          "(k/37 + corner zoom) max %.3g (relative to diagonal)\n",
          name.c_str(), level, a.max_relative(), a.rms_distance / a.diagonal, c.max_relative(), b.max_relative());
    }
  }
  const Cage frog = load_obj_cage(sdk_cage("monsterfrog_mapped_00"));
  const auto rss_kb = [] { return long(mallinfo2().uordblks / 1024); };  // heap bytes in use
  for (int level : {10, 2, 6, 8}) {
    const long before = rss_kb();
    const auto t0 = std::chrono::steady_clock::now();
    const LimitSurface s = LimitSurface::create(frog, level);
    const auto t1 = std::chrono::steady_clock::now();
    const long after = rss_kb();
    std::size_t subs = 0;
    for (int f = 0; f < s.face_count(); ++f) subs += std::size_t(s.sub_patch_count(f));
    const int R = 64;
    double sink = 0;
    const auto t2 = std::chrono::steady_clock::now();
    for (int f = 0; f < s.face_count(); ++f)
      for (int k = 0; k < s.sub_patch_count(f); ++k)
        for (int i = 1; i < R; ++i)
          for (int j = 1; j < R; ++j) sink += s.evaluate(f, k, float(i) / R, float(j) / R).position.x;
    const auto t3 = std::chrono::steady_clock::now();
    const double n_eval = double(subs) * (R - 1) * (R - 1);
    double edge_ns = 0;
    {
      const auto t4 = std::chrono::steady_clock::now();
      long cnt = 0;
      for (int f = 0; f < s.face_count(); ++f)
        for (int k = 0; k < s.sub_patch_count(f); ++k)
          for (int i = 1; i < R; ++i) {
            sink += s.evaluate(f, k, float(i) / R, 0.0f).position.x;
            ++cnt;
          }
      edge_ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t4).count() / double(cnt);
    }
    std::printf(
        "frog (%d faces, %zu sub-patches) level %2d: create %.1f ms, heap +%.1f MB, per-face data %.2f MB; evaluate "
        "%.0f ns/interior point, %.0f ns/edge point (%g)\n",
        s.face_count(), subs, level, std::chrono::duration<double, std::milli>(t1 - t0).count(),
        double(after - before) / 1024.0, double(s.memory_bytes()) / 1048576.0,
        std::chrono::duration<double, std::nano>(t3 - t2).count() / n_eval, edge_ns, sink);
  }
}

TEST_CASE("limit surface: Far patches agree with Bfr where both work", "[limit]") {
  // far_patches.h evaluates the faces Bfr 3.5.0 fails on; on cages where Bfr works, the same faces
  // through Far give the same surface to within the end caps' difference at the isolation level.
  for (const char* name :
       {"catmark_cube_creases1", "catmark_xord_interior", "catmark_nonquads", "catmark_edgecorner"}) {
    INFO(name);
    const Cage cage = load_obj_cage(osd_shape(name));
    const LimitSurface bfr = LimitSurface::create(cage);
    std::vector<int> faces;
    for (int f = 0; f < cage.face_count(); ++f)
      if (bfr.has_surface(f)) faces.push_back(f);
    const subdiv::FarPatches far(cage, bfr.approx_level(), faces);
    double worst = 0.0;
    for (int f : faces)
      for (int k = 0; k < bfr.sub_patch_count(f); ++k)
        for (int i = 0; i <= 4; ++i)
          for (int j = 0; j <= 4; ++j) {
            const float s = float(i) / 4.0f, t = float(j) / 4.0f;
            const glm::dvec3 a(bfr.evaluate_unowned(f, k, s, t).position);
            worst = std::max(worst, glm::length(far.evaluate(f, k, s, t).p - a));
          }
    CHECK(worst / bfr.bounding_box_diagonal() < 1e-5);
  }
}

TEST_CASE("limit surface: OpenSubdiv 3.5.0's valence-2 crease crash is avoided", "[limit]") {
  // catmark_val2_interior: faces with a valence-2 interior corner, a boundary corner and creases,
  // which Bfr 3.5.0 builds from uninitialized memory (a crash in most runs). Far evaluates them.
  const Cage cage = load_obj_cage(osd_shape("catmark_val2_interior"));
  const std::vector<int> far_faces = subdiv::needs_far_patches(Topology(cage));
  CHECK_FALSE(far_faces.empty());
  for (int run = 0; run < 3; ++run) {
    const LimitSurface s = LimitSurface::create(cage);
    const WatertightResult owned = check_watertight(s, cage, true);
    CHECK(owned.points > 0);
    CHECK(owned.mismatches == 0);
    CHECK(check_watertight(s, cage, false).max_distance < 1e-5);
    for (int f : far_faces)
      for (int k = 0; k < s.sub_patch_count(f); ++k) {
        const SurfacePoint p = s.evaluate(f, k, 0.5f, 0.5f);
        CHECK(std::isfinite(p.position.x + p.position.y + p.position.z));
        CHECK(glm::length(p.normal) == Approx(1.0).epsilon(1e-5));
      }
  }
  // The creases are honoured: without them the same faces give another surface.
  Cage smooth = cage;
  smooth.tags.creases.clear();
  CHECK(subdiv::needs_far_patches(Topology(smooth)).empty());
  const LimitSurface a = LimitSurface::create(cage), b = LimitSurface::create(smooth);
  double apart = 0.0;
  for (int f : far_faces)
    apart = std::max(
        apart, double(glm::length(a.evaluate(f, 0, 0.5f, 0.5f).position - b.evaluate(f, 0, 0.5f, 0.5f).position)));
  CHECK(apart > 1e-3);
}

TEST_CASE("limit surface: a pose moves only the points, to the bits of a surface built from the posed cage",
          "[limit]") {
  // Bfr faces, Far faces (catmark_val2_interior's, where Bfr 3.5.0 fails) and the adaptive method: a
  // surface built from the rest cage and reposed must evaluate to the bits of one built from the moved
  // cage, at owned points (cage vertices and edges) and inside.
  for (const char* name : {"osd-shapes/catmark_cubes_semisharp.obj", "osd-shapes/catmark_val2_interior.obj"})
    for (const bool adaptive : {false, true}) {
      INFO(name << (adaptive ? " adaptive" : " exact"));
      const Cage rest = load_obj_cage(data(name));
      Cage moved = rest;
      for (glm::vec3& p : moved.positions) p = glm::vec3(p.x * 1.25f + 0.5f * p.y * p.y, p.y - 0.3f * p.z, p.z + 0.1f);
      LimitSurface reposed = adaptive ? LimitSurface::create_adaptive(rest, 3) : LimitSurface::create(rest, 6);
      const LimitSurface fresh = adaptive ? LimitSurface::create_adaptive(moved, 3) : LimitSurface::create(moved, 6);
      const SurfacePoint before = reposed.evaluate(0, 0, 0.25f, 0.5f);
      reposed.repose(moved.positions);
      CHECK(reposed.bounds_min() == fresh.bounds_min());
      CHECK(reposed.bounds_max() == fresh.bounds_max());
      int compared = 0;
      for (int f = 0; f < fresh.face_count(); ++f)
        for (int k = 0; k < fresh.sub_patch_count(f); ++k)
          for (const float u : {0.0f, 0.25f, 1.0f})
            for (const float v : {0.0f, 0.5f, 1.0f}) {
              const SurfacePoint a = reposed.evaluate(f, k, u, v), b = fresh.evaluate(f, k, u, v);
              CHECK(std::bit_cast<std::array<std::uint32_t, 3>>(a.position) ==
                    std::bit_cast<std::array<std::uint32_t, 3>>(b.position));
              CHECK(std::bit_cast<std::array<std::uint32_t, 3>>(a.normal) ==
                    std::bit_cast<std::array<std::uint32_t, 3>>(b.normal));
              ++compared;
            }
      CHECK(compared > 0);
      CHECK(before.position != reposed.evaluate(0, 0, 0.25f, 0.5f).position);
      CHECK_THROWS_AS(reposed.repose(std::span<const glm::vec3>(moved.positions).first(3)), std::logic_error);
    }
}

namespace tessera {

TEST_CASE("semi-sharp vertices: the locally refined limit position equals OpenSubdiv's", "[limit]") {
  // semi_sharp_limit_position refines a vertex's 1-ring until its tags relax and applies the smooth
  // mask; OpenSubdiv (Bfr) evaluates the same limit at the face corner. Corner tags of sharpness 0.7,
  // 1.4, 2.8, 3; two creases of 2 meeting; three creases of 5 (a corner rule that relaxes); the mixed
  // tags of cubes_semisharp; fractional creases on a pyramid and on a sheet.
  for (const char* name :
       {"catmark_cube_corner0", "catmark_cube_corner1", "catmark_cube_corner2", "catmark_cube_corner3",
        "catmark_cube_creases0", "catmark_cube_creases1", "catmark_cubes_semisharp", "catmark_pyramid_creases0",
        "catmark_chaikin0", "catmark_single_crease"}) {
    const Cage cage = load_obj_cage(test::data(std::string("osd-shapes/") + name + ".obj"));
    const Topology t(cage);
    const LimitSurface s = LimitSurface::create(cage);
    const double diag = s.bounding_box_diagonal();
    int checked = 0;
    for (int v = 0; v < t.vertex_count(); ++v) {
      const std::optional<Stencil> p = semi_sharp_limit_position(cage, t, v);
      if (!p) continue;
      glm::dvec3 mine(0.0);
      for (const auto& [i, w] : p->terms) mine += w * glm::dvec3(cage.positions[std::size_t(i)]);
      // The corner of a quad face at v: corner k sits at (0,0), (1,0), (1,1), (0,1).
      for (int f = 0; f < t.face_count(); ++f) {
        if (t.face_size(f) != 4) continue;
        for (int k = 0; k < 4; ++k) {
          if (cage.face_vertex(f, k) != v) continue;
          const float u = k == 1 || k == 2 ? 1.0f : 0.0f, w = k >= 2 ? 1.0f : 0.0f;
          const glm::dvec3 exact(s.evaluate(f, 0, u, w).position);
          INFO(name << " vertex " << v << " face " << f);
          CHECK(glm::length(mine - exact) / diag < 1e-5);
          ++checked;
        }
      }
    }
    INFO(name);
    CHECK(checked > 0);
  }
}

}  // namespace tessera
