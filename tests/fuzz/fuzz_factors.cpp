// libFuzzer harness: raw tessellation factors (any float bits: NaN, ±inf, denormals, huge) through
// process_factors -> generate, for every domain, partitioning and output primitive, checking the
// tessellator's invariants: points inside the domain, indices in range, primitive counts as
// predicted, and a shared edge's points identical in two patches that agree on its factor only.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <vector>

#include "tessellator/tessellator.h"

namespace {

using namespace tessera::ts;

[[noreturn]] void broken(const char* what, double a, double b) {
  std::fprintf(stderr, "fuzz_factors: invariant broken: %s (%.9g, %.9g)\n", what, a, b);
  std::abort();
}

void check_pattern(const ProcessedFactors& p, OutputPrimitive output, const Pattern& out) {
  if (p.culled) {
    if (!out.points.empty() || !out.indices.empty()) broken("a culled patch has points", double(out.points.size()), 0);
    return;
  }
  for (const DomainPoint& d : out.points) {
    if (!(d.u >= 0.0f && d.u <= 1.0f && d.v >= 0.0f && d.v <= 1.0f)) broken("a point outside [0, 1]^2", d.u, d.v);
    if (p.domain == Domain::tri && !(d.u + d.v <= 1.0f + 1e-6f)) broken("a tri point outside u + v <= 1", d.u, d.v);
  }
  for (const std::uint32_t i : out.indices)
    if (i >= out.points.size()) broken("an index out of range", i, double(out.points.size()));
  if (out.primitive_count() != primitive_count(p, output))
    broken("primitive_count disagrees with generate", double(out.primitive_count()),
           double(primitive_count(p, output)));
  if (out.points.size() > kMaxPointCount || out.indices.size() > kMaxIndexCount)
    broken("a pattern larger than its bound", double(out.points.size()), double(out.indices.size()));
}

// The v coordinates of the points on the edge u == edge_u, sorted.
std::vector<float> edge_points(const Pattern& p, float edge_u) {
  std::vector<float> v;
  for (const DomainPoint& d : p.points)
    if (d.u == edge_u) v.push_back(d.v);
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2 + 8 * sizeof(float)) return 0;
  const Partitioning partitioning = Partitioning(data[0] % 4);
  const OutputPrimitive output = OutputPrimitive(data[1] % 4);
  float f[8];
  std::memcpy(f, data + 2, sizeof f);
  Pattern out;
  for (const Domain domain : {Domain::quad, Domain::tri, Domain::isoline}) {
    FactorSet set{domain, {f[0], f[1], f[2], f[3], f[4], f[5]}};
    const ProcessedFactors p = process_factors(partitioning, set);
    generate(p, output, out);
    check_pattern(p, output, out);
  }
  // Two quads sharing an edge (A's u = 1 is B's u = 0) that agree on its factor f[6] only.
  if (output == OutputPrimitive::point || output == OutputPrimitive::line) return 0;
  Pattern a, b;
  const ProcessedFactors pa = process_quad_factors(partitioning, {f[0], f[1], f[6], f[3], f[4], f[5]});
  const ProcessedFactors pb = process_quad_factors(partitioning, {f[6], f[2], f[7], f[1], f[5], f[4]});
  generate(pa, output, a);
  generate(pb, output, b);
  if (pa.culled || pb.culled) return 0;
  // Under fractional partitioning an inside factor just above an odd integer (a denormal inside
  // factor is bumped to 1 + epsilon) collapses its ring onto the domain's edges, so interior points
  // lie on the edge line too: D3D11's reference does the same (llvmpipe's dump of the first input this
  // harness flagged, tests/fuzz/regressions/factors/, matches Tessera's bit for bit). The edge's own
  // points are then not separable from the pattern; the check holds for integer and pow2, where rings
  // never collapse.
  if (partitioning == Partitioning::fractional_odd || partitioning == Partitioning::fractional_even) return 0;
  const std::vector<float> ea = edge_points(a, 1.0f), eb = edge_points(b, 0.0f);
  if (ea.size() != eb.size()) broken("a shared edge has different point counts", double(ea.size()), double(eb.size()));
  for (std::size_t i = 0; i < ea.size(); ++i)
    if (std::memcmp(&ea[i], &eb[i], sizeof(float)) != 0) broken("a shared edge point differs", ea[i], eb[i]);
  return 0;
}
