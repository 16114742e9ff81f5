#include "shaders_cpp/debug/debug_render.h"

namespace tessera {

PatchTables build_patch_tables(const SubdModel& model, const Displacement* displacement, const SubdFactors& factors,
                               const PatchCull& cull, ts::Partitioning partitioning, const DicingCamera& camera) {
  PatchTables tables;
  tables.combinations = analyze_combinations(*model.topology);
  const std::vector<std::int64_t> seam_keys = uv_seam_edge_keys(model.cage, *model.topology);
  for_each_surface_group(model, displacement, factors, cull, partitioning,
                         [&](const PatchGroup& g, const TessellatorState& ts, const auto& hs, const auto&) {
                           auto rows = build_patch_table(model, g, hs, ts, tables.combinations, seam_keys, camera);
                           (g.domain == ts::Domain::tri ? tables.tris : tables.quads) = std::move(rows);
                           return DrawResult{};
                         });
  return tables;
}

DrawResult render_debug(Device& device, const SubdModel& model, const Displacement* displacement,
                        const SubdFactors& factors, const PatchCull& cull, ts::Partitioning partitioning,
                        const DebugRender& view,
                        const PatchTables& tables, const SubdCamera& camera, Framebuffer& fb) {
  DrawResult total;
  for (const bool wire : {false, true}) {
    if (wire && !view.wire_pass) continue;
    const DrawResult r = for_each_surface_group(
        model, displacement, factors, cull, partitioning,
        [&](const PatchGroup& g, const TessellatorState& ts, const auto& hs, const auto& ds) {
          const SubdPassState st = subd_pass_state(model, fb, wire);
          using Ds = std::decay_t<decltype(ds)>;
          // 0.2 % of the distance to the eye: enough to win the depth test against the surface the
          // edge lies on at the depth buffer's precision, far less than any surface the edge is behind.
          const DebugDS<Ds> debug_ds{ds, camera.view_projection, camera.eye, wire ? 2e-3f : 0.0f};
          auto go = [&](const auto& ps) { return draw_group_pass(device, model, g, ts, hs, debug_ds, ps, st, fb); };
          const std::vector<PatchInfo>& rows = tables.of(g.domain);
          if (wire) return go(DebugWirePS{rows, view.ps.light, view.ps.paper, face_sides(model)});
          DebugPS ps = view.ps;
          ps.patches = rows;
          ps.sides = face_sides(model);
          return go(ps);
        });
    if (!r.ok()) return r;
    if (!wire) {
      add_draw_report(total.report, r.report);
    } else {
      // The wire pass draws the same surface again: its counts would double every count of the view
      // (triangles, pixels, patches culled); only its time and memory are the view's.
      total.report.times += r.report.times;
      total.report.memory.geometry_peak_bytes =
          std::max(total.report.memory.geometry_peak_bytes, r.report.memory.geometry_peak_bytes);
    }
  }
  total.report.memory.framebuffer_bytes = fb.bytes();
  return total;
}

}  // namespace tessera
