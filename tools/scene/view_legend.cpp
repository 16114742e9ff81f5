#include "tools/scene/view_legend.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "shaders_cpp/image_io/image_file.h"
#include "shaders_cpp/render/surface_framing.h"
#include "tools/scene/common.h"

namespace tessera::scene {
namespace {

// Draws on RGBA float pixels, text in `font` (DejaVu Sans, shipped with tessera: a font found on the
// machine would make a legend's pixels depend on the machine).
struct Painter {
  FloatImageView img;
  std::string font;
  void fill(int x0, int y0, int x1, int y1, glm::vec3 c, float alpha) {
    for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
      for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) {
        float* px = img.pixels + (std::size_t(y) * std::size_t(img.width) + std::size_t(x)) * 4;
        for (int k = 0; k < 3; ++k) px[k] = px[k] + alpha * (c[k] - px[k]);
      }
  }
  // A legend is never drawn without its text: a font that cannot draw is an error.
  void text(int x, int y, const std::string& s, int size, TextAlignX ax) {
    if (s.empty()) return;
    const float ink[4] = {0.06f, 0.06f, 0.08f, 1.0f};
    if (std::string e =
            image_codec().draw_text(img, x, y, s, size, font, std::span<const float>(ink), ax, TextAlignY::baseline);
        !e.empty())
      throw InputError(font + ": cannot draw the legend's text (" + e + ")");
  }
};

// DejaVu Sans averages about 0.56 em per character: the width of n characters at `size` pixels.
int text_width(std::size_t n, int size) { return int(float(n) * float(size) * 0.56f); }

// `text` broken at spaces into lines of at most `chars` characters (a longer word is cut).
std::vector<std::string> wrap(const std::string& text, std::size_t chars) {
  std::vector<std::string> out;
  std::string current;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t end = std::min(text.find(' ', i), text.size());
    std::string word = text.substr(i, end - i);
    i = end + 1;
    while (word.size() > chars) {
      if (!current.empty()) out.push_back(current), current.clear();
      out.push_back(word.substr(0, chars));
      word = word.substr(chars);
    }
    if (current.empty())
      current = word;
    else if (current.size() + 1 + word.size() <= chars)
      current += " " + word;
    else
      out.push_back(current), current = word;
  }
  if (!current.empty() || out.empty()) out.push_back(current);
  return out;
}

// The legend's text size at an image height (h / 40, 11 to 40 pixels; readable at 1280x720), before
// any shrinking to fit, and the row height and padding that follow from a text size.
int first_text_size(int height) { return std::clamp(height / 40, 11, 40); }
int row_height(int text_size) { return text_size * 5 / 4; }
int padding(int text_size) { return text_size * 2 / 3; }

// The legend's text size and its lines as drawn. The size follows the image height (h / 40, 11 to 40
// pixels; readable at 1280x720). A legend whose longest line does not fit across the image, or whose
// panel with its margins would be taller than the band framing keeps for it (kMaxBottomBand of the
// height), gets a smaller size (down to 7 pixels) and its lines wrapped to the width, so a small image
// (a suite's 320x180) keeps its text whole and most of its picture.
struct LegendLayout {
  int text_size = 11;
  int text_w = 0;  // the longest line's width
  std::vector<std::string> title, lines;
  std::vector<std::pair<glm::vec3, std::vector<std::string>>> swatches;
};
LegendLayout layout_legend(const Legend& legend, int w, int h) {
  const int extra_rows = legend.ramp.empty() ? 0 : 2;
  const auto lay_out = [&](int size, std::size_t chars) {
    LegendLayout l;
    l.text_size = size;
    l.title = wrap(legend.title, chars);
    for (const auto& s : legend.lines)
      for (auto& piece : wrap(s, chars)) l.lines.push_back(std::move(piece));
    std::size_t longest = 0;
    for (const auto& s : l.title) longest = std::max(longest, s.size());
    for (const auto& s : l.lines) longest = std::max(longest, s.size());
    for (const auto& [color, label] : legend.swatches) {
      l.swatches.emplace_back(color, wrap(label, chars > 3 ? chars - 3 : 1));
      for (const auto& s : l.swatches.back().second) longest = std::max(longest, s.size() + 3);
    }
    l.text_w = text_width(longest, size);
    return l;
  };
  const auto fits = [&](const LegendLayout& l) {
    const int pad = padding(l.text_size), line = row_height(l.text_size);
    std::size_t rows = l.title.size() + l.lines.size() + std::size_t(extra_rows);
    for (const auto& sw : l.swatches) rows += sw.second.size();
    return l.text_w + 4 * pad <= w && float(int(rows) * line + 4 * pad) <= kMaxBottomBand * float(h);
  };
  const std::size_t unwrapped = std::string::npos;
  const int first = first_text_size(h);
  LegendLayout l = lay_out(first, unwrapped);
  if (fits(l)) return l;  // as every legend was drawn before sizes were fitted
  for (int size = first; size >= 7; --size) {
    const int pad = padding(size);
    const std::size_t chars = std::size_t(std::max(8, int(float(w - 4 * pad) / (float(size) * 0.56f))));
    l = lay_out(size, chars);
    if (fits(l)) return l;
  }
  return l;  // the smallest size, wrapped: taller than half the image, but whole
}

