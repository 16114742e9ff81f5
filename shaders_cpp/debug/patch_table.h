// Per-patch facts for the debug views and statistics: what each patch is (face, kind, type,
// topology combination), the factors its hull shader gave (raw, as SV_TessFactor) and what the
// tessellator made of them (processed: clamped and rounded by the partitioning), its triangles, its
// size on screen and whether it was culled.
//
// Contract: build_patch_table replays the draw's own VS and HS (the same functors, the same inputs) on
// the calling thread, so its factors are the bits the draw uses; it tessellates nothing (triangle
// counts come from ts::primitive_count). Rows are in patch order within the group, as SV_PrimitiveID.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/stage_io.h"
#include "shaders_cpp/cage/topology_combinations.h"
#include "shaders_cpp/lod/edge_lod.h"
#include "shaders_cpp/lod/frustum_cull.h"
#include "shaders_cpp/render/subd_model.h"
#include "tessellator/tessellator.h"

namespace tessera {

// What kind of surface a patch is, as the patch-type view colours it.
enum class PatchType : std::uint8_t { regular, regular_boundary, irregular, boundary, triangle, ngon_fan, polar };
inline constexpr int kPatchTypeCount = 7;
const char* to_string(PatchType t);

struct PatchInfo {
  int face = 0, sub = 0;
  PatchKind kind = PatchKind::gregory;
  PatchType type = PatchType::regular;
  int combination = -1;                   // TopologyCombinations index (-1: none)
  bool tri = false;                       // on the tri domain
  bool culled = false;                    // the hull shader gave it zero factors (outside the view)
  bool faces_away = false;                // not culled, but proven to face away: skipped before its DS
  TessFactors raw;                        // what the hull shader would give without culling
  std::array<float, 4> edge_processed{};  // after the partitioning's clamp and rounding
  std::array<float, 2> inside_processed{};
  std::array<int, 4> edge_segments{};
  std::array<int, 2> inside_segments{};
  std::uint32_t triangles = 0;           // what the tessellator makes of its factors: 0 when culled
  float screen_pixels = 0.0f;            // projected diameter of the hull's bounding sphere (edge_lod.h)
  float pixels_per_segment = 0;          // screen_pixels over the patch's largest segment count
  std::uint8_t seam_edges = 0;           // bit k: domain edge k (SV_TessFactor order) lies on a UV seam
  std::array<glm::vec2, 4> corner_uv{};  // the face frame's corners (fan: corner k, k+1, centre)
  Box3 bound;                            // box of the hull the frustum test uses
};

// The cage edge keys of the UV seam edges, sorted (for PatchInfo::seam_edges).
std::vector<std::int64_t> uv_seam_edge_keys(const Cage& cage, const Topology& topology);

// The rows of one patch group, for the draw's HS over the model's cage; `seam_keys` from
// uv_seam_edge_keys.
template <class Hs>
std::vector<PatchInfo> build_patch_table(const SubdModel& m, const PatchGroup& g, const Hs& hs,
                                         const TessellatorState& ts_state, const TopologyCombinations& combos,
                                         const std::vector<std::int64_t>& seam_keys, const DicingCamera& camera);

namespace detail {
PatchType patch_type(const SubdPatch& p, const Topology& t, const TopologyCombinations& combos, bool tri);
void finish_patch_info(PatchInfo& info, const SubdModel& m, const SubdPatch& patch, const TessFactors& raw,
                       std::span<const glm::vec3> hull, const TessellatorState& ts_state, const DicingCamera& camera,
                       const std::vector<std::int64_t>& seam_keys);
// Whether a draw of the model skips the patch as facing away (pipeline/patch_orientation.h), for the
// pattern of its factors and the rasterizer state the model's passes use (subd_render.h).
bool proven_facing_away(const SubdModel& m, const OrientationBound& bound, const TessFactors& raw,
                        const TessellatorState& ts_state);
}  // namespace detail

template <class Hs>
std::vector<PatchInfo> build_patch_table(const SubdModel& m, const PatchGroup& g, const Hs& hs,
                                         const TessellatorState& ts_state, const TopologyCombinations& combos,
                                         const std::vector<std::int64_t>& seam_keys, const DicingCamera& camera) {
  const SubdVS vs = m.vertex_shader();
  const SubdHS& base = [&]() -> const SubdHS& {
    if constexpr (requires { hs.base; })
      return hs.base;
    else
      return hs;
  }();
  std::vector<PatchInfo> rows(g.patches.size());
  std::vector<SubdVertex> in(std::size_t(g.control_points));
  std::vector<SubdControlPoint> out(
      static_cast<std::size_t>(Hs::kOutputControlPoints));  // (not a declaration for clang)
  std::vector<glm::vec3> hull;
  for (std::size_t p = 0; p < g.patches.size(); ++p) {
    const SubdPatch& patch = g.patches[p];
    for (std::size_t i = 0; i < in.size(); ++i) {
      const std::uint32_t v = g.indices[p * in.size() + i];
      in[i] = vs(m.vertex_buffer()[v], v);
    }
    for (int i = 0; i < Hs::kOutputControlPoints; ++i) out[std::size_t(i)] = hs.control_point(in, i, std::uint32_t(p));
    PatchInfo& info = rows[p];
    info.culled = base.outside_view(patch, out);
    hull.clear();
    for (int i = 0; i < base.hull_size(patch); ++i) hull.push_back(base.hull_point(patch, out, i));
    info.combination = std::size_t(patch.face) < combos.face_combination.size()
                           ? combos.face_combination[std::size_t(patch.face)]
                           : -1;
    info.type = detail::patch_type(patch, *m.topology, combos, g.domain == ts::Domain::tri);
    const TessFactors raw = base.edge_and_inside_factors(patch);
    detail::finish_patch_info(info, m, patch, raw, hull, ts_state, camera, seam_keys);
    info.faces_away =
        !info.culled && detail::proven_facing_away(m, base.orientation_bound(patch, out, raw), raw, ts_state);
  }
  return rows;
}

}  // namespace tessera
