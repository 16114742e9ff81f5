// Scene files: one render fully described in JSON (docs/scene.schema.json, printed by `tessera render
// --scene-schema`), so an ad-hoc command line becomes a checked-in test.
//
// Contract
// - read_scene() returns the render's settings with every relative path resolved against the scene
//   file's directory, and throws InputError -- one line, the file and the field -- for anything the
//   schema refuses: not JSON (with line and column), a missing or unknown field, a wrong type, a value
//   outside its set. Values the schema allows but a render refuses (a factor of NaN, a camera at its
//   target) are the render's to refuse, as on the command line.
// - scene_json() is the inverse: read_scene(a file holding scene_json(s, dir)) gives `s` back, floats
//   bit for bit (shortest round-trip text); paths are written relative to `dir` (absolute when `dir`
//   is empty). Fields at their defaults are written too: a scene says everything it renders with.
#pragma once

#include <string>

#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"
#include "tools/scene/render_settings.h"
#include "tools/scene/view_options.h"

namespace tessera::scene {

// Registers every setting of `s` but the cage as `tessera render`'s options, bound to `s`: scheme and
// factors, camera, LOD and culling (--cull defaulting to `cull_default`), --view, --msaa,
// --factor-kind, displacement and the glTF asset. render, view, bench view and the viewer's request
// parser all read settings through it, so an option means one thing in each.
void add_settings_options(CLI::App& cmd, RenderSettings& s, PatchCullMode cull_default);
// The settings that make a model and its factors, without those of a picture (--view, --msaa,
// --factor-kind): scheme and factors, camera (view LOD and culling read it), LOD and culling,
// displacement and the glTF asset. tessellate, bench frog and bench dolly read them; so does
// add_settings_options, which adds the picture's.
void add_model_settings_options(CLI::App& cmd, RenderSettings& s, PatchCullMode cull_default);

RenderSettings read_scene(const std::string& path);
// The settings of a scene object (a scene file's JSON): errors name `where`, relative paths are from
// `dir`. read_scene reads a file through it.
RenderSettings scene_settings(const Json& root, const std::string& where, const std::string& dir);
Json scene_json(const RenderSettings& s, const std::string& dir);

// docs/scene.schema.json, compiled in.
extern const char* const kSceneSchema;

}  // namespace tessera::scene
