// One render's setup and image, shared by `tessera render` and `tessera check`: the settings
// (scene_file.h) turned into a loaded model, displacement, view and factors, then drawn in the
// settings' view, and written as `render -o` writes it (with the view's legend when it has one).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "shaders_cpp/image_io/image_file.h"
#include "tools/scene/json_output.h"
#include "tools/scene/render_views.h"
#include "tools/scene/scene_file.h"

namespace tessera::scene {

// The settings, loaded and checked (UsageError for bad values, InputError for unreadable files).
// Not movable: `inputs` refers to its members.
struct PreparedScene {
  RenderSettings settings;
  SubdModel model;
  std::optional<Displacement> displacement;
  ViewSetup view;
  SubdFactors base_factors;  // before LOD and culling (pose_scene starts again from them)
  SubdFactors factors;
  PatchCull cull;
  LodResult lod;
  // The up direction the asset's shape settles where the settings give none: +z for an OBJ cage whose
  // shape says so (up_axis_hint.h), else none (+y). configure_scene applies it.
  std::optional<glm::vec3> suggested_up;
  std::string suggested_up_reason;  // the shape's evidence, in words
  bool configured = false;  // configure_scene has succeeded once: base_factors hold settings' factors
  // The settings `view`, `factors` and `lod` were last computed from by configure_scene; pose_scene
  // and view_scene, which compute them from other inputs, clear it.
  std::optional<RenderSettings> derived_from;
  ViewInputs inputs() const;
};
// `step`: told as each step starts (subd_model.h's PrepareStep, then "framing and factors").
std::unique_ptr<PreparedScene> prepare_scene(const RenderSettings& s, const PrepareStep& step = {});
// prepare_scene for a benchmark: `s` with its cage, or the monster frog shipped with tessera when it
// names none (cage_or_shipped_frog); without a camera position, the benchmarks' fixed camera (frame_cage
// on the rest cage) instead of the surface framing, so times stay comparable across versions.
std::unique_ptr<PreparedScene> prepare_bench_scene(RenderSettings s);
// Applies `s` to a prepared scene whose asset, scheme and displacement it shares (the caller checks
// that: cage, asset selection, scheme and displacement settings equal the scene's): what `s` changes is
// redone as prepare_scene(s) does it, so the scene then draws the same bytes as a scene prepared from
// `s`. Only what changed is redone: the pose when the time or animation changes, the base factors when
// --factor, --vary-factors or the factors file change, the view, LOD and culling when any of those or
// the camera, LOD or cull settings change; a change of view kind, partitioning, MSAA or factor kind
// alone keeps them. On an error the scene is unchanged but for an animated model's pose.
void configure_scene(PreparedScene& scene, const RenderSettings& s);
// Poses an animated scene's model at `time` seconds (settings.asset.time becomes `time`) and
// recomputes what follows the pose (LOD factors, culling); the camera stays where prepare_scene put
// it (framing the rest pose).
void pose_scene(PreparedScene& scene, double time);
// Moves the scene's view camera to `view` and recomputes what follows the camera (LOD factors, culling);
// a dicing camera given in the settings stays where it is.
void view_scene(PreparedScene& scene, const ViewSetup& view);

struct SceneImage {
  std::optional<Framebuffer> fb;
  ViewOutput out;
  std::optional<PatchTables> tables;  // when the view or the caller needed them
};
// What was loaded, for -v: the asset's counts, scheme, maps, view and camera, on one line.
std::string describe_scene(const PreparedScene& scene);
// Where a draw's time went, for -v: wall time and each stage's thread-seconds, on one line.
std::string describe_times(const DrawReport& report);

// Draws the scene; `want_tables` keeps the patch tables (for --stats) even when the view does not use them.
// `reuse`: a target to draw into when it has the scene's size, samples and format (the viewer passes
// its last frame's, which saves allocating and faulting in a new one per frame); the view clears it
// first, so the image is the same bytes either way.
SceneImage render_scene(Device& device, const PreparedScene& scene, bool want_tables,
                        std::optional<Framebuffer> reuse = std::nullopt);
// To a file (`{path}`, atomically) or into memory (`{name, &bytes}`: `name`'s extension picks the
// format), the same bytes either way.
void write_scene_image(const SceneImage& image, const ImageTarget& target);
// The summary `render --json` prints of one image written to `path`: size, scheme, view, camera,
// patches, triangles, pixels shaded, statistics, stage times and memory.
Json scene_summary(const std::string& path, const PreparedScene& scene, const SceneImage& image);
// The adaptive scheme's patch table (isolation, patches by kind and by level, bytes): the "adaptive"
// field of render's --json and --stats and of bench's --json; null for the other schemes.
Json adaptive_patches_json(const SubdModel& model);

}  // namespace tessera::scene
