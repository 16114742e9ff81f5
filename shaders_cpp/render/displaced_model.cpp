#include "shaders_cpp/render/displaced_model.h"

#include "shaders_cpp/displacement/chart_padding.h"
#include "shaders_cpp/displacement/udim_tiles.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tessera {
namespace {

std::string float_text(float x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

bool is_rgb_name(const std::string& n) { return n == "R" || n == "G" || n == "B" || n == "r" || n == "g" || n == "b"; }

}  // namespace

std::size_t Displacement::bytes() const {
  std::size_t b = texcoords.size() * sizeof(PatchTexcoords) + frames.bytes();
  for (const DisplacementMap& m : maps) b += m.bytes();
  for (const DisplacementMap& m : normal_maps) b += m.bytes();
  return b;
}

std::vector<glm::vec2> Displacement::map_sizes() const {
  std::vector<glm::vec2> sizes;
  sizes.reserve(maps.size());
  for (const DisplacementMap& m : maps) sizes.emplace_back(float(m.width()), float(m.height()));
  return sizes;
}

float displacement_bound(const Texture2D& map, DisplacementKind kind, float scale, float bias) {
  // Every level is a box average of level 0 and bilinear filtering blends texels with weights in
  // [0, 1], so no sample leaves level 0's range; computed in double, then rounded up.
  double largest = 0.0;
  for (int y = 0; y < map.height(0); ++y)
    for (int x = 0; x < map.width(0); ++x) {
      const glm::dvec4 t(map.load(0, x, y));
      const double m = kind == DisplacementKind::scalar
                           ? std::abs(double(scale) * t.x + double(bias))
                           : glm::length(glm::dvec3(double(scale) * glm::dvec3(t) + double(bias)));
      largest = std::max(largest, m);
    }
  return std::nextafter(float(largest), INFINITY);
}

float displacement_bound(std::span<const DisplacementMap> maps, DisplacementKind kind, float scale, float bias) {
  float largest = 0.0f;
  for (const DisplacementMap& m : maps) largest = std::max(largest, displacement_bound(m.texture(), kind, scale, bias));
  return largest;
}

std::vector<PatchTexcoords> displacement_texcoords(const SubdModel& model, const std::string& map,
                                                   UvOwnership ownership, bool flip_v, const UvTiles* tiles) {
  const Cage& cage = model.cage;
  // Owner frames are stencils over the 1-ring of the shared edge or vertex (displacement_frames.h);
  // flat and pn patches carry only their face, so a frame owned by a neighbour is out of their reach.
  const Scheme scheme = model.patches.scheme;
  if (scheme == Scheme::flat || scheme == Scheme::pn)
    throw CageError(cage.name + ": --scheme " + to_string(scheme) +
                    " cannot be displaced (its patches carry no 1-ring for the shared normals); use acc, gregory, "
                    "bspline or exact");
  // Texture coordinates first: it checks that the cage has UVs and only quads (CageError).
  // glTF's texture v already points down the image; OBJ's is flipped.
  std::vector<PatchTexcoords> texcoords =
      build_patch_texcoords(cage, *model.topology, model.patches.quads, ownership, flip_v && !cage.uv_v_down, tiles);
  if (tiles != nullptr) return texcoords;  // UDIM space checked by udim_face_tiles
  for (std::size_t i = 0; i < cage.uvs.size(); ++i) {
    const glm::vec2 uv = cage.uvs[i];
    if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f))
      throw DisplacementMapError(map + ": the cage " + cage.name + " has vt " + std::to_string(i + 1) + " (" +
                                 float_text(uv.x) + ", " + float_text(uv.y) +
                                 ") outside the map's [0, 1] square: this map does not fit the cage's UVs" +
                                 (uv.x >= 0.0f && uv.x <= 10.0f && uv.y >= 0.0f
                                      ? " (UDIM tiles? name them with <UDIM>, e.g. height.<UDIM>.exr)"
                                      : ""));
  }
  return texcoords;
}

namespace {

// The files of a UDIM set for the given tiles; one error naming every missing tile.
std::vector<std::string> tile_paths(const std::string& pattern, const std::vector<int>& numbers, const char* what) {
  const std::vector<int> on_disk = udim_tiles_on_disk(pattern);
  std::string missing, first;
  std::size_t count = 0;
  std::vector<std::string> paths;
  for (int n : numbers) {
    paths.push_back(udim_tile_path(pattern, n));
    if (std::binary_search(on_disk.begin(), on_disk.end(), n)) continue;
    if (count == 0) first = paths.back();
    missing += (count++ ? ", " : "") + std::to_string(n);
  }
  if (count != 0)
    throw DisplacementMapError(pattern + ": " + std::to_string(count) + " tile" + (count > 1 ? "s" : "") +
                               " the cage's faces use " + (count > 1 ? "have" : "has") + " no file (" + what +
                               "): " + missing + " (no " + first + "; " + std::to_string(on_disk.size()) + " tile" +
                               (on_disk.size() == 1 ? "" : "s") + " on disk)");
  return paths;
}

}  // namespace

