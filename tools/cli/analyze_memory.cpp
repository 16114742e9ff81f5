#include "tools/cli/analyze_memory.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "shaders_cpp/displacement/displacement_map.h"
#include "shaders_cpp/render/displaced_model.h"
#include "shaders_cpp/subdiv/subd_patches.h"
#include "tools/scene/common.h"
#include "tools/scene/model_options.h"

extern char** environ;

namespace tessera::cli {

using namespace scene;
using namespace measure;

namespace {

std::vector<int> parse_levels(const std::string& text) {
  std::vector<int> levels;
  for (float x : parse_float_list(text, "--levels")) {
    if (!(x >= 1.0f && x <= 64.0f) || x != float(int(x)))
      throw UsageError("--levels: " + float_text(x) + " is not an integer in 1..64");
    levels.push_back(int(x));
  }
  if (levels.empty()) throw UsageError("--levels: empty");
  return levels;
}

// The displacement as `tessera render --displacement` would build it: its map's size and bytes per
// texel as kept (the selected channels as floats) and its per-patch data. Schemes and cages that
// cannot be displaced (faces that are not quads) still get the map's row, with the model's estimate for
// the per-patch data.
struct MapFacts {
  MapSize size;
  int texel_bytes = 0;
  std::optional<std::uint64_t> patch_data_bytes;
  std::string description;
};

MapFacts load_map_facts(const std::string& path, const std::string& channel, const Cage& cage, Scheme scheme) {
  try {
    // The displacement itself when the cage and scheme can take one (it loads the map before any
    // cage check, so map errors come first either way); otherwise the map alone.
    MapFacts f;
    std::optional<Displacement> displacement;
    std::optional<DisplacementMap> map_only;
    std::string estimated;
    try {
      const SubdModel model = make_subd_model(cage, scheme);
      DisplacementOptions d;
      d.map = path;
      d.channel = channel;
      d.normal_map = "derived";  // the normal map is not part of the comparison (memory_model.h)
      displacement = make_displacement(model, d);
      std::size_t patch_bytes = displacement->bytes();
      for (const DisplacementMap& m : displacement->maps) patch_bytes -= m.bytes();
      f.patch_data_bytes = patch_bytes;
    } catch (const CageError& e) {
      map_only = DisplacementMap::load(path, channel);
      estimated = "; per-patch data estimated (" + std::string(e.what()) + ")";
    }
    const DisplacementMap& map = displacement ? displacement->maps.front() : *map_only;
    std::string names;
    for (const std::string& n : map.selected()) names += (names.empty() ? "" : ",") + n;
    f.description = std::filesystem::path(path).filename().string() + " " + std::to_string(map.width()) + "x" +
                    std::to_string(map.height()) + " (channel " + names + ")" + estimated;
    f.size = {map.width(), map.height()};
    f.texel_bytes = map.channels() * int(sizeof(float));
    return f;
  } catch (const DisplacementMapError& e) {
    throw InputError(e.what());
  }
}

// Runs this executable with `args` (argv[0] included), its stdout to `stdout_path` (its summary would
// mix into ours, which may be JSON; its stderr, errors, passes through). Returns the exit status and
// sets the child's peak RSS from wait4.
int run_child(std::vector<std::string> args, const std::string& stdout_path, std::uint64_t& peak_rss_bytes) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  ::posix_spawn_file_actions_init(&actions);
  int spawned = ::posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path.c_str(),
                                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = 0;
  if (spawned == 0) spawned = ::posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, argv.data(), environ);
  ::posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw InputError(std::string("--measure: cannot start tessera: ") + std::strerror(spawned));
  int status = 0;
  struct rusage usage {};
  pid_t waited;
  while ((waited = ::wait4(pid, &status, 0, &usage)) < 0 && errno == EINTR) {
  }
  if (waited < 0) throw InputError(std::string("--measure: cannot wait for tessera: ") + std::strerror(errno));
  peak_rss_bytes = std::uint64_t(usage.ru_maxrss) * 1024;  // kilobytes on Linux
  return status;
}

