// Options the subdivision commands (tessellate, render, accuracy) share: scheme, factors, partitioning.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "shaders_cpp/lod/subd_factors.h"
#include "shaders_cpp/render/displaced_model.h"
#include "shaders_cpp/render/subd_model.h"
#include "shaders_cpp/render/subd_shaders.h"
#include "shaders_cpp/subdiv/subd_patches.h"
#include "tessellator/tessellator.h"
#include "tools/scene/render_settings.h"

namespace tessera::scene {

// --scheme, --factor, --vary-factors, --factors-per-edge, --partitioning and --threads, read into `s`.
void add_scheme_options(CLI::App& cmd, RenderSettings& s);
// --factor, --vary-factors and --factors-per-edge FILE (lines "v0 v1 factor", cage vertex indices from
// 0; edges not listed take --factor), read once; a line that is not an edge of `cage` is an InputError
// naming it. The ranges are lod/subd_factors.h's (base_factors); out of range is a UsageError.
SubdFactors factors_option(float factor, float vary, const std::string& file, const Cage& cage);
// `with_time`: also --animation and --time (commands that draw a pose).
void add_asset_options(CLI::App& cmd, AssetSettings& a, bool with_time = true);
// --scene-index and --mesh as a GltfSelection; UsageError for an OBJ path.
GltfSelection gltf_selection(const std::string& path, const AssetSettings& a);
// load_subd_model with its CageError turned into the CLI's InputError (one line, exit 1), its
// warnings logged; an animated glTF asset is posed at `asset.time` (pose_model). Asset options on an
// OBJ cage, or a non-zero time on a static asset, are UsageErrors.
SubdModel load_model(const std::string& path, Scheme scheme, const AssetSettings& asset = {},
                     int isolation = kDefaultIsolation, const PrepareStep& step = {});
// Poses an animated model at `time` seconds of the animation `asset.animation` names (default: the
// first); a time that is not finite or an unknown animation is a UsageError.
void pose_model(SubdModel& m, const AssetSettings& asset, double time);
// An animated model posed at `asset.time` (pose_model); for a static one, a UsageError when `asset`
// asks for a time or an animation. (load_model does this once the model of `path` is loaded.)
void pose_or_refuse(SubdModel& m, const std::string& path, const AssetSettings& asset);

// --displacement MAP and its companions (render, tessellate, bench frog).
// The up axis the asset at `path` suggests (cage/up_axis_hint.h), in words for a log line or a report:
// "+y (glTF is +y up)", "+z (24 cage vertices on the lowest z plane, 6 on the lowest y)", ...; `axis`
// is 1 or 2.
struct UpAxisAdvice {
  int axis = 1;
  std::string reason;
};
UpAxisAdvice up_axis_advice(const std::string& path, const Cage& cage);

void add_displacement_options(CLI::App& cmd, DisplacementSettings& d);
// Nothing without --displacement (or with `--displacement none`), unless the asset is a glTF whose
// material has a KHR_materials_displacement texture: then that map (its R channel, scaled by the
// factor and offset; the options given replace each), with its normalTexture as the normal map. The
// loaded displacement, its errors turned into InputError (one line naming the file) and bad option
// values into UsageError.
std::optional<Displacement> displacement_option(const DisplacementSettings& d, const SubdModel& model);

}  // namespace tessera::scene
