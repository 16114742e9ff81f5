#include "shaders_cpp/bake/base_surface.h"

#include <tbb/parallel_for.h>

#include "shaders_cpp/render/displaced_shaders.h"

namespace tessera {
namespace {

constexpr int kPoints = SubdHS::kOutputControlPoints;

SubdHS hull_shader(const SubdModel& m, const SubdFactors& factors) {
  const PatchGroup& g = m.patches.quads;
  return SubdHS{g.patches, m.patches.tables, factors, false, m.ring_boxes, ts::Partitioning::integer, m.precomputed};
}

}  // namespace

BaseSurface::BaseSurface(const SubdModel& model, std::span<const PatchTexcoords> texcoords)
    : model_(model), texcoords_(texcoords) {
  const PatchGroup& g = model.patches.quads;
  control_points_.resize(g.patches.size() * std::size_t(kPoints));
  const SubdHS hs = hull_shader(model, factors_);
  const SubdVS vs = model.vertex_shader();
  const auto buffer = model.vertex_buffer();
  // The input assembler's view of one patch: its ring through the vertex shader, then the hull shader.
  tbb::parallel_for(std::size_t(0), g.patches.size(), [&](std::size_t p) {
    std::vector<SubdVertex> ring(std::size_t(g.control_points));
    for (int i = 0; i < g.control_points; ++i) {
      const std::uint32_t id = g.indices[p * std::size_t(g.control_points) + std::size_t(i)];
      ring[std::size_t(i)] = vs(buffer[id], id);
    }
    for (int i = 0; i < kPoints; ++i)
      control_points_[p * kPoints + std::size_t(i)] = hs.control_point(ring, i, std::uint32_t(p));
  });
}

BaseFrame BaseSurface::evaluate(std::uint32_t patch, float u, float v) const {
  const PatchGroup& g = model_.patches.quads;
  const SubdDS ds{g.patches, model_.limit.get(), model_.cage.tags.left_handed, false};
  const std::span<const SubdControlPoint> cp(control_points_.data() + std::size_t(patch) * kPoints, kPoints);
  const SurfaceSample s = ds(SubdPatchConstants{}, cp, DomainLocation{u, v, 0.0f}, patch);
  BaseFrame f;
  f.position = s.position, f.normal = s.normal;
  f.face = s.face, f.face_u = s.u, f.face_v = s.v;
  // DisplacedDS's interior branch: dP/dU and dP/dV from the patch's derivatives and its UV's.
  const auto& c = texcoords_[patch].interior;
  const glm::vec2 ja = (1.0f - v) * (c[1] - c[0]) + v * (c[2] - c[3]);
  const glm::vec2 jb = (1.0f - u) * (c[3] - c[0]) + u * (c[2] - c[1]);
  glm::vec3 dpdu, dpdv;
  texture_derivatives(s.du, s.dv, ja, jb, dpdu, dpdv);
  const glm::vec3 n = s.normal;
  f.tangent = unit_or_zero(dpdu - glm::dot(n, dpdu) * n);
  f.bitangent = glm::cross(n, f.tangent);
  if (glm::dot(f.bitangent, dpdv) < 0.0f) f.bitangent = -f.bitangent;
  f.shade_tangent = f.tangent;
  f.shade_bitangent = unit_or_zero(dpdv - glm::dot(n, dpdv) * n - glm::dot(f.shade_tangent, dpdv) * f.shade_tangent);
  return f;
}

}  // namespace tessera
