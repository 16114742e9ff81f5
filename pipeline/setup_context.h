// What setup needs to know about a draw (viewport transform, guard band, the writable pixel rectangle,
// culling, fill mode, tile grid), computed once per draw by make_setup_context.
#pragma once

#include "pipeline/clipper.h"
#include "pipeline/pipeline_state.h"
#include "pipeline/tile_bins.h"

namespace tessera {

// What setup needs to know about the draw, computed once.
struct SetupContext {
  // Viewport transform: window = ndc * scale + offset (y flipped: D3D's y-down window space).
  float scale_x = 0, offset_x = 0, scale_y = 0, offset_y = 0, z_scale = 1, z_offset = 0;
  float min_depth = 0, max_depth = 1;
  GuardBand guard;
  // Pixels that may be written: viewport, scissor and render target intersected (inclusive).
  int clip_min_x = 0, clip_min_y = 0, clip_max_x = -1, clip_max_y = -1;
  CullMode cull = CullMode::back;
  bool front_ccw = false;
  FillMode fill = FillMode::solid;
  TileGrid tiles;
  // The render target's samples per pixel: above 1, triangles keep the boxes of their samples and
  // their vertices (raster_tile.h tests each sample), not those of their pixel centres.
  int samples = 1;
};

SetupContext make_setup_context(const Viewport& vp, const RasterizerState& rs, int target_width, int target_height,
                                int tile_size, int samples = 1);

}  // namespace tessera
