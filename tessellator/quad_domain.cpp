// Quad domain: an outer ring of four edges, then inner rings spiralling to the centre.
//
//   (0,0) ---- Veq0 ----> (1,0)        Point order (D3D11 reference): each ring clockwise in this
//     ^                     |          picture (v grows downwards), starting at (0,1) and going up
//    Ueq0                  Ueq1        the Ueq0 edge; each edge excludes its end point, which starts
//     |                     v          the next edge. Even-parity centres end with a row of points
//   (0,1) <---- Veq1 ---- (1,1)        (the degenerate innermost ring).
#include <algorithm>

#include "tessellator/domains.h"
#include "tessellator/edge_context.h"
#include "tessellator/stitch.h"

namespace tessera::ts::detail {
namespace {
constexpr int U = 0, V = 1;
}

void quad_generate_points(const ProcessedFactors& p, std::vector<DomainPoint>& points) {
  // Outer ring. Edges Ueq0 and Veq1 are walked from their far end.
  for (int edge = 0; edge < 4; ++edge) {
    const EdgeContext& e = p.outside[static_cast<std::size_t>(edge)];
    const int last = e.num_points - 1;
    const bool forward = edge == 1 || edge == 2;
    for (int i = 0; i < last; ++i) {
      const Fxp t = place_point(e, forward ? i : last - i);
      if (edge & 1)
        points.push_back(make_point(t, edge == 3 ? kFxpOne : 0));
      else
        points.push_back(make_point(edge == 2 ? kFxpOne : 0, t));
    }
  }

  // Inner rings, placed with the inside factors on both axes.
  const std::array<int, 2> n = {p.inside[U].num_points, p.inside[V].num_points};
  const int rings = std::min(n[U], n[V]) >> 1;  // an even centre's row of points is not a ring
  for (int ring = 1; ring < rings; ++ring) {
    const int first = ring;
    const std::array<int, 2> last = {n[U] - 1 - ring, n[V] - 1 - ring};
    for (int edge = 0; edge < 4; ++edge) {
      const int across = edge & 1;       // the axis held constant along this side
      const int along = (edge + 1) & 1;  // the axis that varies
      const Fxp perp = place_point(p.inside[static_cast<std::size_t>(across)],
                                   edge < 2 ? first : last[static_cast<std::size_t>(across)]);
      const EdgeContext& e = p.inside[static_cast<std::size_t>(along)];
      const int end = last[static_cast<std::size_t>(along)];
      const bool forward = edge == 1 || edge == 2;
      for (int i = first; i < end; ++i) {
        const Fxp t = place_point(e, forward ? i : end - (i - first));
        points.push_back(along == V ? make_point(perp, t) : make_point(t, perp));
      }
    }
  }

  // Even parity on the narrower axis leaves a centre row rather than a ring.
  if (n[U] > n[V] && p.inside[V].parity == Parity::even) {
    for (int i = rings; i <= n[U] - 1 - rings; ++i)
      points.push_back(make_point(place_point(p.inside[U], i), kFxpOneHalf));
  } else if (n[V] >= n[U] && p.inside[U].parity == Parity::even) {
    for (int i = n[V] - 1 - rings; i >= rings; --i)
      points.push_back(make_point(kFxpOneHalf, place_point(p.inside[V], i)));
  }
}

void quad_generate_connectivity(const ProcessedFactors& p, bool ccw, std::vector<std::uint32_t>& indices) {
  TriangleWriter out(indices, ccw);
  const std::array<int, 2> n = {p.inside[U].num_points, p.inside[V].num_points};
  const std::array<int, 2> rows_to_centre = {(n[U] + 1) >> 1, (n[V] + 1) >> 1};  // even: centre row included
  const int rings = quad_rings(p);
  // The ring whose inner side is an even centre row, per axis of that row (-1: none). Walking
  // around such a ring, the return trip along the row runs backwards through the points.
  const std::array<int, 2> centre_row_ring = {p.inside[V].parity == Parity::even ? rows_to_centre[V] - 1 : -1,
                                              p.inside[U].parity == Parity::even ? rows_to_centre[U] - 1 : -1};

  std::array<const EdgeContext*, 4> outer = {&p.outside[0], &p.outside[1], &p.outside[2], &p.outside[3]};
  std::array<int, 4> outer_points = {p.outside[0].num_points, p.outside[1].num_points, p.outside[2].num_points,
                                     p.outside[3].num_points};
  int inside_base = outer_points[0] + outer_points[1] + outer_points[2] + outer_points[3] - 4;
  int outside_base = 0;
  for (int ring = 1; ring < rings; ++ring) {
    const std::array<int, 2> inner_points = {n[U] - 2 * ring, n[V] - 2 * ring};
    const int ring_inside_start = inside_base, ring_outside_start = outside_base;
    for (int edge = 0; edge < 4; ++edge) {
      const int along = (edge + 1) & 1;
      const int ni = inner_points[static_cast<std::size_t>(along)];
      const int no = outer_points[static_cast<std::size_t>(edge)];
      const bool backwards = ring == centre_row_ring[static_cast<std::size_t>(along)] && (edge == 2 || edge == 3);
      Row inside{inside_base};
      Row outside{outside_base};
      if (backwards) inside.step = -1;
      if (edge == 3) {  // the last side closes the ring on its first points
        outside.wrap_at = no - 1, outside.wrap_to = ring_outside_start;
        if (!backwards) inside.wrap_at = ni - 1, inside.wrap_to = ring_inside_start;
      }
      if (ring == 1) {
        const EdgeContext& in_ctx = p.inside[static_cast<std::size_t>(along)];
        stitch_transition(out, inside, in_ctx.num_half_points, in_ctx.parity, outside,
                          outer[static_cast<std::size_t>(edge)]->num_half_points,
                          outer[static_cast<std::size_t>(edge)]->parity);
      } else {
        stitch_regular(out, /*trapezoid=*/true, Diagonals::mirrored, ni, inside, outside);
      }
      outside_base += no - 1;
      inside_base += (backwards && edge == 2) ? -(ni - 1) : ni - 1;
      outer_points[static_cast<std::size_t>(edge)] = ni;
    }
    if (ring == 1)
      for (int edge = 0; edge < 4; ++edge)
        outer[static_cast<std::size_t>(edge)] = &p.inside[static_cast<std::size_t>(edge & 1)];
  }

  // Odd parity on the narrower axis leaves a strip of quads in the middle (the spec's "Z").
  // outside_base is now the first point of the innermost ring, two points wide.
  const int o = outside_base;
  const QuadMiddleStrip strip = quad_middle_strip(p);
  const int quads = strip.quads;
  if (quads > 0 && strip.along_u) {
    // The inside row is the ring's far side, walked back from its end; it starts at the ring's first point.
    const Row inside{o + 2 * quads + 2, -1, 0, o};
    stitch_regular(out, false, Diagonals::inside_to_outside, quads + 1, inside, Row{o + 1});
  } else if (quads > 0) {
    const Diagonals d =
        p.inside[V].parity == Parity::even ? Diagonals::inside_to_outside : Diagonals::inside_to_outside_except_middle;
    stitch_regular(out, false, d, quads + 1, Row{o + 2 * quads + 1, -1}, Row{o});
  }
}

}  // namespace tessera::ts::detail
