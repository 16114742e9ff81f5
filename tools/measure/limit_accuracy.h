// How close a LimitSurface (Bfr at a given approximation level) is to the true Catmull-Clark limit.
//
// Contract
// - measure_limit_accuracy: refines the cage uniformly `refine_level` times with OpenSubdiv's
//   Far::PrimvarRefiner and takes the exact limit positions of the refined vertices
//   (PrimvarRefiner::Limit, closed-form vertex limit masks: no patches involved). Each refined vertex
//   sits at a dyadic domain location (a multiple of 2^-refine_level in some face or sub-patch), where
//   the LimitSurface is sampled (sample_reference, double). Use refine_level >= 4 so most samples are
//   not on multiples of 1/8, where a Bfr approximation is exact by construction and hides its error.
//   Vertices of faces without a surface are skipped.
// - compare_limit_surfaces: max distance between two LimitSurfaces of the same cage (e.g. level L
//   against level 10) on a rate x rate grid of every sub-patch, at parameters i/rate, plus points
//   zooming into each sub-patch corner (distances 2^-1 .. 2^-12), where approximations differ.
// Caveat: a Bfr surface at level L is exact (to round-off) at multiples of 2^-L, so the uniform
// refinement reference only sees errors of levels below refine_level.
// Distances are absolute and also relative to the limit surface's bounding-box diagonal.
#pragma once

#include <cstddef>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/subdiv/limit_surface.h"

namespace tessera::measure {

struct LimitAccuracy {
  std::size_t samples = 0;
  double max_distance = 0.0;  // absolute
  double rms_distance = 0.0;
  double diagonal = 0.0;  // of the limit surface's bounding box
  double max_relative() const { return diagonal > 0 ? max_distance / diagonal : max_distance; }
};

// Throws CageError for a cage OpenSubdiv cannot take; std::invalid_argument for refine_level
// outside 1..8 (level 8 of a 1000-face cage is 65 million vertices' worth of memory already).
LimitAccuracy measure_limit_accuracy(const Cage& cage, const LimitSurface& surface, int refine_level = 5);

LimitAccuracy compare_limit_surfaces(const LimitSurface& a, const LimitSurface& b, int rate = 37);

}  // namespace tessera::measure
