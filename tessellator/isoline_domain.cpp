// Isoline domain: `density` lines at v = place(k) for k < lines (never at v = 1), each with the
// same u points from the detail factor. Output line gives each line's segments; anything else
// gives the points.
#include "tessellator/domains.h"
#include "tessellator/edge_context.h"

namespace tessera::ts::detail {

void isoline_generate(const ProcessedFactors& p, OutputPrimitive output, Pattern& out) {
  const EdgeContext& density = p.outside[0];
  const EdgeContext& detail = p.outside[1];
  const int lines = density.num_points - 1;
  const int per_line = detail.num_points;
  out.points.reserve(static_cast<std::size_t>(lines * per_line));
  for (int line = 0; line < lines; ++line) {
    const Fxp v = place_point(density, line);
    for (int i = 0; i < per_line; ++i) out.points.push_back(make_point(place_point(detail, i), v));
  }
  if (output == OutputPrimitive::point) {
    for (std::uint32_t i = 0; i < out.points.size(); ++i) out.indices.push_back(i);
    return;
  }
  for (int line = 0; line < lines; ++line) {
    for (int i = 1; i < per_line; ++i) {
      out.indices.push_back(static_cast<std::uint32_t>(line * per_line + i - 1));
      out.indices.push_back(static_cast<std::uint32_t>(line * per_line + i));
    }
  }
}

}  // namespace tessera::ts::detail
