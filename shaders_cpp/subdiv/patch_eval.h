// Evaluation of the patches the schemes build: bicubic Bezier (with Loop & Schaefer's tangent
// patches), 20-point Gregory, 15-point triangular Gregory (quartic), polar triangles (a bicubic with a
// collapsed row), Bezier triangles (PN triangles),
// bilinear and linear; position and the two partial derivatives, and PN's quadratic normal fields.
//
// Watertight by construction: a point on a patch edge (u or v exactly 0 or 1) is evaluated from that
// edge's four boundary control points only, with a cubic Bernstein sum that is symmetric under
// t -> 1 - t and reversing the points: (b0 P0 + b3 P3) + (b1 P1 + b2 P2), where b0(t) = b3(1 - t) and
// b1(t) = b2(1 - t) are computed with identical operations. The tessellator places the points of a
// shared edge at mirrored parameters (t on one side, 1 - t on the other, both exact multiples of 2^-16),
// and the schemes make shared boundary control points bit-identical, so both patches produce the same
// bits. Interior points use the full tensor-product sum. No FMA is contracted (-ffp-contract=off).
// The tri domain does the same: corner 0 at w = 1, corner 1 at u = 1, corner 2 at v = 1; the edge v = 0
// runs from corner 0 with parameter u, w = 0 from corner 1 with v, u = 0 from corner 2 with w, and the
// other coordinate is exactly 1 - t there (tessellator coordinates are multiples of 2^-16), so a
// triangle's edge is the same cubic sum as a quad's.
#pragma once

#include <array>
#include <span>
#include <tuple>

#include <glm/glm.hpp>

