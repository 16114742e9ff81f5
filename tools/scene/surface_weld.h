// The weld check of a subdivision surface's stream output, its border named (weld_check.h): each
// patch's domain edges that lie on a cage edge are curves keyed by that edge, drawn once per patch that
// streams out; a point the tessellator put on such a domain edge lies on its curve. So the border is
// where fewer than two drawn patches meet: a cage boundary edge, the rim of a hole or of a face with
// no surface, and the edge of a culled patch's neighbour. The spokes of an n-gon's fan lie inside the
// face and are never border.
//
// Contract: `p` is a PatchOutput of `g`'s draw (p.patch_id indexes g.patches), as stream_surface's sink
// receives them.
#pragma once

#include <array>
#include <cstdint>

#include "tessellator/check.h"
#include "tools/verify/weld_check.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera::scene {

template <class PatchOut>
void add_surface_patch(verify::WeldChecker& weld, const PatchOut& p, const PatchGroup& g) {
  TESSERA_DCHECK_LT(p.patch_id, g.patches.size());
  const SubdPatch& patch = g.patches[p.patch_id];
  const bool tri = g.domain == ts::Domain::tri;
  // Per domain edge in SV_TessFactor order (quad: u = 0, v = 0, u = 1, v = 1; tri: u = 0, v = 0, w = 0).
  std::array<std::int64_t, 4> curve{-1, -1, -1, -1};
  for (std::size_t k = 0; k < (tri ? 3u : 4u); ++k) {
    const EdgeFactorKey& e = patch.edge_keys[k];
    if (e.a < 0 || e.b >= 0) continue;  // the base factor, or a spoke of a fan
    curve[k] = e.a;
    weld.add_curve_use(e.a);
  }
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    const float u = p.domain[i].u, v = p.domain[i].v;
    const std::array<bool, 4> on = tri ? std::array<bool, 4>{u == 0.0f, v == 0.0f, (1.0f - u) - v <= 0.0f, false}
                                       : std::array<bool, 4>{u == 0.0f, v == 0.0f, u == 1.0f, v == 1.0f};
    for (std::size_t k = 0; k < 4; ++k)
      if (on[k] && curve[k] >= 0) weld.add_curve_point(p.points[i].position, curve[k]);
  }
  verify::add_patch_triangles(weld, p);
}

}  // namespace tessera::scene
