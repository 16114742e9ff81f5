#include "shaders_cpp/render/displaced_model.h"

#include "shaders_cpp/displacement/chart_padding.h"

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
  return (map ? map->bytes() : 0) + (normal_map ? normal_map->bytes() : 0) + texcoords.size() * sizeof(PatchTexcoords) +
         frames.bytes();
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

std::vector<PatchTexcoords> displacement_texcoords(const SubdModel& model, const std::string& map,
                                                   UvOwnership ownership, bool flip_v) {
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
      build_patch_texcoords(cage, *model.topology, model.patches.quads, ownership, flip_v && !cage.uv_v_down);
  for (std::size_t i = 0; i < cage.uvs.size(); ++i) {
    const glm::vec2 uv = cage.uvs[i];
    if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f))
      throw DisplacementMapError(map + ": the cage " + cage.name + " has vt " + std::to_string(i + 1) + " (" +
                                 float_text(uv.x) + ", " + float_text(uv.y) +
                                 ") outside the map's [0, 1] square: this map does not fit the cage's UVs");
  }
  return texcoords;
}

Displacement make_displacement(const SubdModel& model, const DisplacementOptions& o) {
  if (!std::isfinite(o.scale) || !std::isfinite(o.bias))
    throw DisplacementMapError(o.map + ": displacement scale and bias must be finite");
  Displacement d;
  // One decode of the file serves the displacement and, with "auto", the normal map beside it.
  const DisplacementImage image = [&] {
    try {
      const DisplacementImage::Selection selection{o.channel, 0};
      return o.map_bytes.empty() ? DisplacementImage::read(o.map, selection)
                                 : DisplacementImage::read_encoded(o.map, o.map_bytes, o.map_format, selection);
    } catch (const DisplacementMapError& e) {
      throw DisplacementMapError(std::string(e.what()) + " (displacement map)");
    }
  }();
  d.map = image.select(o.channel, 0);
  const bool vector = d.map->channels() == 3;
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

  const Cage& cage = model.cage;
  d.texcoords = displacement_texcoords(model, o.map, o.ownership, o.flip_v);
  if (o.normal_map == "auto") {
    const bool has_rgb = image.channel_names().size() >= 4 &&
                         std::none_of(d.map->selected().begin(), d.map->selected().end(), is_rgb_name);
    if (!vector && has_rgb) d.normal_map = image.select("R,G,B", 3);
  } else if (o.normal_map != "derived") {
    try {
      d.normal_map = o.normal_map_bytes.empty() ? DisplacementMap::load(o.normal_map, "R,G,B", 3)
                                                : DisplacementMap::load_encoded(o.normal_map, o.normal_map_bytes,
                                                                                o.normal_map_format, "R,G,B", 3);
    } catch (const DisplacementMapError& e) {  // the same reader as the height's: say which map
      throw DisplacementMapError(std::string(e.what()) + " (normal map)");
    }
  }

  if (o.pad_charts && o.ownership == UvOwnership::owned) {
    // The texels beyond and on each chart's border continue its inside (chart_padding.h): no ridge
    // along the seams. Only the displacement map: a normal map's border texels are its bake's own.
    d.map = d.map->padded(chart_coverage(d.texcoords, d.map->width(), d.map->height(), kChartBorderTexels));
  }
  d.frames = build_patch_frames(cage, *model.topology, model.patches.quads, model.patches.scheme);
  d.bound = displacement_bound(d.map->texture(), d.kind, d.scale, d.bias);
  return d;
}

}  // namespace tessera
