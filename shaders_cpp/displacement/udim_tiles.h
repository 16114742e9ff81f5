// UDIM tiles: one map per unit square of UV space, as Mari, Blender, Maya and RenderMan write them.
// Tile (column c, row r) covers u in [c, c + 1), v in [r, r + 1) (v up, OBJ's convention) and is
// numbered 1001 + c + 10 r, c in 0..9; a path names the set with Mari's token: `height.<UDIM>.exr`
// stands for `height.1001.exr`, `height.1002.exr`, ...
//
// Which tile a point samples is decided per face, never per point: a face takes the tile of its UV
// centre, and every point of a patch that ownership gives another face's UVs (watertight_uv.h: an edge
// owner's, a vertex owner's) takes that face's tile with them. Both patches along an edge then read the
// same tile at the same UV bits, so tile borders stay watertight as UV seams do; and a point exactly on
// a tile border (u = 1) reads its face's tile at its edge, not the next tile's first column. A face
// whose corners lie in several tiles is sampled from its centre's tile (clamped at its border).
//
// Contract: pure functions; errors are DisplacementMapError, one line starting with the map's path.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"

namespace tessera {

// Whether `path` holds the <UDIM> token (any case).
bool has_udim_token(std::string_view path);
// `pattern` with its <UDIM> token replaced by the tile number.
std::string udim_tile_path(std::string_view pattern, int number);
inline int udim_number(glm::ivec2 cell) { return 1001 + cell.x + 10 * cell.y; }
// The tile numbers whose files exist for `pattern`, ascending.
std::vector<int> udim_tiles_on_disk(const std::string& pattern);

// Each face's tile: an index into `numbers` (the tiles the cage's faces use, ascending).
struct UvTiles {
  std::vector<int> numbers;
  std::vector<glm::ivec2> cells;  // (column, row) of each tile in `numbers`
  std::vector<std::uint16_t> face_tile;
  std::size_t spanning_faces = 0;  // faces with a corner in another tile than their centre's
  // A face's UV in its tile's texture coordinates, v down the image (texture.h): (u - c, 1 - (v_up - r)),
  // v_up = v for cages whose v points up (OBJ), 1 - v for those whose v points down (glTF).
  glm::vec2 local(glm::vec2 uv, std::uint16_t tile, bool v_down) const;
};

// The tiles of the cage's faces (holes take tile 0). Throws DisplacementMapError naming `map` and the
// first vt outside UDIM space (u in [0, 10), v in [0, 100)) or not finite.
UvTiles udim_face_tiles(const Cage& cage, const Topology& topology, const std::string& map);

}  // namespace tessera
