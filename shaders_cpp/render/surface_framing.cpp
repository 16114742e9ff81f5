#include "shaders_cpp/render/surface_framing.h"

#include <algorithm>
#include <cmath>

#include <tbb/task_arena.h>

#include "shaders_cpp/cage/bounding_box.h"

namespace tessera {

std::vector<glm::vec3> surface_points(const SubdModel& model) {
  // Factor 8 follows a patch that bulges between its corners as a render draws it; factor 2 (corners,
  // edge midpoints, centre) still bounds it within a few percent, at control-point rate.
  const double patches = double(std::max<std::size_t>(1, model.patches.quads.size() + model.patches.tris.size()));
  const double fitting = std::floor(std::sqrt(double(kFramingPoints) / patches)) - 1.0;  // (f + 1)^2 points a quad
  const float factor = float(std::clamp(fitting, 2.0, 8.0));
  // As many threads as the calling arena has: the stream hands patches over in order on this thread,
  // so the points are the same for any count.
  DeviceOptions options;
  options.threads = std::max(1, tbb::this_task_arena::max_concurrency());
  Device device(options);
  // Reserved for every patch drawn uncut at the factor (grown copies would cost as much as the draw).
  const std::size_t per_side = std::size_t(factor) + 1;
  std::vector<glm::vec3> points;
  points.reserve(model.patches.quads.size() * per_side * per_side +
                 model.patches.tris.size() * per_side * (per_side + 1) / 2);
  const DrawResult r = stream_subd(device, model, base_factors(factor, 0.0f), ts::Partitioning::integer,
                                   [&](const PatchOutput<SurfaceSample>& p, const PatchGroup&) {
                                     for (const SurfaceSample& s : p.points) points.push_back(s.position);
                                   });
  // The draw that follows would report the same error; framing on the control points loses nothing.
  if (!r.ok() || points.empty()) return model.positions();
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
