// Shared helpers for the tessellator tests: a portable seeded generator and pattern queries.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "tessellator/tessellator.h"

namespace tessera::test {

// Seeded and portable: only raw mt19937 output is used (distributions differ between libraries).
class Rng {
 public:
  explicit Rng(std::uint32_t seed) : g_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * (double(g_()) / 4294967296.0); }
  int integer(int lo, int hi) { return lo + int(g_() % std::uint32_t(hi - lo + 1)); }
  bool chance(double p) { return uniform(0, 1) < p; }
  // A factor in [lo, hi], sometimes an exact integer.
  float factor(double lo, double hi) {
    if (chance(0.3)) return float(integer(int(std::ceil(lo)), int(std::floor(hi))));
    return float(uniform(lo, hi));
  }

 private:
  std::mt19937 g_;
};

inline const std::array<ts::Partitioning, 4> kAllPartitionings = {ts::Partitioning::integer, ts::Partitioning::pow2,
                                                                  ts::Partitioning::fractional_odd,
                                                                  ts::Partitioning::fractional_even};

inline ts::Pattern run(ts::Partitioning p, ts::OutputPrimitive o, const ts::FactorSet& f) {
  ts::Pattern out;
  ts::tessellate(p, o, f, out);
  return out;
}
inline ts::FactorSet quad(float a, float b, float c, float d, float iu, float iv) {
  return {ts::Domain::quad, {a, b, c, d, iu, iv}};
}
inline ts::FactorSet tri(float a, float b, float c, float in) { return {ts::Domain::tri, {a, b, c, in, 0, 0}}; }
inline ts::FactorSet iso(float density, float detail) { return {ts::Domain::isoline, {density, detail, 0, 0, 0, 0}}; }

inline std::uint32_t fx(float x) { return std::uint32_t(std::lround(double(x) * 65536.0)); }

// Number of outer-ring points: the first points of every tri/quad pattern.
inline std::size_t outer_ring_points(const ts::ProcessedFactors& p) {
  if (p.minimal) return p.domain == ts::Domain::quad ? 4 : 3;
  std::size_t n = 0;
  const int edges = ts::outer_factor_count(p.domain);
  for (int e = 0; e < edges; ++e) n += std::size_t(p.outside[std::size_t(e)].num_points - 1);
  return n;
}

// Is domain point `pt` on outer edge e (exact coordinates)?
inline bool on_edge(ts::Domain d, int e, const ts::DomainPoint& pt) {
  if (d == ts::Domain::tri) {
    const float w = (1.0f - pt.u) - pt.v;
    return e == 0 ? pt.u == 0 : e == 1 ? pt.v == 0 : w == 0;
  }
  return e == 0 ? pt.u == 0 : e == 1 ? pt.v == 0 : e == 2 ? pt.u == 1 : pt.v == 1;
}

// The parameter that varies along edge e (quad: v, u, v, u; tri: v, u, u).
inline float edge_parameter(ts::Domain d, int e, const ts::DomainPoint& pt) {
  if (d == ts::Domain::tri) return e == 0 ? pt.v : pt.u;
  return (e & 1) ? pt.u : pt.v;
}

// Sorted parameters of the outer-ring points on edge e (identified by index, so interior points
// that land on the boundary, as fractional_odd with inside <= 1 does, are not mixed in).
inline std::vector<float> edge_parameters(const ts::Pattern& pattern, const ts::ProcessedFactors& p, int e) {
  std::vector<float> out;
  const std::size_t n = std::min(outer_ring_points(p), pattern.points.size());
  for (std::size_t i = 0; i < n; ++i)
    if (on_edge(p.domain, e, pattern.points[i])) out.push_back(edge_parameter(p.domain, e, pattern.points[i]));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

using Tri = std::array<std::array<std::uint32_t, 2>, 3>;
// A triangle by the bit patterns of its vertices' (u, v), rotated to start at its smallest vertex.
inline Tri canonical_triangle(const ts::DomainPoint& a, const ts::DomainPoint& b, const ts::DomainPoint& c) {
  auto bits = [](const ts::DomainPoint& p) {
    return std::array<std::uint32_t, 2>{std::bit_cast<std::uint32_t>(p.u), std::bit_cast<std::uint32_t>(p.v)};
  };
  Tri t = {bits(a), bits(b), bits(c)};
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

// Twice the signed (u, v) area in exact integer arithmetic on the 16.16 grid.
inline std::int64_t doubled_area(const ts::DomainPoint& a, const ts::DomainPoint& b, const ts::DomainPoint& c) {
  const std::int64_t ax = fx(a.u), ay = fx(a.v), bx = fx(b.u), by = fx(b.v), cx = fx(c.u), cy = fx(c.v);
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

// Is x inside one of the fractional_even fold windows (documented reference quirk)?
inline bool in_fold_window(float x) { return (x >= 6.0f && x <= 6.0002f) || (x >= 30.0f && x <= 30.007f); }

}  // namespace tessera::test
