// patch_eval.h's Gregory and ACC patches for eight domain points at once, in simd::F8 lanes: ACC
// patches (bezier_patch with acc_tangents' derivatives), 20-point Gregory patches (gregory_to_bezier,
// then bezier_patch) and 15-point triangular Gregory patches (gregory_triangle). Each lane computes patch_eval.h's
// expressions on the same operands in the same order (glm's vec3 operations are per component), so every PatchPoint has
// the bits the scalar functions give; a test compares the two on a grid of locations that includes the edges and
// corners.
//
// The branches of the scalar forms are taken per lane afterwards: a location on a patch edge gets its
// position from the edge's four points (bezier_edge_position, gregory_triangle_edge: the watertight
// form), and a group with a Gregory corner (where a blend's weights both vanish) is evaluated one
// location at a time.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "pipeline/simd8.h"
#include "shaders_cpp/subdiv/patch_eval.h"

namespace tessera {

namespace lanes {

using simd::F8;

struct Vec3 {
  F8 x, y, z;
};
inline Vec3 splat(const glm::vec3& v) { return {F8::splat(v.x), F8::splat(v.y), F8::splat(v.z)}; }
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator*(F8 s, const Vec3& v) { return {s * v.x, s * v.y, s * v.z}; }
inline Vec3 operator/(const Vec3& v, F8 s) { return {v.x / s, v.y / s, v.z / s}; }

struct Cubic {
  F8 b0, b1, b2, b3;
};
inline Cubic cubic_bernstein(F8 t) {
  const F8 s = F8::splat(1.0f) - t;
  return {(s * s) * s, (F8::splat(3.0f) * t) * (s * s), (F8::splat(3.0f) * s) * (t * t), (t * t) * t};
}
inline Cubic cubic_bernstein_derivative(F8 t) {
  const F8 s = F8::splat(1.0f) - t;
  const F8 ss = s * s, st = s * t, tt = t * t;
  const F8 three = F8::splat(3.0f), six = F8::splat(6.0f);
  return {F8::splat(-3.0f) * ss, three * ss - six * st, six * st - three * tt, three * tt};
}
inline Vec3 cubic_sum(const Cubic& w, const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  return (w.b0 * p0 + w.b3 * p3) + (w.b1 * p1 + w.b2 * p2);
}

// bezier_patch's interior position and derivatives; `derivatives` false leaves du and dv unset (an ACC
// patch takes them from its tangent patches).
inline void bezier_patch(const std::array<Vec3, 16>& b, F8 u, F8 v, bool derivatives, Vec3& position, Vec3& du,
                         Vec3& dv) {
  const Cubic bu = cubic_bernstein(u), bv = cubic_bernstein(v);
  std::array<Vec3, 4> row, drow;
  const Cubic dwu = cubic_bernstein_derivative(u);
  for (std::size_t j = 0; j < 4; ++j) {
    row[j] = cubic_sum(bu, b[4 * j], b[4 * j + 1], b[4 * j + 2], b[4 * j + 3]);
    if (derivatives) drow[j] = cubic_sum(dwu, b[4 * j], b[4 * j + 1], b[4 * j + 2], b[4 * j + 3]);
  }
  position = cubic_sum(bv, row[0], row[1], row[2], row[3]);
  if (!derivatives) return;
  du = cubic_sum(bv, drow[0], drow[1], drow[2], drow[3]);
  dv = cubic_sum(cubic_bernstein_derivative(v), row[0], row[1], row[2], row[3]);
}

// bezier_triangle<4>: the Bernstein sums in its order, from zero.
inline void bezier_triangle4(const std::array<Vec3, 15>& b, F8 u, F8 v, F8 w, Vec3& position, Vec3& du, Vec3& dv) {
  constexpr int D = 4;
  std::array<F8, D + 1> pu, pv, pw;
  pu[0] = pv[0] = pw[0] = F8::splat(1.0f);
  for (std::size_t n = 1; n <= D; ++n) pu[n] = pu[n - 1] * u, pv[n] = pv[n - 1] * v, pw[n] = pw[n - 1] * w;
  constexpr float kFactorial[] = {1.0f, 1.0f, 2.0f, 6.0f, 24.0f};
  const auto basis = [&](int n, int j, int k) {
    const int i = n - j - k;
    const float c = kFactorial[n] / (kFactorial[i] * kFactorial[j] * kFactorial[k]);
    return F8::splat(c) * ((pw[std::size_t(i)] * pu[std::size_t(j)]) * pv[std::size_t(k)]);
  };
  const auto at = [&](int j, int k) -> const Vec3& { return b[std::size_t(tri_index(D, j, k))]; };
  const Vec3 zero = splat(glm::vec3(0.0f));
  position = zero, du = zero, dv = zero;
  for (int k = 0; k <= D; ++k)
    for (int j = 0; j + k <= D; ++j) position = position + basis(D, j, k) * at(j, k);
  for (int k = 0; k < D; ++k)
    for (int j = 0; j + k < D; ++j) {
      const F8 w1 = basis(D - 1, j, k);
      const Vec3& base = at(j, k);
      const Vec3& a = at(j + 1, k);
      const Vec3& c = at(j, k + 1);
      du = du + w1 * Vec3{a.x - base.x, a.y - base.y, a.z - base.z};
      dv = dv + w1 * Vec3{c.x - base.x, c.y - base.y, c.z - base.z};
    }
  const F8 d = F8::splat(float(D));
  du = Vec3{du.x * d, du.y * d, du.z * d};
  dv = Vec3{dv.x * d, dv.y * d, dv.z * d};
}

}  // namespace lanes

// PatchPoints of patch_eval.h's patches for many domain locations (u[i], v[i]), eight at a time.
class PatchLanes {
 public:
  // An ACC patch: bezier_patch(b, u, v) with acc_tangents(du, dv, u, v) as its derivatives.
  static void acc(std::span<const glm::vec3, 16> b, std::span<const glm::vec3, 12> du,
                  std::span<const glm::vec3, 12> dv, std::span<const float> u, std::span<const float> v,
                  std::span<PatchPoint> out) {
    using lanes::F8;
    using lanes::Vec3;
    std::array<Vec3, 16> bl;
    std::array<Vec3, 12> dul, dvl;
    for (std::size_t i = 0; i < 16; ++i) bl[i] = lanes::splat(b[i]);
    for (std::size_t i = 0; i < 12; ++i) dul[i] = lanes::splat(du[i]), dvl[i] = lanes::splat(dv[i]);
    for_groups(
        u, v, out,
        [&](F8 fu, F8 fv, Vec3& position, Vec3& pdu, Vec3& pdv) {
          Vec3 unused_du, unused_dv;
          lanes::bezier_patch(bl, fu, fv, false, position, unused_du, unused_dv);
          // acc_tangents
          const F8 one = F8::splat(1.0f);
          const F8 su = one - fu, sv = one - fv;
          const F8 qu[3] = {su * su, (F8::splat(2.0f) * su) * fu, fu * fu};
          const F8 qv[3] = {sv * sv, (F8::splat(2.0f) * sv) * fv, fv * fv};
          const lanes::Cubic cu = lanes::cubic_bernstein(fu), cv = lanes::cubic_bernstein(fv);
          std::array<Vec3, 4> r;
          for (std::size_t j = 0; j < 4; ++j) {
            const Vec3* p = dul.data() + 3 * j;
            r[j] = (qu[0] * p[0] + qu[2] * p[2]) + qu[1] * p[1];
          }
          pdu = lanes::cubic_sum(cv, r[0], r[1], r[2], r[3]);
          std::array<Vec3, 3> c;
          for (std::size_t j = 0; j < 3; ++j) {
            const Vec3* p = dvl.data() + 4 * j;
            c[j] = lanes::cubic_sum(cu, p[0], p[1], p[2], p[3]);
          }
          pdv = (qv[0] * c[0] + qv[2] * c[2]) + qv[1] * c[1];
          return true;
        },
        [&](float pu, float pv) {
          PatchPoint p = bezier_patch(b, pu, pv);
          acc_tangents(du, dv, pu, pv, p.du, p.dv);
          return p;
        });
    fix_edges(b, u, v, out);
  }

