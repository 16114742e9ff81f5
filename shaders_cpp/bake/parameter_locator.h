// Dual parameterisation: the triangle of a parameterised dense mesh (DenseMesh::face, face_uv) that
// holds a given point (cage face, (u, v) in the face's frame), and its barycentric coordinates.
//
// Why: a mesh tessellated from the cage (tessera tessellate's PLY) knows where each of its vertices lies
// on the base surface. A texel's displacement is then the difference between the dense surface's
// position at the texel's (face, u, v), interpolated in the face's own domain, and the base surface's
// there: no ray, no search along the normal, exact at the dense vertices, and defined under any
// sculpting that moves vertices sideways.
//
// Contract: triangles whose three vertices do not name one face are ignored (they cannot be located in a
// face's domain); each face's triangles are indexed by a uniform grid over its domain. locate() returns
// the containing triangle with the largest smallest barycentric (a point on a shared edge takes the
// first of its triangles in file order), accepting points up to 1e-6 outside a triangle; const and
// thread-safe.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "shaders_cpp/bake/dense_mesh.h"

namespace tessera {

struct DenseLocation {
  std::uint32_t triangle = 0;  // index of the triangle (its vertices at 3 * triangle)
  glm::dvec3 weights{0.0};     // barycentric weights of its three vertices, summing to 1
};

class ParameterLocator {
 public:
  // `faces`: the cage's face count; a vertex naming a face beyond it throws BakeError.
  ParameterLocator(const DenseMesh& mesh, int faces);
  std::optional<DenseLocation> locate(std::uint32_t face, glm::vec2 uv) const;
  // How many of the cage's faces have located triangles.
  int faces_covered() const;

 private:
  struct FaceGrid {
    int n = 0;                         // n x n buckets over [0, 1]^2
    std::vector<std::uint32_t> start;  // n * n + 1 offsets into `items`
    std::vector<std::uint32_t> items;  // triangle indices
  };
  const DenseMesh& mesh_;
  std::vector<FaceGrid> grids_;
};

}  // namespace tessera
