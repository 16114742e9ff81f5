#include "shaders_cpp/lod/edge_lod.h"

#include <algorithm>
#include <cmath>

#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera {

std::optional<LodMode> parse_lod_mode(std::string_view name) {
  if (name == "uniform") return LodMode::uniform;
  if (name == "distance") return LodMode::distance;
  if (name == "screen") return LodMode::screen;
  return std::nullopt;
}

const char* to_string(LodMode m) {
  switch (m) {
    case LodMode::uniform: return "uniform";
    case LodMode::distance: return "distance";
    case LodMode::screen: return "screen";
  }
  return "?";
}

float pixels_per_unit(int viewport_height, float fov_y_degrees) {
  return 0.5f * float(viewport_height) / std::tan(0.5f * glm::radians(fov_y_degrees));
}

namespace {
float clamp_factor(float f) {
  // NaN (a degenerate camera was refused before; kept safe here) falls to 1; infinity to 64.
  return f >= 1.0f ? std::min(f, kMaxLodFactor) : 1.0f;
}
}  // namespace

float projected_diameter(const glm::vec3& centre, float radius, const DicingCamera& camera) {
  const float d = glm::length(centre - camera.eye);
  if (!(d > radius)) return INFINITY;  // the eye is inside the sphere
  // The silhouette's half angle has tangent r / sqrt(d^2 - r^2), which grows without bound as the eye
  // nears the sphere, so an edge's factor reaches 64 before the eye enters it (r / d would jump to 64
  // there: a pop in a dolly).
  return 2.0f * radius * camera.pixels_per_unit / std::sqrt((d - radius) * (d + radius));
}

float edge_lod_factor(const glm::vec3& p0, const glm::vec3& p1, const LodSettings& s) {
  if (s.mode == LodMode::uniform) return s.factor;
  // p0 + p1 and |p1 - p0| are symmetric in the end points, so either direction gives the same bits.
  const glm::vec3 centre = 0.5f * (p0 + p1);
  if (s.mode == LodMode::distance) {
    const float d = glm::length(centre - s.camera.eye);
    return d > 0.0f ? clamp_factor(s.factor * s.lod_distance / d) : kMaxLodFactor;
  }
  const float diameter_pixels = projected_diameter(centre, 0.5f * glm::length(p1 - p0) + s.bound, s.camera);
  return clamp_factor(diameter_pixels / s.edge_pixels);
}

std::shared_ptr<const EdgeFactorTable> edge_lod_factors(std::span<const glm::vec3> positions, const Topology& topology,
                                                        const LodSettings& s) {
  auto table = std::make_shared<EdgeFactorTable>();
  table->reserve(std::size_t(topology.edge_count()));
  for (int e = 0; e < topology.edge_count(); ++e) {
    const int h = topology.edge_half_edges(e)[0];
    const int a = topology.origin(h), b = topology.destination(h);
    (*table)[cage_edge_key(a, b)] = edge_lod_factor(positions[std::size_t(a)], positions[std::size_t(b)], s);
  }
  return table;
}

}  // namespace tessera
