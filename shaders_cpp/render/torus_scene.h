// The benchmark scene of ../shared/bench/tessbench.cpp, as Tessera shaders: a 64x32 torus cage of
// regular bicubic B-spline patches (16 control points each, from the periodic 4x4 neighbourhood),
// displaced along the surface normal by 0.05 * (h - 0.5) from a 1024^2 float texture, coloured by the
// undisplaced surface normal. It renders the same image llvmpipe does for the same factor.
//
// Differences from the GL harness, on purpose: clip-space z is D3D's [0, w] (the GL projection's z row
// is remapped, which preserves the depth order); the patch index is SV_PrimitiveID (the harness derives
// it from the first control point only to dodge an llvmpipe bug).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/device.h"
#include "pipeline/simd4.h"
#include "pipeline/texture.h"

namespace tessera::render {

inline constexpr int kTorusColumns = 64;  // around the main axis (i, u)
inline constexpr int kTorusRows = 32;     // around the tube (j, v)
inline constexpr int kTorusTextureSize = 1024;

struct TorusScene {
  std::vector<glm::vec3> cage;         // vertex (i, j) at i * 32 + j
  std::vector<std::uint32_t> indices;  // 16 per patch, patch (i, j) at i * 32 + j
  Texture2D height;                    // R32F, no mips
  glm::mat4 view_projection{1.0f};     // D3D clip space (0 <= z <= w)
};

// Builds the cage, the index buffer, the height texture and the camera for a width x height target.
TorusScene make_torus_scene(int width, int height);

// The uniform cubic B-spline basis and its derivative at t, as the harness's GLSL computes them.
struct CubicBasis {
  glm::vec4 b, d;
};
inline CubicBasis bspline_basis(float t) {
  const float s = 1.0f - t;
  CubicBasis r;
  r.b = glm::vec4(s * s * s, 3.0f * t * t * t - 6.0f * t * t + 4.0f, -3.0f * t * t * t + 3.0f * t * t + 3.0f * t + 1.0f,
                  t * t * t) /
        6.0f;
  r.d = glm::vec4(-s * s, 3.0f * t * t - 4.0f * t, -3.0f * t * t + 2.0f * t + 1.0f, t * t) * 0.5f;
  return r;
}

struct PassThroughVS {
  glm::vec3 operator()(const glm::vec3& p, std::uint32_t) const { return p; }
};

struct UniformFactorPatch {
  TessFactors factors;
};

// Passes the 16 control points through and writes one factor on every edge and inside.
struct UniformFactorHS {
  static constexpr int kOutputControlPoints = 16;
  float factor = 1;
  glm::vec3 control_point(std::span<const glm::vec3> in, int i, std::uint32_t) const { return in[std::size_t(i)]; }
  UniformFactorPatch patch_constants(std::span<const glm::vec3>, std::span<const glm::vec3>, std::uint32_t) const {
    UniformFactorPatch p;
    p.factors.edge = {factor, factor, factor, factor};
    p.factors.inside = {factor, factor};
    return p;
  }
};

// Bicubic B-spline surface, displaced along its normal; outputs the normal as three attributes.
struct DisplacedBsplineDS {
  const Texture2D* height = nullptr;
  Sampler sampler{Filter::bilinear, AddressMode::wrap, AddressMode::wrap};
  glm::mat4 view_projection{1.0f};
  float scale = 0.05f;

  ClipVertex<3> operator()(const UniformFactorPatch&, std::span<const glm::vec3> cp, DomainLocation loc,
                           std::uint32_t patch_id) const;
  // The batch form: four points at a time in SIMD lanes, each lane the same operations in the same
  // order as the per-point form (so the same bits); the texture is sampled four lanes at a time.
  void operator()(const UniformFactorPatch&, std::span<const glm::vec3> cp, std::span<const DomainLocation> locations,
                  std::uint32_t patch_id, std::span<ClipVertex<3>> out) const;
};

// Colour = 0.5 + 0.5 * normalize(N). normalize is spelled out in glm's order (n * (1 / sqrt(dot(n, n))),
// the dot summed x, y, z) so that the per-pixel and the quad form share one definition and give the
// same bits; the quad form's lane loops vectorize (sqrt and division are exact IEEE operations in
// either form).
struct NormalColorPS {
  static void shade_lane(float x, float y, float z, float& r, float& g, float& b) {
    const float inv_len = 1.0f / std::sqrt((x * x + y * y) + z * z);
    r = 0.5f + 0.5f * (x * inv_len);
    g = 0.5f + 0.5f * (y * inv_len);
    b = 0.5f + 0.5f * (z * inv_len);
  }
  glm::vec4 operator()(const PixelInput<3>& in) const {
    glm::vec4 c(0.0f, 0.0f, 0.0f, 1.0f);
    shade_lane(in.attributes[0], in.attributes[1], in.attributes[2], c.r, c.g, c.b);
    return c;
  }
  void shade_quad(const QuadInput<3>& in, QuadColor& out) const {
    using simd::F4;
    const F4 x = F4::load(in.attributes[0]), y = F4::load(in.attributes[1]), z = F4::load(in.attributes[2]);
    const F4 inv_len = F4::splat(1.0f) / simd::sqrt((x * x + y * y) + z * z);
    const F4 half = F4::splat(0.5f);
    (half + half * (x * inv_len)).store(out.c[0]);
    (half + half * (y * inv_len)).store(out.c[1]);
    (half + half * (z * inv_len)).store(out.c[2]);
    out.c[3] = {1.0f, 1.0f, 1.0f, 1.0f};
  }
};

using TorusDraw = PatchDraw<glm::vec3, PassThroughVS, UniformFactorHS, DisplacedBsplineDS, NormalColorPS>;

// The draw call of the scene at one factor and partitioning.
TorusDraw make_torus_draw(const TorusScene& scene, float factor, ts::Partitioning partitioning, int width, int height);

}  // namespace tessera::render
