// Baking maps from a dense mesh onto a cage's base surface: vector or scalar displacement, a
// tangent-space normal map and ambient occlusion, texel by texel in the cage's UV layout.
//
// Per texel covered by a chart (texel_sites.h), the base point and frames come from BaseSurface (the
// renderer's evaluation), and the dense surface's point is found by
// - dual parameterisation (parameter_locator.h): the dense mesh at the texel's (face, u, v);
// - ray casting (ray_caster.h): a hit along the base normal, both ways, within max_distance (the nearest,
//   or the outward one first: RayPreference).
// The values are what the renderer inverts (displaced_shaders.h), so the map re-renders at scale 1 and
// bias 0: vector displacement is the difference d = dense − base, in object space as is or in tangent
// space as (d·T, d·B, d·N); scalar displacement is d·N (the distance along the normal, for ray casting
// exactly the hit's). The normal map holds the dense surface's normal (its vertex normals interpolated)
// in the shading frame, as (n + 1) / 2 with green along −V when `flip_green` (the renderer's default).
// Ambient occlusion is the fraction of `ao_rays` cosine-distributed rays from the dense point that
// escape within `ao_distance` (a fixed Hammersley set, turned per texel by a hash of its coordinates).
//
// Texels no chart covers, and covered texels whose dense point was not found (a ray's miss, a face the
// dense mesh lacks), are padded from their neighbours (chart_padding.h), so bilinear taps and mip
// levels across a chart's edge read continuations.
//
// Contract: deterministic — every texel is computed on its own from immutable data, so the maps are the
// same bits for any thread count; progress(fraction) is called on the calling thread between batches of
// rows. Throws BakeError for a dense mesh without a parameterisation under `dual`.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "shaders_cpp/bake/base_surface.h"
#include "shaders_cpp/bake/dense_mesh.h"
#include "shaders_cpp/bake/ray_caster.h"
#include "shaders_cpp/render/displaced_model.h"

namespace tessera {

enum class BakeMethod : std::uint8_t { dual, raycast };
enum class BakeKind : std::uint8_t { vector, scalar };

struct BakeOptions {
  int width = 1024, height = 1024;
  BakeMethod method = BakeMethod::dual;
  BakeKind kind = BakeKind::vector;
  DisplacementSpace space = DisplacementSpace::tangent;  // vector only
  float max_distance = 0.0f;                             // ray casting: how far along the normal to look (> 0)
  RayPreference preference = RayPreference::nearest;
  bool normal_map = false;
  bool flip_green = true;
  bool ao = false;
  int ao_rays = 64;
  float ao_distance = 0.0f;  // > 0 when ao
};

struct BakedMaps {
  int width = 0, height = 0;
  int displacement_channels = 0;     // 3 (vector) or 1 (scalar)
  std::vector<float> displacement;   // row-major, displacement_channels per texel
  std::vector<float> normal;         // 3 per texel, encoded; empty unless asked for
  std::vector<float> ao;             // 1 per texel; empty unless asked for
  std::uint64_t texels_covered = 0;  // texels some chart covers
  std::uint64_t texels_missed = 0;   // covered texels whose dense point was not found (padded)
  std::uint64_t texels_padded = 0;   // all texels filled from neighbours (uncovered + missed)
  double max_displacement = 0.0;     // the largest |d| baked (a vector's length)
};

// Throws BakeError when `dense` cannot be baked by `options` (dual parameterisation without the
// parameterisation on the mesh); bake_maps calls it first.
void check_bake_inputs(const DenseMesh& dense, const BakeOptions& options);

BakedMaps bake_maps(const SubdModel& model, std::span<const PatchTexcoords> texcoords, const DenseMesh& dense,
                    const BakeOptions& options, const std::function<void(double)>& progress = {});

}  // namespace tessera
