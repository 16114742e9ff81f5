// The dispatcher of build_patches: which face gets which construction (patch_construction.h lists them,
// one file each).
#include "shaders_cpp/subdiv/subd_patches.h"

#include <optional>
#include <vector>

#include "shaders_cpp/cage/topology_combinations.h"
#include "shaders_cpp/subdiv/crease_cross_rows.h"
#include "shaders_cpp/subdiv/fitted_faces.h"
#include "shaders_cpp/subdiv/patch_assembler.h"
#include "shaders_cpp/subdiv/patch_construction.h"
#include "shaders_cpp/subdiv/polar_patch.h"
#include "shaders_cpp/subdiv/semi_sharp_limit.h"

namespace tessera {

const char* to_string(Scheme s) {
  switch (s) {
    case Scheme::flat: return "flat";
    case Scheme::bspline: return "bspline";
    case Scheme::acc: return "acc";
    case Scheme::gregory: return "gregory";
    case Scheme::exact: return "exact";
    case Scheme::pn: return "pn";
    case Scheme::adaptive: return "adaptive";
  }
  return "?";
}

const char* to_string(PatchKind k) {
  switch (k) {
    case PatchKind::bilinear: return "bilinear";
    case PatchKind::linear: return "linear";
    case PatchKind::acc: return "acc";
    case PatchKind::gregory: return "gregory";
    case PatchKind::gregory_triangle: return "gregory_triangle";
    case PatchKind::polar_triangle: return "polar_triangle";
    case PatchKind::pn_triangle: return "pn_triangle";
    case PatchKind::pn_quad: return "pn_quad";
    case PatchKind::exact: return "exact";
  }
  return "?";
}

std::optional<Scheme> parse_scheme(std::string_view name) {
  for (int k = 0; k < kSchemeCount; ++k)
    if (const Scheme s = Scheme(k); name == to_string(s)) return s;
  return std::nullopt;
}

bool fits_limit(const Cage& cage, const Topology& t, Scheme scheme, int face) {
  const int m = t.face_size(face);
  if ((scheme != Scheme::gregory && scheme != Scheme::bspline && scheme != Scheme::acc) || t.is_hole(face) ||
      (m != 3 && m != 4))
    return false;
  for (int k = 0; k < m; ++k)
    if (t.has_sharpness_at(cage.face_vertex(face, k))) return true;
  return false;
}

namespace {

bool is_stencil_scheme(Scheme s) { return s == Scheme::acc || s == Scheme::gregory || s == Scheme::bspline; }

// Face f's frame: its rotation (a polar triangle starts at its pole, the corner its patch collapses to;
// a stencil scheme's face at its canonical corner, so faces of one topology combination share a table),
// whether a corner is tagged, and its edges' factor keys.
subdiv::FaceFrame face_frame(const Cage& cage, const Topology& t, int f, int polar, int rotation) {
  subdiv::FaceFrame face;
  face.cage = &cage;
  face.f = f;
  face.n = t.face_size(f);
  face.polar = polar;
  face.rot = polar >= 0 ? t.corner_of(f, polar) : rotation;
  for (int k = 0; k < face.n; ++k) face.creased |= t.has_sharpness_at(cage.face_vertex(f, k));
  if (face.n <= 4)
    for (int k = 0; k < face.n; ++k)
      face.edges[std::size_t((k + 1) % face.n)] = {cage_edge_key(face.corner(k), face.corner(k + 1)), -1};
  return face;
}

// Which construction draws a face (not a hole) under the context's scheme.
void build_face(subdiv::PatchContext& ctx, const subdiv::FaceFrame& face) {
  using namespace subdiv;
  if (!is_stencil_scheme(ctx.scheme)) return build_corner_patch(ctx, face);
  // acc: quads whose corner rings are all quads. gregory and bspline: every face; faces of other sizes
  // in a corner ring act through their virtual quad point (limit_masks.h).
  if (face.n != 4 && ctx.scheme == Scheme::acc)
    throw CageError(where(ctx.cage, face.f) + " has " + std::to_string(face.n) +
                    " sides; --scheme acc handles quads only (use --scheme gregory, adaptive, exact or flat)");
  if (face.n > 4) return build_ngon_fan(ctx, face);
  if (face.n == 3) return face.polar >= 0 ? build_polar_triangle(ctx, face) : build_gregory_triangle(ctx, face);
  if (ctx.scheme == Scheme::acc && !ctx.fitted.fitted(face.f)) return build_acc_patch(ctx, face);
  build_gregory_quad(ctx, face);
}

}  // namespace

SubdPatches build_patches(const Cage& cage, const Topology& t, Scheme scheme, std::span<const char> refit) {
  SubdPatches out;
  out.scheme = scheme;
  out.quads.domain = ts::Domain::quad;
  out.tris.domain = ts::Domain::tri;
  const bool stencil_scheme = is_stencil_scheme(scheme);
  const std::vector<int> rotation =
      stencil_scheme ? analyze_combinations(t).face_rotation : std::vector<int>(std::size_t(t.face_count()), 0);
  std::vector<std::optional<Stencil>> semi_sharp(static_cast<std::size_t>(stencil_scheme ? t.vertex_count() : 0));
  for (std::size_t v = 0; v < semi_sharp.size(); ++v)
    if (t.has_sharpness_at(int(v))) semi_sharp[v] = semi_sharp_limit_position(cage, t, int(v));
  // The triangles of polar configurations (polar_patch.h), gregory's and bspline's: per face, its pole.
  const std::vector<int> pole =
      scheme == Scheme::gregory || scheme == Scheme::bspline ? polar_poles(t) : std::vector<int>{};
  subdiv::FittedFaces fitted(cage, t, scheme, refit);
  out.refit_faces = fitted.refit_count();
  subdiv::NeighbourRows neighbours(cage, t, semi_sharp);
  subdiv::PatchAssembler assembler(cage, out);
  subdiv::PatchContext ctx{cage, t, scheme, out, assembler, semi_sharp, fitted, neighbours};
  for (int f = 0; f < t.face_count(); ++f) {
    if (t.is_hole(f)) {
      ++out.holes;
      continue;
    }
    build_face(ctx, face_frame(cage, t, f, pole.empty() ? -1 : pole[std::size_t(f)], rotation[std::size_t(f)]));
  }
  assembler.finish();
  return out;
}

}  // namespace tessera
