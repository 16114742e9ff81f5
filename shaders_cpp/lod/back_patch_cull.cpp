#include "shaders_cpp/lod/back_patch_cull.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "shaders_cpp/lod/frustum_cull.h"

namespace tessera {

namespace {

// A screen position's error budget: snapping to 1/256 pixel moves a vertex by at most 1/512 in x and y;
// the viewport transform's float rounding adds under 1/1000 at coordinates below 2^13.
constexpr double kScreenError = 0x1p-8;  // pixels
// The domain shader's float evaluation of a cubic net (a dozen roundings of terms no larger than the
// largest coordinate), relative to that coordinate, with a margin of 8.
constexpr double kEvaluationError = 0x1p-17;
// The float projection's error, taken back to world space, relative to the coordinates and the eye
// (a few roundings of terms of that size; a margin of 4).
constexpr double kProjectionError = 0x1p-20;

// Up to 16 points without the heap (this runs once per patch): a net, (n + 1)^2 points i + (n + 1) j
// with u along i, or a derivative net.
struct Net {
  std::array<glm::dvec3, 16> p{};
  std::size_t count = 0;
  const glm::dvec3* begin() const { return p.data(); }
  const glm::dvec3* end() const { return p.data() + count; }
  glm::dvec3& operator[](std::size_t i) { return p[i]; }
  const glm::dvec3& operator[](std::size_t i) const { return p[i]; }
  void push_back(const glm::dvec3& x) { p[count++] = x; }
};

// The halves of a net at u = 1/2 (along i) or v = 1/2 (along j), by de Casteljau.
std::array<Net, 2> split(const Net& net, int n, bool along_u) {
  const int n1 = n + 1;
  std::array<Net, 2> out;
  out[0].count = out[1].count = net.count;
  std::array<glm::dvec3, 4> c;
  for (int line = 0; line < n1; ++line) {
    const auto at = [&](int k) { return std::size_t(along_u ? k + n1 * line : line + n1 * k); };
    for (int k = 0; k < n1; ++k) c[std::size_t(k)] = net[at(k)];
    for (int r = 0; r <= n; ++r) {
      out[0][at(r)] = c[0];
      out[1][at(n - r)] = c[std::size_t(n - r)];
      for (int k = 0; k + r < n; ++k) c[std::size_t(k)] = 0.5 * (c[std::size_t(k)] + c[std::size_t(k + 1)]);
    }
  }
  return out;
}

struct Sphere {
  glm::dvec3 centre;
  double radius;
};
Sphere bounding_sphere(const Net& net) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::dvec3& p : net) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return {0.5 * (lo + hi), 0.5 * glm::length(hi - lo)};
}

// First differences of a net along u or v, times `scale`.
Net differences(const Net& net, int n, bool along_u, double scale) {
  const int n1 = n + 1;
  Net d;
  for (int j = 0; j < (along_u ? n1 : n); ++j)
    for (int i = 0; i < (along_u ? n : n1); ++i) {
      const std::size_t a = std::size_t(i + n1 * j), b = along_u ? a + 1 : a + std::size_t(n1);
      d.push_back(scale * (net[b] - net[a]));
    }
  return d;
}

double largest_norm(const Net& v) {
  double m = 0.0;
  for (const glm::dvec3& x : v) m = std::max(m, glm::length(x));
  return m;
}

// The range of f = (p - e) . (p_u x p_v) over a (sub)patch: p in the net's sphere, p_u and p_v in the
// hulls of `du` and `dv` (f is linear in each, so its extremes over the hulls are at their points).
void facing_range(const Net& net, const Net& du, const Net& dv, const glm::dvec3& eye, double& lo, double& hi) {
  // f = u . (v x (c - e)) +- r |u x v|: one cross product per v, and |u x v| <= |u| |v| (a square root
  // per point instead of one per pair).
  const Sphere s = bounding_sphere(net);
  const glm::dvec3 ce = s.centre - eye;
  std::array<glm::dvec3, 16> w{};
  std::array<double, 16> v_len{};
  for (std::size_t k = 0; k < dv.count; ++k) {
    w[k] = glm::cross(dv[k], ce);
    v_len[k] = s.radius * glm::length(dv[k]);
  }
  for (const glm::dvec3& u : du) {
    const double u_len = glm::length(u);
    for (std::size_t k = 0; k < dv.count; ++k) {
      const double g = glm::dot(u, w[k]), r = u_len * v_len[k];
      lo = std::min(lo, g - r);
      hi = std::max(hi, g + r);
    }
  }
}

}  // namespace

