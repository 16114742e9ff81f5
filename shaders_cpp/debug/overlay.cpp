#include "shaders_cpp/debug/overlay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace tessera {
namespace {

struct ScreenPoint {
  glm::vec2 p;
  float depth;
};

ScreenPoint to_screen(const Framebuffer& fb, const glm::vec4& c) {
  const float x = (c.x / c.w * 0.5f + 0.5f) * float(fb.width());
  const float y = (0.5f - c.y / c.w * 0.5f) * float(fb.height());
  return {{x, y}, c.z / c.w};
}

// Clips the clip-space segment to z >= 0 (D3D's near plane); false when nothing is left.
bool clip_near(glm::vec4& a, glm::vec4& b) {
  if (a.z < 0.0f && b.z < 0.0f) return false;
  if (a.z < 0.0f) a = glm::mix(a, b, a.z / (a.z - b.z));
  if (b.z < 0.0f) b = glm::mix(b, a, b.z / (b.z - a.z));
  return a.w > 0.0f && b.w > 0.0f;
}

void blend(Framebuffer& fb, int x, int y, const glm::vec3& color, float alpha) {
  const glm::vec4 old = fb.color(x, y);
  fb.set_color(x, y, glm::vec4(glm::mix(glm::vec3(old), color, alpha), old.a));
}

void draw_segment(Framebuffer& fb, const ScreenPoint& a, const ScreenPoint& b, const OverlayStyle& s) {
  const glm::vec2 d = b.p - a.p;
  const float length2 = glm::dot(d, d);
  const float reach = 0.5f * s.width + 1.0f;
  const bool along_x = std::abs(d.x) >= std::abs(d.y);
  // Walk the major axis; at each step, the pixels across the line within its reach.
  const float lo = std::min(along_x ? a.p.x : a.p.y, along_x ? b.p.x : b.p.y) - reach;
  const float hi = std::max(along_x ? a.p.x : a.p.y, along_x ? b.p.x : b.p.y) + reach;
  const int limit_major = along_x ? fb.width() : fb.height(), limit_minor = along_x ? fb.height() : fb.width();
  const int m0 = std::max(0, int(std::floor(lo))), m1 = std::min(limit_major - 1, int(std::ceil(hi)));
  for (int m = m0; m <= m1; ++m) {
    const float centre_major = float(m) + 0.5f;
    const float major_d = along_x ? d.x : d.y, minor_d = along_x ? d.y : d.x;
    const float major_a = along_x ? a.p.x : a.p.y, minor_a = along_x ? a.p.y : a.p.x;
    float t = major_d != 0.0f ? (centre_major - major_a) / major_d : 0.0f;
    t = std::clamp(t, 0.0f, 1.0f);
    const float minor_centre = minor_a + t * minor_d;
    const int n0 = std::max(0, int(std::floor(minor_centre - reach))),
              n1 = std::min(limit_minor - 1, int(std::ceil(minor_centre + reach)));
    for (int n = n0; n <= n1; ++n) {
      const int x = along_x ? m : n, y = along_x ? n : m;
      const glm::vec2 c(float(x) + 0.5f, float(y) + 0.5f);
      const float u = length2 > 0.0f ? std::clamp(glm::dot(c - a.p, d) / length2, 0.0f, 1.0f) : 0.0f;
      const float distance = glm::length(c - (a.p + u * d));
      const float coverage = std::clamp(0.5f * s.width + 0.5f - distance, 0.0f, 1.0f);
      if (coverage <= 0.0f) continue;
      if (s.depth_test && a.depth + u * (b.depth - a.depth) > fb.depth(x, y) + s.depth_slack) continue;
      blend(fb, x, y, s.color, coverage * s.opacity);
    }
  }
}

// Clips a screen segment to the rectangle [lo, hi] (Liang-Barsky); false when nothing is left.
bool clip_rect(ScreenPoint& a, ScreenPoint& b, glm::vec2 lo, glm::vec2 hi) {
  const glm::vec2 d = b.p - a.p;
  float t0 = 0.0f, t1 = 1.0f;
  const std::array<float, 4> p = {-d.x, d.x, -d.y, d.y};
  const std::array<float, 4> q = {a.p.x - lo.x, hi.x - a.p.x, a.p.y - lo.y, hi.y - a.p.y};
  for (std::size_t i = 0; i < 4; ++i) {
    if (p[i] == 0.0f) {
      if (q[i] < 0.0f) return false;
      continue;
    }
    const float r = q[i] / p[i];
    if (p[i] < 0.0f)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
  }
  if (t0 > t1) return false;
  const ScreenPoint a0 = a;
  a = {a0.p + t0 * d, a0.depth + t0 * (b.depth - a0.depth)};
  b = {a0.p + t1 * d, a0.depth + t1 * (b.depth - a0.depth)};
  return true;
}

}  // namespace

void draw_lines(Framebuffer& fb, const glm::mat4& view_projection, std::span<const OverlayLine> lines,
                const OverlayStyle& style) {
  fb.finish_clear();  // pixel-rate writes and reads: no tile may still hold a pending clear
  for (const OverlayLine& l : lines) {
    glm::vec4 a = view_projection * glm::vec4(l.a, 1.0f), b = view_projection * glm::vec4(l.b, 1.0f);
    if (!clip_near(a, b)) continue;
    ScreenPoint sa = to_screen(fb, a), sb = to_screen(fb, b);
    if (!std::isfinite(sa.p.x + sa.p.y + sb.p.x + sb.p.y)) continue;
    // Clipped to the target plus a margin first, so a segment from near the eye does not walk
    // millions of pixels off screen.
    const glm::vec2 margin(style.width + 2.0f);
    if (!clip_rect(sa, sb, -margin, glm::vec2(float(fb.width()), float(fb.height())) + margin)) continue;
    draw_segment(fb, sa, sb, style);
  }
}

void draw_points(Framebuffer& fb, const glm::mat4& view_projection, std::span<const glm::vec3> points,
                 const OverlayStyle& style) {
  fb.finish_clear();  // pixel-rate writes and reads: no tile may still hold a pending clear
  for (const glm::vec3& p : points) {
    const glm::vec4 c = view_projection * glm::vec4(p, 1.0f);
    if (c.z < 0.0f || c.w <= 0.0f) continue;
    const ScreenPoint s = to_screen(fb, c);
    draw_segment(fb, s, s, style);
  }
}

void box_lines(const glm::vec3& lo, const glm::vec3& hi, std::vector<OverlayLine>& out) {
  auto corner = [&](int i) { return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4})
      if (!(i & bit)) out.push_back({corner(i), corner(i | bit)});
}

void frustum_lines(const glm::mat4& view_projection, std::vector<OverlayLine>& out) {
  const glm::mat4 inverse = glm::inverse(view_projection);
  auto corner = [&](int i) {
    const glm::vec4 c = inverse * glm::vec4(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : 0.0f, 1.0f);
    return glm::vec3(c) / c.w;
  };
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4})
      if (!(i & bit)) out.push_back({corner(i), corner(i | bit)});
}

}  // namespace tessera
