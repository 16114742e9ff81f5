#include "tools/cli/glb_writer.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

namespace tessera::cli {
namespace {

static_assert(std::endian::native == std::endian::little, "GLB is little-endian; this writer copies memory as is");

constexpr std::uint32_t kMagic = 0x46546C67u;  // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534Au, kBinChunk = 0x004E4942u;

void put_u32(std::ofstream& out, std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); }
std::uint64_t padded(std::uint64_t n) { return (n + 3) & ~std::uint64_t(3); }

// A float accessor's JSON numbers: shortest text that reads back to the same float.
nlohmann::json vec3_json(const glm::vec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

GlbStreamWriter::GlbStreamWriter(std::string path, std::string label)
    : path_(std::move(path)), label_(std::move(label)) {
  const char* suffix[3] = {".positions", ".normals", ".indices"};
  for (int i = 0; i < 3; ++i) {
    parts_[std::size_t(i)] = path_ + suffix[i];
    out_[std::size_t(i)].open(parts_[std::size_t(i)], std::ios::binary);
    if (!out_[std::size_t(i)]) throw std::runtime_error(label_ + ": cannot write");
  }
}

GlbStreamWriter::~GlbStreamWriter() {
  for (std::size_t i = 0; i < 3; ++i) {
    out_[i].close();
    std::error_code ignored;
    std::filesystem::remove(parts_[i], ignored);
  }
}

void GlbStreamWriter::append(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                             const std::vector<std::uint32_t>& triangles) {
  if (positions.empty()) return;
  if (vertices_ == 0) lo_ = hi_ = positions[0];
  for (const glm::vec3& p : positions) lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
  out_[0].write(reinterpret_cast<const char*>(positions.data()), std::streamsize(positions.size() * sizeof(glm::vec3)));
  out_[1].write(reinterpret_cast<const char*>(normals.data()), std::streamsize(normals.size() * sizeof(glm::vec3)));
  std::vector<std::uint32_t> shifted(triangles.size());
  if (vertices_ + positions.size() > 0xFFFFFFFFull) throw std::runtime_error(label_ + ": more than 2^32 vertices");
  for (std::size_t i = 0; i < triangles.size(); ++i) shifted[i] = std::uint32_t(vertices_ + triangles[i]);
  out_[2].write(reinterpret_cast<const char*>(shifted.data()), std::streamsize(shifted.size() * 4));
  vertices_ += positions.size();
  indices_ += triangles.size();
}

void GlbStreamWriter::finish(const std::string& generator, const std::string& extras_json) {
  for (auto& o : out_) {
    if (!o.flush()) throw std::runtime_error(label_ + ": write failed");
    o.close();
  }
  const std::uint64_t vbytes = vertices_ * 12, ibytes = indices_ * 4;
  const std::uint64_t bin = 2 * vbytes + ibytes;  // every part is a multiple of 4 bytes
  using nlohmann::json;
  json j;
  j["asset"] = {{"version", "2.0"}, {"generator", generator}};
  if (!extras_json.empty()) j["asset"]["extras"] = json::parse(extras_json);
  j["scene"] = 0;
  j["scenes"] = json::array({{{"nodes", {0}}}});
  j["nodes"] = json::array({{{"mesh", 0}}});
  if (vertices_ > 0) {
    j["buffers"] = json::array({{{"byteLength", bin}}});
    j["bufferViews"] =
        json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vbytes}, {"target", 34962}},
                     {{"buffer", 0}, {"byteOffset", vbytes}, {"byteLength", vbytes}, {"target", 34962}},
                     {{"buffer", 0}, {"byteOffset", 2 * vbytes}, {"byteLength", ibytes}, {"target", 34963}}});
    j["accessors"] =
        json::array({{{"bufferView", 0},
                      {"componentType", 5126},
                      {"count", vertices_},
                      {"type", "VEC3"},
                      {"min", vec3_json(lo_)},
                      {"max", vec3_json(hi_)}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", vertices_}, {"type", "VEC3"}},
                     {{"bufferView", 2}, {"componentType", 5125}, {"count", indices_}, {"type", "SCALAR"}}});
    j["meshes"] = json::array(
        {{{"primitives",
           json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"mode", 4}}})}}});
  } else {
    // Nothing drawn (every patch culled): a valid file with an empty mesh is not allowed (a mesh needs a
    // primitive), so the node draws nothing.
    j["nodes"] = json::array({json::object()});
  }
  std::string text = j.dump();
  text.append(std::size_t(padded(text.size()) - text.size()), ' ');
  const std::uint64_t total = 12 + 8 + text.size() + (vertices_ > 0 ? 8 + bin : 0);
  if (total > 0xFFFFFFFFull) throw std::runtime_error(label_ + ": larger than the 4 GiB a GLB file can hold");
  std::ofstream out(path_, std::ios::binary);
  put_u32(out, kMagic);
  put_u32(out, 2);
  put_u32(out, std::uint32_t(total));
  put_u32(out, std::uint32_t(text.size()));
  put_u32(out, kJsonChunk);
  out.write(text.data(), std::streamsize(text.size()));
  if (vertices_ > 0) {
    put_u32(out, std::uint32_t(bin));
    put_u32(out, kBinChunk);
    for (const std::string& part : parts_) {
      std::ifstream in(part, std::ios::binary);
      if (in.peek() != std::ifstream::traits_type::eof()) out << in.rdbuf();
    }
  }
  out.close();
  if (!out) throw std::runtime_error(label_ + ": write failed");
}

}  // namespace tessera::cli
