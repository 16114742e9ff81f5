#include "shaders_cpp/debug/debug_shaders.h"

namespace tessera {

glm::vec3 heat_color(float t) {
  // Piecewise-linear through six stops, perceptually ordered dark-to-bright-to-hot.
  static constexpr std::array<glm::vec3, 6> stops = {glm::vec3(0.19f, 0.07f, 0.43f), glm::vec3(0.15f, 0.42f, 0.93f),
                                                     glm::vec3(0.10f, 0.80f, 0.78f), glm::vec3(0.45f, 0.94f, 0.30f),
                                                     glm::vec3(0.98f, 0.78f, 0.16f), glm::vec3(0.80f, 0.12f, 0.05f)};
  const float x = std::clamp(t, 0.0f, 1.0f) * 5.0f;
  const int i = std::min(4, int(x));
  return glm::mix(stops[std::size_t(i)], stops[std::size_t(i) + 1], x - float(i));
}

glm::vec3 diverging_color(float t) {
  const glm::vec3 blue(0.13f, 0.35f, 0.85f), white(0.97f, 0.97f, 0.95f), red(0.85f, 0.15f, 0.12f);
  const float x = std::clamp(t, 0.0f, 1.0f);
  return x < 0.5f ? glm::mix(blue, white, x * 2.0f) : glm::mix(white, red, (x - 0.5f) * 2.0f);
}

glm::vec3 hashed_color(std::uint32_t i) {
  std::uint32_t x = i * 0x9E3779B1u + 0x7F4A7C15u;
  x ^= x >> 15, x *= 0x2C1B3C6Du, x ^= x >> 12, x *= 0x297A2D39u, x ^= x >> 15;
  // Bright enough to read under shading, never grey.
  return {0.25f + 0.7f * float(x & 255u) / 255.0f, 0.25f + 0.7f * float((x >> 8) & 255u) / 255.0f,
          0.25f + 0.7f * float((x >> 16) & 255u) / 255.0f};
}

glm::vec3 category_color(int i) {
  static constexpr std::array<glm::vec3, 10> palette = {glm::vec3(0.36f, 0.62f, 0.85f), glm::vec3(0.95f, 0.55f, 0.20f),
                                                        glm::vec3(0.35f, 0.75f, 0.38f), glm::vec3(0.88f, 0.30f, 0.33f),
                                                        glm::vec3(0.62f, 0.45f, 0.80f), glm::vec3(0.60f, 0.42f, 0.32f),
                                                        glm::vec3(0.92f, 0.55f, 0.78f), glm::vec3(0.55f, 0.55f, 0.55f),
                                                        glm::vec3(0.78f, 0.78f, 0.25f), glm::vec3(0.25f, 0.78f, 0.80f)};
  if (i >= 0 && i < int(palette.size())) return palette[std::size_t(i)];
  return hashed_color(std::uint32_t(i));
}

glm::vec3 adaptive_patch_color(AdaptivePatchKind kind, int level) {
  static constexpr std::array<glm::vec3, kAdaptivePatchKinds> base = {
      glm::vec3(0.55f, 0.75f, 0.95f),   // regular: light blue
      glm::vec3(0.97f, 0.72f, 0.35f),   // boundary (and infinitely sharp crease): orange
      glm::vec3(0.92f, 0.35f, 0.35f),   // single-crease: red
      glm::vec3(0.45f, 0.82f, 0.45f)};  // end cap: green
  // Deeper levels darker, by 7% a level down to half: levels stay apart and the kind's hue readable
  // under shading; the sub-patch borders the view draws give the level exactly.
  return base[std::size_t(kind)] * std::max(0.5f, 1.0f - 0.07f * float(level));
}

namespace {

// A screen-space gradient's length floor: a pixel where the domain does not vary (a degenerate patch
// corner) gets a finite, huge scale instead of a division by zero.
constexpr float kMinGradientLength = 1e-12f;
// The height view's divisor floor: a flat surface maps to the middle colour.
constexpr float kMinHeightRange = 1e-20f;

float gradient_length(const PixelInput<kDebugAttributes>& in, std::size_t a) {
  const float x = in.ddx(a), y = in.ddy(a);
  return std::sqrt(x * x + y * y);
}

// Coverage of a line `width` pixels wide at `distance` pixels from its centre, with a 1-pixel ramp.
float line_coverage(float distance, float width) { return std::clamp(0.5f * width + 0.5f - distance, 0.0f, 1.0f); }

// Which region of the tessellation a domain location is in: an outer ring (the edge's index) or the
// interior (-1). Ring widths are one inside segment (the triangle's rings: 2/3 of 1/inside in each
// barycentric coordinate).
int region_of(const PatchInfo& p, float u, float v, float w) {
  // Distance to each domain edge in ring widths (SV_TessFactor order); below 1 is that edge's ring.
  std::array<float, 4> rings;
  if (p.tri) {
    const float s = 1.5f * float(p.inside_segments[0]);
    rings = {u * s, v * s, w * s, INFINITY};
  } else {
    const float su = float(p.inside_segments[0]), sv = float(p.inside_segments[1]);
    rings = {u * su, v * sv, (1.0f - u) * su, (1.0f - v) * sv};
  }
  const auto nearest = std::min_element(rings.begin(), rings.end());
  return *nearest < 1.0f ? int(nearest - rings.begin()) : -1;
}

}  // namespace

std::array<float, 4> domain_edge_pixels(const PixelInput<kDebugAttributes>& in, bool tri) {
  const auto& a = in.attributes;
  const float gu = std::max(gradient_length(in, 3), kMinGradientLength), gv = std::max(gradient_length(in, 4), kMinGradientLength);
  if (tri) {
    const float gw = std::max(gradient_length(in, 5), kMinGradientLength);
    return {a[3] / gu, a[4] / gv, a[5] / gw, INFINITY};
  }
  return {a[3] / gu, a[4] / gv, (1.0f - a[3]) / gu, (1.0f - a[4]) / gv};
}

glm::vec4 DebugPS::operator()(const PixelInput<kDebugAttributes>& in) const {
  const auto& a = in.attributes;
  const glm::vec3 n = sides.facing(unit_or_zero(glm::vec3(a[0], a[1], a[2])), in.front_face);
  const float diffuse = std::max(0.0f, glm::dot(n, light));
  const std::size_t id = std::size_t(std::max(0.0f, a[6]) + 0.5f);
  if (id >= patches.size()) return {1.0f, 0.0f, 1.0f, 1.0f};  // magenta: a patch the table does not know
  const PatchInfo& p = patches[id];
  if (view == DebugView::pick) return pick_color(pick_code(id, p.tri));
  const float u = a[3], v = a[4], w = a[5];
  const std::array<float, 4> edge_px = domain_edge_pixels(in, p.tri);
  const float boundary_px = std::min({edge_px[0], edge_px[1], edge_px[2], edge_px[3]});
  auto shade = [&](glm::vec3 c) { return c * (0.35f + 0.65f * diffuse); };
  glm::vec3 c;
  float border_width = 1.0f, border_strength = 0.45f;
  switch (view) {
    case DebugView::wire:
      c = paper ? glm::vec3(0.97f, 0.97f, 0.96f) : glm::vec3(clay(n, light, kClayColor));
      border_width = 2.0f, border_strength = 0.85f;
      break;
    case DebugView::factors:
    case DebugView::density: {
      const int region = region_of(p, u, v, w);
      const int edges = p.tri ? 3 : 4;
      if (view == DebugView::factors) {
        float f;
        if (region >= 0 && region < edges)
          f = processed ? p.edge_processed[std::size_t(region)] : p.raw.edge[std::size_t(region)];
        else if (p.tri)
          f = processed ? p.inside_processed[0] : p.raw.inside[0];
        else
          f = processed ? std::max(p.inside_processed[0], p.inside_processed[1])
                        : std::max(p.raw.inside[0], p.raw.inside[1]);
        c = shade(heat_color(factor_position(f)));
      } else {
        // Segments along u and v here: the inside counts, or along an outer ring its edge's count.
        float su = float(p.inside_segments[0]), sv = float(p.tri ? p.inside_segments[0] : p.inside_segments[1]);
        if (!p.tri && (region == 0 || region == 2)) sv = float(p.edge_segments[std::size_t(region)]);
        if (!p.tri && (region == 1 || region == 3)) su = float(p.edge_segments[std::size_t(region)]);
        const float pu = 1.0f / (su * std::max(gradient_length(in, 3), kMinGradientLength));
        const float pv = 1.0f / (sv * std::max(gradient_length(in, 4), kMinGradientLength));
        c = shade(diverging_color(density_position(std::sqrt(pu * pv) / edge_pixels)));
      }
      break;
    }
    case DebugView::patch_type: {
      if (adaptive == nullptr || !adaptive->has_surface(p.face)) {
        c = shade(category_color(int(p.type)));
        break;
      }
      const LimitSurface::PatchFacts f = adaptive->patch_at_face_frame(p.face, p.sub, a[7], a[8]);
      c = shade(adaptive_patch_color(f.kind, f.level));
      if (!p.tri && f.level > 0) {
        // The sub-patch borders of a quad at this level: the face (u,v) at multiples of 2^-level.
        const float cells = std::ldexp(1.0f, f.level);
        const float fu = a[7] * cells, fv = a[8] * cells;
        const float du =
            std::min(fu - std::floor(fu), std::ceil(fu) - fu) / (cells * std::max(gradient_length(in, 7), kMinGradientLength));
        const float dv =
            std::min(fv - std::floor(fv), std::ceil(fv) - fv) / (cells * std::max(gradient_length(in, 8), kMinGradientLength));
        c = glm::mix(c, glm::vec3(0.1f, 0.1f, 0.14f), 0.5f * line_coverage(std::min(du, dv), 1.0f));
      }
      break;
    }
    case DebugView::combination: c = shade(category_color(p.combination)); break;
    case DebugView::patch_id: c = shade(hashed_color(std::uint32_t(id) * 2u + (p.tri ? 1u : 0u))); break;
    case DebugView::normals:
      c = n * 0.5f + 0.5f;
      border_strength = 0.0f;
      break;
    case DebugView::uv: {
      glm::vec2 t;
      if (!heights.empty()) {
        t = {a[9], a[10]};
      } else {
        const float fu = a[7], fv = a[8];
        const auto& k = p.corner_uv;
        t = p.tri || p.sub > 0 || p.kind == PatchKind::linear
                ? (1.0f - fu - fv) * k[0] + fu * k[1] + fv * k[2]
                : glm::mix(glm::mix(k[0], k[1], fu), glm::mix(k[3], k[2], fu), fv);
      }
      const int checks = int(std::floor(t.x * 16.0f)) + int(std::floor(t.y * 16.0f));
      const glm::vec3 tint(0.45f + 0.5f * std::clamp(t.x, 0.0f, 1.0f), 0.45f + 0.5f * std::clamp(t.y, 0.0f, 1.0f),
                           0.6f);
      c = shade(tint * ((checks & 1) ? 1.0f : 0.6f));
      float seam = 0.0f;
      for (int e = 0; e < 4; ++e)
        if (p.seam_edges & (1u << e)) seam = std::max(seam, line_coverage(edge_px[std::size_t(e)], 4.0f));
      c = glm::mix(c, glm::vec3(0.95f, 0.1f, 0.1f), seam);
      break;
    }
    case DebugView::displacement: {
      float hgt = 0.0f;
      if (!heights.empty()) {
        Sampler s;
        s.address_u = s.address_v = AddressMode::clamp;
        const std::size_t tile = id < texcoords.size() ? texcoords[id].tile : 0;
        const glm::vec4 texel = heights[tile].texture().sample_grad(s, glm::vec2(a[9], a[10]), glm::vec2(in.ddx(9), in.ddx(10)),
                                                    glm::vec2(in.ddy(9), in.ddy(10)));
        hgt = height_scale * texel.x + height_bias;
      }
      c = shade(diverging_color(0.5f + 0.5f * hgt / std::max(height_range, kMinHeightRange)));
      break;
    }
    case DebugView::pick: c = glm::vec3(0.0f); break;  // (returned above)
    case DebugView::culled: c = shade(p.culled ? kCulledColor : p.faces_away ? kBackCulledColor : kClayColor); break;
  }
  const float border = border_strength * line_coverage(boundary_px, border_width);
  c = glm::mix(c, glm::vec3(0.08f, 0.09f, 0.12f), border);
  return {c, 1.0f};
}

glm::vec4 DebugWirePS::operator()(const PixelInput<kDebugAttributes>& in) const {
  const auto& a = in.attributes;
  const std::size_t id = std::size_t(std::max(0.0f, a[6]) + 0.5f);
  const PatchInfo* p = id < patches.size() ? &patches[id] : nullptr;
  const glm::vec3 n = sides.facing(unit_or_zero(glm::vec3(a[0], a[1], a[2])), in.front_face);
  const glm::vec3 under = paper ? glm::vec3(0.97f, 0.97f, 0.96f) : glm::vec3(clay(n, light, kClayColor));
  // An edge on the patch boundary interpolates a domain coordinate that is exactly 0 (or 1) at both
  // ends: it keeps the border's dark colour, so the wires do not lighten the surface pass's border.
  constexpr float e = 1e-6f;
  const bool border = p != nullptr && (p->tri ? (a[3] <= e || a[4] <= e || a[5] <= e)
                                              : (a[3] <= e || a[4] <= e || a[3] >= 1.0f - e || a[4] >= 1.0f - e));
  const glm::vec3 ink(0.08f, 0.09f, 0.12f);
  if (border) return {glm::mix(under, ink, 0.85f), 1.0f};
  // Full strength from 12 pixels per segment, gone below 3: dense interiors fade, patch borders stay.
  const float pixels = p != nullptr ? p->pixels_per_segment : 0.0f;
  const float strength = 0.55f * std::clamp((pixels - 3.0f) / 9.0f, 0.0f, 1.0f);
  return {glm::mix(under, glm::vec3(0.16f, 0.22f, 0.36f), strength), 1.0f};
}

}  // namespace tessera
