#include "tools/scene/view_options.h"

#include <cmath>

#include "shaders_cpp/cage/bounding_box.h"
#include "shaders_cpp/render/subd_render.h"
#include "shaders_cpp/render/surface_framing.h"
#include "tools/scene/common.h"

namespace tessera::scene {

namespace {
// An optional vector option: "x,y,z", or empty for "not given".
auto optional_vec3(const std::string& what, bool direction) {
  return [what, direction](const std::string& text) -> std::optional<glm::vec3> {
    if (text.empty()) return std::nullopt;
    return direction ? direction_option(text, what) : vec3_option(text, what);
  };
}
}  // namespace

void add_camera_options(CLI::App& cmd, CameraSettings& c) {
  cmd.add_option_function<std::string>(
         "--resolution", [&c](const std::string& text) { std::tie(c.width, c.height) = resolution_option(text); },
         "WxH")
      ->default_str(resolution_text(c.width, c.height));
  add_setting_option(cmd, "--camera-position", c.eye, optional_vec3("--camera-position", false),
                     "x,y,z (default: framing the model)");
  add_setting_option(cmd, "--camera-target", c.target, optional_vec3("--camera-target", false),
                     "x,y,z (default: the model's centre)");
  cmd.add_option("--fov", c.fov, "vertical field of view, degrees")->capture_default_str();
  add_setting_option(cmd, "--camera-up", c.up, optional_vec3("--camera-up", true),
                     "x,y,z: the world's up direction (default 0,1,0; 0,0,1 for z-up assets)");
}

namespace {
// Resolution and field of view, checked.
ViewSetup view_frame(const CameraSettings& c) {
  ViewSetup v;
  v.width = c.width;
  v.height = c.height;
  if (!(c.fov > 1.0f && c.fov < 179.0f)) throw UsageError("--fov: must be in (1, 179) degrees");
  v.fov = c.fov;
  return v;
}
}  // namespace

// --camera-up as a unit vector (+y when not given).
glm::vec3 unit_up(const CameraSettings& c) {
  if (!c.up) return {0.0f, 1.0f, 0.0f};
  return glm::vec3(glm::dvec3(*c.up) / glm::length(glm::dvec3(*c.up)));  // direction_option: not of length 0
}

// A camera looking along its up axis has no defined orientation (lookAt divides by zero and the image
// is empty), so it is refused rather than drawn as nothing.
void check_camera_orientation(const SubdCamera& camera, const CameraSettings& c) {
  const glm::dvec3 d = glm::dvec3(camera.target) - glm::dvec3(camera.eye);
  const double across = glm::length(glm::cross(glm::normalize(d), glm::dvec3(camera.up)));
  if (!(across > 1e-4))
    throw UsageError("--camera-position/--camera-target: the camera looks straight along the up axis (" +
                     (c.up ? vec3_text(*c.up) : std::string("+y")) +
                     "), which leaves its orientation undefined; move it off that axis or give --camera-up");
}

ViewSetup view_option(const CameraSettings& c, const SubdModel& model, float bottom_band, bool with_cage) {
  ViewSetup v = view_frame(c);
  if (c.eye && c.target && glm::length(*c.eye - *c.target) <= 0.0f)
    throw UsageError("camera position and target coincide");
  const std::vector<glm::vec3>& posed = model.positions();
  if (c.eye) {
    v.camera =
        look_at(posed, v.width, v.height, v.fov, *c.eye, c.target.value_or(bounding_box(posed).centre()), unit_up(c));
    if (glm::length(v.camera.eye - v.camera.target) <= 0.0f)
      throw UsageError("--camera-position: equal to the model's centre (give --camera-target)");
  } else {
    std::vector<glm::vec3> points = surface_points(model);
    if (with_cage) points.insert(points.end(), posed.begin(), posed.end());
    v.camera =
        fit_camera(points, posed, v.width, v.height, v.fov, framing_direction(model, unit_up(c)), c.target, unit_up(c),
                   kFrameFill, bottom_band);
  }
  check_camera_orientation(v.camera, c);
  return v;
}

ViewSetup view_at(const CameraSettings& c, const SubdModel& model, glm::vec3 eye, glm::vec3 target) {
  ViewSetup v = view_frame(c);
  if (glm::length(eye - target) <= 0.0f) throw UsageError("camera position and target coincide");
  v.camera = look_at(model.positions(), v.width, v.height, v.fov, eye, target, unit_up(c));
  check_camera_orientation(v.camera, c);
  return v;
}

namespace {
// Orbit view i of n: 2 pi i / n, in double from the integers, so view i is the same for any n that
// names the same angle.
double orbit_angle(int i, int n) { return 2.0 * 3.14159265358979323846 * double(i) / double(n); }

// `v` turned by `angle` about the unit axis `up` (Rodrigues), in double.
glm::dvec3 turn_about(glm::dvec3 v, glm::dvec3 up, double angle) {
  const double cos_a = std::cos(angle), sin_a = std::sin(angle);
  return v * cos_a + glm::cross(up, v) * sin_a + up * glm::dot(up, v) * (1.0 - cos_a);
}
}  // namespace

ViewSetup orbit_base(const CameraSettings& c, const SubdModel& model, const ViewSetup& base, int n) {
  if (c.eye || n < 2) return base;
  // One distance for the whole turntable, the largest any view needs: every view holds the surface
  // whole and the camera does not move in and out as it turns.
  const glm::dvec3 up(base.camera.up), target(base.camera.target);
  const glm::vec3 start = glm::normalize(base.camera.eye - base.camera.target);
  const std::vector<glm::vec3> points = surface_points(model);
  double distance = 0.0;
  for (int i = 0; i < n; ++i) {
    const double angle = orbit_angle(i, n);
    const glm::vec3 direction(glm::normalize(turn_about(glm::dvec3(start), up, angle)));
    const SubdCamera fit = fit_camera(points, model.positions(), base.width, base.height, base.fov, direction,
                                      base.camera.target, base.camera.up);
    distance = std::max(distance, glm::length(glm::dvec3(fit.eye) - target));
  }
  return view_at(c, model, glm::vec3(target + glm::dvec3(start) * distance), base.camera.target);
}

ViewSetup orbit_view(const CameraSettings& c, const SubdModel& model, const ViewSetup& base, int i, int n) {
  if (i == 0) return base;
  const glm::dvec3 up(base.camera.up), target(base.camera.target);
  const double angle = orbit_angle(i, n);
  const glm::dvec3 turned = turn_about(glm::dvec3(base.camera.eye) - target, up, angle);
  return view_at(c, model, glm::vec3(target + turned), base.camera.target);
}

void add_lod_options(CLI::App& cmd, LodCullSettings& l, PatchCullMode cull_default) {
  l.cull = cull_default;
  add_setting_option(cmd, "--lod", l.mode, lod_mode_option,
                     "tessellation factors: uniform (--factor), distance (falling with each edge's distance to the "
                     "dicing camera) or screen (each cage edge's projected size over --edge-pixels)")
      ->default_str(to_string(l.mode));
  cmd.add_option("--edge-pixels", l.edge_pixels, "--lod screen: target pixels per segment")->capture_default_str();
  cmd.add_option("--lod-distance", l.lod_distance,
                 "--lod distance: the distance at which an edge gets --factor (default: camera to target)");
  add_setting_option(cmd, "--dicing-camera-position", l.dicing_eye, optional_vec3("--dicing-camera-position", false),
                     "x,y,z: measure LOD from here instead of the view camera (a frozen tessellation to fly around)");
  add_setting_option(cmd, "--cull", l.cull, cull_option,
                     "patch culling: none, frustum (the control-point hull outside the view), backface (every "
                     "triangle proven to face away; undisplaced Bezier patches) or all (both; neither changes a pixel)")
      ->default_str(to_string(l.cull));
}

LodResult apply_lod_options(const LodCullSettings& l, const ViewSetup& view, const SubdModel& model,
                            Displacement* displacement, SubdFactors& factors, PatchCull& cull) {
  const LodRequest request{l.mode, l.cull, l.edge_pixels, l.lod_distance, l.dicing_eye};
  const LodView lod_view{view.camera.eye, view.camera.target, view.camera.view_projection,
                         view.width,      view.height,        view.fov};
  const LodModel lod_model{model.positions(), *model.topology, subd_culled_screen_sign(model),
                           displacement ? displacement->bound : 0.0f, displacement != nullptr};
  LodResult r;
  r.cull = l.cull;
  r.settings = with_usage_errors([&] { return apply_lod(request, lod_view, lod_model, factors, cull); });
  // Set both ways: a scene reconfigured from view-dependent to uniform LOD samples as a fresh one.
  if (displacement) displacement->trilinear = r.settings.mode != LodMode::uniform;
  return r;
}

}  // namespace tessera::scene
