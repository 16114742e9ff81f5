#include "tools/cli/pattern_image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "shaders_cpp/image_io/image_file.h"
#include "tools/scene/common.h"

namespace tessera::cli {

using namespace scene;

namespace {

constexpr int kSupersample = 3;
const char* const kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

struct Rgb {
  float r, g, b;
};
struct P2 {
  double x, y;
};

// A supersampled RGB canvas with the few primitives the picture needs.
class Canvas {
 public:
  explicit Canvas(int size) : w_(size * kSupersample), px_(std::size_t(w_) * std::size_t(w_), Rgb{1, 1, 1}) {}

  void triangle(P2 a, P2 b, P2 c, Rgb color) {
    a = scale(a), b = scale(b), c = scale(c);
    const int x0 = clampi(std::floor(std::min({a.x, b.x, c.x}))), x1 = clampi(std::ceil(std::max({a.x, b.x, c.x})));
    const int y0 = clampi(std::floor(std::min({a.y, b.y, c.y}))), y1 = clampi(std::ceil(std::max({a.y, b.y, c.y})));
    const double area = cross(a, b, c);
    if (area == 0) return;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const P2 p{x + 0.5, y + 0.5};
        const double e0 = cross(b, c, p) / area, e1 = cross(c, a, p) / area, e2 = cross(a, b, p) / area;
        if (e0 >= 0 && e1 >= 0 && e2 >= 0) at(x, y) = color;
      }
  }

  void line(P2 a, P2 b, double width_px, Rgb color) {
    a = scale(a), b = scale(b);
    const double r = width_px * kSupersample / 2;
    const int x0 = clampi(std::floor(std::min(a.x, b.x) - r)), x1 = clampi(std::ceil(std::max(a.x, b.x) + r));
    const int y0 = clampi(std::floor(std::min(a.y, b.y) - r)), y1 = clampi(std::ceil(std::max(a.y, b.y) + r));
    const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5 - a.x, py = y + 0.5 - a.y;
        const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
        const double ex = px - t * dx, ey = py - t * dy;
        if (ex * ex + ey * ey <= r * r) at(x, y) = color;
      }
  }

  void dot(P2 c, double radius_px, Rgb color) { line(c, c, radius_px * 2, color); }

  // Box-filters down to the output resolution: RGB floats, row 0 at the top.
  std::vector<float> resolve() const {
    const int size = w_ / kSupersample;
    std::vector<float> out(std::size_t(size) * std::size_t(size) * 3);
    for (int y = 0; y < size; ++y) {
      float* row = &out[std::size_t(y) * std::size_t(size) * 3];
      for (int x = 0; x < size; ++x) {
        Rgb sum{0, 0, 0};
        for (int sy = 0; sy < kSupersample; ++sy)
          for (int sx = 0; sx < kSupersample; ++sx) {
            const Rgb& p =
                px_[std::size_t(y * kSupersample + sy) * std::size_t(w_) + std::size_t(x * kSupersample + sx)];
            sum.r += p.r, sum.g += p.g, sum.b += p.b;
          }
        const float n = float(kSupersample * kSupersample);
        float* out_pixel = &row[std::size_t(x) * 3];
        out_pixel[0] = sum.r / n;
        out_pixel[1] = sum.g / n;
        out_pixel[2] = sum.b / n;
      }
    }
    return out;
  }

 private:
  static double cross(P2 a, P2 b, P2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }
  P2 scale(P2 p) const { return {p.x * kSupersample, p.y * kSupersample}; }
  int clampi(double v) const { return std::clamp(static_cast<int>(v), 0, w_ - 1); }
  Rgb& at(int x, int y) { return px_[std::size_t(y) * std::size_t(w_) + std::size_t(x)]; }

  int w_;
  std::vector<Rgb> px_;
};

// Where domain coordinates land on the picture. Quads and isolines: u right, v down (the D3D11
// spec's picture). Triangles: an equilateral triangle with u = 1 bottom right, v = 1 at the top,
// w = 1 bottom left.
struct Layout {
  ts::Domain domain;
  double left, top, extent;
  P2 map(const ts::DomainPoint& p) const {
    if (domain != ts::Domain::tri) return {left + p.u * extent, top + p.v * extent};
    const double h = extent * std::sqrt(3.0) / 2;
    const double w = 1.0 - p.u - p.v;
    const P2 U{left + extent, top + h}, V{left + extent / 2, top}, W{left, top + h};
    return {p.u * U.x + p.v * V.x + w * W.x, p.u * U.y + p.v * V.y + w * W.y};
  }
};

constexpr Rgb kEdgeColor[4] = {
    {0.99f, 0.85f, 0.62f}, {0.72f, 0.88f, 0.98f}, {0.78f, 0.93f, 0.74f}, {0.92f, 0.80f, 0.96f}};
