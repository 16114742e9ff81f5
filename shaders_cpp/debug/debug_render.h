// Drawing the debug views: the model through the debug shaders (debug_shaders.h) with per-patch facts
// (patch_table.h), and, for the wireframe views, the triangle edges over the surface.
//
// Contract: the same draws as render_subd / render_displaced (the same VS, HS and DS, so the same
// tessellation, and the same culling), with the debug pixel shader; deterministic for any thread count.
#pragma once

#include <vector>

#include "shaders_cpp/debug/debug_shaders.h"
#include "shaders_cpp/debug/patch_table.h"
#include "shaders_cpp/render/displaced_model.h"
#include "shaders_cpp/render/subd_render.h"

namespace tessera {

// The rows of both patch groups (quad domain, tri domain), for one draw's factors, and the cage's
// topology combinations they index.
struct PatchTables {
  std::vector<PatchInfo> quads, tris;
  TopologyCombinations combinations;
  const std::vector<PatchInfo>& of(ts::Domain d) const { return d == ts::Domain::tri ? tris : quads; }
  // visit(const PatchInfo&) for every row, quad domain first.
  template <class Visit>
  void for_each(Visit&& visit) const {
    for (const auto* group : {&quads, &tris})
      for (const PatchInfo& p : *group) visit(p);
  }
};
PatchTables build_patch_tables(const SubdModel& model, const Displacement* displacement, const SubdFactors& factors,
                               const PatchCull& cull, ts::Partitioning partitioning, const DicingCamera& camera);

struct DebugRender {
  DebugPS ps;              // the view and its parameters; `patches` is set per group
  bool wire_pass = false;  // draw the triangle edges over the surface
};

// Draws the view's surface pass (and its wire pass when asked). The report counts the surface once:
// a wire pass adds its time and memory, not its counts.
DrawResult render_debug(Device& device, const SubdModel& model, const Displacement* displacement,
                        const SubdFactors& factors, const PatchCull& cull, ts::Partitioning partitioning,
                        const DebugRender& view,
                        const PatchTables& tables, const SubdCamera& camera, Framebuffer& fb);

}  // namespace tessera
