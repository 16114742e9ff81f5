// `tessera bench view`: what a `tessera view` user waits for per frame — settings in, encoded image
// out (ViewerSession::frame: configure the kept scene for the camera, LOD, draw, encode) — over a
// turntable of camera positions, so every frame has new view-dependent factors. Defaults are the
// viewer's interactive case: screen LOD at 8 pixels per edge, 1280x720, PNG.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <thread>

#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/viewer/viewer_session.h"

namespace tessera::cli {

using namespace scene;
using namespace viewer;

namespace {

struct BenchViewOptions {
  RenderSettings s;
  int frames = 24;
  std::string format = "png";
  bool json = false;
};

int session_threads(int threads) {
  return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

int run_bench_view(BenchViewOptions o) {
  o.s.cage = cage_or_shipped_frog(o.s.cage);
  if (o.frames < 1 || o.frames > 100000)
    throw UsageError("--frames: " + std::to_string(o.frames) + " is not in 1..100000");
  if (o.format != "png" && o.format != "jpeg") throw UsageError("--format: '" + o.format + "' is not png or jpeg");
  const FrameFormat format = o.format == "png" ? FrameFormat::png : FrameFormat::jpeg;
  ViewerSession session(o.s);
  // The turntable around the framing camera (render --orbit's views).
  const std::vector<RenderSettings> views = session.turntable(o.s, o.frames);
  session.frame(o.s, format);  // warm-up: the kept scene and the pattern cache
  std::vector<double> total, draw, configure, render, encode;
  std::uint64_t triangles = 0, bytes = 0;
  for (const RenderSettings& s : views) {
    const auto start = std::chrono::steady_clock::now();
    const std::optional<ViewerFrame> f = session.frame(s, format);
    total.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    draw.push_back(f->summary["times"]["wall_s"].get<double>());
    configure.push_back(f->configure_s);
    render.push_back(f->render_s);
    encode.push_back(f->encode_s);
    triangles += f->summary["triangles"].get<std::uint64_t>();
    bytes += f->bytes.size();
  }
  const double t = median(total), d = median(draw);
  const double n = double(o.frames);
  if (o.json) {
    std::cout << json_text(Json{{"cage", o.s.cage},
                                {"resolution", resolution_text(o.s.camera.width, o.s.camera.height)},
                                {"lod", to_string(o.s.lod.mode)},
                                {"format", o.format},
                                {"frames", o.frames},
                                {"threads", session_threads(o.s.threads)},
                                {"median_frame_s", t},
                                {"min_frame_s", *std::min_element(total.begin(), total.end())},
                                {"median_draw_s", d},
                                {"median_encode_and_setup_s", t - d},
                                {"median_configure_s", median(configure)},
                                {"median_render_s", median(render)},
                                {"median_encode_s", median(encode)},
                                {"mean_triangles", double(triangles) / n},
                                {"mean_bytes", double(bytes) / n}})
              << "\n";
    return kExitOk;
  }
  std::cout << o.s.cage << ", " << resolution_text(o.s.camera.width, o.s.camera.height) << ", LOD "
            << to_string(o.s.lod.mode) << ", " << o.format << ", "
            << o.frames << " orbit frames on " << session_threads(o.s.threads) << " threads: median frame "
            << float_text(float(t * 1e3)) << " ms (min "
            << float_text(float(*std::min_element(total.begin(), total.end()) * 1e3)) << "), of which draw "
            << float_text(float(d * 1e3)) << " ms and configure + encode " << float_text(float((t - d) * 1e3))
            << " ms (configure " << float_text(float(median(configure) * 1e3)) << ", render_scene "
            << float_text(float(median(render) * 1e3)) << ", encode " << float_text(float(median(encode) * 1e3))
            << "); " << std::uint64_t(double(triangles) / n) << " triangles and "
            << std::uint64_t(double(bytes) / n / 1024.0) << " KiB a frame\n";
  return kExitOk;
}

}  // namespace

Runner add_bench_view_command(CLI::App& bench) {
  auto o = std::make_shared<BenchViewOptions>();
  CLI::App* cmd =
      bench.add_subcommand("view", "tessera view's frame path (settings to encoded image) over a turntable of cameras");
  cmd->add_option("--cage", o->s.cage, "the cage (default: the monster frog shipped with tessera)");
  o->s.camera.width = 1280;
  o->s.camera.height = 720;
  o->s.lod.mode = LodMode::screen;
  add_settings_options(*cmd, o->s, PatchCullMode::all);
  cmd->add_option("--frames", o->frames, "timed frames, each from the next camera of the turntable")
      ->capture_default_str();
  cmd->add_option("--format", o->format, "png (the still frame) or jpeg (the moving camera's)")->capture_default_str();
  cmd->add_flag("--json", o->json, "print results as JSON");
  return [o, cmd]() -> int { return cmd->parsed() ? run_bench_view(*o) : -1; };
}

}  // namespace tessera::cli
