// Internal (not part of the public API): the limit surface of chosen base faces through OpenSubdiv's
// Far (feature-adaptive refinement to an isolation level, Gregory end caps, a patch map), for the
// faces where Debian's OpenSubdiv 3.5.0 cannot give it through Bfr.
//
// Why: 3.5.0's Bfr::IrregularPatchBuilder, for a face with a valence-2 interior corner, a boundary
// corner and tagged sharp edges, writes the boundary's sharp edges over the tagged ones and then reads
// as many entries past them uninitialized (fixed upstream after 3.5.0, commit 51eb6a0): the local
// refiner it builds finds no such edge and the process crashes (catmark_val2_interior). Far's patch
// tables do not go through that builder. needs_far_patches() names the faces; LimitSurface evaluates
// them here and every other face through Bfr, so a cage without such a face is unchanged.
//
// Contract
// - FarPatches(cage, level, faces): builds the refiner, the patch table (double precision) and the
//   points of every patch for `faces` only; throws CageError naming the cage when OpenSubdiv gives
//   no patch table.
// - evaluate(face, k, s, t): position and first derivatives, in double, at (s,t) of sub-face k of a
//   non-quad face or at (u,v) = (s,t) of a quad (k = 0): the parameterization Bfr gives the same face
//   (corner k at the origin, s along edge k). `face` must be one of `faces`.
#pragma once

#include <glm/ext/vector_double3.hpp>

#include <memory>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"

namespace tessera::osd_detail {

// The faces whose Bfr surface 3.5.0 would build from uninitialized memory (see above): a corner
// is an interior vertex of valence 2, another corner lies on the boundary, and a corner has a tagged
// sharp edge or corner.
std::vector<int> needs_far_patches(const Topology& topology);

class FarPatches {
 public:
  struct Point {
    glm::dvec3 p, ds, dt;
  };
  FarPatches(const Cage& cage, int level, const std::vector<int>& faces);
  ~FarPatches();
  FarPatches(const FarPatches&) = delete;
  FarPatches& operator=(const FarPatches&) = delete;

  Point evaluate(int face, int k, double s, double t) const;
  std::size_t memory_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera::osd_detail
