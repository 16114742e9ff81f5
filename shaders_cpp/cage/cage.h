// A Catmull-Clark control cage as read from a file: positions, faces of any size, face-varying
// texture coordinates, and OpenSubdiv's tags (creases, corners, holes, boundary rules).
//
// Contract: a Cage is plain data with no invariants beyond those `validate_cage` (topology.h)
// checks; loaders fill it, the topology and the schemes read it. Indices are 0-based.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {

// Bad cage data (unreadable file, malformed line, broken topology). The message is one line that
// names the file and the line, face or vertex, e.g. "frog.obj:12: face 7 has vertex 0".
struct CageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// OpenSubdiv's vertex boundary interpolation (Sdc::Options::VtxBoundaryInterpolation). The OBJ tag
// `t interpolateboundary 1 0 N` maps 0 → none, 1 → edge_and_corner, 2 → edge_only, as OpenSubdiv's
// regression shapes do; a cage without the tag gets edge_only (their default too).
enum class BoundaryInterpolation : uint8_t { none, edge_only, edge_and_corner };
// Sdc::Options::CreasingMethod: `t creasemethod 0 0 1 chaikin|normal`.
enum class CreaseMethod : uint8_t { uniform, chaikin };

// A semi-sharp (0 < s < 10) or infinitely sharp (s >= 10) edge between two vertices.
struct Crease {
  int v0 = 0, v1 = 0;
  float sharpness = 0.0f;
};
// A sharp vertex.
struct Corner {
  int vertex = 0;
  float sharpness = 0.0f;
};

struct CageTags {
  std::vector<Crease> creases;
  std::vector<Corner> corners;
  std::vector<int> holes;  // face indices that produce no surface
  BoundaryInterpolation boundary = BoundaryInterpolation::edge_only;
  CreaseMethod crease_method = CreaseMethod::uniform;
  bool smooth_triangles = false;        // Sdc TRI_SUB_SMOOTH
  bool left_handed = false;             // faces wound clockwise
  int fvar_boundary = 1;                // `t facevaryinginterpolateboundary`: 0..5 as OpenSubdiv
  bool fvar_propagate_corners = false;  // `t facevaryingpropagatecorners 1 0 0 N`: N != 0
};

struct Cage {
  std::string name;  // where it came from (a file path), for messages
  std::vector<glm::vec3> positions;
  // Faces, flattened: face f has face_sizes[f] vertices starting at face_offsets[f] of face_vertices,
  // in the file's order (counter-clockwise seen from outside unless tags.left_handed).
  std::vector<int> face_sizes;
  std::vector<int> face_offsets;
  std::vector<int> face_vertices;
  // Face-varying texture coordinates: empty, or one index per entry of face_vertices into uvs.
  std::vector<glm::vec2> uvs;
  std::vector<int> face_uvs;
  // Texture v points down the image (glTF); OBJ's points up. Maps are sampled accordingly.
  bool uv_v_down = false;
  CageTags tags;
  // What the loader read but did not use (unsupported tags such as OpenSubdiv's hierarchical edits,
  // unknown OBJ statements, creases on no edge), one line each naming the file and line, and what a
  // model's scheme leaves out (make_subd_model: creases and corners drawn smooth). Not errors: the
  // cage is usable.
  std::vector<std::string> warnings;
  // Set by split_non_manifold (non_manifold.h) when the file's cage is not manifold: per vertex, the
  // vertex of the file it copies (empty: every vertex is the file's own), and each non-manifold place.
  std::vector<int> vertex_source;
  std::vector<std::string> non_manifold;

  int vertex_count() const { return static_cast<int>(positions.size()); }
  int face_count() const { return static_cast<int>(face_sizes.size()); }
  bool has_uvs() const { return !face_uvs.empty(); }
  // Vertex k (0 <= k < face_sizes[f]) of face f.
  int face_vertex(int f, int k) const { return face_vertices[face_offsets[f] + k]; }
  // The file's vertex that vertex v is (itself unless the cage was split).
  int source_vertex(int v) const { return vertex_source.empty() ? v : vertex_source[std::size_t(v)]; }
};

}  // namespace tessera
