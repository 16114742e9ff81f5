#include "shaders_cpp/render/strayed_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "shaders_cpp/subdiv/limit_fit.h"

namespace tessera {
namespace {

// Interior samples per quad side (a triangle takes the points of the same lattice inside it): far
// enough from the corners that an extraordinary vertex's own undefined normal is not sampled, close
// enough to the edges to see an edge curve that strays.
constexpr int kGrid = 8;

// A limit normal shorter than this fraction of |du| |dv| is undefined (a collapsed direction).
constexpr double kDefinedNormal = 1e-6;

bool regular_quad(const Cage& cage, const Topology& t, int f) {
  if (t.face_size(f) != 4) return false;
  for (int k = 0; k < 4; ++k) {
    const int v = cage.face_vertex(f, k);
    if (t.is_boundary_vertex(v) || t.valence(v) != 4 || t.vertex_face_count(v) != 4 || t.has_sharpness_at(v))
      return false;
    for (const int h : t.ring(v))
      if (t.face_size(t.face(h)) != 4 || t.is_hole(t.face(h))) return false;
  }
  return true;
}

glm::dvec3 sum(const Stencil& s, const std::vector<glm::vec3>& positions) {
  glm::dvec3 p(0.0);
  for (const auto& [v, w] : s.terms) p += w * glm::dvec3(positions[std::size_t(v)]);
  return p;
}

std::vector<DomainLocation> sample_locations(bool triangles) {
  // The corners, whose normal the patch takes from its corner derivatives (a vertex of valence 2 turns
  // them nearly parallel), then the interior lattice.
  std::vector<DomainLocation> at;
  if (triangles)
    at = {{0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  else
    at = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const float u = (float(i) + 0.5f) / float(kGrid), v = (float(j) + 0.5f) / float(kGrid);
      if (!triangles) {
        at.push_back({u, v, 0.0f});
      } else if (u + v < 1.0f) {
        at.push_back({u, v, (1.0f - u) - v});
      }
    }
  return at;
}

}  // namespace

int StrayedFaces::count() const { return int(std::count(faces.begin(), faces.end(), char(1))); }

StrayedFaces find_strayed_faces(const SubdModel& m) {
  StrayedFaces out;
  const Scheme scheme = m.patches.scheme;
  if (scheme != Scheme::gregory && scheme != Scheme::bspline && scheme != Scheme::acc) return out;
  const Cage& cage = m.cage;
  const Topology& t = *m.topology;
  auto candidate = [&](const SubdPatch& p) {
    const int n = t.face_size(p.face);
    return (n == 3 || n == 4) && p.sub == 0 && p.kind != PatchKind::polar_triangle && !regular_quad(cage, t, p.face);
  };
  bool any = false;
  for (const PatchGroup* g : {&m.patches.quads, &m.patches.tris})
    for (const SubdPatch& p : g->patches) any = any || candidate(p);
  if (!any) return out;

  const LimitStencils limit(cage);
  out.faces.assign(std::size_t(cage.face_count()), 0);
  const SubdFactors factors;
  const SubdVS vs = m.vertex_shader();
  const auto buffer = m.vertex_buffer();
  const double flip = cage.tags.left_handed ? -1.0 : 1.0;
  for (const PatchGroup* g : {&m.patches.quads, &m.patches.tris}) {
    const bool tri = g->domain == ts::Domain::tri;
    const SubdHS hs{g->patches, m.patches.tables, factors, tri, m.ring_boxes, ts::Partitioning::integer, m.precomputed};
    const SubdDS ds{g->patches, m.limit.get(), cage.tags.left_handed, tri};
    const std::vector<DomainLocation> at = sample_locations(tri);
    std::vector<SubdVertex> ring(std::size_t(g->control_points));
    std::vector<SubdControlPoint> cp(std::size_t(SubdHS::kOutputControlPoints));
    std::vector<SurfaceSample> samples(at.size());
    std::vector<std::array<double, 2>> uv(at.size());
    for (std::size_t id = 0; id < g->patches.size(); ++id) {
      const SubdPatch& patch = g->patches[id];
      if (!candidate(patch)) continue;
      for (int i = 0; i < g->control_points; ++i) {
        const std::uint32_t v = g->indices[id * std::size_t(g->control_points) + std::size_t(i)];
        ring[std::size_t(i)] = vs(buffer[v], v);
      }
      for (int i = 0; i < SubdHS::kOutputControlPoints; ++i)
        cp[std::size_t(i)] = hs.control_point(ring, i, std::uint32_t(id));
      ds.samples(SubdPatchConstants{}, cp, at, std::uint32_t(id), samples);
      // The corners' limit a step inside the face (kInwardStep, as a fitted corner takes it at a vertex of
      // valence 2, where the limit's derivatives at the vertex are parallel).
      const int n = tri ? 3 : 4;
      for (std::size_t i = 0; i < at.size(); ++i) {
        uv[i] = {double(samples[i].u), double(samples[i].v)};
        if (i < std::size_t(n)) uv[i] = step_inward(n, uv[i]);
      }
      std::vector<Stencil> du, dv;
      if (!limit.at(patch.face, uv, &du, &dv)) continue;
      bool folded = false;
      for (std::size_t i = 0; i < at.size() && !folded; ++i) {
        const glm::dvec3 ld = sum(du[i], cage.positions), le = sum(dv[i], cage.positions);
        const glm::dvec3 ln = flip * glm::cross(ld, le);
        const double defined = kDefinedNormal * glm::length(ld) * glm::length(le);
        folded = glm::length(ln) > defined && glm::dot(ln, glm::dvec3(samples[i].normal)) < 0.0;
      }
      if (folded) out.faces[std::size_t(patch.face)] = 1;
    }
  }
  return out;
}

}  // namespace tessera