  // A 20-point Gregory patch: bezier_patch(gregory_to_bezier(g, u, v), u, v).
  static void gregory(std::span<const glm::vec3, 20> g, std::span<const float> u, std::span<const float> v,
                      std::span<PatchPoint> out) {
    using lanes::F8;
    using lanes::Vec3;
    // The 12 points that do not depend on the location; the four interior ones are blended per lane.
    const std::array<glm::vec3, 16> fixed = gregory_to_bezier(g, 0.5f, 0.5f);
    std::array<Vec3, 16> bl;
    for (std::size_t i = 0; i < 16; ++i) bl[i] = lanes::splat(fixed[i]);
    std::array<Vec3, 4> fp, fm;
    for (std::size_t k = 0; k < 4; ++k) fp[k] = lanes::splat(g[5 * k + 3]), fm[k] = lanes::splat(g[5 * k + 4]);
    for_groups(
        u, v, out,
        [&](F8 s, F8 t, Vec3& position, Vec3& du, Vec3& dv) {
          const F8 one = F8::splat(1.0f);
          const F8 s1 = one - s, t1 = one - t;
          // A lane whose weights sum to 0 (a corner) takes the scalar form below.
          bool degenerate = false;
          const auto blend = [&](const Vec3& plus, F8 wp, const Vec3& minus, F8 wm) {
            return gregory_blend(plus, wp, minus, wm, degenerate);
          };
          bl[5] = blend(fp[0], s, fm[0], t);
          bl[6] = blend(fp[1], t, fm[1], s1);
          bl[10] = blend(fp[2], s1, fm[2], t1);
          bl[9] = blend(fp[3], t1, fm[3], s);
          if (degenerate) return false;
          lanes::bezier_patch(bl, s, t, true, position, du, dv);
          return true;
        },
        [&](float pu, float pv) { return bezier_patch(gregory_to_bezier(g, pu, pv), pu, pv); });
    fix_edges(fixed, u, v, out);
  }

