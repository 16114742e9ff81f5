// Back-patch culling, the hull shader's half: a proof that every triangle of a patch lands on screen
// with one orientation (pipeline/patch_orientation.h states the claim and does the rest).
//
// The test is on the triangles the rasterizer sees, not on the limit surface alone: cone-of-normals
// and tangent-plane tests (Shirmun & Abi-Ezzi 1993; Loop, Niessner & Eisenacher 2011) bound the
// surface's normals, but a chord triangle can face another way than the tangent planes under it. For
// a triangle with corners A = p(a), B = p(b), C = p(c) of a polynomial patch p and the eye e, the
// screen orientation is the sign of F = (A - e) . ((B - A) x (C - A)) (times the sign of the
// projection's determinant). With d1 = b - a = (s1, t1), d2 = c - a = (s2, t2) and D = s1 t2 - t1 s2,
//   B - A = s1 p_u(a) + t1 p_v(a) + E1,   |E1| <= |d1|1^2 M2 / 2   (M2 bounds the second derivatives),
// so  F = D f(a) + err,  f = (p - e) . (p_u x p_v)  the tangent-plane facing function, and
//   |err| <= R (W M2 / 2 |d1| |d2| (|d1| + |d2|) + M2^2 / 4 |d1|^2 |d2|^2)   (R >= |A - e|, W >= |p_u|, |p_v|).
// f keeps one sign over the patch when it does over each quarter of it, bounded there from the
// quarter's Bezier net (its points in a sphere, p_u and p_v in the hulls of its derivative nets); err
// shrinks with the triangle (the pattern's cubic and quartic shape terms). The rasterizer does not see
// exact points: the domain shader rounds, the projection rounds, setup snaps to 1/256 pixel. Each
// vertex's error is bounded by a world-space distance eps (a few ulps of the coordinates, and 1/128
// pixel at the patch's farthest depth taken back through the projection), which moves F by at most
//   eps |D1| |D2| + R (2 eps (|D1| + |D2|) + 4 eps^2) + ...,   |Di| <= W |di|1,
// subtracted through the product, perimeter and inverse shape terms. Triangles that would be clipped
// could split into slivers of either orientation, so a patch whose hull (grown by eps) is not
// strictly inside the view volume gets no claim.
//
// Contract: bound() returns a claim (screen_sign != 0) only when the above proves it; otherwise the
// default OrientationBound (no claim). Tensor-product Bezier nets only (acc, pn_quad and bilinear
// patches); Gregory patches (rational interior points), `exact` patches and displaced surfaces (whose
// normals the height map's slope can turn any way) get none.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "pipeline/patch_orientation.h"

namespace tessera {

// The most segments the tessellator makes on an outer edge of factor f under any partitioning
// (integer: ceil f, pow2: at most 2 ceil f, fractional: at most f + 2; never above 64).
int max_edge_segments(float f);

class BackPatchCull {
 public:
  BackPatchCull() = default;  // disabled: bound() claims nothing
  // For a view: its projection, viewport size in pixels, and the screen_sign
  // (patch_orientation.h) of the patches the draw would cull (+1: the rasterizer culls clockwise
  // triangles and patterns are triangle_cw). bound() gives up early on patches that face the other
  // way, as no claim about them saves work. A singular projection disables the test.
  BackPatchCull(const glm::mat4& view_projection, int width, int height, int culled_sign);

  float z_bias = 0.0f;  // as FrustumCull: z moved by -z_bias * w (set per pass)

  bool enabled() const { return enabled_; }
  // `net` holds (degree + 1)^2 points, point i + (degree + 1) j with u along i: the patch's
  // DomainLocation (u, v). Degrees 1 to 3. `edge_segments` bounds from above the segment count of
  // some outer edge of the patch's pattern (max_edge_segments of its factor), for a cheap early
  // refusal.
  OrientationBound bound(std::span<const glm::vec3> net, int degree, int edge_segments) const;

 private:
  bool enabled_ = false;
  glm::dmat4 view_projection_{1.0};
  int culled_sign_ = 0;
  double det_ = 0.0;          // of P3, the projection's rows x, y, w over the coordinates
  glm::dvec3 eye_{0.0};       // where P3 p + t = 0
  double pixel_world_ = 0.0;  // world distance of kScreenError pixels at w = 1
};

}  // namespace tessera
