#include "tools/cli/ply_writer.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace tessera::cli {

PlyStreamWriter::PlyStreamWriter(std::string path, std::string label, std::vector<Property> vertex_properties)
    : path_(std::move(path)),
      label_(std::move(label)),
      vertex_path_(path_ + ".vertices"),
      face_path_(path_ + ".faces"),
      properties_(std::move(vertex_properties)),
      vertex_out_(vertex_path_, std::ios::binary),
      face_out_(face_path_, std::ios::binary) {
  if (!vertex_out_ || !face_out_) throw std::runtime_error(label_ + ": cannot write");
}

PlyStreamWriter::~PlyStreamWriter() {
  vertex_out_.close();
  face_out_.close();
  std::error_code ignored;
  std::filesystem::remove(vertex_path_, ignored);
  std::filesystem::remove(face_path_, ignored);
}

void PlyStreamWriter::put_triangle(std::string& out, std::int32_t a, std::int32_t b, std::int32_t c) {
  put(out, std::uint8_t(3), a, b, c);
}

void PlyStreamWriter::append(const std::string& vertex_records, std::uint64_t vertices, const std::string& face_records,
                             std::uint64_t faces) {
  vertex_out_.write(vertex_records.data(), std::streamsize(vertex_records.size()));
  face_out_.write(face_records.data(), std::streamsize(face_records.size()));
  vertices_ += vertices;
  faces_ += faces;
}

void PlyStreamWriter::finish(const std::vector<std::string>& comments) {
  if (!vertex_out_.flush() || !face_out_.flush()) throw std::runtime_error(label_ + ": write failed");
  vertex_out_.close();
  face_out_.close();
  std::ofstream out(path_, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\n";
  for (const std::string& c : comments) out << "comment " << c << "\n";
  out << "element vertex " << vertices_ << "\n";
  for (const Property& p : properties_) out << "property " << p.type << " " << p.name << "\n";
  out << "element face " << faces_ << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const std::string& part : {vertex_path_, face_path_}) {
    std::ifstream in(part, std::ios::binary);
    // `out << rdbuf` sets failbit when it copies nothing: an empty part (every patch culled) is skipped.
    if (in.peek() != std::ifstream::traits_type::eof()) out << in.rdbuf();
  }
  out.close();
  if (!out) throw std::runtime_error(label_ + ": write failed");
}

}  // namespace tessera::cli
