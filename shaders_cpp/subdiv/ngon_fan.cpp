// A face of n >= 5 sides under gregory and bspline: the fan of the exact scheme, triangle k = (face
// corner k, corner k + 1, centre), unrotated (the limit surface's fan_location names it by k), each a
// triangular Gregory patch (patch_stencils.h, gregory_fan_stencils) whose centre is the face centre's
// limit (face_centre_limit.h). Spokes take the mean of the factors of the cage edges beside them
// (fan_edge_keys), so both triangles on a spoke compute the same factor.
//
// Contract: triangle k's ring is the union of every corner's ring from corner k on (the centre reads
// them all), so the fans of one face, and of faces alike, share a table; its corners' P and outer edge
// points are the rows its neighbours across the cage edges compute (crease blend, semi-sharp corners,
// fitted corners and edges), so the fan is watertight to them. bspline counts it in fallback_faces.
#include "shaders_cpp/subdiv/crease_blend.h"
#include "shaders_cpp/subdiv/face_centre_limit.h"
#include "shaders_cpp/subdiv/patch_construction.h"
#include "shaders_cpp/subdiv/patch_stencils.h"

namespace tessera::subdiv {

void build_ngon_fan(PatchContext& ctx, const FaceFrame& face) {
  const Cage& cage = ctx.cage;
  const Topology& t = ctx.t;
  const int n = face.n, f = face.f;
  if (ctx.scheme == Scheme::bspline) ++ctx.out.fallback_faces;  // never a regular face
  std::vector<CornerRing> rings, cut(static_cast<std::size_t>(n));
  std::vector<double> w(static_cast<std::size_t>(n), 0.0);
  for (int k = 0; k < n; ++k) {
    rings.push_back(gather_corner_ring(cage, t, f, k));
    float sharpness = 0.0f;
    if (face.creased) cut[std::size_t(k)] = gather_creased_corner_ring(cage, t, f, k, &sharpness);
    w[std::size_t(k)] = crease_weight(sharpness);
  }
  const FaceCentre centre = face_centre_limit(cage, t, f);
  auto at = [&](int k) { return std::size_t(((k % n) + n) % n); };
  for (int k = 0; k < n; ++k) {
    const std::array<EdgeFactorKey, 4> fan_edges = fan_edge_keys(cage, f, k);
    std::vector<Stencil> stencils = gregory_fan_stencils(rings[at(k)], rings[at(k + 1)], centre, k);
    const int va = cage.face_vertex(f, int(at(k))), vb = cage.face_vertex(f, int(at(k + 1)));
    if (face.creased) {
      const std::vector<Stencil> smooth = stencils;
      stencils = blend_by_corner(stencils, gregory_fan_stencils(cut[at(k)], cut[at(k + 1)], centre, k),
                                 std::array<double, 3>{w[at(k)], w[at(k + 1)], 0.0}, false);
      // Corner a's rows: P 0, outer edge point 1, spoke 2; corner b's: P 5, spoke 6, outer edge point 7.
      exact_corner(stencils, smooth, t, va, ctx.semi_sharp[std::size_t(va)], 0, {1, 2});
      exact_corner(stencils, smooth, t, vb, ctx.semi_sharp[std::size_t(vb)], 5, {6, 7});
    }
    if (ctx.fitted.any()) {
      ctx.fitted.fit_corner(stencils, va, 0);
      ctx.fitted.fit_corner(stencils, vb, 5);
      ctx.fitted.fit_edge(stencils, va, vb, 0, 5, 1, 7);
    }
    std::vector<CornerRing> from_k;
    for (int j = 0; j < n; ++j) from_k.push_back(rings[at(k + j)]);
    ctx.assembler.add(ctx.out.tris, f, k, PatchKind::gregory_triangle, gather_ring(from_k), stencils, fan_edges, 0, n);
  }
}

}  // namespace tessera::subdiv
