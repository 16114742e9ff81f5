// The HLSL helper layer (Process*TessFactors*): hand-computed cases.
#include <catch2/catch.hpp>

#include <limits>

#include "tessellator/hlsl_helpers.h"

using namespace tessera::ts;
using namespace tessera::ts::hlsl;

TEST_CASE("edge cleanup, scale clamp, rounding and clamping", "[tessellator][hlsl]") {
  CHECK(cleanup_edge_factor(std::numeric_limits<float>::quiet_NaN()) == 1.0f);
  CHECK(cleanup_edge_factor(0.25f) == 1.0f);
  CHECK(cleanup_edge_factor(7.5f) == 7.5f);
  CHECK(clamp_scale(std::numeric_limits<float>::quiet_NaN()) == 0.0f);
  CHECK(clamp_scale(-2.0f) == 0.0f);
  CHECK(clamp_scale(3.0f) == 1.0f);
  CHECK(clamp_scale(0.5f) == 0.5f);
  CHECK(round_factor(5.2f, Partitioning::integer) == 6.0f);
  CHECK(round_factor(5.2f, Partitioning::pow2) == 8.0f);
  CHECK(round_factor(8.0f, Partitioning::pow2) == 8.0f);
  CHECK(round_factor(1.5f, Partitioning::pow2) == 2.0f);
  CHECK(round_factor(5.2f, Partitioning::fractional_odd) == 5.2f);
  CHECK(clamp_factor(100.0f, Partitioning::fractional_odd) == 63.0f);
  CHECK(clamp_factor(1.0f, Partitioning::fractional_even) == 2.0f);
  CHECK(clamp_factor(100.0f, Partitioning::integer) == 64.0f);
}

TEST_CASE("quad reductions over cleaned, unrounded edges", "[tessellator][hlsl]") {
  const QuadFactors edges{2.5f, 4.0f, 6.5f, 8.0f, 1.0f, 1.0f};  // Ueq0 Veq0 Ueq1 Veq1, scales 1
  auto q = process_quad(Partitioning::integer, Reduction::min, QuadReductionAxis::one_axis, edges);
  CHECK(q.Ueq0 == 3.0f);
  CHECK(q.Ueq1 == 7.0f);
  CHECK(q.insideU == 3.0f);  // min 2.5 -> ceil 3 (odd, but not < 3: no anti-popping)
  CHECK(q.insideV == 3.0f);
  q = process_quad(Partitioning::integer, Reduction::average, QuadReductionAxis::one_axis, edges);
  CHECK(q.insideU == 6.0f);  // (4 + 8 + 2.5 + 6.5) / 4 = 5.25 -> 6
  q = process_quad(Partitioning::fractional_even, Reduction::max, QuadReductionAxis::two_axis, edges);
  CHECK(q.insideU == 8.0f);  // max(Veq0, Veq1)
  CHECK(q.insideV == 6.5f);  // max(Ueq0, Ueq1)
  QuadFactors unrounded{};
  q = process_quad(Partitioning::pow2, Reduction::average, QuadReductionAxis::two_axis, {3, 5, 3, 5, 1, 0.5f},
                   &unrounded);
  CHECK(q.Ueq0 == 4.0f);
  CHECK(q.Veq0 == 8.0f);
  CHECK(q.insideU == 8.0f);  // (5 + 5) / 2 = 5 -> pow2 8
  CHECK(q.insideV == 2.0f);  // (3 + 3) / 2 * 0.5 = 1.5 -> pow2 2
  CHECK(unrounded.insideV == 1.5f);
}

TEST_CASE("anti-popping: odd inside factors below 3 come in from the edges", "[tessellator][hlsl]") {
  // Scale 0 would make the inside 1 (odd in fractional_odd): replaced by min(3, average).
  auto q =
      process_quad(Partitioning::fractional_odd, Reduction::average, QuadReductionAxis::one_axis, {5, 5, 5, 5, 0, 0});
  CHECK(q.insideU == 3.0f);
  auto t = process_tri(Partitioning::fractional_odd, Reduction::min, {2, 2, 2, 0});
  CHECK(t.inside == 2.0f);  // min(3, average 2)
  t = process_tri(Partitioning::integer, Reduction::max, {1.5f, 2.5f, 1.0f, 0.1f});
  // max 2.5 * 0.1 = 0.25 -> clamp 1 -> ceil 1 -> even (1 counts as even): no anti-popping.
  CHECK(t.inside == 1.0f);
  t = process_tri(Partitioning::integer, Reduction::max, {1.5f, 2.5f, 1.0f, 0.9f});
  // 2.25 -> ceil 3: odd but not < 3.
  CHECK(t.inside == 3.0f);
  // 2 axes: an odd axis below 3 is raised to min(other axis, 3).
  q = process_quad(Partitioning::fractional_odd, Reduction::min, QuadReductionAxis::two_axis, {1, 9, 1, 9, 1, 1});
  CHECK(q.insideV == 3.0f);
}

TEST_CASE("culled inputs give zero factors, isolines round density as integer", "[tessellator][hlsl]") {
  const auto q = process_quad(Partitioning::integer, Reduction::min, QuadReductionAxis::one_axis, {0, 4, 4, 4, 1, 1});
  CHECK(q.Ueq0 == 0.0f);
  CHECK(q.insideU == 0.0f);
  CHECK(process_tri(Partitioning::integer, Reduction::min, {4, -1, 4, 1}).inside == 0.0f);
  const auto iso = process_isoline(Partitioning::fractional_odd, {2.2f, 3.5f});
  CHECK(iso.density == 3.0f);
  CHECK(iso.detail == 3.5f);
  CHECK(process_isoline(Partitioning::pow2, {70.0f, 5.0f}).detail == 8.0f);
  CHECK(process_isoline(Partitioning::pow2, {70.0f, 5.0f}).density == 64.0f);
}
