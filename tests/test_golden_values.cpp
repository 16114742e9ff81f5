// Golden values of the D3D11 reference tessellator (16.16 hex), from experiments with the
// reference code (shared/reference/tessellator.md §2.12, §2.11, property 21). Exact.
#include <catch2/catch.hpp>

#include "tessellator/fixed_point.h"
#include "test_support.h"

using namespace tessera;
using namespace tessera::test;

namespace {

// The u coordinates of an isoline with density 1: the 1D placement along one edge.
std::vector<std::uint32_t> edge_hex(ts::Partitioning p, float factor) {
  const auto pattern = run(p, ts::OutputPrimitive::point, iso(1, factor));
  std::vector<std::uint32_t> out;
  for (const auto& pt : pattern.points) {
    REQUIRE(pt.v == 0.0f);
    out.push_back(fx(pt.u));
  }
  return out;
}

}  // namespace

TEST_CASE("float_to_fixed rounds to nearest even on the float's bits", "[tessellator][fixed]") {
  CHECK(ts::float_to_fixed(1.0f) == 0x10000u);
  CHECK(ts::float_to_fixed(std::nanf("")) == 0u);
  CHECK(ts::float_to_fixed(-3.0f) == 0u);
  CHECK(ts::float_to_fixed(-0.0f) == 0u);
  CHECK(ts::float_to_fixed(1e-30f) == 0u);
  CHECK(ts::float_to_fixed(65536.0f) == 0xFFFFFFFFu);
  CHECK(ts::float_to_fixed(std::numeric_limits<float>::infinity()) == 0xFFFFFFFFu);
  // 3 + 2^-17 is a tie between 3.0 and 3 + 2^-16: it goes to the even one.
  CHECK(ts::float_to_fixed(3.0f + 0x1p-17f) == 0x30000u);
  CHECK(ts::float_to_fixed(3.0f + 0x1p-16f + 0x1p-17f) == 0x30002u);
  CHECK(ts::float_to_fixed(0x1p-17f) == 0u);  // tie at the bottom: even (0)
  CHECK(ts::float_to_fixed(0x1.8p-17f) == 1u);
  for (std::uint32_t x : {0u, 1u, 0x5555u, 0x8000u, 0xFFFFu, 0x10000u})
    CHECK(ts::float_to_fixed(ts::fixed_to_float(x)) == x);  // fixed -> float is exact
}

TEST_CASE("the reciprocal table is round(65536 / n)", "[tessellator][fixed]") {
  for (int n = 1; n <= 64; ++n) CHECK(ts::kFixedReciprocal[std::size_t(n)] == std::uint32_t(std::lround(65536.0 / n)));
}

TEST_CASE("golden edge placements match the reference", "[tessellator][golden]") {
  using P = ts::Partitioning;
  CHECK(edge_hex(P::integer, 7) ==
        std::vector<std::uint32_t>{0, 0x2492, 0x4924, 0x6DB6, 0x924A, 0xB6DC, 0xDB6E, 0x10000});
  CHECK(edge_hex(P::integer, 3) == std::vector<std::uint32_t>{0, 0x5555, 0xAAAB, 0x10000});
  CHECK(edge_hex(P::fractional_odd, 1.5f) == std::vector<std::uint32_t>{0, 0x1555, 0xEAAB, 0x10000});
  CHECK(edge_hex(P::fractional_odd, 3.5f) == std::vector<std::uint32_t>{0, 0x4CCD, 0x5999, 0xA667, 0xB333, 0x10000});
  CHECK(edge_hex(P::fractional_odd, 5.25f) ==
        std::vector<std::uint32_t>{0, 0x315F, 0x35F1, 0x6750, 0x98B0, 0xCA0F, 0xCEA1, 0x10000});
  CHECK(edge_hex(P::fractional_even, 2.5f) == std::vector<std::uint32_t>{0, 0x7000, 0x8000, 0x9000, 0x10000});
  CHECK(edge_hex(P::fractional_even, 5.0f) ==
        std::vector<std::uint32_t>{0, 0x3556, 0x4AAB, 0x8000, 0xB555, 0xCAAA, 0x10000});
  CHECK(edge_hex(P::fractional_even, 8.5f) ==
        std::vector<std::uint32_t>{0, 0x1E67, 0x24CD, 0x4334, 0x619A, 0x8000, 0x9E66, 0xBCCC, 0xDB33, 0xE199, 0x10000});
}

