// A quad under acc that is not fitted to the limit (a fitted quad is build_gregory_quad's): Loop and
// Schaefer's approximate Catmull-Clark patch, 16 bicubic Bezier points and the tangent patches' 24
// (patch_stencils.h, acc_quad_stencils), blended at its creases (crease_blend.h).
//
// Contract: beside a fitted face its boundary is that face's: a fitted edge takes the fitted points, an
// unfitted edge shared with a fitted face takes that face's Gregory edge points (their corners are
// already the same rows: the limit position of the same rings, unblended at untagged vertices), and
// the tangent patch's three points along such an edge become the new boundary's derivative. So it is
// watertight to every neighbour under any factors.
#include "shaders_cpp/subdiv/crease_blend.h"
#include "shaders_cpp/subdiv/patch_construction.h"
#include "shaders_cpp/subdiv/patch_stencils.h"

namespace tessera::subdiv {
namespace {

// The geometry rows along patch edge k from its first corner; the tangent rows along it, and their sign
// (d/du or d/dv runs backward on edges 2 and 3). ACC's own boundary rows are that derivative: the
// corners' limit tangents are 3 (E - P).
constexpr std::size_t kAlong[4][4] = {{0, 1, 2, 3}, {3, 7, 11, 15}, {15, 14, 13, 12}, {12, 8, 4, 0}};
constexpr std::size_t kTangent[4][3] = {{16, 17, 18}, {31, 35, 39}, {27, 26, 25}, {36, 32, 28}};
constexpr double kSign[4] = {1.0, 1.0, -1.0, -1.0};
// The corner points b(0,0), b(3,0), b(3,3), b(0,3).
constexpr std::size_t kCornerRow[4] = {0, 3, 15, 12};

// Patch edge k's Bezier points (rows a) from the fitted face across it, when the edge is not fitted.
void gregory_edge(PatchContext& ctx, const FaceFrame& face, std::vector<Stencil>& rows, int k,
                  const std::size_t (&a)[4]) {
  const Topology& t = ctx.t;
  const int h = t.face_offset(face.f) + (k + face.rot) % 4, twin = t.twin(h);
  if (twin < 0 || !ctx.fitted.fitted(t.face(twin))) return;
  if (ctx.fitted.is_fitted_edge(cage_edge_key(face.corner(k), face.corner(k + 1)))) return;
  const int g = t.face(twin), m = t.face_size(g), j = twin - t.face_offset(g);
  const std::vector<Stencil>& gr = ctx.neighbours.of(g);
  rows[a[1]] = gr[std::size_t(5 * ((j + 1) % m) + 2)];
  rows[a[2]] = gr[std::size_t(5 * j + 1)];
}

}  // namespace

void build_acc_patch(PatchContext& ctx, const FaceFrame& face) {
  const FaceRings<4> rings = face_rings<4>(ctx, face);
  std::vector<Stencil> stencils = acc_quad_stencils(rings.whole);
  if (face.creased) {
    stencils = blend_by_corner(stencils, acc_quad_stencils(rings.cut), rings.weight, true);
    // A semi-sharp vertex's corner point is its exact limit; ACC's edge points and tangent patches keep
    // the blend (moving them would need the tangent patches moved with them).
    for (int k = 0; k < 4; ++k)
      if (const std::optional<Stencil>& p = ctx.semi_sharp[std::size_t(face.corner(k))]) stencils[kCornerRow[k]] = *p;
  }
  if (ctx.fitted.any()) {
    for (int k = 0; k < 4; ++k) {
      const auto& a = kAlong[k];
      const std::array<Stencil, 4> before = {stencils[a[0]], stencils[a[1]], stencils[a[2]], stencils[a[3]]};
      ctx.fitted.fit_edge(stencils, face.corner(k), face.corner(k + 1), a[0], a[3], a[1], a[2]);
      gregory_edge(ctx, face, stencils, k, a);
      if (stencils[a[1]].terms == before[1].terms && stencils[a[2]].terms == before[2].terms) continue;
      for (std::size_t i = 0; i < 3; ++i)
        stencils[kTangent[k][i]] = (3.0 * kSign[k]) * (stencils[a[i + 1]] - stencils[a[i]]);
    }
  }
  add_creased(ctx, face, ctx.out.quads, PatchKind::acc, gather_ring(rings.whole), stencils);
}

}  // namespace tessera::subdiv
