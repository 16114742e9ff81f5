// `tessera bench dolly`: the camera moves in a straight line toward its target, with view-dependent
// LOD, frame by frame: per frame the triangles, the frame time and the largest vertex movement since
// the previous frame, which is how continuous the LOD is (fractional partitioning should move
// vertices in proportion to the camera step; integer partitioning pops by a fixed amount).
//
// Movement: for each tessellated vertex of a frame, the screen distance (through this frame's camera,
// so the camera's own motion does not count) to the nearest vertex, in domain space, of the same
// patch in the previous frame. A vertex that appears where an old one was (fractional_odd's split
// points) has moved 0; a vertex that appears in the middle of a segment (integer) has moved half a
// segment. The nearest vertex is found in a 64 x 64 grid over each patch's domain (DomainGrid).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <span>
#include <unordered_map>

#include "shaders_cpp/render/displaced_render.h"
#include "shaders_cpp/render/subd_render.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"
#include "tools/scene/scene_render.h"
#include "tools/scene/view_options.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct DollyOptions {
  RenderSettings s;             // s.cage empty: the monster frog shipped beside the binary
  std::optional<glm::vec3> to;  // not given: halfway to the target
  int frames = 30;
  bool json = false;
};

// One frame's tessellation: per patch (quad group ids first, then tri ids offset by the quad count),
// its vertices' domain locations and world positions.
struct PatchPoints {
  std::vector<glm::vec2> domain;
  std::vector<glm::vec3> position;
};
using FramePoints = std::vector<PatchPoints>;

// The points of one patch's domain in a 64 x 64 grid of cells, for nearest-point queries.
class DomainGrid {
 public:
  explicit DomainGrid(std::span<const glm::vec2> points) : points_(points), cells_(std::size_t(kGrid * kGrid)) {
    for (std::uint32_t i = 0; i < points.size(); ++i) cells_[cell(points[i])].push_back(i);
  }
  // The index of the point nearest q: rings of cells outward, until the nearest found is closer than
  // any point of an unvisited ring can be (a point beyond ring r - 1 is at least (r - 1) / 64 away).
  std::int64_t nearest(glm::vec2 q) const {
    const int cx = coordinate(q.x), cy = coordinate(q.y);
    std::int64_t best = -1;
    float best_d = INFINITY;
    for (int r = 0; r < kGrid && !(best >= 0 && best_d <= float(r - 1) / float(kGrid)); ++r)
      for (int y = std::max(0, cy - r); y <= std::min(kGrid - 1, cy + r); ++y)
        for (int x = std::max(0, cx - r); x <= std::min(kGrid - 1, cx + r); ++x) {
          if (std::max(std::abs(x - cx), std::abs(y - cy)) != r) continue;  // ring r only
          for (const std::uint32_t j : cells_[std::size_t(y * kGrid + x)])
            if (const float d = glm::length(points_[j] - q); d < best_d) best_d = d, best = j;
        }
    return best;
  }

 private:
  static constexpr int kGrid = 64;
  static int coordinate(float x) { return std::clamp(int(x * float(kGrid)), 0, kGrid - 1); }
  static std::size_t cell(glm::vec2 p) { return std::size_t(coordinate(p.y) * kGrid + coordinate(p.x)); }
  std::span<const glm::vec2> points_;
  std::vector<std::vector<std::uint32_t>> cells_;
};

// The largest screen distance from a vertex of `now` to its nearest (in domain space) vertex of the
// same patch in `before`, both projected by `vp` into a w x h target.
double largest_move(const FramePoints& before, const FramePoints& now, const glm::mat4& vp, int w, int h) {
  auto screen = [&](const glm::vec3& p, glm::dvec2& s) {
    const glm::vec4 c = vp * glm::vec4(p, 1.0f);
    if (!(c.w > 0.0f)) return false;
    s = {(double(c.x) / c.w * 0.5 + 0.5) * w, (0.5 - double(c.y) / c.w * 0.5) * h};
    return true;
  };
  double largest = 0.0;
  for (std::size_t p = 0; p < now.size() && p < before.size(); ++p) {
    const PatchPoints& a = before[p];
    const PatchPoints& b = now[p];
    if (a.domain.empty() || b.domain.empty()) continue;  // culled in one of the frames
    const DomainGrid grid(a.domain);
    for (std::size_t i = 0; i < b.domain.size(); ++i) {
      const std::int64_t j = grid.nearest(b.domain[i]);
      glm::dvec2 sa, sb;
      if (j >= 0 && screen(a.position[std::size_t(j)], sa) && screen(b.position[i], sb))
        largest = std::max(largest, glm::length(sa - sb));
    }
  }
  return largest;
}

