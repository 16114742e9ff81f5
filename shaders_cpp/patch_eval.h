// Evaluation of the patches the schemes build: bicubic Bezier (with Loop & Schaefer's tangent
// patches), 20-point Gregory, bilinear; position and the two partial derivatives.
//
// Watertight by construction: a point on a patch edge (u or v exactly 0 or 1) is evaluated from that
// edge's four boundary control points only, with a cubic Bernstein sum that is symmetric under
// t -> 1 - t and reversing the points: (b0 P0 + b3 P3) + (b1 P1 + b2 P2), where b0(t) = b3(1 - t) and
// b1(t) = b2(1 - t) are computed with identical operations. The tessellator places the points of a
// shared edge at mirrored parameters (t on one side, 1 - t on the other, both exact multiples of 2^-16),
// and the schemes make shared boundary control points bit-identical, so both patches produce the same
// bits. Interior points use the full tensor-product sum. No FMA is contracted (-ffp-contract=off).
#pragma once

#include <array>
#include <span>

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

// The 16 Bezier points of a 20-point Gregory patch at (u, v): the four interior points are rational
// blends of each corner's face-point pair, the "+" point weighted toward its own edge. Denominators
// that vanish (only at the corners, which edge evaluation handles) count as 1.
inline std::array<glm::vec3, 16> gregory_to_bezier(std::span<const glm::vec3, 20> g, float u, float v) {
  auto P = [&](int k) { return g[std::size_t(5 * k)]; };
  auto Ep = [&](int k) { return g[std::size_t(5 * k + 1)]; };
  auto Em = [&](int k) { return g[std::size_t(5 * k + 2)]; };
  auto Fp = [&](int k) { return g[std::size_t(5 * k + 3)]; };
  auto Fm = [&](int k) { return g[std::size_t(5 * k + 4)]; };
  auto blend = [](const glm::vec3& plus, float wp, const glm::vec3& minus, float wm) {
    const float d = wp + wm;
    if (d == 0.0f) return 0.5f * (plus + minus);
    return (wp * plus + wm * minus) / d;
  };
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
  if (v == 0.0f) p.position = w * p0 + u * p1;
  else if (w == 0.0f) p.position = u * p1 + v * p2;
  else if (u == 0.0f) p.position = v * p2 + w * p0;
  else p.position = (w * p0 + u * p1) + v * p2;
  p.du = p1 - p0;
  p.dv = p2 - p0;
  return p;
}

}  // namespace tessera
