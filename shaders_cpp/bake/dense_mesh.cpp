#include "shaders_cpp/bake/dense_mesh.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "shaders_cpp/render/subd_model.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

enum class PlyFormat { ascii, binary_le, binary_be };

struct PlyProperty {
  std::string name, type, count_type;  // count_type set: a list
  bool list() const { return !count_type.empty(); }
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

int type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// Reads PLY values of any scalar type as double, in the file's byte order.
class PlyReader {
 public:
  PlyReader(std::istream& in, PlyFormat format, std::string name) : in_(in), format_(format), name_(std::move(name)) {}
  double read(const std::string& type, const std::string& where) {
    if (format_ == PlyFormat::ascii) {
      std::string token;
      if (!(in_ >> token)) fail(where, "the file ends early");
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') not_a_number(where, token);
      return x;
    }
    const int n = type_size(type);
    unsigned char b[8];
    if (!in_.read(reinterpret_cast<char*>(b), n)) fail(where, "the file ends early");
    const bool swap = (format_ == PlyFormat::binary_be) != (std::endian::native == std::endian::big);
    if (swap)  // by hand: GCC 12 warns falsely on std::reverse over a variable part of b
      for (int i = 0; i < n / 2; ++i) {
        const unsigned char t = b[i];
        b[i] = b[n - 1 - i], b[n - 1 - i] = t;
      }
    auto as = [&](auto v) {
      std::memcpy(&v, b, sizeof v);
      return double(v);
    };
    if (type == "char" || type == "int8") return as(std::int8_t{});
    if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
    if (type == "short" || type == "int16") return as(std::int16_t{});
    if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
    if (type == "int" || type == "int32") return as(std::int32_t{});
    if (type == "uint" || type == "uint32") return as(std::uint32_t{});
    if (type == "float" || type == "float32") return as(float{});
    return as(double{});
  }
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw BakeError(name_ + ": " + where + ": " + what);
  }
  // Out of line: inlined into the readers, GCC 12 warns falsely (-Wrestrict) on the concatenation.
  [[noreturn, gnu::noinline]] void not_a_number(const std::string& where, const std::string& token) const {
    std::string quoted = token.substr(0, 32);
    if (token.size() > 32) quoted += "...";
    fail(where, "'" + quoted + "' is not a number");
  }

 private:
  std::istream& in_;
  PlyFormat format_;
  std::string name_;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
};

// The header after the 'ply' line: the format, each element's count (at most the file's size) and
// properties. BakeError naming the line for anything else.
PlyHeader read_ply_header(std::istream& in, const std::string& path, std::uintmax_t file_size) {
  std::string line;
  PlyFormat format = PlyFormat::ascii;
  bool have_format = false;
  std::vector<PlyElement> elements;
  for (int number = 2;; ++number) {
    if (!std::getline(in, line)) throw BakeError(path + ": the header has no end_header");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    const std::string where = path + ": line " + std::to_string(number) + ": ";
    if (key == "end_header") break;
    if (key == "comment" || key == "obj_info" || key.empty()) continue;
    if (key == "format") {
      std::string f;
      words >> f;
      if (f == "ascii")
        format = PlyFormat::ascii;
      else if (f == "binary_little_endian")
        format = PlyFormat::binary_le;
      else if (f == "binary_big_endian")
        format = PlyFormat::binary_be;
      else
        throw BakeError(where + "unknown format '" + f.substr(0, 40) + "'");
      have_format = true;
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      char* end = nullptr;
      const unsigned long long n = std::strtoull(count.c_str(), &end, 10);
      if (count.empty() || *end != '\0') throw BakeError(where + "element " + e.name + " has no count");
      // Every element takes at least one byte per entry (two for ascii): refuse what the file cannot hold.
      if (n > file_size)
        throw BakeError(where + "element " + e.name + " claims " + count + " entries in a file of " +
                        std::to_string(file_size) + " bytes");
      e.count = n;
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) throw BakeError(where + "a property before any element");
      PlyProperty p;
      words >> p.type;
      if (p.type == "list") words >> p.count_type >> p.type;
      words >> p.name;
      if (type_size(p.type) == 0 || (p.list() && type_size(p.count_type) == 0) || p.name.empty())
        throw BakeError(where + "a property with an unknown type");
      elements.back().properties.push_back(p);
    } else {
      throw BakeError(where + "unknown header keyword '" + key.substr(0, 40) + "'");
    }
  }
  if (!have_format) throw BakeError(path + ": the header has no format line");
  return {format, std::move(elements)};
}

