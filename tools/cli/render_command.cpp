// `tessera render CAGE.obj --scheme S -o out.png`: the cage's surface through the whole pipeline, with
// an automatic camera that frames it (or one given), in one of the views of render_views.h: shaded,
// wireframes, and the debug views of factors, density, patch types, UVs, the cage, cracks and culling.
// --stats writes the pipeline statistics and a row per patch (render_stats.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <regex>
#include <iostream>

#include "tools/cli/commands.h"
#include "tools/cli/progress.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"
#include "tools/scene/render_stats.h"
#include "tools/scene/render_views.h"
#include "tools/scene/scene_file.h"
#include "tools/scene/scene_render.h"
#include "tools/scene/view_options.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct RenderOptions {
  RenderSettings s;  // what a scene file holds
  std::string output, stats, scene, print_scene;
  bool scene_schema = false, json = false;
  int frames = 1, orbit = 0;
  double fps = 24.0;
};

// Image `i`'s path: the pattern's one printf integer field (%d, %4d, %04d) replaced by i.
std::string frame_path(const std::string& pattern, int i, const std::string& option) {
  const std::regex field(R"(%(0?)([1-9]?)d)");
  std::smatch m;
  if (!std::regex_search(pattern, m, field) || std::count(pattern.begin(), pattern.end(), '%') != 1)
    throw UsageError(option + ": -o " + pattern + " needs one frame-number field such as %04d (frame_%04d.png)");
  std::string number = std::to_string(i);
  const std::size_t width = m[2].length() ? std::size_t(std::stoi(m[2])) : 0;
  if (number.size() < width) number.insert(0, width - number.size(), m[1].length() ? '0' : ' ');
  return m.prefix().str() + number + m.suffix().str();
}

// Renders a sequence from one load of the asset: --frames N of an animation (frame i at time + i / fps)
// or --orbit N views around the model (view i turned by 2 pi i / N about the up axis). Every image is
// written beside its final name first and renamed at the end: all images or none.
int render_sequence(const RenderOptions& o, bool orbit) {
  const int count = orbit ? o.orbit : o.frames;
  const std::string option = orbit ? "--orbit" : "--frames";
  if (count < 1 || count > 100000) throw UsageError(option + ": " + std::to_string(count) + " is not in 1..100000");
  if (!(std::isfinite(o.fps) && o.fps > 0.0 && o.fps <= 10000.0))
    throw UsageError("--fps: " + std::to_string(o.fps) + " is not in (0, 10000]");
  if (!o.stats.empty()) throw UsageError("--stats describes one image; drop " + option + " or --stats");
  std::vector<std::string> paths;
  for (int i = 0; i < count; ++i) {
    paths.push_back(frame_path(o.output, i, option));
    if (i > 0 && paths[std::size_t(i)] == paths[0]) throw UsageError(option + ": -o " + o.output + " names one file");
  }
  // Each image's path is checked (no collision with an input, its directory exists).
  for (const std::string& p : paths)
    check_output_paths({{"-o", p}},
                       {o.s.cage, o.s.factors_file, o.s.displacement.map, o.s.displacement.normal_map, o.scene});
  StepProgress preparing("preparing " + o.s.cage);
  const std::unique_ptr<PreparedScene> scene = prepare_scene(o.s, preparing.hook());
  preparing.finish();
  if (!orbit && !scene->model.rig)
    throw UsageError("--frames: " + o.s.cage + " is not animated (no skin, morph target or animation)");
  const ViewSetup base = orbit ? orbit_base(scene->settings.camera, scene->model, scene->view, count) : scene->view;
  if (orbit && !o.s.camera.eye) view_scene(*scene, base);
  Device device(device_options(o.s.threads));
  std::vector<std::string> partial;
  auto remove_partial = [&] {
    for (const std::string& p : partial) {
      std::error_code ignored;
      std::filesystem::remove(p, ignored);
    }
  };
  Json summaries = Json::array();
  Progress progress(orbit ? "orbit" : "frames", "images", std::uint64_t(count));
  try {
    for (int i = 0; i < count; ++i) {
      const double time = orbit ? o.s.asset.time : o.s.asset.time + double(i) / o.fps;
      // Image 0 is the scene prepare_scene made: the settings' pose (frame 0 is at their time) and
      // view (orbit view 0 is the base view itself).
      if (i > 0) {
        if (orbit)
          view_scene(*scene, orbit_view(scene->settings.camera, scene->model, base, i, count));
        else
          pose_scene(*scene, time);
      }
      const SceneImage image = render_scene(device, *scene, false);
      const std::filesystem::path final_path(paths[std::size_t(i)]);
      partial.push_back((final_path.parent_path() / (".tessera-partial-" + final_path.filename().string())).string());
      write_scene_image(image, {partial.back()});
      const DrawReport& total = image.out.result.report;
      if (o.json) {
        Json j = scene_summary(paths[std::size_t(i)], *scene, image);
        j["time"] = time;
        summaries.push_back(std::move(j));
      } else {
        std::cout << paths[std::size_t(i)] << ": ";
        if (orbit) std::cout << "view " << i + 1 << "/" << count << ", ";
        std::cout << "t " << float_text(float(time)) << " s, " << total.statistics.CInvocations << " triangles, "
                  << total.statistics.PSInvocations << " pixels shaded, VS "
                  << float_text(float(total.times.ia_vs * 1e3)) << " ms, DS " << float_text(float(total.times.ds * 1e3))
                  << " ms\n";
      }
      progress.advance(1);
    }
    for (std::size_t i = 0; i < paths.size(); ++i) std::filesystem::rename(partial[i], paths[i]);
  } catch (...) {
    remove_partial();
    throw;
  }
  progress.finish();
  if (o.json) std::cout << json_text(Json{{"images", summaries}}) << "\n";
  return kExitOk;
}

