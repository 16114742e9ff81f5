// (c) What a draw reports, and a check that its output is watertight: the built-in subdivision model
// of a sphere-like cage (valence-3 and valence-5 vertices, so Gregory patches meet regular ones) with
// fractional factors that differ from edge to edge. The stream-output pass (stream_subd: IA..DS, no
// rasterizer) hands every patch's triangles to a weld on exact float bits; the rendered draw's D3D11
// pipeline statistics are printed; the image is written to statistics_and_weld.png.
#include <cstdio>

#include "shaders_cpp/cage/cage_generators.h"
#include "shaders_cpp/image_io/image_file.h"
#include "shaders_cpp/render/subd_model.h"
#include "shaders_cpp/render/subd_render.h"
#include "tools/verify/weld_check.h"

using namespace tessera;

int main() {
  const SubdModel model = make_subd_model(sphere_cage(5, 6, 1.0f), Scheme::gregory);
  SubdFactors factors;
  factors.factor = 2.5f;
  factors.vary = 1.0f;  // each cage edge's factor in [2.5, 5], by a hash of the edge
  const ts::Partitioning partitioning = ts::Partitioning::fractional_odd;
  Device device(DeviceOptions{.threads = 0});

  // Welded on exact bits: a closed surface uses every edge twice, once each way.
  verify::WeldChecker weld;
  const DrawResult streamed =
      stream_subd(device, model, factors, partitioning, [&](const PatchOutput<SurfaceSample>& p, const PatchGroup&) {
        for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3)
          weld.add_triangle(p.points[p.indices[i]].position, p.points[p.indices[i + 1]].position,
                            p.points[p.indices[i + 2]].position);
      });
  if (!streamed.ok()) return std::fprintf(stderr, "statistics_and_weld: %s\n", streamed.error.c_str()), 1;
  const verify::WeldReport w = weld.report();
  std::printf("weld: %llu triangles, %llu open edges, %llu non-manifold edges: %s\n",
              static_cast<unsigned long long>(w.triangles), static_cast<unsigned long long>(w.open_edges),
              static_cast<unsigned long long>(w.nonmanifold_edges), w.closed_manifold() ? "watertight" : "cracked");

  const int width = 640, height = 480;
  std::string error;
  auto fb = Framebuffer::create(width, height, ColorFormat::rgba8_unorm, &error);
  if (!fb) return std::fprintf(stderr, "statistics_and_weld: %s\n", error.c_str()), 1;
  device.clear(*fb, kBackgroundColor, 1.0f);
  const SubdCamera camera = frame_cage(model.cage, width, height, 35.0f, std::nullopt, std::nullopt);
  const DrawResult drawn =
      render_subd(device, model, factors, PatchCull{}, partitioning, SubdView::wire_on_shaded, camera, *fb);
  if (!drawn.ok()) return std::fprintf(stderr, "statistics_and_weld: %s\n", drawn.error.c_str()), 1;
  const PipelineStatistics& s = drawn.report.statistics;
  std::printf("D3D11_QUERY_DATA_PIPELINE_STATISTICS (shaded and wireframe passes):\n"
              "  IAVertices %llu  IAPrimitives %llu  VSInvocations %llu\n"
              "  HSInvocations %llu  DSInvocations %llu\n"
              "  CInvocations %llu  CPrimitives %llu  PSInvocations %llu\n",
              static_cast<unsigned long long>(s.IAVertices), static_cast<unsigned long long>(s.IAPrimitives),
              static_cast<unsigned long long>(s.VSInvocations), static_cast<unsigned long long>(s.HSInvocations),
              static_cast<unsigned long long>(s.DSInvocations), static_cast<unsigned long long>(s.CInvocations),
              static_cast<unsigned long long>(s.CPrimitives), static_cast<unsigned long long>(s.PSInvocations));
  std::printf("draw: %.1f ms wall on %d threads\n", drawn.report.times.wall * 1e3, device.threads());
  error = write_color(*fb, {"statistics_and_weld.png"});
  if (!error.empty()) return std::fprintf(stderr, "statistics_and_weld: %s\n", error.c_str()), 1;
  return w.closed_manifold() ? 0 : 1;
}
