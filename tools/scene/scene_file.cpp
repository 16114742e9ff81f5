#include "tools/scene/scene_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "pipeline/framebuffer.h"
#include "pipeline/sample_pattern.h"
#include "tools/scene/common.h"
#include "tools/scene/render_views.h"

namespace tessera::scene {

void add_model_settings_options(CLI::App& cmd, RenderSettings& s, PatchCullMode cull_default) {
  add_scheme_options(cmd, s);
  add_camera_options(cmd, s.camera);
  add_lod_options(cmd, s.lod, cull_default);
  add_displacement_options(cmd, s.displacement);
  add_asset_options(cmd, s.asset);
}

void add_settings_options(CLI::App& cmd, RenderSettings& s, PatchCullMode cull_default) {
  add_model_settings_options(cmd, s, cull_default);
  add_setting_option(cmd, "--view", s.view, view_kind_option, view_names())->default_str(to_string(s.view));
  cmd.add_option("--msaa", s.msaa,
                 "samples per pixel: 1, 2, 4, 8 or 16 (D3D11's standard sample patterns; coverage and depth per "
                 "sample, shading per pixel, a box-filter resolve)")
      ->capture_default_str();
  cmd.add_flag("--two-sided", s.two_sided,
               "draw both sides of the surface (D3D11's CullMode NONE), the inner side shaded with its normal turned "
               "toward the viewer: for open sheets seen from behind");
  add_setting_option(cmd, "--factor-kind", s.factor_kind, factor_kind_option,
                     "--view factors: raw (as the hull shader gave them) or processed")
      ->default_str(to_string(s.factor_kind));
}
namespace {

namespace fs = std::filesystem;

// Reads one scene's fields, naming the file and the field in every error.
class SceneReader {
 public:
  // Errors name `where` (the scene file); relative paths are from `dir`.
  SceneReader(std::string where, fs::path dir) : path_(std::move(where)), dir_(std::move(dir)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw InputError(path_ + ": \"" + field + "\": " + message);
  }

  // Every key of `object` is one of `known`.
  void only(const Json& object, const std::string& where, std::initializer_list<const char*> known) const {
    if (!object.is_object()) fail(where, "expected an object");
    const std::set<std::string> names(known.begin(), known.end());
    for (const auto& [key, value] : object.items()) {
      (void)value;
      if (!names.count(key)) fail(where.empty() ? key : where + "." + key, "not a scene field (see --scene-schema)");
    }
  }
  float number(const Json& v, const std::string& field) const {
    if (!v.is_number()) fail(field, "expected a number, got " + v.dump());
    const double d = v.get<double>();
    return float(d);
  }
  std::string text(const Json& v, const std::string& field) const {
    if (!v.is_string()) fail(field, "expected a string, got " + v.dump());
    return v.get<std::string>();
  }
  // A name, read by the option reader `read` (render_settings.h): the names the command line takes.
  // Its refusal ("--scheme: 'x' is not one of ...") is given under the field's name instead.
  template <class Read>
  auto one_of(const Json& v, const std::string& field, Read read) const {
    const std::string s = text(v, field);
    try {
      return read(s);
    } catch (const UsageError& e) {
      const std::string what = e.what();
      const auto colon = what.find(": ");
      fail(field, colon == std::string::npos ? what : what.substr(colon + 2));
    }
  }
  std::string path(const Json& v, const std::string& field) const {
    const std::string s = text(v, field);
    if (s.empty()) fail(field, "an empty path");
    const fs::path p(s);
    return p.is_absolute() ? s : (dir_ / p).lexically_normal().string();
  }
  // [x, y, z], each finite.
  glm::vec3 vec3(const Json& v, const std::string& field) const {
    if (!v.is_array() || v.size() != 3) fail(field, "expected [x, y, z], got " + v.dump());
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
      out[i] = number(v[std::size_t(i)], field);
      if (!std::isfinite(out[i])) fail(field, "not finite: " + v.dump());
    }
    return out;
  }
  // [x, y, z], a direction: not of length 0.
  glm::vec3 direction(const Json& v, const std::string& field) const {
    const glm::vec3 d = vec3(v, field);
    if (!has_direction(d)) fail(field, v.dump() + " has no direction (give a non-zero x,y,z)");
    return d;
  }

