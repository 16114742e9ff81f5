// Turns a cage into patch draws for one subdivision scheme: per face its IA patch (the face with its
// 1-ring, at most 32 control points), and per topology combination one stencil table that the hull
// shader (subd_shaders.h) applies to that 1-ring. A face whose 1-ring is larger than a D3D11 patch's 32
// control points (beside a vertex of high valence) is precomputed instead: its IA patch is the face's
// corners, and its hull-shader control points come from a pre-pass at control-point rate
// (control_point_prepass.h), as GPU engines do with a compute pass before the draw.
//
// Contract
// - Every non-hole face becomes patches in face order within each domain: a quad one quad-domain patch;
//   a triangle one tri-domain patch (every scheme but `acc`); and, for `flat` and `exact`, a face of
//   n > 4 sides n tri-domain patches, its fan: triangle k = (vertex k, vertex k+1, centre) with u = 1 at
//   vertex k+1 and v = 1 at the centre (limit_surface.h states how `exact` maps it onto the face's
//   surface). The fan's outer edge is the whole cage edge, so every cage edge is tessellated as one edge
//   on both of its sides.
// - Tables are deduplicated by content: faces whose 1-rings have the same structure share one table
//   (the talk's topology combinations); `tables.size()` is how many distinct ones the cage needs.
// - A patch's `order` lists its ring positions sorted by cage vertex index: the hull shader sums in
//   that order, so shared control points come out bit-identical on both patches (stencil.h).
// - Precomputed patches (acc, gregory, bspline) sum their stencil rows over the whole 1-ring in the
//   same order and arithmetic as the hull shader (ascending vertex index, zero weights skipped, double,
//   rounded once), so a point they share with an ordinary neighbour has the neighbour's bits.
// - Faces a scheme cannot handle give a CageError naming the face and why (a triangle for acc, an
//   n-gon for gregory or pn, ...). `bspline` draws faces that are not
//   regular as Gregory patches (triangles as triangular Gregory patches) and counts them in
//   `fallback_faces`.
// - `pn` patches are the face's corners only (no table): the hull shader builds the PN points from
//   the corners' positions and the per-vertex normals SubdVS passes along (pn_patch.h).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"
#include "tessellator/tessellator.h"

