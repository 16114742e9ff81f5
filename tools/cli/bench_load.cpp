// `tessera bench load`: what a user waits for before the first frame of a large cage — reading the file,
// the topology, the patches and their stencil tables, the fold check, the control-point pre-pass, the
// limit surface (exact and adaptive), then the scene's framing, factors and culling — with the process's
// peak memory, so that the cost per cage face can be measured and compared across cage sizes.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include <tbb/task_arena.h>

#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/scene_file.h"
#include "tools/scene/scene_render.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct BenchLoadOptions {
  RenderSettings s;
  int repeat = 3;
  bool json = false;
};

// The process's peak resident memory so far, in bytes (getrusage's ru_maxrss is in KiB on Linux).
double peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) * 1024.0;
}

struct LoadRun {
  PrepareTimes times;
  double total_s = 0;
  std::size_t faces = 0, vertices = 0, patches = 0, tables = 0;
};

int run_bench_load(BenchLoadOptions o) {
  if (o.s.cage.empty()) throw UsageError("bench load: give a cage (OBJ or glTF)");
  if (o.repeat < 1 || o.repeat > 100) throw UsageError("--repeat: " + std::to_string(o.repeat) + " is not in 1..100");
  const int threads = o.s.threads > 0 ? o.s.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  if (threads > 1024) throw UsageError("--threads: " + std::to_string(threads) + " is not in 0..1024");
  tbb::task_arena arena(threads);
  std::vector<LoadRun> runs;
  for (int r = 0; r < o.repeat; ++r) {
    LoadRun run;
    arena.execute([&] {
      const auto start = std::chrono::steady_clock::now();
      const std::unique_ptr<PreparedScene> scene = prepare_scene(o.s);
      run.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const SubdModel& m = scene->model;
      run.times = m.times;
      run.faces = std::size_t(m.cage.face_count());
      run.vertices = m.cage.positions.size();
      run.patches = m.patches.quads.patches.size() + m.patches.tris.patches.size();
      run.tables = m.patches.tables.size();
    });
    runs.push_back(run);
  }
  // The run of median total time stands for all (its phases add up to its total).
  std::sort(runs.begin(), runs.end(), [](const LoadRun& a, const LoadRun& b) { return a.total_s < b.total_s; });
  const LoadRun& m = runs[runs.size() / 2];
  const PrepareTimes& t = m.times;
  const double model_s = t.read_s + t.topology_s + t.patches_s + t.fold_check_s + t.precompute_s + t.limit_s;
  const double scene_s = std::max(0.0, m.total_s - model_s);
  const double bytes = double(std::filesystem::file_size(o.s.cage));
  const double peak = peak_rss_bytes();
  if (o.json) {
    std::cout << json_text(Json{{"cage", o.s.cage},
                                {"scheme", to_string(o.s.scheme)},
                                {"threads", threads},
                                {"repeat", o.repeat},
                                {"faces", m.faces},
                                {"vertices", m.vertices},
                                {"patches", m.patches},
                                {"tables", m.tables},
                                {"file_bytes", bytes},
                                {"total_s", m.total_s},
                                {"min_total_s", runs.front().total_s},
                                {"read_s", t.read_s},
                                {"read_mb_per_s", t.read_s > 0 ? bytes / t.read_s / 1e6 : 0.0},
                                {"topology_s", t.topology_s},
                                {"patches_s", t.patches_s},
                                {"fold_check_s", t.fold_check_s},
                                {"precompute_s", t.precompute_s},
                                {"limit_s", t.limit_s},
                                {"scene_s", scene_s},
                                {"peak_rss_bytes", peak},
                                {"peak_rss_bytes_per_face", m.faces > 0 ? peak / double(m.faces) : 0.0}})
              << "\n";
    return kExitOk;
  }
  auto ms = [](double s) { return float_text(float(s * 1e3)) + " ms"; };
  std::cout << o.s.cage << " (" << m.faces << " faces, " << m.vertices << " vertices), scheme "
            << to_string(o.s.scheme) << ", " << threads << " thread" << (threads == 1 ? "" : "s") << ": ready in "
            << ms(m.total_s) << " (median of " << o.repeat << ")\n"
            << "  read " << ms(t.read_s) << " (" << float_text(float(bytes / std::max(t.read_s, 1e-9) / 1e6))
            << " MB/s), topology " << ms(t.topology_s) << ", patches " << ms(t.patches_s) << " (" << m.patches
            << " patches, " << m.tables << " tables), fold check " << ms(t.fold_check_s) << ", pre-pass "
            << ms(t.precompute_s) << ", limit surface " << ms(t.limit_s) << ", scene (framing, factors, culling) "
            << ms(scene_s) << "\n"
            << "  peak memory " << float_text(float(peak / 1048576.0)) << " MiB ("
            << float_text(float(peak / std::max<double>(1.0, double(m.faces)))) << " bytes per face)\n";
  return kExitOk;
}

}  // namespace

Runner add_bench_load_command(CLI::App& bench) {
  auto o = std::make_shared<BenchLoadOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "load", "Time to prepare a cage for its first frame (read, topology, patches, pre-pass, scene), and peak memory");
  cmd->add_option("cage", o->s.cage, "the cage (OBJ or glTF)");
  add_settings_options(*cmd, o->s, PatchCullMode::all);
  cmd->add_option("--repeat", o->repeat, "preparations timed; the median is reported")->capture_default_str();
  cmd->add_flag("--json", o->json, "print results as JSON");
  return [o, cmd]() -> int { return cmd->parsed() ? run_bench_load(*o) : -1; };
}

}  // namespace tessera::cli
