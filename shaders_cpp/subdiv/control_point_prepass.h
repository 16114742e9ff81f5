// The control-point pre-pass: the hull-shader control points of the patches whose 1-ring is larger
// than a D3D11 IA patch holds (SubdPatch::precomputed), computed before the draw at control-point rate,
// as GPU engines do with a compute pass, and read by the hull shader in place of its own sum.
//
// Contract: the result has patches.precomputed_rows points; patch P's row r is at
// P.precomputed + r. Each is summed as SubdHS sums a row: over the ring's vertices in ascending index,
// zero weights skipped, weight (float) times position in double, rounded to float once. A row that an
// ordinary neighbour computes too (a corner's P and E points) therefore has the neighbour's bits, and
// edges stay watertight. `positions` are the vertex shader's outputs for every cage vertex (the posed
// cage when animated).
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera {

std::vector<glm::vec3> precompute_control_points(const SubdPatches& patches, std::span<const glm::vec3> positions);

// The same sums for any list of precomputed patches (displacement_frames.h keeps its frames' rows of
// such patches this way): their rows, one after another.
std::vector<glm::vec3> precompute_rows(std::span<const PrecomputedPatch> patches, std::span<const glm::vec3> positions);

}  // namespace tessera
