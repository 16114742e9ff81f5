#include "tools/scene/view_options.h"

#include <cmath>

#include "shaders_cpp/render/subd_render.h"
#include "tools/scene/common.h"

namespace tessera::cli {

glm::vec3 parse_vec3(const std::string& text, const char* what) {
  const auto v = parse_float_list(text, what);
  if (v.size() != 3) throw UsageError(std::string(what) + ": expected x,y,z");
  for (float x : v)
    if (!std::isfinite(x)) throw UsageError(std::string(what) + ": not finite");
  return {v[0], v[1], v[2]};
}

void add_camera_options(CLI::App& cmd, CameraCli& c) {
  cmd.add_option("--resolution", c.resolution, "WxH")->capture_default_str();
  cmd.add_option("--camera-position", c.eye, "x,y,z (default: framing the model)");
  cmd.add_option("--camera-target", c.target, "x,y,z (default: the model's centre)");
  cmd.add_option("--fov", c.fov, "vertical field of view, degrees")->capture_default_str();
  cmd.add_option("--camera-up", c.up, "x,y,z: the world's up direction (default 0,1,0; 0,0,1 for z-up assets)");
}

namespace {
// Resolution and field of view, checked.
ViewSetup view_frame(const CameraCli& c) {
  ViewSetup v;
  std::tie(v.width, v.height) = parse_resolution(c.resolution);
  if (!(c.fov > 1.0f && c.fov < 179.0f)) throw UsageError("--fov: must be in (1, 179) degrees");
  v.fov = c.fov;
  return v;
}
}  // namespace

// --camera-up as a unit vector (+y when not given).
glm::vec3 up_option(const CameraCli& c) {
  if (c.up.empty()) return {0.0f, 1.0f, 0.0f};
  const glm::vec3 up = parse_vec3(c.up, "--camera-up");
  const double length = glm::length(glm::dvec3(up));
  if (!(length > 1e-12) || !std::isfinite(length))
    throw UsageError("--camera-up: " + c.up + " has no direction (give a non-zero x,y,z)");
  return glm::vec3(glm::dvec3(up) / length);
}

// A camera looking along its up axis has no defined orientation (lookAt divides by zero and the image
// is empty), so it is refused rather than drawn as nothing.
void check_camera_orientation(const SubdCamera& camera, const CameraCli& c) {
  const glm::dvec3 d = glm::dvec3(camera.target) - glm::dvec3(camera.eye);
  const double across = glm::length(glm::cross(glm::normalize(d), glm::dvec3(camera.up)));
  if (!(across > 1e-4))
    throw UsageError("--camera-position/--camera-target: the camera looks straight along the up axis (" +
                     (c.up.empty() ? std::string("+y") : c.up) +
                     "), which leaves its orientation undefined; move it off that axis or give --camera-up");
}

ViewSetup view_option(const CameraCli& c, const Cage& cage) {
  ViewSetup v = view_frame(c);
  std::optional<glm::vec3> eye, target;
  if (!c.eye.empty()) eye = parse_vec3(c.eye, "--camera-position");
  if (!c.target.empty()) target = parse_vec3(c.target, "--camera-target");
  if (eye && target && glm::length(*eye - *target) <= 0.0f) throw UsageError("camera position and target coincide");
  v.camera = frame_cage(cage, v.width, v.height, c.fov, eye, target, up_option(c));
  if (glm::length(v.camera.eye - v.camera.target) <= 0.0f)
    throw UsageError("--camera-position: equal to the model's centre (give --camera-target)");
  check_camera_orientation(v.camera, c);
  return v;
}

ViewSetup view_at(const CameraCli& c, const Cage& cage, glm::vec3 eye, glm::vec3 target) {
  ViewSetup v = view_frame(c);
  if (glm::length(eye - target) <= 0.0f) throw UsageError("camera position and target coincide");
  v.camera = frame_cage(cage, v.width, v.height, c.fov, eye, target, up_option(c));
  check_camera_orientation(v.camera, c);
  return v;
}

ViewSetup orbit_view(const CameraCli& c, const Cage& cage, const ViewSetup& base, int i, int n) {
  if (i == 0) return base;
  // In double, the angle from the integers, so view i is the same for any n that names the same angle.
  const glm::dvec3 up(base.camera.up), target(base.camera.target);
  const glm::dvec3 offset = glm::dvec3(base.camera.eye) - target;
  const double angle = 2.0 * 3.14159265358979323846 * double(i) / double(n);
  const double cos_a = std::cos(angle), sin_a = std::sin(angle);
  const glm::dvec3 turned = offset * cos_a + glm::cross(up, offset) * sin_a + up * glm::dot(up, offset) * (1.0 - cos_a);
  return view_at(c, cage, glm::vec3(target + turned), base.camera.target);
}

void add_lod_options(CLI::App& cmd, LodCli& l, const std::string& cull_default) {
  l.cull = cull_default;
  cmd.add_option("--lod", l.mode,
                 "tessellation factors: uniform (--factor), distance (falling with each edge's distance to the "
                 "dicing camera) or screen (each cage edge's projected size over --edge-pixels)")
      ->capture_default_str();
  cmd.add_option("--edge-pixels", l.edge_pixels, "--lod screen: target pixels per segment")->capture_default_str();
  cmd.add_option("--lod-distance", l.lod_distance,
                 "--lod distance: the distance at which an edge gets --factor (default: camera to target)");
  cmd.add_option("--dicing-camera-position", l.dicing_eye,
                 "x,y,z: measure LOD from here instead of the view camera (a frozen tessellation to fly around)");
  cmd.add_option("--cull", l.cull,
                 "patch culling: none, frustum (the control-point hull outside the view), backface (every "
                 "triangle proven to face away; undisplaced Bezier patches) or all (both; neither changes a pixel)")
      ->capture_default_str();
}

LodResult apply_lod_options(const LodCli& l, const ViewSetup& view, const SubdModel& model, Displacement* displacement,
                            SubdFactors& factors) {
  const auto mode = parse_lod_mode(l.mode);
  if (!mode) throw UsageError("--lod: '" + l.mode + "' is not uniform, distance or screen");
  const auto cull = parse_patch_cull_mode(l.cull);
  if (!cull) throw UsageError("--cull: '" + l.cull + "' is not none, frustum, backface or all");
  LodRequest request{*mode, *cull, l.edge_pixels, l.lod_distance, std::nullopt};
  const LodView lod_view{view.camera.eye, view.camera.target, view.camera.view_projection,
                         view.width,      view.height,        view.fov};
  const LodModel lod_model{model.positions(), *model.topology, subd_culled_screen_sign(model),
                           displacement ? displacement->bound : 0.0f, displacement != nullptr};
  LodResult r;
  r.cull = *cull;
  if (!l.dicing_eye.empty()) request.dicing_eye = parse_vec3(l.dicing_eye, "--dicing-camera-position");
  r.settings = with_usage_errors([&] { return apply_lod(request, lod_view, lod_model, factors); });
  // Set both ways: a scene reconfigured from view-dependent to uniform LOD samples as a fresh one.
  if (displacement) displacement->trilinear = r.settings.mode != LodMode::uniform;
  return r;
}

}  // namespace tessera::cli
