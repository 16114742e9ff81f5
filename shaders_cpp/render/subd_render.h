// Rendering a SubdModel: a camera that frames the cage, and the draws of the shaded, wireframe and
// wire-on-shaded views (the wireframe pulled toward the camera by a small depth bias).
#pragma once

#include <optional>
#include <span>

#include "pipeline/framebuffer.h"
#include "shaders_cpp/render/subd_model.h"

namespace tessera {

enum class SubdView { shaded, wireframe, wire_on_shaded };

// The background the renders and benchmarks clear to.
inline constexpr glm::vec4 kBackgroundColor{0.93f, 0.94f, 0.96f, 1.0f};

struct SubdCamera {
  glm::vec3 eye{0.0f}, target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};  // unit length; the image's up is its part across the view direction
  glm::mat4 view_projection{1.0f};
};

// Looks at the cage's bounding-box centre (or `target`) from `eye`, or from a default direction at a
// distance that frames the bounding sphere; near and far planes enclose it. fov_degrees is vertical.
// `up` (unit length) is the world's up: the default direction is the +y-up one, (0.35, 0.25, 1), turned
// by the shortest rotation that takes +y to `up` (for +z up: from -y, slightly above, as a front view).
// The caller checks that the view direction is not along `up` (the orientation would be undefined).
SubdCamera frame_cage(const Cage& cage, int width, int height, float fov_degrees, std::optional<glm::vec3> eye,
                      std::optional<glm::vec3> target, glm::vec3 up = {0.0f, 1.0f, 0.0f});
// The camera at `eye` looking at `target`, its near and far planes enclosing the box of `bounds`.
SubdCamera look_at(std::span<const glm::vec3> bounds, int width, int height, float fov_degrees, glm::vec3 eye,
                   glm::vec3 target, glm::vec3 up);
// The default eye direction of frame_cage for the world's `up` (unit length), a unit vector.
glm::vec3 default_view_direction(glm::vec3 up);

// Draws the model into fb (not cleared here); returns the first draw error, statistics summed.
DrawResult render_subd(Device& device, const SubdModel& model, const SubdFactors& factors, const PatchCull& cull,
                       ts::Partitioning partitioning, SubdView view, const SubdCamera& camera, Framebuffer& fb);

// The fixed-function state of one pass over a subdivision model: back faces culled (front faces on a
// left-handed cage; none when the model is drawn two-sided), solid or wireframe, depth less_equal (the wireframe pass
// draws over the shaded one), the whole target; and the depth bias the wireframe's domain shader pulls points forward
// by.
struct SubdPassState {
  RasterizerState rasterizer;
  DepthState depth;
  Viewport viewport;
  float z_bias = 0.0f;
};
SubdPassState subd_pass_state(const SubdModel& model, const Framebuffer& fb, bool wire);
// Its rasterizer state alone (CullMode NONE when the model is drawn two-sided).
RasterizerState subd_rasterizer(const SubdModel& model, bool wire);
// How the pixel shaders tell the surface's sides apart (two-sided drawing).
FaceSides face_sides(const SubdModel& model);
// The screen orientation (pipeline/patch_orientation.h: +1 clockwise) of the patches whose every
// triangle the solid passes cull, for their triangle_cw patterns.
int subd_culled_screen_sign(const SubdModel& model);

// One pass's draw of one patch group of the model, with the pass's fixed-function state.
template <class Hs, class Ds, class Ps>
DrawResult draw_group_pass(Device& device, const SubdModel& model, const PatchGroup& g, const TessellatorState& ts,
                           const Hs& hs, const Ds& ds, const Ps& ps, const SubdPassState& st, Framebuffer& fb) {
  const PatchDraw<glm::vec3, SubdVS, Hs, Ds, Ps> d{
      {model.vertex_buffer(), g.indices, g.control_points, model.vertex_shader(), hs, ds, ts},
      ps,
      st.rasterizer,
      st.depth,
      st.viewport};
  return device.draw(d, fb);
}

// Runs pass(wire) -> DrawResult for the passes `view` needs (the shaded pass, then the wireframe over
// it) and sums their reports, with the framebuffer's bytes; stops at the first error.
template <class Pass>
DrawResult draw_view_passes(SubdView view, const Framebuffer& fb, Pass&& pass) {
  DrawResult total;
  for (const bool wire : {false, true}) {
    if (wire ? view == SubdView::shaded : view == SubdView::wireframe) continue;
    const DrawResult r = pass(wire);
    if (!r.ok()) return r;
    add_draw_report(total.report, r.report);
  }
  total.report.memory.framebuffer_bytes = fb.bytes();
  return total;
}

}  // namespace tessera