// The options a scene file sets: given with --scene they would be ambiguous, so they are refused.
constexpr const char* kSceneOptions[] = {"--scheme",
                                         "--factor",
                                         "--vary-factors",
                                         "--factors-per-edge",
                                         "--partitioning",
                                         "--resolution",
                                         "--camera-position",
                                         "--camera-target",
                                         "--fov",
                                         "--camera-up",
                                         "--msaa",
                                         "--lod",
                                         "--edge-pixels",
                                         "--lod-distance",
                                         "--dicing-camera-position",
                                         "--cull",
                                         "--view",
                                         "--factor-kind",
                                         "--displacement",
                                         "--displacement-channel",
                                         "--displacement-scale",
                                         "--displacement-bias",
                                         "--displacement-space",
                                         "--normal-map",
                                         "--time",
                                         "--animation",
                                         "--mesh",
                                         "--scene-index"};

// The settings: the command line's, or the scene file's (with --threads still the command line's).
RenderSettings settings_of(const RenderOptions& o, const CLI::App& cmd) {
  if (o.scene.empty()) {
    if (o.s.cage.empty()) throw UsageError("give a cage, or --scene FILE");
    return o.s;
  }
  for (const char* name : kSceneOptions)
    if (cmd.count(name) > 0)
      throw UsageError(std::string(name) + " with --scene: the scene sets it (edit the scene, or drop --scene)");
  if (!o.s.cage.empty()) throw UsageError("a cage and --scene: the scene names its asset");
  RenderSettings s = read_scene(o.scene);
  if (cmd.count("--threads") > 0) s.threads = o.s.threads;
  return s;
}

