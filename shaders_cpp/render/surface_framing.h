// Framing what the renderer draws, as a modeller's "frame selected" does: the camera keeps its view
// direction and is placed so that the surface fills the image in its tighter direction, centred, with
// a margin, whatever the object's shape (tall chess pieces, flat sheets) and wherever the pose put it.
//
// Contract
// - surface_points: the domain shader's positions of every patch at uniform factor 2 (corners, edge
//   midpoints and centres of the surface the model draws, in its current pose; displacement is not
//   applied), in draw order. Deterministic; runs its own one-thread device.
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

std::vector<glm::vec3> surface_points(const SubdModel& model);

// The fraction of the image's half extent the framed surface reaches (a 5 % margin on each side).
inline constexpr float kFrameFill = 0.9f;

// `direction`: unit, from the target toward the eye; `up`: unit, not along `direction`; `points`: not
// empty.
SubdCamera fit_camera(std::span<const glm::vec3> points, std::span<const glm::vec3> bounds, int width, int height,
                      float fov_degrees, glm::vec3 direction, std::optional<glm::vec3> target, glm::vec3 up,
                      float fill = kFrameFill);

}  // namespace tessera
