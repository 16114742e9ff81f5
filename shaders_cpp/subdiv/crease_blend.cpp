#include "shaders_cpp/subdiv/crease_blend.h"

#include <cmath>

namespace tessera::subdiv {

double crease_weight(float s) { return s >= kSharpnessInfinite ? 1.0 : s > 0.0f ? 1.0 - std::exp2(-double(s)) : 0.0; }

void exact_corner(std::vector<Stencil>& stencils, const std::vector<Stencil>& smooth, const Topology& t, int vertex,
                  const std::optional<Stencil>& exact, std::size_t p_row, std::initializer_list<std::size_t> e_rows) {
  if (!exact) return;
  const Stencil shift = *exact - smooth[p_row];
  stencils[p_row] = *exact;
  for (const int h : t.ring(vertex))
    if (t.edge_sharpness(t.edge(h)) > 0.0f) return;
  const double fade = std::exp2(-double(t.corner_sharpness(vertex)));
  for (const std::size_t r : e_rows) stencils[r] = smooth[r] + fade * shift;
}

}  // namespace tessera::subdiv