  // A 15-point triangular Gregory patch: gregory_triangle(g, u, v, w).
  static void gregory_triangle(std::span<const glm::vec3, 15> g, std::span<const float> u, std::span<const float> v,
                               std::span<const float> w, std::span<PatchPoint> out) {
    using lanes::F8;
    using lanes::Vec3;
    // The 12 points that do not depend on the location (the degree-raised boundaries); the three
    // interior ones are blended per lane.
    std::array<Vec3, 15> bl;
    {
      const auto raise1 = [](const glm::vec3& a0, const glm::vec3& a1) { return 0.25f * (a0 + 3.0f * a1); };
      const auto raise2 = [](const glm::vec3& a1, const glm::vec3& a2) { return 0.5f * (a1 + a2); };
      const auto P = [&](std::size_t k) { return g[5 * k]; };
      const auto Ep = [&](std::size_t k) { return g[5 * k + 1]; };
      const auto Em = [&](std::size_t k) { return g[5 * k + 2]; };
      const auto at = [&](int j, int k) -> Vec3& { return bl[std::size_t(tri_index(4, j, k))]; };
      at(0, 0) = lanes::splat(P(0)), at(4, 0) = lanes::splat(P(1)), at(0, 4) = lanes::splat(P(2));
      at(1, 0) = lanes::splat(raise1(P(0), Ep(0))), at(2, 0) = lanes::splat(raise2(Ep(0), Em(1)));
      at(3, 0) = lanes::splat(raise1(P(1), Em(1))), at(3, 1) = lanes::splat(raise1(P(1), Ep(1)));
      at(2, 2) = lanes::splat(raise2(Ep(1), Em(2))), at(1, 3) = lanes::splat(raise1(P(2), Em(2)));
      at(0, 3) = lanes::splat(raise1(P(2), Ep(2))), at(0, 2) = lanes::splat(raise2(Ep(2), Em(0)));
      at(0, 1) = lanes::splat(raise1(P(0), Em(0)));
    }
    std::array<Vec3, 3> fp, fm;
    for (std::size_t k = 0; k < 3; ++k) fp[k] = lanes::splat(g[5 * k + 3]), fm[k] = lanes::splat(g[5 * k + 4]);
    for_groups3(
        u, v, w, out,
        [&](F8 fu, F8 fv, F8 fw, Vec3& position, Vec3& du, Vec3& dv) {
          bool degenerate = false;
          const auto blend = [&](const Vec3& plus, F8 wp, const Vec3& minus, F8 wm) {
            return gregory_blend(plus, wp, minus, wm, degenerate);
          };
          bl[std::size_t(tri_index(4, 1, 1))] = blend(fp[0], fu, fm[0], fv);
          bl[std::size_t(tri_index(4, 2, 1))] = blend(fp[1], fv, fm[1], fw);
          bl[std::size_t(tri_index(4, 1, 2))] = blend(fp[2], fw, fm[2], fu);
          if (degenerate) return false;
          lanes::bezier_triangle4(bl, fu, fv, fw, position, du, dv);
          return true;
        },
        [&](float pu, float pv, float pw) { return tessera::gregory_triangle(g, pu, pv, pw); });
    for (std::size_t i = 0; i < u.size(); ++i) detail::gregory_triangle_edge(g, u[i], v[i], w[i], out[i].position);
  }

