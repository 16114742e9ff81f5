// Per-patch statistics for --stats (render, tessellate): a row per patch (face, kind, type,
// combination, raw and processed factors, segments, triangles, screen size, cull reason),
// histograms of the edge factors and of the screen area of every triangle, and totals.
//
// The rows come from the patch table (a replay of the draw's VS and HS); the triangle areas from one
// stream pass of the same draw (IA..DS), projected with the view camera: the exact area of each
// triangle in pixels, before clipping (triangles with a vertex behind the eye are counted apart).
#pragma once

#include "tools/scene/json_output.h"
#include "tools/scene/render_views.h"

namespace tessera::scene {

// The row --stats writes for a patch: domain, id (its index in the group), face, kind, type,
// combination, raw and processed factors, segments, triangles, screen size, cull reason.
Json patch_row(const PatchInfo& p, std::size_t id);

// `tables`: view_patch_tables(in).
void add_patch_statistics(Json& stats, Device& device, const ViewInputs& in, const PatchTables& tables,
                          const LodResult& lod);

}  // namespace tessera::scene
