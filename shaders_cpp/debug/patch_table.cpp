#include "shaders_cpp/debug/patch_table.h"

#include <algorithm>
#include <cmath>

#include "shaders_cpp/cage/bounding_box.h"
#include "shaders_cpp/render/subd_render.h"
#include "tessellator/pattern_shape.h"

namespace tessera {

const char* to_string(PatchType t) {
  switch (t) {
    case PatchType::regular: return "regular";
    case PatchType::regular_boundary: return "regular boundary";
    case PatchType::irregular: return "irregular";
    case PatchType::boundary: return "boundary";
    case PatchType::triangle: return "triangle";
    case PatchType::ngon_fan: return "n-gon fan";
    case PatchType::polar: return "polar triangle";
  }
  return "?";
}

std::vector<std::int64_t> uv_seam_edge_keys(const Cage& cage, const Topology& topology) {
  std::vector<std::int64_t> keys;
  if (!cage.has_uvs()) return keys;
  const std::vector<bool> seams = uv_seam_edges(cage, topology);
  for (int e = 0; e < topology.edge_count(); ++e) {
    if (!seams[std::size_t(e)]) continue;
    const int h = topology.edge_half_edges(e)[0];
    keys.push_back(cage_edge_key(topology.origin(h), topology.destination(h)));
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

namespace detail {

PatchType patch_type(const SubdPatch& p, const Topology& t, const TopologyCombinations& combos, bool tri) {
  if (t.face_size(p.face) > 4) return PatchType::ngon_fan;
  if (p.kind == PatchKind::polar_triangle) return PatchType::polar;
  if (tri) return PatchType::triangle;
  const int c =
      std::size_t(p.face) < combos.face_combination.size() ? combos.face_combination[std::size_t(p.face)] : -1;
  if (c < 0) return PatchType::irregular;
  switch (combos.combinations[std::size_t(c)].patch_class) {
    case PatchClass::regular: return PatchType::regular;
    case PatchClass::regular_boundary: return PatchType::regular_boundary;
    case PatchClass::boundary: return PatchType::boundary;
    default: return PatchType::irregular;
  }
}

void finish_patch_info(PatchInfo& info, const SubdModel& m, const SubdPatch& patch, const TessFactors& raw,
                       std::span<const glm::vec3> hull, const TessellatorState& ts_state, const DicingCamera& camera,
                       const std::vector<std::int64_t>& seam_keys) {
  info.face = patch.face;
  info.sub = patch.sub;
  info.kind = patch.kind;
  info.tri = ts_state.domain == ts::Domain::tri;
  info.raw = raw;
  const ts::ProcessedFactors pf = ts::process_factors(ts_state.partitioning, detail::factor_set(ts_state.domain, raw));
  const int edges = info.tri ? 3 : 4, insides = info.tri ? 1 : 2;
  int most = 1;
  for (int k = 0; k < edges; ++k) {
    info.edge_processed[std::size_t(k)] = float(pf.outside[std::size_t(k)].factor) / 65536.0f;
    info.edge_segments[std::size_t(k)] = std::max(1, pf.outside[std::size_t(k)].num_points - 1);
    most = std::max(most, info.edge_segments[std::size_t(k)]);
  }
  for (int k = 0; k < insides; ++k) {
    info.inside_processed[std::size_t(k)] = float(pf.inside[std::size_t(k)].factor) / 65536.0f;
    info.inside_segments[std::size_t(k)] = std::max(1, pf.inside[std::size_t(k)].num_points - 1);
    most = std::max(most, info.inside_segments[std::size_t(k)]);
  }
  info.triangles = info.culled ? 0u : std::uint32_t(ts::primitive_count(pf, ts_state.output));
  // The hull's bounding sphere (box centre, farthest point), projected as an edge's LOD sphere is.
  const Box3 b = bounding_box(hull);
  info.bound = b;
  const glm::vec3 centre = b.centre();
  float radius = 0.0f;
  for (const glm::vec3& p : hull) radius = std::max(radius, glm::length(p - centre));
  info.screen_pixels = projected_diameter(centre, radius, camera);
  info.pixels_per_segment = info.screen_pixels / float(most);
  for (int k = 0; k < edges; ++k) {
    const EdgeFactorKey& key = patch.edge_keys[std::size_t(k)];
    if (key.b < 0 && key.a >= 0 && std::binary_search(seam_keys.begin(), seam_keys.end(), key.a))
      info.seam_edges = std::uint8_t(info.seam_edges | (1u << k));
  }
  // Texture coordinates of the face frame's corners (the uv view interpolates them).
  const Cage& c = m.cage;
  if (c.has_uvs()) {
    const int n = c.face_sizes[std::size_t(patch.face)];
    auto uv = [&](int k) {
      return c.uvs[std::size_t(c.face_uvs[std::size_t(c.face_offsets[std::size_t(patch.face)] + (k % n))])];
    };
    if (n <= 4) {
      for (int k = 0; k < n; ++k) info.corner_uv[std::size_t(k)] = uv(k);
    } else {
      glm::vec2 centre_uv(0.0f);
      for (int k = 0; k < n; ++k) centre_uv += uv(k);
      info.corner_uv = {uv(patch.sub), uv(patch.sub + 1), centre_uv / float(n), glm::vec2(0.0f)};
    }
  }
}

bool proven_facing_away(const SubdModel& m, const OrientationBound& bound, const TessFactors& raw,
                        const TessellatorState& ts_state) {
  if (!bound.may_hold()) return false;
  ts::Pattern pattern;
  ts::generate(ts::process_factors(ts_state.partitioning, detail::factor_set(ts_state.domain, raw)), ts_state.output,
               pattern);
  const ts::PatternShape shape = ts::pattern_shape(pattern);
  const int culled = subd_culled_screen_sign(m);
  return bound.holds(shape) && culled != 0 && pattern_screen_sign(bound, shape) == culled;
}

}  // namespace detail
}  // namespace tessera
