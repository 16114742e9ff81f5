// Gregory points fitted to the exact limit surface: what the per-face schemes put on faces whose
// corners carry crease or corner tags, where the masks of a smooth or cut-open ring only approximate the
// limit (a semi-sharp crease of sharpness s rounds over a band 2^-s wide; a corner tag pulls the surface
// over a neighbourhood no corner mask describes).
//
// The limit surface of a face is linear in its 1-ring (OpenSubdiv's Bfr gives it as a stencil at any
// domain point, from topology and tags alone), so a least-squares fit of a patch's points to it is a
// stencil too: it is computed once per face from the tags, and every pose sums it in the hull shader as
// it sums the masks' rows.
// - fit_edge_points: the edge's two Bezier points (E near its first vertex, E near its second) that
//   bring the cubic from the fixed limit corners P0, P1 closest, in least squares at 16 points, to the
//   limit curve along the edge. Computed once per cage edge (the caller keeps it) and read by both faces,
//   so the edge stays the same bits on both sides.
// - fit_face_points: a 20-point Gregory patch's face points, one per corner (F+ = F-, so the patch is a
//   bicubic Bezier patch that back-patch culling can prove facing away), the boundary points fixed,
//   closest in least squares to the limit at a 10 x 10 grid of interior domain points and,
//   along the patch's smooth edges (weighted 0.01), to the limit's cross derivative there, which pulls
//   the two patches on such an edge toward the limit's tangent plane.
// - fit_inward_derivative: the limit's derivative across an edge, for the normal on a semi-sharp
//   crease line, where the limit is smooth but a patch's own derivative is not.
// How close the fitted patches come to the exact limit on OpenSubdiv's creased shapes: README.md here,
// "Creased faces fitted to the limit".
//
// Contract: triangles and quads, in the patch domains (a quad's is Bfr's own parameterization, corner 0
// at (0, 0), 1 at (1, 0), 2 at (1, 1), 3 at (0, 1); a triangle is mapped into Bfr's three quad sub-faces
// as the exact scheme maps it, LimitSurface::triangle_location). A face Bfr cannot evaluate gives nullopt
// (false) and the caller keeps the masks' points. Limit weights below 1e-12 are dropped; keeping the
// rows inside both faces' rings is the caller's (subd_patches.cpp drops what lies beyond an edge's two
// vertex neighbourhoods, below 1e-9).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "shaders_cpp/subdiv/stencil.h"

namespace tessera {

struct Cage;

class LimitStencils {
 public:
  explicit LimitStencils(const Cage& cage);
  ~LimitStencils();
  LimitStencils(const LimitStencils&) = delete;
  LimitStencils& operator=(const LimitStencils&) = delete;

  // The limit position at (u, v) of face f (a triangle or a quad) as a stencil over the cage; nullopt
  // when Bfr has no surface for f or f has another size.
  // Quads: (u, v) in Bfr's (and the quad domain's) parameterization; triangles: barycentric (u, v) of the
  // tri domain (corner 0 at w = 1, 1 at u = 1, 2 at v = 1), as the exact scheme evaluates them.
  // With `du` and `dv`, also the partial derivatives there.
  std::optional<std::vector<Stencil>> at(int face, std::span<const std::array<double, 2>> uv,
                                         std::vector<Stencil>* du = nullptr, std::vector<Stencil>* dv = nullptr) const;
  int face_size(int face) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The limit at corner k of face f (a cage vertex's limit position), as a stencil: the corner point of a
// tagged vertex, which the masks give exactly only for uniform creasing (semi_sharp_limit.h).
std::optional<Stencil> limit_at_corner(const LimitStencils& limit, int face, int k);

// The limit's two partial derivatives at corner k of face f, in f's own domain frame (a quad's (u, v),
// a triangle's barycentric (u, v)): their cross product is the limit's one-sided normal there, which a
// fitted patch's corner does not reproduce where the limit bends within a fraction of the face (a cusp,
// a corner tag's pull).
// With `inward`, a step of kInwardStep toward the face's centre: at an interior vertex of valence 2 the
// limit's two derivatives are parallel (its two edges leave along one line), and the normal is the
// limit of the normal approaching the vertex from inside the face.
inline constexpr double kInwardStep = 1.0 / 1024.0;
// Domain point `uv` of a face of `n` sides moved kInwardStep of the way to the face's centre ((1/3, 1/3)
// for a triangle's barycentrics, (1/2, 1/2) for a quad).
std::array<double, 2> step_inward(int n, std::array<double, 2> uv);
std::optional<std::array<Stencil, 2>> limit_corner_derivatives(const LimitStencils& limit, int face, int k,
                                                               bool inward = false);

struct EdgePoints {
  Stencil near_a, near_b;  // the Bezier points beside the edge's vertex a and vertex b
};

// The fitted edge points of face f's edge from corner e to corner e + 1 (a = corner e's vertex).
std::optional<EdgePoints> fit_edge_points(const LimitStencils& limit, int face, int e, const Stencil& pa,
                                          const Stencil& pb);

// The limit's derivative into face f across its edge e (corner e -> e + 1), in f's domain units, as a
// cubic along the edge from corner e: its four Bezier coefficients, fitted in least squares at 16
// points (a neighbour's cross derivative along a semi-sharp crease, for the crease line's normal).
std::optional<std::array<Stencil, 4>> fit_inward_derivative(const LimitStencils& limit, int face, int e);

// Replaces rows 5k + 3, 5k + 4 (F+, F-, both by one point) of a 20-point Gregory patch of face f, whose patch corner k
// is face corner k + rotation, by the fit; false (rows unchanged) when the limit is not available. `smooth_edges[k]`:
// patch edge k is an interior edge without a tag.
bool fit_face_points(const LimitStencils& limit, int face, int rotation, std::vector<Stencil>& rows,
                     std::array<bool, 4> smooth_edges = {});

// The same for a 15-point triangular Gregory patch (rows 5k + 3, 5k + 4, k = 0..2, six points; patch corner
// k is face corner k + rotation), fitted at 78 interior points of the tri domain and, along its smooth
// edges (weighted 0.01), to the limit's derivative across the edge just inside it.
bool fit_triangle_face_points(const LimitStencils& limit, int face, int rotation, std::vector<Stencil>& rows,
                              std::array<bool, 3> smooth_edges = {});

}  // namespace tessera