int run_render(const RenderOptions& given, const CLI::App& cmd) {
  if (given.scene_schema) {
    std::cout << kSceneSchema;
    return kExitOk;
  }
  RenderOptions o = given;
  o.s = settings_of(given, cmd);
  if (!o.print_scene.empty()) {
    // The camera as resolved: where the command line leaves it to the framing, the scene gets the
    // framing's position, target and up, so it does not change when the framing heuristic does (the
    // floats are written to round-trip, so the scene renders the same bytes).
    if (!o.s.camera.eye || !o.s.camera.target || !o.s.camera.up) {
      const std::unique_ptr<PreparedScene> framed = prepare_scene(o.s);
      if (!o.s.camera.eye) o.s.camera.eye = framed->view.camera.eye;
      if (!o.s.camera.target) o.s.camera.target = framed->view.camera.target;
      if (!o.s.camera.up) o.s.camera.up = framed->view.camera.up;
    }
    // Paths relative to where the scene goes (absolute on stdout), so the file can move with them.
    if (o.print_scene == "-") {
      std::cout << scene_json(o.s, "").dump(2) << "\n";
    } else {
      check_output_paths({{"--print-scene", o.print_scene}},
                         {o.s.cage, o.s.factors_file, o.s.displacement.map, o.s.displacement.normal_map, o.scene});
      const std::string dir = std::filesystem::path(o.print_scene).parent_path().string();
      write_text_atomically(o.print_scene, scene_json(o.s, dir.empty() ? "." : dir).dump(2) + "\n");
      log_info("wrote " + o.print_scene);
    }
    return kExitOk;
  }
  if (o.output.empty()) throw UsageError("-o out.png is required");
  if (cmd.count("--orbit") > 0 && (cmd.count("--frames") > 0 || cmd.count("--fps") > 0))
    throw UsageError("--orbit and --frames: render a turntable or an animation, not both");
  if (cmd.count("--frames") > 0 || cmd.count("--fps") > 0 || cmd.count("--orbit") > 0)
    return render_sequence(o, cmd.count("--orbit") > 0);
  check_output_paths({{"-o", o.output}, {"--stats", o.stats}},
                     {o.s.cage, o.s.factors_file, o.s.displacement.map, o.s.displacement.normal_map, o.scene});
  const auto load_start = std::chrono::steady_clock::now();
  StepProgress preparing("preparing " + o.s.cage);
  const std::unique_ptr<PreparedScene> scene = prepare_scene(o.s, preparing.hook());
  preparing.finish();
  log_debug(describe_scene(*scene) + ", prepared in " +
            float_text(float(std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count())) +
            " s");
  Progress progress("render", "patches", 0);
  Device device(device_options(o.s.threads));
  device.set_progress([&](std::size_t done, std::size_t total) { progress.update(done, total); });
  const SceneImage image = render_scene(device, *scene, !o.stats.empty());
  progress.finish();
  log_debug(describe_times(image.out.result.report));
  const ViewOutput& out = image.out;
  const DrawReport& total = out.result.report;
  write_scene_image(image, {o.output});
  // Back faces are culled, so an open surface seen from behind draws little or nothing: say so when
  // most of the patches in view were proven to face away (a closed surface shows about half), or when
  // triangles in view lit no pixel at all.
  const std::uint64_t in_view =
      total.statistics.HSInvocations - std::min(total.statistics.HSInvocations, total.patches_culled);
  const bool mostly_away = in_view > 0 && total.patches_back_culled * 4 > in_view * 3;
  const bool nothing_lit = total.statistics.CPrimitives >= 64 && total.statistics.PSInvocations == 0;
  if (!scene->settings.two_sided && (mostly_away || nothing_lit))
    log_info("warning: the surface in view faces away from the camera (" + std::to_string(total.patches_back_culled) +
             " of " + std::to_string(in_view) + " patches proven to, " +
             std::to_string(total.statistics.PSInvocations) +
             " pixels shaded), and back faces are culled: an open surface seen from behind? Try the other side "
             "(--camera-position), or draw both sides (--two-sided)");
  const ViewKind kind = scene->settings.view;
  const Scheme scheme = scene->settings.scheme;
  const ViewSetup& view = scene->view;
  if (!o.stats.empty()) {
    // Counts only: the same bytes for the same input on any thread count. Times and memory, which
    // are measurements, are in the --json summary.
    Json s = {{"statistics", to_json(total.statistics)}, {"warnings", scene->model.cage.warnings}};
    add_patch_statistics(s, device, scene->inputs(), *image.tables, scene->lod);
    if (Json a = adaptive_patches_json(scene->model); !a.is_null()) s["adaptive"] = a;
    if (kind == ViewKind::cracks)
      s["cracks"] = {{"crack_edges", out.crack_edges},
                     {"border_edges", out.border_edges},
                     {"nonmanifold_edges", out.nonmanifold_edges}};
    write_text_atomically(o.stats, json_text(s) + "\n");
  }
  if (o.json) {
    Json j = scene_summary(o.output, *scene, image);
    j["peak_rss_bytes"] = peak_rss_bytes();
    if (!o.stats.empty()) j["stats"] = o.stats;
    std::cout << json_text(j) << "\n";
    return kExitOk;
  }
  std::cout << o.output << ": " << view.width << "x" << view.height << ", scheme " << to_string(scheme) << ", view "
            << to_string(kind) << ", " << total.statistics.CInvocations << " triangles, " << total.patches_culled
            << " patches culled, " << total.patches_back_culled << " facing away, " << total.statistics.PSInvocations
            << " pixels shaded";
  if (kind == ViewKind::cracks)
    std::cout << ", " << out.crack_edges << " crack edges, " << out.nonmanifold_edges << " non-manifold, "
              << out.border_edges << " border edges";
  std::cout << "\n";
  return kExitOk;
}

}  // namespace

Runner add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "render a cage's subdivision surface to an image");
  cmd->add_option("cage", o->s.cage, "the cage: OBJ (OpenSubdiv tags allowed) or glTF (.gltf, .glb); or --scene");
  cmd->add_option("-o,--output", o->output, "output image (PNG or EXR)");
  add_settings_options(*cmd, o->s, PatchCullMode::all);
  cmd->add_option("--frames", o->frames,
                  "render N frames of the animation from --time, 1/fps apart, to -o frame_%04d.png")
      ->capture_default_str();
  cmd->add_option("--fps", o->fps, "frames per second of --frames")->capture_default_str();
  cmd->add_option("--orbit", o->orbit,
                  "render N views around the model (a turntable about the up axis, from the camera position or "
                  "the framing one) to -o view_%02d.png, loading the asset once");
  cmd->add_option("--scene", o->scene,
                  "render the scene file FILE (JSON: asset, scheme, partitioning, factor, lod, cull, displacement, "
                  "camera, resolution, view, time, threads; relative paths from the file; schema: --scene-schema)");
  cmd->add_option("--print-scene", o->print_scene,
                  "write this command line's scene to FILE (paths relative to it) or to stdout (-, absolute "
                  "paths) and render nothing");
  cmd->add_flag("--scene-schema", o->scene_schema, "print the scene files' JSON Schema and exit");
  cmd->add_option("--stats", o->stats,
                  "write D3D11 pipeline statistics, a row per patch and histograms as JSON (the same bytes for the "
                  "same input; times and memory are in --json)");
  cmd->add_flag("--json", o->json,
                "print a JSON summary on stdout: output, size, patches, triangles, pixels shaded, statistics, "
                "stage times, memory");
  return [o, cmd] { return run_render(*o, *cmd); };
}

}  // namespace tessera::cli