// The vertex element: positions, and the (face, u, v) parameterization when all three are present.
void read_ply_vertices(PlyReader& r, const PlyElement& e, const std::string& path, DenseMesh& m) {
  int ix = -1, iy = -1, iz = -1, iface = -1, iu = -1, iv = -1;
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    const std::string& n = e.properties[k].name;
    int* slot = n == "x"      ? &ix
                : n == "y"    ? &iy
                : n == "z"    ? &iz
                : n == "face" ? &iface
                : n == "u"    ? &iu
                : n == "v"    ? &iv
                              : nullptr;
    if (slot && !e.properties[k].list()) *slot = int(k);
  }
  if (ix < 0 || iy < 0 || iz < 0) throw BakeError(path + ": the vertex element has no x, y and z");
  const bool param = iface >= 0 && iu >= 0 && iv >= 0;
  m.positions.resize(e.count);
  if (param) m.face.resize(e.count), m.face_uv.resize(e.count);
  std::vector<double> values(e.properties.size());
  for (std::uint64_t i = 0; i < e.count; ++i) {
    const std::string where = "vertex " + std::to_string(i);
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (p.list()) {
        const double n = r.read(p.count_type, where);
        if (!(n >= 0 && n < 256)) r.fail(where, "a list of " + std::to_string(n) + " values");
        for (int j = 0; j < int(n); ++j) r.read(p.type, where);
      } else {
        values[k] = r.read(p.type, where);
      }
    }
    const glm::vec3 pos(float(values[std::size_t(ix)]), float(values[std::size_t(iy)]),
                        float(values[std::size_t(iz)]));
    if (!std::isfinite(pos.x) || !std::isfinite(pos.y) || !std::isfinite(pos.z))
      r.fail(where, "a position that is not finite");
    m.positions[i] = pos;
    if (param) {
      const double f = values[std::size_t(iface)];
      if (!(f >= 0 && f < 2147483647.0) || f != std::floor(f))
        r.fail(where, "face " + std::to_string(f) + " is not a face index");
      const glm::vec2 uv(float(values[std::size_t(iu)]), float(values[std::size_t(iv)]));
      if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f))
        r.fail(where, "(u, v) outside the face's [0, 1] domain");
      m.face[i] = std::int32_t(f), m.face_uv[i] = uv;
    }
  }
}

// The face element's vertex_indices, as a triangle fan per polygon.
void read_ply_faces(PlyReader& r, const PlyElement& e, const std::string& path, DenseMesh& m) {
  int idx = -1;
  for (std::size_t k = 0; k < e.properties.size(); ++k)
    if (e.properties[k].list() &&
        (e.properties[k].name == "vertex_indices" || e.properties[k].name == "vertex_index"))
      idx = int(k);
  if (idx < 0) throw BakeError(path + ": the face element has no vertex_indices list");
  std::vector<std::uint32_t> poly;
  for (std::uint64_t i = 0; i < e.count; ++i) {
    const std::string where = "face " + std::to_string(i);
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (!p.list()) {
        r.read(p.type, where);
        continue;
      }
      const double n = r.read(p.count_type, where);
      if (!(n >= 0 && n < 65536)) r.fail(where, "a list of " + std::to_string(n) + " values");
      poly.clear();
      for (int j = 0; j < int(n); ++j) {
        const double x = r.read(p.type, where);
        if (int(k) == idx) {
          if (!(x >= 0 && x < double(m.positions.size())) || x != std::floor(x))
            r.fail(where, "vertex index " + std::to_string(x) + " is not one of the " +
                              std::to_string(m.positions.size()) +
                              " vertices (elements are read in order: vertices first)");
          poly.push_back(std::uint32_t(x));
        }
      }
      if (int(k) == idx) {
        if (poly.size() < 3) r.fail(where, "fewer than 3 vertices");
        for (std::size_t j = 1; j + 1 < poly.size(); ++j)
          m.triangles.insert(m.triangles.end(), {poly[0], poly[j], poly[j + 1]});
      }
    }
  }
}

