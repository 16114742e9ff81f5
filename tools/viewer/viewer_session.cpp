#include "tools/viewer/viewer_session.h"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "shaders_cpp/cage/bounding_box.h"
#include "tools/scene/common.h"
#include "tools/scene/render_stats.h"

namespace tessera::viewer {

using namespace scene;

namespace {

namespace fs = std::filesystem;

// Whether a kept scene loaded what `s` would load: the same scheme, displacement and glTF selection
// (the cage, factor file and normal map are the session's own and never change).
bool loads_alike(const RenderSettings& a, const RenderSettings& b) {
  return a.scheme == b.scheme && a.isolation == b.isolation && a.displacement == b.displacement &&
         a.asset.scene_index == b.asset.scene_index && a.asset.mesh == b.asset.mesh;
}

// Runs `f` when the scope ends, however it ends.
template <class F>
struct AtExit {
  F f;
  ~AtExit() { f(); }
};
template <class F>
AtExit(F) -> AtExit<F>;

}  // namespace

ViewerSession::ViewerSession(RenderSettings base, const PrepareStep& step)
    : base_(std::move(base)), device_(device_options(base_.threads)) {
  scenes_.push_front(prepare_scene(base_, [&](const char* name) {
    begin_step(name, true);
    if (step) step(name);
  }));
  end_steps();
}

void ViewerSession::begin_step(const std::string& step, bool loading) {
  std::lock_guard lock(progress_mutex_);
  if (loading && load_steps_.empty()) ++loads_;
  if (loading) load_steps_.push_back(step);
  step_ = step;
  step_start_ = std::chrono::steady_clock::now();
}

void ViewerSession::end_steps() {
  std::lock_guard lock(progress_mutex_);
  if (!load_steps_.empty()) last_load_ = std::move(load_steps_);
  load_steps_.clear();
  step_.clear();
}

Json ViewerSession::progress() const {
  std::lock_guard lock(progress_mutex_);
  const double s =
      step_.empty() ? 0.0 : std::chrono::duration<double>(std::chrono::steady_clock::now() - step_start_).count();
  return Json{{"busy", !step_.empty()}, {"step", step_}, {"step_s", s}, {"loads", loads_}, {"last_load", last_load_}};
}

PreparedScene& ViewerSession::scene_for(const RenderSettings& s) {
  for (auto it = scenes_.begin(); it != scenes_.end(); ++it) {
    if (!loads_alike((*it)->settings, s)) continue;
    begin_step("framing and factors");
    configure_scene(**it, s);
    scenes_.splice(scenes_.begin(), scenes_, it);
    return *scenes_.front();
  }
  auto fresh = prepare_scene(s, [this](const char* name) { begin_step(name, true); });
  scenes_.push_front(std::move(fresh));
  while (scenes_.size() > kKeptScenes) scenes_.pop_back();
  return *scenes_.front();
}

std::vector<RenderSettings> ViewerSession::turntable(const RenderSettings& s, int frames) {
  std::lock_guard lock(mutex_);
  const AtExit idle{[this] { end_steps(); }};
  PreparedScene& p = scene_for(s);
  std::vector<RenderSettings> out;
  const ViewSetup base = orbit_base(p.settings.camera, p.model, p.view, frames);
  for (int i = 0; i < frames; ++i) {
    const ViewSetup v = orbit_view(p.settings.camera, p.model, base, i, frames);
    RenderSettings t = s;
    t.camera.eye = v.camera.eye;
    t.camera.target = v.camera.target;
    out.push_back(std::move(t));
  }
  return out;
}

Json ViewerSession::info() {
  std::lock_guard lock(mutex_);
  const AtExit idle{[this] { end_steps(); }};
  PreparedScene& p = scene_for(base_);
  const Cage& cage = p.model.cage;
  const Box3 box = bounding_box(p.model.positions());
  Json animations = Json::array();
  if (p.model.rig)
    for (const Animation& a : p.model.rig->animations)
      animations.push_back({{"name", a.name}, {"start", json_float(a.start)}, {"end", json_float(a.end)}});
  // Only the schemes that draw this asset; the others with their reason (a request for one is a 422).
  Json schemes = Json::array(), refused = Json::object();
  for (int k = 0; k < kSchemeCount; ++k) {
    const std::string why = scheme_refusal(cage, Scheme(k), p.displacement.has_value());
    if (why.empty())
      schemes.push_back(to_string(Scheme(k)));
    else
      refused[to_string(Scheme(k))] = why;
  }
  Json views = Json::array();
  for (int k = 0; k <= int(ViewKind::culled); ++k) views.push_back(to_string(ViewKind(k)));
  return {{"asset", fs::path(base_.cage).filename().string()},
          {"vertices", cage.vertex_count()},
          {"faces", cage.face_count()},
          {"patches", p.model.patches.quads.size() + p.model.patches.tris.size()},
          {"animated", bool(p.model.rig)},
          {"animations", animations},
          {"displaced", p.displacement.has_value()},
          {"bounding_box", {{"min", json_vec3(box.lo)}, {"max", json_vec3(box.hi)}}},
          {"camera",
           {{"position", json_vec3(p.view.camera.eye)},
            {"target", json_vec3(p.view.camera.target)},
            {"up", json_vec3(p.view.camera.up)},
            {"fov", json_float(p.view.fov)}}},
          {"views", views},
          {"schemes", schemes},
          {"schemes_refused", refused},
          {"settings", settings_json(base_)},
          {"settable", settable_settings()}};
}

std::optional<ViewerFrame> ViewerSession::frame(const RenderSettings& s, FrameFormat format,
                                                const std::function<bool()>& wanted) {
  std::lock_guard lock(mutex_);
  if (wanted && !wanted()) return std::nullopt;
  const AtExit idle{[this] { end_steps(); }};  // progress() goes back to idle however the call ends
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const auto t0 = Clock::now();
  PreparedScene& p = scene_for(s);
  const auto t1 = Clock::now();
  begin_step("drawing");
  SceneImage image = render_scene(device_, p, false, std::move(spare_));
  spare_.reset();
  const auto t2 = Clock::now();
  // Encoded by render's own writer, in memory, so the bytes are the ones `tessera render` writes.
  ViewerFrame f;
  begin_step("encoding");
  write_scene_image(image, {format == FrameFormat::png ? "frame.png" : "frame.jpg", &f.bytes});
  f.configure_s = seconds(t0, t1);
  f.render_s = seconds(t1, t2);
  f.encode_s = seconds(t2, Clock::now());
  if (f.bytes.empty()) throw InputError("tessera view: the frame's image came out empty");
  f.content_type = format == FrameFormat::png ? "image/png" : "image/jpeg";
  f.summary = scene_summary("", p, image);
  f.summary.erase("output");
  spare_ = std::move(image.fb);
  return f;
}

Json ViewerSession::pick(const RenderSettings& s, int x, int y) {
  std::lock_guard lock(mutex_);
  const AtExit idle{[this] { end_steps(); }};
  PreparedScene& p = scene_for(s);
  if (x < 0 || y < 0 || x >= p.view.width || y >= p.view.height)
    throw RequestError("x, y: (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the " +
                       std::to_string(p.view.width) + "x" + std::to_string(p.view.height) + " frame");
  const std::string key = json_text(scene_json(s, ""));
  if (!pick_ || pick_->key != key) {
    pick_.reset();
    const ViewInputs inputs = p.inputs();
    PickBuffer b{key, std::nullopt, view_patch_tables(inputs)};
    std::string error;
    b.ids = Framebuffer::create(p.view.width, p.view.height, ColorFormat::rgba8_unorm, &error);
    if (!b.ids) throw UsageError(error);
    const DrawResult r = render_pick_buffer(device_, p.settings.view, inputs, b.tables, *b.ids);
    if (!r.ok()) throw InputError(base_.cage + ": " + r.error);
    pick_ = std::move(b);
  }
  const Framebuffer& ids = *pick_->ids;
  const PatchTables& tables = pick_->tables;
  const std::size_t at = (std::size_t(y) * std::size_t(p.view.width) + std::size_t(x)) * 4;
  const auto& c = ids.color_bytes();
  const std::uint32_t code = c[at] | (std::uint32_t(c[at + 1]) << 8) | (std::uint32_t(c[at + 2]) << 16);
  std::size_t index = 0;
  const PatchInfo* row = picked_patch(tables, code, &index);
  Json j = {{"x", x}, {"y", y}};
  if (row == nullptr) {
    j["patch"] = nullptr;
    return j;
  }
  Json patch = patch_row(*row, index);
  const auto& combos = tables.combinations.combinations;
  if (row->combination >= 0 && std::size_t(row->combination) < combos.size())
    patch["combination_text"] = combos[std::size_t(row->combination)].text;
  j["patch"] = patch;
  return j;
}

Json ViewerSession::command(const RenderSettings& s) const {
  const std::vector<std::string> words = render_arguments(s, "frame.png");
  std::vector<std::string> line = {"tessera"};
  line.insert(line.end(), words.begin(), words.end());
  return {{"command", shell_words(line)}, {"arguments", words}, {"scene", scene_json(s, "")}};
}

}  // namespace tessera::viewer