constexpr Rgb kInteriorColor{0.93f, 0.93f, 0.90f};
constexpr Rgb kInvertedColor{0.95f, 0.15f, 0.12f};
constexpr Rgb kWire{0.25f, 0.27f, 0.32f};
constexpr Rgb kPointColor{0.10f, 0.20f, 0.55f};
constexpr Rgb kDomainColor{0.05f, 0.05f, 0.08f};

// Which outer edge a domain point lies on (-1: none).
int edge_of(ts::Domain d, const ts::DomainPoint& p) {
  if (d == ts::Domain::tri) {
    if (p.u == 0) return 0;
    if (p.v == 0) return 1;
    if ((1.0f - p.u) - p.v == 0) return 2;
    return -1;
  }
  if (p.u == 0) return 0;
  if (p.v == 0) return 1;
  if (p.u == 1) return 2;
  if (p.v == 1) return 3;
  return -1;
}

void text(const FloatImageView& img, int x, int y, const std::string& s, int size, TextAlignX ax, bool& font_ok) {
  if (!font_ok) return;
  const float black[3] = {0.08f, 0.08f, 0.1f};
  if (!image_codec()
           .draw_text(img, x, y, s, size, kFont, std::span<const float>(black), ax, TextAlignY::center)
           .empty()) {
    log_info(std::string("cannot draw text on the pattern image (font ") + kFont +
             "; install fonts-dejavu-core); drawing without labels");
    font_ok = false;
  }
}

std::string segments_text(const ts::EdgeContext& e) { return std::to_string(e.num_points - 1); }

}  // namespace

