#include "tools/scene/model_options.h"

#include <cmath>
#include <fstream>
#include <filesystem>
#include <set>
#include <sstream>
#include <unordered_map>

#include "shaders_cpp/animation/animation_sampler.h"
#include "shaders_cpp/cage/up_axis_hint.h"
#include "shaders_cpp/gltf/gltf_cage.h"
#include "tools/scene/common.h"

namespace tessera::scene {

void add_scheme_options(CLI::App& cmd, RenderSettings& s) {
  add_setting_option(
      cmd, "--scheme", s.scheme, [](const std::string& text) { return scheme_option(text); },
      "flat (bilinear/linear), bspline (regular faces; others Gregory), acc (quads only), gregory "
      "(Gregory ACC: quads, triangles, n-gons as fans), exact (OpenSubdiv limit), pn (PN triangles and quads) or "
      "adaptive "
      "(feature-adaptive patches to --isolation: creases, corners and every face)")
      ->default_str(to_string(s.scheme));
  add_setting_option(
      cmd, "--isolation", s.isolation, [](const std::string& text) { return isolation_option(text); },
      "--scheme adaptive: the isolation level, 1 to " + std::to_string(kMaxIsolation) +
          " (refinement around extraordinary vertices and creases; higher is closer to exact)")
      ->default_str(std::to_string(s.isolation));
  cmd.add_option("--factor", s.factor, "tessellation factor on every edge")->capture_default_str();
  cmd.add_option("--vary-factors", s.vary, "spread edge factors over [F, F*(1+X)] by a hash of each cage edge");
  cmd.add_option("--factors-per-edge", s.factors_file, "file of 'v0 v1 factor' lines (cage vertex indices from 0)");
  add_setting_option(
      cmd, "--partitioning", s.partitioning, [](const std::string& text) { return partitioning_option(text); },
      "integer, pow2, fractional_odd or fractional_even")
      ->default_str(std::string(ts::to_string(s.partitioning)));
  cmd.add_option("--threads", s.threads, "worker threads (0: all)");
}

SubdFactors factors_option(float factor, float vary, const std::string& file, const Cage& cage) {
  // The range rules first (lod/subd_factors.h), so a bad --factor is named before a bad file.
  SubdFactors f = with_usage_errors([&] { return base_factors(factor, vary); });
  if (file.empty()) return f;
  if (std::filesystem::is_directory(file)) throw InputError(file + ": a directory, not a factors file");
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open");
  std::set<std::int64_t> edges;
  for (int face = 0; face < cage.face_count(); ++face) {
    const int n = cage.face_sizes[std::size_t(face)];
    for (int k = 0; k < n; ++k)
      edges.insert(cage_edge_key(cage.source_vertex(cage.face_vertex(face, k)),
                                 cage.source_vertex(cage.face_vertex(face, (k + 1) % n))));
  }
  auto map = std::make_shared<std::unordered_map<std::int64_t, float>>();
  std::string line;
  int number = 0, outside = 0;
  constexpr int kNamedOutside = 3;  // lines named one by one; the rest counted
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    const std::string where = file + ":" + std::to_string(number);
    std::istringstream s(line);
    long long a = -1, b = -1;
    std::string value;
    if (!(s >> a >> b >> value) || a < 0 || b < 0 || a > 0x7fffffff || b > 0x7fffffff)
      throw InputError(where + ": expected 'v0 v1 factor'");
    const auto x = parse_float(value);
    if (!x) throw InputError(where + ": '" + value + "' is not a number");
    const std::int64_t key = cage_edge_key(int(a), int(b));
    if (!edges.count(key))
      throw InputError(where + ": " + std::to_string(a) + " " + std::to_string(b) + " is not an edge of " + cage.name +
                       " (" + std::to_string(cage.vertex_count()) + " vertices; indices count from 0, OBJ's from 1)");
    // D3D11's rules apply to the value (<= 0 culls the patches on the edge, > 64 clamps to 64): such
    // values pass through, named once each. A value that is not finite is refused: in a file it is a
    // mistake far more often than a test of the cull, which 0 asks for plainly.
    if (!std::isfinite(*x))
      throw InputError(where + ": factor '" + value +
                       "' is not finite (D3D11 culls the patches on an edge whose factor is NaN; give 0 to cull them)");
    const bool culls = *x <= 0.0f, clamps = *x > 64.0f;
    if ((culls || clamps) && ++outside <= kNamedOutside)
      log_info("warning: " + where + ": factor " + value +
               (culls ? " <= 0: D3D11 culls the patches on this edge (their neighbours' edges become border)"
                      : " > 64: D3D11 clamps it to 64"));
    (*map)[key] = *x;
  }
  // The file names the file's vertices; a non-manifold cage's split copies of an edge take its factor.
  for (int face = 0; face < cage.face_count() && !cage.vertex_source.empty(); ++face) {
    const int n = cage.face_sizes[std::size_t(face)];
    for (int k = 0; k < n; ++k) {
      const int a = cage.face_vertex(face, k), b = cage.face_vertex(face, (k + 1) % n);
      const auto it = map->find(cage_edge_key(cage.source_vertex(a), cage.source_vertex(b)));
      if (it == map->end()) continue;
      const float value = it->second;  // read before the insertion may rehash
      (*map)[cage_edge_key(a, b)] = value;
    }
  }
  if (outside > kNamedOutside)
    log_info("warning: " + file + ": " + std::to_string(outside - kNamedOutside) +
             " more factors <= 0 (culled) or > 64 (clamped)");
  f.per_edge = std::move(map);
  return f;
}

