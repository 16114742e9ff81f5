#include "pipeline/setup_context.h"

#include <algorithm>
#include <cmath>

namespace tessera {

SetupContext make_setup_context(const Viewport& vp, const RasterizerState& rs, int target_width, int target_height,
                                int tile_size, int samples) {
  SetupContext c;
  c.samples = samples;
  c.scale_x = vp.width * 0.5f;
  c.offset_x = vp.x + vp.width * 0.5f;
  c.scale_y = -vp.height * 0.5f;  // NDC y up, window y down
  c.offset_y = vp.y + vp.height * 0.5f;
  c.z_scale = vp.max_depth - vp.min_depth;
  c.z_offset = vp.min_depth;
  c.min_depth = std::min(vp.min_depth, vp.max_depth);
  c.max_depth = std::max(vp.min_depth, vp.max_depth);
  c.guard.gx = kGuardBandHalfExtentPixels / (vp.width * 0.5f);
  c.guard.gy = kGuardBandHalfExtentPixels / (vp.height * 0.5f);
  // Pixels whose centre lies inside the viewport rectangle [x, x + width) x [y, y + height).
  c.clip_min_x = std::max(0, static_cast<int>(std::ceil(vp.x - 0.5f)));
  c.clip_max_x = std::min(target_width, static_cast<int>(std::ceil(vp.x + vp.width - 0.5f))) - 1;
  c.clip_min_y = std::max(0, static_cast<int>(std::ceil(vp.y - 0.5f)));
  c.clip_max_y = std::min(target_height, static_cast<int>(std::ceil(vp.y + vp.height - 0.5f))) - 1;
  if (rs.scissor) {
    c.clip_min_x = std::max(c.clip_min_x, rs.scissor->left);
    c.clip_max_x = std::min(c.clip_max_x, rs.scissor->right - 1);
    c.clip_min_y = std::max(c.clip_min_y, rs.scissor->top);
    c.clip_max_y = std::min(c.clip_max_y, rs.scissor->bottom - 1);
  }
  c.cull = rs.cull;
  c.front_ccw = rs.front_counter_clockwise;
  c.fill = rs.fill;
  c.tiles.set_tile_size(tile_size);
  c.tiles.columns = (target_width + tile_size - 1) / tile_size;
  c.tiles.rows = (target_height + tile_size - 1) / tile_size;
  return c;
}

}  // namespace tessera
