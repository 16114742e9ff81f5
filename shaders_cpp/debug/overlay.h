// Lines and points drawn over a rendered image, for what is not a surface: the control cage, open
// edges (cracks), bounding boxes and a view frustum.
//
// Contract: world-space segments are projected with `view_projection`, clipped to the near plane
// (clip z >= 0), and drawn anti-aliased `width` pixels wide by blending `color` over the pixel with
// its coverage times `opacity`. With `depth_test`, a pixel is drawn only where the line's depth is at
// most the framebuffer's depth plus `depth_slack` (NDC), so a line behind the surface stays hidden.
// The framebuffer's depth is not written. Pixels are visited in line order: the same lines give the
// same bytes.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "pipeline/framebuffer.h"

namespace tessera {

struct OverlayLine {
  glm::vec3 a{0.0f}, b{0.0f};
};

struct OverlayStyle {
  glm::vec3 color{0.0f};
  float width = 1.5f;
  float opacity = 1.0f;
  bool depth_test = false;
  float depth_slack = 0.0f;
};

void draw_lines(Framebuffer& fb, const glm::mat4& view_projection, std::span<const OverlayLine> lines,
                const OverlayStyle& style);
// Dots `style.width` pixels across.
void draw_points(Framebuffer& fb, const glm::mat4& view_projection, std::span<const glm::vec3> points,
                 const OverlayStyle& style);

// The 12 edges of a box, and the 12 edges of the frustum of a view-projection matrix (near and far
// rectangles and the four sides), in world space.
void box_lines(const glm::vec3& lo, const glm::vec3& hi, std::vector<OverlayLine>& out);
void frustum_lines(const glm::mat4& view_projection, std::vector<OverlayLine>& out);

}  // namespace tessera