// Runs `tessera render` for one level in a child process and reads the memory it reports.
MeasuredMemory measure_render(const std::string& cage_path, const MemoryOptions& o, int level) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path();
  const std::string stem = "tessera-memory-" + std::to_string(::getpid()) + "-" + std::to_string(level);
  const std::string image = (dir / (stem + ".png")).string(), stats = (dir / (stem + ".json")).string();
  std::vector<std::string> args = {"tessera",      "-q",         "render",    cage_path,
                                   "--scheme",     o.scheme,     "--factor",  std::to_string(level),
                                   "--resolution", o.resolution, "--threads", std::to_string(o.threads),
                                   "-o",           image,        "--json"};
  if (o.scheme == "adaptive") args.insert(args.end(), {"--isolation", std::to_string(o.isolation)});
  if (!o.displacement.empty()) {
    args.insert(args.end(), {"--displacement", o.displacement});
    if (!o.channel.empty()) args.insert(args.end(), {"--displacement-channel", o.channel});
  }
  const auto start = std::chrono::steady_clock::now();
  MeasuredMemory m;
  // The peak from wait4, as for the process base row: both from the operating system, the same way.
  const int status = run_child(args, stats, m.peak_rss_bytes);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::error_code ec;
  fs::remove(image, ec);
  nlohmann::json j;
  {
    std::ifstream in(stats);
    j = nlohmann::json::parse(in, nullptr, false);
  }
  fs::remove(stats, ec);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw InputError("--measure: tessera render at level " + std::to_string(level) + " failed (its error is above)");
  if (j.is_discarded() || !j.contains("memory"))
    throw InputError("--measure: tessera render at level " + std::to_string(level) + " printed no memory statistics");
  m.geometry_peak_bytes = j["memory"].value("geometry_peak_bytes", std::uint64_t(0));
  m.framebuffer_bytes = j["memory"].value("framebuffer_bytes", std::uint64_t(0));
  m.seconds = seconds;
  return m;
}

std::string megabytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", double(bytes) / (1024.0 * 1024.0));
  return text;
}

}  // namespace

void add_memory_options(CLI::App& cmd, MemoryOptions& o) {
  cmd.add_flag("--memory", o.enabled,
               "print the talk's memory table: a pre-tessellated mesh against the cage, patches and displacement map");
  cmd.add_option("--displacement", o.displacement, "--memory: the displacement map (its size sets the map rows)");
  cmd.add_option("--displacement-channel", o.channel,
                 "--memory: the map's height channel, a name or letter (A, height)");
  cmd.add_option("--levels", o.levels, "--memory: tessellation levels (integer factors 1..64)")->capture_default_str();
  cmd.add_option("--memory-scheme", o.scheme, "--memory: the scheme whose patch data is counted")
      ->capture_default_str();
  add_setting_option(
      cmd, "--memory-isolation", o.isolation,
      [](const std::string& text) { return isolation_option(text, "--memory-isolation"); },
      "--memory-scheme adaptive: the isolation level")
      ->default_str(std::to_string(o.isolation));
  cmd.add_option("--texel-bytes", o.texel_bytes,
                 "--memory: bytes per map texel (0: as Tessera keeps the map, a float per channel)")
      ->capture_default_str();
  cmd.add_option("--mesh-vertex-bytes", o.mesh_vertex_bytes, "--memory: bytes per vertex of the pre-tessellated mesh")
      ->capture_default_str();
  cmd.add_flag("--measure", o.measure, "--memory: also render each level (tessera render) and report its peak memory");
  cmd.add_option("--resolution", o.resolution, "--measure: render resolution WxH")->capture_default_str();
  cmd.add_option("--threads", o.threads, "--measure: render threads (0: all)");
}

MemoryAnalysis analyze_memory(const std::string& cage_path, const Cage& cage, const Topology& topology,
                              const MemoryOptions& o) {
  MemoryAnalysis a;
  a.options = o;
  MemoryModelOptions model;
  model.levels = parse_levels(o.levels);
  if (o.texel_bytes < 0 || o.texel_bytes > 64) throw UsageError("--texel-bytes: must be in 0..64");
  if (o.mesh_vertex_bytes < 1 || o.mesh_vertex_bytes > 1024)
    throw UsageError("--mesh-vertex-bytes: must be in 1..1024");
  int texel_bytes = o.texel_bytes;
  model.mesh_vertex_bytes = o.mesh_vertex_bytes;
  const Scheme scheme = scheme_option(o.scheme, "--memory-scheme");
  if (o.measure) {
    parse_resolution(o.resolution);
    device_options(o.threads);
  }
  if (!o.displacement.empty()) {
    const MapFacts facts = load_map_facts(o.displacement, o.channel, cage, scheme);
    model.map = facts.size;
    model.displacement_data_bytes = facts.patch_data_bytes;
    a.map_description = facts.description;
    if (texel_bytes == 0) texel_bytes = facts.texel_bytes;
  } else {
    a.map_description = "none given: a square map of exactly the side each level needs";
    if (texel_bytes == 0) texel_bytes = int(sizeof(float));  // one float channel, as a scalar map is kept
  }
  model.texel_bytes = a.texel_bytes = texel_bytes;
  try {
    if (uses_limit_surface(scheme))
      model.limit_surface_bytes =
          (scheme == Scheme::adaptive ? LimitSurface::create_adaptive(cage, o.isolation) : LimitSurface::create(cage))
              .memory_bytes();
    a.table = memory_table(cage, topology, build_patches(cage, topology, scheme), model);
  } catch (const CageError& e) {
    throw InputError(e.what());
  }
  if (o.measure) {
    // What the process holds before it draws anything (shared libraries, allocator, thread pool):
    // `tessera render --help` loads the commands module and its libraries and exits (`--version` is
    // answered by the launcher alone, without them).
    run_child({"tessera", "render", "--help"}, "/dev/null", a.base_rss_bytes);
    for (int level : model.levels) {
      log_info("analyze --measure: rendering level " + std::to_string(level));
      a.measured.push_back(measure_render(cage_path, o, level));
    }
  }
  return a;
}