 private:
  std::string path_;
  fs::path dir_;
};

std::string relative_to(const std::string& path, const std::string& dir) {
  const fs::path absolute = fs::absolute(path).lexically_normal();
  if (dir.empty()) return absolute.string();
  return absolute.lexically_relative(fs::absolute(dir).lexically_normal()).string();
}

}  // namespace

RenderSettings read_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path)) throw InputError(path + ": cannot read the scene file");
  std::stringstream text;
  text << in.rdbuf();
  Json root;
  try {
    root = Json::parse(text.str());
  } catch (const Json::exception& e) {  // parse_error, or out_of_range for a number past double
    // nlohmann's message carries the line and column.
    std::string what = e.what();
    const auto colon = what.find("] ");
    throw InputError(path + ": not a JSON scene (" + (colon == std::string::npos ? what : what.substr(colon + 2)) +
                     ")");
  }
  return scene_settings(root, path, fs::path(path).parent_path().string());
}

RenderSettings scene_settings(const Json& root, const std::string& where, const std::string& dir) {
  const SceneReader r(where, dir);
  r.only(root, "",
         {"tessera_scene",    "asset", "scheme",    "isolation",    "partitioning", "factor",     "vary_factors",
          "factors_per_edge", "lod",   "cull",      "displacement", "camera",       "resolution", "view",
          "factor_kind",      "time",  "animation", "mesh",         "scene_index",  "threads",    "msaa",
          "two_sided",        "source"});
  if (!root.contains("tessera_scene") || root["tessera_scene"] != 1)
    r.fail("tessera_scene", "must be 1 (this format's version)");
  if (!root.contains("asset")) r.fail("asset", "missing: the cage to render");

  RenderSettings s;
  s.cage = r.path(root["asset"], "asset");
  if (root.contains("scheme"))
    s.scheme = r.one_of(root["scheme"], "scheme", [](const std::string& t) { return scheme_option(t); });
  if (root.contains("isolation")) {
    const Json& v = root["isolation"];
    if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > kMaxIsolation)
      r.fail("isolation",
             "expected an isolation level from 1 to " + std::to_string(kMaxIsolation) + ", got " + v.dump());
    s.isolation = int(v.get<long long>());
  }
  if (root.contains("partitioning"))
    s.partitioning =
        r.one_of(root["partitioning"], "partitioning", [](const std::string& t) { return partitioning_option(t); });
  if (root.contains("factor")) s.factor = r.number(root["factor"], "factor");
  if (root.contains("vary_factors")) s.vary = r.number(root["vary_factors"], "vary_factors");
  if (root.contains("factors_per_edge")) s.factors_file = r.path(root["factors_per_edge"], "factors_per_edge");
  s.lod.cull = PatchCullMode::all;
  if (root.contains("cull")) s.lod.cull = r.one_of(root["cull"], "cull", cull_option);
  if (root.contains("lod")) {
    const Json& l = root["lod"];
    r.only(l, "lod", {"mode", "edge_pixels", "distance", "dicing_camera_position"});
    if (l.contains("mode")) s.lod.mode = r.one_of(l["mode"], "lod.mode", lod_mode_option);
    if (l.contains("edge_pixels")) s.lod.edge_pixels = r.number(l["edge_pixels"], "lod.edge_pixels");
    if (l.contains("distance")) s.lod.lod_distance = r.number(l["distance"], "lod.distance");
    if (l.contains("dicing_camera_position"))
      s.lod.dicing_eye = r.vec3(l["dicing_camera_position"], "lod.dicing_camera_position");
  }
  if (root.contains("displacement")) {
    const Json& d = root["displacement"];
    r.only(d, "displacement", {"map", "channel", "scale", "bias", "space", "normal_map", "uv_seams"});
    if (!d.contains("map")) r.fail("displacement.map", "missing: the displacement map");
    s.displacement.map = r.path(d["map"], "displacement.map");
    if (d.contains("channel")) s.displacement.channel = r.text(d["channel"], "displacement.channel");
    if (d.contains("scale")) s.displacement.scale = r.number(d["scale"], "displacement.scale");
    if (d.contains("bias")) s.displacement.bias = r.number(d["bias"], "displacement.bias");
    if (d.contains("space"))
      s.displacement.space = r.one_of(d["space"], "displacement.space", displacement_space_option);
    if (d.contains("uv_seams"))
      s.displacement.uv_seams = r.one_of(d["uv_seams"], "displacement.uv_seams", uv_seams_option);
    if (d.contains("normal_map")) {
      const std::string n = r.text(d["normal_map"], "displacement.normal_map");
      s.displacement.normal_map =
          n == "auto" || n == "derived" ? n : r.path(d["normal_map"], "displacement.normal_map");
    }
  }
  if (root.contains("camera")) {
    const Json& c = root["camera"];
    r.only(c, "camera", {"position", "target", "up", "fov"});
    if (c.contains("position")) s.camera.eye = r.vec3(c["position"], "camera.position");
    if (c.contains("target")) s.camera.target = r.vec3(c["target"], "camera.target");
    if (c.contains("up")) s.camera.up = r.direction(c["up"], "camera.up");
    if (c.contains("fov")) s.camera.fov = r.number(c["fov"], "camera.fov");
  }
  if (root.contains("resolution")) {
    const Json& v = root["resolution"];
    if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer())
      r.fail("resolution", "expected [width, height] in pixels, got " + v.dump());
    const long long w = v[0].get<long long>(), h = v[1].get<long long>();
    if (w < 1 || h < 1 || w > kMaxRenderTargetSize || h > kMaxRenderTargetSize)
      r.fail("resolution", v.dump() + " is outside 1.." + std::to_string(kMaxRenderTargetSize) + " per side");
    s.camera.width = int(w);
    s.camera.height = int(h);
  }
  if (root.contains("view")) s.view = r.one_of(root["view"], "view", view_kind_option);
  if (root.contains("factor_kind")) s.factor_kind = r.one_of(root["factor_kind"], "factor_kind", factor_kind_option);
  if (root.contains("time")) {
    if (!root["time"].is_number()) r.fail("time", "expected seconds, got " + root["time"].dump());
    s.asset.time = root["time"].get<double>();
  }
  if (root.contains("animation")) s.asset.animation = r.text(root["animation"], "animation");
  if (root.contains("mesh")) s.asset.mesh = r.text(root["mesh"], "mesh");
  if (root.contains("scene_index")) {
    const Json& v = root["scene_index"];
    if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > 1000000)
      r.fail("scene_index", "expected a glTF scene index >= 0, got " + v.dump());
    s.asset.scene_index = int(v.get<long long>());
  }
  if (root.contains("threads")) {
    const Json& t = root["threads"];
    if (!t.is_number_integer() || t.get<long long>() < 0 || t.get<long long>() > 4096)
      r.fail("threads", "expected a count in 0..4096 (0: all), got " + t.dump());
    s.threads = int(t.get<long long>());
  }
  if (root.contains("msaa")) {
    const Json& m = root["msaa"];
    if (!m.is_number_integer() || !valid_sample_count(int(std::clamp<long long>(m.get<long long>(), 0, 64))))
      r.fail("msaa", "expected 1, 2, 4, 8 or 16 samples per pixel, got " + m.dump());
    s.msaa = int(m.get<long long>());
  }
  if (root.contains("two_sided")) {
    if (!root["two_sided"].is_boolean()) r.fail("two_sided", "expected true or false, got " + root["two_sided"].dump());
    s.two_sided = root["two_sided"].get<bool>();
  }
  if (root.contains("source")) {
    const Json& src = root["source"];
    if (!src.is_object()) r.fail("source", "expected an object (application, file, object, frame), got " + src.dump());
    r.only(src, "source", {"application", "file", "object", "frame"});
    if (src.contains("application")) s.source.application = r.text(src["application"], "source.application");
    if (src.contains("file")) s.source.file = r.text(src["file"], "source.file");
    if (src.contains("object")) s.source.object = r.text(src["object"], "source.object");
    if (src.contains("frame")) {
      if (!src["frame"].is_number()) r.fail("source.frame", "expected a number, got " + src["frame"].dump());
      s.source.frame = src["frame"].get<double>();
    }
  }
  return s;
}

