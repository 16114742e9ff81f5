// Framing what the renderer draws, as a modeller's "frame selected" does: the camera keeps its view
// direction and is placed so that the surface fills the image in its tighter direction, centred, with
// a margin, whatever the object's shape (tall chess pieces, flat sheets) and wherever the pose put it.
//
// Contract
// - surface_points: the domain shader's positions of every patch at a uniform factor of 8 (the surface
//   as drawn at 8; a lower factor, down to 2, on a cage so large that 8 would give over kFramingPoints
//   points), in the model's current pose, without displacement: the point set stream_subd draws, each
//   point on a cage edge or vertex once (from its owner quad), in patch order. Deterministic, on the
//   calling task arena's threads (the points do not depend on their number). The framing below depends
//   on the set alone.
// - framing_direction: the default view direction for `up`, unless the cage is a sheet that mostly
//   faces one way (its vector area at least half its area: an open, nearly flat or gently curved
//   surface), which back-face culling would hide from behind or show edge-on; then a direction on its
//   front side, at least about 50 degrees off its plane.
// - fit_camera: the eye on the line through the points' fit along -`direction` such that every point lies
//   inside the frustum's `fill` fraction (of the half-width and half-height in normalized device
//   coordinates), with both pairs of opposite sides touching in the tighter direction. With `target`
//   given the camera looks at it and only the distance is fitted. Near and far enclose `bounds` (the
//   posed control points, which hold the surface) and the points.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "shaders_cpp/render/subd_render.h"

namespace tessera {

inline constexpr std::size_t kFramingPoints = std::size_t(1) << 20;
std::vector<glm::vec3> surface_points(const SubdModel& model);
glm::vec3 framing_direction(const SubdModel& model, glm::vec3 up);

// The fraction of the image's half extent the framed surface reaches (a 5 % margin on each side).
inline constexpr float kFrameFill = 0.9f;

// The most of the image's height a bottom band may keep free.
inline constexpr float kMaxBottomBand = 0.3f;

// `direction`: unit, from the target toward the eye; `up`: unit, not along `direction`; `points`: not
// empty. `bottom_band`: the fraction of the image height at its bottom that the surface keeps clear
// (a legend's place; 0 to kMaxBottomBand), the surface framed in what is above it; ignored with a
// `target` (the camera then looks at it).
SubdCamera fit_camera(std::span<const glm::vec3> points, std::span<const glm::vec3> bounds, int width, int height,
                      float fov_degrees, glm::vec3 direction, std::optional<glm::vec3> target, glm::vec3 up,
                      float fill = kFrameFill, float bottom_band = 0.0f);

}  // namespace tessera