TEST_CASE("golden triangle (2,2,2 | 2), triangle_cw", "[tessellator][golden]") {
  const auto p = run(ts::Partitioning::integer, ts::OutputPrimitive::triangle_cw, tri(2, 2, 2, 2));
  const std::vector<std::array<std::uint32_t, 2>> want = {{0, 0x10000}, {0, 0x8000},      {0, 0},          {0x8000, 0},
                                                          {0x10000, 0}, {0x8000, 0x8000}, {0x5555, 0x5555}};
  REQUIRE(p.points.size() == want.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    CHECK(std::array<std::uint32_t, 2>{fx(p.points[i].u), fx(p.points[i].v)} == want[i]);
  CHECK(p.indices == std::vector<std::uint32_t>{0, 1, 6, 1, 2, 6, 2, 3, 6, 3, 4, 6, 4, 5, 6, 5, 0, 6});
}

TEST_CASE("property 21: bit-exactness pitfalls", "[tessellator][golden]") {
  SECTION("ties at n + 2^-17 round down to n segments") {
    // fractional_odd 3 + 2^-17 is a tie -> 3.0 in 16.16 -> 3 segments; 3 + 2^-16 -> 5 segments.
    CHECK(edge_hex(ts::Partitioning::fractional_odd, 3.0f + 0x1p-17f).size() == 4);
    CHECK(edge_hex(ts::Partitioning::fractional_odd, 3.0f + 0x1p-16f).size() == 6);
    CHECK(edge_hex(ts::Partitioning::fractional_even, 4.0f + 0x1p-17f).size() == 5);
    CHECK(edge_hex(ts::Partitioning::fractional_even, 4.0f + 0x1p-16f).size() == 7);
  }
  SECTION("fractional_even fold windows above 6 and 30 put points on the wrong side of 0.5") {
    for (float f : {6.00005f, 30.003f}) {
      const auto u = edge_hex(ts::Partitioning::fractional_even, f);
      const std::size_t mid = u.size() / 2;
      CHECK(u[mid] == 0x8000u);
      CHECK(u[mid - 1] > 0x8000u);  // e.g. 0x8005, 0x8000, 0x7FFB
      CHECK(u[mid + 1] < 0x8000u);
    }
    // Bases 14 and 62 do not fold.
    for (float f : {14.0001f, 62.0001f}) {
      const auto u = edge_hex(ts::Partitioning::fractional_even, f);
      CHECK(std::is_sorted(u.begin(), u.end()));
    }
  }
  SECTION("integer 7 gives 0x6DB6, not the correctly rounded 0x6DB7") {
    CHECK(edge_hex(ts::Partitioning::integer, 7)[3] == 0x6DB6u);
  }
  SECTION("the triangle centre is (0x5555, 0x5555) with w = 0x5556") {
    const auto p = run(ts::Partitioning::integer, ts::OutputPrimitive::point, tri(4, 4, 4, 4));
    const auto c = p.points.back();
    CHECK(fx(c.u) == 0x5555u);
    CHECK(fx(c.v) == 0x5555u);
    CHECK(fx((1.0f - c.u) - c.v) == 0x5556u);
  }
  SECTION("inner triangle vertices at (3,3,3 | 3) are not permutation-symmetric") {
    const auto p = run(ts::Partitioning::integer, ts::OutputPrimitive::point, tri(3, 3, 3, 3));
    std::set<std::array<std::uint32_t, 3>> inner;
    for (std::size_t i = 9; i < p.points.size(); ++i)
      inner.insert({fx(p.points[i].u), fx(p.points[i].v), fx((1.0f - p.points[i].u) - p.points[i].v)});
    const std::set<std::array<std::uint32_t, 3>> want = {
        {0x38E3, 0x8E39, 0x38E4}, {0x38E3, 0x38E3, 0x8E3A}, {0x8E39, 0x38E4, 0x38E3}};
    CHECK(inner == want);
  }
}

TEST_CASE("property 16: minimal cases", "[tessellator][golden]") {
  for (auto p : {ts::Partitioning::integer, ts::Partitioning::pow2, ts::Partitioning::fractional_odd}) {
    const auto q = run(p, ts::OutputPrimitive::triangle_cw, quad(1, 1, 1, 1, 1, 1));
    CHECK(q.points == std::vector<ts::DomainPoint>{{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    CHECK(q.indices == std::vector<std::uint32_t>{0, 1, 3, 1, 2, 3});
    const auto t = run(p, ts::OutputPrimitive::triangle_ccw, tri(1, 1, 1, 1));
    CHECK(t.points == std::vector<ts::DomainPoint>{{0, 1}, {0, 0}, {1, 0}});
    CHECK(t.indices == std::vector<std::uint32_t>{0, 2, 1});
  }
  // fractional_even clamps to 2: never minimal.
  CHECK(run(ts::Partitioning::fractional_even, ts::OutputPrimitive::triangle_cw, quad(1, 1, 1, 1, 1, 1))
            .primitive_count() == 8);
}

TEST_CASE("property 17: inside factor 1 is promoted when an edge is larger", "[tessellator][golden]") {
  const auto integer = ts::process_factors(ts::Partitioning::integer, quad(3, 1, 1, 1, 1, 1));
  CHECK(integer.inside[0].num_points - 1 == 2);
  CHECK(integer.inside[1].num_points - 1 == 2);
  const auto odd = ts::process_factors(ts::Partitioning::fractional_odd, tri(3, 1, 1, 1));
  CHECK(odd.inside[0].num_points - 1 == 3);
}
