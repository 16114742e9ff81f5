#include "tools/viewer/viewer_settings.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include "tools/scene/common.h"

namespace tessera::viewer {

using namespace scene;

namespace {

// The settings a request may set, with `tessera render`'s own options bound to `s`.
void add_settable_options(CLI::App& app, RenderSettings& s) {
  const PatchCullMode cull = s.lod.cull;  // the session's, not render's default
  add_settings_options(app, s, cull);
}

// Settings whose empty value means "not given" (the framing camera, +y up, the view camera dices).
bool clears_when_empty(const std::string& name) {
  return name == "camera-position" || name == "camera-target" || name == "camera-up" ||
         name == "dicing-camera-position";
}

std::optional<glm::vec3>& camera_vector(RenderSettings& s, const std::string& name) {
  if (name == "camera-position") return s.camera.eye;
  if (name == "camera-target") return s.camera.target;
  if (name == "camera-up") return s.camera.up;
  return s.lod.dicing_eye;
}

// `render`'s defaults: a default RenderSettings with the cull mode render registers.
RenderSettings render_defaults() {
  RenderSettings d;
  d.lod.cull = PatchCullMode::all;
  return d;
}

std::string optional_text(const std::optional<glm::vec3>& v) { return v ? vec3_text(*v) : std::string(); }

std::string double_text(double x) {
  // The shortest of %.15g..%.17g that reads back as the same double.
  char buffer[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (std::strtod(buffer, nullptr) == x) break;
  }
  return buffer;
}

std::string absolute(const std::string& path) {
  return path.empty() ? path : std::filesystem::absolute(path).lexically_normal().string();
}

}  // namespace

const std::vector<std::string>& settable_settings() {
  static const std::vector<std::string> names = {"scheme",
                                                 "isolation",
                                                 "partitioning",
                                                 "factor",
                                                 "vary-factors",
                                                 "resolution",
                                                 "camera-position",
                                                 "camera-target",
                                                 "camera-up",
                                                 "fov",
                                                 "lod",
                                                 "edge-pixels",
                                                 "lod-distance",
                                                 "dicing-camera-position",
                                                 "cull",
                                                 "view",
                                                 "msaa",
                                                 "factor-kind",
                                                 "displacement-scale",
                                                 "displacement-bias",
                                                 "uv-seams",
                                                 "time",
                                                 "animation"};
  return names;
}

bool is_request_parameter(const std::string& name) {
  return name == "format" || name == "x" || name == "y" || name == "client" || name == "seq";
}

RenderSettings settings_from_query(const RenderSettings& base, const QueryParams& query) {
  RenderSettings s = base;
  const auto& names = settable_settings();
  std::set<std::string> seen;
  std::vector<std::string> args;
  for (const auto& [name, value] : query) {
    if (!seen.insert(name).second) throw RequestError("'" + name + "' is given twice");
    if (is_request_parameter(name)) continue;
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      const std::string shown = name.size() > 40 ? name.substr(0, 40) + "..." : name;
      throw RequestError("'" + shown + "' is not a setting a request may change (see GET /api/info)");
    }
    if (value.empty()) {
      if (!clears_when_empty(name)) throw RequestError(name + ": an empty value");
      camera_vector(s, name).reset();
      continue;
    }
    args.push_back("--" + name + "=" + value);
  }
  CLI::App app;
  add_settable_options(app, s);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last to first
  try {
    app.parse(args);
  } catch (const CLI::ConversionError& e) {
    // CLI11 says "Could not convert: --factor = abc"; a request names the setting, not an option.
    const std::string text = one_line_message(e.what());
    if (const auto bad = unconverted_option(text))
      throw RequestError(bad->first + ": cannot read '" + bad->second + "' (see GET /api/info for the settings)");
    throw RequestError(text);
  } catch (const CLI::ParseError& e) {
    throw RequestError(one_line_message(e.what()));
  } catch (const UsageError& e) {  // a value the settings' readers refuse
    throw RequestError(e.what());
  }
  const long long w = s.camera.width, h = s.camera.height;
  if (w > kMaxViewerSide || h > kMaxViewerSide || w * h > kMaxViewerPixels)
    throw RequestError("resolution: " + resolution_text(s.camera.width, s.camera.height) +
                       " is more than the viewer draws (" + std::to_string(kMaxViewerSide) +
                       " pixels a side, 4096x4096 in all)");
  return s;
}

