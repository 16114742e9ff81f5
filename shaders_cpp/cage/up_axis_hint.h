// Which world axis a cage's shape suggests is up, for a hint to the user: OBJ files carry no up axis,
// and OpenSubdiv's shapes and many DCC exports are +z up while Tessera's default camera is +y up.
//
// The evidence is a flat base: objects are modelled standing on the ground, so the axis whose lowest
// plane holds the most cage vertices (within 1 % of the largest extent) is the likely up. Only +y and
// +z are weighed (the two conventions in use); +z is suggested only when its base holds at least
// three vertices and twice as many as +y's, so symmetric shapes (a sphere, a torus) stay +y.
// A hint, not a rule: glTF (+y by definition) and scene files (camera_up) settle the question.
#pragma once

#include <span>

#include <glm/glm.hpp>

namespace tessera {

struct UpAxisHint {
  int axis = 1;                      // 1: +y, 2: +z
  int base_vertices[3] = {0, 0, 0};  // vertices on the lowest plane of x, y, z
  glm::vec3 extent{0.0f};
};

UpAxisHint suggest_up_axis(std::span<const glm::vec3> positions);

}  // namespace tessera
