// Reading a control cage from glTF 2.0 (.gltf JSON or .glb binary) through tinygltf.
//
// What is read: every triangle primitive (mode 4) of every node that draws a mesh in the chosen scene
// (the default scene, or `scene_index`; all root nodes when the file has no scene), in depth-first node
// order, each node an instance of its mesh with the node's world transform; or only the meshes (or
// nodes) named `mesh`. Per primitive: POSITION, TEXCOORD_0, indices (none: 0, 1, 2, ...), JOINTS_0/1
// with WEIGHTS_0/1 (up to 8 influences), morph targets' POSITION deltas; sparse accessors; buffers
// embedded (GLB), external or data URIs.
//
// Topology: glTF splits a vertex wherever its UV changes, so vertices of one instance whose POSITION
// has identical bits are welded into one cage vertex, first occurrence first (the FB_ngon_encoding
// cages of tests/data keep the OBJ's numbering this way). A primitive with the FB_ngon_encoding
// extension is decoded into polygons: consecutive fan triangles with the same first index form one
// polygon. Without it, every triangle is a face (a triangle cage: `gregory` and `pn` take it).
// Texture coordinates stay per corner, as glTF stores them, with v pointing down (Cage::uv_v_down).
//
// Materials: the first primitive's material gives `normalTexture` and, from the KHR_materials_displacement
// proposal, displacementGeometryTexture / Factor / Offset: as paths for external images, or the
// encoded bytes for embedded ones (GltfImage).
//
// Errors throw CageError with one line naming the file and the element: "frog.gltf: mesh 0
// (frog) primitive 0: accessor 2 (TEXCOORD_0) reads past the end of buffer view 1". Checked: not
// glTF, required extensions Tessera does not read, missing buffers or images, accessors out of range
// or of the wrong type, indices out of range, non-finite positions, deltas, weights or matrices, joints
// beyond the skin, node cycles, a file without triangles. Warnings (Cage::warnings): skipped
// primitives (points, lines), skin weights that do not sum to one (normalised).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/animation/cage_rig.h"

namespace tessera {

struct GltfSelection {
  std::optional<int> scene;  // default: the file's default scene
  std::string mesh;          // empty: every mesh; otherwise a mesh or node name
};

// An image a material refers to: a file (path resolved against the glTF's directory) or bytes.
struct GltfImage {
  std::string path;                 // external file, or a name for messages ("frog.glb image 2")
  std::vector<std::uint8_t> bytes;  // embedded (data URI or buffer view): the encoded file
  std::string mime_type;
  bool embedded() const { return !bytes.empty(); }
};

struct GltfMaterialMaps {
  std::optional<GltfImage> normal;        // normalTexture
  std::optional<GltfImage> displacement;  // KHR_materials_displacement's displacementGeometryTexture
  float displacement_factor = 1.0f, displacement_offset = 0.0f;
};

struct GltfCage {
  Cage cage;                           // the rest pose
  std::shared_ptr<const CageRig> rig;  // null when nothing can move (no skin, target or animation)
  GltfMaterialMaps maps;
  int gltf_vertices = 0;  // before welding
};

GltfCage load_gltf_cage(const std::string& path, const GltfSelection& selection = {});
// The same from the file's bytes; `path` names it in messages and its directory resolves external URIs.
GltfCage parse_gltf_cage(std::span<const std::uint8_t> bytes, const std::string& path,
                         const GltfSelection& selection = {});
inline constexpr std::size_t kMaxGltfFileBytes = std::size_t(1) << 31;

// True for a path ending in .gltf or .glb (any case).
bool is_gltf_path(const std::string& path);

}  // namespace tessera
