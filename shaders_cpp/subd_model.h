// A cage ready to draw with one scheme: the cage, its topology, its patches (and, for `exact`, the
// limit surface), and the calls that run it through the pipeline as stream output or as a render.
//
// Contract: load_subd_model throws CageError (one line naming the file and element) for files that
// cannot be read, cages that fail validation, and faces the scheme cannot handle. The draws run the
// quad-domain patches, then the tri-domain ones; within each, patches are in face order.
#pragma once

#include <memory>
#include <string>

#include "cage.h"
#include "limit_surface.h"
#include "stream_output.h"
#include "subd_patches.h"
#include "subd_shaders.h"
#include "topology.h"

namespace tessera {

struct SubdModel {
  Cage cage;
  std::unique_ptr<Topology> topology;
  SubdPatches patches;
  std::unique_ptr<LimitSurface> limit;  // exact scheme only
};

SubdModel load_subd_model(const std::string& path, Scheme scheme);
SubdModel make_subd_model(Cage cage, Scheme scheme);

// Runs IA..DS over both patch groups and hands each patch's SurfaceSamples to sink(PatchOutput, domain).
template <class Sink>
DrawResult stream_subd(Device& device, const SubdModel& m, const SubdFactors& factors, ts::Partitioning partitioning,
                       Sink&& sink) {
  DrawResult total;
  const std::span<const glm::vec3> vertices(m.cage.positions);
  SubdDS ds{{}, m.limit.get(), m.cage.tags.left_handed};
  for (const PatchGroup* g : {&m.patches.quads, &m.patches.tris}) {
    if (g->patches.empty()) continue;
    TessellatorState ts;
    ts.domain = g->domain;
    ts.partitioning = partitioning;
    ts.output = ts::OutputPrimitive::triangle_cw;
    ds.patches = g->patches;
    ds.triangles = g->domain == ts::Domain::tri;
    auto run = [&](const auto& hs) {
      StreamDraw<glm::vec3, SubdVS, std::decay_t<decltype(hs)>, SubdDS> d{
          vertices, g->indices, g->control_points, SubdVS{}, hs, ds, ts};
      return stream_out(device, d, [&](const PatchOutput<SurfaceSample>& p) { sink(p, *g); });
    };
    DrawResult r = g->domain == ts::Domain::tri ? run(SubdTriHS{{g->patches, m.patches.tables, factors}})
                                                : run(SubdHS{g->patches, m.patches.tables, factors});
    if (!r.ok()) return r;
    total.report.statistics += r.report.statistics;
    total.report.times += r.report.times;
    total.report.memory.geometry_peak_bytes =
        std::max(total.report.memory.geometry_peak_bytes, r.report.memory.geometry_peak_bytes);
  }
  return total;
}

}  // namespace tessera
