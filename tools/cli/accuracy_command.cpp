// `tessera accuracy CAGE.obj --scheme S`: how far a scheme's surface is from the exact Catmull-Clark
// limit surface (OpenSubdiv at its highest isolation level), measured at the domain points the scheme
// actually produces. Distances are parametric (the scheme's point against the limit's point at the same
// face and domain location), an upper bound of the distance to the surface, relative to the limit
// surface's bounding-box diagonal; normal errors are angles between the two unit normals. The ripple
// (curvature): along every edge of the tessellation, the normal curvature (n1 - n0) . (p1 - p0) / |p1 - p0|^2
// of the scheme's points and normals against the limit's at the same domain points, the difference
// times the diagonal (so a sphere's curvature is about 3.5 whatever its size). The largest curvature of
// each surface on its own is reported too: around a vertex of high valence Catmull-Clark's limit itself
// ripples (a valence-32 pole of a sphere: 54, against gregory's 35), so a large curvature error there is
// the limit's ripple as much as the scheme's. A sample whose normal is more than 90 degrees from the limit's,
// where the limit's is defined (limit_normal_defined), is folded: the surface turned over there.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <sstream>
#include <utility>
#include <vector>

#include "shaders_cpp/render/subd_model.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"

namespace tessera::cli {

using namespace scene;

namespace {

// Whether the limit's normal at point (s, t) of a face's sub-patch is defined: finite, and not turning
// by more than kUndefinedTurnDegrees within kNeighbourStep of the point inside the sub-patch. It turns so
// where a crease line runs through the point, at a cusp and at a degenerate vertex (valence 2, a collapsed
// edge), where a scheme's normal may point anywhere without a fold anyone sees. Asked only of samples whose
// error exceeds kCheckAboveDegrees, so it costs nothing where the scheme follows the limit.
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

struct AccuracyOptions {
  RenderSettings s = [] {
    RenderSettings d;
    d.factor = 7.0f;
    return d;
  }();  // the cage, scheme, factors, partitioning, threads and glTF asset, as render's
  bool json = false;
};

int run_accuracy(const AccuracyOptions& o) {
  const Scheme scheme = o.s.scheme;
  const ts::Partitioning partitioning = o.s.partitioning;
  const SubdModel model = load_model(o.s.cage, scheme, o.s.asset, o.s.isolation);
  const SubdFactors factors = factors_option(o.s.factor, o.s.vary, o.s.factors_file, model.cage);
  std::unique_ptr<LimitSurface> own_reference;
  try {
    // The limit of the cage the vertex shader outputs (the posed cage of an animated asset).
    Cage posed = model.cage;
    posed.positions = model.positions();
    // exact measures against its own surface; adaptive's is not the reference.
    if (!model.limit || model.limit->adaptive())
      own_reference = std::make_unique<LimitSurface>(LimitSurface::create(posed));
  } catch (const CageError& e) {
    throw InputError(e.what());
  }
  const LimitSurface& reference = own_reference ? *own_reference : *model.limit;
  const double diagonal = reference.bounding_box_diagonal();
  Device device(device_options(o.s.threads));
  double max_d = 0, sum_d2 = 0, max_angle = 0, sum_angle = 0, max_k = 0, sum_k = 0, max_ks = 0, max_kl = 0;
  double max_angle_defined = 0;
  std::uint64_t samples = 0, edges = 0, folded = 0, undefined = 0;
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
          max_d = std::max(max_d, d);
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
          if (defined && !(angle <= kFoldDegrees)) ++folded;
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
  if (!r.ok()) throw InputError(o.s.cage + ": " + r.error);
  const double rms = samples ? std::sqrt(sum_d2 / double(samples)) : 0.0;
  const double rel_max = max_d / diagonal, rel_rms = rms / diagonal;
  if (o.json) {
    const Json j = {{"cage", o.s.cage},
                    {"scheme", to_string(scheme)},
                    {"factor", json_float(o.s.factor)},
                    {"samples", samples},
                    {"diagonal", diagonal},
                    {"max_distance", max_d},
                    {"rms_distance", rms},
                    {"max_relative", rel_max},
                    {"rms_relative", rel_rms},
                    {"max_normal_degrees", max_angle},
                    {"mean_normal_degrees", samples ? sum_angle / double(samples) : 0.0},
                    {"max_normal_degrees_defined", max_angle_defined},
                    {"undefined_normal_samples", undefined},
                    {"folded_samples", folded},
                    {"max_curvature_error", max_k * diagonal},
                    {"mean_curvature_error", edges ? sum_k / double(edges) * diagonal : 0.0},
                    {"max_curvature_scheme", max_ks * diagonal},
                    {"max_curvature_limit", max_kl * diagonal},
                    {"fallback_faces", model.patches.fallback_faces}};
    std::cout << json_text(j) << "\n";
  } else {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s: scheme %s vs exact limit, %llu samples: max %.3e, rms %.3e of the diagonal (%.4g); normals max "
                  "%.3f deg (%.3f where the limit's is defined; %llu samples where it is not), mean %.4f deg; "
                  "%llu folded samples; curvature error max %.3g, mean %.3g; largest curvature: scheme %.3g, "
                  "limit %.3g (per diagonal)\n",
                  o.s.cage.c_str(), to_string(scheme), (unsigned long long)samples, rel_max, rel_rms, diagonal,
                  max_angle, max_angle_defined, (unsigned long long)undefined,
                  samples ? sum_angle / double(samples) : 0.0, (unsigned long long)folded, max_k * diagonal,
                  edges ? sum_k / double(edges) * diagonal : 0.0, max_ks * diagonal, max_kl * diagonal);
    std::cout << line;
  }
  return kExitOk;
}

}  // namespace

Runner add_accuracy_command(CLI::App& app) {
  auto o = std::make_shared<AccuracyOptions>();
  CLI::App* cmd = app.add_subcommand("accuracy", "distance of a scheme's surface to the exact limit surface");
  cmd->add_option("cage", o->s.cage, "the cage: OBJ (OpenSubdiv tags allowed) or glTF (.gltf, .glb)")->required();
  add_scheme_options(*cmd, o->s);
  add_asset_options(*cmd, o->s.asset);
  cmd->add_flag("--json", o->json, "print the result as JSON");
  return [o] { return run_accuracy(*o); };
}

}  // namespace tessera::cli
