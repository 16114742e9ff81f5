#include "shaders_cpp/cage/up_axis_hint.h"

#include <algorithm>

#include "shaders_cpp/cage/bounding_box.h"

namespace tessera {

UpAxisHint suggest_up_axis(std::span<const glm::vec3> positions) {
  UpAxisHint h;
  if (positions.empty()) return h;
  const Box3 box = bounding_box(positions);
  h.extent = box.hi - box.lo;
  const float tolerance = 0.01f * std::max({h.extent.x, h.extent.y, h.extent.z});
  for (const glm::vec3& p : positions)
    for (int a = 0; a < 3; ++a)
      if (p[a] - box.lo[a] <= tolerance) ++h.base_vertices[a];
  if (h.base_vertices[2] >= 3 && h.base_vertices[2] >= 2 * h.base_vertices[1]) h.axis = 2;
  return h;
}

}  // namespace tessera
