// Internal (not part of the public API): the surface of base faces through OpenSubdiv's Far:
// feature-adaptive refinement to an isolation level (Niessner, Loop, Meyer, DeRose, TOG 2012), regular
// faces as B-spline patches (infinitely sharp creases as their boundaries), optionally a regular face
// beside one semi-sharp crease as a single-crease patch (evaluated here: single_crease_basis.h), and
// what stays irregular at the last level as Gregory end caps; a patch map finds the patch of a point.
// Two users: the `adaptive` scheme (every face, single-crease patches on) and the exact limit surface,
// for the faces where Debian's OpenSubdiv 3.5.0 cannot give it through Bfr.
//
// Why the exact surface needs it: 3.5.0's Bfr::IrregularPatchBuilder, for a face with a valence-2 interior corner, a
// boundary corner and tagged sharp edges, writes the boundary's sharp edges over the tagged ones and then reads as many
// entries past them uninitialized (fixed upstream after 3.5.0, commit 51eb6a0): the local refiner it builds finds no
// such edge and the process crashes (catmark_val2_interior). Far's patch tables do not go through that builder.
// needs_far_patches() names the faces; LimitSurface evaluates them here and every other face through Bfr, so a cage
// without such a face is unchanged.
//
// Contract
// - FarPatches(cage, level, faces, single_crease): builds the refiner, the patch table (double
//   precision) and the points of every patch for `faces` (empty: every face); throws CageError naming
//   the cage when OpenSubdiv gives no patch table. Semi-sharp sharpness above the levels left at a
//   patch is clamped to them (Far's rule), so sharpness above `level` is drawn as `level`.
// - evaluate(face, k, s, t): position and first derivatives, in double, at (s,t) of sub-face k of a
//   non-quad face or at (u,v) = (s,t) of a quad (k = 0): the parameterization Bfr gives the same face
//   (corner k at the origin, s along edge k), derivatives with respect to that (s,t). `face` must have
//   a patch there (has_patches).
// - patch_at: the kind and isolation level of the patch that evaluate() uses at that point; counts():
//   patches per kind and per level.
// - repose(positions): the same cage's vertices moved (an animation's pose): only the points are
//   recomputed, through the same stencils as the constructor's, so the result has the bits a new
//   FarPatches of the moved cage would have. Keeps the stencils from its first call on.
#pragma once

#include <glm/ext/vector_double3.hpp>

#include <memory>
#include <span>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/limit_surface.h"

namespace tessera::subdiv {

// The faces whose Bfr surface 3.5.0 would build from uninitialized memory (see above): a corner
// is an interior vertex of valence 2, another corner lies on the boundary, and a corner has a tagged
// sharp edge or corner.
std::vector<int> needs_far_patches(const Topology& topology);

class FarPatches {
 public:
  struct Point {
    glm::dvec3 p, ds, dt;
  };
  using PatchInfo = LimitSurface::PatchFacts;
  using Counts = LimitSurface::PatchCounts;
  FarPatches(const Cage& cage, int level, const std::vector<int>& faces, bool single_crease = false);
  ~FarPatches();
  FarPatches(const FarPatches&) = delete;
  FarPatches& operator=(const FarPatches&) = delete;

  void repose(std::span<const glm::vec3> positions);
  bool has_patches(int face) const;
  Point evaluate(int face, int k, double s, double t) const;
  PatchInfo patch_at(int face, int k, double s, double t) const;
  Counts counts() const;
  std::size_t memory_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera::subdiv
