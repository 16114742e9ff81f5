// The Catmull-Clark limit surface of a Cage, evaluated through OpenSubdiv, by one of two methods:
// - create(): the exact surface through Bfr (Far for the faces 3.5.0's Bfr fails on). It is the
//   domain-shader evaluator of the `exact` scheme and the reference for accuracy measurements.
// - create_adaptive(): the `adaptive` scheme, feature-adaptive patches to an isolation level through
//   Far (B-spline, boundary, single-crease and Gregory end-cap patches, far_patches.h); exact to
//   round-off on regular and single-crease regions and converging to the limit as the level rises.
// Both give the same domains, ownership and contract below; they differ in the surface between.
//
// Contract
// - Domains follow D3D11 patches.
//   * Quad face: corners 0,1,2,3 <-> (u,v) = (0,0),(1,0),(1,1),(0,1); sub_patch must be 0.
//   * Any other face of n vertices (triangles included) is, in OpenSubdiv's own parameterization, n
//     quad sub-patches: sub-patch k has corners (vertex k, midpoint of edge k->k+1, face centre,
//     midpoint of edge k-1->k) <-> (0,0),(1,0),(1,1),(0,1). Derivatives are with respect to the
//     sub-patch's own (u,v). `evaluate` and `sample_reference` take this domain.
//   * Triangle face, barycentric: `evaluate_triangle(face, u, v, w)` with w = (1-u)-v; corner 0 <-> w=1,
//     corner 1 <-> u=1, corner 2 <-> v=1. Derivatives are d/du and d/dv with w = 1-u-v. Inside, the
//     point is mapped to the quad sub-patch of the nearest corner (the largest barycentric) by the
//     inverse of that sub-patch's bilinear map; the surface is the same, only the parameterization
//     differs from the sub-patch one.
//   * Fan triangle k of a face of n != 4 vertices (how faces of more than four sides are drawn):
//     `evaluate_fan(face, k, u, v, w)`, vertex k <-> w=1, vertex k+1 <-> u=1, face centre <-> v=1, so
//     its v = 0 edge is the whole cage edge k -> k+1 at parameter u. The map into the sub-patches is
//     piecewise affine (fan_location): with x = 2u + v, the half x <= 1 (vertex k, midpoint of edge k,
//     centre) is sub-patch k at (x, v); the half x > 1 is sub-patch k+1 at (v, 2 - x). The spokes
//     (centre, vertex k) are the diagonals of sub-patch k, reached at the same (s, t) from both
//     triangles that share them. Derivatives are d/du and d/dv of the triangle; the normal is the
//     sub-patch's (the same bits from both sides of a spoke).
// - Normals are normalize(du x dv), pointing outward for counter-clockwise faces (flipped when the
//   cage is tagged left-handed, so they point outward there too).
// - Watertight, bitwise: the position and the normal of a point exactly on a cage vertex, on a cage
//   edge, or on an edge between two sub-patches of one face are computed once, by the element's owner,
//   so every face (and sub-patch) that shares the point gets the same bits. Owners: a cage vertex's
//   limit is taken from the lowest-index face with a surface that uses it; a cage edge belongs to the
//   lowest-index face with a surface that uses it (its first occurrence there), evaluated at the same
//   point of the edge (t <-> 1-t where the faces run the edge opposite ways, exact for tessellator
//   parameters, which are multiples of 2^-16); a face centre belongs to sub-patch 0 at (1,1); the edge
//   between sub-patches k and k+1 belongs to sub-patch k (its u = 1 side). A fan spoke needs no owner:
//   both triangles evaluate the same sub-patch at the same (s, t), bit for bit (tessellator parameters
//   are multiples of 2^-16, so 2 - (2u + v) = v exactly when u = 1 - v). du and dv are always this
//   face's own derivatives (they are not shared: the two faces parameterize the edge differently).
// - Thread-safe and allocation-free after create(): everything per face is precomputed; evaluation
//   only reads. Internally double precision; results are rounded to float once.
// - Faces without a limit surface (holes; boundary faces under boundary interpolation "none") have
//   0 sub-patches; evaluating them, or a face/sub-patch index out of range, or a coordinate outside
//   [0,1] (or NaN) throws std::out_of_range with a one-line message. create() validates the cage as
//   the topology does (validate_cage, topology.h) and then checks OpenSubdiv's own limits (face size,
//   valence); both throw a one-line CageError.
#pragma once

