// The base surface a map is baked onto: the renderer's own evaluation (SubdHS's control points, SubdDS's
// surface point, DisplacedDS's frames) at any domain location of any quad patch, so that a baked value
// displaces exactly the point the renderer draws there.
//
// Frames, as the renderer applies them (displaced_shaders.h):
// - `normal`: what scalar displacement moves along, and the normal map's z;
// - `tangent`, `bitangent`: vector displacement's x and y (DisplacedDS: T is dP/dU in the tangent plane,
//   B = ±N x T following dP/dV);
// - `shade_tangent`, `shade_bitangent`: the normal map's x and y (DisplacedPS: dP/dU and dP/dV
//   orthonormalized against N, in that order).
// Interior points use their patch's own derivatives; the renderer's owner frames on cage edges are the
// same surface's, and texel centres are interior points of their patch.
//
// Contract: the model's quad patches (displaced cages are quads); control points are computed once per
// patch at construction, in parallel and deterministically; evaluate() is const and thread-safe.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "shaders_cpp/displacement/watertight_uv.h"
#include "shaders_cpp/render/subd_model.h"

namespace tessera {

struct BaseFrame {
  glm::vec3 position{0.0f}, normal{0.0f};
  glm::vec3 tangent{0.0f}, bitangent{0.0f};
  glm::vec3 shade_tangent{0.0f}, shade_bitangent{0.0f};
  std::uint32_t face = 0;  // the cage face, and the location in its own frame (SurfaceSample's)
  float face_u = 0, face_v = 0;
};

class BaseSurface {
 public:
  // `texcoords`: per quad patch (build_patch_texcoords); both must outlive this object.
  BaseSurface(const SubdModel& model, std::span<const PatchTexcoords> texcoords);
  BaseFrame evaluate(std::uint32_t patch, float u, float v) const;
  std::size_t patch_count() const { return texcoords_.size(); }

 private:
  const SubdModel& model_;
  std::span<const PatchTexcoords> texcoords_;
  SubdFactors factors_;
  std::vector<SubdControlPoint> control_points_;  // SubdHS::kOutputControlPoints per patch
};

}  // namespace tessera
