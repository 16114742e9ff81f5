#include "shaders_cpp/render/subd_render.h"

#include "pipeline/patch_orientation.h"
#include "shaders_cpp/cage/bounding_box.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace tessera {

glm::vec3 default_view_direction(glm::vec3 up) {
  const glm::vec3 y_up = glm::normalize(glm::vec3(0.35f, 0.25f, 1.0f));
  const glm::vec3 y(0.0f, 1.0f, 0.0f);
  const float c = glm::dot(y, up);
  if (c > 0.9999f) return y_up;
  // Rotating +y onto -y has no single shortest arc: half a turn about z (x and y change sign).
  if (c < -0.9999f) return {-y_up.x, -y_up.y, y_up.z};
  // Rodrigues' rotation about y x up by the angle between them, in double (then one rounding).
  const glm::dvec3 axis = glm::normalize(glm::cross(glm::dvec3(y), glm::dvec3(up)));
  const double cos_a = double(c), sin_a = std::sqrt(std::max(0.0, 1.0 - cos_a * cos_a));
  const glm::dvec3 v(y_up);
  const glm::dvec3 r = v * cos_a + glm::cross(axis, v) * sin_a + axis * glm::dot(axis, v) * (1.0 - cos_a);
  return glm::vec3(glm::normalize(r));
}

// The smallest bounding radius a camera frames: a cage of one point still gets a finite view.
constexpr float kMinFramedRadius = 1e-6f;

SubdCamera look_at(std::span<const glm::vec3> bounds, int width, int height, float fov_degrees, glm::vec3 eye,
                   glm::vec3 target, glm::vec3 up) {
  const Box3 box = bounding_box(bounds);
  const glm::vec3 centre = box.centre();
  const float radius = std::max(kMinFramedRadius, 0.5f * glm::length(box.hi - box.lo));
  SubdCamera c;
  c.eye = eye;
  c.target = target;
  c.up = up;
  const float distance = glm::length(c.eye - c.target);
  const float reach = distance + glm::length(centre - c.target) + radius;
  const glm::mat4 view = glm::lookAtRH(c.eye, c.target, up);
  const glm::mat4 proj = glm::perspectiveRH_ZO(glm::radians(fov_degrees), float(width) / float(height),
                                               std::max(reach * 1e-4f, distance - reach), reach * 1.01f);
  c.view_projection = proj * view;
  return c;
}

SubdCamera frame_cage(const Cage& cage, int width, int height, float fov_degrees, std::optional<glm::vec3> eye,
                      std::optional<glm::vec3> target, glm::vec3 up) {
  const Box3 box = bounding_box(cage.positions);
  const glm::vec3 centre = box.centre();
  const float radius = std::max(kMinFramedRadius, 0.5f * glm::length(box.hi - box.lo));
  const float aspect = float(width) / float(height);
  const float fov = glm::radians(fov_degrees);
  const float fit = std::min(fov, 2.0f * std::atan(std::tan(0.5f * fov) * aspect));
  const glm::vec3 aim = target.value_or(centre);
  // The limit surface lies well inside the cage's bounding sphere: frame 80 % of it.
  const glm::vec3 from = eye.value_or(centre + default_view_direction(up) * (radius / std::tan(0.5f * fit) * 0.8f));
  return look_at(cage.positions, width, height, fov_degrees, from, aim, up);
}

RasterizerState subd_rasterizer(const SubdModel& model, bool wire) {
  RasterizerState r;
  r.cull = model.two_sided ? CullMode::none : model.cage.tags.left_handed ? CullMode::front : CullMode::back;
  // Patches emit triangle_cw: counter-clockwise seen from outside a counter-clockwise cage, which
  // after the viewport's y flip is counter-clockwise on screen.
  r.front_counter_clockwise = true;
  if (wire) r.fill = FillMode::wireframe;
  return r;
}

FaceSides face_sides(const SubdModel& model) { return {model.two_sided, !model.cage.tags.left_handed}; }

int subd_culled_screen_sign(const SubdModel& model) {
  const RasterizerState state = subd_rasterizer(model, false);
  SetupContext c;
  c.cull = state.cull;
  c.front_ccw = state.front_counter_clockwise;
  return rasterizer_culls(c, 1) ? 1 : rasterizer_culls(c, -1) ? -1 : 0;
}

SubdPassState subd_pass_state(const SubdModel& model, const Framebuffer& fb, bool wire) {
  SubdPassState st;
  st.rasterizer = subd_rasterizer(model, wire);
  st.depth.func = CompareFunc::less_equal;
  st.viewport = Viewport{0, 0, float(fb.width()), float(fb.height()), 0, 1};
  st.z_bias = wire ? 2e-4f : 0.0f;
  return st;
}

DrawResult render_subd(Device& device, const SubdModel& model, const SubdFactors& factors, const PatchCull& cull,
                       ts::Partitioning partitioning, SubdView view, const SubdCamera& camera, Framebuffer& fb) {
  const glm::vec3 light = glm::normalize(camera.eye - camera.target);
  auto pass = [&](bool wire) {
    const SubdPassState st = subd_pass_state(model, fb, wire);
    return for_each_patch_group(
        model, factors, cull.with_depth_bias(st.z_bias), partitioning,  // the tests see the pass's depth bias
        [&](const PatchGroup& g, const TessellatorState& ts, const SubdHS& hs, const SubdDS& ds) {
          const ProjectDS<SubdDS> project{ds, camera.view_projection, st.z_bias};
          auto go = [&](const auto& ps) { return draw_group_pass(device, model, g, ts, hs, project, ps, st, fb); };
          return wire ? go(ConstantPS<>{}) : go(ClayPS{light, kClayColor, face_sides(model)});
        });
  };
  return draw_view_passes(view, fb, pass);
}

}  // namespace tessera
