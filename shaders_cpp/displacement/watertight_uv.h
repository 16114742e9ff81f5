// Watertight texture sampling (Castaño's edge and corner ownership): per patch 16 texture coordinates,
// four per corner, so that a point on a cage edge or vertex gets the same UV bits on every patch that
// shares it, even across a UV seam, and so samples the same texels in the same order.
//
// Ownership (a pure function of the topology, computed once per model):
// - a cage edge belongs to the lower-index of its two half-edges whose face is not a hole (the face
//   first in face order; boundary edges to their only half-edge);
// - a cage vertex belongs to its first outgoing half-edge, in half-edge order, whose face is not a hole
//   (the lowest-index face around it).
//
// Slots, per patch corner k (patch corner k is face corner k + rotation, as SubdPatch says):
// - interior[k]: the face's own UV at the corner; interior points interpolate these bilinearly;
// - edge[k]: for patch edge k (corner k -> k+1) the edge owner face's UVs a, b at the edge's ends in
//   the owner's direction, and c, d at the owner face's far corners (c next to b, d next to a; they
//   give the UV derivative across the edge for tangent frames). `reversed[k]`: this patch runs the
//   edge against the owner (its parameter t becomes the owner's 1 − t, exact for tessellator
//   parameters). A point on the edge interpolates a and b at the owner's parameter:
//   a (1 − t) + b t, the same operations on the same bits on both sides;
// - corner[k]: the vertex owner's UV; corner_span[k]: the vertex owner face's UV steps toward its
//   next and previous corners (the UV derivatives at the corner, for tangent frames); corner_key[k]:
//   the cage edge key of the owner's outgoing edge (the corner's LOD uses that edge's factor).
//
// - seam_edges, twin, twin_mirrored: the face across each patch edge, for shading (see the struct).
//
// Per-face (naive) texcoords put the face's own UVs in the edge and corner UV slots (the owners, spans
// and LOD keys stay): what the negative tests use to show that a UV seam then cracks.
//
// Contract: quad patches only (displaced cages must be quads; build throws CageError naming the face
// otherwise); the cage must have UVs (CageError naming the cage). Slots are copies of the cage's
// floats (corner_span one subtraction each, computed once per model, so shared by construction).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/subdiv/subd_patches.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/displacement/udim_tiles.h"

namespace tessera {

struct PatchTexcoords {
  std::array<glm::vec2, 4> interior{};
  std::array<std::array<glm::vec2, 4>, 4> edge{};  // a, b, c, d per patch edge
  std::array<std::uint8_t, 4> reversed{};
  std::array<glm::vec2, 4> corner{};
  std::array<std::array<glm::vec2, 2>, 4> corner_span{};
  std::array<std::int64_t, 4> corner_key{};
  std::array<std::int32_t, 4> edge_face{}, vertex_face{};
  std::array<std::uint8_t, 4> edge_corner{}, vertex_corner{};
  // For shading across UV seams (displaced_shaders.h, DisplacedPS): bit k of `seam_edges` says patch
  // edge k is a UV seam (the face across it has other UVs at the edge's ends); `twin[k]` holds that
  // face's UVs at patch corners k and k + 1, and bit k of `twin_mirrored` says its chart has the other
  // orientation (a mirrored chart). Not used for sampling positions.
  std::array<std::array<glm::vec2, 2>, 4> twin{};
  std::uint8_t seam_edges = 0, twin_mirrored = 0;
  // UDIM (udim_tiles.h): the tile each slot's UVs are in, an index into the model's tiles; the UVs
  // are in that tile's texture coordinates. Every tile 0 for a single map.
  std::uint16_t tile = 0;  // interior
  std::array<std::uint16_t, 4> edge_tile{}, corner_tile{}, twin_tile{};
};

enum class UvOwnership : std::uint8_t { owned, per_face };

// The half-edge that owns h's cage edge, and the one that owns vertex v (-1 if only holes touch it).
int edge_owner(const Topology& t, int h);
int vertex_owner(const Topology& t, int v);

// One entry per patch of the group, in patch order.
// `flip_v` stores (u, 1 − v): OBJ texture coordinates have v = 0 at the bottom of the image, textures
// (texture.h, D3D) have row 0 at v = 0. Each cage UV is flipped once, so shared slots stay identical.
// With `tiles` (UDIM), each slot holds its face's UVs in that face's tile (UvTiles::local; v taken as
// pointing down when `flip_v` is false) and names the tile; a UV seam is then a change of UV or of tile.
std::vector<PatchTexcoords> build_patch_texcoords(const Cage& cage, const Topology& topology, const PatchGroup& group,
                                                  UvOwnership ownership = UvOwnership::owned, bool flip_v = true,
                                                  const UvTiles* tiles = nullptr);

// Bilinear interpolation of four corner values at (u, v), corner k at (0,0),(1,0),(1,1),(0,1).
inline glm::vec2 bilerp_uv(const std::array<glm::vec2, 4>& c, float u, float v) {
  const float s = 1.0f - u, t = 1.0f - v;
  return t * (s * c[0] + u * c[1]) + v * (s * c[3] + u * c[2]);
}

}  // namespace tessera
