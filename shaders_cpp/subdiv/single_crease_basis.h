// Internal (not part of the public API): the basis of a single-crease patch (Niessner, Loop, Greiner,
// "Efficient evaluation of semi-smooth creases in Catmull-Clark subdivision surfaces", Eurographics 2012
// short paper): a regular 4x4 B-spline neighbourhood whose control row on one patch edge is a crease of
// one sharpness, evaluated exactly (OpenSubdiv's CPU Far::PatchBasis treats that edge as a boundary,
// i.e. infinitely sharp; its GPU shaders alone honour the sharpness).
//
// Why a product of two curves: in a regular neighbourhood with one straight crease, Catmull-Clark's
// crease rules are tensor products of the uniform cubic B-spline rule along the crease and a 1D rule
// across it (the crease vertex keeps its place, lerped with the smooth rule by the fraction while the
// sharpness is below 1; RenderMan/OpenSubdiv's semi-sharp rules). Across the crease the 1D curve is
// evaluated by that subdivision: each step halves the span; the half away from the crease is a plain
// B-spline segment of the new points, the half at the crease recurses with the sharpness less 1, and
// after ceil(sharpness) steps the rest is plain B-spline too.
//
// Contract
// - crease_curve_basis(x, sharpness, w, dw): the four weights (and d/dx) of control rows Q0..Q3 at x in
//   [0,1] across the span Q1 (x = 0) .. Q2 (x = 1), with the crease on row Q2; sharpness <= 0 gives the
//   uniform cubic B-spline basis. Sharpness is taken as is (the caller clamps, Far clamps to the levels
//   left); the loop runs at most ceil(sharpness) steps, each exact in binary fractions of x.
// - RegularCurves: a regular patch's basis as the two curves whose tensor product it is: weights per
//   column in s and per row in t, and their derivatives (Far's point order: row-major, s along a row, t
//   across rows; the face is rows and columns 1..2), at (s,t) in the patch's own unit square.
//   regular_patch_curves: Far's boundary bits (0 t=0, 1 s=1, 2 t=1, 3 s=0 as bit values 1, 2, 4, 8),
//   phantom rows and columns folded into the ones inside as Far's basis does, no crease.
//   single_crease_curves: the crease on face edge `edge` (0 t=0, 1 s=1, 2 t=1, 3 s=0). The domain shader
//   sums the 16 points row by row instead of by 16 weights.
#pragma once

namespace tessera::subdiv {

void cubic_bspline_basis(double x, double w[4], double dw[4]);
void crease_curve_basis(double x, double sharpness, double w[4], double dw[4]);
struct RegularCurves {
  double s[4], ds[4], t[4], dt[4];
};
RegularCurves regular_patch_curves(int boundary, double s, double t);
RegularCurves single_crease_curves(int edge, double sharpness, double s, double t);

}  // namespace tessera::subdiv
