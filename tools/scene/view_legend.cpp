#include "tools/scene/view_legend.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "shaders_cpp/image_io/image_file.h"
#include "tools/scene/common.h"

namespace tessera::cli {
namespace {

const char* const kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// Draws on RGBA float pixels.
struct Painter {
  FloatImageView img;
  bool font_ok = true;
  void fill(int x0, int y0, int x1, int y1, glm::vec3 c, float alpha) {
    for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
      for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) {
        float* px = img.pixels + (std::size_t(y) * std::size_t(img.width) + std::size_t(x)) * 4;
        for (int k = 0; k < 3; ++k) px[k] = px[k] + alpha * (c[k] - px[k]);
      }
  }
  void text(int x, int y, const std::string& s, int size, TextAlignX ax) {
    if (!font_ok || s.empty()) return;
    const float ink[4] = {0.06f, 0.06f, 0.08f, 1.0f};
    if (!image_codec()
             .draw_text(img, x, y, s, size, kFont, std::span<const float>(ink), ax, TextAlignY::baseline)
             .empty()) {
      log_info(std::string("cannot draw the legend's text (font ") + kFont + "; install fonts-dejavu-core)");
      font_ok = false;
    }
  }
};

}  // namespace

void write_with_legend(const Framebuffer& fb, const Legend& legend, const ImageTarget& target) {
  const int w = fb.width(), h = fb.height();
  std::vector<float> rgba(std::size_t(w) * std::size_t(h) * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec4 c = fb.color(x, y);
      float* px = &rgba[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
      px[0] = c.r, px[1] = c.g, px[2] = c.b, px[3] = 1.0f;
    }
  Painter paint{FloatImageView{rgba.data(), w, h, 4}};
  using AX = TextAlignX;
  const int text_size = std::clamp(h / 40, 11, 40), line = text_size * 5 / 4, pad = text_size * 2 / 3;
  const int bar_w = std::min(w - 6 * pad, text_size * 22), bar_h = text_size;
  int rows = 1 + int(legend.lines.size()) + int(legend.swatches.size());
  if (!legend.ramp.empty()) rows += 2;
  // DejaVu Sans averages about 0.55 em per character; the panel fits the longest line.
  std::size_t longest = legend.title.size();
  for (const auto& s : legend.lines) longest = std::max(longest, s.size());
  for (const auto& sw : legend.swatches) longest = std::max(longest, sw.second.size() + 3);
  const int text_w = int(float(longest) * float(text_size) * 0.56f);
  const int panel_w =
      std::min(w - 2 * pad, std::max(legend.ramp.empty() ? 0 : bar_w + 2 * pad + 2 * text_size, text_w + 2 * pad));
  const int panel_h = rows * line + 2 * pad;
  const int x0 = pad, y0 = h - pad - panel_h;
  paint.fill(x0, y0, x0 + panel_w, y0 + panel_h, glm::vec3(1.0f), 0.82f);
  int y = y0 + pad + text_size;
  paint.text(x0 + pad, y, legend.title, text_size, AX::left);
  for (const std::string& s : legend.lines) paint.text(x0 + pad, y += line, s, text_size * 9 / 10, AX::left);
  for (const auto& [color, label] : legend.swatches) {
    y += line;
    paint.fill(x0 + pad, y - text_size * 4 / 5, x0 + pad + text_size, y + text_size / 5, color, 1.0f);
    paint.text(x0 + pad + text_size * 3 / 2, y, label, text_size * 9 / 10, AX::left);
  }
  if (!legend.ramp.empty()) {
    const int bx = x0 + pad + text_size, by = y + line / 2;
    const int n = int(legend.ramp.size());
    for (int i = 0; i < bar_w; ++i) {
      const glm::vec3 c = legend.ramp[std::size_t(std::min(n - 1, i * n / bar_w))];
      paint.fill(bx + i, by, bx + i + 1, by + bar_h, c, 1.0f);
    }
    for (const auto& [t, label] : legend.ticks) {
      const int tx = bx + int(t * float(bar_w - 1));
      paint.fill(tx, by + bar_h, tx + 1, by + bar_h + text_size / 3, glm::vec3(0.1f), 1.0f);
      paint.text(tx, by + bar_h + text_size * 4 / 3, label, text_size * 4 / 5, AX::center);
    }
  }
  // RGB of the float pixels, stored as the framebuffer's format (8-bit or float).
  std::vector<float> rgb(std::size_t(w) * std::size_t(h) * 3);
  for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h); ++i)
    for (std::size_t k = 0; k < 3; ++k) rgb[i * 3 + k] = rgba[i * 4 + k];
  const PixelType stored = fb.format() == ColorFormat::rgba8_unorm ? PixelType::u8 : PixelType::f32;
  if (std::string e = write_image(target, ImageLayout{w, h, 3, stored}, PixelType::f32, rgb.data()); !e.empty())
    throw InputError(e);
}

}  // namespace tessera::cli