#include <cmath>

#include <glm/vec3.hpp>
#include <glm/vec2.hpp>
#include <glm/ext/vector_double3.hpp>

#include <cstdint>
#include <memory>
#include <span>

#include "shaders_cpp/cage/cage.h"

namespace tessera {

struct SurfacePoint {
  glm::vec3 position{0.0f};
  glm::vec3 du{0.0f}, dv{0.0f};  // this face's own parametric derivatives
  glm::vec3 normal{0.0f};        // unit, outward
};

// The accuracy command's reference sample: the same point in double precision, without rounding.
struct ReferenceSample {
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0};
};

// Above this valence the exact surface is costly to build: OpenSubdiv's work around a vertex grows as
// about valence^2.4 (128: about 0.2 s; 360: 2.5 s; 800: 18 s). Any valence OpenSubdiv takes is drawn;
// make_subd_model warns with the estimate (exact_build_seconds) above this one.
inline constexpr int kCostlyExactValence = 128;
// The estimated seconds to build the exact surface around one vertex of valence `valence`.
inline double exact_build_seconds(int valence) { return 0.2 * std::pow(double(valence) / 128.0, 2.4); }

// The adaptive method's patch at a point (patch_at), for the patch-type view and statistics.
enum class AdaptivePatchKind : std::uint8_t { regular, boundary, single_crease, end_cap };
inline constexpr int kAdaptivePatchKinds = 4;
const char* to_string(AdaptivePatchKind k);

// The isolation levels the adaptive method takes (Far's maximum is 10) and its default, chosen for
// accuracy: at 7 every OpenSubdiv shape is as close to the exact limit as gregory draws it or closer
// (at 4, six creased shapes were farther: cube_creases1 6.5e-3 of the diagonal against 2.3e-3), the
// worst within 5.2e-4. The cost is patches and memory near features (the frog: 23,456 patches, 4.5 MB
// against 13,520 and 2.8 MB at 4), not frame time. scripts/shape_numbers.sh measures it.
inline constexpr int kMaxIsolation = 10;
inline constexpr int kDefaultIsolation = 7;

class LimitSurface {
 public:
  // Bfr represents the surface exactly (B-spline patches) except within 2^-level (in face
  // parameter) of extraordinary vertices and semi-sharp features, where it closes with Gregory
  // patches. At 10, OpenSubdiv's maximum, every point farther than 1/1024 from such a vertex is
  // exact to double round-off; closer points carry a small error (measured in README.md here,
  // "Exact limit surface").
  static constexpr int kDefaultApproxLevel = 10;
  static constexpr int kMaxApproxLevel = 10;  // OpenSubdiv 3.5 crashes above 10

  // Throws CageError (one line) for cages that fail validate_cage or exceed OpenSubdiv's limits, or
  // whose limit is not finite; std::invalid_argument for a level outside
  // 1..kMaxApproxLevel.
  static LimitSurface create(const Cage& cage, int approx_level = kDefaultApproxLevel);
  // The adaptive method at `isolation` (1..kMaxIsolation; std::invalid_argument outside); the same
  // CageErrors as create().
  static LimitSurface create_adaptive(const Cage& cage, int isolation);