// Where the legend's panel goes: the first corner (lower left, lower right, upper left, upper right)
// where it covers no surface (a pixel whose depth is not the clear's 1.0), else the corner where it
// covers the fewest such pixels.
std::pair<int, int> legend_corner(const Framebuffer& fb, int panel_w, int panel_h, int pad) {
  const int w = fb.width(), h = fb.height();
  const std::array<std::pair<int, int>, 4> corners{{{pad, h - pad - panel_h},
                                                     {w - pad - panel_w, h - pad - panel_h},
                                                     {pad, pad},
                                                     {w - pad - panel_w, pad}}};
  std::pair<int, int> best = corners[0];
  std::int64_t fewest = -1;
  for (const auto& [x0, y0] : corners) {
    std::int64_t covered = 0;
    for (int y = std::max(0, y0); y < std::min(h, y0 + panel_h); ++y)
      for (int x = std::max(0, x0); x < std::min(w, x0 + panel_w); ++x) covered += fb.depth(x, y) < 1.0f ? 1 : 0;
    if (covered == 0) return {x0, y0};
    if (fewest < 0 || covered < fewest) fewest = covered, best = {x0, y0};
  }
  return best;
}

}  // namespace

float legend_band(ViewKind kind, int height) {
  if (kind == ViewKind::shaded || kind == ViewKind::wireframe || kind == ViewKind::wire_on_shaded || height <= 0)
    return 0.0f;
  constexpr int kRows = 5;
  const int text_size = first_text_size(height), line = row_height(text_size), pad = padding(text_size);
  return std::min(kMaxBottomBand, float(kRows * line + 4 * pad) / float(height));
}

void write_with_legend(const Framebuffer& fb, const Legend& legend, const ImageTarget& target) {
  const int w = fb.width(), h = fb.height();
  std::vector<float> rgba(std::size_t(w) * std::size_t(h) * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec4 c = fb.color(x, y);
      float* px = &rgba[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
      px[0] = c.r, px[1] = c.g, px[2] = c.b, px[3] = 1.0f;
    }
  Painter paint{FloatImageView{rgba.data(), w, h, 4},
                shared_data_file("DejaVuSans.ttf", "--view shaded, which has no legend")};
  using AX = TextAlignX;
  const LegendLayout lay = layout_legend(legend, w, h);
  const int text_size = lay.text_size, line = row_height(text_size), pad = padding(text_size);
  const int bar_w = std::min(w - 6 * pad, text_size * 22), bar_h = text_size;
  int rows = int(lay.title.size() + lay.lines.size());
  for (const auto& sw : lay.swatches) rows += int(sw.second.size());
  if (!legend.ramp.empty()) rows += 2;
  const int panel_w = std::min(
      w - 2 * pad, std::max(legend.ramp.empty() ? 0 : bar_w + 2 * pad + 2 * text_size, lay.text_w + 2 * pad));
  const int panel_h = rows * line + 2 * pad;
  // Text drawn past the image's edge is not drawn whole (and OpenImageIO's text renderer asserts on
  // some such positions): an image too small for the legend even at its smallest size is refused.
  if (panel_w + 2 * pad > w || panel_h + 2 * pad > h || lay.text_w + 2 * pad > panel_w)
    throw InputError(target.path + ": " + std::to_string(w) + "x" + std::to_string(h) + " is too small for the legend \"" +
                     legend.title + "\" (about " + std::to_string(lay.text_w + 4 * pad) + "x" +
                     std::to_string(panel_h + 2 * pad) + " at the least); render larger, or --view shaded");
  const auto [x0, y0] = legend_corner(fb, panel_w, panel_h, pad);
  paint.fill(x0, y0, x0 + panel_w, y0 + panel_h, glm::vec3(1.0f), 0.82f);
  int y = y0 + pad + text_size - line;
  for (const std::string& s : lay.title) paint.text(x0 + pad, y += line, s, text_size, AX::left);
  for (const std::string& s : lay.lines) paint.text(x0 + pad, y += line, s, text_size * 9 / 10, AX::left);
  for (const auto& [color, label] : lay.swatches) {
    y += line;
    paint.fill(x0 + pad, y - text_size * 4 / 5, x0 + pad + text_size, y + text_size / 5, color, 1.0f);
    paint.text(x0 + pad + text_size * 3 / 2, y, label.front(), text_size * 9 / 10, AX::left);
    for (std::size_t k = 1; k < label.size(); ++k)
      paint.text(x0 + pad + text_size * 3 / 2, y += line, label[k], text_size * 9 / 10, AX::left);
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
  // RGBA (alpha 1) as every view without a legend is written, stored as the framebuffer's format
  // (8-bit or float): a suite's images all have four channels.
  const PixelType stored = fb.format() == ColorFormat::rgba8_unorm ? PixelType::u8 : PixelType::f32;
  if (std::string e = write_image(target, ImageLayout{w, h, 4, stored}, PixelType::f32, rgba.data()); !e.empty())
    throw InputError(e);
}

}  // namespace tessera::scene
