#include "shaders_cpp/lod/subd_factors.h"

#include <cmath>

#include "shaders_cpp/cage/one_line.h"

namespace tessera {

SubdFactors base_factors(float factor, float vary,
                         std::shared_ptr<const std::unordered_map<std::int64_t, float>> per_edge) {
  if (!std::isfinite(factor) || factor <= 0.0f || factor > 64.0f)
    throw FactorSettingError("--factor: " + float_text(factor) + " is not in (0, 64]");
  if (!std::isfinite(vary) || vary < 0.0f || vary > 63.0f)
    throw FactorSettingError("--vary-factors: must be in [0, 63]");
  SubdFactors f;
  f.factor = factor;
  f.vary = vary;
  f.per_edge = std::move(per_edge);
  return f;
}

LodSettings apply_lod(const LodRequest& r, const LodView& view, const LodModel& model, SubdFactors& factors,
                      PatchCull& cull) {
  if (!(std::isfinite(r.edge_pixels) && r.edge_pixels >= 0.25f && r.edge_pixels <= 4096.0f))
    throw FactorSettingError("--edge-pixels: " + float_text(r.edge_pixels) + " is not in [0.25, 4096]");
  if (!(std::isfinite(r.lod_distance) && r.lod_distance >= 0.0f))
    throw FactorSettingError("--lod-distance: " + float_text(r.lod_distance) + " is not a finite distance >= 0");
  if (r.mode == LodMode::uniform && (r.edge_pixels != 8.0f || r.lod_distance != 0.0f || r.dicing_eye))
    throw FactorSettingError(
        "--edge-pixels, --lod-distance and --dicing-camera-position need --lod distance or screen");
  LodSettings s;
  s.mode = r.mode;
  s.factor = factors.factor;
  s.edge_pixels = r.edge_pixels;
  s.bound = model.displacement_bound;
  s.camera.eye = r.dicing_eye.value_or(view.eye);
  s.camera.pixels_per_unit = pixels_per_unit(view.height, view.fov);
  s.lod_distance = r.lod_distance > 0.0f ? r.lod_distance : glm::length(view.eye - view.target);
  if (s.mode != LodMode::uniform) {
    if (factors.per_edge || factors.vary > 0.0f)
      throw FactorSettingError(std::string("--lod ") + to_string(s.mode) +
                               " sets every edge's factor: drop --factors-per-edge and --vary-factors");
    factors.per_edge = edge_lod_factors(model.positions, model.topology, s);
  }
  if (culls_frustum(r.cull)) {
    cull.frustum.enabled = true;
    cull.frustum.view_projection = view.view_projection;
    cull.frustum.growth = model.displacement_bound;
  }
  // Displaced patches carry no orientation claim (back_patch_cull.h): no test for them.
  if (culls_backface(r.cull) && !model.displaced)
    cull.back = BackPatchCull(view.view_projection, view.width, view.height, model.culled_screen_sign);
  return s;
}

}  // namespace tessera
