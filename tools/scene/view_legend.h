// The legend of a debug view: a panel in a corner of the image (the lower left, unless the surface is
// there: legend_corner in view_legend.cpp) with a title, lines of text,
// and a colour bar with tick labels or a list of colour swatches. Text is drawn by the image codec
// (OpenImageIO's render_text) in DejaVu Sans at a size that follows the image height (readable at 1280x720),
// smaller and wrapped where the legend would not fit.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/framebuffer.h"
#include "shaders_cpp/image_io/image_file.h"
#include "tools/scene/render_settings.h"

namespace tessera::scene {

struct Legend {
  std::string title;
  std::vector<std::string> lines;
  // A colour bar: colours sampled left to right, and labels at positions in [0, 1].
  std::vector<glm::vec3> ramp;
  std::vector<std::pair<float, std::string>> ticks;
  // Or swatches: a colour and what it means.
  std::vector<std::pair<glm::vec3, std::string>> swatches;
};

// The fraction of an image `height` pixels tall that automatic framing keeps clear at the bottom for
// the legend of view `kind` (none for the views without one): a legend of five rows at the size
// write_with_legend draws it, with its margins, at most kMaxBottomBand. A taller legend, or a camera
// placed by hand, may still meet the surface; the legend then takes the corner where it covers least.
float legend_band(ViewKind kind, int height);

// Writes the framebuffer's colour with the legend drawn over it to `target` (a file, atomically, or
// memory). The text is drawn in the font shipped with tessera (share/tessera/DejaVuSans.ttf); on a
// small image it is made smaller and wrapped so that it stays whole. InputError if the font is
// missing or cannot draw (a legend is never written without its text) or the image cannot be written.
void write_with_legend(const Framebuffer& fb, const Legend& legend, const ImageTarget& target);

}  // namespace tessera::scene