namespace tessera {

struct Cubic {
  float b0, b1, b2, b3;
};

// Bernstein weights of degree 3, symmetric: cubic_bernstein(1 - t) is cubic_bernstein(t) reversed.
inline Cubic cubic_bernstein(float t) {
  const float s = 1.0f - t;
  return {s * s * s, (3.0f * t) * (s * s), (3.0f * s) * (t * t), t * t * t};
}
// Derivative weights of a cubic with respect to t (3 (P1 - P0) ... in Bernstein form of degree 2, then
// expanded onto the four points): -3 s^2, 3 s^2 - 6 s t, 6 s t - 3 t^2, 3 t^2.
inline Cubic cubic_bernstein_derivative(float t) {
  const float s = 1.0f - t;
  const float ss = s * s, st = s * t, tt = t * t;
  return {-3.0f * ss, 3.0f * ss - 6.0f * st, 6.0f * st - 3.0f * tt, 3.0f * tt};
}
// Quadratic Bernstein weights, symmetric in the same way.
inline glm::vec3 quadratic_bernstein(float t) {
  const float s = 1.0f - t;
  return {s * s, (2.0f * s) * t, t * t};
}

inline glm::vec3 cubic_sum(const Cubic& w, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                           const glm::vec3& p3) {
  return (w.b0 * p0 + w.b3 * p3) + (w.b1 * p1 + w.b2 * p2);
}

struct PatchPoint {
  glm::vec3 position{0.0f};
  glm::vec3 du{0.0f}, dv{0.0f};
};

// Which edge of the quad domain a location lies on, if any; corners count as edges.
enum class QuadEdge { none, v0, u1, v1, u0 };
inline QuadEdge quad_edge(float u, float v) {
  if (v == 0.0f) return QuadEdge::v0;
  if (v == 1.0f) return QuadEdge::v1;
  if (u == 0.0f) return QuadEdge::u0;
  if (u == 1.0f) return QuadEdge::u1;
  return QuadEdge::none;
}

// The position of a bicubic Bezier patch b[i + 4 j] on one of its edges, from that edge's points.
inline glm::vec3 bezier_edge_position(std::span<const glm::vec3, 16> b, QuadEdge e, float u, float v) {
  switch (e) {
    case QuadEdge::v0: return cubic_sum(cubic_bernstein(u), b[0], b[1], b[2], b[3]);
    case QuadEdge::v1: return cubic_sum(cubic_bernstein(u), b[12], b[13], b[14], b[15]);
    case QuadEdge::u0: return cubic_sum(cubic_bernstein(v), b[0], b[4], b[8], b[12]);
    case QuadEdge::u1: return cubic_sum(cubic_bernstein(v), b[3], b[7], b[11], b[15]);
    case QuadEdge::none: break;
  }
  return {};
}

// Position and partial derivatives of a bicubic Bezier patch.
inline PatchPoint bezier_patch(std::span<const glm::vec3, 16> b, float u, float v) {
  const Cubic bu = cubic_bernstein(u), bv = cubic_bernstein(v);
  const Cubic du = cubic_bernstein_derivative(u), dv = cubic_bernstein_derivative(v);
  std::array<glm::vec3, 4> row, drow;  // per j: sum over i with bu, and with du
  for (int j = 0; j < 4; ++j) {
    const glm::vec3* r = b.data() + 4 * j;
    row[std::size_t(j)] = cubic_sum(bu, r[0], r[1], r[2], r[3]);
    drow[std::size_t(j)] = cubic_sum(du, r[0], r[1], r[2], r[3]);
  }
  PatchPoint p;
  const QuadEdge e = quad_edge(u, v);
  p.position = e == QuadEdge::none ? cubic_sum(bv, row[0], row[1], row[2], row[3]) : bezier_edge_position(b, e, u, v);
  p.du = cubic_sum(bv, drow[0], drow[1], drow[2], drow[3]);
  p.dv = cubic_sum(dv, row[0], row[1], row[2], row[3]);
  return p;
}

// Loop & Schaefer's tangent patches: du[i + 3 j] (quadratic in u, cubic in v) and dv[i + 4 j] (cubic in
// u, quadratic in v). Returns d/du and d/dv at (u, v).
inline void acc_tangents(std::span<const glm::vec3, 12> du, std::span<const glm::vec3, 12> dv, float u, float v,
                         glm::vec3& out_du, glm::vec3& out_dv) {
  const glm::vec3 qu = quadratic_bernstein(u), qv = quadratic_bernstein(v);
  const Cubic cu = cubic_bernstein(u), cv = cubic_bernstein(v);
  std::array<glm::vec3, 4> r;
  for (int j = 0; j < 4; ++j) {
    const glm::vec3* p = du.data() + 3 * j;
    r[std::size_t(j)] = (qu.x * p[0] + qu.z * p[2]) + qu.y * p[1];
  }
  out_du = cubic_sum(cv, r[0], r[1], r[2], r[3]);
  std::array<glm::vec3, 3> c;
  for (int j = 0; j < 3; ++j) {
    const glm::vec3* p = dv.data() + 4 * j;
    c[std::size_t(j)] = cubic_sum(cu, p[0], p[1], p[2], p[3]);
  }
  out_dv = (qv.x * c[0] + qv.z * c[2]) + qv.y * c[1];
}

// v / |v|, or zero where |v| is 0 (or NaN): a normal that degenerates (at a pole, or between a
// patch's collapsed points) reads as none rather than as NaN.
inline glm::vec3 unit_or_zero(const glm::vec3& v) {
  const float len = glm::length(v);
  return len > 0.0f ? v / len : glm::vec3(0.0f);
}

namespace detail {
// A Gregory interior point: the face-point pair (F+, F-) blended by the weights of their edges. The
// weights vanish together only at a corner, where edge evaluation does not read the point.
inline glm::vec3 gregory_blend(const glm::vec3& plus, float wp, const glm::vec3& minus, float wm) {
  const float d = wp + wm;
  if (d == 0.0f) return 0.5f * (plus + minus);
  return (wp * plus + wm * minus) / d;
}

// The five points of corner k of a Gregory patch (quad or triangle), stored at 5k: P, E+, E-, F+, F-,
// as five accessors k -> point.
template <std::size_t Extent>
auto gregory_points(std::span<const glm::vec3, Extent> g) {
  const auto slot = [g](int s) { return [g, s](int k) { return g[std::size_t(5 * k + s)]; }; };
  return std::tuple{slot(0), slot(1), slot(2), slot(3), slot(4)};
}
}  // namespace detail

// The 16 Bezier points of a 20-point Gregory patch at (u, v): the four interior points are rational
// blends of each corner's face-point pair, the "+" point weighted toward its own edge. Denominators
// that vanish (only at the corners, which edge evaluation handles) count as 1.
inline std::array<glm::vec3, 16> gregory_to_bezier(std::span<const glm::vec3, 20> g, float u, float v) {
  const auto [P, Ep, Em, Fp, Fm] = detail::gregory_points(g);
  constexpr auto blend = detail::gregory_blend;
  const float s = u, t = v, s1 = 1.0f - u, t1 = 1.0f - v;
  std::array<glm::vec3, 16> b;
  b[0] = P(0), b[1] = Ep(0), b[2] = Em(1), b[3] = P(1);
  b[4] = Em(0), b[7] = Ep(1);
  b[8] = Ep(3), b[11] = Em(2);
  b[12] = P(3), b[13] = Em(3), b[14] = Ep(2), b[15] = P(2);
  // Corner 0's F+ belongs to edge v = 0, F- to u = 0; corner 1's F+ to u = 1, F- to v = 0; corner 2's
  // F+ to v = 1, F- to u = 1; corner 3's F+ to u = 0, F- to v = 1.
  b[5] = blend(Fp(0), s, Fm(0), t);
  b[6] = blend(Fp(1), t, Fm(1), s1);
  b[10] = blend(Fp(2), s1, Fm(2), t1);
  b[9] = blend(Fp(3), t1, Fm(3), s);
  return b;
}

// Bilinear patch of the four corners (the `flat` baseline).
inline PatchPoint bilinear_patch(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3,
                                 float u, float v) {
  PatchPoint p;
  const QuadEdge e = quad_edge(u, v);
  const float s = 1.0f - u, t = 1.0f - v;
  switch (e) {
    case QuadEdge::v0: p.position = s * p0 + u * p1; break;
    case QuadEdge::v1: p.position = s * p3 + u * p2; break;
    case QuadEdge::u0: p.position = t * p0 + v * p3; break;
    case QuadEdge::u1: p.position = t * p1 + v * p2; break;
    case QuadEdge::none: p.position = t * (s * p0 + u * p1) + v * (s * p3 + u * p2); break;
  }
  p.du = t * (p1 - p0) + v * (p2 - p3);
  p.dv = s * (p3 - p0) + u * (p2 - p1);
  return p;
}

// Linear triangle of three corners (the `flat` baseline on the tri domain): corner 0 at w = 1, corner 1
// at u = 1, corner 2 at v = 1. On an edge only that edge's two corners are summed, so the point does
// not depend on which neighbour computes it.
inline PatchPoint linear_triangle(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, float u, float v,
                                  float w) {
  PatchPoint p;
  if (v == 0.0f)
    p.position = w * p0 + u * p1;
  else if (w == 0.0f)
    p.position = u * p1 + v * p2;
  else if (u == 0.0f)
    p.position = v * p2 + w * p0;
  else
    p.position = (w * p0 + u * p1) + v * p2;
  p.du = p1 - p0;
  p.dv = p2 - p0;
  return p;
}

// Which edge of the tri domain a location lies on, if any; corners count as edges.
enum class TriEdge { none, v0, w0, u0 };
inline TriEdge tri_edge(float u, float v, float w) {
  if (v == 0.0f) return TriEdge::v0;
  if (w == 0.0f) return TriEdge::w0;
  if (u == 0.0f) return TriEdge::u0;
  return TriEdge::none;
}

// Bezier triangles of degree D: point b[tri_index(D, j, k)] carries w^i u^j v^k, i = D - j - k, stored
// row by row in k, j ascending within a row.
constexpr int tri_index(int D, int j, int k) { return k * (D + 1) - k * (k - 1) / 2 + j; }

// Position and d/du, d/dv (v resp. u held, w = 1 - u - v) of a degree-D Bezier triangle, by the
// Bernstein sums in a fixed order: sum over k, then j, of (D! / (i! j! k!)) w^i u^j v^k b_ijk.
template <int D>
inline PatchPoint bezier_triangle(std::span<const glm::vec3, (D + 1) * (D + 2) / 2> b, float u, float v, float w) {
  static_assert(D >= 1 && D <= 4);
  std::array<float, D + 1> pu{}, pv{}, pw{};
  pu[0] = pv[0] = pw[0] = 1.0f;
  for (int n = 1; n <= D; ++n) {
    pu[std::size_t(n)] = pu[std::size_t(n - 1)] * u;
    pv[std::size_t(n)] = pv[std::size_t(n - 1)] * v;
    pw[std::size_t(n)] = pw[std::size_t(n - 1)] * w;
  }
  constexpr float kFactorial[] = {1.0f, 1.0f, 2.0f, 6.0f, 24.0f};
  auto basis = [&](int n, int j, int k) {
    const int i = n - j - k;
    const float c = kFactorial[n] / (kFactorial[i] * kFactorial[j] * kFactorial[k]);
    return c * ((pw[std::size_t(i)] * pu[std::size_t(j)]) * pv[std::size_t(k)]);
  };
  auto at = [&](int j, int k) { return b[std::size_t(tri_index(D, j, k))]; };
  PatchPoint p;
  for (int k = 0; k <= D; ++k)
    for (int j = 0; j + k <= D; ++j) p.position += basis(D, j, k) * at(j, k);
  for (int k = 0; k < D; ++k)
    for (int j = 0; j + k < D; ++j) {
      const float w1 = basis(D - 1, j, k);
      const glm::vec3 base = at(j, k);  // b_{i+1, j, k}
      p.du += w1 * (at(j + 1, k) - base);
      p.dv += w1 * (at(j, k + 1) - base);
    }
  p.du *= float(D);
  p.dv *= float(D);
  return p;
}

namespace detail {
// On an edge of the tri domain, `position` becomes that edge's cubic over the 15 Gregory slots (corner
// k's P, E+, E- at 5k, 5k + 1, 5k + 2): what the Gregory and polar triangles and their neighbours share.
inline void gregory_triangle_edge(std::span<const glm::vec3, 15> g, float u, float v, float w, glm::vec3& position) {
  const auto [P, Ep, Em, Fp, Fm] = gregory_points(g);
  switch (tri_edge(u, v, w)) {
    case TriEdge::v0: position = cubic_sum(cubic_bernstein(u), P(0), Ep(0), Em(1), P(1)); break;
    case TriEdge::w0: position = cubic_sum(cubic_bernstein(v), P(1), Ep(1), Em(2), P(2)); break;
    case TriEdge::u0: position = cubic_sum(cubic_bernstein(w), P(2), Ep(2), Em(0), P(0)); break;
    case TriEdge::none: break;
  }
}
}  // namespace detail

// The triangular Gregory patch (Loop, Schaefer, Ni, Castano 2009, after Kovacs): 15 points, five per
// corner k at 5k as the quad's, P, E+ (on edge k -> k+1), E- (on edge k -> k-1), F+ (pairs with E+),
// F-. It is a quartic Bezier triangle whose boundaries are the cubics (P_k, E_k+, E_{k+1}-, P_{k+1})
// raised to degree 4, and whose three interior points are rational blends of each corner's face-point
// pair, weighted by parametric distance: the point of an edge takes over as the location reaches it,
//   b211 = (u F0+ + v F0-) / (u + v),  b121 = (v F1+ + w F1-) / (v + w),  b112 = (w F2+ + u F2-) / (w + u)
// (corner 0's F+ belongs to v = 0, F- to u = 0; corner 1's F+ to w = 0, F- to v = 0; corner 2's F+ to
// u = 0, F- to w = 0). On an edge the position is that edge's cubic (watertight); d/du and d/dv freeze
// the blend, as the quad's do, which is exact on the edges (the blended points' weights vanish there).
inline PatchPoint gregory_triangle(std::span<const glm::vec3, 15> g, float u, float v, float w) {
  const auto [P, Ep, Em, Fp, Fm] = detail::gregory_points(g);
  constexpr auto blend = detail::gregory_blend;
  // Degree raising of the cubic (a0, a1, a2, a3) to (a0, (a0 + 3 a1) / 4, (a1 + a2) / 2, (3 a2 + a3) / 4, a3).
  auto raise1 = [](const glm::vec3& a0, const glm::vec3& a1) { return 0.25f * (a0 + 3.0f * a1); };
  auto raise2 = [](const glm::vec3& a1, const glm::vec3& a2) { return 0.5f * (a1 + a2); };
  std::array<glm::vec3, 15> b;
  auto at = [&](int j, int k) -> glm::vec3& { return b[std::size_t(tri_index(4, j, k))]; };
  at(0, 0) = P(0), at(4, 0) = P(1), at(0, 4) = P(2);
  at(1, 0) = raise1(P(0), Ep(0)), at(2, 0) = raise2(Ep(0), Em(1)), at(3, 0) = raise1(P(1), Em(1));  // v = 0
  at(3, 1) = raise1(P(1), Ep(1)), at(2, 2) = raise2(Ep(1), Em(2)), at(1, 3) = raise1(P(2), Em(2));  // w = 0
  at(0, 3) = raise1(P(2), Ep(2)), at(0, 2) = raise2(Ep(2), Em(0)), at(0, 1) = raise1(P(0), Em(0));  // u = 0
  at(1, 1) = blend(Fp(0), u, Fm(0), v);
  at(2, 1) = blend(Fp(1), v, Fm(1), w);
  at(1, 2) = blend(Fp(2), w, Fm(2), u);
  PatchPoint p = bezier_triangle<4>(b, u, v, w);
  detail::gregory_triangle_edge(g, u, v, w, p.position);
  return p;
}

// The polar triangle (polar_patch.h): a bicubic Bezier patch b(s, t), s around the pole (corner 0) from
// corner 1 to corner 2 and t from the pole out to the edge w = 0, whose row t = 0 is the pole itself, on
// the tri domain through s = v / (u + v), t = u + v. Its 13 distinct points sit in the Gregory
// triangle's 15 slots, so that its three boundary cubics are the Gregory triangle's edges (the same edge
// rule, the same bits as a neighbour's):
//   row t = 0:    P0 (four times)         row t = 1/3:  E0+, F0+, F0-, E0-
//   row t = 2/3:  E1-, F1+, F1-, E2+       row t = 1:    P1, E1+, E2-, P2
// (F2+ and F2- are unused). d/du and d/dv by the chain rule; at the pole itself, where the map is
// singular, both are the radial derivative toward corner 1 (parallel: the domain shader takes the
// normal a step inside, as at any corner whose derivatives do not span the tangent plane).
inline PatchPoint polar_triangle(std::span<const glm::vec3, 15> g, float u, float v, float w) {
  const auto [P, Ep, Em, Fp, Fm] = detail::gregory_points(g);
  const std::array<glm::vec3, 16> b = {P(0),  P(0),  P(0),  P(0),  Ep(0), Fp(0), Fm(0), Em(0),
                                       Em(1), Fp(1), Fm(1), Ep(2), P(1),  Ep(1), Em(2), P(2)};
  PatchPoint p;
  const float t = u + v;
  if (t == 0.0f) {
    p.position = P(0);
    p.du = p.dv = 3.0f * (Ep(0) - P(0));
    return p;
  }
  const float s = v / t;
  const PatchPoint q = bezier_patch(b, s, t);
  // ds/du = -v / t^2, ds/dv = u / t^2, dt/du = dt/dv = 1.
  const float inv = 1.0f / (t * t);
  p.position = q.position;
  p.du = q.dv - (v * inv) * q.du;
  p.dv = q.dv + (u * inv) * q.du;
  detail::gregory_triangle_edge(g, u, v, w, p.position);
  return p;
}

// A cubic Bezier triangle (PN triangles) b[tri_index(3, j, k)], with the edge rule of the quads: on an
// edge, the cubic sum of that edge's four points from its first corner.
inline PatchPoint cubic_triangle(std::span<const glm::vec3, 10> b, float u, float v, float w) {
  PatchPoint p = bezier_triangle<3>(b, u, v, w);
  auto at = [&](int j, int k) { return b[std::size_t(tri_index(3, j, k))]; };
  switch (tri_edge(u, v, w)) {
    case TriEdge::v0: p.position = cubic_sum(cubic_bernstein(u), at(0, 0), at(1, 0), at(2, 0), at(3, 0)); break;
    case TriEdge::w0: p.position = cubic_sum(cubic_bernstein(v), at(3, 0), at(2, 1), at(1, 2), at(0, 3)); break;
    case TriEdge::u0: p.position = cubic_sum(cubic_bernstein(w), at(0, 3), at(0, 2), at(0, 1), at(0, 0)); break;
    case TriEdge::none: break;
  }
  return p;
}

// The quadratic normal field of a PN triangle, n[tri_index(2, j, k)], normalized; on an edge only
// that edge's three coefficients, by a sum symmetric under reversal (the same bits from both sides).
inline glm::vec3 quadratic_triangle_normal(std::span<const glm::vec3, 6> n, float u, float v, float w) {
  auto at = [&](int j, int k) { return n[std::size_t(tri_index(2, j, k))]; };
  auto edge = [](float t, const glm::vec3& a, const glm::vec3& m, const glm::vec3& b) {
    const glm::vec3 q = quadratic_bernstein(t);
    return (q.x * a + q.z * b) + q.y * m;
  };
  glm::vec3 r;
  switch (tri_edge(u, v, w)) {
    case TriEdge::v0: r = edge(u, at(0, 0), at(1, 0), at(2, 0)); break;
    case TriEdge::w0: r = edge(v, at(2, 0), at(1, 1), at(0, 2)); break;
    case TriEdge::u0: r = edge(w, at(0, 2), at(0, 1), at(0, 0)); break;
    case TriEdge::none: r = bezier_triangle<2>(n, u, v, w).position; break;
  }
  return unit_or_zero(r);
}

// The biquadratic normal field of a PN quad, n[i + 3 j] (i along u), normalized, with the same edge rule.
inline glm::vec3 biquadratic_normal(std::span<const glm::vec3, 9> n, float u, float v) {
  const glm::vec3 qu = quadratic_bernstein(u), qv = quadratic_bernstein(v);
  auto sum = [](const glm::vec3& q, const glm::vec3& a, const glm::vec3& m, const glm::vec3& b) {
    return (q.x * a + q.z * b) + q.y * m;
  };
  glm::vec3 r;
  switch (quad_edge(u, v)) {
    case QuadEdge::v0: r = sum(qu, n[0], n[1], n[2]); break;
    case QuadEdge::v1: r = sum(qu, n[6], n[7], n[8]); break;
    case QuadEdge::u0: r = sum(qv, n[0], n[3], n[6]); break;
    case QuadEdge::u1: r = sum(qv, n[2], n[5], n[8]); break;
    case QuadEdge::none:
      r = sum(qv, sum(qu, n[0], n[1], n[2]), sum(qu, n[3], n[4], n[5]), sum(qu, n[6], n[7], n[8]));
      break;
  }
  return unit_or_zero(r);
}

}  // namespace tessera
