#include "shaders_cpp/render/surface_framing.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "pipeline/front_end.h"
#include "pipeline/pattern_cache.h"
#include "shaders_cpp/displacement/watertight_uv.h"

#include "shaders_cpp/cage/bounding_box.h"

namespace tessera {

namespace {

// Which of a quad patch's edge and corner points it reports: bit k, patch edge k (its half-edge owns
// the cage edge); bit 4 + k, patch corner k (its half-edge is the vertex's owner). The other patches
// that hold such a point compute the same bits (the surface is watertight to the bit), so the point set
// is the same with each point once. Fan triangles and n-gon faces report every point.
std::uint8_t owned_points(const Topology& t, const SubdPatch& p, bool quads) {
  if (!quads || p.sub != 0 || t.face_size(p.face) != 4) return 0xFF;
  std::uint8_t mask = 0;
  for (int k = 0; k < 4; ++k) {
    const int h = t.face_offset(p.face) + (k + p.rotation) % 4;
    if (edge_owner(t, h) == h) mask = std::uint8_t(mask | (1u << k));
    if (vertex_owner(t, t.origin(h)) == h) mask = std::uint8_t(mask | (1u << (4 + k)));
  }
  return mask;
}

bool reported(const DomainLocation& l, std::uint8_t mask) {
  const bool on_u = l.u == 0.0f || l.u == 1.0f, on_v = l.v == 0.0f || l.v == 1.0f;
  if (on_u && on_v) return (mask >> (4 + (l.v == 0.0f ? (l.u == 0.0f ? 0 : 1) : (l.u == 1.0f ? 2 : 3))) & 1u) != 0;
  if (on_u || on_v) return (mask >> (l.v == 0.0f ? 0 : l.u == 1.0f ? 1 : l.v == 1.0f ? 2 : 3) & 1u) != 0;
  return true;
}

}  // namespace

std::vector<glm::vec3> surface_points(const SubdModel& model) {
  // Factor 8 follows a patch that bulges between its corners as a render draws it; factor 2 (corners,
  // edge midpoints, centre) still bounds it within a few percent, at control-point rate.
  const double patches = double(std::max<std::size_t>(1, model.patches.quads.size() + model.patches.tris.size()));
  const double fitting = std::floor(std::sqrt(double(kFramingPoints) / patches)) - 1.0;  // (f + 1)^2 points a quad
  const float factor = float(std::clamp(fitting, 2.0, 8.0));
  // What stream_subd draws at the factor, evaluated patch by patch without the pipeline's windows and
  // chunks: the same vertex, hull and domain shader calls on the same inputs (so the same bits), on the
  // calling arena's threads, in blocks whose points are joined in patch order.
  constexpr std::size_t kBlock = 1024;
  std::vector<glm::vec3> points;
  const SubdVS vs = model.vertex_shader();
  const std::span<const glm::vec3> vertices = model.vertex_buffer();
  const Topology& topology = *model.topology;
  for_each_patch_group(
      model, base_factors(factor, 0.0f), PatchCull{}, ts::Partitioning::integer,
      [&](const PatchGroup& g, const TessellatorState& ts, const SubdHS& hs, const SubdDS& ds) {
        const std::size_t n = g.patches.size(), cp = std::size_t(g.control_points);
        const bool quads = g.domain == ts::Domain::quad;
        std::vector<std::vector<glm::vec3>> blocks((n + kBlock - 1) / kBlock);
        tbb::enumerable_thread_specific<PatternCache> patterns;
        tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t b) {
          PatternCache& cache = patterns.local();
          std::array<SubdVertex, 32> in;
          std::array<SubdControlPoint, SubdHS::kOutputControlPoints> out;
          std::vector<glm::vec3>& block = blocks[b];
          for (std::size_t p = b * kBlock; p < std::min(n, (b + 1) * kBlock); ++p) {
            const auto id = std::uint32_t(p);
            for (std::size_t i = 0; i < cp; ++i) {
              const std::uint32_t v = g.indices[p * cp + i];
              in[i] = vs(v < vertices.size() ? vertices[v] : glm::vec3(0.0f), v);
            }
            const std::span<const SubdVertex> ins(in.data(), cp);
            for (int j = 0; j < SubdHS::kOutputControlPoints; ++j) out[std::size_t(j)] = hs.control_point(ins, j, id);
            const SubdPatchConstants pc = hs.patch_constants(ins, out, id);
            const ts::ProcessedFactors processed =
                ts::process_factors(ts.partitioning, detail::factor_set(ts.domain, pc.factors));
            if (processed.culled) continue;
            bool hit = false;
            const ts::Pattern& pattern = cache.get(processed, ts.output, hit);
            const std::uint8_t mask = owned_points(topology, g.patches[p], quads);
            for (const ts::DomainPoint q : pattern.points) {
              const DomainLocation l = detail::domain_location(q, ts.domain);
              if (reported(l, mask)) block.push_back(ds(pc, out, l, id).position);
            }
          }
        });
        for (const auto& block : blocks) points.insert(points.end(), block.begin(), block.end());
        return DrawResult{};
      });
  // A model drawing nothing is framed on its control points, as the draw that follows would report.
  if (points.empty()) return model.positions();
  return points;
}

