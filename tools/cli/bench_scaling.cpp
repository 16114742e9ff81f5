// `tessera bench scaling`: one scene rendered with 1, 2, 4, ... threads up to all cores (or
// --max-threads), each count on its own device, median of --frames after one warm-up frame; a table of
// time, speed-up over one thread and parallel efficiency (speed-up / threads), so that a user can size a
// machine. The scene is the benchmark torus, the frog (any cage, scheme, LOD and displacement that
// `bench frog` takes), or a scene file, drawn as `tessera render` draws it. The CPU's name (from
// /proc/cpuinfo, where there is one) heads the table; it changes no result. The image is the same
// bytes for every thread count (device.h); this command checks it and fails if not.
//
// Where the time goes: `busy` is the draw's summed stage time (VS, HS, tessellator, DS, setup, raster,
// as each thread measured it) over threads x the draw's wall time; the rest is threads waiting. The
// stage times themselves grow with the thread count when the cores share something (caches, memory
// bandwidth, a lower all-core clock): --ceiling measures that limit apart from Tessera's pipeline, by
// running N independent one-thread devices at once (N frames rendered side by side, nothing shared
// but the scene) and reporting N x the one-thread frame over their median frame, the speed-up N
// threads could reach if the pipeline never waited.
#include <algorithm>
#include <chrono>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <thread>

#include "pipeline/device.h"
#include "shaders_cpp/render/displaced_render.h"
#include "shaders_cpp/render/subd_render.h"
#include "shaders_cpp/render/torus_scene.h"
#include "tools/cli/bench_options.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"
#include "tools/scene/scene_file.h"
#include "tools/scene/scene_render.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct ScalingOptions {
  std::string scene = "torus";  // torus, frog, or a scene file's path
  RenderSettings s;             // the torus's factor, resolution and --msaa; the frog's model settings
  int frames = 5;
  int max_threads = 0;  // 0: the hardware's
  bool ceiling = false;
  bool json = false;
};

// The options a scene reads besides --scene, --frames, --max-threads, --ceiling and --json: the torus
// reads these (it has its own cage, scheme and camera), the frog every model setting, a scene file none
// (it sets them all).
const char* const kTorusOptions[] = {"--factor", "--resolution", "--msaa"};
const char* const kScalingOptions[] = {"--scene", "--frames", "--max-threads", "--ceiling", "--json", "--help"};

// A setting given on the command line that `scene` does not read: UsageError naming it.
void check_scene_options(const CLI::App& cmd, const std::string& scene, bool scene_file) {
  for (const CLI::Option* opt : cmd.get_options()) {
    if (opt->count() == 0) continue;
    const std::string name = opt->get_name(false, true);
    const auto in = [&](const auto& names) {
      return std::find(std::begin(names), std::end(names), name) != std::end(names);
    };
    if (in(kScalingOptions)) continue;
    if (scene_file) throw UsageError(name + " with a scene file: the scene sets it (edit the scene)");
    if (scene == "torus" && !in(kTorusOptions))
      throw UsageError(name + ": the torus has its own cage, scheme and camera (--scene frog reads it)");
  }
}

std::string cpu_name() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown CPU";
}

// 1, 2, 4, ... below `most`, then `most`.
std::vector<int> thread_counts(int most) {
  std::vector<int> counts;
  for (int t = 1; t < most; t *= 2) counts.push_back(t);
  counts.push_back(most);
  return counts;
}

