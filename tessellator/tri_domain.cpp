// Triangle domain: an outer ring of three edges, inner rings scaled by 2/3 towards the centre.
//
// Point order: Ueq0 from (u,v) = (0,1) with v decreasing, Veq0 from (0,0) with u increasing, Weq0
// from (1,0) with u decreasing; then each inner ring the same way. Even parity ends with the
// centre point (0x5555, 0x5555); odd parity ends with one centre triangle. Because the inner
// points are rounded in (u, v) with w implicit, they are not exactly symmetric under permutation
// of (u, v, w): that 1-ulp asymmetry is part of the reference and is reproduced here.
#include "tessellator/domains.h"
#include "tessellator/edge_context.h"
#include "tessellator/stitch.h"

namespace tessera::ts::detail {

void tri_generate_points(const ProcessedFactors& p, std::vector<DomainPoint>& points) {
  for (int edge = 0; edge < 3; ++edge) {
    const EdgeContext& e = p.outside[static_cast<std::size_t>(edge)];
    const int last = e.num_points - 1;
    for (int i = 0; i < last; ++i) {
      const Fxp t = place_point(e, edge == 1 ? i : last - i);
      if (edge == 0)
        points.push_back(make_point(0, t));
      else
        points.push_back(make_point(t, edge == 2 ? kFxpOne - t : 0));
    }
  }

  const EdgeContext& in = p.inside[0];
  const int rings = in.num_points >> 1;
  for (int ring = 1; ring < rings; ++ring) {
    const int first = ring, end = in.num_points - 1 - ring;
    // Distance of this ring from each edge, in barycentric units: 2/3 of the 1D placement.
    Fxp perp = place_point(in, first);
    perp = (perp * kFxpTwoThirds + kFxpOneHalf) >> kFxpFractionBits;
    const Fxp shift = (perp + 1) / 2;  // moving in from two edges pulls the parallel coordinate by half
    for (int edge = 0; edge < 3; ++edge) {
      for (int i = first; i < end; ++i) {
        const Fxp t = place_point(in, edge == 1 ? i : end - (i - first));
        switch (edge) {
          case 0: points.push_back(make_point(perp, t - shift)); break;
          case 1: points.push_back(make_point(t - shift, perp)); break;
          default: points.push_back(make_point(t - shift, kFxpOne - (t - shift) - perp)); break;
        }
      }
    }
  }
  if (in.parity == Parity::even) points.push_back(make_point(kFxpOneThird, kFxpOneThird));
}

void tri_generate_connectivity(const ProcessedFactors& p, bool ccw, std::vector<std::uint32_t>& indices) {
  TriangleWriter out(indices, ccw);
  const EdgeContext& in = p.inside[0];
  const int rings = (in.num_points + 1) >> 1;  // even: the centre point counts as a ring
  std::array<const EdgeContext*, 3> outer = {&p.outside[0], &p.outside[1], &p.outside[2]};
  std::array<int, 3> outer_points = {p.outside[0].num_points, p.outside[1].num_points, p.outside[2].num_points};
  int inside_base = outer_points[0] + outer_points[1] + outer_points[2] - 3;
  int outside_base = 0;
  for (int ring = 1; ring < rings; ++ring) {
    const int ni = in.num_points - 2 * ring;
    const int ring_inside_start = inside_base, ring_outside_start = outside_base;
    for (int edge = 0; edge < 3; ++edge) {
      const int no = outer_points[static_cast<std::size_t>(edge)];
      Row inside{inside_base}, outside{outside_base};
      if (edge == 2) {  // the last side closes the ring on its first points
        inside.wrap_at = ni - 1, inside.wrap_to = ring_inside_start;
        outside.wrap_at = no - 1, outside.wrap_to = ring_outside_start;
      }
      if (ring == 1) {
        stitch_transition(out, inside, in.num_half_points, in.parity, outside,
                          outer[static_cast<std::size_t>(edge)]->num_half_points,
                          outer[static_cast<std::size_t>(edge)]->parity);
      } else {
        stitch_regular(out, /*trapezoid=*/true, Diagonals::mirrored, ni, inside, outside);
      }
      outside_base += no - 1;
      inside_base += ni - 1;
      outer_points[static_cast<std::size_t>(edge)] = ni;
    }
    if (ring == 1) outer = {&in, &in, &in};
  }
  if (in.parity == Parity::odd) out.clockwise(outside_base, outside_base + 1, outside_base + 2);
}

}  // namespace tessera::ts::detail
