// Non-manifold cages: the split (shaders_cpp/cage/non_manifold.h) is checked against OpenSubdiv itself,
// which refines the original non-manifold topology: every face's refined vertices, followed down the
// same child faces in both refinements, sit at the same limit positions.
#include <catch2/catch.hpp>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/non_manifold.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/osd_refiner.h"
#include "test_data.h"

using namespace tessera;

namespace {

std::string osd_shape(const std::string& name) { return test::data("osd-shapes/" + name + ".obj"); }

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;
using Refiner = osd::Far::TopologyRefiner;

// The faces, positions and tags of the file the split cage came from: the copies mapped back. The split's
// own sharpening tags come back as tags on the non-manifold edges and vertices, which OpenSubdiv sharpens
// to infinity anyway, so the original refines as OpenSubdiv refines the file.
struct Original {
  std::vector<int> sizes, verts, crease_pairs, corner_verts;
  std::vector<float> crease_weights, corner_weights;
  std::vector<glm::dvec3> positions;
};

Original original_of(const Cage& split) {
  Original o;
  int n = 0;
  for (int v = 0; v < split.vertex_count(); ++v) n = std::max(n, split.source_vertex(v) + 1);
  for (int v = 0; v < n; ++v) o.positions.push_back(glm::dvec3(split.positions[std::size_t(v)]));
  o.sizes = split.face_sizes;
  for (int v : split.face_vertices) o.verts.push_back(split.source_vertex(v));
  for (const Crease& c : split.tags.creases)
    if (split.source_vertex(c.v0) != split.source_vertex(c.v1)) {
      o.crease_pairs.push_back(split.source_vertex(c.v0)), o.crease_pairs.push_back(split.source_vertex(c.v1));
      o.crease_weights.push_back(c.sharpness);
    }
  for (const Corner& c : split.tags.corners) o.corner_verts.push_back(split.source_vertex(c.vertex)), o.corner_weights.push_back(c.sharpness);
  return o;
}

std::unique_ptr<Refiner> refine(const Original& o, const CageTags& tags, int levels) {
  osd::Far::TopologyDescriptor d;
  d.numVertices = int(o.positions.size());
  d.numFaces = int(o.sizes.size());
  d.numVertsPerFace = o.sizes.data();
  d.vertIndicesPerFace = o.verts.data();
  d.numCreases = int(o.crease_weights.size());
  d.creaseVertexIndexPairs = o.crease_pairs.data();
  d.creaseWeights = o.crease_weights.data();
  d.numCorners = int(o.corner_weights.size());
  d.cornerVertexIndices = o.corner_verts.data();
  d.cornerWeights = o.corner_weights.data();
  d.numHoles = int(tags.holes.size());
  d.holeIndices = tags.holes.data();
  using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
  std::unique_ptr<Refiner> r(Factory::Create(d, Factory::Options(osd::Sdc::SCHEME_CATMARK, subdiv::sdc_options(tags))));
  REQUIRE(r);
  osd::Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = true;
  r->RefineUniform(uniform);
  return r;
}

struct Point {
  glm::dvec3 p{0.0};
  void Clear() { p = glm::dvec3(0.0); }
  void AddWithWeight(const Point& o, double w) { p += w * o.p; }
};

// Limit positions of the last level's vertices.
std::vector<Point> limit_positions(const Refiner& r, const std::vector<glm::dvec3>& base) {
  std::vector<Point> all(std::size_t(r.GetNumVerticesTotal()));
  for (std::size_t v = 0; v < base.size(); ++v) all[v].p = base[v];
  osd::Far::PrimvarRefinerReal<double> pr(r);
  Point* src = all.data();
  for (int level = 1; level <= r.GetMaxLevel(); ++level) {
    Point* dst = src + r.GetLevel(level - 1).GetNumVertices();
    pr.Interpolate(level, src, dst);
    src = dst;
  }
  std::vector<Point> limit(std::size_t(r.GetLevel(r.GetMaxLevel()).GetNumVertices()));
  pr.Limit(src, limit);
  return limit;
}

// The corners of every last-level face under base face f, in the refinement's child order.
void leaf_corners(const Refiner& r, int level, int f, std::vector<int>& out) {
  const auto& l = r.GetLevel(level);
  if (level == r.GetMaxLevel()) {
    for (int v : l.GetFaceVertices(f)) out.push_back(v);
    return;
  }
  for (int c : l.GetFaceChildFaces(f)) leaf_corners(r, level + 1, c, out);
}

}  // namespace