Displacement make_displacement(const SubdModel& model, const DisplacementOptions& o) {
  if (!std::isfinite(o.scale) || !std::isfinite(o.bias))
    throw DisplacementMapError(o.map + ": displacement scale and bias must be finite");
  Displacement d;
  const Cage& cage = model.cage;
  const bool udim = o.map_bytes.empty() && has_udim_token(o.map);
  const bool normal_path = o.normal_map != "auto" && o.normal_map != "derived";
  if (normal_path && o.normal_map_bytes.empty() && has_udim_token(o.normal_map) != udim)
    throw DisplacementMapError(o.normal_map + ": the normal map " + (udim ? "needs" : "has") +
                               " the <UDIM> token as the displacement map " + o.map + (udim ? " has" : " does not"));
  std::optional<UvTiles> tiles;
  std::vector<std::string> paths = {o.map};
  if (udim) {
    // The cage's UVs, faces and scheme are checked before any tile is read.
    tiles = udim_face_tiles(cage, *model.topology, o.map);
    d.texcoords = displacement_texcoords(model, o.map, o.ownership, o.flip_v, &*tiles);
    paths = tile_paths(o.map, tiles->numbers, "displacement map");
    d.udim = tiles->numbers;
    d.spanning_faces = tiles->spanning_faces;
  }

  // One decode of each file serves the displacement and, with "auto", the normal map beside it.
  bool has_rgb = false;
  for (std::size_t t = 0; t < paths.size(); ++t) {
    const DisplacementImage image = [&] {
      try {
        const DisplacementImage::Selection selection{o.channel, 0};
        return o.map_bytes.empty() ? DisplacementImage::read(paths[t], selection)
                                   : DisplacementImage::read_encoded(o.map, o.map_bytes, o.map_format, selection);
      } catch (const DisplacementMapError& e) {
        throw DisplacementMapError(std::string(e.what()) + " (displacement map)");
      }
    }();
    d.maps.push_back(image.select(o.channel, 0));
    const DisplacementMap& m = d.maps.back();
    if (m.channels() != d.maps.front().channels())
      throw DisplacementMapError(paths[t] + ": " + std::to_string(m.channels()) + " channel(s) selected where tile " +
                                 std::to_string(d.udim.front()) + " has " +
                                 std::to_string(d.maps.front().channels()) + " (displacement map)");
    if (o.normal_map == "auto") {
      const bool rgb = m.channels() == 1 && image.channel_names().size() >= 4 &&
                       std::none_of(m.selected().begin(), m.selected().end(), is_rgb_name);
      if (t == 0) has_rgb = rgb;
      if (rgb != has_rgb)
        throw DisplacementMapError(paths[t] + ": " + (rgb ? "has" : "lacks") + " the RGB normal map that tile " +
                                   std::to_string(d.udim.front()) + (rgb ? " lacks" : " has") +
                                   " (--normal-map auto); give --normal-map derived or a normal map");
      if (rgb) d.normal_maps.push_back(image.select("R,G,B", 3));
    }
  }
  const bool vector = d.maps.front().channels() == 3;
  // A height moves along the normal only: an object-space request would be silently meaningless.
  if (!vector && o.space == DisplacementSpace::object)
    throw DisplacementMapError(o.map +
                               ": object-space displacement needs a vector map (three channels, e.g. R,G,B); the "
                               "selected channel is a scalar height");
  d.kind = !vector                                ? DisplacementKind::scalar
           : o.space == DisplacementSpace::object ? DisplacementKind::vector_object
                                                  : DisplacementKind::vector_tangent;
  d.scale = o.scale, d.bias = o.bias;
  d.shared_normals = o.shared_normals;
  d.own_chart_shading = o.own_chart_shading;
  d.seam_blending = o.seam_blending;
  d.flip_v = o.flip_v;

  if (!udim) d.texcoords = displacement_texcoords(model, o.map, o.ownership, o.flip_v);
  if (normal_path) {
    try {
      if (!o.normal_map_bytes.empty())
        d.normal_maps.push_back(
            DisplacementMap::load_encoded(o.normal_map, o.normal_map_bytes, o.normal_map_format, "R,G,B", 3));
      else
        for (const std::string& p : udim ? tile_paths(o.normal_map, tiles->numbers, "normal map")
                                         : std::vector<std::string>{o.normal_map})
          d.normal_maps.push_back(DisplacementMap::load(p, "R,G,B", 3));
    } catch (const DisplacementMapError& e) {  // the same reader as the height's: say which map
      throw DisplacementMapError(std::string(e.what()) + " (normal map)");
    }
  }

  if (o.pad_charts && o.ownership == UvOwnership::owned) {
    // The texels beyond and on each chart's border continue its inside (chart_padding.h): no ridge
    // along the seams. Only the displacement map: a normal map's border texels are its bake's own.
    // Each tile from the charts of the faces it serves.
    for (std::size_t t = 0; t < d.maps.size(); ++t) {
      std::vector<PatchTexcoords> in_tile;  // a single map's charts are all the patches: no copy
      if (d.maps.size() > 1)
        for (const PatchTexcoords& tc : d.texcoords)
          if (tc.tile == t) in_tile.push_back(tc);
      DisplacementMap& m = d.maps[t];
      m = m.padded(chart_coverage(d.maps.size() == 1 ? std::span<const PatchTexcoords>(d.texcoords) : in_tile,
                                  m.width(), m.height(), kChartBorderTexels));
    }
  }
  d.frames = build_patch_frames(cage, *model.topology, model.patches.quads, model.patches.scheme);
  d.bound = displacement_bound(d.maps, d.kind, d.scale, d.bias);
  return d;
}

}  // namespace tessera
