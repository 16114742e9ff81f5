#include "shaders_cpp/render/displaced_render.h"

namespace tessera {
DrawResult render_displaced(Device& device, const SubdModel& model, const Displacement& displacement,
                            const SubdFactors& factors, const PatchCull& cull, ts::Partitioning partitioning,
                            SubdView view, const SubdCamera& camera, Framebuffer& fb) {
  const glm::vec3 light = glm::normalize(camera.eye - camera.target);
  auto pass = [&](bool wire) {
    const SubdPassState st = subd_pass_state(model, fb, wire);
    return with_displaced_group(
        model, displacement, factors, cull.with_depth_bias(st.z_bias), partitioning,  // the pass's depth bias
        [&](const PatchGroup& g, const TessellatorState& ts, const DisplacedHS& hs, const DisplacedDS& ds) {
          const DisplacedProjectDS<DisplacedDS> project{ds, camera.view_projection, st.z_bias};
          auto go = [&](const auto& ps) { return draw_group_pass(device, model, g, ts, hs, project, ps, st, fb); };
          if (wire) return go(ConstantPS<kDisplacedAttributes>{});
          DisplacedPS ps;
          ps.light = light;
          ps.sides = face_sides(model);
          ps.texcoords = displacement.texcoords;
          ps.seam_blending = displacement.seam_blending;
          if (!displacement.normal_maps.empty()) {
            ps.normal_maps = displacement.normal_maps;
            ps.flip_green = displacement.flip_v;
          } else if (displacement.kind == DisplacementKind::scalar) {
            ps.heights = displacement.maps;
            ps.height_scale = displacement.scale;
          }
          return go(ps);
        });
  };
  return draw_view_passes(view, fb, pass);
}

DrawResult render_surface(Device& device, const SubdModel& model, const Displacement* displacement,
                          const SubdFactors& factors, const PatchCull& cull, ts::Partitioning partitioning,
                          SubdView view, const SubdCamera& camera, Framebuffer& fb) {
  return displacement ? render_displaced(device, model, *displacement, factors, cull, partitioning, view, camera, fb)
                      : render_subd(device, model, factors, cull, partitioning, view, camera, fb);
}

}  // namespace tessera