// Any other element: read and dropped.
void skip_ply_element(PlyReader& r, const PlyElement& e) {
  for (std::uint64_t i = 0; i < e.count; ++i)
    for (const PlyProperty& p : e.properties) {
      const std::string where = e.name + " " + std::to_string(i);
      if (p.list()) {
        const double n = r.read(p.count_type, where);
        if (!(n >= 0 && n < 65536)) r.fail(where, "a list of " + std::to_string(n) + " values");
        for (int j = 0; j < int(n); ++j) r.read(p.type, where);
      } else {
        r.read(p.type, where);
      }
    }
}

DenseMesh read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BakeError(path + ": cannot open the file");
  const std::uintmax_t file_size = fs::file_size(path);
  std::string line;
  std::getline(in, line);
  if (line != "ply" && line != "ply\r") throw BakeError(path + ": line 1: not a PLY file (no 'ply' magic)");
  const PlyHeader header = read_ply_header(in, path, file_size);
  PlyReader r(in, header.format, path);
  DenseMesh m;
  m.name = path;
  bool have_vertices = false, have_faces = false;
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex") {
      have_vertices = true;
      read_ply_vertices(r, e, path, m);
    } else if (e.name == "face") {
      have_faces = true;
      read_ply_faces(r, e, path, m);
    } else {
      skip_ply_element(r, e);
    }
  }
  if (!have_vertices || !have_faces || m.triangles.empty())
    throw BakeError(path + ": no triangles (a PLY needs vertex and face elements)");
  return m;
}

DenseMesh read_cage_mesh(const std::string& path) {
  Cage c;
  try {
    c = load_cage(path);
  } catch (const std::exception& e) {
    throw BakeError(e.what());
  }
  DenseMesh m;
  m.name = path;
  m.positions = c.positions;
  for (int f = 0; f < c.face_count(); ++f)
    for (int k = 1; k + 1 < c.face_sizes[std::size_t(f)]; ++k)
      m.triangles.insert(m.triangles.end(), {std::uint32_t(c.face_vertex(f, 0)), std::uint32_t(c.face_vertex(f, k)),
                                             std::uint32_t(c.face_vertex(f, k + 1))});
  if (m.triangles.empty()) throw BakeError(path + ": no faces");
  return m;
}

}  // namespace

void compute_dense_normals(DenseMesh& m) {
  // Corners welded on exact bits: the first vertex with a position stands for all that share it.
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> buckets;
  std::vector<std::uint32_t> rep(m.positions.size());
  auto bits = [](const glm::vec3& p) {
    std::uint32_t x, y, z;
    std::memcpy(&x, &p.x, 4), std::memcpy(&y, &p.y, 4), std::memcpy(&z, &p.z, 4);
    return (std::uint64_t(x) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(y) * 0xC2B2AE3D27D4EB4Full) ^ std::uint64_t(z);
  };
  for (std::uint32_t i = 0; i < m.positions.size(); ++i) {
    auto& list = buckets[bits(m.positions[i])];
    rep[i] = i;
    for (std::uint32_t j : list)
      if (std::memcmp(&m.positions[j], &m.positions[i], sizeof(glm::vec3)) == 0) {
        rep[i] = j;
        break;
      }
    if (rep[i] == i) list.push_back(i);
  }
  std::vector<glm::dvec3> sum(m.positions.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < m.triangles.size(); t += 3) {
    const glm::dvec3 a(m.positions[m.triangles[t]]), b(m.positions[m.triangles[t + 1]]),
        c(m.positions[m.triangles[t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // twice the area, along the normal
    for (int k = 0; k < 3; ++k) sum[rep[m.triangles[t + std::size_t(k)]]] += n;
  }
  m.normals.resize(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const glm::dvec3 s = sum[rep[i]];
    const double len = glm::length(s);
    m.normals[i] = len > 0.0 ? glm::vec3(s / len) : glm::vec3(0.0f);
  }
}

DenseMesh load_dense_mesh(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw BakeError(path + ": no such file");
  if (fs::is_directory(path, ec)) throw BakeError(path + ": a directory, not a mesh");
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  DenseMesh m = ext == ".ply" ? read_ply(path) : read_cage_mesh(path);
  compute_dense_normals(m);
  return m;
}

}  // namespace tessera
