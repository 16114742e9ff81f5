// The dispatcher of build_patches: which face gets which construction (patch_construction.h lists them,
// one file each).
#include "shaders_cpp/subdiv/subd_patches.h"

#include <algorithm>
#include <optional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

namespace {

// A face whose patch depends on its topology combination alone (topology_combinations.h): a triangle or
// quad of a stencil scheme, not at a pole, with no tag at a corner and, where faces are fitted, neither
// fitted nor beside a fitted face or edge. Such faces of one combination, read from their canonical
// corner and reaching the same ring structure (SharedRing), have the same stencils: one table.
bool shared_by_combination(const subdiv::PatchContext& ctx, const subdiv::FaceFrame& face) {
  if (!is_stencil_scheme(ctx.scheme) || face.n < 3 || face.n > 4 || face.polar >= 0 || face.creased) return false;
  if (!ctx.fitted.any()) return true;
  if (ctx.fitted.fitted(face.f) || ctx.fitted.fits_face_points(face.f)) return false;
  for (int k = 0; k < face.n; ++k) {
    const int h = ctx.t.face_offset(face.f) + k, twin = ctx.t.twin(h);
    if (twin >= 0 && ctx.fitted.fitted(ctx.t.face(twin))) return false;
    if (ctx.fitted.is_fitted_edge(cage_edge_key(face.corner(k), face.corner(k + 1)))) return false;
  }
  return true;
}

// The IA patch of a face shared_by_combination (gather_ring's), and where each vertex the traversal
// reaches landed in it. Faces of one combination reach their vertices in the same traversal; with the
// same landing places, their rings have the same structure, global coincidences (a vertex reached from
// two corners, as round a small cage) included, so the stencils over them give one table.
struct SharedRing {
  std::vector<int> ring;
  std::vector<std::uint8_t> landed;
};
SharedRing shared_ring(const subdiv::PatchContext& ctx, const subdiv::FaceFrame& face) {
  SharedRing out;
  subdiv::gather_ring_landing(ctx.cage, ctx.t, face, out.ring, {}, &out.landed);
  return out;
}

// What a combination's first face made: its table and kind, its ring's structure, and whether bspline
// counts it as a fallback face.
struct SharedPatch {
  int table = -1;
  PatchKind kind = PatchKind::gregory;
  std::vector<std::uint8_t> landed;
  bool fallback = false;
};

}  // namespace

SubdPatches build_patches(const Cage& cage, const Topology& t, Scheme scheme, std::span<const char> refit,
                          PatchBuild build) {
  SubdPatches out;
  out.scheme = scheme;
  out.quads.domain = ts::Domain::quad;
  out.tris.domain = ts::Domain::tri;
  const bool stencil_scheme = is_stencil_scheme(scheme);
  TopologyCombinations combinations;
  if (stencil_scheme) combinations = analyze_combinations(t);
  const std::vector<int>& rotation = combinations.face_rotation;
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
  // In face order, each face's patches are built, or, when its combination's patch is known, its place
  // is reserved and filled below, in parallel: per face only its ring is gathered.
  std::vector<std::optional<SharedPatch>> shared(combinations.combinations.size());
  const auto frame_of = [&](int f) {
    return face_frame(cage, t, f, pole.empty() ? -1 : pole[std::size_t(f)], stencil_scheme ? rotation[std::size_t(f)] : 0);
  };
  // Whether each face's combination decides its patch: a pure function of the face (the fitted faces
  // are known before any is built), found in parallel.
  const int nf = t.face_count();
  std::vector<char> sharable(std::size_t(nf), 0);
  if (build == PatchBuild::by_combination && stencil_scheme)
    tbb::parallel_for(tbb::blocked_range<int>(0, nf, 4096), [&](const tbb::blocked_range<int>& range) {
      for (int f = range.begin(); f < range.end(); ++f)
        if (!t.is_hole(f)) sharable[std::size_t(f)] = shared_by_combination(ctx, frame_of(f));
    });
  struct Deferred {
    int face, slot;
    const SharedPatch* patch;
  };
  std::vector<Deferred> deferred;
  {  // Storage for every patch at once: grown copies of a large cage's patches cost as much as building them.
    std::size_t quads = 0, tris = 0;
    for (int f = 0; f < nf; ++f) {
      const int n = t.face_size(f);
      if (t.is_hole(f)) continue;
      (n == 4 ? quads : tris) += std::size_t(n == 4 || n == 3 ? 1 : n);
    }
    out.quads.patches.reserve(quads);
    out.tris.patches.reserve(tris);
    assembler.reserve_slots(quads + tris);
    deferred.reserve(quads + tris);
  }
  for (int f = 0; f < nf; ++f) {
    if (t.is_hole(f)) {
      ++out.holes;
      continue;
    }
    const bool share = sharable[std::size_t(f)] != 0;
    std::optional<SharedPatch> unshared;
    std::optional<SharedPatch>& known = share ? shared[std::size_t(combinations.face_combination[std::size_t(f)])] : unshared;
    if (share && known) {
      deferred.push_back({f, assembler.reserve(t.face_size(f) == 4 ? out.quads : out.tris), &*known});
      if (known->fallback) ++out.fallback_faces;
      continue;
    }
    const subdiv::FaceFrame face = frame_of(f);
    const int fallback_before = out.fallback_faces;
    build_face(ctx, face);
    if (!share) continue;
    const PatchGroup& group = face.n == 4 ? out.quads : out.tris;
    const SubdPatch& p = group.patches.back();
    if (p.face != f || p.precomputed >= 0 || p.averaged_edges != 0 || p.limit_corners != 0 || p.table < 0) continue;
    if (SharedRing r = shared_ring(ctx, face); r.ring.size() == std::size_t(p.ring_size))
      known = SharedPatch{p.table, p.kind, std::move(r.landed), out.fallback_faces != fallback_before};
  }
  // The reserved faces: their rings, in parallel. A ring whose structure differs from the combination's
  // (a global coincidence the key cannot see) is built in full afterwards, in face order.
  std::vector<char> folded(deferred.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, deferred.size(), 256), [&](const auto& range) {
    std::vector<int> ring;
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const Deferred& d = deferred[i];
      const subdiv::FaceFrame face = frame_of(d.face);
      ring.clear();
      ring.reserve(d.patch->landed.size());
      if (!subdiv::gather_ring_landing(cage, t, face, ring, d.patch->landed)) {
        folded[i] = 1;
        continue;
      }
      assembler.place(d.slot, face.f, d.patch->kind, std::move(ring), d.patch->table, face.edges, face.rot);
    }
  });
  for (std::size_t i = 0; i < deferred.size(); ++i) {
    if (!folded[i]) continue;
    if (deferred[i].patch->fallback) --out.fallback_faces;  // build_face counts it again
    assembler.add_into(deferred[i].slot);
    build_face(ctx, frame_of(deferred[i].face));
  }
  assembler.finish();
  return out;
}

}  // namespace tessera
