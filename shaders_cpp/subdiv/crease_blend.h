// The masks' own crease construction for the per-face schemes (acc, gregory, bspline's fallback):
// what a patch gets where its face is not fitted to the exact limit (limit_fit.h): the n-gon fans, and
// faces Bfr gives no surface.
//
// Each patch is built twice, from the whole corner rings (smooth) and from the rings cut open at every
// crease (corner_ring.h: Catmull-Clark's crease and corner rules are the boundary rules on each side,
// so an infinitely sharp crease is exact where a boundary is), and the control points near corner k
// are blended by the sharpness s of its vertex: w = 1 - 2^-s (1 for infinitely sharp). A semi-sharp
// crease of sharpness s stays sharp for s subdivision steps and then relaxes over what is left, a band
// of width 2^-s of the face; the blend gives the sharp patch that share.
//
// Contract: rows shared with a neighbour (P and E points) come from the same vertex's rings and
// weight on both faces, so they stay bit-identical.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <vector>

#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/stencil.h"

namespace tessera::subdiv {

// A corner's blend weight from its vertex's sharpness s: 1 - 2^-s, 1 when infinitely sharp, 0 smooth.
double crease_weight(float s);

// Row r of a patch's stencils -> the corner whose sharpness blends it, or -1 for the mean of two
// (ACC's tangent rows between corners). Gregory quads and triangles: five rows per corner.
template <std::size_t N>
std::vector<Stencil> blend_by_corner(const std::vector<Stencil>& smooth, const std::vector<Stencil>& sharp,
                                     const std::array<double, N>& w, bool acc) {
  std::vector<Stencil> out(smooth.size());
  for (std::size_t r = 0; r < smooth.size(); ++r) {
    double weight = 0.0;
    if (!acc) {
      weight = w[r / 5];
    } else if (r < 16) {  // b(i, j): the corner of its quadrant
      const std::size_t i = r % 4, j = r / 4;
      weight = w[i < 2 ? (j < 2 ? 0 : 3) : (j < 2 ? 1 : 2)];
    } else if (r < 28) {  // du(i, j), i = 0..2 along u
      const std::size_t i = (r - 16) % 3, j = (r - 16) / 3;
      const double left = w[j < 2 ? 0 : 3], right = w[j < 2 ? 1 : 2];
      weight = i == 0 ? left : i == 2 ? right : 0.5 * (left + right);
    } else {  // dv(i, j), j = 0..2 along v
      const std::size_t i = (r - 28) % 4, j = (r - 28) / 4;
      const double low = w[i < 2 ? 0 : 1], high = w[i < 2 ? 3 : 2];
      weight = j == 0 ? low : j == 2 ? high : 0.5 * (low + high);
    }
    if (weight == 0.0) {
      out[r] = smooth[r];
    } else if (weight == 1.0) {
      out[r] = sharp[r];
    } else {
      out[r].add(smooth[r], 1.0 - weight).add(sharp[r], weight);
    }
  }
  return out;
}

// A semi-sharp vertex's corner: row `p_row` becomes the exact limit `exact` (semi_sharp_limit.h), when
// there is one. Its edge points (rows `e_rows`, a fan's spoke among them): at a crease vertex the crease
// runs the length of its edges and the blended points stand; a corner tag alone pulls the surface only
// within about 2^-s of the vertex, so its edge points, a third along the edges, are the smooth ones
// (`smooth`, the unblended rows) moved by that share of P's move. Every face at the vertex makes the
// same rows from the same stencils: shared points share bits.
void exact_corner(std::vector<Stencil>& stencils, const std::vector<Stencil>& smooth, const Topology& t, int vertex,
                  const std::optional<Stencil>& exact, std::size_t p_row, std::initializer_list<std::size_t> e_rows);

}  // namespace tessera::subdiv