int run_bench_scaling(const ScalingOptions& o, const CLI::App& cmd) {
  const bool scene_file = o.scene != "torus" && o.scene != "frog";
  if (scene_file && !std::filesystem::is_regular_file(o.scene))
    throw UsageError("--scene: '" + o.scene + "' is not torus, frog or a scene file");
  check_scene_options(cmd, o.scene, scene_file);
  if (o.scene == "torus" && (!std::isfinite(o.s.factor) || o.s.factor < 1.0f || o.s.factor > 64.0f))
    throw UsageError("--factor: must be in 1..64 (the tessellator's range)");
  if (o.frames < 1 || o.frames > 1000) throw UsageError("--frames: must be in 1..1000");
  const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
  if (o.max_threads < 0 || o.max_threads > 4096) throw UsageError("--max-threads: must be in 0..4096 (0: all cores)");
  const int most = o.max_threads > 0 ? o.max_threads : hardware;

  // A run's targets: the one drawn into, and where a multisampled one is resolved (made once per run,
  // as a swap chain's; a scene file's frame is `tessera render`'s, which resolves into a new one).
  struct Targets {
    std::optional<Framebuffer> fb, resolved;
    const Framebuffer& image() const { return resolved ? *resolved : *fb; }
  };
  // One frame of the scene on a device: clear, draw, resolve; the draws' report. The torus and the
  // frog are one draw into the run's cleared target (`draw`); a scene file's frame is render_scene's.
  std::function<DrawReport(Device&, Targets&)> frame;
  std::function<DrawResult(Device&, Framebuffer&)> draw;
  std::optional<render::TorusScene> torus;
  std::unique_ptr<PreparedScene> subd;
  RenderSettings settings = o.s;
  if (o.scene == "torus") {
    settings.msaa = msaa_option(settings.msaa);
    const int w = settings.camera.width, h = settings.camera.height;
    log_info("building the torus scene");
    torus = render::make_torus_scene(w, h);
    draw = [&, d = render::make_torus_draw(*torus, settings.factor, ts::Partitioning::integer, w, h)](
               Device& device, Framebuffer& fb) { return device.draw(d, fb); };
  } else if (o.scene == "frog") {
    subd = prepare_bench_scene(settings);  // checks --msaa and the rest
    draw = [&](Device& device, Framebuffer& fb) {
      DrawResult r =
          render_surface(device, subd->model, subd->displacement ? &*subd->displacement : nullptr, subd->factors,
                         subd->cull, subd->settings.partitioning, SubdView::shaded, subd->view.camera, fb);
      if (!r.ok()) r.error = subd->settings.cage + ": " + r.error;
      return r;
    };
  } else {
    settings = read_scene(o.scene);
    subd = prepare_scene(settings);
    frame = [&](Device& device, Targets& t) {
      SceneImage image = render_scene(device, *subd, false, std::move(t.fb));
      t.fb = std::move(image.fb);
      return image.out.result.report;
    };
  }
  if (draw)
    frame = [&](Device& device, Targets& t) {
      device.clear(*t.fb, kBackgroundColor, 1.0f);
      const DrawResult r = draw(device, *t.fb);
      if (!r.ok()) throw InputError(r.error);
      if (t.resolved) device.resolve(*t.fb, *t.resolved, ResolvedPlanes::color);  // as ResolveSubresource
      return r.report;
    };
  const int w = subd ? subd->view.width : settings.camera.width, h = subd ? subd->view.height : settings.camera.height;
  const int msaa = subd ? subd->settings.msaa : settings.msaa;
  const float factor = subd ? subd->settings.factor : settings.factor;
  const auto make_targets = [&] {
    Targets t;
    if (scene_file) return t;  // render_scene makes them
    std::string error;
    t.fb = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error, msaa);
    if (!t.fb) throw UsageError("--resolution: " + error);
    if (msaa > 1) t.resolved = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error);
    return t;
  };

  struct Row {
    int threads;
    double median_s, min_s;
    double busy;             // summed stage time / (threads x draw wall time), the median frame's
    double independent = 0;  // --ceiling: the speed-up of `threads` independent one-thread devices
  };
  struct Run {
    std::vector<double> times;  // sorted
    double busy = 0;
    std::vector<std::uint8_t> image;
  };
  // --frames frames (after one warm-up) on a new device of `threads` threads and its own target.
  const auto run = [&](int threads) {
    Device device(device_options(threads));
    Targets targets = make_targets();
    std::vector<std::pair<double, double>> frames;  // seconds, busy
    for (int k = 0; k <= o.frames; ++k) {
      const auto start = std::chrono::steady_clock::now();
      const DrawReport report = frame(device, targets);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const StageTimes& t = report.times;
      const double stages = t.ia_vs + t.hs + t.tessellator + t.ds + t.setup + t.raster;
      if (k > 0) frames.push_back({s, t.wall > 0 ? stages / (threads * t.wall) : 0.0});
    }
    std::sort(frames.begin(), frames.end());
    Run out;
    for (const auto& f : frames) out.times.push_back(f.first);
    out.busy = frames[frames.size() / 2].second;
    out.image = targets.image().color_bytes();
    return out;
  };
  const auto check_image = [&](const std::vector<std::uint8_t>& image, const std::vector<std::uint8_t>& first,
                               const std::string& what) {
    if (image != first)
      throw InputError("bench scaling: the image " + what +
                       " differs from the 1-thread image (a determinism bug; please report it)");
  };
  std::vector<Row> rows;
  std::vector<std::uint8_t> first_image;
  for (const int threads : thread_counts(most)) {
    Run r = run(threads);
    rows.push_back({threads, r.times[r.times.size() / 2], r.times.front(), r.busy});
    if (first_image.empty())
      first_image = std::move(r.image);
    else
      check_image(r.image, first_image, "with " + std::to_string(threads) + " threads");
    log_info("threads " + std::to_string(threads) + ": median " + std::to_string(rows.back().median_s) + " s");
  }
  if (o.ceiling) {
    rows.front().independent = 1.0;
    for (Row& row : rows) {
      if (row.threads == 1) continue;
      // Each independent device's median frame; a failure on one thread is rethrown here.
      std::vector<Run> runs(std::size_t(row.threads));
      std::vector<std::exception_ptr> errors(runs.size());
      std::vector<std::thread> workers;
      for (std::size_t i = 0; i < runs.size(); ++i)
        workers.emplace_back([&, i] {
          try {
            runs[i] = run(1);
          } catch (...) {
            errors[i] = std::current_exception();
          }
        });
      for (auto& t : workers) t.join();
      for (const auto& e : errors)
        if (e) std::rethrow_exception(e);
      std::vector<double> medians;
      for (const Run& r : runs) {
        check_image(r.image, first_image, "of " + std::to_string(row.threads) + " independent devices");
        medians.push_back(r.times[r.times.size() / 2]);
      }
      std::sort(medians.begin(), medians.end());
      row.independent = row.threads * rows.front().median_s / medians[medians.size() / 2];
      log_info(std::to_string(row.threads) + " independent one-thread devices: speed-up " +
               std::to_string(row.independent));
    }
  }

  const double one = rows.front().median_s;
  const std::string cpu = cpu_name();
  if (o.json) {
    Json list = Json::array();
    for (const Row& r : rows) {
      Json row = {{"threads", r.threads},
                  {"median_s", r.median_s},
                  {"min_s", r.min_s},
                  {"speedup", one / r.median_s},
                  {"efficiency", one / r.median_s / r.threads},
                  {"busy", r.busy}};
      if (o.ceiling) row["independent_speedup"] = r.independent;
      list.push_back(std::move(row));
    }
    const Json j = {{"scene", o.scene},
                    {"factor", json_float(factor)},
                    {"msaa", msaa},
                    {"resolution", std::to_string(w) + "x" + std::to_string(h)},
                    {"frames", o.frames},
                    {"cpu", cpu},
                    {"hardware_threads", hardware},
                    {"same_image", true},
                    {"rows", list}};
    std::cout << json_text(j) << "\n";
  } else {
    std::ostringstream out;
    out << "bench scaling: " << o.scene << " factor " << factor << ", " << w << "x" << h
        << (msaa > 1 ? ", " + std::to_string(msaa) + "x MSAA" : std::string()) << ", median of " << o.frames
        << " frames; " << cpu << ", " << hardware << " hardware threads\n";
    out << "threads  time (ms)  speed-up  efficiency  busy" << (o.ceiling ? "  independent" : "") << "\n";
    char line[160];
    for (const Row& r : rows) {
      std::snprintf(line, sizeof line, "%7d  %9.2f  %7.2fx  %9.0f%%  %3.0f%%", r.threads, r.median_s * 1e3,
                    one / r.median_s, 100.0 * one / r.median_s / r.threads, 100.0 * r.busy);
      out << line;
      if (o.ceiling) {
        std::snprintf(line, sizeof line, "  %10.2fx", r.independent);
        out << line;
      }
      out << "\n";
    }
    out << "busy: summed stage time over threads x wall time"
        << (o.ceiling ? "; independent: N one-thread devices at once, N x one thread's frame over their median" : "")
        << "\n";
    out << "the same image bytes for every thread count\n";
    std::cout << out.str();
  }
  return kExitOk;
}

}  // namespace