void write_pattern_image(const PatternPicture& pic, const std::string& path) {
  const ts::Pattern& pattern = *pic.pattern;
  const ts::Domain domain = pic.raw.domain;
  const double size = pic.size;
  const double margin = size * 0.12;
  Layout layout{domain, margin, margin * 1.15, size - 2 * margin};
  if (domain == ts::Domain::tri) layout.top += layout.extent * (1 - std::sqrt(3.0) / 2) / 2;
  Canvas canvas(pic.size);

  const int per = pattern.vertices_per_primitive();
  int inverted = 0, degenerate = 0;
  std::vector<P2> inverted_marks;
  if (per == 3) {
    for (std::size_t i = 0; i + 2 < pattern.indices.size(); i += 3) {
      const ts::DomainPoint a = pattern.points[pattern.indices[i]], b = pattern.points[pattern.indices[i + 1]],
                            c = pattern.points[pattern.indices[i + 2]];
      // Signed (u, v) area: positive for D3D triangle_cw; the fold quirk makes some negative.
      double area = (double(b.u) - a.u) * (double(c.v) - a.v) - (double(b.v) - a.v) * (double(c.u) - a.u);
      if (pattern.output == ts::OutputPrimitive::triangle_ccw) area = -area;
      Rgb color = kInteriorColor;
      for (const auto& p : {a, b, c}) {
        const int e = edge_of(domain, p);
        if (e >= 0) color = kEdgeColor[e];
      }
      if (area < 0) {
        color = kInvertedColor, ++inverted;
        // Folded slivers are too thin to see: mark them with a ring at their centroid.
        const ts::DomainPoint centre{(a.u + b.u + c.u) / 3, (a.v + b.v + c.v) / 3};
        inverted_marks.push_back(layout.map(centre));
      }
      if (area == 0) ++degenerate;
      canvas.triangle(layout.map(a), layout.map(b), layout.map(c), color);
    }
  }
  // The domain outline.
  if (domain == ts::Domain::tri) {
    const P2 U = layout.map({1, 0}), V = layout.map({0, 1}), W = layout.map({0, 0});
    canvas.line(U, V, 2.0, kDomainColor), canvas.line(V, W, 2.0, kDomainColor), canvas.line(W, U, 2.0, kDomainColor);
  } else {
    const P2 c[4] = {layout.map({0, 0}), layout.map({1, 0}), layout.map({1, 1}), layout.map({0, 1})};
    for (int i = 0; i < 4; ++i) canvas.line(c[i], c[(i + 1) % 4], 2.0, kDomainColor);
  }
  if (per >= 2) {
    const double width = pattern.points.size() > 1500 ? 0.8 : 1.3;
    for (std::size_t i = 0; i + std::size_t(per) <= pattern.indices.size(); i += std::size_t(per))
      for (int k = 0; k < per; ++k) {
        if (per == 2 && k == 1) break;
        canvas.line(layout.map(pattern.points[pattern.indices[i + std::size_t(k)]]),
                    layout.map(pattern.points[pattern.indices[i + std::size_t((k + 1) % per)]]), width,
                    per == 2 ? kPointColor : kWire);
      }
  }
  const double radius = pattern.points.size() > 1500 ? 1.4 : pattern.points.size() > 300 ? 2.2 : 3.2;
  for (const auto& p : pattern.points) canvas.dot(layout.map(p), radius, kPointColor);
  for (const auto& m : inverted_marks) {
    canvas.dot(m, 9.0, kInvertedColor);
    canvas.dot(m, 6.5, Rgb{1, 1, 1});
  }

  std::vector<float> pixels = canvas.resolve();
  const FloatImageView img{pixels.data(), pic.size, pic.size, 3};
  bool font_ok = true;
  using AX = TextAlignX;
  const int big = std::max(12, pic.size / 40), small = std::max(10, pic.size / 52);
  const auto& f = pic.raw.values;
  std::string title = std::string(ts::to_string(domain)) + "   " + std::string(ts::to_string(pic.partitioning)) +
                      "   " + std::string(ts::to_string(pattern.output));
  text(img, pic.size / 2, int(margin * 0.35), title, big, AX::center, font_ok);
  std::string counts = pattern.culled ? std::string("CULLED: an edge factor is <= 0, -0 or NaN")
                                      : std::to_string(pattern.points.size()) + " points, " +
                                            std::to_string(pattern.primitive_count()) +
                                            (per == 3   ? " triangles"
                                             : per == 2 ? " segments"
                                                        : " points");
  if (inverted) counts += ", " + std::to_string(inverted) + " inverted (red)";
  if (degenerate) counts += ", " + std::to_string(degenerate) + " zero-area";
  text(img, pic.size / 2, int(margin * 0.75), counts, small, AX::center, font_ok);

  // Factors along their edges: "name = raw -> segments".
  const auto& pf = pic.processed;
  auto label = [&](const char* name, float raw, const ts::EdgeContext* e, const char* sep = " = ",
                   const char* sep2 = "  ") {
    std::string s = name;
    s += sep;
    s += float_text(raw);
    if (e && !pf.culled) {
      s += sep2;
      if (pf.minimal) {
        s += "(1 seg)";
      } else {
        s += "(";
        s += segments_text(*e);
        s += " segs)";
      }
    }
    return s;
  };
  const double L = layout.left, T = layout.top, E = layout.extent;
  if (domain == ts::Domain::quad || domain == ts::Domain::isoline) {
    const bool quad = domain == ts::Domain::quad;
    if (quad) {
      text(img, int(L - 8), int(T + E / 2), label("Ueq0", f[0], &pf.outside[0], "\n= ", "\n"), small, AX::right,
           font_ok);
      text(img, int(L + E / 2), int(T - small), label("Veq0", f[1], &pf.outside[1]), small, AX::center, font_ok);
      text(img, int(L + E + 8), int(T + E / 2), label("Ueq1", f[2], &pf.outside[2], "\n= ", "\n"), small, AX::left,
           font_ok);
      text(img, int(L + E / 2), int(T + E + small), label("Veq1", f[3], &pf.outside[3]), small, AX::center, font_ok);
      text(img, pic.size / 2, int(T + E + 2.4 * small),
           "inside U = " + float_text(f[4]) +
               (pf.culled || pf.minimal ? "" : " (" + segments_text(pf.inside[0]) + ")") + ",  inside V = " +
               float_text(f[5]) + (pf.culled || pf.minimal ? "" : " (" + segments_text(pf.inside[1]) + ")"),
           small, AX::center, font_ok);
    } else {
      text(
          img, int(L - 8), int(T + E / 2),
          label("density", f[0], nullptr, "\n= ") + (pf.culled ? "" : "\n(" + segments_text(pf.outside[0]) + " lines)"),
          small, AX::right, font_ok);
      text(img, int(L + E / 2), int(T - small), label("detail", f[1], &pf.outside[1]), small, AX::center, font_ok);
    }
    text(img, int(L - 4), int(T - small), "(0,0)", small, AX::right, font_ok);
    text(img, int(L + E + 4), int(T + E + small), "(1,1)", small, AX::left, font_ok);
  } else {
    const P2 U = layout.map({1, 0}), V = layout.map({0, 1}), W = layout.map({0, 0});
    text(img, int((V.x + W.x) / 2 - 10), int((V.y + W.y) / 2), label("Ueq0", f[0], &pf.outside[0]), small, AX::right,
         font_ok);
    text(img, int((W.x + U.x) / 2), int(W.y + small * 1.4), label("Veq0", f[1], &pf.outside[1]), small, AX::center,
         font_ok);
    text(img, int((U.x + V.x) / 2 + 10), int((U.y + V.y) / 2), label("Weq0", f[2], &pf.outside[2]), small, AX::left,
         font_ok);
    text(img, int(V.x), int(V.y - small), "v = 1", small, AX::center, font_ok);
    text(img, int(U.x + 6), int(U.y + small), "u = 1", small, AX::left, font_ok);
    text(img, int(W.x - 6), int(W.y + small), "w = 1", small, AX::right, font_ok);
    text(img, pic.size / 2, int(W.y + small * 3),
         "inside = " + float_text(f[3]) + (pf.culled || pf.minimal ? "" : " (" + segments_text(pf.inside[0]) + ")"),
         small, AX::center, font_ok);
  }

  if (auto e = write_image(ImageTarget{path}, ImageLayout{pic.size, pic.size, 3, PixelType::u8}, PixelType::f32,
                           pixels.data());
      !e.empty())
    throw InputError(e);
}

}  // namespace tessera::cli
