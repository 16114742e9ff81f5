// Golden suites for `tessera check`: a suite file lists cases (a scene, how its image is compared, which
// geometry checks apply); the golden directory holds each case's blessed image (<name>.png) and digest
// (<name>.json: the geometry digest and the scene the golden was rendered from). run_case() renders one
// case and compares it; nothing here writes a golden.
//
// Suite file (JSON; relative paths from the suite file):
//   {"tessera_suite": 1, "name": "frog", "golden": "golden-dir",
//    "cases": [{"name": "screen-lod", "scene": "scenes/frog.json",
//               "compare": "exact" | {"fail": 0.004, "failpercent": 0.1, ...idiff's thresholds...},
//               "checks": ["watertight", "triangles", "factors_hash", "ds_hash"]}]}
// The geometry checks trace a change to its stage: `factors_hash` (the hull shader's factors, every
// patch's raw SV_TessFactor bits), `ds_hash` (the domain shader's output stream: positions and normals
// bits, in draw order), `triangles`, `watertight` (after welding on exact bits, no crack and no
// non-manifold edge; the surface's own border is not a crack: surface_weld.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tools/scene/json_output.h"
#include "tools/scene/scene_file.h"
#include "tools/verify/image_diff.h"

namespace tessera::scene {

struct SuiteCase {
  std::string name, scene;  // scene: resolved path
  bool exact = false;
  verify::DiffThresholds thresholds;
  std::vector<std::string> checks;
};

struct Suite {
  std::string path, name, golden_dir;  // golden_dir: resolved
  std::vector<SuiteCase> cases;
};

// InputError (one line: file and field) for a bad suite; case names are unique and file-name safe.
Suite read_suite(const std::string& path);

// The folder beside the suite file where a self-contained suite keeps the files its scenes name:
// `assets/`.
std::string suite_assets_dir(const Suite& suite);
// Case `c`'s scene settings. A file the scene names (asset, factors file, displacement and normal
// maps) that does not exist where the scene says is taken from the suite's assets folder by its file
// name, so a suite copied elsewhere with its assets runs; neither there: InputError naming both.
RenderSettings suite_scene(const Suite& suite, const SuiteCase& c);
// Makes the suite self-contained: copies every file its scenes name (a .gltf with the buffers and
// images it names) into suite_assets_dir and rewrites each scene file to name the copies, relative to
// the scene. One line per case saying what it did; InputError when a file is missing or a different
// file of the same name is already there.
std::vector<std::string> collect_suite_assets(const Suite& suite);

// What the geometry checks compare.
struct GeometryDigest {
  std::uint64_t triangles = 0, crack_edges = 0, border_edges = 0, nonmanifold_edges = 0;
  std::string factors_hash, ds_hash;  // 16 hex digits (FNV-1a 64)
  Json json() const;
};

enum class CaseStatus { pass, warning, fail, new_case, error };
const char* to_string(CaseStatus s);  // "pass", "warning", "fail", "new", "error"

// The fields of two scene JSON objects (scene_json) whose values differ, as dotted paths in the order
// of `now`, then those only `golden` has: [{"field", "golden", "new"}] (a missing side is null). Files
// (asset, maps, factors) are compared by file name: a copied or moved suite names them differently.
Json scene_differences(const Json& golden, const Json& now);

struct CaseResult {
  std::string name;
  CaseStatus status = CaseStatus::error;
  std::string message;       // why it is not a pass
  std::string new_image;     // relative to the report directory
  std::string golden_image;  // absolute
  std::string diff_image;    // relative to the report directory; empty when identical
  std::optional<verify::DiffReport> diff;
  Json checks = Json::object();  // per check: {"golden", "new", "pass"}
  GeometryDigest digest;
  std::string command;  // reproduces the render
  // The scene fields (dotted paths, "camera.position") whose values differ from the scene recorded with
  // the golden: [{"field", "golden", "new"}]; null when the golden records no scene.
  Json scene_changes = nullptr;
  Json scene;  // scene_json of the case's settings, paths relative to the golden directory
  // What the loader and the scheme left out (make_subd_model's warnings: creases drawn smooth or
  // capped, tags on no edge), one line each; in the report beside the case's verdict.
  std::vector<std::string> warnings;
  double seconds = 0;
  Json json() const;
};

// Renders the case into report_dir/new/<name>.png, compares with the golden (and draws
// report_dir/diff/<name>.png when they differ), runs its checks. Errors become status `error`.
// `threads` >= 0 overrides the scene's thread count (the bytes are the same for any count).
CaseResult run_case(const Suite& suite, const SuiteCase& c, const std::string& report_dir, int threads = -1);

// Writes the case's golden image, and its digest with the scene it was rendered from, from its new
// render (check --update).
void bless_case(const Suite& suite, const SuiteCase& c, const CaseResult& r, const std::string& report_dir);
// Adds the case's scene to a golden digest that has none, leaving the golden's image and values.
void record_golden_scene(const Suite& suite, const SuiteCase& c, const CaseResult& r);

}  // namespace tessera::scene