std::string memory_text(const MemoryAnalysis& a) {
  const MemoryTable& t = a.table;
  std::ostringstream s;
  s << "Memory (level L: integer factor L on every edge; the model is in tools/measure/memory_model.h):\n";
  s << "- pre-tessellated mesh: " << a.options.mesh_vertex_bytes
    << " B per vertex (position, normal, UV; split on UV seams), 32-bit indices\n";
  s << "- Tessera: cage " << megabytes(t.cage_bytes) << " MB + patch data (" << a.options.scheme
    << (a.options.scheme == "adaptive" ? ", isolation " + std::to_string(a.options.isolation) : std::string()) << ") "
    << megabytes(t.patch_bytes) << " MB + map at one texel per generated vertex, " << a.texel_bytes
    << " B per texel, with its mip chain\n";
  s << "- map: " << a.map_description << "; UV area " << t.uv_area << " over " << t.faces << " faces\n";
  s << "level | mesh vertices | mesh triangles | mesh MB (vertices + indices) | map side needed | map kept | Tessera "
       "MB | ratio";
  if (!a.measured.empty())
    s << " | render peak RSS MB (process base " << megabytes(a.base_rss_bytes) << ") | geometry peak MB";
  s << "\n";
  for (std::size_t i = 0; i < t.levels.size(); ++i) {
    const MemoryLevel& m = t.levels[i];
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.1f", m.ratio());
    s << m.level << " | " << m.mesh_vertices << " | " << m.mesh_triangles << " | " << megabytes(m.mesh_bytes()) << " ("
      << megabytes(m.mesh_vertex_bytes) << " + " << megabytes(m.mesh_index_bytes) << ") | " << m.needed_map_side
      << " | " << m.map_width << "x" << m.map_height << " | " << megabytes(m.tessera_bytes) << " | " << ratio;
    if (!a.measured.empty())
      s << " | " << megabytes(a.measured[i].peak_rss_bytes) << " | " << megabytes(a.measured[i].geometry_peak_bytes);
    s << "\n";
  }
  return s.str();
}

nlohmann::ordered_json memory_json(const MemoryAnalysis& a) {
  const MemoryTable& t = a.table;
  nlohmann::ordered_json j;
  j["model"] = {{"mesh_vertex_bytes", a.options.mesh_vertex_bytes},
                {"index_bytes", MemoryModelOptions{}.index_bytes},
                {"texel_bytes", a.texel_bytes},
                {"scheme", a.options.scheme},
                {"map", a.map_description},
                {"uv_area", t.uv_area},
                {"faces", t.faces}};
  j["cage_bytes"] = t.cage_bytes;
  if (!a.measured.empty()) j["process_base_rss_bytes"] = a.base_rss_bytes;
  j["patch_bytes"] = t.patch_bytes;
  if (a.options.scheme == "adaptive") j["isolation"] = a.options.isolation;
  auto& levels = j["levels"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < t.levels.size(); ++i) {
    const MemoryLevel& m = t.levels[i];
    nlohmann::ordered_json l = {{"level", m.level},
                                {"mesh_vertices", m.mesh_vertices},
                                {"mesh_triangles", m.mesh_triangles},
                                {"mesh_vertex_bytes", m.mesh_vertex_bytes},
                                {"mesh_index_bytes", m.mesh_index_bytes},
                                {"mesh_bytes", m.mesh_bytes()},
                                {"needed_map_side", m.needed_map_side},
                                {"map_width", m.map_width},
                                {"map_height", m.map_height},
                                {"map_bytes", m.map_bytes},
                                {"tessera_bytes", m.tessera_bytes},
                                {"ratio", m.ratio()}};
    if (!a.measured.empty()) {
      const MeasuredMemory& r = a.measured[i];
      l["render_peak_rss_bytes"] = r.peak_rss_bytes;
      l["render_geometry_peak_bytes"] = r.geometry_peak_bytes;
      l["render_framebuffer_bytes"] = r.framebuffer_bytes;
      l["render_seconds"] = r.seconds;
    }
    levels.push_back(l);
  }
  return j;
}

}  // namespace tessera::cli
