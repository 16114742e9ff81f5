// The views of `tessera render`: their names, and drawing one (the pipeline's draws, then overlays)
// with the legend that explains it.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "shaders_cpp/debug/debug_render.h"
#include "tools/scene/view_legend.h"
#include "tools/scene/render_settings.h"
#include "tools/scene/view_options.h"

namespace tessera::scene {

struct ViewInputs {
  const SubdModel& model;
  const Displacement* displacement = nullptr;
  SubdFactors factors;  // with the LOD's per-edge factors
  PatchCull cull;       // the cull policy of the view
  ts::Partitioning partitioning = ts::Partitioning::integer;
  const ViewSetup& view;
  float edge_pixels = 8.0f;  // density's target
  bool processed = false;    // factors: processed rather than raw
};

// Whether render_view reads per-patch facts (PatchTables) for `kind`.
bool view_uses_patch_tables(ViewKind kind);

struct ViewOutput {
  DrawResult result;
  Legend legend;
  bool has_legend = false;
  std::uint64_t crack_edges = 0, border_edges = 0, nonmanifold_edges = 0;  // cracks
};

// The patch tables of the inputs' draw, measured from the view camera.
PatchTables view_patch_tables(const ViewInputs& in);

// Draws view `kind` into fb, cleared here by Device::clear (on a multisampled fb the tiles no draw
// entered may still hold the pending clear, which a resolve or Device::finish_clear writes); `tables`
// (view_patch_tables of the same inputs) is needed when view_uses_patch_tables(kind). UsageError for a
// view the inputs cannot give (the displacement view without a displacement).
ViewOutput render_view(Device& device, ViewKind kind, const ViewInputs& in, const PatchTables* tables, Framebuffer& fb);

// The patch under each pixel of view `kind` as render_view draws it (the same draw and camera; the
// culled view's overview camera), written as pick codes (debug_shaders.h) into `fb`, a single-sampled
// rgba8 target of the view's size (cleared here to 0: no patch).
DrawResult render_pick_buffer(Device& device, ViewKind kind, const ViewInputs& in, const PatchTables& tables,
                              Framebuffer& fb);
// The patch row a pick code names, or nothing for 0 or a code no row has.
const PatchInfo* picked_patch(const PatchTables& tables, std::uint32_t code, std::size_t* index = nullptr);

}  // namespace tessera::scene
