// Clip-space clipping (D3D11 §15.4): against the near (z >= 0) and far (z <= w) planes, and against a
// guard band in x and y instead of the viewport edges. Geometry inside the guard band is never cut;
// the rasterizer's scissor to the viewport removes what lies beyond the viewport, so tessellated
// meshes crossing the screen edge are not split into slivers.
//
// Watertight by construction: a new vertex on an edge is always interpolated from the edge's inside
// end towards its outside end, so the two triangles that share an edge (and walk it in opposite
// directions) compute bit-identical intersection points. Planes are applied in a fixed order.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "pipeline/stage_io.h"

namespace tessera {

// Half extent of the guard band in pixels, measured from the viewport centre. 16.8 fixed-point window
// coordinates then stay below 2^23 in magnitude, so edge functions fit comfortably in 64 bits.
inline constexpr float kGuardBandHalfExtentPixels = 8192.0f;

// kW keeps w strictly positive: near and far (0 <= z <= w) already imply w >= 0, but a vertex at
// w == 0 on both would reach the perspective division; clipping at a tiny positive w prevents that.
enum ClipPlane : std::uint8_t { kNear = 0, kFar, kLeft, kRight, kBottom, kTop, kW, kPlaneCount };
inline constexpr float kMinClipW = 1e-6f;

// Guard-band size in clip-space units (|x| <= gx * w).
struct GuardBand {
  float gx = 1, gy = 1;
};

inline float clip_distance(int plane, const glm::vec4& p, GuardBand g) {
  switch (plane) {
    case kNear: return p.z;
    case kFar: return p.w - p.z;
    case kLeft: return g.gx * p.w + p.x;
    case kRight: return g.gx * p.w - p.x;
    case kBottom: return g.gy * p.w + p.y;
    case kTop: return g.gy * p.w - p.y;
    default: return p.w - kMinClipW;
  }
}

// Bit i set: the point is outside plane i (of the guard band, for x and y).
inline unsigned clip_outcode(const glm::vec4& p, GuardBand g) {
  // The same tests as clip_distance(i, p, g) < 0, written out so they compile without branches.
  const float gx = g.gx * p.w, gy = g.gy * p.w;
  return unsigned(p.z < 0.0f) << kNear | unsigned(p.w - p.z < 0.0f) << kFar | unsigned(gx + p.x < 0.0f) << kLeft |
         unsigned(gx - p.x < 0.0f) << kRight | unsigned(gy + p.y < 0.0f) << kBottom |
         unsigned(gy - p.y < 0.0f) << kTop | unsigned(p.w - kMinClipW < 0.0f) << kW;
}

// Bit i set: the point is outside the view volume's plane i (the viewport itself, not the guard band),
// for trivial rejection of primitives wholly outside one plane.
inline unsigned view_outcode(const glm::vec4& p) {
  unsigned code = 0;
  if (p.z < 0.0f) code |= 1u << kNear;
  if (p.z > p.w) code |= 1u << kFar;
  if (p.x < -p.w) code |= 1u << kLeft;
  if (p.x > p.w) code |= 1u << kRight;
  if (p.y < -p.w) code |= 1u << kBottom;
  if (p.y > p.w) code |= 1u << kTop;
  if (!(p.w > 0.0f)) code |= 1u << kW;
  return code;
}

inline bool finite_position(const glm::vec4& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w);
}

// A triangle clipped by up to seven planes has at most 3 + 7 vertices.
template <std::size_t N>
struct ClipPolygon {
  std::array<ClipVertex<N>, 12> v;
  int count = 0;
};

// The point on the edge from `inside` to `outside` where the plane distance is zero.
template <std::size_t N>
ClipVertex<N> clip_intersection(const ClipVertex<N>& inside, float d_in, const ClipVertex<N>& outside, float d_out) {
  const float t = d_in / (d_in - d_out);
  ClipVertex<N> r;
  r.position = inside.position + t * (outside.position - inside.position);
  for (std::size_t k = 0; k < N; ++k)
    r.attributes[k] = inside.attributes[k] + t * (outside.attributes[k] - inside.attributes[k]);
  return r;
}

// Sutherland-Hodgman against every plane in `planes` (a bit mask), in plane order. `poly` is clipped in place.
template <std::size_t N>
void clip_polygon(ClipPolygon<N>& poly, unsigned planes, GuardBand g) {
  ClipPolygon<N> out;
  for (int plane = 0; plane < kPlaneCount && poly.count > 0; ++plane) {
    if (!(planes & (1u << plane))) continue;
    out.count = 0;
    for (int i = 0; i < poly.count; ++i) {
      const ClipVertex<N>& a = poly.v[i];
      const ClipVertex<N>& b = poly.v[(i + 1) % poly.count];
      const float da = clip_distance(plane, a.position, g), db = clip_distance(plane, b.position, g);
      if (da >= 0.0f) out.v[out.count++] = a;
      if ((da >= 0.0f) != (db >= 0.0f))
        out.v[out.count++] = da >= 0.0f ? clip_intersection(a, da, b, db) : clip_intersection(b, db, a, da);
    }
    poly = out;
  }
}

// A segment clipped in place; returns false when nothing is left.
template <std::size_t N>
bool clip_segment(ClipVertex<N>& a, ClipVertex<N>& b, unsigned planes, GuardBand g) {
  for (int plane = 0; plane < kPlaneCount; ++plane) {
    if (!(planes & (1u << plane))) continue;
    const float da = clip_distance(plane, a.position, g), db = clip_distance(plane, b.position, g);
    if (da < 0.0f && db < 0.0f) return false;
    if (da < 0.0f)
      a = clip_intersection(b, db, a, da);
    else if (db < 0.0f)
      b = clip_intersection(a, da, b, db);
  }
  return true;
}

}  // namespace tessera