int run_dolly(const DollyOptions& o) {
  if (o.frames < 2 || o.frames > 10000) throw UsageError("--frames: must be in 2..10000");
  // The scene library's one route from settings to a model; each frame's view and LOD follow.
  const std::unique_ptr<PreparedScene> scene = prepare_bench_scene(o.s);
  const std::string& cage = scene->settings.cage;
  const ts::Partitioning partitioning = scene->settings.partitioning;
  const Scheme scheme = scene->settings.scheme;
  const SubdModel& model = scene->model;
  const SubdFactors& base_factors = scene->base_factors;
  Displacement* d = scene->displacement ? &*scene->displacement : nullptr;
  const ViewSetup& start = scene->view;
  const glm::vec3 from = start.camera.eye, target = start.camera.target;
  const glm::vec3 to = o.to ? *o.to : glm::mix(from, target, 0.5f);
  if (glm::length(to - target) <= 0.0f) throw UsageError("--to: equal to the camera target");
  Device device(device_options(o.s.threads));
  std::string error;
  auto fb = Framebuffer::create(start.width, start.height, ColorFormat::rgba8_unorm, &error);
  if (!fb) throw UsageError(error);

  using Clock = std::chrono::steady_clock;
  Json frames = Json::array();
  FramePoints before;
  std::vector<double> moves, times;
  const std::size_t quad_count = model.patches.quads.size();
  for (int f = 0; f < o.frames; ++f) {
    const float t = float(f) / float(o.frames - 1);
    const glm::vec3 eye = glm::mix(from, to, t);
    const ViewSetup view = view_at(o.s.camera, model, eye, target);
    SubdFactors factors = base_factors;
    PatchCull cull;
    apply_lod_options(o.s.lod, view, model, d, factors, cull);
    const auto t0 = Clock::now();
    device.clear(*fb, kBackgroundColor, 1.0f);
    const DrawResult r = render_surface(device, model, d, factors, cull, partitioning, SubdView::shaded, view.camera, *fb);
    if (!r.ok()) throw InputError(cage + ": " + r.error);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    // The same tessellation, streamed: where every vertex is.
    FramePoints now(quad_count + model.patches.tris.size());
    auto sink = [&](const auto& p, const PatchGroup& g) {
      PatchPoints& pts = now[(g.domain == ts::Domain::tri ? quad_count : 0) + p.patch_id];
      for (std::size_t i = 0; i < p.points.size(); ++i) {
        pts.domain.emplace_back(p.domain[i].u, p.domain[i].v);
        pts.position.push_back(p.points[i].position);
      }
    };
    const DrawResult s = stream_surface(device, model, d, factors, cull, partitioning, sink);
    if (!s.ok()) throw InputError(cage + ": " + s.error);
    const double move = f == 0 ? 0.0 : largest_move(before, now, view.camera.view_projection, view.width, view.height);
    before = std::move(now);
    if (f > 0) moves.push_back(move);
    times.push_back(seconds);
    frames.push_back({{"frame", f},
                      {"eye", {json_float(eye.x), json_float(eye.y), json_float(eye.z)}},
                      {"triangles", r.report.statistics.CInvocations},
                      {"patches_culled", r.report.patches_culled},
                      {"seconds", seconds},
                      {"largest_move_pixels", move}});
    log_debug("frame " + std::to_string(f) + ": " + std::to_string(r.report.statistics.CInvocations) +
              " triangles, largest move " + std::to_string(move) + " px");
  }
  std::vector<double> sorted = moves;
  std::sort(sorted.begin(), sorted.end());
  const double max_move = sorted.back(), median_move = sorted[sorted.size() / 2];
  std::sort(times.begin(), times.end());
  if (o.json) {
    const Json j = {{"scene", "dolly"},
                    {"cage", cage},
                    {"scheme", to_string(scheme)},
                    {"partitioning", std::string(ts::to_string(partitioning))},
                    {"lod", to_string(o.s.lod.mode)},
                    {"edge_pixels", json_float(o.s.lod.edge_pixels)},
                    {"frames", o.frames},
                    {"largest_move_pixels", max_move},
                    {"median_move_pixels", median_move},
                    {"median_frame_s", times[times.size() / 2]},
                    {"per_frame", frames}};
    std::cout << json_text(j) << "\n";
  } else {
    std::cout << cage << ", " << to_string(scheme) << ", " << ts::to_string(partitioning) << ", lod "
              << to_string(o.s.lod.mode) << ", " << o.frames << " frames: largest vertex move " << max_move
              << " px (median " << median_move << "), median frame " << times[times.size() / 2] << " s\n";
  }
  return kExitOk;
}

}  // namespace

Runner add_bench_dolly_command(CLI::App& bench) {
  auto o = std::make_shared<DollyOptions>();
  o->s.factor = 16.0f;
  o->s.partitioning = ts::Partitioning::fractional_odd;
  o->s.lod.mode = LodMode::screen;
  CLI::App* cmd = bench.add_subcommand(
      "dolly", "The camera moves toward its target with view-dependent LOD: per-frame triangles, time, vertex moves");
  cmd->add_option("--cage", o->s.cage, "the cage (default: the monster frog shipped with tessera)");
  add_model_settings_options(*cmd, o->s, PatchCullMode::all);
  add_setting_option(
      *cmd, "--to", o->to, [](const std::string& text) { return vec3_option(text, "--to"); },
      "x,y,z: where the camera ends (default: halfway to the target)");
  cmd->add_option("--frames", o->frames, "frames along the path")->capture_default_str();
  cmd->add_flag("--json", o->json, "print results (and every frame) as JSON");
  cmd->fallthrough();
  return [o, cmd]() -> int { return cmd->parsed() ? run_dolly(*o) : -1; };
}

}  // namespace tessera::cli