Json scene_json(const RenderSettings& s, const std::string& dir) {
  Json j = {{"tessera_scene", 1},
            {"asset", relative_to(s.cage, dir)},
            {"scheme", to_string(s.scheme)},
            {"partitioning", std::string(ts::to_string(s.partitioning))},
            {"factor", json_float(s.factor)},
            {"vary_factors", json_float(s.vary)}};
  if (s.scheme == Scheme::adaptive) j["isolation"] = s.isolation;
  if (!s.factors_file.empty()) j["factors_per_edge"] = relative_to(s.factors_file, dir);
  Json lod = {{"mode", to_string(s.lod.mode)},
              {"edge_pixels", json_float(s.lod.edge_pixels)},
              {"distance", json_float(s.lod.lod_distance)}};
  if (s.lod.dicing_eye) lod["dicing_camera_position"] = json_vec3(*s.lod.dicing_eye);
  j["lod"] = lod;
  j["cull"] = to_string(s.lod.cull);
  if (!s.displacement.map.empty()) {
    const DisplacementSettings& d = s.displacement;
    Json dj = {{"map", relative_to(d.map, dir)}};
    if (!d.channel.empty()) dj["channel"] = d.channel;
    if (d.scale) dj["scale"] = json_float(*d.scale);
    if (d.bias) dj["bias"] = json_float(*d.bias);
    dj["space"] = to_string(d.space);
    dj["normal_map"] =
        d.normal_map == "auto" || d.normal_map == "derived" ? d.normal_map : relative_to(d.normal_map, dir);
    dj["uv_seams"] = to_string(d.uv_seams);
    j["displacement"] = dj;
  }
  Json camera = Json::object();
  if (s.camera.eye) camera["position"] = json_vec3(*s.camera.eye);
  if (s.camera.target) camera["target"] = json_vec3(*s.camera.target);
  if (s.camera.up) camera["up"] = json_vec3(*s.camera.up);
  camera["fov"] = json_float(s.camera.fov);
  j["camera"] = camera;
  j["resolution"] = {s.camera.width, s.camera.height};
  j["view"] = to_string(s.view);
  j["factor_kind"] = to_string(s.factor_kind);
  j["time"] = s.asset.time;
  if (!s.asset.animation.empty()) j["animation"] = s.asset.animation;
  if (!s.asset.mesh.empty()) j["mesh"] = s.asset.mesh;
  if (s.asset.scene_index >= 0) j["scene_index"] = s.asset.scene_index;
  j["threads"] = s.threads;
  if (s.msaa != 1) j["msaa"] = s.msaa;
  if (s.two_sided) j["two_sided"] = true;
  if (!s.source.empty()) {
    Json src = Json::object();
    if (!s.source.application.empty()) src["application"] = s.source.application;
    if (!s.source.file.empty()) src["file"] = s.source.file;
    if (!s.source.object.empty()) src["object"] = s.source.object;
    if (s.source.frame) src["frame"] = *s.source.frame;
    j["source"] = src;
  }
  return j;
}

}  // namespace tessera::scene
