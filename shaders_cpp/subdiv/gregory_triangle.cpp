// A triangle under gregory and bspline: the 15-point triangular Gregory patch (quartic, cubic
// boundaries; patch_stencils.h, gregory_triangle_stencils), blended at its creases (crease_blend.h),
// its corners and edges fitted to the limit where a fitted face has them and its face points fitted
// where one of its edges is (fitted_faces.h). bspline counts it in fallback_faces.
//
// Contract: its corner and edge points are the rows every neighbour on them computes, so it is
// watertight to them under any factors.
#include "shaders_cpp/subdiv/crease_blend.h"
#include "shaders_cpp/subdiv/limit_fit.h"
#include "shaders_cpp/subdiv/patch_construction.h"
#include "shaders_cpp/subdiv/patch_stencils.h"

namespace tessera::subdiv {

void build_gregory_triangle(PatchContext& ctx, const FaceFrame& face) {
  const FaceRings<3> rings = face_rings<3>(ctx, face);
  if (ctx.scheme == Scheme::bspline) ++ctx.out.fallback_faces;  // never a regular face
  std::vector<Stencil> stencils = gregory_triangle_stencils(rings.whole);
  if (face.creased) {
    const std::vector<Stencil> smooth = stencils;
    stencils = blend_by_corner(stencils, gregory_triangle_stencils(rings.cut), rings.weight, false);
    exact_corners(ctx, face, stencils, smooth, 3);
  }
  fit_boundary(ctx, face, stencils);
  if (ctx.fitted.any() && ctx.fitted.fits_face_points(face.f))
    fit_triangle_face_points(ctx.fitted.limit(), face.f, face.rot, stencils, smooth_edges<3>(ctx.t, face));
  add_creased(ctx, face, ctx.out.tris, PatchKind::gregory_triangle, gather_ring(rings.whole), stencils);
}

}  // namespace tessera::subdiv
