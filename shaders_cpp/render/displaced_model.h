// A displacement bound to a SubdModel: the map (and the normal map used for shading), the per-patch
// watertight texture coordinates and owner frames, computed once; and the draws that run the
// displaced shaders (displaced_shaders.h) as stream output.
//
// Contract: make_displacement throws DisplacementMapError (one line starting with the map's path) for a
// missing or unreadable map, a channel the map does not have, a wrong channel count, a cage whose UVs
// leave the map's [0, 1] square; CageError (naming the cage) for a cage without UVs, with faces that
// are not quads, or drawn with a scheme whose patches carry no 1-ring (flat, pn). Everything it builds is immutable;
// draws may run on any number of threads.
//
// Normal maps (for shading): `normal_map` = "auto" takes the RGB of the displacement file when the
// displacement is a scalar read from a file that has RGB besides it (the monster frog: height in A,
// tangent-space normal in RGB), and derives normals from the height otherwise; "derived" always
// derives them (scalar maps; vector maps shade with the base normal); any other value is a path
// whose R, G, B (channels 0..2) are the normal map.
//
// UDIM (udim_tiles.h): a path with the <UDIM> token names one map per tile. Each face samples its UV
// centre's tile; only the tiles the faces use are read, and a used tile without a file is an error
// naming every missing tile. A normal map path then needs the token too ("auto" takes the RGB of each
// displacement tile). Each tile is padded from its own charts and has its own mip chain.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "shaders_cpp/displacement/displacement_map.h"
#include "shaders_cpp/render/displaced_shaders.h"
#include "shaders_cpp/render/subd_model.h"
#include "shaders_cpp/subdiv/control_point_prepass.h"

namespace tessera {

enum class DisplacementSpace : std::uint8_t { tangent, object };

struct DisplacementOptions {
  std::string map;  // path (or, with map_bytes, the name of an embedded image)
  // An encoded image in memory (a glTF's embedded texture) and its format as an extension (".png").
  std::vector<std::uint8_t> map_bytes{}, normal_map_bytes{};
  std::string map_format{}, normal_map_format{};
  std::string channel;  // displacement_map.h's selection; 1 channel = scalar, 3 = vector
  float scale = 1.0f, bias = 0.0f;
  DisplacementSpace space = DisplacementSpace::tangent;  // vector maps only
  std::string normal_map = "auto";
  bool flip_v = true;  // OBJ UVs have v up: flipped for the texture (glTF cages are not); watertight_uv.h
  // Seams: the displacement map padded beyond and on its charts' borders (chart_padding.h), shading
  // from each patch's own chart, and normals blended across UV seams (DisplacedPS). Off: the map as the
  // file holds it, each seam point shaded from its sampling chart (the seam test's reference).
  bool pad_charts = true;
  bool own_chart_shading = true;
  bool seam_blending = true;
  // Test knobs (the negative tests): per-face UVs, and each patch's own normals.
  UvOwnership ownership = UvOwnership::owned;
  bool shared_normals = true;
};

// Texel rings of each chart's border rebuilt by padding (chart_padding.h).
inline constexpr int kChartBorderTexels = 2;

struct Displacement {
  // One map per tile, in the order of PatchTexcoords' tile indices (a single map: one).
  std::vector<DisplacementMap> maps;
  std::vector<DisplacementMap> normal_maps;  // per tile as `maps`; empty: derived (scalar) or base normals
  std::vector<int> udim;                     // the tiles' UDIM numbers; empty for a single map
  std::size_t spanning_faces = 0;            // UDIM: faces whose UVs leave their centre's tile
  DisplacementKind kind = DisplacementKind::scalar;
  float scale = 1.0f, bias = 0.0f;
  bool shared_normals = true;
  bool own_chart_shading = true;
  bool seam_blending = true;
  // A normal map's green points up the image, along −V (OBJ's v, the OpenGL and glTF convention):
  // the pixel shader flips it. (The UVs themselves are flipped only for OBJ cages: Cage::uv_v_down.)
  bool flip_v = true;
  std::vector<PatchTexcoords> texcoords;  // per quad patch
  PatchFrames frames;                     // per quad patch
  std::size_t bytes() const;              // maps (all levels) + per-patch data
  // The largest distance a point is moved: max |scale * texel + bias| over level 0 (a vector's length).
  // LOD and culling grow their bounds by it.
  float bound = 0.0f;

  // Mip levels blended (view-dependent LOD: displaced_shaders.h, DisplacementParams::trilinear).
  bool trilinear = false;

