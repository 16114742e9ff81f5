#include "shaders_cpp/subdiv/control_point_prepass.h"

namespace tessera {

std::vector<glm::vec3> precompute_control_points(const SubdPatches& patches, std::span<const glm::vec3> positions) {
  return precompute_rows(patches.precomputed, positions);
}

std::vector<glm::vec3> precompute_rows(std::span<const PrecomputedPatch> patches,
                                       std::span<const glm::vec3> positions) {
  std::vector<glm::vec3> out;
  for (const PrecomputedPatch& p : patches) {
    const std::size_t n = p.vertices.size();
    for (int r = 0; r < p.rows; ++r) {
      const float* w = p.weights.data() + std::size_t(r) * n;
      glm::dvec3 sum(0.0);
      for (std::size_t k = 0; k < n; ++k)
        if (w[k] != 0.0f) sum += double(w[k]) * glm::dvec3(positions[std::size_t(p.vertices[k])]);
      out.push_back(glm::vec3(sum));
    }
  }
  return out;
}

}  // namespace tessera
