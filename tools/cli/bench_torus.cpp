// `tessera bench torus`: the benchmark scene of ../shared/bench/tessbench.cpp rendered through the whole
// pipeline, timed per frame (median and minimum over --frames after one warm-up frame). With
// --llvmpipe PATH it also runs that harness with the same arguments in the same run, and reports the
// speed ratio and how many pixels of the two images differ by more than 2/255. With --rounds R the two
// take turns R times: on a shared machine whose speed drifts between runs, each round's ratio compares
// measurements taken moments apart, and the reported ratio is the median of the rounds' ratios.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <regex>
#include <sstream>

#include "pipeline/device.h"
#include "shaders_cpp/image_io/image_file.h"
#include "shaders_cpp/render/torus_scene.h"
#include "tools/cli/bench_options.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/render_settings.h"
#include "tools/verify/image_compare.h"
#include "tools/verify/oracle.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct TorusOptions {
  float factor = 16;
  ts::Partitioning partitioning = ts::Partitioning::integer;
  std::string resolution = "1920x1080";
  int frames = 5;
  int rounds = 1;
  int threads = 0;
  int msaa = 1;
  std::string output;
  std::string stats;
  std::string llvmpipe;
  std::string trace;
  std::size_t chunk_primitives = DeviceOptions{}.chunk_primitives;
  BenchDeviceOptions device;
  int window_patches = DeviceOptions{}.window_patches;
  bool json = false;
};

struct LlvmpipeRun {
  double median_s = 0, min_s = 0;
  std::uint64_t triangles = 0;
  std::string image;
};

// Checked before rendering, so a bad --llvmpipe fails at once.
void check_llvmpipe(const TorusOptions& o, ts::Partitioning p) {
  // The harness is asked for a GL spacing and GL names none for pow2. (The D3D11 tessellator runs pow2
  // as integer, so equal_spacing would draw the same pattern; the option stays refused so that the
  // llvmpipe run is always of the partitioning the user named.)
  if (p == ts::Partitioning::pow2)
    throw UsageError("--llvmpipe: GL has no pow2 spacing; use integer or a fractional partitioning");
  if (!std::filesystem::exists(o.llvmpipe))
    throw InputError(o.llvmpipe + ": no such llvmpipe harness (build tessbench.cpp)");
}

LlvmpipeRun run_llvmpipe(const TorusOptions& o, ts::Partitioning p, int w, int h, int threads) {
  const char* spacing = oracle::gl_spacing(p);
  LlvmpipeRun r;
  r.image =
      (std::filesystem::temp_directory_path() / ("tessera-llvmpipe-" + std::to_string(::getpid()) + ".ppm")).string();
  // Multisampled: the harness renders o.msaa samples in D3D11's pixel convention (upper-left origin),
  // whose standard sample positions are Tessera's; GL's default origin mirrors the pattern vertically.
  char cmd[2048];
  std::snprintf(cmd, sizeof cmd,
                "LP_NUM_THREADS=%d TESSBENCH_SAMPLES=%d TESSBENCH_UPPER_LEFT=%d '%s' %.9g %d %d %d %s '%s' 2>&1",
                threads, o.msaa, o.msaa > 1 ? 1 : 0, o.llvmpipe.c_str(), double(o.factor), w, h, o.frames, spacing,
                r.image.c_str());
  log_info(std::string("running llvmpipe: ") + cmd);
  FILE* pipe = ::popen(cmd, "r");
  if (!pipe) throw InputError(o.llvmpipe + ": cannot start");
  std::string text;
  std::array<char, 512> buf;
  while (std::fgets(buf.data(), int(buf.size()), pipe)) text += buf.data();
  const int status = ::pclose(pipe);
  const std::regex re(R"(triangles (\d+) median_s ([0-9.eE+-]+) min_s ([0-9.eE+-]+))");
  std::smatch m;
  if (status != 0 || !std::regex_search(text, m, re))
    throw InputError(o.llvmpipe + ": harness failed: " + text.substr(0, text.find('\n')));
  r.triangles = std::stoull(m[1]);
  r.median_s = std::stod(m[2]);
  r.min_s = std::stod(m[3]);
  return r;
}

