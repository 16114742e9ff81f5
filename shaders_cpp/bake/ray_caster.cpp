#include "shaders_cpp/bake/ray_caster.h"

#include <cmath>
#include <cstring>
#include <limits>

#include <embree3/rtcore.h>

namespace tessera {

struct RayCaster::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RayCaster::RayCaster(const DenseMesh& mesh) : mesh_(mesh), embree_(std::make_unique<Embree>()) {
  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device) throw BakeError(mesh.name + ": Embree could not create a device");
  embree_->scene = rtcNewScene(embree_->device);
  // Robust traversal: a ray through a shared edge or vertex hits one of its triangles, never neither.
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
  auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), mesh.triangle_count()));
  if (!vertices || !indices) {
    rtcReleaseGeometry(geometry);
    throw BakeError(mesh.name + ": Embree could not allocate the mesh's buffers");
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) std::memcpy(vertices + 3 * i, &mesh.positions[i], 12);
  std::memcpy(indices, mesh.triangles.data(), mesh.triangles.size() * sizeof(std::uint32_t));
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(embree_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(embree_->scene);
  if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE)
    throw BakeError(mesh.name + ": Embree could not build the mesh's acceleration structure");
}

RayCaster::~RayCaster() = default;

std::optional<RayHit> RayCaster::cast(glm::vec3 origin, glm::vec3 dir, float max_distance) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = origin.x, rh.ray.org_y = origin.y, rh.ray.org_z = origin.z;
  rh.ray.dir_x = dir.x, rh.ray.dir_y = dir.y, rh.ray.dir_z = dir.z;
  rh.ray.tnear = 0.0f, rh.ray.tfar = max_distance;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(embree_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  // The hit, recomputed from the triangle alone (see the header).
  RayHit hit;
  hit.triangle = rh.hit.primID;
  const std::uint32_t* tri = mesh_.triangles.data() + 3 * std::size_t(rh.hit.primID);
  const glm::dvec3 a(mesh_.positions[tri[0]]), b(mesh_.positions[tri[1]]), c(mesh_.positions[tri[2]]);
  const glm::dvec3 o(origin), d(dir);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double dn = glm::dot(n, d);
  if (dn == 0.0) return std::nullopt;  // grazing: Embree's float test saw a hit the plane does not have
  hit.t = glm::dot(n, a - o) / dn;
  hit.point = o + hit.t * d;
  const double nn = glm::dot(n, n);
  const double w1 = glm::dot(glm::cross(hit.point - a, c - a), n) / nn;
  const double w2 = glm::dot(glm::cross(b - a, hit.point - a), n) / nn;
  hit.weights = glm::clamp(glm::dvec3(1.0 - w1 - w2, w1, w2), 0.0, 1.0);
  hit.weights /= hit.weights.x + hit.weights.y + hit.weights.z;
  return hit;
}

std::optional<RayHit> RayCaster::hit_on_line(glm::vec3 origin, glm::vec3 dir, float max_distance,
                                             RayPreference preference) const {
  std::optional<RayHit> ahead = cast(origin, dir, max_distance);
  std::optional<RayHit> behind = cast(origin, -dir, max_distance);
  if (behind) behind->t = -behind->t;
  if (ahead && behind && preference == RayPreference::outward) return ahead;
  if (ahead && behind) return std::abs(behind->t) < std::abs(ahead->t) ? behind : ahead;
  return ahead ? ahead : behind;
}

bool RayCaster::occluded(glm::vec3 origin, glm::vec3 dir, float t_near, float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
  ray.dir_x = dir.x, ray.dir_y = dir.y, ray.dir_z = dir.z;
  ray.tnear = t_near, ray.tfar = t_far;
  ray.mask = 0xFFFFFFFFu;
  rtcOccluded1(embree_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace tessera
