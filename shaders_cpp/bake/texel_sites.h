// Where each texel of a map lies on the base surface: the inverse of the cage's UV layout.
//
// A texel (x, y) of a w x h map is centred at ((x + 0.5) / w, (y + 0.5) / h), the texture convention of
// texture.h. It belongs to the first patch, in patch order, whose UV quad (its own corner UVs,
// `PatchTexcoords::interior`, interpolated bilinearly as the domain shader does) contains that centre;
// its site is the patch's domain location there, found by Newton's method on the bilinear map in
// double precision.
//
// Contract: deterministic; a texel no chart covers has patch -1. Degenerate or folded UV quads cover
// the texels where Newton's method converges inside the domain.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "shaders_cpp/displacement/watertight_uv.h"

namespace tessera {

struct TexelSite {
  std::int32_t patch = -1;  // index into the patch group; -1: no chart covers the texel
  float u = 0, v = 0;       // the patch's domain location (corner k at (0,0),(1,0),(1,1),(0,1))
};

// One site per texel, row-major.
std::vector<TexelSite> texel_sites(std::span<const PatchTexcoords> patches, int w, int h);

// The domain location (u, v) whose bilinear UV over `corners` is `uv`, if it lies in [0, 1]^2 (within
// a tolerance of 1e-6, then clamped).
bool invert_bilinear(const std::array<glm::vec2, 4>& corners, glm::dvec2 uv, float& u, float& v);

}  // namespace tessera