int run_bench_torus(const TorusOptions& o) {
  const ts::Partitioning partitioning = o.partitioning;
  if (!std::isfinite(o.factor))
    throw UsageError("--factor: must be finite (the scene's factor, clamped as D3D11 does)");
  if (o.frames < 1 || o.frames > 10000) throw UsageError("--frames: must be in 1..10000");
  if (o.rounds < 1 || o.rounds > 100) throw UsageError("--rounds: must be in 1..100");
  check_output_paths({{"-o", o.output}, {"--stats", o.stats}, {"--trace", o.trace}}, {});
  // The device would clamp these silently; a benchmark must run what it was asked to.
  if (o.chunk_primitives < 64 || o.chunk_primitives > (std::size_t(1) << 24))
    throw UsageError("--chunk-primitives: " + std::to_string(o.chunk_primitives) + " is not in 64..16777216");
  if (o.window_patches < 1 || o.window_patches > (1 << 20))
    throw UsageError("--window-patches: " + std::to_string(o.window_patches) + " is not in 1..1048576");
  const auto [w, h] = parse_resolution(o.resolution);
  // Mesa's llvmpipe makes multisampled framebuffers of 2 and 4 samples only (8 and 16 are incomplete).
  if (!o.llvmpipe.empty() && o.msaa > 4)
    throw UsageError("--msaa " + std::to_string(o.msaa) +
                     " with --llvmpipe: Mesa's llvmpipe renders 1, 2 or 4 samples per pixel");
  if (!o.llvmpipe.empty()) check_llvmpipe(o, partitioning);

  DeviceOptions dopt = device_options(o.threads);
  dopt.chunk_primitives = o.chunk_primitives;
  o.device.apply(dopt);
  dopt.window_patches = o.window_patches;
  Device device(dopt);
  std::string error;
  auto fb = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error, msaa_option(o.msaa));
  if (!fb) throw UsageError("--resolution: " + error);
  // A multisampled frame ends with its colour's resolve, as a GPU's frame would before display
  // (ResolveSubresource: colour only), into a target made once (as a swap chain's).
  auto resolved = o.msaa > 1 ? Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error) : std::nullopt;
  log_info("building the torus scene");
  const render::TorusScene scene = render::make_torus_scene(w, h);
  const auto draw = render::make_torus_draw(scene, o.factor, partitioning, w, h);

  const auto median_of = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  std::vector<double> times, round_speedups;
  std::vector<LlvmpipeRun> llvmpipe_rounds;
  DrawReport report;
  const auto render_frame = [&] {
    device.clear(*fb, glm::vec4(0, 0, 0, 1), 1.0f);
    DrawResult r = device.draw(draw, *fb);
    if (resolved) device.resolve(*fb, *resolved, ResolvedPlanes::color);  // also the tiles no draw entered
    if (!r.ok()) throw InputError(r.error);
    return r;
  };
  for (int round = 0; round < o.rounds; ++round) {
    std::vector<double> round_times;
    for (int frame = 0; frame <= o.frames; ++frame) {
      const auto start = std::chrono::steady_clock::now();
      DrawResult r = render_frame();
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (frame > 0) round_times.push_back(s);  // frame 0 warms caches and allocations, as the harness does
      report = r.report;
      log_info("round " + std::to_string(round) + " frame " + std::to_string(frame) + ": " + std::to_string(s) + " s");
    }
    times.insert(times.end(), round_times.begin(), round_times.end());
    if (!o.llvmpipe.empty()) {
      llvmpipe_rounds.push_back(run_llvmpipe(o, partitioning, w, h, device.threads()));
      round_speedups.push_back(llvmpipe_rounds.back().median_s / median_of(round_times));
    }
  }
  const double median = median_of(times), minimum = *std::min_element(times.begin(), times.end());
  const std::uint64_t triangles = report.statistics.CInvocations;
  const std::uint64_t rss = peak_rss_bytes();
  std::optional<TraceSummary> traced;
  if (!o.trace.empty())
    traced = trace_frame(
        device, render_frame, o.trace,
        "bench torus, factor " + float_text(o.factor) + ", " + std::to_string(device.threads()) + " threads");

  if (!o.output.empty()) {
    if (auto e = write_color(*fb, {o.output}); !e.empty()) throw InputError(e);
  }
  if (!o.stats.empty()) {
    const Json s = {{"scene", "torus"},
                    {"factor", json_float(o.factor)},
                    {"threads", device.threads()},
                    {"statistics", to_json(report.statistics)},
                    {"times", to_json(report.times)},
                    {"memory", to_json(report.memory)},
                    {"peak_rss_bytes", rss}};
    write_text_atomically(o.stats, json_text(s) + "\n");
  }

  std::optional<LlvmpipeRun> lp;
  std::optional<verify::ImageDiff> diff;
  double speedup = 0;
  if (!o.llvmpipe.empty()) {
    // Over the rounds: the median of the harness's medians, its minimum, the median of the ratios.
    lp = llvmpipe_rounds.back();
    std::vector<double> medians;
    for (const LlvmpipeRun& r : llvmpipe_rounds)
      medians.push_back(r.median_s), lp->min_s = std::min(lp->min_s, r.min_s);
    lp->median_s = median_of(medians);
    speedup = median_of(round_speedups);
    const std::string ours =
        o.output.empty()
            ? (std::filesystem::temp_directory_path() / ("tessera-torus-" + std::to_string(::getpid()) + ".png"))
                  .string()
            : o.output;
    if (o.output.empty())
      if (auto e = write_color(*fb, {ours}); !e.empty()) throw InputError(e);
    diff = verify::compare_images(ours, lp->image, 2);
    std::filesystem::remove(lp->image);
    if (o.output.empty()) std::filesystem::remove(ours);
  }

  if (o.json) {
    Json j = {{"scene", "torus"},
              {"factor", json_float(o.factor)},
              {"partitioning", std::string(ts::to_string(partitioning))},
              {"resolution", std::to_string(w) + "x" + std::to_string(h)},
              {"msaa", o.msaa},
              {"isa", kBuildIsa},
              {"threads", device.threads()},
              {"frames", o.frames},
              {"rounds", o.rounds},
              {"triangles", triangles},
              {"median_s", median},
              {"min_s", minimum},
              {"triangles_per_s", double(triangles) / median},
              {"geometry_peak_bytes", report.memory.geometry_peak_bytes},
              {"framebuffer_bytes", report.memory.framebuffer_bytes},
              {"peak_rss_bytes", rss},
              {"times", to_json(report.times)}};
    if (traced) j["trace"] = to_json(*traced);
    if (lp)
      j["llvmpipe"] = {{"median_s", lp->median_s},         {"min_s", lp->min_s},
                       {"triangles", lp->triangles},       {"speedup", speedup},
                       {"round_speedups", round_speedups}, {"pixels_over_2", diff->over_threshold},
                       {"share_over_2", diff->share()},    {"max_difference", diff->max_difference}};
    std::cout << json_text(j) << "\n";
  } else {
    char line[512];
    std::snprintf(
        line, sizeof line,
        "torus factor %s %s %dx%d %s threads %d: triangles %llu median_s %.4f min_s %.4f (%.1f M triangles/s), "
        "geometry peak %.1f MB, framebuffer %.1f MB, peak RSS %.1f MB\n",
        float_text(o.factor).c_str(), std::string(ts::to_string(partitioning)).c_str(), w, h, kBuildIsa,
        device.threads(), static_cast<unsigned long long>(triangles), median, minimum, double(triangles) / median / 1e6,
        double(report.memory.geometry_peak_bytes) / 1e6, double(report.memory.framebuffer_bytes) / 1e6,
        double(rss) / 1e6);
    std::cout << line;
    if (traced) std::cout << summary_line(*traced) << "\n";
    if (lp) {
      std::snprintf(line, sizeof line,
                    "llvmpipe: triangles %llu median_s %.4f min_s %.4f; speedup %.2fx; pixels differing by more than "
                    "2/255: %llu of %llu (%.4f%%), max difference %d\n",
                    static_cast<unsigned long long>(lp->triangles), lp->median_s, lp->min_s, speedup,
                    static_cast<unsigned long long>(diff->over_threshold),
                    static_cast<unsigned long long>(diff->pixels), 100.0 * diff->share(), diff->max_difference);
      std::cout << line;
    }
  }
  return kExitOk;
}

}  // namespace

