// A quad under gregory and bspline, and a fitted quad under acc: the 20-point Gregory patch (Loop,
// Schaefer, Ni and Castano's masks; patch_stencils.h, gregory_quad_stencils), blended at its creases
// (crease_blend.h), its corners and edges fitted to the limit where a fitted face has them and its
// face points fitted where one of its edges is (fitted_faces.h). On a regular face (every corner an
// interior, untagged vertex of four quads) the Gregory patch is the face's bicubic B-spline patch,
// which is what bspline draws; bspline counts every other quad in fallback_faces.
//
// Contract: its corner and edge points are the rows every neighbour on them computes, so it is
// watertight to them under any factors.
#include "shaders_cpp/subdiv/crease_blend.h"
#include "shaders_cpp/subdiv/limit_fit.h"
#include "shaders_cpp/subdiv/patch_construction.h"
#include "shaders_cpp/subdiv/patch_stencils.h"

namespace tessera::subdiv {

void build_gregory_quad(PatchContext& ctx, const FaceFrame& face) {
  const FaceRings<4> rings = face_rings<4>(ctx, face);
  if (ctx.scheme == Scheme::bspline && !is_regular_face(ctx.t, rings.whole)) ++ctx.out.fallback_faces;
  std::vector<Stencil> stencils = gregory_quad_stencils(rings.whole);
  if (face.creased) {
    const std::vector<Stencil> smooth = stencils;
    stencils = blend_by_corner(stencils, gregory_quad_stencils(rings.cut), rings.weight, false);
    exact_corners(ctx, face, stencils, smooth, 4);
  }
  fit_boundary(ctx, face, stencils);
  if (ctx.fitted.any() && ctx.fitted.fits_face_points(face.f))
    fit_face_points(ctx.fitted.limit(), face.f, face.rot, stencils, smooth_edges<4>(ctx.t, face));
  add_creased(ctx, face, ctx.out.quads, PatchKind::gregory, gather_ring(rings.whole), stencils);
}

}  // namespace tessera::subdiv
