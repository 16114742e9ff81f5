#include "tools/measure/scheme_accuracy.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace tessera::measure {

namespace {

constexpr double kUndefinedTurnDegrees = 30.0, kNeighbourStep = 1.0 / 256.0, kCheckAboveDegrees = 10.0;
constexpr double kFoldDegrees = 90.0;  // a defined normal this far off: the surface is folded over there

bool limit_normal_defined(const LimitSurface& reference, int face, int sub, double s, double t,
                          const glm::dvec3& normal) {
  const double len = glm::length(normal);
  if (!std::isfinite(len) || len == 0.0) return false;
  const glm::dvec3 n = normal / len;
  const double cos_limit = std::cos(kUndefinedTurnDegrees * std::numbers::pi / 180.0);
  for (const auto& [ds, dt] : {std::pair(1.0, 0.0), std::pair(-1.0, 0.0), std::pair(0.0, 1.0), std::pair(0.0, -1.0)}) {
    const double x = std::clamp(s + ds * kNeighbourStep, 0.0, 1.0), y = std::clamp(t + dt * kNeighbourStep, 0.0, 1.0);
    const glm::dvec3 m = reference.sample_reference(face, sub, x, y).normal;
    const double ml = glm::length(m);
    if (!std::isfinite(ml) || ml == 0.0 || glm::dot(n, m / ml) < cos_limit) return false;
  }
  return true;
}

}  // namespace

