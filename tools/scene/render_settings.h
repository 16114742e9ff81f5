// The settings of one render, typed, and the one reader of their text.
//
// Contract
// - RenderSettings holds everything `tessera render` takes but its outputs, each setting in its own
//   type (a scheme is a Scheme, a camera position a vector), so a render, a scene file, the viewer and
//   Python hand each other values, never text to parse again.
// - Text becomes a setting only through the readers below (scheme_option ... resolution_option): the
//   command line's options, a viewer request (which goes through the same options) and the scene file
//   reader call them, so a value means the same thing wherever it is written. Each throws UsageError
//   naming the option and the value; the scene file reader names its file and field instead.
// - Settings become text through to_string and the *_text functions: the names and shortest
//   round-trip numbers that the readers take back to the same value, bit for bit.
// - Values each reader accepts but a render may still refuse (a NaN factor, a camera at its target,
//   a field of view of 0) are checked where they are used, as they depend on the model.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "shaders_cpp/lod/edge_lod.h"
#include "shaders_cpp/lod/frustum_cull.h"
#include "shaders_cpp/render/displaced_model.h"
#include "shaders_cpp/subdiv/subd_patches.h"
#include "tessellator/tessellator.h"

namespace tessera::scene {

// The debug views of `tessera render --view` (render_views.h draws them).
enum class ViewKind : std::uint8_t {
  shaded,
  wireframe,
  wire_on_shaded,
  factors,
  density,
  patch_type,
  combination,
  patch_id,
  normals,
  uv,
  displacement,
  cage,
  cracks,
  culled,
};
// --view factors: the factors as the hull shader gave them, or as the tessellator processed them.
enum class FactorKind : std::uint8_t { raw, processed };
// --uv-seams: blend (each patch shaded from its own chart, normals blended at seams, maps padded) or
// raw (the maps as stored).
enum class UvSeams : std::uint8_t { blend, raw };

// The view camera: --resolution, --camera-position, --camera-target, --camera-up, --fov.
struct CameraSettings {
  int width = 1920, height = 1080;
  std::optional<glm::vec3> eye, target;  // not given: framing the model, its centre
  std::optional<glm::vec3> up;           // a non-zero direction as given; not given: +y
  float fov = 35.0f;                     // degrees, vertical
  friend bool operator==(const CameraSettings&, const CameraSettings&) = default;
};

// Level of detail and patch culling: --lod, --edge-pixels, --lod-distance, --dicing-camera-position,
// --cull.
struct LodCullSettings {
  LodMode mode = LodMode::uniform;
  std::optional<glm::vec3> dicing_eye;  // not given: the view camera dices
  PatchCullMode cull = PatchCullMode::all;
  float edge_pixels = 8.0f, lod_distance = 0.0f;
  friend bool operator==(const LodCullSettings&, const LodCullSettings&) = default;
};

// --displacement MAP and its companions.
struct DisplacementSettings {
  std::string map;      // a path, "none", or empty (a glTF material's map, if any)
  std::string channel;  // a channel name, letter or list; empty: the map's own choice
  DisplacementSpace space = DisplacementSpace::tangent;
  std::string normal_map = "auto";  // auto, derived, or a path
  // Not given: 1 and 0, or a glTF material's displacementGeometryFactor and Offset.
  std::optional<float> scale, bias;
  UvSeams uv_seams = UvSeams::blend;
  friend bool operator==(const DisplacementSettings&, const DisplacementSettings&) = default;
};

// Which part of a glTF asset, and when: --scene-index, --mesh, --animation, --time.
struct AssetSettings {
  int scene_index = -1;  // -1: the file's default scene
  std::string mesh, animation;
  double time = 0.0;  // seconds
  friend bool operator==(const AssetSettings&, const AssetSettings&) = default;
};

// Where a scene's cage came from, when a tool exported it (the Blender add-on: the .blend, the object
// and the frame it was posed at). Recorded and written back; it changes no pixel.
struct SourceSettings {
  std::string application, file, object;
  std::optional<double> frame;
  bool empty() const { return application.empty() && file.empty() && object.empty() && !frame; }
  friend bool operator==(const SourceSettings&, const SourceSettings&) = default;
};

// What a scene describes: everything `tessera render` takes but its outputs.
struct RenderSettings {
  std::string cage;
  Scheme scheme = Scheme::gregory;
  int isolation = kDefaultIsolation;  // --scheme adaptive's level (limit_surface.h)
  ts::Partitioning partitioning = ts::Partitioning::integer;
  float factor = 8.0f, vary = 0.0f;
  std::string factors_file;  // --factors-per-edge
  ViewKind view = ViewKind::shaded;
  FactorKind factor_kind = FactorKind::raw;
  CameraSettings camera;
  LodCullSettings lod;
  DisplacementSettings displacement;
  AssetSettings asset;
  int threads = 0;
  int msaa = 1;            // samples per pixel: 1, 2, 4, 8 or 16 (D3D11's standard patterns)
  bool two_sided = false;  // CullMode NONE, the inner side shaded with its normal turned to the viewer
  SourceSettings source;
  friend bool operator==(const RenderSettings&, const RenderSettings&) = default;
};

// The readers of settings text. `what` names the option in the error (the scene file reader and
// other commands pass their own).
Scheme scheme_option(std::string_view text, const std::string& what = "--scheme");
// 1..kMaxIsolation.
int isolation_option(std::string_view text, const std::string& what = "--isolation");
ts::Partitioning partitioning_option(std::string_view text, const std::string& what = "--partitioning");
ViewKind view_kind_option(std::string_view text);
FactorKind factor_kind_option(std::string_view text);
LodMode lod_mode_option(std::string_view text);
PatchCullMode cull_option(std::string_view text);
DisplacementSpace displacement_space_option(std::string_view text);
UvSeams uv_seams_option(std::string_view text);
// "x,y,z", each finite.
glm::vec3 vec3_option(std::string_view text, const std::string& what);
// Whether `v` gives a direction (its length is not 0, nor too small or large to normalise).
bool has_direction(glm::vec3 v);
// vec3_option, and a direction (has_direction).
glm::vec3 direction_option(std::string_view text, const std::string& what);
// "WIDTHxHEIGHT", each side 1..kMaxRenderTargetSize (framebuffer.h).
std::pair<int, int> resolution_option(std::string_view text);
// `msaa` itself when it is a supported sample count (1, 2, 4, 8 or 16); else UsageError naming --msaa.
int msaa_option(int msaa);

// The names each reader takes, in order, for help and errors ("shaded, wireframe, ...").
std::string view_names();
const char* to_string(ViewKind v);
const char* to_string(FactorKind k);
const char* to_string(UvSeams u);
const char* to_string(DisplacementSpace s);
// "x,y,z" and "WxH" in shortest round-trip text: vec3_option and resolution_option read them back.
std::string vec3_text(glm::vec3 v);
std::string resolution_text(int width, int height);

// Registers option `name` on `cmd`: its text, when given, goes through `read` into `target` (CLI11
// runs the reader once parsing is done, so its UsageError leaves `parse` as it is).
template <class T, class Read>
CLI::Option* add_setting_option(CLI::App& cmd, const std::string& name, T& target, Read read, const std::string& help) {
  return cmd.add_option_function<std::string>(
      name, [&target, read](const std::string& text) { target = read(text); }, help);
}

}  // namespace tessera::scene