void add_asset_options(CLI::App& cmd, AssetSettings& a, bool with_time) {
  cmd.add_option("--scene-index", a.scene_index, "glTF: the scene to read (default: the file's default scene)");
  cmd.add_option("--mesh", a.mesh, "glTF: read only the mesh (or node) of this name");
  if (!with_time) return;
  cmd.add_option("--animation", a.animation, "glTF: the animation to play, by name or index (default: the first)");
  cmd.add_option("--time", a.time, "glTF: seconds into the animation; skins and morph targets pose the cage")
      ->capture_default_str();
}

void pose_model(SubdModel& m, const AssetSettings& asset, double time) {
  if (!std::isfinite(time) || std::abs(time) > 1e9)
    throw UsageError("--time: " + std::to_string(time) + " is not a finite time in seconds");
  int animation = m.rig->animations.empty() ? -1 : 0;
  if (!asset.animation.empty()) {
    animation = find_animation(*m.rig, asset.animation);
    if (animation < 0) {
      std::string names;
      for (std::size_t a = 0; a < m.rig->animations.size(); ++a)
        names += (a ? ", " : "") + std::to_string(a) +
                 (m.rig->animations[a].name.empty() ? "" : " (" + m.rig->animations[a].name + ")");
      throw UsageError("--animation: " + m.cage.name + " has no animation '" + asset.animation +
                       "' (it has: " + (names.empty() ? "none" : names) + ")");
    }
  }
  try {
    set_pose(m, pose_at(*m.rig, animation, time));
  } catch (const CageError& e) {
    throw InputError(e.what());  // the exact scheme's limit surface of this pose
  }
  for (const glm::vec3& p : m.posed_positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(m.cage.name + ": the pose at " + std::to_string(time) + " s moves a vertex to infinity");
}

GltfSelection gltf_selection(const std::string& path, const AssetSettings& a) {
  if (!is_gltf_path(path) && (a.scene_index >= 0 || !a.mesh.empty() || !a.animation.empty()))
    throw UsageError("--scene-index, --mesh and --animation apply to glTF assets; " + path + " is not one");
  GltfSelection selection;
  if (a.scene_index >= 0) selection.scene = a.scene_index;
  selection.mesh = a.mesh;
  return selection;
}

SubdModel load_model(const std::string& path, Scheme scheme, const AssetSettings& asset, int isolation,
                     const PrepareStep& step) {
  const GltfSelection selection = gltf_selection(path, asset);
  SubdModel m;
  try {
    m = load_subd_model(path, scheme, selection, isolation, step);
  } catch (const CageError& e) {
    throw InputError(e.what());
  }
  for (const std::string& w : m.cage.warnings) log_info("warning: " + w);
  pose_or_refuse(m, path, asset);
  return m;
}

void pose_or_refuse(SubdModel& m, const std::string& path, const AssetSettings& asset) {
  if (m.rig) {
    pose_model(m, asset, asset.time);
  } else if (asset.time != 0.0) {
    throw UsageError("--time " + float_text(float(asset.time)) + ": " + path + " is not animated" +
                     (is_gltf_path(path) ? " (no skin, morph target or animation)" : " (OBJ cages are static)"));
  } else if (!asset.animation.empty()) {
    throw UsageError("--animation: " + path + " has no animations");
  }
}

void add_displacement_options(CLI::App& cmd, DisplacementSettings& d) {
  cmd.add_option("--displacement", d.map,
                 "displacement map (EXR, TIFF, PNG, DDS, ...), sampled at the cage's UVs; UDIM tiles as "
                 "name.<UDIM>.exr (1001 + u + 10 v); default: a glTF material's KHR_materials_displacement "
                 "texture; none: no displacement");
  cmd.add_option("--displacement-channel", d.channel,
                 "channel(s) of the map: a name or letter (A, height) for a scalar, three (RGB, 'X,Y,Z') for a vector");
  cmd.add_option("--displacement-scale", d.scale,
                 "displacement = scale * texel + bias (object units; default 1, or a glTF material's factor)");
  cmd.add_option("--displacement-bias", d.bias, "added after scaling (default 0, or a glTF material's offset)");
  add_setting_option(cmd, "--displacement-space", d.space, displacement_space_option, "vector maps: tangent or object")
      ->default_str(to_string(d.space));
  cmd.add_option(
         "--normal-map", d.normal_map,
         "shading normals: auto (the displacement file's RGB when the height is another channel, else derived), "
         "derived (from the height), or a tangent-space normal map file")
      ->capture_default_str();
  add_setting_option(cmd, "--uv-seams", d.uv_seams, uv_seams_option,
                     "across UV seams: blend (shade each patch from its own chart, blend the two charts' normals at "
                     "the seam, pad the displacement map beyond its charts) or raw (the maps as stored, the owner's "
                     "UV shaded across seams: what the asset alone gives)")
      ->default_str(to_string(d.uv_seams));
}

namespace {

// An encoded glTF image's decoder, as the extension OpenImageIO picks it by.
std::string format_of(const GltfImage& image) {
  if (image.mime_type == "image/png") return ".png";
  if (image.mime_type == "image/jpeg") return ".jpg";
  const auto& b = image.bytes;
  if (b.size() >= 4 && b[0] == 0x89 && b[1] == 'P') return ".png";
  if (b.size() >= 2 && b[0] == 0xFF && b[1] == 0xD8) return ".jpg";
  if (b.size() >= 4 && b[0] == 'D' && b[1] == 'D' && b[2] == 'S') return ".dds";
  if (b.size() >= 4 && b[0] == 0x76 && b[1] == 0x2F && b[2] == 0x31 && b[3] == 0x01) return ".exr";
  return ".png";
}

}  // namespace

std::optional<Displacement> displacement_option(const DisplacementSettings& d, const SubdModel& model) {
  const GltfMaterialMaps& material = model.material;
  const bool none = d.map == "none";
  const bool from_material = d.map.empty() && material.displacement.has_value();
  if ((d.map.empty() && !from_material) || none) {
    DisplacementSettings companions = d;
    companions.map.clear();
    if (!(companions == DisplacementSettings{}))  // a companion option given without the map
      throw UsageError("--displacement-* and --normal-map need --displacement MAP");
    return std::nullopt;
  }
  DisplacementOptions o;
  o.scale = d.scale.value_or(from_material ? material.displacement_factor : 1.0f);
  o.bias = d.bias.value_or(from_material ? material.displacement_offset : 0.0f);
  if (!std::isfinite(o.scale) || !std::isfinite(o.bias)) throw UsageError("--displacement-scale/-bias: not finite");
  o.map = d.map;
  o.channel = d.channel;
  if (from_material) {
    const GltfImage& image = *material.displacement;
    o.map = image.path;
    o.map_bytes = image.bytes;
    o.map_format = format_of(image);
    // The proposal reads the red channel.
    if (o.channel.empty()) o.channel = "R";
    log_info("displacement: " + image.path + " (the material's displacementGeometryTexture, scale " +
             float_text(o.scale) + ", offset " + float_text(o.bias) + ")");
  }
  o.space = d.space;
  o.pad_charts = o.own_chart_shading = o.seam_blending = d.uv_seams == UvSeams::blend;
  o.normal_map = d.normal_map;
  if (d.normal_map == "auto" && material.normal) {
    o.normal_map = material.normal->path;
    o.normal_map_bytes = material.normal->bytes;
    o.normal_map_format = format_of(*material.normal);
  }
  try {
    Displacement displacement = make_displacement(model, o);
    if (displacement.spanning_faces != 0)
      log_info("warning: " + o.map + ": " + std::to_string(displacement.spanning_faces) + " of " +
               std::to_string(model.cage.face_count()) +
               " faces have UVs in more than one UDIM tile; each is sampled from the tile of its UV centre");
    return displacement;
  } catch (const DisplacementMapError& e) {
    throw InputError(e.what());
  } catch (const CageError& e) {
    throw InputError(e.what());
  }
}

UpAxisAdvice up_axis_advice(const std::string& path, const Cage& cage) {
  if (is_gltf_path(path)) return {1, "glTF is +y up"};
  const UpAxisHint h = suggest_up_axis(cage.positions);
  const auto base = [&](int a) {
    return std::to_string(h.base_vertices[a]) + " cage vertices on the lowest " + "xyz"[a] + " plane";
  };
  return {h.axis, base(h.axis) + ", " + base(3 - h.axis)};
}

}  // namespace tessera::scene
