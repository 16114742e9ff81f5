// A triangle of a polar configuration under gregory and bspline (polar_patch.h): a bicubic with its row
// at the pole collapsed, in the Gregory triangle's 15 slots. Its patch corner 0 is the pole.
//
// Contract: its ring edge (patch edge 1 -> 2) is the Gregory edge the quad across it computes (that
// quad's rows, NeighbourRows, fitted where the quad is), and its spokes the Gregory edge points the
// sectors beside it share, so the cap is watertight to the bit under any factors. It is not blended at
// creases (a pole is untagged); a crease on its ring edge still gets cross rows (add_creased).
// bspline counts it in fallback_faces.
#include "shaders_cpp/subdiv/patch_construction.h"
#include "shaders_cpp/subdiv/patch_stencils.h"
#include "shaders_cpp/subdiv/polar_patch.h"

namespace tessera::subdiv {

void build_polar_triangle(PatchContext& ctx, const FaceFrame& face) {
  const Topology& t = ctx.t;
  const FaceRings<3> rings = face_rings<3>(ctx, face);
  if (ctx.scheme == Scheme::bspline) ++ctx.out.fallback_faces;  // never a regular face
  std::vector<Stencil> stencils = gregory_triangle_stencils(rings.whole);
  fit_boundary(ctx, face, stencils);  // a fitted quad across the ring edge gives that edge's points
  const int across = t.twin(t.face_offset(face.f) + (1 + face.rot) % 3);  // the ring edge, from the quad
  polar_triangle_rows(stencils, t.valence(face.polar), ctx.neighbours.of(t.face(across)), t.corner(across));
  add_creased(ctx, face, ctx.out.tris, PatchKind::polar_triangle, gather_ring(rings.whole), stencils);
}

}  // namespace tessera::subdiv
