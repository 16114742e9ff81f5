// Rays against a dense mesh, through Embree (Debian's libembree-dev): the nearest hit along a line in
// both directions, and occlusion tests for ambient occlusion.
//
// Determinism: Embree finds which triangle a ray hits; the hit itself (distance, point, barycentrics)
// is recomputed here in double from that triangle's vertices, so a result depends only on the triangle,
// not on the BVH Embree built or the SIMD width it chose.
//
// Contract: the mesh must outlive the caster; queries are const and thread-safe. Construction throws
// BakeError if Embree cannot create a device or scene.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "shaders_cpp/bake/dense_mesh.h"

namespace tessera {

struct RayHit {
  std::uint32_t triangle = 0;
  double t = 0;  // signed distance along the direction (negative: behind the origin)
  glm::dvec3 point{0.0};
  glm::dvec3 weights{0.0};  // barycentric weights of the triangle's three vertices
};

// Which of a line's hits a bake takes: the nearest either way, or the one ahead (outward along the
// normal) whenever there is one. Where the dense surface folds over itself (a displacement larger than
// the base surface's radius of curvature, in creases), the nearest hit may lie on another layer than
// the one displaced from this point; for a surface displaced outward, `outward` finds it more often.
enum class RayPreference : std::uint8_t { nearest, outward };

class RayCaster {
 public:
  explicit RayCaster(const DenseMesh& mesh);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // A hit on the line origin + t dir, |t| <= max_distance (dir unit length), by `preference`; of a
  // forward and a backward hit at the same distance, the forward one.
  std::optional<RayHit> hit_on_line(glm::vec3 origin, glm::vec3 dir, float max_distance,
                                    RayPreference preference = RayPreference::nearest) const;
  // Whether the ray origin + t dir, t in (t_near, t_far], hits anything.
  bool occluded(glm::vec3 origin, glm::vec3 dir, float t_near, float t_far) const;

 private:
  struct Embree;
  const DenseMesh& mesh_;
  std::unique_ptr<Embree> embree_;
  std::optional<RayHit> cast(glm::vec3 origin, glm::vec3 dir, float max_distance) const;
};

}  // namespace tessera