int max_edge_segments(float f) {
  if (!(f < 64.0f)) return 64;  // and NaN: the tessellator culls that patch anyway
  return std::min(64, 2 * int(std::ceil(std::max(f, 1.0f))) + 2);
}

BackPatchCull::BackPatchCull(const glm::mat4& view_projection, int width, int height, int culled_sign)
    : view_projection_(view_projection), culled_sign_(culled_sign) {
  // Rows x, y, w of the projection: H = P3 p + t; the eye is where H = 0.
  glm::dmat3 p3;
  glm::dvec3 t;
  const int rows[3] = {0, 1, 3};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) p3[c][r] = view_projection_[c][rows[r]];
    t[r] = view_projection_[3][rows[r]];
  }
  det_ = glm::determinant(p3);
  if (!std::isfinite(det_) || det_ == 0.0 || width <= 0 || height <= 0) return;
  const glm::dmat3 inv = glm::inverse(p3);
  eye_ = -(inv * t);
  // World distance per unit of clip-space x, y at fixed w (a snapped vertex keeps its w): the
  // Frobenius norm of P3^-1's first two columns; kScreenError pixels are that many clip units times w.
  const double inv_norm = std::sqrt(glm::dot(inv[0], inv[0]) + glm::dot(inv[1], inv[1]));
  pixel_world_ = inv_norm * kScreenError * 2.0 * std::sqrt(2.0) / double(std::min(width, height));
  enabled_ = std::isfinite(glm::length(eye_)) && std::isfinite(pixel_world_);
}

