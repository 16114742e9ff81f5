// The dense (sculpted or tessellated) mesh a bake reads: triangles, smooth normals, and — when the file
// carries it — the cage's parameterisation of each vertex (its cage face and that face's (u, v), as
// `tessera tessellate`'s PLY writes them: properties `face`, `u`, `v`).
//
// Readers: PLY (ascii or binary little/big endian; vertex x y z, optional face/u/v; polygons as
// `vertex_indices` lists, fanned into triangles), OBJ and glTF through the cage readers (faces fanned).
//
// Normals: each triangle's area-weighted normal summed at its corners, where corners are the vertices
// welded on exact position bits (a tessellated mesh writes each patch's own copy of a shared point),
// in triangle order; then normalized. Deterministic.
//
// Contract: errors throw BakeError, one line naming the file and the element (header line, vertex or
// face index); counts a file's size cannot hold are refused before anything is allocated.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

struct BakeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct DenseMesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;        // per vertex, unit (zero where no triangle has area)
  std::vector<std::uint32_t> triangles;  // 3 vertex indices per triangle
  std::vector<std::int32_t> face;        // per vertex, or empty: the cage face of the parameterisation
  std::vector<glm::vec2> face_uv;        // per vertex, with `face`: the location in the face's frame
  bool parameterised() const { return !face.empty(); }
  std::size_t triangle_count() const { return triangles.size() / 3; }
};

DenseMesh load_dense_mesh(const std::string& path);

// Fills mesh.normals from positions and triangles (the rule above).
void compute_dense_normals(DenseMesh& mesh);

}  // namespace tessera
