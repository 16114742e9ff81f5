// Shaders of the debug views: a domain shader wrapper that hands the pixel shader where each point
// came from (patch, domain location, face frame, texture coordinates), and one pixel shader that
// colours by what a view shows.
//
// Attributes (kDebugAttributes floats): 0-2 the surface normal, 3-5 SV_DomainLocation (u, v, w), 6
// SV_PrimitiveID of the patch within its group (exact as a float below 2^24), 7-8 the face-frame
// (u, v) of subd_shaders.h's SurfaceSample, 9-10 the texture coordinate (displaced draws; 0 else).
//
// Views read per-patch facts (patch_table.h) by the patch id. Anything drawn along a domain edge
// (patch boundaries, seams, region borders) is measured in pixels from the coarse derivatives of the
// domain location, so it is as wide on a near patch as on a far one, and anti-aliased.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "pipeline/stage_io.h"
#include "pipeline/texture.h"
#include "shaders_cpp/debug/patch_table.h"
#include "shaders_cpp/displacement/displacement_map.h"
#include "shaders_cpp/displacement/watertight_uv.h"
#include "shaders_cpp/render/subd_shaders.h"

namespace tessera {

inline constexpr std::size_t kDebugAttributes = 11;

template <class Inner>
struct DebugDS {
  Inner inner;
  glm::mat4 view_projection{1.0f};
  glm::vec3 eye{0.0f};
  // Moves the point toward the eye by this fraction of its distance (the wireframe pass over the
  // surface: hidden lines stay hidden, visible ones win the depth test).
  float pull = 0.0f;
  template <class PC, class CP>
  ClipVertex<kDebugAttributes> operator()(const PC& pc, std::span<const CP> cps, DomainLocation loc,
                                          std::uint32_t patch_id) const {
    const auto s = inner(pc, cps, loc, patch_id);
    ClipVertex<kDebugAttributes> out;
    glm::vec3 p = s.position;
    if (pull > 0.0f) p = p + pull * (eye - p);
    out.position = view_projection * glm::vec4(p, 1.0f);
    glm::vec2 uv(0.0f);
    if constexpr (requires { s.uv; }) uv = s.uv;
    out.attributes = {s.normal.x, s.normal.y, s.normal.z, loc.u, loc.v, loc.w, float(patch_id), s.u, s.v, uv.x, uv.y};
    return out;
  }
};

enum class DebugView : std::uint8_t {
  wire,          // clay, patch boundaries drawn bold (under the wireframe pass)
  factors,       // heat map of tessellation factors per edge region
  density,       // pixels per segment against the target
  patch_type,    // PatchType colours; the adaptive scheme: its patches' kinds and isolation levels
  combination,   // topology combination colours
  patch_id,      // a colour per patch
  normals,       // world normal as RGB
  uv,            // checker of the texture coordinates, UV seams marked
  displacement,  // signed displacement height
  culled,        // frustum-culled patches red, back-culled blue, the rest clay (from an overview camera)
  pick,          // not a picture: each pixel's patch as exact bytes (pick_code), for picking
};

// The pick view's bytes: code = 2 * (patch index in its group) + (tri domain ? 1 : 0) + 1 in the
// RGB bytes of an rgba8 target, least significant first; 0 where no patch covers the pixel. 24 bits
// name 8,388,607 patches; a patch beyond that is written as 0xffffff (kPickOverflow).
inline constexpr std::uint32_t kPickOverflow = 0xffffffu;
inline std::uint32_t pick_code(std::size_t index, bool tri) {
  const std::uint64_t code = std::uint64_t(index) * 2u + (tri ? 1u : 0u) + 1u;
  return code < kPickOverflow ? std::uint32_t(code) : kPickOverflow;
}
inline glm::vec4 pick_color(std::uint32_t code) {
  return glm::vec4(float(code & 255u), float((code >> 8) & 255u), float((code >> 16) & 255u), 255.0f) / 255.0f;
}

// The culled view's colour of a culled patch (and its legend swatch).
inline constexpr glm::vec3 kCulledColor{0.92f, 0.25f, 0.18f};
// ... and of a patch the back-patch test skipped.
inline constexpr glm::vec3 kBackCulledColor{0.25f, 0.45f, 0.9f};

// Colour maps, t in [0, 1].
glm::vec3 heat_color(float t);       // dark blue -> cyan -> green -> yellow -> red (a turbo-like ramp)
glm::vec3 diverging_color(float t);  // blue -> white -> red, white at 0.5
glm::vec3 category_color(int i);     // well-separated colours for small indices, hashed beyond
glm::vec3 hashed_color(std::uint32_t i);
// The adaptive patch-type view's colour of a kind at an isolation level (its legend swatch at level 0).
glm::vec3 adaptive_patch_color(AdaptivePatchKind kind, int level);

struct DebugPS {
  DebugView view = DebugView::wire;
  std::span<const PatchInfo> patches;
  glm::vec3 light{0.0f, 0.0f, 1.0f};
  bool processed = false;             // factors: processed rather than raw
  float edge_pixels = 8.0f;           // density: the target
  // displacement: the map per tile (channel 0 scalar) and each patch's tile (PatchTexcoords::tile; empty:
  // tile 0). The uv view reads the displaced DS's texture coordinates when `heights` is given.
  std::span<const DisplacementMap> heights;
  std::span<const PatchTexcoords> texcoords;
  float height_scale = 1.0f, height_bias = 0.0f, height_range = 1.0f;
  bool paper = false;  // wire: a flat white surface (the wireframe view) instead of clay
  // patch_type under the adaptive scheme: the surface whose patch at each point is coloured (by kind,
  // darker per isolation level, quads with their sub-patch borders) instead of the face's type.
  const LimitSurface* adaptive = nullptr;
  FaceSides sides;

  // The factor range the factors view maps to its colour bar (log2 from 1 to 64).
  static float factor_position(float f) { return std::clamp(std::log2(std::max(f, 1.0f)) / 6.0f, 0.0f, 1.0f); }
  // The density view: log2(pixels per segment / target) from -3 to 3.
  static float density_position(float ratio) {
    return std::clamp((std::log2(std::max(ratio, 1e-6f)) + 3.0f) / 6.0f, 0.0f, 1.0f);
  }

  glm::vec4 operator()(const PixelInput<kDebugAttributes>& in) const;
};

// The wireframe pass: triangle edges over the surface (depth-tested against it), fading out where a
// patch's segments are too short on screen for its lines to read.
struct DebugWirePS {
  std::span<const PatchInfo> patches;
  glm::vec3 light{0.0f, 0.0f, 1.0f};
  bool paper = false;
  FaceSides sides;
  glm::vec4 operator()(const PixelInput<kDebugAttributes>& in) const;
};

// The distance in pixels from a pixel to the domain edges of its patch (in SV_TessFactor order), from
// the domain location and its coarse derivatives.
std::array<float, 4> domain_edge_pixels(const PixelInput<kDebugAttributes>& in, bool tri);

}  // namespace tessera