 private:
  // detail::gregory_blend's division form in each lane; `degenerate` is set where the weights sum to 0
  // (its other form, which the caller then takes one location at a time).
  static lanes::Vec3 gregory_blend(const lanes::Vec3& plus, lanes::F8 wp, const lanes::Vec3& minus, lanes::F8 wm,
                                   bool& degenerate) {
    const lanes::F8 d = wp + wm;
    std::array<float, 8> a;
    d.store(a);
    for (float x : a) degenerate = degenerate || x == 0.0f;
    return (wp * plus + wm * minus) / d;
  }

  // Runs `lanes_of(u, v, w, position, du, dv)` on groups of eight locations (a short last group repeats
  // its last location) and stores each lane's PatchPoint. A group for which it returns false is
  // evaluated one location at a time by `one(u, v, w)`.
  template <class LanesOf, class One>
  static void for_groups3(std::span<const float> u, std::span<const float> v, std::span<const float> w,
                          std::span<PatchPoint> out, const LanesOf& lanes_of, const One& one) {
    using lanes::F8;
    for (std::size_t first = 0; first < u.size(); first += 8) {
      const std::size_t count = std::min<std::size_t>(8, u.size() - first);
      // Each lane read one by one (F8::lanes): a vector load of values just stored one by one would wait
      // for the stores to reach the cache. A short last group repeats its last location.
      const auto in_lanes = [&](std::span<const float> s) {
        const auto at = [&](std::size_t k) { return s[first + std::min(k, count - 1)]; };
        return F8::lanes(at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7));
      };
      lanes::Vec3 position, du, dv;
      if (!lanes_of(in_lanes(u), in_lanes(v), in_lanes(w), position, du, dv)) {
        for (std::size_t i = first; i < first + count; ++i) out[i] = one(u[i], v[i], w[i]);
        continue;
      }
      std::array<float, 8> c[9];
      position.x.store(c[0]), position.y.store(c[1]), position.z.store(c[2]);
      du.x.store(c[3]), du.y.store(c[4]), du.z.store(c[5]);
      dv.x.store(c[6]), dv.y.store(c[7]), dv.z.store(c[8]);
      for (std::size_t k = 0; k < count; ++k) {
        PatchPoint& p = out[first + k];
        p.position = {c[0][k], c[1][k], c[2][k]};
        p.du = {c[3][k], c[4][k], c[5][k]};
        p.dv = {c[6][k], c[7][k], c[8][k]};
      }
    }
  }
  // The same on the quad domain: lanes_of(u, v, position, du, dv) and one(u, v).
  template <class LanesOf, class One>
  static void for_groups(std::span<const float> u, std::span<const float> v, std::span<PatchPoint> out,
                         const LanesOf& lanes_of, const One& one) {
    using lanes::F8;
    for_groups3(
        u, v, v, out,
        [&](F8 fu, F8 fv, F8, lanes::Vec3& position, lanes::Vec3& du, lanes::Vec3& dv) {
          return lanes_of(fu, fv, position, du, dv);
        },
        [&](float pu, float pv, float) { return one(pu, pv); });
  }

  // bezier_patch's edge branch: a location on an edge takes its position from that edge's points.
  static void fix_edges(std::span<const glm::vec3, 16> b, std::span<const float> u, std::span<const float> v,
                        std::span<PatchPoint> out) {
    for (std::size_t i = 0; i < u.size(); ++i) {
      const QuadEdge e = quad_edge(u[i], v[i]);
      if (e != QuadEdge::none) out[i].position = bezier_edge_position(b, e, u[i], v[i]);
    }
  }
};

}  // namespace tessera
