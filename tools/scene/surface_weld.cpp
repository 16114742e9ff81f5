#include "tools/scene/surface_weld.h"

#include <algorithm>

namespace tessera::scene {

WeldCurves weld_curves(const Cage& cage, const Topology& topology) {
  WeldCurves out;
  if (cage.vertex_source.empty()) return out;
  out.source = cage.vertex_source;
  std::vector<std::int64_t> curves;
  for (int e = 0; e < topology.edge_count(); ++e) {
    const int h = topology.edge_half_edges(e)[0];
    curves.push_back(cage_edge_key(cage.source_vertex(topology.origin(h)), cage.source_vertex(topology.destination(h))));
  }
  std::sort(curves.begin(), curves.end());
  for (std::size_t i = 0; i + 1 < curves.size(); ++i)
    if (curves[i] == curves[i + 1] && (out.fins.empty() || out.fins.back() != curves[i])) out.fins.push_back(curves[i]);
  return out;
}

}  // namespace tessera::scene
