#include "displaced_render.h"

namespace tessera {
namespace {

struct WirePS {
  glm::vec4 color{0.2f, 0.25f, 0.35f, 1.0f};
  glm::vec4 operator()(const PixelInput<kDisplacedAttributes>&) const { return color; }
};

}  // namespace

DrawResult render_displaced(Device& device, const SubdModel& model, const Displacement& displacement,
                            const SubdFactors& factors, ts::Partitioning partitioning, SubdView view,
                            const SubdCamera& camera, Framebuffer& fb) {
  const glm::vec3 light = glm::normalize(camera.eye - camera.target);
  auto pass = [&](bool wire) {
    return with_displaced_group(model, displacement, factors, partitioning,
                                [&](const PatchGroup& g, const TessellatorState& ts, const DisplacedHS& hs,
                                    const DisplacedDS& ds) {
      RasterizerState rs;
      rs.cull = model.cage.tags.left_handed ? CullMode::front : CullMode::back;
      rs.front_counter_clockwise = true;  // as render_subd
      if (wire) rs.fill = FillMode::wireframe;
      DepthState depth;
      depth.func = CompareFunc::less_equal;
      const Viewport viewport{0, 0, float(fb.width()), float(fb.height()), 0, 1};
      const DisplacedProjectDS<DisplacedDS> project{ds, camera.view_projection, wire ? 2e-4f : 0.0f};
      auto go = [&](const auto& ps) {
        using Ps = std::decay_t<decltype(ps)>;
        const PatchDraw<glm::vec3, SubdVS, DisplacedHS, DisplacedProjectDS<DisplacedDS>, Ps> d{
            model.cage.positions, g.indices, g.control_points, SubdVS{}, hs, project, ps, ts, rs, depth, viewport};
        return device.draw(d, fb);
      };
      if (wire) return go(WirePS{});
      DisplacedPS ps;
      ps.light = light;
      if (displacement.normal_map) {
        ps.normal_map = &displacement.normal_map->texture();
        ps.flip_green = displacement.flip_v;
      } else if (displacement.kind == DisplacementKind::scalar) {
        ps.height = &displacement.map->texture();
        ps.height_scale = displacement.scale;
      }
      return go(ps);
    });
  };
  return draw_view_passes(view, fb, pass);
}

}  // namespace tessera
