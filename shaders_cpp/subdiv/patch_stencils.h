// The control points of one patch as stencils over the cage, for each approximation scheme.
//
// Inputs are the rings of the face's corners (corner_ring.h), corner k of the face first.
// Outputs, per scheme (i runs along u from corner 0 to corner 1, j along v from corner 0 to corner 3;
// the quad domain maps corners 0, 1, 2, 3 to (0,0), (1,0), (1,1), (0,1)):
// - acc_quad_stencils: 40 stencils: the bicubic Bezier geometry patch b[i + 4 j] (16), then Loop &
//   Schaefer's u-tangent patch du[i + 3 j] (i = 0..2 quadratic, j = 0..3 cubic, 12), then the v-tangent
//   patch dv[i + 4 j] (i = 0..3 cubic, j = 0..2 quadratic, 12). Regular faces give the B-spline patch
//   and its exact derivatives.
// - gregory_quad_stencils: 20 stencils, five per corner k at 5k: P, E+, E-, F+, F- (Loop, Schaefer, Ni,
//   Castano 2009). E+ lies on the edge k -> k+1, E- on the edge k -> k-1; F+ pairs with E+.
// - gregory_triangle_stencils: 15 stencils in the same layout for a triangle face (corners 0, 1, 2 at
//   w = 1, u = 1, v = 1 of the tri domain): the quartic triangular Gregory patch with cubic boundaries
//   (Loop et al. 2009 after Kovacs; evaluated by patch_eval.h). P and E are built exactly as for quads,
//   so a triangle and a quad sharing an edge share its four boundary points bit for bit; the face points
//   are re-derived for the quartic (patch_stencils.cpp states the derivation).
// - gregory_fan_stencils: 15 stencils in the triangle's layout for fan triangle k of a face of n >= 5
//   sides (corner 0 = face corner k, corner 1 = face corner k + 1, corner 2 = the face's centre, as the
//   exact scheme's fan, limit_surface.h). Its outer edge is the cage edge k -> k+1 with the P and E points
//   every other face beside that edge computes, bit for bit; the centre is the exact limit
//   (face_centre_limit.h). The derivation is stated in patch_stencils.cpp.
// acc needs a quad whose corner rings have only quads; gregory takes any face (larger faces in a
// corner ring act through their "virtual quad" far point,
// limit_masks.h). The caller (subd_patches.cpp) checks.
#pragma once

#include <array>
#include <vector>

#include "shaders_cpp/cage/corner_ring.h"
#include "shaders_cpp/subdiv/face_centre_limit.h"
#include "shaders_cpp/subdiv/stencil.h"

namespace tessera {

inline constexpr int kAccStencils = 40;
inline constexpr int kGregoryQuadStencils = 20;
inline constexpr int kGregoryTriangleStencils = 15;

std::vector<Stencil> acc_quad_stencils(const std::array<CornerRing, 4>& corners);
std::vector<Stencil> gregory_quad_stencils(const std::array<CornerRing, 4>& corners);
std::vector<Stencil> gregory_triangle_stencils(const std::array<CornerRing, 3>& corners);
// `a` and `b`: the rings of face corners k and k + 1 (gather_corner_ring, or the creased rings).
std::vector<Stencil> gregory_fan_stencils(const CornerRing& a, const CornerRing& b, const FaceCentre& centre, int k);

}  // namespace tessera