Runner add_bench_scaling_command(CLI::App& bench) {
  auto o = std::make_shared<ScalingOptions>();
  o->s.factor = 64.0f;
  CLI::App* cmd = bench.add_subcommand(
      "scaling", "One scene over 1, 2, 4, ... threads up to all cores: time, speed-up and efficiency per count");
  cmd->add_option("--scene", o->scene,
                  "torus (the benchmark torus), frog (a cage, by default the monster frog, with the model options "
                  "below, as bench frog takes them) or a scene file (drawn as tessera render draws it)")
      ->capture_default_str();
  cmd->add_option("--cage", o->s.cage, "--scene frog: the cage (default: the monster frog shipped with tessera)");
  add_model_settings_options(*cmd, o->s, PatchCullMode::all);
  cmd->remove_option(cmd->get_option("--threads"));  // the command's own subject
  add_bench_msaa_option(*cmd, o->s.msaa);
  cmd->add_option("--frames", o->frames, "timed frames per thread count (after one warm-up)")->capture_default_str();
  cmd->add_option("--max-threads", o->max_threads, "the largest thread count (0: all cores)")->capture_default_str();
  cmd->add_flag("--ceiling", o->ceiling,
                "also render N independent one-thread frames at once per count: the speed-up the cores "
                "reach with nothing waiting (the machine's limit, apart from the pipeline)");
  cmd->add_flag("--json", o->json, "print results as JSON");
  return [o, cmd]() -> int { return cmd->parsed() ? run_bench_scaling(*o, *cmd) : -1; };
}

}  // namespace tessera::cli
