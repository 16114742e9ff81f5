// Patches whose IA patch is the face itself: flat (bilinear quads, linear triangles), exact and
// adaptive (the domain shader evaluates the limit surface, limit_surface.h) and pn (the hull shader
// builds the PN points from the corners and their normals, pn_patch.h).
//
// A face of n > 4 sides (flat, exact, adaptive) is a fan of n triangles k = (corner k, corner k+1,
// centre), u = 1 at corner k+1 and v = 1 at the centre. Each fan triangle's ring starts at corner k, so
// every fan triangle of every n-gon shares one flat table; the centre is summed in vertex order
// (SubdPatch::order), so the n triangles compute the same bits for it.
#include "shaders_cpp/subdiv/patch_construction.h"

namespace tessera::subdiv {

void build_corner_patch(PatchContext& ctx, const FaceFrame& face) {
  const int n = face.n, f = face.f;
  const Scheme scheme = ctx.scheme;
  SubdPatches& out = ctx.out;
  if (scheme == Scheme::pn) {
    if (n > 4)
      throw CageError(where(ctx.cage, f) + " has " + std::to_string(n) +
                      " sides; --scheme pn handles triangles and quads only (use --scheme adaptive, exact or flat)");
    ctx.assembler.add(n == 3 ? out.tris : out.quads, f, 0, n == 3 ? PatchKind::pn_triangle : PatchKind::pn_quad,
                      face.corners_from(0), {}, face.edges);
    return;
  }
  if (n > kMaxPatchControlPoints)
    throw CageError(where(ctx.cage, f) + " has " + std::to_string(n) + " sides; --scheme " + to_string(scheme) +
                    " draws faces of up to " + std::to_string(kMaxPatchControlPoints) +
                    " (the face is the patch's control points)");
  const PatchKind tri_kind = uses_limit_surface(scheme) ? PatchKind::exact : PatchKind::linear;
  if (n == 3 || n == 4) {
    std::vector<Stencil> corners;
    if (scheme == Scheme::flat)
      for (int k = 0; k < n; ++k) corners.push_back(Stencil::vertex(face.corner(k)));
    const PatchKind kind = n == 3 ? tri_kind : uses_limit_surface(scheme) ? PatchKind::exact : PatchKind::bilinear;
    ctx.assembler.add(n == 3 ? out.tris : out.quads, f, 0, kind, face.corners_from(0), corners, face.edges);
    return;
  }
  Stencil centre;
  for (int k = 0; k < n; ++k) centre.add_vertex(face.corner(k), 1.0 / n);
  for (int k = 0; k < n; ++k) {
    const std::array<EdgeFactorKey, 4> fan_edges = fan_edge_keys(ctx.cage, f, k);
    std::vector<Stencil> points;
    if (scheme == Scheme::flat)
      points = {Stencil::vertex(face.corner(k)), Stencil::vertex(face.corner(k + 1)), centre};
    ctx.assembler.add(out.tris, f, k, tri_kind, face.corners_from(k), points, fan_edges);
  }
}

}  // namespace tessera::subdiv
