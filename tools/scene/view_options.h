// Options the commands that look at a cage share (render, tessellate, bench frog): the camera, the
// level of detail that follows a dicing camera, and patch culling.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "shaders_cpp/lod/edge_lod.h"
#include "shaders_cpp/lod/frustum_cull.h"
#include "shaders_cpp/lod/subd_factors.h"
#include "shaders_cpp/render/displaced_model.h"
#include "shaders_cpp/render/subd_model.h"
#include "shaders_cpp/render/subd_render.h"
#include "tools/scene/render_settings.h"

namespace tessera::scene {

// --resolution, --camera-position, --camera-target, --fov, --camera-up, read into `c`.
void add_camera_options(CLI::App& cmd, CameraSettings& c);

// The view camera: WxH, the vertical field of view, and without --camera-position the camera that frames
// the posed surface along the default direction (render/surface_framing.h; looking at --camera-target
// when given); near and far enclose the posed control points.
// UsageError for a bad resolution, fov, up vector, a position equal to the target, or a view direction
// along the up vector.
struct ViewSetup {
  int width = 0, height = 0;
  float fov = 35.0f;  // degrees
  SubdCamera camera;
};
// `bottom_band`: the fraction of the image height automatic framing keeps clear at the bottom, for a
// legend (legend_band); a given camera position ignores it. `with_cage`: automatic framing holds the
// posed control cage as well as the surface (the cage view draws it, and it reaches beyond the surface).
ViewSetup view_option(const CameraSettings& c, const SubdModel& model, float bottom_band = 0.0f,
                      bool with_cage = false);
// --camera-up as a unit vector (+y when not given).
glm::vec3 unit_up(const CameraSettings& c);
// The same with the camera's position and target given (a path of cameras).
ViewSetup view_at(const CameraSettings& c, const SubdModel& model, glm::vec3 eye, glm::vec3 target);
// The base view of an orbit of n views: `base` itself when the camera was given; a framed camera (no
// --camera-position) moved out along its direction to the largest distance any of the n views needs to
// hold the surface whole (surface_framing.h), so the turntable keeps one distance and crops nothing.
ViewSetup orbit_base(const CameraSettings& c, const SubdModel& model, const ViewSetup& base, int n);
// View i of n around `base`'s target: its eye turned by 2 pi i / n about the up axis through the target
// (counter-clockwise seen from above), at the same distance and height. View 0 is `base` itself.
ViewSetup orbit_view(const CameraSettings& c, const SubdModel& model, const ViewSetup& base, int i, int n);

// --lod, --edge-pixels, --lod-distance, --dicing-camera-position, and --cull with its default.
void add_lod_options(CLI::App& cmd, LodCullSettings& l, PatchCullMode cull_default);

// The policy of lod/subd_factors.h (apply_lod: per-edge LOD factors, frustum and back-patch culling)
// applied for the view and the model; under view-dependent LOD the displacement's mip levels are
// blended (Displacement::trilinear). UsageError for values the policy refuses.
struct LodResult {
  LodSettings settings;
  PatchCullMode cull = PatchCullMode::none;
};
LodResult apply_lod_options(const LodCullSettings& l, const ViewSetup& view, const SubdModel& model,
                            Displacement* displacement, SubdFactors& factors, PatchCull& cull);

}  // namespace tessera::scene
