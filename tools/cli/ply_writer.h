// Binary little-endian PLY written in one pass over data whose counts are known only at the end
// (a stream of patches): the records go to two side files beside the output, and finish() writes
// the header with the final counts followed by both. Faces are triangles (`property list uchar int
// vertex_indices`); vertex properties are the caller's.
//
// Contract: records are appended with put() in the header's byte order whatever the host's;
// failures throw std::runtime_error naming `label` (the path the user gave); the side files are
// removed when the writer is destroyed, finished or not.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

namespace tessera::cli {

class PlyStreamWriter {
 public:
  struct Property {
    std::string type, name;  // PLY type ("float", "int", ...) and name
  };

  PlyStreamWriter(std::string path, std::string label, std::vector<Property> vertex_properties);
  ~PlyStreamWriter();
  PlyStreamWriter(const PlyStreamWriter&) = delete;
  PlyStreamWriter& operator=(const PlyStreamWriter&) = delete;

  // Values appended to a record buffer in order, each little-endian.
  template <class... T>
  static void put(std::string& out, const T&... values) {
    (put_one(out, values), ...);
  }
  static void put_triangle(std::string& out, std::int32_t a, std::int32_t b, std::int32_t c);

  // Appends complete records: `vertices` vertex records and `faces` triangles. One write per call:
  // a stream write per value took as long as the tessellation itself.
  void append(const std::string& vertex_records, std::uint64_t vertices, const std::string& face_records,
              std::uint64_t faces);

  // Writes the file: header (with `comments`, one per line) and the records appended so far.
  void finish(const std::vector<std::string>& comments);

 private:
  std::string path_, label_, vertex_path_, face_path_;
  std::vector<Property> properties_;
  std::ofstream vertex_out_, face_out_;
  std::uint64_t vertices_ = 0, faces_ = 0;

  template <class T>
  static void put_one(std::string& out, const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::array<char, sizeof(T)> bytes;
    std::memcpy(bytes.data(), &v, sizeof v);
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes.begin(), bytes.end());
    out.append(bytes.data(), bytes.size());
  }
};

}  // namespace tessera::cli
