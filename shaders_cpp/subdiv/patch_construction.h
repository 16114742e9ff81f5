// What build_patches' constructions share: the context of one build (the cage, its tags' exact
// corners, the fitted faces, the neighbours' rows, where patches go), one face as a construction sees
// it (FaceFrame), the steps its triangle and quad constructions have in common, and one builder per
// construction, each defined in the file named after it:
//
//   corner_patch.cpp      flat, exact, adaptive and pn: the face's corners are the IA patch
//   gregory_quad.cpp      gregory's quads, and bspline's (a regular face's Gregory patch is its B-spline patch)
//   acc_patch.cpp         acc's quads: Bezier points and tangent patches
//   gregory_triangle.cpp  gregory's and bspline's triangles
//   polar_triangle.cpp    a triangle at a pole (polar_patch.h)
//   ngon_fan.cpp          a face of five or more sides: a fan of Gregory triangles
//
// Contract: a builder appends the patches of face `face.f` to ctx.assembler in the order the face's
// domain needs (a fan's triangles k = 0..n-1), changes nothing of another face, and throws a CageError
// naming the face when the scheme cannot draw it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/corner_ring.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/crease_cross_rows.h"
#include "shaders_cpp/subdiv/fitted_faces.h"
#include "shaders_cpp/subdiv/patch_assembler.h"
#include "shaders_cpp/subdiv/stencil.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera::subdiv {

// "cage.obj: face 12", the start of an error about a face.
inline std::string where(const Cage& cage, int face) { return cage.name + ": face " + std::to_string(face); }

struct PatchContext {
  const Cage& cage;
  const Topology& t;
  Scheme scheme;
  SubdPatches& out;
  PatchAssembler& assembler;
  // The exact limit at each semi-sharp vertex (semi_sharp_limit.h), once per vertex, so every face
  // around it puts the same bits at its corner; empty for the schemes without stencils.
  const std::vector<std::optional<Stencil>>& semi_sharp;
  FittedFaces& fitted;
  NeighbourRows& neighbours;
};

// Face f as its patches see it: patch corner k is face corner k + rot.
struct FaceFrame {
  const Cage* cage = nullptr;
  int f = 0, n = 0;
  int rot = 0;
  int polar = -1;        // the pole vertex of a triangle in a polar configuration, else -1
  bool creased = false;  // a corner carries a tag: built smooth and cut open, blended (crease_blend.h)
  // Edge keys in SV_TessFactor order: patch edge k (corner k -> k+1) is factor (k + 1) % n (n <= 4).
  std::array<EdgeFactorKey, 4> edges{};

  int corner(int k) const { return cage->face_vertex(f, (((k + rot) % n) + n) % n); }
  // The face's corners from patch corner `first` on: the IA patch of a patch made of the face alone.
  std::vector<int> corners_from(int first) const;
};

// The IA patch: the patch's corners in order, then each corner's ring vertices not yet listed (edge
// neighbours and far vertices, counter-clockwise from the face). `landed`, when given, gets for each
// vertex the traversal reaches (listed or not) its position in the IA patch (at most 255): the ring's
// structure, global coincidences included.
std::vector<int> gather_ring(std::span<const CornerRing> rings, std::vector<std::uint8_t>* landed = nullptr);
// gather_ring of the face's whole corner rings (face_rings' `whole`), traversed in place with no
// allocation but the ring itself: `ring` gets the IA patch. With `record`, the landing places are
// appended there; otherwise the result says whether they equal `landed` (false stops it early; `ring`
// is then incomplete).
bool gather_ring_landing(const Cage& cage, const Topology& t, const FaceFrame& face, std::vector<int>& ring,
                         std::span<const std::uint8_t> landed, std::vector<std::uint8_t>* record = nullptr);

// The SV_TessFactor keys of fan triangle k of face f (vertex k, vertex k + 1, centre): Ueq0 is the spoke
// to vertex k, keyed by the two cage edges there; Veq0 the cage edge k -> k+1; Weq0 the spoke to
// vertex k + 1. Both triangles beside a spoke name its two edges in the same order.
std::array<EdgeFactorKey, 4> fan_edge_keys(const Cage& cage, int f, int k);

// Whether every corner of a quad is an interior, untagged vertex of four quads (bspline's own patch).
bool is_regular_face(const Topology& t, const std::array<CornerRing, 4>& rings);

// The corner rings of a triangle or quad from patch corner 0, and when the face is creased, the rings
// cut open at its creases with each corner's blend weight (crease_blend.h).
template <std::size_t N>
struct FaceRings {
  std::array<CornerRing, N> whole, cut;
  std::array<double, N> weight{};
};
template <std::size_t N>
FaceRings<N> face_rings(const PatchContext& ctx, const FaceFrame& face);

// The fitted corner and edge points of a triangle's or quad's rows (fitted_faces.h).
void fit_boundary(PatchContext& ctx, const FaceFrame& face, std::vector<Stencil>& stencils);
// Which patch edges are smooth (interior, untagged): those fit the limit's cross derivative too.
template <std::size_t N>
std::array<bool, N> smooth_edges(const Topology& t, const FaceFrame& face);
// exact_corner at each of the patch's `corners` corners (five rows each).
void exact_corners(const PatchContext& ctx, const FaceFrame& face, std::vector<Stencil>& stencils,
                   const std::vector<Stencil>& smooth, int corners);
// Adds a triangle's or quad's patch with its crease edges' cross rows (none on a smooth face) and, on
// a fitted face, the limit's derivatives at its corners (SubdPatch::limit_corners).
void add_creased(PatchContext& ctx, const FaceFrame& face, PatchGroup& group, PatchKind kind,
                 const std::vector<int>& ring, std::vector<Stencil>& stencils);

void build_corner_patch(PatchContext& ctx, const FaceFrame& face);
void build_gregory_quad(PatchContext& ctx, const FaceFrame& face);
void build_acc_patch(PatchContext& ctx, const FaceFrame& face);
void build_gregory_triangle(PatchContext& ctx, const FaceFrame& face);
void build_polar_triangle(PatchContext& ctx, const FaceFrame& face);
void build_ngon_fan(PatchContext& ctx, const FaceFrame& face);

}  // namespace tessera::subdiv
