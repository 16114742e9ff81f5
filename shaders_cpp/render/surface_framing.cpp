#include "shaders_cpp/render/surface_framing.h"

#include <algorithm>
#include <cmath>

#include "shaders_cpp/cage/bounding_box.h"

namespace tessera {

std::vector<glm::vec3> surface_points(const SubdModel& model) {
  // Factor 2 puts points at the corners, edge midpoints and centre of each quad (and the like on a
  // triangle): enough to bound a patch that bulges between its corners, and cheap at control-point rate.
  DeviceOptions options;
  options.threads = 1;
  Device device(options);
  std::vector<glm::vec3> points;
  const DrawResult r = stream_subd(device, model, base_factors(2.0f, 0.0f), ts::Partitioning::integer,
                                   [&](const PatchOutput<SurfaceSample>& p, const PatchGroup&) {
                                     for (const SurfaceSample& s : p.points) points.push_back(s.position);
                                   });
  // The draw that follows would report the same error; framing on the control points loses nothing.
  if (!r.ok() || points.empty()) return model.positions();
  return points;
}

namespace {
// The supports of the points in one plane of the camera: across is the image axis (right or up),
// back the view axis toward the eye, t the tangent of the fitted half angle. The camera at lateral
// offset a and distance D holds a point (x, w) when |x - a| <= (D - w) t, that is when
// x + w t <= D t + a and -x + w t <= D t - a; the least D that holds them all and the a that centres
// them come from the two largest left-hand sides.
struct PlaneFit {
  double distance = 0, offset = 0;
};
PlaneFit fit_plane(std::span<const glm::vec3> points, glm::dvec3 centre, glm::dvec3 across, glm::dvec3 back, double t,
                   bool centred) {
  double high = -INFINITY, low = -INFINITY;
  for (const glm::vec3& p : points) {
    const glm::dvec3 q = glm::dvec3(p) - centre;
    const double x = glm::dot(q, across), w = glm::dot(q, back);
    if (centred) {
      high = std::max(high, w + std::abs(x) / t);
    } else {
      high = std::max(high, x + w * t);
      low = std::max(low, -x + w * t);
    }
  }
  if (centred) return {high, 0.0};
  return {(high + low) / (2.0 * t), (high - low) / 2.0};
}
}  // namespace

SubdCamera fit_camera(std::span<const glm::vec3> points, std::span<const glm::vec3> bounds, int width, int height,
                      float fov_degrees, glm::vec3 direction, std::optional<glm::vec3> target, glm::vec3 up,
                      float fill) {
  // In double: the same points give the same camera, and a far-off model keeps its precision.
  const glm::dvec3 back = glm::normalize(glm::dvec3(direction));
  const glm::dvec3 right = glm::normalize(glm::cross(-back, glm::dvec3(up)));
  const glm::dvec3 image_up = glm::cross(right, -back);
  const double aspect = double(width) / double(height);
  const double ty = std::tan(0.5 * double(glm::radians(fov_degrees))) * double(fill);
  const double tx = ty * aspect;
  const Box3 box = bounding_box(points);
  const glm::dvec3 centre = target ? glm::dvec3(*target) : glm::dvec3(box.centre());
  const PlaneFit h = fit_plane(points, centre, right, back, tx, target.has_value());
  const PlaneFit v = fit_plane(points, centre, image_up, back, ty, target.has_value());
  // A point-like or flat-on model still gets a camera in front of it.
  const double extent = std::max(1e-6, double(glm::length(box.hi - box.lo)));
  const double distance = std::max({h.distance, v.distance, 1e-3 * extent});
  const glm::dvec3 aim = centre + right * h.offset + image_up * v.offset;
  Box3 all = bounding_box(bounds);
  all.extend(box.lo), all.extend(box.hi);
  const glm::vec3 corners[2] = {all.lo, all.hi};
  return look_at(corners, width, height, fov_degrees, glm::vec3(aim + back * distance), glm::vec3(aim), up);
}

}  // namespace tessera
