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

namespace tessera::cli {

void add_scheme_options(CLI::App& cmd, std::string& scheme, float& factor, float& vary, std::string& factors_file,
                        std::string& partitioning, int& threads);
// The scheme named by option `what` (--scheme, or analyze's --memory-scheme); UsageError otherwise.
Scheme scheme_option(const std::string& name, const std::string& what = "--scheme");
ts::Partitioning partitioning_option(const std::string& name);
// --factor, --vary-factors and --factors-per-edge FILE (lines "v0 v1 factor", cage vertex indices from
// 0; edges not listed take --factor), read once; a line that is not an edge of `cage` is an InputError
// naming it. The ranges are lod/subd_factors.h's (base_factors); out of range is a UsageError.
SubdFactors factors_option(float factor, float vary, const std::string& file, const Cage& cage);
// Which part of a glTF asset, and when: --scene-index, --mesh, --animation, --time.
struct AssetCli {
  int scene_index = -1;  // -1: the file's default scene
  std::string mesh, animation;
  double time = 0.0;  // seconds
  friend bool operator==(const AssetCli&, const AssetCli&) = default;
};
// `with_time`: also --animation and --time (commands that draw a pose).
void add_asset_options(CLI::App& cmd, AssetCli& a, bool with_time = true);
// --scene-index and --mesh as a GltfSelection; UsageError for an OBJ path.
GltfSelection gltf_selection(const std::string& path, const AssetCli& a);
// load_subd_model with its CageError turned into the CLI's InputError (one line, exit 1), its
// warnings logged; an animated glTF asset is posed at `asset.time` (pose_model). Asset options on an
// OBJ cage, or a non-zero time on a static asset, are UsageErrors.
SubdModel load_model(const std::string& path, Scheme scheme, const AssetCli& asset = {});
// Poses an animated model at `time` seconds of the animation `asset.animation` names (default: the
// first); a time that is not finite or an unknown animation is a UsageError.
void pose_model(SubdModel& m, const AssetCli& asset, double time);
// An animated model posed at `asset.time` (pose_model); for a static one, a UsageError when `asset`
// asks for a time or an animation. (load_model does this once the model of `path` is loaded.)
void pose_or_refuse(SubdModel& m, const std::string& path, const AssetCli& asset);

// --displacement MAP and its companions (render, tessellate, bench frog).
struct DisplacementCli {
  std::string map, channel, space = "tangent", normal_map = "auto";
  // Not given: 1 and 0, or a glTF material's displacementGeometryFactor and Offset.
  std::optional<float> scale, bias;
  std::string uv_seams = "blend";  // or raw
  friend bool operator==(const DisplacementCli&, const DisplacementCli&) = default;
};
void add_displacement_options(CLI::App& cmd, DisplacementCli& d);
// Nothing without --displacement (or with `--displacement none`), unless the asset is a glTF whose
// material has a KHR_materials_displacement texture: then that map (its R channel, scaled by the
// factor and offset; the options given replace each), with its normalTexture as the normal map. The
// loaded displacement, its errors turned into InputError (one line naming the file) and bad option
// values into UsageError.
std::optional<Displacement> displacement_option(const DisplacementCli& d, const SubdModel& model);

}  // namespace tessera::cli