  // The same cage with its vertices moved (an animation's pose; one position per cage vertex): only
  // what depends on the points is recomputed (Bfr's patch points, Far's points through its kept
  // stencils, each vertex's owned limit, the bounds), so a pose costs a fraction of create() and gives
  // the bits a surface created from the moved cage would. The same CageErrors as create() for a limit
  // that is not finite; a failed TESSERA_CHECK for a wrong count.
  void repose(std::span<const glm::vec3> positions);

  LimitSurface(LimitSurface&&) noexcept;
  LimitSurface& operator=(LimitSurface&&) noexcept;
  ~LimitSurface();

  int face_count() const;
  int face_size(int face) const;
  bool has_surface(int face) const;
  // 1 for a quad, n for any other n-gon, 0 for a face without a surface.
  int sub_patch_count(int face) const;
  // create()'s approximation level, or create_adaptive()'s isolation level.
  int approx_level() const;
  bool adaptive() const;

  // The adaptive method only (a failed TESSERA_CHECK otherwise): the patch evaluate() uses at a point given as
  // the domain shader's face frame (a quad's (u,v), a triangle's barycentric (u,v), or fan triangle
  // `sub` of a larger face; coordinates clamped to [0,1]), and the patch table's counts.
  struct PatchFacts {
    AdaptivePatchKind kind = AdaptivePatchKind::regular;
    int level = 0;
  };
  PatchFacts patch_at_face_frame(int face, int sub, float u, float v) const;
  struct PatchCounts {
    int by_kind[kAdaptivePatchKinds] = {};
    int by_level[16] = {};
    int total = 0;
  };
  PatchCounts patch_counts() const;

  // Quad-domain evaluation (quads: sub_patch 0; other faces: sub-patch k), with ownership.
  SurfacePoint evaluate(int face, int sub_patch, float u, float v) const;
  // Barycentric evaluation of a triangle face, with ownership. w must be (1-u)-v.
  SurfacePoint evaluate_triangle(int face, float u, float v, float w) const;
  // Fan triangle `triangle` (0..n-1) of a face of n != 4 vertices, with ownership. w must be (1-u)-v.
  SurfacePoint evaluate_fan(int face, int triangle, float u, float v, float w) const;

  // Where point (u, v) of fan triangle k of an n-gon lies in the face's quad sub-patches (the map in the
  // contract above). Exact for tessellator parameters on the spokes; no range checks.
  struct SubPatchLocation {
    int sub;
    double s, t;
  };
  static SubPatchLocation fan_location(int n, int k, double u, double v);
  // Where barycentric point (u, v) of a triangle face lies: the quad sub-patch of its largest coordinate,
  // by the inverse of that sub-patch's bilinear map, with d(s, t)/d(u, v) (evaluate_triangle's map).
  struct TriangleLocation {
    int sub;
    double s, t;
    double ds_du, ds_dv, dt_du, dt_dv;
  };
  static TriangleLocation triangle_location(double u, double v);

  // Plain per-face evaluation, without ownership: what Bfr gives for this face alone. Not watertight
  // bitwise (it exists to measure exactly that); same checks as evaluate().
  SurfacePoint evaluate_unowned(int face, int sub_patch, float u, float v) const;

  // Double-precision point and normal for accuracy measurements (no ownership needed: the two sides
  // of an edge agree to ~1e-15).
  ReferenceSample sample_reference(int face, int sub_patch, double u, double v) const;

  // Axis-aligned bounds of the limit surface, sampled on a 9x9 grid of every sub-patch at create();
  // errors are reported relative to the diagonal.
  glm::dvec3 bounds_min() const;
  glm::dvec3 bounds_max() const;
  double bounding_box_diagonal() const;

  // Bytes held by the precomputed per-face data (patch points, surfaces, ownership tables); Bfr's
  // shared irregular-patch trees are not included.
  std::size_t memory_bytes() const;

 private:
  struct Impl;
  explicit LimitSurface(std::unique_ptr<Impl> impl);
  static LimitSurface build(const Cage& cage, int level, bool adaptive);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera
