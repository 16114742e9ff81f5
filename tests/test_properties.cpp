// The tessellator's invariance properties (shared/reference/tessellator.md §8, numbered as
// there), as property tests over many random factor sets with fixed seeds.
#include <catch2/catch.hpp>

#include <map>
#include <thread>

#include "test_support.h"

using namespace tessera;
using namespace tessera::test;

namespace {

constexpr int kCases = 400;
const float kInf = std::numeric_limits<float>::infinity();
const float kNan = std::numeric_limits<float>::quiet_NaN();

ts::FactorSet random_factors(Rng& rng, ts::Domain d, double lo = 0.6, double hi = 20.0) {
  ts::FactorSet f;
  f.domain = d;
  for (auto& v : f.values) v = rng.factor(lo, hi);
  if (rng.chance(0.05))
    for (auto& v : f.values) v = rng.factor(lo, 66);
  return f;
}

// The i-th random tri-or-quad case: alternating domains, a random partitioning, random factors.
struct RandomCase {
  ts::Domain d;
  ts::Partitioning p;
  ts::FactorSet f;
};
RandomCase random_patch(Rng& rng, int i, double lo = 0.6, double hi = 20.0) {
  const auto d = i % 2 ? ts::Domain::quad : ts::Domain::tri;
  const auto p = kAllPartitionings[std::size_t(rng.integer(0, 3))];
  return {d, p, random_factors(rng, d, lo, hi)};
}

// GL-style clamp-and-round of one level, written independently of the tessellator: the number
// of segments the level gives.
int gl_segments(ts::Partitioning p, float x) {
  switch (p) {
    case ts::Partitioning::fractional_odd: {
      x = std::clamp(x, 1.0f, 63.0f);
      return 2 * int(std::ceil((double(x) - 1) / 2)) + 1;
    }
    case ts::Partitioning::fractional_even: {
      x = std::clamp(x, 2.0f, 64.0f);
      return 2 * int(std::ceil(double(x) / 2));
    }
    default: return int(std::ceil(std::clamp(x, 1.0f, 64.0f)));
  }
}

// True if a level sits within 2^-16 above a parity threshold, where the reference's rounding
// (ties to even) differs from GL's round-up (a documented exception to the count formulas).
bool near_threshold(float x) {
  const double frac = double(x) - std::floor(double(x));
  return frac > 0 && frac <= 0x1p-16;
}

}  // namespace

TEST_CASE("property 1: the same input gives the same output", "[tessellator][properties]") {
  Rng rng(1);
  for (int i = 0; i < kCases; ++i) {
    const auto d = std::array{ts::Domain::quad, ts::Domain::tri, ts::Domain::isoline}[std::size_t(i % 3)];
    const auto p = kAllPartitionings[std::size_t(rng.integer(0, 3))];
    const auto f = random_factors(rng, d);
    const auto a = run(p, ts::OutputPrimitive::triangle_cw, f);
    ts::Pattern b;  // reused storage must not leak state between calls
    ts::tessellate(p, ts::OutputPrimitive::triangle_cw, random_factors(rng, d), b);
    ts::tessellate(p, ts::OutputPrimitive::triangle_cw, f, b);
    REQUIRE(a.points == b.points);
    REQUIRE(a.indices == b.indices);
    REQUIRE(ts::hash(ts::process_factors(p, f), ts::OutputPrimitive::triangle_cw) ==
            ts::hash(ts::process_factors(p, f), ts::OutputPrimitive::triangle_cw));
  }
}

TEST_CASE("property 1: reentrant from many threads at once", "[tessellator][properties][threads]") {
  Rng rng(2);
  std::vector<ts::FactorSet> inputs;
  for (int i = 0; i < 200; ++i) inputs.push_back(random_factors(rng, i % 2 ? ts::Domain::quad : ts::Domain::tri));
  std::vector<ts::Pattern> serial(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    ts::tessellate(ts::Partitioning::fractional_odd, ts::OutputPrimitive::triangle_cw, inputs[i], serial[i]);
  std::vector<ts::Pattern> parallel(inputs.size());
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      ts::Pattern scratch;
      for (std::size_t i = std::size_t(t); i < inputs.size(); i += 4) {
        ts::tessellate(ts::Partitioning::fractional_odd, ts::OutputPrimitive::triangle_cw, inputs[i], scratch);
        parallel[i] = scratch;
      }
    });
  for (auto& th : threads) th.join();
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    REQUIRE(parallel[i].points == serial[i].points);
    REQUIRE(parallel[i].indices == serial[i].indices);
  }
}

TEST_CASE("property 2: culling", "[tessellator][properties]") {
  for (auto p : kAllPartitionings) {
    for (float bad : {0.0f, -0.0f, -1.0f, kNan, -kInf}) {
      for (int e = 0; e < 4; ++e) {
        auto f = quad(4, 4, 4, 4, 4, 4);
        f.values[std::size_t(e)] = bad;
        const auto q = run(p, ts::OutputPrimitive::triangle_cw, f);
        CHECK(q.culled);
        CHECK(q.points.empty());
        CHECK(q.indices.empty());
      }
      for (int e = 0; e < 3; ++e) {
        auto f = tri(4, 4, 4, 4);
        f.values[std::size_t(e)] = bad;
        CHECK(run(p, ts::OutputPrimitive::triangle_cw, f).culled);
      }
      CHECK(run(p, ts::OutputPrimitive::line, iso(bad, 4)).culled);
      CHECK(run(p, ts::OutputPrimitive::line, iso(4, bad)).culled);
      // Inside factors never cull.
      CHECK_FALSE(run(p, ts::OutputPrimitive::triangle_cw, quad(4, 4, 4, 4, bad, bad)).culled);
      CHECK_FALSE(run(p, ts::OutputPrimitive::triangle_cw, tri(4, 4, 4, bad)).culled);
    }
  }
}

TEST_CASE("property 3: clamping", "[tessellator][properties]") {
  for (auto p : kAllPartitionings) {
    const float max = p == ts::Partitioning::fractional_odd ? 63.0f : 64.0f;
    const float lower = p == ts::Partitioning::fractional_even ? 2.0f : 1.0f;
    const auto at_max = run(p, ts::OutputPrimitive::triangle_cw, quad(max, max, max, max, max, max));
    for (float huge : {100.0f, 1e30f, kInf}) {
      const auto q = run(p, ts::OutputPrimitive::triangle_cw, quad(huge, huge, huge, huge, huge, huge));
      CHECK(q.points == at_max.points);
      CHECK(q.indices == at_max.indices);
    }
    // NaN inside behaves like the lower bound (fractional_odd: 1 + 2^-16 once edges exceed 1).
    const float nan_like = p == ts::Partitioning::fractional_odd ? 1.0f + 0x1p-16f : lower;
    const auto nan_inside = run(p, ts::OutputPrimitive::triangle_cw, tri(5, 6, 7, kNan));
    const auto low_inside = run(p, ts::OutputPrimitive::triangle_cw, tri(5, 6, 7, nan_like));
    CHECK(nan_inside.points == low_inside.points);
    CHECK(nan_inside.indices == low_inside.indices);
  }
}

TEST_CASE("property 4: point and primitive counts", "[tessellator][properties]") {
  Rng rng(4);
  for (int i = 0; i < kCases * 3; ++i) {
    const auto p = kAllPartitionings[std::size_t(rng.integer(0, 3))];
    const auto d = std::array{ts::Domain::quad, ts::Domain::tri, ts::Domain::isoline}[std::size_t(rng.integer(0, 2))];
    const auto f = random_factors(rng, d, 1.0, 40.0);
    if (std::any_of(f.values.begin(), f.values.end(), near_threshold)) continue;
    const auto pattern = run(p, ts::OutputPrimitive::triangle_cw, f);
    const auto& v = f.values;
    INFO("partitioning " << ts::to_string(p) << " domain " << ts::to_string(d) << " factors " << v[0] << " " << v[1]
                         << " " << v[2] << " " << v[3] << " " << v[4] << " " << v[5]);
    if (d == ts::Domain::isoline) {
      const int lines = int(std::ceil(std::clamp(v[0], 1.0f, 64.0f)));
      const int segs = gl_segments(p, v[1]);
      CHECK(pattern.points.size() == std::size_t(lines * (segs + 1)));
      CHECK(pattern.primitive_count() == std::size_t(lines * segs));
      continue;
    }
    const bool odd = p == ts::Partitioning::fractional_odd;
    const int edges = d == ts::Domain::quad ? 4 : 3;
    int sum_outer = 0;
    bool all_one = true;
    for (int e = 0; e < edges; ++e) {
      sum_outer += gl_segments(p, v[std::size_t(e)]);
      all_one = all_one && gl_segments(p, v[std::size_t(e)]) == 1;
    }
    auto inner = [&](float x) {
      int s = gl_segments(p, x);
      if (s == 1 && !(all_one && gl_segments(p, x) == 1)) s = odd ? 3 : 2;  // inner = 1 promotion
      return s;
    };
    if (d == ts::Domain::quad) {
      const int i0 = inner(v[4]), i1 = inner(v[5]);
      if (all_one && gl_segments(p, v[4]) == 1 && gl_segments(p, v[5]) == 1) {
        CHECK(pattern.primitive_count() == 2);
        continue;
      }
      CHECK(pattern.primitive_count() ==
            std::size_t(2 * (i0 - 2) * (i1 - 2) + 2 * (i0 - 2) + 2 * (i1 - 2) + sum_outer));
      CHECK(pattern.points.size() == std::size_t(sum_outer + (i0 - 1) * (i1 - 1)));
    } else {
      if (all_one && gl_segments(p, v[3]) == 1) {
        CHECK(pattern.primitive_count() == 1);
        continue;
      }
      const int in = inner(v[3]);
      std::size_t tris = std::size_t(sum_outer);
      for (int k = 0;; ++k) {
        const int level = in - 2 * (k + 1);
        if (level < 1) break;
        tris += level == 1 ? 4 : std::size_t(6 * level);
      }
      CHECK(pattern.primitive_count() == tris);
      const int r = (in + 1) / 2 - 1;
      const int interior = (in % 2) ? 3 * r * r : 3 * r * (r + 1) + 1;
      CHECK(pattern.points.size() == std::size_t(sum_outer + interior));
    }
  }
}

TEST_CASE("property 5: range, grid and exact complements", "[tessellator][properties]") {
  Rng rng(5);
  for (int i = 0; i < kCases; ++i) {
    const auto d = std::array{ts::Domain::quad, ts::Domain::tri, ts::Domain::isoline}[std::size_t(i % 3)];
    const auto p = kAllPartitionings[std::size_t(rng.integer(0, 3))];
    const auto pattern = run(p, ts::OutputPrimitive::point, random_factors(rng, d, 0.6, 66));
    for (const auto& pt : pattern.points) {
      for (float c : {pt.u, pt.v}) {
        REQUIRE(c >= 0.0f);
        REQUIRE(c <= 1.0f);
        REQUIRE(double(c) * 65536.0 == std::floor(double(c) * 65536.0));  // on the 2^-16 grid
        REQUIRE(c + (1.0f - c) == 1.0f);
        REQUIRE(1.0f - (1.0f - c) == c);
      }
      if (d == ts::Domain::tri) {
        const float w = (1.0f - pt.u) - pt.v;
        REQUIRE(double(w) == 1.0 - double(pt.u) - double(pt.v));  // exact in float
        REQUIRE(w >= 0.0f);
      }
    }
  }
}

TEST_CASE("properties 6, 7, 8, 19: edges depend only on their factor, are symmetric and interchangeable",
          "[tessellator][properties]") {
  Rng rng(6);
  for (int i = 0; i < kCases; ++i) {
    const auto p = kAllPartitionings[std::size_t(rng.integer(0, 3))];
    const float shared = rng.factor(0.6, 40);
    // Two quads and a triangle that share the factor on some edge, everything else random.
    auto a = random_factors(rng, ts::Domain::quad), b = random_factors(rng, ts::Domain::quad),
         t = random_factors(rng, ts::Domain::tri);
    const int ea = rng.integer(0, 3), eb = rng.integer(0, 3), et = rng.integer(0, 2);
    a.values[std::size_t(ea)] = shared, b.values[std::size_t(eb)] = shared, t.values[std::size_t(et)] = shared;
    const auto pa = ts::process_factors(p, a), pb = ts::process_factors(p, b), pt = ts::process_factors(p, t);
    const auto A = run(p, ts::OutputPrimitive::point, a), B = run(p, ts::OutputPrimitive::point, b),
               T = run(p, ts::OutputPrimitive::point, t);
    const auto sa = edge_parameters(A, pa, ea), sb = edge_parameters(B, pb, eb), st = edge_parameters(T, pt, et);
    INFO("partitioning " << ts::to_string(p) << " shared factor " << shared << " edges " << ea << " " << eb << " "
                         << et);
    REQUIRE(sa == sb);  // 6 + 8: independent of the other factors and of which edge
    REQUIRE(sa == st);  // 19: a quad edge and a triangle edge with the same factor match bit for bit
    for (float x : sa) REQUIRE(std::binary_search(sa.begin(), sa.end(), 1.0f - x));  // 7: exact symmetry
  }
}

TEST_CASE("property 9: cw and ccw give the same triangles, cw has positive area", "[tessellator][properties]") {
  Rng rng(9);
  for (int i = 0; i < kCases; ++i) {
    const auto [d, p, f] = random_patch(rng, i);
    const auto cw = run(p, ts::OutputPrimitive::triangle_cw, f), ccw = run(p, ts::OutputPrimitive::triangle_ccw, f);
    REQUIRE(cw.points == ccw.points);
    REQUIRE(cw.indices.size() == ccw.indices.size());
    const bool folds =
        p == ts::Partitioning::fractional_even && std::any_of(f.values.begin(), f.values.end(), in_fold_window);
    for (std::size_t k = 0; k < cw.indices.size(); k += 3) {
      REQUIRE(cw.indices[k] == ccw.indices[k]);
      REQUIRE(cw.indices[k + 1] == ccw.indices[k + 2]);
      REQUIRE(cw.indices[k + 2] == ccw.indices[k + 1]);
      if (!folds)
        REQUIRE(doubled_area(cw.points[cw.indices[k]], cw.points[cw.indices[k + 1]], cw.points[cw.indices[k + 2]]) >=
                0);
    }
  }
}

TEST_CASE("properties 10 and 11: interior and edge strips depend only on their own factors",
          "[tessellator][properties]") {
  Rng rng(10);
  for (int i = 0; i < kCases; ++i) {
    const auto d = i % 2 ? ts::Domain::quad : ts::Domain::tri;
    const int edges = d == ts::Domain::quad ? 4 : 3;
    const auto p = kAllPartitionings[std::size_t(rng.integer(0, 3))];
    auto a = random_factors(rng, d, 2.0, 24), b = a;
    const int keep = rng.integer(0, edges - 1);  // edge whose strip must not change
    for (int e = 0; e < edges; ++e)
      if (e != keep) b.values[std::size_t(e)] = rng.factor(2.0, 24);
    const auto pa = ts::process_factors(p, a), pb = ts::process_factors(p, b);
    const auto A = run(p, ts::OutputPrimitive::triangle_cw, a), B = run(p, ts::OutputPrimitive::triangle_cw, b);
    auto collect = [&](const ts::Pattern& P, const ts::ProcessedFactors& pf) {
      std::set<Tri> interior, strip;
      const std::size_t outer = outer_ring_points(pf);
      for (std::size_t k = 0; k < P.indices.size(); k += 3) {
        const std::uint32_t ix[3] = {P.indices[k], P.indices[k + 1], P.indices[k + 2]};
        int boundary = 0, on_keep = 0, on_keep_inner = 0;
        for (auto x : ix) {
          if (x < outer) ++boundary;
          if (x < outer && on_edge(d, keep, P.points[x])) {
            ++on_keep;
            const float t = edge_parameter(d, keep, P.points[x]);
            if (t != 0.0f && t != 1.0f) ++on_keep_inner;
          }
        }
        const Tri tri_ = canonical_triangle(P.points[ix[0]], P.points[ix[1]], P.points[ix[2]]);
        if (boundary == 0) interior.insert(tri_);
        if (on_keep >= 2 || on_keep_inner >= 1) strip.insert(tri_);  // the strip stitched to edge `keep`
      }
      return std::pair{interior, strip};
    };
    const auto [ia, sa] = collect(A, pa);
    const auto [ib, sb] = collect(B, pb);
    INFO("partitioning " << ts::to_string(p) << " domain " << ts::to_string(d) << " kept edge " << keep);
    REQUIRE(ia == ib);
    REQUIRE(sa == sb);
  }
}

TEST_CASE("property 12: coverage, no T-junctions inside a patch", "[tessellator][properties]") {
  Rng rng(12);
  for (int i = 0; i < kCases; ++i) {
    const auto [d, p, f] = random_patch(rng, i, 0.6, 30);
    const auto P = run(p, ts::OutputPrimitive::triangle_cw, f);
    std::int64_t area = 0;
    bool zero_area = false;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (std::size_t k = 0; k < P.indices.size(); k += 3) {
      const auto a2 = doubled_area(P.points[P.indices[k]], P.points[P.indices[k + 1]], P.points[P.indices[k + 2]]);
      area += a2;
      zero_area = zero_area || a2 == 0;
      for (int e = 0; e < 3; ++e) ++directed[{P.indices[k + std::size_t(e)], P.indices[k + std::size_t((e + 1) % 3)]}];
    }
    INFO("partitioning " << ts::to_string(p) << " domain " << ts::to_string(d));
    // Total signed area, doubled, on the 2^-16 grid: quad 2 * 1, tri 2 * 1/2.
    REQUIRE(area == (d == ts::Domain::quad ? 2 : 1) * (std::int64_t(1) << 32));
    if (zero_area) continue;  // coincident points (allowed near thresholds) break edge pairing
    for (const auto& [edge, count] : directed) {
      REQUIRE(count == 1);
      if (!directed.count({edge.second, edge.first})) {
        const auto a = P.points[edge.first], b = P.points[edge.second];
        bool boundary = false;
        for (int e = 0; e < (d == ts::Domain::quad ? 4 : 3); ++e)
          boundary = boundary || (on_edge(d, e, a) && on_edge(d, e, b));
        REQUIRE(boundary);
      }
    }
  }
}

TEST_CASE("property 13: point mode lists the triangle-mode points", "[tessellator][properties]") {
  Rng rng(13);
  for (int i = 0; i < kCases / 2; ++i) {
    const auto [d, p, f] = random_patch(rng, i);
    const auto pts = run(p, ts::OutputPrimitive::point, f), tris = run(p, ts::OutputPrimitive::triangle_cw, f);
    REQUIRE(pts.points == tris.points);
    REQUIRE(pts.indices.size() == pts.points.size());
    for (std::uint32_t k = 0; k < pts.indices.size(); ++k) REQUIRE(pts.indices[k] == k);
  }
}

TEST_CASE("property 14: integer spacing is i * round(65536/n), mirrored", "[tessellator][properties]") {
  for (int n = 1; n <= 64; ++n) {
    const auto P = run(ts::Partitioning::integer, ts::OutputPrimitive::point, iso(1, float(n)));
    REQUIRE(P.points.size() == std::size_t(n + 1));
    const std::uint32_t r = ts::kFixedReciprocal[std::size_t(n)];
    for (int i = 0; i <= n; ++i) {
      const std::uint32_t want = 2 * i == n  ? 0x8000u
                                 : 2 * i < n ? std::uint32_t(i) * r
                                             : 0x10000u - std::uint32_t(n - i) * r;
      REQUIRE(fx(P.points[std::size_t(i)].u) == want);
      REQUIRE(std::abs(double(P.points[std::size_t(i)].u) - double(i) / n) <= 2e-4);
    }
  }
}

TEST_CASE("property 15: fractional spacing is n-2 equal segments and 2 shorter symmetric ones",
          "[tessellator][properties]") {
  Rng rng(15);
  for (auto p : {ts::Partitioning::fractional_odd, ts::Partitioning::fractional_even}) {
    for (int i = 0; i < 300; ++i) {
      const float f = float(rng.uniform(p == ts::Partitioning::fractional_even ? 2.0 : 1.0, 63.0));
      if (in_fold_window(f) || near_threshold(f)) continue;
      const auto P = run(p, ts::OutputPrimitive::point, iso(1, f));
      std::vector<std::int64_t> seg;
      for (std::size_t k = 1; k < P.points.size(); ++k)
        seg.push_back(std::int64_t(fx(P.points[k].u)) - std::int64_t(fx(P.points[k - 1].u)));
      INFO(ts::to_string(p) << " " << f);
      for (std::size_t k = 0; k < seg.size(); ++k)
        REQUIRE(std::llabs(seg[k] - seg[seg.size() - 1 - k]) <= 0);  // symmetric
      std::vector<std::int64_t> sorted = seg;
      std::sort(sorted.begin(), sorted.end());
      if (sorted.size() >= 3) {
        // All but the two shortest are equal up to rounding, except that the middle segment (odd)
        // or the two beside the midpoint (even) absorb the reciprocal table's error: each half
        // edge is off 1/2 by up to n/2 * 0.5 ulp16 (12 ulp16 at n = 53, see property 14).
        const auto n = std::int64_t(seg.size());
        REQUIRE(sorted.back() - sorted[2] <= 2 + n / 2);
        REQUIRE(sorted[1] - sorted[0] <= 4);
      }
    }
  }
}

TEST_CASE("property 18: isolines", "[tessellator][properties]") {
  Rng rng(18);
  for (int i = 0; i < 200; ++i) {
    const auto p = kAllPartitionings[std::size_t(rng.integer(0, 3))];
    const float density = rng.factor(0.6, 70), detail = rng.factor(0.6, 70);
    const auto P = run(p, ts::OutputPrimitive::line, iso(density, detail));
    const int lines = int(std::ceil(std::clamp(density, 1.0f, 64.0f)));  // always integer, whatever the partitioning
    const std::size_t per = P.points.size() / std::size_t(lines);
    REQUIRE(P.points.size() == per * std::size_t(lines));
    std::vector<float> v;
    for (int l = 0; l < lines; ++l) {
      v.push_back(P.points[std::size_t(l) * per].v);
      for (std::size_t k = 0; k < per; ++k) {
        REQUIRE(P.points[std::size_t(l) * per + k].v == v.back());
        REQUIRE(P.points[std::size_t(l) * per + k].u == P.points[k].u);  // same u set on every line
      }
    }
    REQUIRE(v.front() == 0.0f);
    REQUIRE(v.back() < 1.0f);  // no line at v = 1
    for (int k = 1; k < lines; ++k) REQUIRE(v[std::size_t(k)] == 1.0f - v[std::size_t(lines - k)]);
    REQUIRE(P.primitive_count() == std::size_t(lines) * (per - 1));
  }
}

TEST_CASE("processed factors decide the pattern (pattern caches are sound)", "[tessellator][properties]") {
  Rng rng(20);
  for (int i = 0; i < kCases; ++i) {
    const auto d = i % 2 ? ts::Domain::quad : ts::Domain::tri;
    const auto p = kAllPartitionings[std::size_t(rng.integer(0, 3))];
    // Different raw factors that process to the same thing: integer rounding makes many.
    auto a = random_factors(rng, d, 0.6, 12), b = a;
    if (p == ts::Partitioning::integer || p == ts::Partitioning::pow2)
      for (auto& x : b.values) x = std::ceil(x);
    const auto pa = ts::process_factors(p, a), pb = ts::process_factors(p, b);
    REQUIRE(pa == pb);
    REQUIRE(ts::hash(pa, ts::OutputPrimitive::triangle_cw) == ts::hash(pb, ts::OutputPrimitive::triangle_cw));
    const auto A = run(p, ts::OutputPrimitive::triangle_cw, a), B = run(p, ts::OutputPrimitive::triangle_cw, b);
    REQUIRE(A.points == B.points);
    REQUIRE(A.indices == B.indices);
  }
}

TEST_CASE("primitive_count() is the generated pattern's primitive count", "[tessellator][properties]") {
  // Every small integer factor set of each domain (all parities, ring counts, minimal and culled
  // cases), then random real factors up to past the clamp, with NaN and infinities mixed in.
  const std::array<ts::OutputPrimitive, 4> outputs = {ts::OutputPrimitive::point, ts::OutputPrimitive::line,
                                                      ts::OutputPrimitive::triangle_cw,
                                                      ts::OutputPrimitive::triangle_ccw};
  std::size_t checked = 0, culled = 0, largest = 0;
  ts::Pattern pattern;
  const auto check = [&](ts::Partitioning p, const ts::FactorSet& f) {
    const ts::ProcessedFactors processed = ts::process_factors(p, f);
    for (ts::OutputPrimitive o : outputs) {
      ts::generate(processed, o, pattern);
      const std::size_t count = ts::primitive_count(processed, o);
      if (count != pattern.primitive_count()) {
        INFO("domain " << ts::to_string(f.domain) << ", " << ts::to_string(p) << ", " << ts::to_string(o)
                       << ", factors " << f.values[0] << " " << f.values[1] << " " << f.values[2] << " " << f.values[3]
                       << " " << f.values[4] << " " << f.values[5]);
        REQUIRE(count == pattern.primitive_count());
      }
      ++checked;
      culled += processed.culled ? 1 : 0;
      largest = std::max(largest, count);
    }
  };
  for (ts::Partitioning p : kAllPartitionings) {
    for (int a = 0; a < 5 * 5 * 5 * 5 * 5 * 5; ++a) {  // quad: 1..5 on all six factors
      ts::FactorSet f{ts::Domain::quad, {}};
      for (int k = 0, r = a; k < 6; ++k, r /= 5) f.values[std::size_t(k)] = float(1 + r % 5);
      check(p, f);
    }
    for (int a = 0; a < 9 * 9 * 9 * 9; ++a) {  // tri: 1..9 on all four
      ts::FactorSet f{ts::Domain::tri, {}};
      for (int k = 0, r = a; k < 4; ++k, r /= 9) f.values[std::size_t(k)] = float(1 + r % 9);
      check(p, f);
    }
    for (int a = 0; a < 70 * 70; a += 7) check(p, ts::FactorSet{ts::Domain::isoline, {float(a % 70), float(a / 70)}});
  }
  Rng rng(31);
  const std::array<float, 6> special = {kNan, kInf, -kInf, -1.0f, 0.0f, 1e30f};
  for (int i = 0; i < 6000; ++i) {
    const ts::Domain d = i % 3 == 0 ? ts::Domain::quad : i % 3 == 1 ? ts::Domain::tri : ts::Domain::isoline;
    ts::FactorSet f = random_factors(rng, d, 0.5, 70.0);
    if (rng.chance(0.02)) f.values[std::size_t(rng.integer(0, 5))] = special[std::size_t(rng.integer(0, 5))];
    check(kAllPartitionings[std::size_t(rng.integer(0, 3))], f);
  }
  for (ts::Partitioning p : kAllPartitionings) check(p, ts::FactorSet{ts::Domain::quad, {64, 64, 64, 64, 64, 64}});
  CHECK(checked > 380000);
  CHECK(culled > 0);
  CHECK(largest == 64u * 64u * 2u);  // quad, every factor 64: 8192 triangles
}
