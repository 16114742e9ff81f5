// 2D float textures with mip chains, sampled the way Direct3D 11 (and GL / llvmpipe) sample them.
//
// Contract
// - A Texture2D is immutable after create(): every member function is const and reads only, so any
//   number of threads (VS, HS, DS and PS invocations alike) may sample one texture at once. Nothing
//   is global; sampling never allocates.
// - Texels are float, 1 to 4 channels, row-major, row 0 at v near 0 (the top of the image, as in
//   D3D). Reads return a glm::vec4; missing channels read as D3D's defaults (0, 0, 0, 1), so an
//   R-only texture reads (r, 0, 0, 1) and RGB reads (r, g, b, 1).
// - Deterministic: plain float arithmetic in a fixed order (the project builds with
//   -ffp-contract=off), so a texel, a coordinate and a sampler give the same bits on every call.
//
// Conventions (D3D11.3 §7.18, GL 4.6 §8.14; both agree on all of this)
// - Texel i of a level of size n has its centre at u = (i + 0.5) / n.
// - Point: texel floor(u * n). Bilinear: x = u * n - 0.5, i0 = floor(x), frac = x - i0; texels i0
//   and i0 + 1 are addressed separately, then blended as a * (1 - frac) + b * frac (u first, then v).
// - Addressing works on integer texel coordinates: wrap = i mod n (non-negative), clamp = clamp(i,
//   0, n - 1), mirror = mirrored repeat with period 2n (0 1 .. n-1 n-1 .. 1 0 0 1 ..).
// - Level of detail: lod + mip_lod_bias, then clamped to [min_lod, max_lod] (max_lod wins if the
//   sampler has min_lod > max_lod), then to [0, levels() - 1]; a NaN lod becomes the lower bound.
//   Point and bilinear use level floor(lod + 0.5) (D3D's MIP_POINT); trilinear blends levels
//   floor(lod) and floor(lod) + 1 with weight frac(lod). Magnification (lod <= 0) is level 0 with
//   the sampler's filter: there is one filter, not separate min and mag filters.
//
// Degenerate input
// - NaN and Inf texels are accepted and kept; they propagate through mips and filtering (a NaN or
//   Inf texel in a bilinear footprint can make the result NaN even where its weight is 0).
// - A texel-space coordinate (u * n or u * n - 0.5) that is NaN or +-Inf is replaced by 0 before it
//   becomes an index. A huge finite one (|x| >= 2^30, e.g. u = 1e30) is first reduced exactly
//   (fmod in double by the addressing period, or clamped), so no int conversion can overflow and
//   every index is in range.
//
// Mip chain (build_mips): each level is floor(previous / 2) per axis, at least 1, down to 1x1.
// Each texel is the area-weighted box average of its footprint in the previous level, one axis at
// a time (u, then v):
// - even size s: destination i = (src[2i] + src[2i+1]) / 2;
// - odd size s = 2d + 1 > 1: destination i covers the source interval [i*s/d, (i+1)*s/d) and each
//   source texel weighs its overlap, e.g. 5 -> 2: (2a + 2b + c) / 5 and (c + 2d + 2e) / 5, and
//   3 -> 1: (a + b + c) / 3;
// - size 1 stays 1 (copied) while the other axis shrinks.
// This keeps the mean of every level equal to the mean of level 0 (up to rounding).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

// D3D11 MIN_MAG_MIP_POINT, MIN_MAG_LINEAR_MIP_POINT, MIN_MAG_MIP_LINEAR.
enum class Filter : std::uint8_t { point, bilinear, trilinear };
// D3D11_TEXTURE_ADDRESS_WRAP, _CLAMP, _MIRROR.
enum class AddressMode : std::uint8_t { wrap, clamp, mirror };

// As D3D11_SAMPLER_DESC (without anisotropy, comparison and border colour).
struct Sampler {
  Filter filter = Filter::trilinear;
  AddressMode address_u = AddressMode::wrap;
  AddressMode address_v = AddressMode::wrap;
  float mip_lod_bias = 0.0f;
  float min_lod = 0.0f;
  float max_lod = 1000.0f;
};

