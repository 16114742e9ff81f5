// How many primitives generate() makes, from the processed factors alone: the ring and stitch
// structure of quad_domain.cpp, tri_domain.cpp and isoline_domain.cpp, counted instead of walked.
// A pipeline cuts its work into chunks by primitive count before any pattern is needed; counting by
// generating the pattern tessellated each patch twice when factors vary from patch to patch.
#include <algorithm>
#include <array>

#include "tessellator/domains.h"
#include "tessellator/tessellator.h"

namespace tessera::ts {
namespace {

// stitch_transition's triangles: each row advances once per split-order entry below its (even)
// half-point count on each half, the outside row also at the corner entry, and the middle adds a
// quad (both odd), one triangle (parities differ) or nothing (both even).
std::size_t transition_triangles(const EdgeContext& inside, const EdgeContext& outside) {
  const int in_half = inside.num_half_points - (inside.parity == Parity::odd ? 1 : 0);
  const int out_half = outside.num_half_points - (outside.parity == Parity::odd ? 1 : 0);
  const bool both_odd = inside.parity == Parity::odd && outside.parity == Parity::odd;
  const int middle = both_odd ? 2 : inside.parity != outside.parity ? 1 : 0;
  return std::size_t(2 * std::max(out_half, 0) + 2 * std::max(in_half - 1, 0) + middle);
}

std::size_t quad_points(const ProcessedFactors& p) {
  if (p.minimal) return 4;
  std::size_t count = 0;
  for (const EdgeContext& e : p.outside) count += std::size_t(e.num_points - 1);
  const int nu = p.inside[0].num_points, nv = p.inside[1].num_points;
  const int rings = std::min(nu, nv) >> 1;
  for (int ring = 1; ring < rings; ++ring) count += std::size_t(2 * (nu - 1 - 2 * ring) + 2 * (nv - 1 - 2 * ring));
  if (nu > nv && p.inside[1].parity == Parity::even)
    count += std::size_t(nu - 2 * rings);
  else if (nv >= nu && p.inside[0].parity == Parity::even)
    count += std::size_t(nv - 2 * rings);
  return count;
}

std::size_t quad_triangles(const ProcessedFactors& p) {
  if (p.minimal) return 2;
  const std::array<int, 2> n = {p.inside[0].num_points, p.inside[1].num_points};
  const int rings = detail::quad_rings(p);
  std::size_t count = 0;
  for (int ring = 1; ring < rings; ++ring)
    for (int edge = 0; edge < 4; ++edge) {
      const int along = (edge + 1) & 1;
      if (ring == 1)
        count += transition_triangles(p.inside[std::size_t(along)], p.outside[std::size_t(edge)]);
      else
        count += std::size_t(2 * (n[std::size_t(along)] - 2 * ring));  // a trapezoid: 2 per inside point
    }
  return count + std::size_t(2 * detail::quad_middle_strip(p).quads);
}

std::size_t tri_points(const ProcessedFactors& p) {
  if (p.minimal) return 3;
  std::size_t count = 0;
  for (int edge = 0; edge < 3; ++edge) count += std::size_t(p.outside[std::size_t(edge)].num_points - 1);
  const int n = p.inside[0].num_points, rings = n >> 1;
  for (int ring = 1; ring < rings; ++ring) count += std::size_t(3 * (n - 1 - 2 * ring));
  return count + (p.inside[0].parity == Parity::even ? 1 : 0);
}

std::size_t tri_triangles(const ProcessedFactors& p) {
  if (p.minimal) return 1;
  const int n = p.inside[0].num_points, rings = (n + 1) >> 1;
  std::size_t count = 0;
  for (int ring = 1; ring < rings; ++ring)
    for (int edge = 0; edge < 3; ++edge)
      count +=
          ring == 1 ? transition_triangles(p.inside[0], p.outside[std::size_t(edge)]) : std::size_t(2 * (n - 2 * ring));
  return count + (p.inside[0].parity == Parity::odd ? 1 : 0);
}

}  // namespace

std::size_t primitive_count(const ProcessedFactors& p, OutputPrimitive output) {
  if (p.culled) return 0;
  if (p.domain == Domain::isoline) {
    const std::size_t lines = std::size_t(p.outside[0].num_points - 1), per_line = std::size_t(p.outside[1].num_points);
    return output == OutputPrimitive::point ? lines * per_line : lines * (per_line - 1);
  }
  const std::size_t points = p.domain == Domain::quad ? quad_points(p) : tri_points(p);
  switch (output) {
    case OutputPrimitive::point: return points;
    case OutputPrimitive::line: return points - 1;  // the points in order, as one line list
    case OutputPrimitive::triangle_cw:
    case OutputPrimitive::triangle_ccw: break;
  }
  return p.domain == Domain::quad ? quad_triangles(p) : tri_triangles(p);
}

}  // namespace tessera::ts