  DisplacementParams params() const { return {maps, kind, scale, bias, shared_normals, trilinear, own_chart_shading}; }
  // Level 0's size of each tile (DisplacedHS::map_sizes).
  std::vector<glm::vec2> map_sizes() const;
};

Displacement make_displacement(const SubdModel& model, const DisplacementOptions& options);
// The per-patch watertight texture coordinates of a model that a map named `map` will displace (and
// `tessera bake` writes): CageError for a scheme without 1-rings (flat, pn), a cage without UVs or with
// faces that are not quads; DisplacementMapError naming `map` for a UV outside [0, 1].
// With `tiles` (UDIM) the UVs are in their faces' tiles (build_patch_texcoords) and not checked here.
std::vector<PatchTexcoords> displacement_texcoords(const SubdModel& model, const std::string& map,
                                                   UvOwnership ownership = UvOwnership::owned, bool flip_v = true,
                                                   const UvTiles* tiles = nullptr);
float displacement_bound(const Texture2D& map, DisplacementKind kind, float scale, float bias);
// The largest over the tiles.
float displacement_bound(std::span<const DisplacementMap> maps, DisplacementKind kind, float scale, float bias);

// The displaced hull and domain shaders of the model's (quad) patch group, handed to
// draw(group, tessellator_state, hs, ds) -> DrawResult.
template <class Draw>
DrawResult with_displaced_group(const SubdModel& m, const Displacement& d, const SubdFactors& factors,
                                const PatchCull& cull, ts::Partitioning partitioning, Draw&& draw) {
  const PatchGroup& g = m.patches.quads;
  if (g.patches.empty()) return {};
  const TessellatorState ts{g.domain, partitioning, ts::OutputPrimitive::triangle_cw};
  // The frames of precomputed patches follow the pose: summed here, before the draw.
  const std::vector<glm::vec3> frame_rows = precompute_rows(d.frames.precomputed, m.positions());
  const std::vector<glm::vec2> map_sizes = d.map_sizes();
  const DisplacedHS hs{SubdHS{g.patches, m.patches.tables, factors, false, m.ring_boxes, partitioning, m.precomputed, cull},
                       d.texcoords, &d.frames, map_sizes, frame_rows};
  const DisplacedDS ds{SubdDS{g.patches, m.limit.get(), m.cage.tags.left_handed, false}, d.texcoords, d.params()};
  return draw(g, ts, hs, ds);
}

// IA..DS with displacement; each patch's DisplacedPoints go to sink(PatchOutput<DisplacedPoint>, group).
template <class Sink>
DrawResult stream_displaced(Device& device, const SubdModel& m, const Displacement& d, const SubdFactors& factors,
                            const PatchCull& cull, ts::Partitioning partitioning, Sink&& sink) {
  return with_displaced_group(
      m, d, factors, cull, partitioning,
      [&](const PatchGroup& g, const TessellatorState& ts, const DisplacedHS& hs, const DisplacedDS& ds) {
        const StreamDraw<glm::vec3, SubdVS, DisplacedHS, DisplacedDS> draw{
            m.vertex_buffer(), g.indices, g.control_points, m.vertex_shader(), hs, ds, ts};
        return stream_out(device, draw, [&](const PatchOutput<DisplacedPoint>& p) { sink(p, g); });
      });
}

// The draw's patch groups, displaced (with_displaced_group) when `d` is given, else plain
// (for_each_patch_group): draw(group, tessellator_state, hs, ds) -> DrawResult with the matching shaders.
template <class Draw>
DrawResult for_each_surface_group(const SubdModel& m, const Displacement* d, const SubdFactors& factors,
                                  const PatchCull& cull, ts::Partitioning partitioning, Draw&& draw) {
  if (d != nullptr) return with_displaced_group(m, *d, factors, cull, partitioning, draw);
  return for_each_patch_group(m, factors, cull, partitioning, draw);
}

// stream_displaced or stream_subd by `d`: the sink takes (PatchOutput<DisplacedPoint or SurfaceSample>, group).
template <class Sink>
DrawResult stream_surface(Device& device, const SubdModel& m, const Displacement* d, const SubdFactors& factors,
                          const PatchCull& cull, ts::Partitioning partitioning, Sink&& sink) {
  if (d != nullptr) return stream_displaced(device, m, *d, factors, cull, partitioning, sink);
  return stream_subd(device, m, factors, cull, partitioning, sink);
}

// The streams without a cull policy: every patch.
template <class Sink>
DrawResult stream_displaced(Device& device, const SubdModel& m, const Displacement& d, const SubdFactors& factors,
                            ts::Partitioning partitioning, Sink&& sink) {
  return stream_displaced(device, m, d, factors, PatchCull{}, partitioning, std::forward<Sink>(sink));
}
template <class Sink>
DrawResult stream_surface(Device& device, const SubdModel& m, const Displacement* d, const SubdFactors& factors,
                          ts::Partitioning partitioning, Sink&& sink) {
  return stream_surface(device, m, d, factors, PatchCull{}, partitioning, std::forward<Sink>(sink));
}

}  // namespace tessera
