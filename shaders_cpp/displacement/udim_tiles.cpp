#include "shaders_cpp/displacement/udim_tiles.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <system_error>

#include "shaders_cpp/cage/one_line.h"
#include "shaders_cpp/displacement/displacement_map.h"

namespace tessera {
namespace {

constexpr std::string_view kToken = "<udim>";

std::size_t token_at(std::string_view path) {
  for (std::size_t i = 0; i + kToken.size() <= path.size(); ++i) {
    std::size_t k = 0;
    while (k < kToken.size() && std::tolower(static_cast<unsigned char>(path[i + k])) == kToken[k]) ++k;
    if (k == kToken.size()) return i;
  }
  return std::string_view::npos;
}

}  // namespace

bool has_udim_token(std::string_view path) { return token_at(path) != std::string_view::npos; }

std::string udim_tile_path(std::string_view pattern, int number) {
  const std::size_t at = token_at(pattern);
  if (at == std::string_view::npos) return std::string(pattern);
  return std::string(pattern.substr(0, at)) + std::to_string(number) + std::string(pattern.substr(at + kToken.size()));
}

std::vector<int> udim_tiles_on_disk(const std::string& pattern) {
  namespace fs = std::filesystem;
  const fs::path p(pattern);
  const std::string name = p.filename().string();
  const std::size_t at = token_at(name);
  if (at == std::string::npos) return {};
  const std::string prefix = name.substr(0, at), suffix = name.substr(at + kToken.size());
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::vector<int> found;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string f = it->path().filename().string();
    if (f.size() != prefix.size() + 4 + suffix.size() || f.compare(0, prefix.size(), prefix) != 0 ||
        f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits = f.substr(prefix.size(), 4);
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
    const int n = std::stoi(digits);
    if (n >= 1001 && n <= 2000) found.push_back(n);
  }
  std::sort(found.begin(), found.end());
  return found;
}

glm::vec2 UvTiles::local(glm::vec2 uv, std::uint16_t tile, bool v_down) const {
  const glm::ivec2 c = cells[tile];
  const float v_up = v_down ? 1.0f - uv.y : uv.y;
  return {uv.x - float(c.x), 1.0f - (v_up - float(c.y))};
}

UvTiles udim_face_tiles(const Cage& cage, const Topology& t, const std::string& map) {
  if (!cage.has_uvs()) throw CageError(cage.name + ": has no texture coordinates (vt); a displacement map needs them");
  const bool v_down = cage.uv_v_down;
  // UDIM space: ten columns, rows up to tile 1999's.
  constexpr float kColumns = 10.0f, kRows = 100.0f;
  for (std::size_t i = 0; i < cage.uvs.size(); ++i) {
    const float u = cage.uvs[i].x, v = v_down ? 1.0f - cage.uvs[i].y : cage.uvs[i].y;
    if (!(u >= 0.0f && u <= kColumns && v >= 0.0f && v <= kRows))
      throw DisplacementMapError(map + ": the cage " + cage.name + " has vt " + std::to_string(i + 1) + " (" +
                                 float_text(cage.uvs[i].x) + ", " + float_text(cage.uvs[i].y) +
                                 ") outside UDIM space (u in [0, 10], v in [0, 100])");
  }
  UvTiles out;
  out.face_tile.assign(std::size_t(t.face_count()), 0);
  std::vector<glm::ivec2> face_cell(std::size_t(t.face_count()), glm::ivec2(-1));
  std::map<int, glm::ivec2> used;
  for (int f = 0; f < t.face_count(); ++f) {
    if (t.is_hole(f)) continue;
    const int n = t.face_size(f);
    double su = 0.0, sv = 0.0;
    for (int k = 0; k < n; ++k) {
      const glm::vec2 uv = cage.uvs[std::size_t(cage.face_uvs[std::size_t(t.face_offset(f) + k)])];
      su += uv.x, sv += v_down ? 1.0 - double(uv.y) : double(uv.y);
    }
    const glm::ivec2 cell(std::min(int(std::floor(su / n)), 9), std::min(int(std::floor(sv / n)), 99));
    face_cell[std::size_t(f)] = cell;
    used.emplace(udim_number(cell), cell);
    bool spans = false;
    for (int k = 0; k < n; ++k) {
      const glm::vec2 uv = cage.uvs[std::size_t(cage.face_uvs[std::size_t(t.face_offset(f) + k)])];
      const float v = v_down ? 1.0f - uv.y : uv.y;
      spans |= !(uv.x >= float(cell.x) && uv.x <= float(cell.x + 1) && v >= float(cell.y) && v <= float(cell.y + 1));
    }
    out.spanning_faces += spans ? 1 : 0;
  }
  if (used.empty()) used.emplace(1001, glm::ivec2(0));
  std::map<int, std::uint16_t> index;
  for (const auto& [number, cell] : used) {
    index[number] = std::uint16_t(out.numbers.size());
    out.numbers.push_back(number);
    out.cells.push_back(cell);
  }
  for (int f = 0; f < t.face_count(); ++f)
    if (face_cell[std::size_t(f)].x >= 0) out.face_tile[std::size_t(f)] = index[udim_number(face_cell[std::size_t(f)])];
  return out;
}

}  // namespace tessera
