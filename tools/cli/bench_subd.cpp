// `tessera bench frog`: the second benchmark scene, a Catmull-Clark cage (the monster frog by default)
// through the whole pipeline with one scheme, plus the stream-output throughput of the hull shader's
// control-point evaluation and of the domain shader; with --displacement, the displaced shaders.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>

#include "shaders_cpp/image_io/image_file.h"
#include "shaders_cpp/render/displaced_render.h"
#include "shaders_cpp/render/subd_render.h"
#include "tools/cli/bench_options.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"
#include "tools/scene/scene_render.h"
#include "tools/scene/view_options.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct BenchSubdOptions {
  RenderSettings s;  // s.cage empty: the monster frog shipped beside the binary (shared_data_file)
  std::string output;
  std::string trace;
  int frames = 5;
  BenchDeviceOptions device;
  bool json = false, compare_cull = false;
};

int run_bench_subd(const BenchSubdOptions& o) {
  if (o.frames < 1 || o.frames > 1000) throw UsageError("--frames: must be in 1..1000");
  DeviceOptions dopt = device_options(o.s.threads);
  o.device.apply(dopt);
  const std::string cage = cage_or_shipped_frog(o.s.cage);
  check_output_paths({{"-o", o.output}, {"--trace", o.trace}},
                     {cage, o.s.factors_file, o.s.displacement.map, o.s.displacement.normal_map});
  // The scene library's one route from settings to a model, its view and factors.
  const std::unique_ptr<PreparedScene> scene = prepare_bench_scene(o.s);
  const Scheme scheme = scene->settings.scheme;
  const ts::Partitioning partitioning = scene->settings.partitioning;
  const SubdModel& model = scene->model;
  const ViewSetup& view = scene->view;
  const int w = view.width, h = view.height;
  const SubdCamera& camera = view.camera;
  const std::optional<Displacement>& displacement = scene->displacement;
  Displacement* d = scene->displacement ? &*scene->displacement : nullptr;
  const SubdFactors& base_factors = scene->base_factors;
  const SubdFactors& factors = scene->factors;
  const PatchCull& cull = scene->cull;
  Device device(dopt);
  std::string error;
  auto fb = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error, o.s.msaa);
  if (!fb) throw UsageError("--resolution: " + error);  // prepare_scene has checked --msaa
  // A multisampled frame ends with its colour's resolve (as ResolveSubresource), into a target made
  // once (as a swap chain's).
  auto resolved = o.s.msaa > 1 ? Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error) : std::nullopt;

  using Clock = std::chrono::steady_clock;
  struct Timed {
    std::vector<double> frame_s;  // sorted
    DrawReport last;
  };
  // One frame: clear, draw, and a multisampled target's colour resolved.
  const auto render_frame = [&](const SubdFactors& f, const PatchCull& c) {
    device.clear(*fb, kBackgroundColor, 1.0f);
    DrawResult r = render_surface(device, model, d, f, c, partitioning, SubdView::shaded, camera, *fb);
    if (!r.ok()) throw InputError(cage + ": " + r.error);
    if (resolved) device.resolve(*fb, *resolved, ResolvedPlanes::color);  // also the tiles no draw entered
    return r;
  };
  const auto time_frames = [&](const SubdFactors& f, const PatchCull& c) {
    Timed t;
    for (int k = 0; k < o.frames + 1; ++k) {  // one warm-up frame
      const auto start = Clock::now();
      const DrawResult r = render_frame(f, c);
      if (k > 0) t.frame_s.push_back(std::chrono::duration<double>(Clock::now() - start).count());
      t.last = r.report;
    }
    std::sort(t.frame_s.begin(), t.frame_s.end());
    return t;
  };

  // --compare-cull: the same frames under each --cull mode, and whether the images are the same bytes.
  Json cull_modes = Json::array();
  if (o.compare_cull) {
    std::vector<std::uint8_t> reference;
    double none_median = 0.0;
    for (const PatchCullMode mode :
         {PatchCullMode::none, PatchCullMode::frustum, PatchCullMode::backface, PatchCullMode::all}) {
      LodCullSettings lod = o.s.lod;
      lod.cull = mode;
      SubdFactors f = base_factors;
      PatchCull c;
      apply_lod_options(lod, view, model, d, f, c);
      const Timed t = time_frames(f, c);
      const double median = t.frame_s[t.frame_s.size() / 2];
      std::vector<std::uint8_t> bytes = fb->color_bytes();
      if (reference.empty()) reference = bytes, none_median = median;
      cull_modes.push_back({{"cull", to_string(mode)},
                            {"median_s", median},
                            {"min_s", t.frame_s.front()},
                            {"saved_s", none_median - median},
                            {"patches_culled", t.last.patches_culled},
                            {"patches_back_culled", t.last.patches_back_culled},
                            {"triangles", t.last.statistics.CInvocations},
                            {"same_image", bytes == reference}});
      if (!o.json)
        std::cout << "--cull " << to_string(mode) << ": median " << median << " s (min " << t.frame_s.front() << "), "
                  << t.last.patches_culled << " patches outside the view, " << t.last.patches_back_culled
                  << " facing away, " << t.last.statistics.CInvocations << " triangles, "
                  << (bytes == reference ? "same image" : "IMAGE DIFFERS") << "\n";
    }
  }

  const Timed timed = time_frames(factors, cull);
  const std::vector<double>& frame_s = timed.frame_s;
  const DrawReport& last = timed.last;
  std::optional<TraceSummary> traced;
  if (!o.trace.empty())
    traced = trace_frame(
        device, [&] { render_frame(factors, cull); }, o.trace,
        "bench frog, " + std::to_string(device.threads()) + " threads");
  if (!o.output.empty())
    if (auto e = write_color(*fb, {o.output}); !e.empty()) throw InputError(e);
  // Front end alone: HS (stencils) and DS through stream output, nothing rasterized.
  const auto discard = [](const auto&, const PatchGroup&) {};
  const auto start = Clock::now();
  const DrawResult s = stream_surface(device, model, d, factors, cull, partitioning, discard);
  const double stream_s = std::chrono::duration<double>(Clock::now() - start).count();
  const double median = frame_s[frame_s.size() / 2];
  const auto& st = last.statistics;
  const double hs_rate = double(s.report.statistics.HSInvocations) / std::max(1e-9, s.report.times.hs);
  const double ds_rate = double(s.report.statistics.DSInvocations) / std::max(1e-9, s.report.times.ds);
  if (o.json) {
    Json j = {{"scene", "subd"},
              {"cage", cage},
              {"scheme", to_string(scheme)},
              {"displacement", displacement ? o.s.displacement.map : std::string()},
              {"factor", json_float(o.s.factor)},
              {"resolution", std::to_string(w) + "x" + std::to_string(h)},
              {"msaa", o.s.msaa},
              {"threads", device.threads()},
              {"frames", o.frames},
              {"lod", to_string(o.s.lod.mode)},
              {"cull", to_string(o.s.lod.cull)},
              {"patches_culled", last.patches_culled},
              {"patches_back_culled", last.patches_back_culled},
              {"triangles", st.CInvocations},
              {"median_s", median},
              {"min_s", frame_s.front()},
              {"triangles_per_s", double(st.CInvocations) / median},
              {"stream_s", stream_s},
              {"hs_patches_per_thread_s", hs_rate},
              {"ds_points_per_thread_s", ds_rate},
              {"adaptive", adaptive_patches_json(model)},
              {"times", to_json(last.times)}};
    if (o.compare_cull) j["cull_modes"] = cull_modes;
    if (traced) j["trace"] = to_json(*traced);
    std::cout << json_text(j) << "\n";
  } else {
    char line[400];
    std::snprintf(
        line, sizeof line,
        "%s, %s%s, factor %g, %dx%d, %d threads: median %.4f s (min %.4f), %llu triangles, %.1f M triangles/s\n"
        "front end alone (stream output): %.4f s; HS %.2f M patches/thread-s, DS %.1f M points/thread-s\n",
        cage.c_str(), to_string(scheme), displacement ? " displaced" : "", double(o.s.factor), w, h, device.threads(),
        median, frame_s.front(), (unsigned long long)st.CInvocations, double(st.CInvocations) / median / 1e6, stream_s,
        hs_rate / 1e6, ds_rate / 1e6);
    std::cout << line;
    if (traced) std::cout << summary_line(*traced) << "\n";
  }
  return kExitOk;
}

}  // namespace

Runner add_bench_subd_command(CLI::App& bench) {
  auto o = std::make_shared<BenchSubdOptions>();
  o->s.factor = 16.0f;
  CLI::App* cmd =
      bench.add_subcommand("frog", "A Catmull-Clark cage (default: the monster frog) through the whole pipeline");
  cmd->add_option("--cage", o->s.cage, "the cage (default: the monster frog shipped with tessera)");
  add_model_settings_options(*cmd, o->s, PatchCullMode::all);
  cmd->add_option("--frames", o->frames, "timed frames (after one warm-up)")->capture_default_str();
  add_bench_msaa_option(*cmd, o->s.msaa);
  o->device.add_options(*cmd);
  cmd->add_option("-o,--output", o->output, "write the last frame");
  add_bench_trace_option(*cmd, o->trace);
  cmd->add_flag("--json", o->json, "print results as JSON");
  cmd->add_flag("--compare-cull", o->compare_cull,
                "also time the frames under each --cull mode (none, frustum, backface, all): the time each "
                "saves, and whether the images are the same bytes (JSON: cull_modes)");
  cmd->fallthrough();
  return [o, cmd]() -> int { return cmd->parsed() ? run_bench_subd(*o) : -1; };
}

}  // namespace tessera::cli
