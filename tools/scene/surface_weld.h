// The weld check of a subdivision surface's stream output, its border named (weld_check.h): each
// patch's domain edges that lie on a cage edge are curves keyed by that edge, drawn once per patch that
// streams out; a point the tessellator put on such a domain edge lies on its curve. So the border is
// where fewer than two drawn patches meet: a cage boundary edge, the rim of a hole or of a face with
// no surface, and the edge of a culled patch's neighbour. The spokes of an n-gon's fan lie inside the
// face and are never border.
//
// A non-manifold cage is drawn split (non_manifold.h): each face on a non-manifold edge of the file has
// its own copy of that edge, so the copies would be curves of one patch each. WeldCurves keys them by the
// file's edge instead, as one fin (weld_check.h) drawn by every face on it: the welded edges there are the
// cage's own non-manifold edges, and a face that leaves one out shows as a crack.
//
// Contract: `p` is a PatchOutput of `g`'s draw (p.patch_id indexes g.patches), as stream_surface's sink
// receives them; `curves` is weld_curves() of the drawn model's cage and topology.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "tessellator/check.h"
#include "tools/verify/weld_check.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera::scene {

// The weld curve of a cage edge key (cage_edge_key of the drawn cage's vertices): the key of the file's
// edge it copies; and the fins, the file's edges the split drew more than once. A cage the reader did
// not split has no source (every edge its own curve) and no fins.
struct WeldCurves {
  std::vector<int> source;         // Cage::vertex_source
  std::vector<std::int64_t> fins;  // sorted curve keys
  std::int64_t curve(std::int64_t edge_key) const {
    if (source.empty()) return edge_key;
    const auto lo = std::size_t(edge_key >> 32), hi = std::size_t((edge_key >> 1) & 0x7fffffff);
    return cage_edge_key(source[lo], source[hi]);
  }
  bool fin(std::int64_t curve_key) const { return std::binary_search(fins.begin(), fins.end(), curve_key); }
};
WeldCurves weld_curves(const Cage& cage, const Topology& topology);

template <class PatchOut>
void add_surface_patch(verify::WeldChecker& weld, const PatchOut& p, const PatchGroup& g, const WeldCurves& curves) {
  TESSERA_DCHECK_LT(p.patch_id, g.patches.size());
  const SubdPatch& patch = g.patches[p.patch_id];
  const bool tri = g.domain == ts::Domain::tri;
  // Per domain edge in SV_TessFactor order (quad: u = 0, v = 0, u = 1, v = 1; tri: u = 0, v = 0, w = 0).
  std::array<std::int64_t, 4> curve{-1, -1, -1, -1};
  for (std::size_t k = 0; k < (tri ? 3u : 4u); ++k) {
    const EdgeFactorKey& e = patch.edge_keys[k];
    if (e.a < 0 || e.b >= 0) continue;  // the base factor, or a spoke of a fan
    curve[k] = curves.curve(e.a);
    weld.add_curve_use(curve[k]);
    if (curves.fin(curve[k])) weld.add_fin(curve[k]);
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
