// Axis-aligned bounding boxes of control points (a cage, a patch's hull, a face's 1-ring): the one
// definition the framing camera, the culling bounds, the debug views and `analyze` share, so they
// agree to the bit on the box of the same points.
//
// Contract: a box starts empty (lo = +inf, hi = -inf) and grows by glm::min / glm::max of each point
// in the order given; an empty box stays inverted (lo > hi). A NaN coordinate is passed over by
// glm::min/max as they define it (the cage readers refuse NaN positions before any box is taken).
#pragma once

#include <cmath>
#include <span>

#include <glm/glm.hpp>

namespace tessera {

struct Box3 {
  glm::vec3 lo{0.0f}, hi{0.0f};

  static Box3 empty() { return {glm::vec3(INFINITY), glm::vec3(-INFINITY)}; }
  void extend(glm::vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  glm::vec3 centre() const { return 0.5f * (lo + hi); }
  // Corner i: bit 0 picks hi.x, bit 1 hi.y, bit 2 hi.z.
  glm::vec3 corner(int i) const { return {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z}; }
};

inline Box3 bounding_box(std::span<const glm::vec3> points) {
  Box3 b = Box3::empty();
  for (const glm::vec3& p : points) b.extend(p);
  return b;
}

}  // namespace tessera