namespace tessera {

class LimitSurface;

enum class Scheme : std::uint8_t { flat, bspline, acc, gregory, exact, pn, adaptive };
inline constexpr int kSchemeCount = int(Scheme::adaptive) + 1;  // every Scheme is in 0..kSchemeCount-1
std::optional<Scheme> parse_scheme(std::string_view name);
const char* to_string(Scheme s);
// exact and adaptive: the domain shader evaluates a LimitSurface (PatchKind::exact), made by create()
// or create_adaptive().
inline bool uses_limit_surface(Scheme s) { return s == Scheme::exact || s == Scheme::adaptive; }

// How the domain shader evaluates a patch.
enum class PatchKind : std::uint8_t {
  bilinear,          // 4 corners (flat quads)
  linear,            // 3 corners (flat triangles and the fan triangles of n-gons)
  acc,               // 16 Bezier points + tangent patches (control points carry du/dv)
  gregory,           // 20 Gregory points (also bspline's regular faces, where it is the B-spline patch)
  gregory_triangle,  // 15 triangular Gregory points (quartic, cubic boundaries) on the tri domain
  polar_triangle,    // a triangle at a pole (polar_patch.h): a bicubic with a collapsed row, in the 15 slots
  pn_triangle,       // PN triangle: 10 cubic Bezier points, 6 normal coefficients, from the corners
  pn_quad,           // PN quad: 16 bicubic Bezier points, 9 normal coefficients, from the corners
  exact,             // the limit surface (limit_surface.h; exact or adaptive), evaluated per domain point
};
const char* to_string(PatchKind k);  // "gregory_triangle", as the enumerator

inline constexpr int kMaxPatchControlPoints = 32;

// Key of the cage edge between vertices a and b (either order), so both faces on it compute the same.
inline std::int64_t cage_edge_key(int a, int b) {
  const std::int64_t lo = a < b ? a : b, hi = a < b ? b : a;
  return (lo << 31 | hi) << 1;
}

// Where a domain edge's tessellation factor comes from, named by cage edge keys so that the two patches
// on an edge compute the same factor: a cage edge names itself (`b` = -1); a spoke of an n-gon's fan
// (centre to vertex v) names the face's two cage edges at v, previous edge first, and takes the mean of
// their factors (the same sum on both fan triangles that share the spoke). `a` = -1: the base factor.
struct EdgeFactorKey {
  std::int64_t a = -1, b = -1;
  friend bool operator==(const EdgeFactorKey&, const EdgeFactorKey&) = default;
};

struct StencilTable {
  int rows = 0, ring = 0;
  std::vector<float> weights;  // rows x ring, row-major
  friend bool operator==(const StencilTable&, const StencilTable&) = default;
};

struct SubdPatch {
  int face = 0;
  int sub = 0;     // fan triangle k of a face of more than four sides (0 otherwise)
  int table = -1;  // into SubdPatches::tables, -1 for exact
  PatchKind kind = PatchKind::gregory;
  int ring_size = 0;
  std::uint8_t rotation = 0;      // patch corner k is face corner (k + rotation) % (3 or 4)
  std::int32_t precomputed = -1;  // its first row in the pre-pass's points (a 1-ring over 32), or -1
  std::array<std::uint8_t, kMaxPatchControlPoints> order{};  // ring positions by ascending vertex index
  // Per domain edge in SV_TessFactor order (quad: Ueq0, Veq0, Ueq1, Veq1; tri: Ueq0, Veq0, Weq0). A fan
  // triangle's Veq0 is its cage edge, Ueq0 the spoke to vertex k, Weq0 the spoke to vertex k+1.
  std::array<EdgeFactorKey, 4> edge_keys{};
  // acc, gregory and bspline: bit k set when patch edge k -> k+1 is a semi-sharp crease (finite sharpness, at
  // least kCutSharpness) with a triangle or quad across it. The exact limit there is smooth on the crease
  // line itself (one normal, about the mean of the two sides') and creased a band of width 2^-s away, so
  // the domain shader gives points on that edge the mean of this patch's normal and the neighbour's,
  // from the neighbour's inward cross derivative: four more table rows per edge (kCrossRows). Also set
  // on a smooth edge between two fitted faces with a tag at one end (always a limit edge, below).
  std::uint8_t averaged_edges = 0;
  // The averaged edges whose rows are the exact limit's derivative into the neighbour (limit_fit.h),
  // not the neighbour's patch: the limit is smooth across a semi-sharp crease or a smooth edge, so that
  // derivative gives the limit's own normal on the line, which the domain shader takes alone.
  std::uint8_t limit_edges = 0;
  // A fitted face (limit_fit.h): bit k set when patch corner k carries the limit's two derivatives there,
  // in the face's frame (two rows per corner, after the patch's own rows and any kCrossRows rows), whose
  // cross product is the normal the domain shader gives that corner.
  std::uint8_t limit_corners = 0;
  friend bool operator==(const SubdPatch&, const SubdPatch&) = default;
};

// The rows a patch with averaged edges adds after its own (20 for a quad, 15 for a triangle): per patch
// edge k, the Bezier coefficients of the neighbour's inward cross derivative along it, from corner k.
inline constexpr int kCrossRows = 4;

struct PatchGroup {
  ts::Domain domain = ts::Domain::quad;
  int control_points = 0;              // per patch in `indices` (the largest ring, padded)
  std::vector<std::uint32_t> indices;  // control_points per patch: the ring, then repeats of ring[0]
  std::vector<SubdPatch> patches;
  std::size_t size() const { return patches.size(); }
};

// A patch whose 1-ring is larger than an IA patch holds: its stencil rows over the ring's cage
// vertices, in ascending vertex order.
struct PrecomputedPatch {
  int rows = 0;
  std::vector<int> vertices;   // ascending
  std::vector<float> weights;  // rows x vertices, row-major
};

struct SubdPatches {
  Scheme scheme = Scheme::gregory;
  std::vector<StencilTable> tables;
  PatchGroup quads, tris;
  std::vector<PrecomputedPatch> precomputed;  // in the order of their rows (SubdPatch::precomputed)
  int precomputed_rows = 0;                   // the pre-pass's point count
  int fallback_faces = 0;
  int refit_faces = 0;  // untagged faces fitted to the limit because their masks' patch folds (`refit`)
  int holes = 0;  // faces that draw nothing: hole tags (and, for exact, faces without a limit surface)
};

// `refit`, when not empty (one entry per face): faces whose masks' patch folds (beside a
// valence-2 vertex, a cusp; strayed_faces.h finds them), fitted to the limit under gregory,
// bspline and acc as a tagged face is: its edges and face points (fitted_faces.h).
// How faces a topology combination decides are built: the combination's first face in full, the rest
// from its table, their rings gathered in parallel (by_combination); or every face in full (per_face,
// for tests: the same patches, tables and indices, slower).
enum class PatchBuild : std::uint8_t { by_combination, per_face };
SubdPatches build_patches(const Cage& cage, const Topology& topology, Scheme scheme,
                          std::span<const char> refit = {}, PatchBuild build = PatchBuild::by_combination);

// Whether build_patches fits face f to the exact limit (limit_fit.h): under gregory, bspline and acc
// (which draws it as that Gregory patch, its face points coinciding), a triangle or quad, not a hole,
// with a tagged corner (unless OpenSubdiv has no surface for it, when it
// keeps the masks' construction).
bool fits_limit(const Cage& cage, const Topology& topology, Scheme scheme, int face);

}  // namespace tessera
