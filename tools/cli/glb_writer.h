// Binary glTF 2.0 (.glb) written in one pass over a stream of patches, so a tessellated surface opens
// in any glTF viewer: one mesh, one triangle primitive with POSITION (with its min/max), NORMAL and
// uint32 indices. As with the PLY writer (ply_writer.h), counts are known only at the end, so each
// attribute goes to a side file beside the output and finish() writes the GLB header, the JSON chunk
// and the binary chunk from them; memory stays flat in the tessellation factor.
//
// Why not tinygltf's writer: it serialises a Model held in memory whole, which would make the output
// grow memory with the factor. The container is small (glTF 2.0 §4.4: 12-byte header, a JSON chunk
// padded with spaces, a BIN chunk padded with zeros, all 4-byte aligned); nlohmann-json writes the JSON.
//
// Contract: the same appends give the same bytes; failures throw std::runtime_error naming `label`;
// the side files are removed when the writer is destroyed, finished or not.
#pragma once

#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace tessera::cli {

class GlbStreamWriter {
 public:
  GlbStreamWriter(std::string path, std::string label);
  ~GlbStreamWriter();
  GlbStreamWriter(const GlbStreamWriter&) = delete;
  GlbStreamWriter& operator=(const GlbStreamWriter&) = delete;

  // One patch: its points and its triangles (indices into `positions`, offset by the writer).
  void append(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
              const std::vector<std::uint32_t>& triangles);
  // Writes the file; `generator` goes to asset.generator, `extras` (JSON text of an object) to asset.extras.
  void finish(const std::string& generator, const std::string& extras_json);

 private:
  std::string path_, label_;
  std::array<std::string, 3> parts_;  // positions, normals, indices
  std::array<std::ofstream, 3> out_;
  std::uint64_t vertices_ = 0, indices_ = 0;
  glm::vec3 lo_{0.0f}, hi_{0.0f};
};

}  // namespace tessera::cli