Runner add_bench_torus_command(CLI::App& bench) {
  auto o = std::make_shared<TorusOptions>();
  CLI::App* cmd =
      bench.add_subcommand("torus", "The displaced B-spline torus of tessbench.cpp through the whole pipeline");
  cmd->add_option("--factor", o->factor, "tessellation factor on every edge and inside")->capture_default_str();
  add_setting_option(
      *cmd, "--partitioning", o->partitioning, [](const std::string& text) { return partitioning_option(text); },
      "integer, pow2, fractional_odd or fractional_even")
      ->default_str("integer");
  cmd->add_option("--resolution", o->resolution, "WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--frames", o->frames, "timed frames (after one warm-up frame)")->capture_default_str();
  cmd->add_option(
         "--rounds", o->rounds,
         "measure this many times, taking turns with --llvmpipe; its speedup is the median of the rounds' ratios")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "worker threads, 0 = all")->capture_default_str();
  add_bench_msaa_option(*cmd, o->msaa);
  cmd->add_option("-o,--output", o->output, "write the last frame (PNG, EXR, ...)");
  cmd->add_option("--stats", o->stats, "write D3D11 pipeline statistics, stage times and memory as JSON");
  cmd->add_option("--llvmpipe", o->llvmpipe, "path of the tessbench harness: run it too and compare");
  add_bench_trace_option(*cmd, o->trace);
  cmd->add_option("--chunk-primitives", o->chunk_primitives, "primitives per geometry chunk")->capture_default_str();
  o->device.add_options(*cmd);
  cmd->add_option("--window-patches", o->window_patches, "patches through the vertex and hull shaders at once")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print results as JSON");
  cmd->fallthrough();
  return [o, cmd]() -> int { return cmd->parsed() ? run_bench_torus(*o) : -1; };
}

}  // namespace tessera::cli
