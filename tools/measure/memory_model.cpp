#include "tools/measure/memory_model.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "tessellator/tessellator.h"

namespace tessera::measure {
namespace {

// Triangles and interior points of one patch tessellated with every factor `level` (integer).
struct PatchCounts {
  std::uint64_t triangles = 0, interior_points = 0;
};

PatchCounts patch_counts(ts::Domain domain, int level) {
  const float f = float(level);
  ts::Pattern pattern;
  int edges = 4;
  if (domain == ts::Domain::quad) {
    ts::tessellate_quad(ts::Partitioning::integer, ts::OutputPrimitive::triangle_cw, {f, f, f, f, f, f}, pattern);
  } else {
    ts::tessellate_tri(ts::Partitioning::integer, ts::OutputPrimitive::triangle_cw, {f, f, f, f}, pattern);
    edges = 3;
  }
  // With integer partitioning every edge has exactly `level` segments: edges * level boundary points.
  return {pattern.primitive_count(), pattern.points.size() - std::uint64_t(edges) * std::uint64_t(level)};
}

double uv_polygon_area(const Cage& cage, int f) {
  const int n = cage.face_sizes[f], o = cage.face_offsets[f];
  double twice = 0.0;
  for (int k = 0; k < n; ++k) {
    const glm::vec2 a = cage.uvs[cage.face_uvs[o + k]], b = cage.uvs[cage.face_uvs[o + (k + 1) % n]];
    twice += double(a.x) * double(b.y) - double(b.x) * double(a.y);
  }
  return std::abs(twice) * 0.5;
}

std::uint64_t mip_chain_bytes(int width, int height, int first_level, int texel_bytes) {
  std::uint64_t texels = 0;
  for (int k = first_level;; ++k) {
    const std::uint64_t w = std::max(1, width >> std::min(k, 30)), h = std::max(1, height >> std::min(k, 30));
    texels += w * h;
    if (w == 1 && h == 1) break;
  }
  return texels * std::uint64_t(texel_bytes);
}

}  // namespace

MemoryTable memory_table(const Cage& cage, const Topology& topology, const SubdPatches& patches,
                         const MemoryModelOptions& options) {
  for (int level : options.levels)
    if (level < 1 || level > 64)
      throw std::invalid_argument("memory level " + std::to_string(level) + " is not in 1..64");
  if (options.mesh_vertex_bytes <= 0 || options.index_bytes <= 0 || options.texel_bytes <= 0)
    throw std::invalid_argument("memory model byte sizes must be positive");
  if (options.map && (options.map->width <= 0 || options.map->height <= 0))
    throw std::invalid_argument("memory model map size must be positive");

  MemoryTable table;
  table.cage_bytes = cage.positions.size() * sizeof(glm::vec3) + cage.uvs.size() * sizeof(glm::vec2) +
                     (cage.face_vertices.size() + cage.face_uvs.size() + 2 * cage.face_sizes.size()) * sizeof(int);
  std::uint64_t weights = 0;
  for (const StencilTable& t : patches.tables) weights += t.weights.size();
  // Precomputed patches (1-rings over 32 points): their rows over the ring, and the pre-pass's points.
  std::uint64_t precomputed = std::uint64_t(patches.precomputed_rows) * sizeof(glm::vec3);
  for (const PrecomputedPatch& p : patches.precomputed)
    precomputed += p.weights.size() * sizeof(float) + p.vertices.size() * sizeof(int);
  const std::uint64_t patch_count = patches.quads.size() + patches.tris.size();
  table.patch_bytes =
      (patches.quads.indices.size() + patches.tris.indices.size()) * sizeof(std::uint32_t) + weights * sizeof(float) +
      precomputed + patch_count * sizeof(SubdPatch) +
      options.displacement_data_bytes.value_or(cage.has_uvs() ? patch_count * 16 * sizeof(glm::vec2) : 0) +
      options.limit_surface_bytes;

  // Vertices of the mesh that do not depend on the level: one per cage vertex and distinct UV.
  std::uint64_t corner_vertices = 0;
  for (int v = 0; v < topology.vertex_count(); ++v) {
    std::set<int> uvs;
    bool used = false;
    for (int h : topology.ring(v)) {
      if (topology.is_hole(topology.face(h))) continue;
      used = true;
      if (cage.has_uvs()) uvs.insert(cage.face_uvs[h]);
    }
    // Every face around v has exactly one half-edge leaving v, whose face-varying index is its UV at v.
    corner_vertices += used ? std::max<std::uint64_t>(1, uvs.size()) : 0;
  }
  const std::vector<bool> seams = uv_seam_edges(cage, topology);
  std::uint64_t edge_copies = 0;  // vertices per unit of (L - 1) along cage edges
  for (int e = 0; e < topology.edge_count(); ++e) {
    const auto [h0, h1] = topology.edge_half_edges(e);
    const bool drawn0 = !topology.is_hole(topology.face(h0)), drawn1 = h1 >= 0 && !topology.is_hole(topology.face(h1));
    if (!drawn0 && !drawn1) continue;
    edge_copies += drawn0 && drawn1 && seams[std::size_t(e)] ? 2 : 1;
  }
  // N-gons: edges between their sub-patches (n of them) and the centre.
  std::uint64_t ngon_inner_edges = 0, ngon_centres = 0;
  for (int f = 0; f < cage.face_count(); ++f) {
    if (topology.is_hole(f)) continue;
    ++table.faces;
    if (cage.face_sizes[f] > 4) {
      ngon_inner_edges += std::uint64_t(cage.face_sizes[f]);
      ++ngon_centres;
    }
    if (cage.has_uvs()) table.uv_area += uv_polygon_area(cage, f);
  }
  const double area = cage.has_uvs() && table.uv_area > 0.0 ? table.uv_area : 1.0;

  for (int level : options.levels) {
    MemoryLevel m;
    m.level = level;
    const PatchCounts quad = patch_counts(ts::Domain::quad, level), tri = patch_counts(ts::Domain::tri, level);
    const std::uint64_t nq = patches.quads.size(), nt = patches.tris.size(), l1 = std::uint64_t(level - 1);
    m.mesh_triangles = nq * quad.triangles + nt * tri.triangles;
    m.mesh_vertices = corner_vertices + edge_copies * l1 + nq * quad.interior_points + nt * tri.interior_points +
                      ngon_inner_edges * l1 + ngon_centres;
    m.mesh_vertex_bytes = m.mesh_vertices * std::uint64_t(options.mesh_vertex_bytes);
    m.mesh_index_bytes = m.mesh_triangles * 3 * std::uint64_t(options.index_bytes);

    const double side = double(level) * std::sqrt(double(std::max(table.faces, 1)) / area);
    m.needed_map_side = int(std::clamp(std::ceil(side), 1.0, double(1 << 30)));
    if (options.map) {
      int first = 0;  // the coarsest mip level still at least needed_map_side wide
      while ((options.map->width >> (first + 1)) >= m.needed_map_side) ++first;
      m.map_width = std::max(1, options.map->width >> first);
      m.map_height = std::max(1, options.map->height >> first);
      m.map_bytes = mip_chain_bytes(options.map->width, options.map->height, first, options.texel_bytes);
    } else {
      m.map_width = m.map_height = m.needed_map_side;
      m.map_bytes = mip_chain_bytes(m.needed_map_side, m.needed_map_side, 0, options.texel_bytes);
    }
    m.tessera_bytes = table.cage_bytes + table.patch_bytes + m.map_bytes;
    table.levels.push_back(m);
  }
  return table;
}

}  // namespace tessera::measure
