// Exact Catmull-Clark limit positions at the vertices of a uniform refinement, with their domain
// locations: the reference that limit-surface approximations are measured against.
//
// Contract
// - exact_limit_samples refines the cage uniformly `refine_level` times with OpenSubdiv's
//   Far::PrimvarRefiner and returns, for every refined vertex that lies in a face with faces[f] set,
//   its exact limit position (PrimvarRefiner::Limit: closed-form vertex limit masks, no patches) and
//   where it sits: base face, sub-patch (0 for quads; the corner's sub-patch for n-gons, as
//   LimitSurface numbers them) and (u, v) in that sub-patch, an exact multiple of 2^-refine_level.
//   Positions are in double, from the cage's float positions.
// - Throws CageError for a cage OpenSubdiv cannot take, std::invalid_argument for refine_level
//   outside 1..8 (level 8 of a 1000-face cage is 65 million vertices' worth of memory already).
// No OpenSubdiv type appears here: osdCPU stays a private dependency of tessera_subdiv.
#pragma once

#include <glm/ext/vector_double2.hpp>
#include <glm/ext/vector_double3.hpp>

#include <vector>

#include "shaders_cpp/cage/cage.h"

namespace tessera {

struct ExactLimitSample {
  int face = -1;
  int sub_patch = 0;
  glm::dvec2 uv{0.0};
  glm::dvec3 position{0.0};
};

std::vector<ExactLimitSample> exact_limit_samples(const Cage& cage, const std::vector<bool>& faces, int refine_level);

}  // namespace tessera
