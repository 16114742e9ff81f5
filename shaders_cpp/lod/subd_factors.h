// The hull shader's two inputs, the factor table (SubdFactors) and the cull policy (PatchCull,
// patch_cull.h), and the policy that builds them from a user's settings: the ranges of a uniform
// factor and its variation, per-edge factors read from a file, view-dependent edge LOD (edge_lod.h),
// and patch culling (frustum_cull.h, back_patch_cull.h). The scene library,
// the benchmarks and the bindings all come through here, so a setting means one thing everywhere.
//
// Errors: a value out of its range is a FactorSettingError (the caller's usage: the message names the
// option). Reading a factors file is the scene library's (tools/scene/model_options.h).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <glm/glm.hpp>

#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/lod/edge_lod.h"
#include "shaders_cpp/lod/patch_cull.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera {

// Tessellation factors as a pure function of cage edge keys (subd_patches.h), so the two patches on
// an edge always agree. `vary` > 0 spreads factors over [factor, factor * (1 + vary)] by a hash of the
// key (to test edges whose factors differ); inside factors average the edges of each direction.
// `per_edge` (a --factors-per-edge file, or the view-dependent LOD of lod/edge_lod.h) overrides both
// for the edges it lists.
struct SubdFactors {
  float factor = 8.0f;
  float vary = 0.0f;
  std::shared_ptr<const std::unordered_map<std::int64_t, float>> per_edge;  // by cage_edge_key
  // The factor of one cage edge (the base factor for key -1).
  float edge(std::int64_t key) const {
    if (key >= 0 && per_edge) {
      const auto it = per_edge->find(key);
      if (it != per_edge->end()) return it->second;
    }
    if (vary <= 0.0f || key < 0) return factor;
    std::uint64_t x = std::uint64_t(key) * 0x9E3779B97F4A7C15ull;
    x ^= x >> 29;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 32;
    const float r = float(x % 1000u) / 999.0f;
    return factor * (1.0f + vary * r);
  }
  // A domain edge's factor: its cage edge's, or for a spoke the mean of the two cage edges beside it.
  float edge(const EdgeFactorKey& key) const {
    if (key.b < 0) return edge(key.a);
    return 0.5f * (edge(key.a) + edge(key.b));
  }
};

struct FactorSettingError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The factors before LOD and culling: --factor in (0, 64] and --vary-factors in [0, 63], and the
// factors of the edges a file lists (already read and checked against the cage; edges not listed take
// `factor`). A listed value keeps D3D11's rules (NaN or <= 0 culls the patch, > 64 clamps).
SubdFactors base_factors(float factor, float vary,
                         std::shared_ptr<const std::unordered_map<std::int64_t, float>> per_edge = nullptr);

// How view-dependent factors and culling are asked for (--lod, --edge-pixels, --lod-distance,
// --dicing-camera-position, --cull), already parsed.
struct LodRequest {
  LodMode mode = LodMode::uniform;
  PatchCullMode cull = PatchCullMode::none;
  float edge_pixels = 8.0f, lod_distance = 0.0f;  // 0: the view camera's distance to its target
  std::optional<glm::vec3> dicing_eye;            // none: the view camera dices
};
// The view the factors are for.
struct LodView {
  glm::vec3 eye{0.0f}, target{0.0f};
  glm::mat4 view_projection{1.0f};
  int width = 1, height = 1;
  float fov = 35.0f;  // vertical, degrees
};
// The model the factors are for: its posed control points, topology, the screen sign of a culled
// triangle (subd_culled_screen_sign), and the displacement bound (0 without displacement).
struct LodModel {
  std::span<const glm::vec3> positions;
  const Topology& topology;
  int culled_screen_sign = 1;
  float displacement_bound = 0.0f;
  bool displaced = false;
};
// Fills factors.per_edge from the LOD (nothing for uniform) and `cull` from the cull mode, with the
// displacement's bound in every LOD sphere and cull bound; returns the LOD's settings. Displaced
// patches carry no orientation claim, so they get no back-patch test. (Under a view-dependent LOD
// the displacement's sampling LOD moves with the camera: the caller blends its mip levels,
// Displacement::trilinear, so the surface does not pop between levels.)
// FactorSettingError for values out of range, or a view-dependent LOD with per-edge or varied factors.
LodSettings apply_lod(const LodRequest& r, const LodView& view, const LodModel& model, SubdFactors& factors,
                      PatchCull& cull);

}  // namespace tessera
