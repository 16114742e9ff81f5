// patch_eval.h's bicubic patches for eight domain points at once, in simd::F8 lanes: ACC patches
// (bezier_patch with acc_tangents' derivatives) and 20-point Gregory patches (gregory_to_bezier, then
// bezier_patch). Each lane computes patch_eval.h's expressions on the same operands in the same order
// (glm's vec3 operations are per component), so every PatchPoint has the bits the scalar functions give;
// a test compares the two on every location of a factor-23 pattern.
//
// The branches of the scalar forms are taken per lane afterwards: a location on a patch edge gets its
// position from the edge's four points (bezier_edge_position, the watertight form), and a group with a
// Gregory corner (where a blend's weights both vanish) is evaluated one location at a time.
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
    for_groups(u, v, out, [&](F8 fu, F8 fv, Vec3& position, Vec3& pdu, Vec3& pdv) {
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
          // detail::gregory_blend; a lane whose weights sum to 0 (a corner) takes the scalar form below.
          bool degenerate = false;
          const auto blend = [&](const Vec3& plus, F8 wp, const Vec3& minus, F8 wm) {
            const F8 d = wp + wm;
            degenerate = degenerate || any_zero(d);
            return (wp * plus + wm * minus) / d;
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

 private:
  static bool any_zero(lanes::F8 d) {
    std::array<float, 8> a;
    d.store(a);
    for (float x : a)
      if (x == 0.0f) return true;
    return false;
  }

  // Runs `lanes_of(u, v, position, du, dv)` on groups of eight locations (a short last group repeats its
  // last location) and stores each lane's PatchPoint. A group for which it returns false is evaluated
  // one location at a time by `one(u, v)`.
  template <class LanesOf, class One>
  static void for_groups(std::span<const float> u, std::span<const float> v, std::span<PatchPoint> out,
                         const LanesOf& lanes_of, const One& one) {
    using lanes::F8;
    for (std::size_t first = 0; first < u.size(); first += 8) {
      const std::size_t count = std::min<std::size_t>(8, u.size() - first);
      std::array<float, 8> lu, lv;
      for (std::size_t k = 0; k < 8; ++k) {
        const std::size_t i = first + std::min(k, count - 1);
        lu[k] = u[i], lv[k] = v[i];
      }
      lanes::Vec3 position, du, dv;
      if (!lanes_of(F8::load(lu), F8::load(lv), position, du, dv)) {
        for (std::size_t k = 0; k < count; ++k) out[first + k] = one(lu[k], lv[k]);
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
  template <class LanesOf>
  static void for_groups(std::span<const float> u, std::span<const float> v, std::span<PatchPoint> out,
                         const LanesOf& lanes_of) {
    for_groups(u, v, out, lanes_of, [](float, float) -> PatchPoint { return {}; });
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