TEST_CASE("non-manifold shapes: the split cage's limit is OpenSubdiv's on the original topology", "[cage][limit]") {
  for (const std::string name : {"catmark_fan", "catmark_val2_nonman", "catmark_gregory_test4", "catmark_nonman_verts",
                                 "catmark_nonman_edges", "catmark_nonman_quadpole8", "catmark_nonman_quadpole64",
                                 "catmark_nonman_edge100", "catmark_nonman_bareverts"}) {
    INFO(name);
    const Cage split = load_obj_cage(osd_shape(name));
    REQUIRE_NOTHROW(Topology(split));  // manifold now
    const Original original = original_of(split);
    constexpr int kLevels = 3;
    const auto a = refine(original, split.tags, kLevels);
    std::vector<glm::dvec3> split_positions;
    for (const glm::vec3& p : split.positions) split_positions.push_back(glm::dvec3(p));
    const auto b = subdiv::build_osd_refiner(split);
    osd::Far::TopologyRefiner::UniformOptions uniform(kLevels);
    uniform.fullTopologyInLastLevel = true;
    b->RefineUniform(uniform);
    const std::vector<Point> la = limit_positions(*a, original.positions), lb = limit_positions(*b, split_positions);
    double diagonal = 0, worst = 0;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : original.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    diagonal = glm::length(hi - lo);
    std::size_t compared = 0;
    for (int f = 0; f < int(original.sizes.size()); ++f) {
      std::vector<int> ca, cb;
      leaf_corners(*a, 0, f, ca), leaf_corners(*b, 0, f, cb);
      REQUIRE(ca.size() == cb.size());
      double fw = 0;
      for (std::size_t i = 0; i < ca.size(); ++i)
        fw = std::max(fw, glm::length(la[std::size_t(ca[i])].p - lb[std::size_t(cb[i])].p));
      worst = std::max(worst, fw);
      compared += ca.size();
    }
    CHECK(compared > 100);
    CHECK(worst <= 1e-9 * diagonal);
  }
}

TEST_CASE("non-manifold places are named and sharpened as OpenSubdiv does", "[cage]") {
  SECTION("an edge of three faces: infinitely sharp, its end vertices corners") {
    // Three quads hinged on the edge 0-1.
    const Cage c = parse_obj_cage("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 -1 0\nv 1 -1 0\nv 0 0 1\nv 1 0 1\n"
                                  "f 1 2 4 3\nf 2 1 5 6\nf 1 2 8 7\n", "hinge.obj");
    REQUIRE(c.non_manifold.size() == 3);
    CHECK(c.non_manifold[0].find("non-manifold edge between vertices 0 and 1 (0-based): 3 faces (0, 1, 2)") == 0);
    CHECK(c.vertex_count() == 8 + 2 * 2);  // vertices 0 and 1: three groups each, two copies each
    const Topology t(c);
    int sharp_edges = 0, sharp_corners = 0;
    for (int e = 0; e < t.edge_count(); ++e) sharp_edges += t.edge_sharpness(e) >= kSharpnessInfinite;
    for (int v = 0; v < t.vertex_count(); ++v) sharp_corners += t.corner_sharpness(v) >= kSharpnessInfinite;
    CHECK(sharp_edges == 3);
    CHECK(sharp_corners == 6);
    for (int v = 8; v < c.vertex_count(); ++v) CHECK(c.positions[std::size_t(v)] == c.positions[std::size_t(c.source_vertex(v))]);
    REQUIRE(c.warnings.size() == 1);
    CHECK(c.warnings[0].find("hinge.obj: 3 non-manifold places drawn by OpenSubdiv's rules") == 0);
  }
  SECTION("a manifold cage is untouched") {
    const Cage c = load_obj_cage(osd_shape("catmark_cube"));
    CHECK(c.vertex_source.empty());
    CHECK(c.non_manifold.empty());
    CHECK(c.warnings.empty());
  }
  SECTION("a face repeating a vertex (a quad pole) is named") {
    const Cage c = load_obj_cage(osd_shape("catmark_nonman_quadpole8"));
    REQUIRE(!c.non_manifold.empty());
    CHECK(std::count_if(c.non_manifold.begin(), c.non_manifold.end(),
                        [](const std::string& s) { return s.find("uses vertex 4 (0-based) more than once") != std::string::npos; }) == 8);
  }
}