SchemeAccuracy measure_scheme_accuracy(Device& device, const SubdModel& model, const LimitSurface& reference,
                                       const SubdFactors& factors, ts::Partitioning partitioning) {
  const double diagonal = reference.bounding_box_diagonal();
  double max_d = 0, sum_d2 = 0, max_angle = 0, sum_angle = 0, max_k = 0, sum_k = 0, max_ks = 0, max_kl = 0;
  double max_angle_defined = 0;
  std::uint64_t samples = 0, edges = 0, folded = 0, undefined = 0;
  std::vector<int> folded_faces;
  int farthest_face = -1;
  // One patch's points and unit normals, the scheme's and the limit's, for the curvature along its edges.
  std::vector<glm::dvec3> scheme_p, scheme_n, limit_p, limit_n;
  auto curvature = [](const glm::dvec3& p0, const glm::dvec3& n0, const glm::dvec3& p1, const glm::dvec3& n1) {
    const glm::dvec3 d = p1 - p0;
    return glm::dot(n1 - n0, d) / glm::dot(d, d);
  };
  const DrawResult r =
      stream_subd(device, model, factors, partitioning, [&](const PatchOutput<SurfaceSample>& p, const PatchGroup& g) {
        const SubdPatch& patch = g.patches[p.patch_id];
        const int n = reference.face_size(patch.face);
        scheme_p.clear(), scheme_n.clear(), limit_p.clear(), limit_n.clear();
        for (std::size_t i = 0; i < p.points.size(); ++i) {
          const SurfaceSample& s = p.points[i];
          const ts::DomainPoint q = p.domain[i];
          // On a crease the limit has two normals, one per side; a point shared by two faces carries its
          // owner's (limit_surface.h), so a normal is measured against this face's and the owner's, the nearer.
          glm::dvec3 pos, nrm, owned;
          int sub = patch.sub;  // where the sample lies among the face's quad sub-patches, for the normal's check
          double ss = s.u, st = s.v;
          if (g.domain == ts::Domain::tri && n == 3) {
            // The face's own barycentrics (the DS undid any rotation); exact: multiples of 2^-16.
            const SurfacePoint e = reference.evaluate_triangle(patch.face, s.u, s.v, (1.0f - s.u) - s.v);
            pos = glm::dvec3(e.position), nrm = owned = glm::dvec3(e.normal);
            const LimitSurface::TriangleLocation l = LimitSurface::triangle_location(s.u, s.v);
            sub = l.sub, ss = l.s, st = l.t;
          } else if (g.domain == ts::Domain::tri) {  // a fan triangle of a larger face
            const LimitSurface::SubPatchLocation l = LimitSurface::fan_location(n, patch.sub, q.u, q.v);
            const ReferenceSample e = reference.sample_reference(patch.face, l.sub, l.s, l.t);
            pos = e.position, nrm = e.normal;
            owned = glm::dvec3(reference.evaluate_fan(patch.face, patch.sub, q.u, q.v, (1.0f - q.u) - q.v).normal);
            sub = l.sub, ss = l.s, st = l.t;
          } else {
            const ReferenceSample e = reference.sample_reference(patch.face, patch.sub, s.u, s.v);  // the face's frame
            pos = e.position, nrm = e.normal;
            owned = glm::dvec3(reference.evaluate(patch.face, patch.sub, s.u, s.v).normal);
          }
          const double d = glm::length(glm::dvec3(s.position) - pos);
          if (d > max_d || farthest_face < 0) max_d = std::max(max_d, d), farthest_face = patch.face;
          sum_d2 += d * d;
          const glm::dvec3 sn = glm::normalize(glm::dvec3(s.normal));
          scheme_p.push_back(glm::dvec3(s.position)), scheme_n.push_back(sn);
          limit_p.push_back(pos), limit_n.push_back(glm::normalize(nrm));
          const double c =
              std::clamp(std::max(glm::dot(sn, glm::normalize(nrm)), glm::dot(sn, glm::normalize(owned))), -1.0, 1.0);
          const double angle = std::acos(c) * 180.0 / std::numbers::pi;
          if (std::isfinite(angle)) {
            max_angle = std::max(max_angle, angle);
            sum_angle += angle;
          }
          const bool defined = !(angle > kCheckAboveDegrees) ||
                               limit_normal_defined(reference, patch.face, sub, ss, st, nrm);
          if (!defined) ++undefined;
          if (defined && std::isfinite(angle)) max_angle_defined = std::max(max_angle_defined, angle);
          if (defined && !(angle <= kFoldDegrees)) ++folded, folded_faces.push_back(patch.face);
          ++samples;
        }
        for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3)
          for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t a = p.indices[t + k], b = p.indices[t + (k + 1) % 3];
            if (limit_p[a] == limit_p[b]) continue;  // a collapsed edge (a pole of the domain) has no direction
            const double ks = curvature(scheme_p[a], scheme_n[a], scheme_p[b], scheme_n[b]);
            const double kl = curvature(limit_p[a], limit_n[a], limit_p[b], limit_n[b]);
            const double e = std::abs(ks - kl);
            if (!std::isfinite(e)) continue;
            max_ks = std::max(max_ks, std::abs(ks));
            max_kl = std::max(max_kl, std::abs(kl));
            max_k = std::max(max_k, e);
            sum_k += e;
            ++edges;
          }
      });
  SchemeAccuracy a;
  if (!r.ok()) {
    a.error = r.error;
    return a;
  }
  a.samples = samples, a.diagonal = diagonal;
  a.max_distance = max_d, a.rms_distance = samples ? std::sqrt(sum_d2 / double(samples)) : 0.0;
  a.max_normal_degrees = max_angle, a.mean_normal_degrees = samples ? sum_angle / double(samples) : 0.0;
  a.max_normal_degrees_defined = max_angle_defined;
  a.undefined_normal_samples = undefined, a.folded_samples = folded;
  std::sort(folded_faces.begin(), folded_faces.end());
  folded_faces.erase(std::unique(folded_faces.begin(), folded_faces.end()), folded_faces.end());
  a.folded_faces = std::move(folded_faces), a.farthest_face = farthest_face;
  a.max_curvature_error = max_k * diagonal, a.mean_curvature_error = edges ? sum_k / double(edges) * diagonal : 0.0;
  a.max_curvature_scheme = max_ks * diagonal, a.max_curvature_limit = max_kl * diagonal;
  return a;
}

}  // namespace tessera::measure
