// (a) Your own hull shader over the built-in subdivision model: each edge's tessellation factor from
// its distance to a point of interest, drawn as a Gregory ACC surface and written to
// distance_factors.png (fine near the point, coarse far from it; the wireframe shows the factors).
//
// The rule that keeps the surface watertight: an edge's factor must be computed from data both patches
// sharing it see alike. Here it is the edge's two cage vertices (the first four control points of a
// quad patch are its corners, in patch order), summed in either order to the same bits.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shaders_cpp/cage/cage_generators.h"
#include "shaders_cpp/image_io/image_file.h"
#include "shaders_cpp/render/subd_model.h"
#include "shaders_cpp/render/subd_render.h"

using namespace tessera;

// Wraps the model's own hull shader: its control points unchanged, its factors replaced.
struct DistanceHS {
  static constexpr int kOutputControlPoints = SubdHS::kOutputControlPoints;
  SubdHS base;
  glm::vec3 focus{0.0f};
  float near_factor = 12.0f, falloff = 1.0f;

  SubdControlPoint control_point(std::span<const SubdVertex> in, int i, std::uint32_t patch_id) const {
    return base.control_point(in, i, patch_id);
  }

  float edge_factor(const glm::vec3& a, const glm::vec3& b) const {
    const glm::vec3 mid = 0.5f * (a + b);  // a + b == b + a, bit for bit: both sides agree
    const float d = glm::length(mid - focus);
    return std::clamp(near_factor / (1.0f + falloff * d * d), 1.0f, 64.0f);
  }

  SubdPatchConstants patch_constants(std::span<const SubdVertex> in, std::span<const SubdControlPoint> out,
                                     std::uint32_t patch_id) const {
    SubdPatchConstants pc = base.patch_constants(in, out, patch_id);
    // Patch edge k (corner k -> k + 1) is SV_TessFactor (k + 1) % 4 of the quad domain.
    for (int k = 0; k < 4; ++k)
      pc.factors.edge[std::size_t((k + 1) % 4)] = edge_factor(in[std::size_t(k)].position, in[std::size_t((k + 1) % 4)].position);
    // InsideTessFactor[0] runs along u, beside the v = 0 and v = 1 edges; [1] along v.
    pc.factors.inside = {std::max(pc.factors.edge[1], pc.factors.edge[3]), std::max(pc.factors.edge[0], pc.factors.edge[2])};
    return pc;
  }
};

int main() {
  const SubdModel model = make_subd_model(torus_cage(24, 12, 2.0f, 0.7f), Scheme::gregory);
  const int width = 800, height = 500;
  Device device(DeviceOptions{.threads = 0});
  std::string error;
  auto fb = Framebuffer::create(width, height, ColorFormat::rgba8_unorm, &error);
  if (!fb) return std::fprintf(stderr, "distance_factors: %s\n", error.c_str()), 1;
  device.clear(*fb, kBackgroundColor, 1.0f);
  const SubdCamera camera = frame_cage(model.cage, width, height, 35.0f, std::nullopt, std::nullopt);
  const glm::vec3 light = glm::normalize(camera.eye - camera.target);

  for (const bool wire : {false, true}) {  // the shaded surface, then its triangles over it
    const SubdPassState st = subd_pass_state(model, *fb, wire);
    const DrawResult r = for_each_patch_group(
        model, SubdFactors{}, PatchCull{}, ts::Partitioning::fractional_odd,
        [&](const PatchGroup& g, const TessellatorState& ts, const SubdHS& hs, const SubdDS& ds) {
          const DistanceHS distance{hs, glm::vec3(2.6f, 0.0f, 0.8f)};
          const ProjectDS<SubdDS> project{ds, camera.view_projection, st.z_bias};
          if (wire) return draw_group_pass(device, model, g, ts, distance, project, ConstantPS<>{}, st, *fb);
          return draw_group_pass(device, model, g, ts, distance, project, ClayPS{light, kClayColor, face_sides(model)},
                                 st, *fb);
        });
    if (!r.ok()) return std::fprintf(stderr, "distance_factors: %s\n", r.error.c_str()), 1;
  }
  error = write_color(*fb, {"distance_factors.png"});
  if (!error.empty()) return std::fprintf(stderr, "distance_factors: %s\n", error.c_str()), 1;
  std::printf("distance_factors.png: %d x %d\n", width, height);
  return 0;
}