OrientationBound BackPatchCull::bound(std::span<const glm::vec3> points, int n, int edge_segments) const {
  const int n1 = n + 1;
  if (!enabled_ || n < 1 || n > 3 || points.size() != std::size_t(n1 * n1) || edge_segments < 1) return {};
  Net net;
  net.count = points.size();
  double extent = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    net[i] = glm::dvec3(points[i]);
    extent = std::max({extent, std::abs(net[i].x), std::abs(net[i].y), std::abs(net[i].z)});
  }
  if (!std::isfinite(extent)) return {};

  // f at the four corners, exactly (n^2 times the net's corner differences' f): a proof would give
  // every point one sign, so a patch whose corners disagree (near a silhouette), face the way the draw
  // keeps, or are degenerate is left at once, as most patches are.
  double corner_f = INFINITY;  // the smallest |f| at a corner: no floor can exceed it
  int sigma = 0;
  {
    const auto at = [n1](int i, int j) { return std::size_t(i + n1 * j); };
    // Each corner with two neighbours (a, b) such that (a - c) x (b - c) has the direction of p_u x p_v.
    const std::array<std::array<std::size_t, 3>, 4> corners = {{{at(0, 0), at(1, 0), at(0, 1)},
                                                                {at(n, 0), at(n, 1), at(n - 1, 0)},
                                                                {at(n, n), at(n - 1, n), at(n, n - 1)},
                                                                {at(0, n), at(0, n - 1), at(1, n)}}};
    for (const auto& [c, a, b] : corners) {
      const double f = double(n * n) * glm::dot(net[c] - eye_, glm::cross(net[a] - net[c], net[b] - net[c]));
      const int s = f > 0.0 ? 1 : f < 0.0 ? -1 : 0;
      if (s == 0 || (sigma != 0 && s != sigma)) return {};
      sigma = s;
      corner_f = std::min(corner_f, std::abs(f));
    }
  }
  // Screen (y down, clockwise positive) = -sign(det P3) * sign(F), and sign(F) = sigma * sign(D).
  const int screen_sign = det_ > 0 ? -sigma : sigma;
  if (culled_sign_ != 0 && screen_sign != culled_sign_) return {};

  // The clip-space planes, z moved as clip_position() does; every point of the hull, grown by eps,
  // strictly inside all of them: w > 0 (the orientation rule needs it) and no triangle is clipped.
  const ClipPlanes clip = clip_planes(glm::mat4(view_projection_), z_bias);
  double w_max = 0.0;
  for (const glm::dvec3& p : net) w_max = std::max(w_max, glm::dot(glm::dvec3(clip.w), p) + clip.w.w);
  const double eps = extent * kEvaluationError + (extent + glm::length(eye_)) * kProjectionError + pixel_world_ * w_max;
  for (const glm::dvec4& plane : clip.planes) {
    const double reach = eps * glm::length(glm::dvec3(plane));
    for (const glm::dvec3& p : net)
      if (!(glm::dot(glm::dvec3(plane), p) + plane.w - reach > 0.0)) return {};
  }

  // Whole-patch bounds for the error terms: R, W and M2 (second differences times n(n-1), the mixed
  // ones times n^2).
  const Sphere whole = bounding_sphere(net);
  const double reach = glm::length(whole.centre - eye_) + whole.radius;
  const Net du = differences(net, n, true, n), dv = differences(net, n, false, n);
  const double w = std::max(largest_norm(du), largest_norm(dv));
  double m2 = 0.0;
  if (n >= 2) {
    // p_uu: differences of du along u (du is n x (n + 1): n points along u per row).
    for (int j = 0; j < n1; ++j)
      for (int i = 0; i + 1 < n; ++i)
        m2 = std::max(m2, double(n - 1) * glm::length(du[std::size_t(i + 1 + n * j)] - du[std::size_t(i + n * j)]));
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i < n1; ++i)
        m2 = std::max(m2, double(n - 1) * glm::length(dv[std::size_t(i + n1 * (j + 1))] - dv[std::size_t(i + n1 * j)]));
  }
  // p_uv: differences of du along v.
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m2 = std::max(m2, double(n) * glm::length(du[std::size_t(i + n * (j + 1))] - du[std::size_t(i + n * j)]));

  OrientationBound b;
  b.screen_sign = std::int8_t(screen_sign);
  b.k_cubic = reach * w * m2 * 0.5;
  b.k_quartic = reach * m2 * m2 * 0.25;
  b.k_product = eps * w * w;
  b.k_perimeter = 2.0 * eps * (eps + reach) * w;
  b.k_inverse = 4.0 * eps * eps * (eps + reach);
  // Before the costly floor: every pattern has cubic >= 1 / edge_segments (a triangle on the longest
  // segment of an edge: cubic >= l1 + l2 >= that segment) and product, perimeter, inverse >= 1 (D <= l1 l2,
  // l <= 2, D <= 1), and the floor is at most corner_f. A patch that fails with those fails for every
  // pattern its factors can make.
  if (!(corner_f > b.k_cubic / double(edge_segments) + b.k_product + b.k_perimeter + b.k_inverse)) return {};

  // The sign of f over each quarter of the patch (derivatives with respect to the patch's own u, v: a
  // quarter's differences times 2n). Quarters against the whole patch: about a quarter more patches
  // proven on the frog; 4 x 4 pieces add a tenth more at four times the cost.
  double lo = INFINITY, hi = -INFINITY;
  for (const Net& half : split(net, n, true))
    for (const Net& quarter : split(half, n, false)) {
      facing_range(quarter, differences(quarter, n, true, 2.0 * n), differences(quarter, n, false, 2.0 * n), eye_, lo,
                   hi);
      if (lo <= 0.0 && hi >= 0.0) return {};
    }
  if (!std::isfinite(hi - lo)) return {};
  // The corners' sign (a range of one sign holds the corners' values).
  const double floor = sigma > 0 ? lo : -hi;
  // Less a margin for this function's own double rounding (2^-40 of the range is far more).
  b.floor = floor - (std::abs(lo) + std::abs(hi)) * 0x1p-40;
  return b;
}

}  // namespace tessera
