// What a `tessera view` request may change, and the command line that reproduces a frame.
//
// Contract
// - A request names settings like the command line's options, without the dashes
//   (`factor=12&view=factors&camera-position=0,1,5`); only the settings listed by
//   settable_settings() exist: no path (cage, maps, factor files) can come from a request.
//   Values are read by the same option parser as `tessera render`'s, so a request and a command
//   line with the same text mean the same settings.
// - settings_from_query() starts from the settings the viewer was started with; it throws
//   RequestError (one line: the setting and why) for an unknown or repeated name, a value the
//   parser refuses, or a resolution beyond kMaxViewerPixels. Values the parser accepts but a render
//   refuses (a NaN factor, a camera at its target) are the render's to refuse (UsageError).
// - render_arguments(s) are the words after `tessera` of the `render` command that draws the
//   frame `s` describes, given the output path: options at their defaults are left out, floats are
//   written in their shortest round-trip text, so the command gives the same bytes as the viewer.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "tools/scene/scene_file.h"

namespace tessera::viewer {

struct RequestError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using QueryParams = std::vector<std::pair<std::string, std::string>>;

// The names a request may set (the options of `tessera render` without the dashes).
const std::vector<std::string>& settable_settings();
// Names a request may carry beside settings (format, x, y, client, seq): not settings, ignored here.
bool is_request_parameter(const std::string& name);

// A frame's largest width and height in pixels, and its largest pixel count (about 16 megapixels).
inline constexpr int kMaxViewerSide = 8192;
inline constexpr long long kMaxViewerPixels = 4096LL * 4096LL;

scene::RenderSettings settings_from_query(const scene::RenderSettings& base, const QueryParams& query);

// Each settable setting's value in `s`, as a request would write it (defaults included).
scene::Json settings_json(const scene::RenderSettings& s);

std::vector<std::string> render_arguments(const scene::RenderSettings& s, const std::string& output);
// The words as one POSIX shell command line (each quoted where the shell would split or expand it).
std::string shell_words(const std::vector<std::string>& words);

}  // namespace tessera::viewer
