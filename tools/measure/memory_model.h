// The talk's memory comparison, made explicit: at tessellation level L, the bytes of the equivalent
// pre-tessellated triangle mesh against the bytes Tessera keeps to draw the same surface (the cage,
// its patch data, and a displacement map at the resolution that level needs).
//
// The model (every assumption is a field or stated here, so the table can be regenerated and argued):
// - Level L means integer partitioning with every edge and inside factor L. Each patch (quad, triangle,
//   or the sub-patches of an n-gon, as build_patches lays them out) tessellates as the D3D11 tessellator
//   does at that factor; its triangles and its interior points are counted from the real pattern.
// - The pre-tessellated mesh shares vertices wherever the surface and its UVs are continuous, as an
//   indexed mesh exported from a modeller would: one vertex per cage vertex and UV (a vertex on a UV seam
//   is stored once per distinct UV around it), L−1 per cage edge (twice on a seam edge), and the
//   interior points of every patch; points inside an n-gon on edges between its sub-patches are shared by
//   them (the n-gon's n inner edges and its centre). Each vertex is `mesh_vertex_bytes` (default 32:
//   float3 position, float3 normal, float2 UV); each triangle is 3 indices of `index_bytes` (default 4).
// - Tessera keeps the cage (positions, UVs, face and face-UV index lists), its patches (IA index
//   buffer, stencil tables, per-patch records, precomputed patches' rows and pre-pass points (1-rings
//   over 32), and the displacement's per-patch data: its watertight
//   texture coordinates and owner frames as built, or 16 texture coordinates per patch when not given),
//   and the displacement map.
// - The map a level needs holds one texel per generated vertex over the cage's UV area: a square atlas
//   of side R_L = ceil(L * sqrt(faces / UV area)) (not rounded to a power of two, which would charge the
//   map up to 4x the texels it needs; its mip chain halves with floor, as OpenImageIO's). Given a real map, Tessera
//   keeps the smallest level of its mip chain at least that wide (never more than the map itself has)
//   and every coarser level; without one, a square map of side R_L with its mip chain. Texels are
//   `texel_bytes` each (default 4: one float, how Tessera samples a scalar map).
// - Not counted on either side: normal or colour maps (both would need them), textures' and vectors'
//   allocation slack, and the framebuffer.
//
// Contract: pure; O(faces + edges + vertices) plus one pattern per distinct (domain, level).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/subdiv/subd_patches.h"
#include "shaders_cpp/cage/topology.h"

namespace tessera::measure {

// A displacement map's size as stored (mip level 0).
struct MapSize {
  int width = 0, height = 0;
};

struct MemoryModelOptions {
  std::vector<int> levels{8, 16, 32, 64};  // each 1..64 (the tessellator's maximum factor)
  int mesh_vertex_bytes = 32;
  int index_bytes = 4;
  int texel_bytes = 4;
  std::optional<MapSize> map;  // the real map; none: a map of exactly the resolution each level needs
  // The per-patch data displacement adds (watertight UVs, owner frames: displaced_model.h), as the
  // caller measured it; none: Castaño's 16 texture coordinates per patch.
  std::optional<std::uint64_t> displacement_data_bytes;
  // exact and adaptive: the limit surface's precomputed data (LimitSurface::memory_bytes: Bfr's patch
  // points, or Far's patch table and points; the ownership tables), as the caller measured it.
  std::uint64_t limit_surface_bytes = 0;
};

struct MemoryLevel {
  int level = 0;
  // The equivalent pre-tessellated mesh.
  std::uint64_t mesh_vertices = 0, mesh_triangles = 0;
  std::uint64_t mesh_vertex_bytes = 0, mesh_index_bytes = 0;
  // What Tessera keeps.
  int needed_map_side = 0;            // R_L, before any cap by the real map
  int map_width = 0, map_height = 0;  // the finest mip level kept
  std::uint64_t map_bytes = 0;        // that level and all coarser ones
  std::uint64_t tessera_bytes = 0;    // cage + patches + map
  std::uint64_t mesh_bytes() const { return mesh_vertex_bytes + mesh_index_bytes; }
  double ratio() const { return tessera_bytes ? double(mesh_bytes()) / double(tessera_bytes) : 0.0; }
};

struct MemoryTable {
  // Independent of the level.
  std::uint64_t cage_bytes = 0;   // positions, UVs, face and face-UV indices
  std::uint64_t patch_bytes = 0;  // IA indices, stencil tables, patch records, displacement data, limit surface
  double uv_area = 0.0;           // sum of the faces' areas in UV space (0 without UVs: unit area per face)
  int faces = 0;                  // non-hole faces
  std::vector<MemoryLevel> levels;
};

// Throws std::invalid_argument for a level outside 1..64 or non-positive byte sizes or map sides.
MemoryTable memory_table(const Cage& cage, const Topology& topology, const SubdPatches& patches,
                         const MemoryModelOptions& options);

}  // namespace tessera::measure
