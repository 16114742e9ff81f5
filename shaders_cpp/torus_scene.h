// The benchmark scene of ../shared/bench/tessbench.cpp, as Tessera shaders: a 64x32 torus cage of
// regular bicubic B-spline patches (16 control points each, from the periodic 4x4 neighbourhood),
// displaced along the surface normal by 0.05 * (h - 0.5) from a 1024^2 float texture, coloured by the
// undisplaced surface normal. It renders the same image llvmpipe does for the same factor.
//
// Differences from the GL harness, on purpose: clip-space z is D3D's [0, w] (the GL projection's z row
// is remapped, which preserves the depth order); the patch index is SV_PrimitiveID (the harness derives
// it from the first control point only to dodge an llvmpipe bug).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "device.h"
#include "texture.h"

namespace tessera::scenes {

inline constexpr int kTorusColumns = 64;  // around the main axis (i, u)
inline constexpr int kTorusRows = 32;     // around the tube (j, v)
inline constexpr int kTorusTextureSize = 1024;

struct TorusScene {
  std::vector<glm::vec3> cage;          // vertex (i, j) at i * 32 + j
  std::vector<std::uint32_t> indices;   // 16 per patch, patch (i, j) at i * 32 + j
  Texture2D height;                     // R32F, no mips
  glm::mat4 view_projection{1.0f};      // D3D clip space (0 <= z <= w)
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
};

// Colour = 0.5 + 0.5 * normalize(N).
struct NormalColorPS {
  glm::vec4 operator()(const PixelInput<3>& in) const {
    const glm::vec3 n = glm::normalize(glm::vec3(in.attributes[0], in.attributes[1], in.attributes[2]));
    return {0.5f + 0.5f * n.x, 0.5f + 0.5f * n.y, 0.5f + 0.5f * n.z, 1.0f};
  }
};

using TorusDraw = PatchDraw<glm::vec3, PassThroughVS, UniformFactorHS, DisplacedBsplineDS, NormalColorPS>;

// The draw call of the scene at one factor and partitioning.
TorusDraw make_torus_draw(const TorusScene& scene, float factor, ts::Partitioning partitioning, int width, int height);

}  // namespace tessera::scenes
