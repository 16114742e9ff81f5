// Shared by the subdivision and displacement watertightness tests: the partitionings and per-edge
// factor variations they weld at, and what a closed weld must show.
#pragma once

#include <array>

#include <catch2/catch.hpp>

#include "tessellator/tessellator.h"
#include "tools/verify/weld_check.h"

namespace tessera::test {

// A base factor and how much it varies from edge to edge (so neighbouring patches disagree on their
// inside factors while sharing each edge's factor).
struct VaryingFactors {
  ts::Partitioning partitioning;
  float factor, vary;
};
inline constexpr std::array<VaryingFactors, 3> kVaryingFactors = {
    VaryingFactors{ts::Partitioning::integer, 3.0f, 1.0f}, VaryingFactors{ts::Partitioning::fractional_odd, 2.3f, 1.7f},
    VaryingFactors{ts::Partitioning::fractional_even, 2.6f, 1.3f}};

// Welded on exact bits, every edge is used twice, once each way, and no triangle collapsed.
inline void check_watertight(const verify::WeldReport& r) {
  CHECK(r.closed_manifold());
  CHECK(r.open_edges == 0);
  CHECK(r.nonmanifold_edges == 0);
  CHECK(r.degenerate_triangles == 0);
}

}  // namespace tessera::test