glm::vec3 framing_direction(const SubdModel& model, glm::vec3 up) {
  const glm::vec3 d = default_view_direction(up);
  const Cage& cage = model.cage;
  const std::vector<glm::vec3>& p = model.positions();
  glm::dvec3 vector_area(0.0);
  double area = 0.0;
  for (int f = 0; f < cage.face_count(); ++f) {
    const int n = cage.face_sizes[std::size_t(f)];
    glm::dvec3 a(0.0);
    for (int k = 0; k < n; ++k)
      a += glm::cross(glm::dvec3(p[std::size_t(cage.face_vertex(f, k))]),
                      glm::dvec3(p[std::size_t(cage.face_vertex(f, (k + 1) % n))]));
    vector_area += 0.5 * a;
    area += 0.5 * glm::length(a);
  }
  if (cage.tags.left_handed) vector_area = -vector_area;
  const double facing = glm::length(vector_area);
  if (!(area > 0.0) || facing < 0.5 * area) return d;  // closed, or facing many ways: any side shows surface
  const glm::dvec3 front = vector_area / facing, dd(d);
  if (glm::dot(dd, front) >= 0.75) return d;
  // Keep the default's bearing across the sheet, lifted to its front side.
  glm::dvec3 across = dd - glm::dot(dd, front) * front;
  if (glm::length(across) < 1e-6) across = glm::dvec3(up) - glm::dot(glm::dvec3(up), front) * front;
  if (glm::length(across) < 1e-6) return glm::vec3(front);
  const glm::dvec3 lifted = glm::normalize(0.6 * glm::normalize(across) + 0.8 * front);
  // fit_camera needs a direction off the up axis.
  if (std::abs(glm::dot(lifted, glm::dvec3(up))) > 0.999) return d;
  return glm::vec3(lifted);
}

namespace {
// The supports of the points in one plane of the camera: across is the image axis (right or up),
// back the view axis toward the eye, t the tangent of the fitted half angle. The camera at lateral
// offset a and distance D holds a point (x, w) when |x - a| <= (D - w) t, that is when
// x + w t <= D t + a and -x + w t <= D t - a; the least D that holds them all and the a that centres
// them come from the two largest left-hand sides.
struct PlaneFit {
  double distance = 0, offset = 0;
  double high = 0, low = 0;  // the supports (not centred)
};
// With `below` < t, the points are held in a frustum that reaches t on the positive side and `below`
// on the negative one (a band at the image's bottom kept free): x - a <= (D - w) t and
// a - x <= (D - w) below.
PlaneFit fit_plane(std::span<const glm::vec3> points, glm::dvec3 centre, glm::dvec3 across, glm::dvec3 back, double t,
                   double below, bool centred) {
  double high = -INFINITY, low = -INFINITY;
  for (const glm::vec3& p : points) {
    const glm::dvec3 q = glm::dvec3(p) - centre;
    const double x = glm::dot(q, across), w = glm::dot(q, back);
    if (centred) {
      high = std::max(high, w + std::abs(x) / below);
    } else {
      high = std::max(high, x + w * t);
      low = std::max(low, -x + w * below);
    }
  }
  if (centred) return {high, 0.0};
  return {(high + low) / (t + below), (high - low) / 2.0, high, low};
}
}  // namespace

SubdCamera fit_camera(std::span<const glm::vec3> points, std::span<const glm::vec3> bounds, int width, int height,
                      float fov_degrees, glm::vec3 direction, std::optional<glm::vec3> target, glm::vec3 up,
                      float fill, float bottom_band) {
  // In double: the same points give the same camera, and a far-off model keeps its precision.
  const glm::dvec3 back = glm::normalize(glm::dvec3(direction));
  const glm::dvec3 right = glm::normalize(glm::cross(-back, glm::dvec3(up)));
  const glm::dvec3 image_up = glm::cross(right, -back);
  const double aspect = double(width) / double(height);
  const double ty = std::tan(0.5 * double(glm::radians(fov_degrees))) * double(fill);
  const double tx = ty * aspect;
  // The band's fraction of the height, 2 band of the normalized device y range, off the lower reach.
  const double band = target ? 0.0 : std::clamp(double(bottom_band), 0.0, double(kMaxBottomBand));
  const double ty_below = band > 0.0 ? std::tan(0.5 * double(glm::radians(fov_degrees))) * (double(fill) - 2.0 * band)
                                     : ty;
  const Box3 box = bounding_box(points);
  const glm::dvec3 centre = target ? glm::dvec3(*target) : glm::dvec3(box.centre());
  const PlaneFit h = fit_plane(points, centre, right, back, tx, tx, target.has_value());
  const PlaneFit v = fit_plane(points, centre, image_up, back, ty, ty_below, target.has_value());
  // A point-like or flat-on model still gets a camera in front of it.
  const double extent = std::max(1e-6, double(glm::length(box.hi - box.lo)));
  const double distance = std::max({h.distance, v.distance, 1e-3 * extent});
  // Off centre when a band is kept: in the middle of what the distance allows, a in
  // [high - D t, D below - low] (both ends equal when the vertical fit is the tighter).
  const double v_offset =
      band > 0.0 ? 0.5 * ((v.high - distance * ty) + (distance * ty_below - v.low)) : v.offset;
  const glm::dvec3 aim = centre + right * h.offset + image_up * v_offset;
  Box3 all = bounding_box(bounds);
  all.extend(box.lo), all.extend(box.hi);
  const glm::vec3 corners[2] = {all.lo, all.hi};
  return look_at(corners, width, height, fov_degrees, glm::vec3(aim + back * distance), glm::vec3(aim), up);
}

}  // namespace tessera
