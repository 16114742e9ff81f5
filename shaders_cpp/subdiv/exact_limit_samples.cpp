// Exact limit positions of uniformly refined vertices, with the domain location of each.
//
// The domain location of every uniformly refined vertex is tracked level by level: a child vertex of
// a parent vertex, edge or face sits at the parent's corner, the edge's midpoint, or the face's
// centre in the parent face's domain (all exact dyadic numbers). Child vertices are identified by
// the ids Far reports (GetVertexChildVertex etc.), so no assumption about child-face ordering is made.
#include "shaders_cpp/subdiv/exact_limit_samples.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyLevel.h>

#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "shaders_cpp/subdiv/osd_refiner.h"

namespace tessera {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;

namespace {

struct Point {  // what PrimvarRefiner interpolates
  double p[3] = {0, 0, 0};
  void Clear() { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const Point& s, double w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

// A refined face: which base face and sub-patch it lies in, and its corners' domain locations.
struct Region {
  int base = -1, sub = 0;
  std::array<glm::dvec2, 4> corner{};
};

struct Location {
  int base = -1, sub = 0;
  glm::dvec2 uv{0.0};
};

}  // namespace

std::vector<ExactLimitSample> exact_limit_samples(const Cage& cage, const std::vector<bool>& faces, int refine_level) {
  if (refine_level < 1 || refine_level > 8)
    throw std::invalid_argument("exact_limit_samples: refine level " + std::to_string(refine_level) +
                                " is outside 1..8");
  auto refiner = subdiv::build_osd_refiner(cage);
  osd::Far::TopologyRefiner::UniformOptions uniform(refine_level);
  uniform.fullTopologyInLastLevel = true;  // PrimvarRefiner::Limit needs the last level's full topology
  refiner->RefineUniform(uniform);

  // Level 1: each child face of base face f is the sub-patch at the corner whose child vertex it holds.
  std::vector<Region> regions;
  {
    const osd::Far::TopologyLevel& l0 = refiner->GetLevel(0);
    const osd::Far::TopologyLevel& l1 = refiner->GetLevel(1);
    regions.resize(std::size_t(l1.GetNumFaces()));
    for (int f = 0; f < l0.GetNumFaces(); ++f) {
      if (f >= int(faces.size()) || !faces[std::size_t(f)]) continue;
      const auto fv = l0.GetFaceVertices(f);
      const auto fe = l0.GetFaceEdges(f);
      const int n = fv.size();
      // Domain location of child vertices in sub-patch `sub` (quads: the whole face, sub 0).
      const auto locate = [&](int child_vertex, int sub) -> glm::dvec2 {
        if (n == 4) {
          static constexpr double qu[4] = {0, 1, 1, 0}, qv[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            if (l0.GetVertexChildVertex(fv[k]) == child_vertex) return {qu[k], qv[k]};
            const int k1 = (k + 1) % 4;
            for (int e = 0; e < 4; ++e) {
              const auto ev = l0.GetEdgeVertices(fe[e]);
              if (l0.GetEdgeChildVertex(fe[e]) == child_vertex &&
                  ((ev[0] == fv[k] && ev[1] == fv[k1]) || (ev[1] == fv[k] && ev[0] == fv[k1])))
                return {0.5 * (qu[k] + qu[k1]), 0.5 * (qv[k] + qv[k1])};
            }
          }
          return {0.5, 0.5};
        }
        if (l0.GetVertexChildVertex(fv[sub]) == child_vertex) return {0, 0};
        if (l0.GetFaceChildVertex(f) == child_vertex) return {1, 1};
        for (int e = 0; e < n; ++e) {
          if (l0.GetEdgeChildVertex(fe[e]) != child_vertex) continue;
          const auto ev = l0.GetEdgeVertices(fe[e]);
          const bool touches = ev[0] == fv[sub] || ev[1] == fv[sub];
          const int other = ev[0] == fv[sub] ? ev[1] : ev[0];
          if (touches && other == fv[(sub + 1) % n]) return {1, 0};
          if (touches) return {0, 1};
        }
        return {1, 1};
      };
      for (int c : l0.GetFaceChildFaces(f)) {
        const auto cv = l1.GetFaceVertices(c);
        int sub = 0;
        if (n != 4)
          for (int k = 0; k < n; ++k)
            for (int j = 0; j < cv.size(); ++j)
              if (cv[j] == l0.GetVertexChildVertex(fv[k])) sub = k;
        Region& r = regions[std::size_t(c)];
        r.base = f;
        r.sub = sub;
        for (int j = 0; j < 4 && j < cv.size(); ++j) r.corner[std::size_t(j)] = locate(cv[j], sub);
      }
    }
  }
  // Levels 2..R: every face is a quad; children at corners, edge midpoints and the centre.
  for (int level = 1; level < refine_level; ++level) {
    const osd::Far::TopologyLevel& lp = refiner->GetLevel(level);
    const osd::Far::TopologyLevel& lc = refiner->GetLevel(level + 1);
    std::vector<Region> next(std::size_t(lc.GetNumFaces()));
    for (int f = 0; f < lp.GetNumFaces(); ++f) {
      const Region& pr = regions[std::size_t(f)];
      if (pr.base < 0) continue;
      const auto fv = lp.GetFaceVertices(f);
      const auto fe = lp.GetFaceEdges(f);
      std::array<std::pair<int, glm::dvec2>, 9> known;
      int count = 0;
      glm::dvec2 centre(0.0);
      for (int k = 0; k < 4; ++k) {
        known[std::size_t(count++)] = {lp.GetVertexChildVertex(fv[k]), pr.corner[std::size_t(k)]};
        centre += pr.corner[std::size_t(k)] * 0.25;
      }
      for (int e = 0; e < 4; ++e) {
        const auto ev = lp.GetEdgeVertices(fe[e]);
        glm::dvec2 mid(0.0);
        for (int k = 0; k < 4; ++k)
          if (fv[k] == ev[0] || fv[k] == ev[1]) mid += pr.corner[std::size_t(k)] * 0.5;
        known[std::size_t(count++)] = {lp.GetEdgeChildVertex(fe[e]), mid};
      }
      known[std::size_t(count++)] = {lp.GetFaceChildVertex(f), centre};
      for (int c : lp.GetFaceChildFaces(f)) {
        Region& r = next[std::size_t(c)];
        r.base = pr.base;
        r.sub = pr.sub;
        const auto cv = lc.GetFaceVertices(c);
        for (int j = 0; j < 4; ++j)
          for (const auto& [id, uv] : known)
            if (id == cv[j]) r.corner[std::size_t(j)] = uv;
      }
    }
    regions = std::move(next);
  }

  // Exact limit positions of the level-R vertices.
  const int total = refiner->GetNumVerticesTotal();
  std::vector<Point> pts(static_cast<std::size_t>(total));
  for (int v = 0; v < cage.vertex_count(); ++v)
    for (int c = 0; c < 3; ++c) pts[std::size_t(v)].p[c] = double(cage.positions[std::size_t(v)][c]);
  osd::Far::PrimvarRefinerReal<double> primvar(*refiner);
  Point* src = pts.data();
  for (int level = 1; level <= refine_level; ++level) {
    Point* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, src, dst);
    src = dst;
  }
  const osd::Far::TopologyLevel& last = refiner->GetLevel(refine_level);
  std::vector<Point> limit(static_cast<std::size_t>(last.GetNumVertices()));
  primvar.Limit(src, limit);

  std::vector<Location> where(limit.size(), Location{});
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const Region& r = regions[std::size_t(f)];
    if (r.base < 0) continue;
    const auto fv = last.GetFaceVertices(f);
    for (int j = 0; j < 4; ++j)
      if (where[std::size_t(fv[j])].base < 0) where[std::size_t(fv[j])] = {r.base, r.sub, r.corner[std::size_t(j)]};
  }
  std::vector<ExactLimitSample> samples;
  for (std::size_t v = 0; v < where.size(); ++v) {
    const Location& w = where[v];
    if (w.base < 0) continue;
    samples.push_back({w.base, w.sub, w.uv, glm::dvec3(limit[v].p[0], limit[v].p[1], limit[v].p[2])});
  }
  return samples;
}

}  // namespace tessera