Json settings_json(const RenderSettings& s) {
  const DisplacementSettings& d = s.displacement;
  Json j = {{"scheme", to_string(s.scheme)},
            {"isolation", s.isolation},
            {"partitioning", std::string(ts::to_string(s.partitioning))},
            {"factor", json_float(s.factor)},
            {"vary-factors", json_float(s.vary)},
            {"resolution", resolution_text(s.camera.width, s.camera.height)},
            {"camera-position", optional_text(s.camera.eye)},
            {"camera-target", optional_text(s.camera.target)},
            {"camera-up", optional_text(s.camera.up)},
            {"fov", json_float(s.camera.fov)},
            {"lod", to_string(s.lod.mode)},
            {"edge-pixels", json_float(s.lod.edge_pixels)},
            {"lod-distance", json_float(s.lod.lod_distance)},
            {"dicing-camera-position", optional_text(s.lod.dicing_eye)},
            {"cull", to_string(s.lod.cull)},
            {"view", to_string(s.view)},
            {"msaa", s.msaa},
            {"factor-kind", to_string(s.factor_kind)},
            {"displacement-scale", d.scale ? Json(json_float(*d.scale)) : Json(nullptr)},
            {"displacement-bias", d.bias ? Json(json_float(*d.bias)) : Json(nullptr)},
            {"uv-seams", to_string(d.uv_seams)},
            {"time", s.asset.time},
            {"animation", s.asset.animation}};
  return j;
}

std::vector<std::string> render_arguments(const RenderSettings& s, const std::string& output) {
  const RenderSettings d = render_defaults();
  std::vector<std::string> w = {"render", absolute(s.cage)};
  const auto text = [&](const char* option, const std::string& value, const std::string& def) {
    if (value != def) w.insert(w.end(), {option, value});
  };
  // A typed setting, written by to_string when it differs from the default.
  const auto name = [&](const char* option, const auto& value, const auto& def) {
    if (value != def) w.insert(w.end(), {option, std::string(to_string(value))});
  };
  const auto vector = [&](const char* option, const std::optional<glm::vec3>& value) {
    if (value) w.insert(w.end(), {option, vec3_text(*value)});
  };
  const auto number = [&](const char* option, float value, float def) {
    if (value != def || std::signbit(value) != std::signbit(def)) w.insert(w.end(), {option, float_text(value)});
  };
  name("--scheme", s.scheme, d.scheme);
  text("--isolation", std::to_string(s.isolation), std::to_string(d.isolation));
  name("--partitioning", s.partitioning, d.partitioning);
  number("--factor", s.factor, d.factor);
  number("--vary-factors", s.vary, d.vary);
  text("--factors-per-edge", absolute(s.factors_file), "");
  name("--view", s.view, d.view);
  name("--factor-kind", s.factor_kind, d.factor_kind);
  text("--resolution", resolution_text(s.camera.width, s.camera.height),
       resolution_text(d.camera.width, d.camera.height));
  vector("--camera-position", s.camera.eye);
  vector("--camera-target", s.camera.target);
  vector("--camera-up", s.camera.up);
  number("--fov", s.camera.fov, d.camera.fov);
  name("--lod", s.lod.mode, d.lod.mode);
  number("--edge-pixels", s.lod.edge_pixels, d.lod.edge_pixels);
  number("--lod-distance", s.lod.lod_distance, d.lod.lod_distance);
  vector("--dicing-camera-position", s.lod.dicing_eye);
  name("--cull", s.lod.cull, d.lod.cull);
  if (s.msaa != d.msaa) w.insert(w.end(), {"--msaa", std::to_string(s.msaa)});
  if (s.two_sided) w.push_back("--two-sided");
  const DisplacementSettings& m = s.displacement;
  text("--displacement", m.map == "none" ? m.map : absolute(m.map), "");
  text("--displacement-channel", m.channel, "");
  name("--displacement-space", m.space, d.displacement.space);
  const bool normal_keyword = m.normal_map == "auto" || m.normal_map == "derived" || m.normal_map == "none";
  text("--normal-map", normal_keyword ? m.normal_map : absolute(m.normal_map), d.displacement.normal_map);
  if (m.scale) w.insert(w.end(), {"--displacement-scale", float_text(*m.scale)});
  if (m.bias) w.insert(w.end(), {"--displacement-bias", float_text(*m.bias)});
  name("--uv-seams", m.uv_seams, d.displacement.uv_seams);
  if (s.asset.scene_index != d.asset.scene_index)
    w.insert(w.end(), {"--scene-index", std::to_string(s.asset.scene_index)});
  text("--mesh", s.asset.mesh, "");
  text("--animation", s.asset.animation, "");
  if (s.asset.time != d.asset.time) w.insert(w.end(), {"--time", double_text(s.asset.time)});
  w.insert(w.end(), {"-o", output});
  return w;
}

std::string shell_words(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& word : words) {
    if (!line.empty()) line += ' ';
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) ||
             std::string_view("_-+=.,/:%@").find(c) != std::string_view::npos;
    });
    if (plain) {
      line += word;
      continue;
    }
    line += '\'';
    for (char c : word) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += '\'';
  }
  return line;
}

}  // namespace tessera::viewer
