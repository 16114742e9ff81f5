#include "tools/viewer/viewer_session.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "tools/cli_common.h"
#include "tools/render_stats.h"

namespace tessera::cli {
namespace {

namespace fs = std::filesystem;

// Whether a kept scene loaded what `s` would load: the same scheme, displacement and glTF selection
// (the cage, factor file and normal map are the session's own and never change).
bool loads_alike(const RenderSettings& a, const RenderSettings& b) {
  return a.scheme == b.scheme && a.displacement == b.displacement && a.asset.scene_index == b.asset.scene_index &&
         a.asset.mesh == b.asset.mesh;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Json vec_json(glm::vec3 v) { return Json::array({json_float(v.x), json_float(v.y), json_float(v.z)}); }

}  // namespace

ViewerSession::ViewerSession(RenderSettings base) : base_(std::move(base)), device_(device_options(base_.threads)) {
  std::string pattern = (fs::temp_directory_path() / "tessera-view-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw InputError("tessera view: cannot make a directory for frames in " + fs::temp_directory_path().string());
  temp_dir_ = pattern;
  try {
    scenes_.push_front(prepare_scene(base_));
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(temp_dir_, ignored);
    throw;
  }
}

ViewerSession::~ViewerSession() {
  std::error_code ignored;
  fs::remove_all(temp_dir_, ignored);
}

PreparedScene& ViewerSession::scene_for(const RenderSettings& s) {
  for (auto it = scenes_.begin(); it != scenes_.end(); ++it) {
    if (!loads_alike((*it)->settings, s)) continue;
    configure_scene(**it, s);
    scenes_.splice(scenes_.begin(), scenes_, it);
    return *scenes_.front();
  }
  auto fresh = prepare_scene(s);
  scenes_.push_front(std::move(fresh));
  while (scenes_.size() > kKeptScenes) scenes_.pop_back();
  return *scenes_.front();
}

namespace {
// A vector as the CLI's x,y,z option text (shortest round-trip floats).
std::string vec_text(glm::vec3 v) { return float_text(v.x) + "," + float_text(v.y) + "," + float_text(v.z); }
}  // namespace

std::vector<RenderSettings> ViewerSession::turntable(const RenderSettings& s, int frames) {
  std::lock_guard lock(mutex_);
  PreparedScene& p = scene_for(s);
  std::vector<RenderSettings> out;
  for (int i = 0; i < frames; ++i) {
    const ViewSetup v = orbit_view(s.camera, p.model.cage, p.view, i, frames);
    RenderSettings t = s;
    t.camera.eye = vec_text(v.camera.eye);
    t.camera.target = vec_text(v.camera.target);
    out.push_back(std::move(t));
  }
  return out;
}

Json ViewerSession::info() {
  std::lock_guard lock(mutex_);
  PreparedScene& p = scene_for(base_);
  const Cage& cage = p.model.cage;
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& v : p.model.positions()) lo = glm::min(lo, v), hi = glm::max(hi, v);
  Json animations = Json::array();
  if (p.model.rig)
    for (const Animation& a : p.model.rig->animations)
      animations.push_back({{"name", a.name}, {"start", json_float(a.start)}, {"end", json_float(a.end)}});
  Json views = Json::array();
  for (int k = 0; k <= int(ViewKind::culled); ++k) views.push_back(to_string(ViewKind(k)));
  return {{"asset", fs::path(base_.cage).filename().string()},
          {"vertices", cage.vertex_count()},
          {"faces", cage.face_count()},
          {"patches", p.model.patches.quads.size() + p.model.patches.tris.size()},
          {"animated", bool(p.model.rig)},
          {"animations", animations},
          {"displaced", p.displacement.has_value()},
          {"bounding_box", {{"min", vec_json(lo)}, {"max", vec_json(hi)}}},
          {"camera",
           {{"position", vec_json(p.view.camera.eye)},
            {"target", vec_json(p.view.camera.target)},
            {"up", vec_json(p.view.camera.up)},
            {"fov", json_float(p.view.fov)}}},
          {"views", views},
          {"schemes", {"bspline", "acc", "gregory", "exact", "pn"}},
          {"settings", settings_json(base_)},
          {"settable", settable_settings()}};
}

std::optional<ViewerFrame> ViewerSession::frame(const RenderSettings& s, FrameFormat format,
                                                const std::function<bool()>& wanted) {
  std::lock_guard lock(mutex_);
  if (wanted && !wanted()) return std::nullopt;
  PreparedScene& p = scene_for(s);
  const SceneImage image = render_scene(device_, p, false);
  // Written by render's own writer, so the bytes are the ones `tessera render` writes.
  const fs::path file =
      temp_dir_ / ("frame-" + std::to_string(next_file_++) + (format == FrameFormat::png ? ".png" : ".jpg"));
  write_scene_image(image, file.string());
  ViewerFrame f;
  f.bytes = read_file(file);
  std::error_code ignored;
  fs::remove(file, ignored);
  if (f.bytes.empty()) throw InputError("tessera view: the frame's image came out empty");
  f.content_type = format == FrameFormat::png ? "image/png" : "image/jpeg";
  f.summary = scene_summary("", p, image);
  f.summary.erase("output");
  return f;
}

Json ViewerSession::pick(const RenderSettings& s, int x, int y) {
  std::lock_guard lock(mutex_);
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
    const DrawResult r = render_pick_buffer(device_, p.kind, inputs, b.tables, *b.ids);
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

}  // namespace tessera::cli
