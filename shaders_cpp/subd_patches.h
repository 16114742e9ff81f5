// Turns a cage into patch draws for one subdivision scheme: per face its IA patch (the face with its
// 1-ring, at most 32 control points), and per topology combination one stencil table that the hull
// shader (subd_shaders.h) applies to that 1-ring.
//
// Contract
// - Every non-hole face becomes one patch (quads; triangles on the tri domain for every scheme but
//   `acc`; for `flat` and `exact` the n quad sub-patches of an n-gon); patches are in face order within
//   each domain.
// - Tables are deduplicated by content: faces whose 1-rings have the same structure share one table
//   (the talk's topology combinations); `tables.size()` is how many distinct ones the cage needs.
// - A patch's `order` lists its ring positions sorted by cage vertex index: the hull shader sums in
//   that order, so shared control points come out bit-identical on both patches (stencil.h).
// - Faces a scheme cannot handle give a CageError naming the face and why (a triangle for acc, an
//   n-gon for gregory or pn, a 1-ring of more than 32 vertices, ...). `bspline` draws faces that are not
//   regular as Gregory patches (triangles as triangular Gregory patches) and counts them in
//   `fallback_faces`.
// - `pn` patches are the face's corners only (no table): the hull shader builds the PN points from
//   the corners' positions and the per-vertex normals SubdVS passes along (pn_patch.h).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cage.h"
#include "tessellator.h"
#include "topology.h"

namespace tessera {

class LimitSurface;

enum class Scheme : std::uint8_t { flat, bspline, acc, gregory, exact, pn };
std::optional<Scheme> parse_scheme(std::string_view name);
const char* to_string(Scheme s);

// How the domain shader evaluates a patch.
enum class PatchKind : std::uint8_t {
  bilinear,  // 4 corners (flat quads and n-gon sub-quads)
  linear,    // 3 corners (flat triangles)
  acc,       // 16 Bezier points + tangent patches (control points carry du/dv)
  gregory,   // 20 Gregory points (also bspline's regular faces, where it is the B-spline patch)
  gregory_triangle,  // 15 triangular Gregory points (quartic, cubic boundaries) on the tri domain
  pn_triangle,       // PN triangle: 10 cubic Bezier points, 6 normal coefficients, from the corners
  pn_quad,           // PN quad: 16 bicubic Bezier points, 9 normal coefficients, from the corners
  exact,     // the limit surface (limit_surface.h), evaluated per domain point
};

inline constexpr int kMaxPatchControlPoints = 32;

// Key of the cage edge between vertices a and b (either order), so both faces on it compute the same.
inline std::int64_t cage_edge_key(int a, int b) {
  const std::int64_t lo = a < b ? a : b, hi = a < b ? b : a;
  return (lo << 31 | hi) << 1;
}
// Key of the half of edge (a, b) at a (n-gon sub-patches): odd, and different from (b, a)'s half.
inline std::int64_t half_edge_key(int a, int b) { return (std::int64_t(a) << 31 | b) << 1 | 1; }
// The full edge a half-edge key lies on.
inline std::int64_t full_edge_key(std::int64_t key) {
  if (key < 0 || (key & 1) == 0) return key;
  const std::int64_t x = key >> 1;
  return cage_edge_key(int(x >> 31), int(x & 0x7fffffff));
}

struct StencilTable {
  int rows = 0, ring = 0;
  std::vector<float> weights;  // rows x ring, row-major
};

struct SubdPatch {
  int face = 0;
  int sub = 0;                 // n-gon sub-patch (0 otherwise)
  int table = -1;              // into SubdPatches::tables, -1 for exact
  PatchKind kind = PatchKind::gregory;
  int ring_size = 0;
  std::uint8_t rotation = 0;   // patch corner k is face corner (k + rotation) % (3 or 4)
  std::array<std::uint8_t, kMaxPatchControlPoints> order{};  // ring positions by ascending vertex index
  // Per domain edge in SV_TessFactor order (quad: Ueq0, Veq0, Ueq1, Veq1; tri: Ueq0, Veq0, Weq0): a key
  // naming the cage edge (or half of it, for n-gon sub-patches) so both sides pick the same factor; -1
  // for edges inside an n-gon.
  std::array<std::int64_t, 4> edge_keys{-1, -1, -1, -1};
};

struct PatchGroup {
  ts::Domain domain = ts::Domain::quad;
  int control_points = 0;              // per patch in `indices` (the largest ring, padded)
  std::vector<std::uint32_t> indices;  // control_points per patch: the ring, then repeats of ring[0]
  std::vector<SubdPatch> patches;
  std::size_t size() const { return patches.size(); }
};

struct SubdPatches {
  Scheme scheme = Scheme::gregory;
  std::vector<StencilTable> tables;
  PatchGroup quads, tris;
  int fallback_faces = 0;
  int holes = 0;
};

SubdPatches build_patches(const Cage& cage, const Topology& topology, Scheme scheme);

}  // namespace tessera