std::string_view to_string(Filter f);
std::optional<Filter> parse_filter(std::string_view s);  // "point", "bilinear", "trilinear"
std::string_view to_string(AddressMode m);
std::optional<AddressMode> parse_address_mode(std::string_view s);  // "wrap", "clamp", "mirror"

// Largest width or height accepted (D3D11 itself requires 16384; larger helps offline baking).
inline constexpr int kMaxTextureSize = 32768;
inline constexpr int kMaxTextureLevels = 16;  // 32768 -> 1

class Texture2D {
 public:
  // `texels` holds width * height * channels floats, row-major, channels interleaved. Builds the
  // full mip chain when build_mips is true, otherwise one level. Returns std::nullopt for a size
  // outside 1..kMaxTextureSize, channels outside 1..4 or a texel count that does not match, and then
  // writes a one-line reason to *error (error may be null).
  static std::optional<Texture2D> create(int width, int height, int channels, std::vector<float> texels,
                                         bool build_mips, std::string* error);

  // Level sizes; 0 for a level outside [0, levels()).
  int width(int level = 0) const;
  int height(int level = 0) const;
  int channels() const { return channels_; }
  int levels() const { return levels_; }

  // HLSL Load: one texel, no filtering or addressing. Out-of-range level or coordinates read
  // (0, 0, 0, 0), as D3D's ld does.
  glm::vec4 load(int level, int x, int y) const;

  // HLSL SampleLevel: explicit lod, usable in any stage (no derivatives needed).
  glm::vec4 sample_level(const Sampler& s, glm::vec2 uv, float lod) const;
  // Four sample_level calls with one lod (a batch shader's lanes): out[k] = sample_level(s, uv[k], lod),
  // the same bits; a one-channel texture's bilinear and trilinear filters run in SIMD lanes.
  void sample_level4(const Sampler& s, const std::array<glm::vec2, 4>& uv, float lod,
                     std::array<glm::vec4, 4>& out) const;

  // HLSL SampleGrad, and Sample in a pixel shader (with the quad's derivatives): isotropic lod =
  // log2(max(|ddx * size|, |ddy * size|)), size = level 0's (width, height), then as sample_level.
  // Zero derivatives give lod -inf, which clamps to the lower bound.
  glm::vec4 sample_grad(const Sampler& s, glm::vec2 uv, glm::vec2 ddx, glm::vec2 ddy) const;
  // Four sample_grad calls with one pair of derivatives (a pixel's neighbourhood): out[k] =
  // sample_grad(s, uv[k], ddx, ddy), the same bits, through sample_level4.
  void sample_grad4(const Sampler& s, const std::array<glm::vec2, 4>& uv, glm::vec2 ddx, glm::vec2 ddy,
                    std::array<glm::vec4, 4>& out) const;
  // The lod sample_grad samples at, before the sampler's bias and clamp.
  float grad_lod(glm::vec2 ddx, glm::vec2 ddy) const;

  // Bytes of texel storage, all levels (for memory reports).
  std::size_t bytes() const { return texels_.size() * sizeof(float); }

 private:
  struct Level {
    int width = 0;
    int height = 0;
    float fwidth = 0.0f;  // width and height as float, so sampling does not convert per call
    float fheight = 0.0f;
    std::size_t offset = 0;  // first float of the level in texels_
  };

  Texture2D() = default;

  float clamp_lod(const Sampler& s, float lod) const;
  glm::vec4 sample_at_lod(const Sampler& s, glm::vec2 uv, float lod) const;
  glm::vec4 sample_point(const Sampler& s, const Level& level, glm::vec2 uv) const;
  glm::vec4 sample_bilinear(const Sampler& s, const Level& level, glm::vec2 uv) const;
  // sample_bilinear's channel r at four coordinates of a one-channel texture, in lanes.
  void bilinear4(const Sampler& s, const Level& level, const std::array<glm::vec2, 4>& uv,
                 std::array<float, 4>& out) const;

  std::vector<float> texels_;  // all levels, contiguous, level 0 first
  std::array<Level, kMaxTextureLevels> levels_info_{};
  int levels_ = 0;
  int channels_ = 0;
};

}  // namespace tessera
