// The state behind `tessera view`: one asset, the settings it was started with, and the frames,
// picks and reproducing commands of the settings a request asks for. Independent of HTTP (the
// server, viewer_server.h, turns requests into calls here), so tests call it directly too.
//
// Contract
// - frame(s) draws exactly what `tessera render` with render_arguments(s) draws and encodes it with
//   the same writer into the same bytes (PNG; JPEG frames, for a moving camera, are the same pixels
//   compressed with loss).
// - Prepared scenes are kept by what loading decides (scheme, displacement, glTF selection); a change
//   of camera, factors, LOD, view or time reconfigures a kept scene (configure_scene), which gives
//   the bytes of a fresh one. At most kKeptScenes are kept, the least recently used dropped.
// - Calls are serialised (one draw at a time, on all the session's threads): safe from any thread.
// - Errors: RequestError or UsageError for settings a render refuses (the caller's fault, HTTP 400);
//   anything else is the asset's or the machine's (HTTP 500).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "pipeline/device.h"
#include "tools/scene/scene_render.h"
#include "tools/viewer/viewer_settings.h"

namespace tessera::viewer {

enum class FrameFormat : std::uint8_t { png, jpeg };

struct ViewerFrame {
  std::string bytes;         // the encoded image
  std::string content_type;  // image/png or image/jpeg
  scene::Json summary;              // as `render --json` prints it (times and memory included)
  // Where the frame's time went (seconds): configuring the kept scene for the settings (pose, view,
  // LOD, culling), drawing it (render_scene: target, draw, resolve), and encoding the image.
  double configure_s = 0.0, render_s = 0.0, encode_s = 0.0;
};

class ViewerSession {
 public:
  static constexpr std::size_t kKeptScenes = 3;

  // Loads the asset of `base` (its errors as `tessera render` gives them), telling `step` as each
  // step of the preparation starts.
  explicit ViewerSession(scene::RenderSettings base, const PrepareStep& step = {});
  ViewerSession(const ViewerSession&) = delete;
  ViewerSession& operator=(const ViewerSession&) = delete;

  const scene::RenderSettings& base() const { return base_; }
  // The asset and what the page needs to build its controls: names, counts, animations and their time
  // ranges, the bounding box, the framing camera, the views, the schemes that draw it (and those that
  // refuse it, with why) and the starting settings.
  scene::Json info();

  // `wanted`, when given, is asked once the session's turn comes: a frame nobody wants any more (a
  // newer camera arrived while it waited) is not drawn, and nothing is returned.
  std::optional<ViewerFrame> frame(const scene::RenderSettings& s, FrameFormat format,
                                   const std::function<bool()>& wanted = {});
  // The patch under pixel (x, y) of frame(s) (x right, y down from the top-left): its --stats row
  // (render_stats.h) with the combination's text, or {"patch": null} over the background. The id
  // buffer is kept: further picks with the same settings read it without drawing.
  scene::Json pick(const scene::RenderSettings& s, int x, int y);
  // The settings of `frames` views turned about the up axis around `s`'s camera (render --orbit's
  // turntable), from the kept scene: no second load of the asset.
  std::vector<scene::RenderSettings> turntable(const scene::RenderSettings& s, int frames);
  // The reproducing command (as words and as one shell line) and the scene file of `s`.
  scene::Json command(const scene::RenderSettings& s) const;

  // What the session is doing, for a page waiting on a frame; safe to call while a frame is drawn (it
  // takes none of the draws' locks): {"busy", "step" (a load's steps as `tessera render -v` names them,
  // "framing and factors" for a kept scene, "drawing", "encoding"), "step_s" (seconds in it), "loads"
  // (loads of the asset so far, the first included) and "last_load" (the steps of the last one)}.
  scene::Json progress() const;

 private:
  scene::PreparedScene& scene_for(const scene::RenderSettings& s);

  scene::RenderSettings base_;
  std::mutex mutex_;
  Device device_;
  std::list<std::unique_ptr<scene::PreparedScene>> scenes_;  // most recently used first
  // The last pick's id buffer and patch tables, kept for further clicks on the same frame.
  struct PickBuffer {
    std::string key;  // the settings' scene JSON
    std::optional<Framebuffer> ids;
    PatchTables tables;
  };
  std::optional<PickBuffer> pick_;
  std::optional<Framebuffer> spare_;  // the last frame's target, drawn into again at the same size

  // progress(): written by the call that holds `mutex_`, read by anyone under `progress_mutex_`.
  void begin_step(const std::string& step, bool loading = false);
  void end_steps();
  mutable std::mutex progress_mutex_;
  std::string step_;
  std::chrono::steady_clock::time_point step_start_{};
  std::vector<std::string> load_steps_, last_load_;
  int loads_ = 0;
};

}  // namespace tessera::viewer
