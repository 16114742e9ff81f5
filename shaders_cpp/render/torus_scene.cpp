#include "shaders_cpp/render/torus_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "pipeline/simd8.h"

namespace tessera::render {

TorusScene make_torus_scene(int width, int height) {
  constexpr int M = kTorusColumns, N = kTorusRows, T = kTorusTextureSize;
  const double pi = std::numbers::pi;
  std::vector<glm::vec3> cage;
  std::vector<std::uint32_t> indices;
  cage.reserve(M * N);
  for (int i = 0; i < M; ++i)
    for (int j = 0; j < N; ++j) {
      const double a = 2 * pi * i / M, b = 2 * pi * j / N;
      cage.emplace_back(float((1 + 0.4 * std::cos(b)) * std::cos(a)), float((1 + 0.4 * std::cos(b)) * std::sin(a)),
                        float(0.4 * std::sin(b)));
    }
  indices.reserve(M * N * 16);
  for (int i = 0; i < M; ++i)
    for (int j = 0; j < N; ++j)
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) indices.push_back(std::uint32_t(((i + c - 1 + M) % M) * N + (j + r - 1 + N) % N));

  std::vector<float> texels(std::size_t(T) * T);
  for (int y = 0; y < T; ++y)
    for (int x = 0; x < T; ++x) {
      const double u = (x + 0.5) / T, v = (y + 0.5) / T;
      texels[std::size_t(y) * T + std::size_t(x)] =
          float(0.5 + 0.25 * std::sin(2 * pi * 8 * u) * std::sin(2 * pi * 8 * v) +
                0.25 * std::sin(2 * pi * (37 * u + 23 * v)));
    }
  std::string error;
  // The sizes above are valid by construction, so create() cannot fail.
  TorusScene s{std::move(cage), std::move(indices), *Texture2D::create(T, T, 1, std::move(texels), false, &error),
               glm::mat4(1.0f)};

  // The harness's camera, computed in double as it does: eye (0,-2.6,1.6), target origin, up +z,
  // fov_y 45 degrees, near 0.1, far 10. Column-major, as GL.
  const double eye[3] = {0, -2.6, 1.6};
  double f[3] = {-eye[0], -eye[1], -eye[2]}, up[3] = {0, 0, 1}, sv[3], uv[3];
  auto cross = [](const double* p, const double* q, double* o) {
    o[0] = p[1] * q[2] - p[2] * q[1];
    o[1] = p[2] * q[0] - p[0] * q[2];
    o[2] = p[0] * q[1] - p[1] * q[0];
  };
  auto normalize = [](double* v) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; ++k) v[k] /= l;
  };
  normalize(f);
  cross(f, up, sv);
  normalize(sv);
  cross(sv, f, uv);
  const double view[16] = {sv[0],
                           uv[0],
                           -f[0],
                           0,
                           sv[1],
                           uv[1],
                           -f[1],
                           0,
                           sv[2],
                           uv[2],
                           -f[2],
                           0,
                           -(sv[0] * eye[0] + sv[1] * eye[1] + sv[2] * eye[2]),
                           -(uv[0] * eye[0] + uv[1] * eye[1] + uv[2] * eye[2]),
                           (f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2]),
                           1};
  const double fy = 1.0 / std::tan(pi / 8), aspect = double(width) / height, zn = 0.1, zf = 10;
  const double proj[16] = {
      fy / aspect, 0, 0, 0, 0, fy, 0, 0, 0, 0, (zf + zn) / (zn - zf), -1, 0, 0, 2 * zf * zn / (zn - zf), 0};
  for (int c = 0; c < 4; ++c) {
    double col[4];
    for (int r = 0; r < 4; ++r) {
      double acc = 0;
      for (int k = 0; k < 4; ++k) acc += proj[k * 4 + r] * view[c * 4 + k];
      col[r] = acc;
    }
    // GL clip z in [-w, w] -> D3D's [0, w]: z' = (z + w) / 2, a monotonic remap of depth.
    col[2] = 0.5 * (col[2] + col[3]);
    for (int r = 0; r < 4; ++r) s.view_projection[c][r] = float(col[r]);
  }
  return s;
}

ClipVertex<3> DisplacedBsplineDS::operator()(const UniformFactorPatch&, std::span<const glm::vec3> cp,
                                             DomainLocation loc, std::uint32_t patch_id) const {
  const CubicBasis bu = bspline_basis(loc.u), bv = bspline_basis(loc.v);
  // Tensor-product evaluation row by row: each row's curve point and u-tangent, then combined in v.
  glm::vec3 p(0.0f), pu(0.0f), pv(0.0f);
  for (int r = 0; r < 4; ++r) {
    const glm::vec3* row = &cp[std::size_t(r * 4)];
    const glm::vec3 c = bu.b[0] * row[0] + bu.b[1] * row[1] + bu.b[2] * row[2] + bu.b[3] * row[3];
    const glm::vec3 cu = bu.d[0] * row[0] + bu.d[1] * row[1] + bu.d[2] * row[2] + bu.d[3] * row[3];
    p += bv.b[r] * c;
    pu += bv.b[r] * cu;
    pv += bv.d[r] * c;
  }
  const glm::vec3 n = glm::normalize(glm::cross(pu, pv));
  const int i = int(patch_id) / kTorusRows, j = int(patch_id) % kTorusRows;
  const glm::vec2 st((float(i) + loc.u) / float(kTorusColumns), (float(j) + loc.v) / float(kTorusRows));
  const float h = height->sample_level(sampler, st, 0.0f).x;
  p += n * scale * (h - 0.5f);
  ClipVertex<3> out;
  out.position = view_projection * glm::vec4(p, 1.0f);
  out.attributes = {n.x, n.y, n.z};
  return out;
}

namespace {

using simd::F8;
using simd::join;

// Eight domain points per step: with AVX one instruction per operation, otherwise two SSE ones (simd8.h).
constexpr std::size_t kLanes = 8;
using Lanes = std::array<float, kLanes>;

struct V3 {
  F8 x, y, z;
};
V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator*(F8 s, const V3& v) { return {s * v.x, s * v.y, s * v.z}; }
V3 splat(const glm::vec3& v) { return {F8::splat(v.x), F8::splat(v.y), F8::splat(v.z)}; }

// bspline_basis() in lanes, with its exact expression trees (left to right, as C++ groups them).
struct BasisLanes {
  F8 b[4], d[4];
};
BasisLanes basis_lanes(F8 t) {
  const F8 one = F8::splat(1.0f), three = F8::splat(3.0f), six = F8::splat(6.0f), half = F8::splat(0.5f);
  const F8 s = one - t;
  BasisLanes r;
  r.b[0] = ((s * s) * s) / six;
  r.b[1] = ((((three * t) * t) * t - (six * t) * t) + F8::splat(4.0f)) / six;
  r.b[2] = ((((F8::splat(-3.0f) * t) * t) * t + (three * t) * t + three * t) + one) / six;
  r.b[3] = ((t * t) * t) / six;
  r.d[0] = ((-s) * s) * half;
  r.d[1] = ((three * t) * t - F8::splat(4.0f) * t) * half;
  r.d[2] = ((((F8::splat(-3.0f) * t) * t) + F8::splat(2.0f) * t) + one) * half;
  r.d[3] = (t * t) * half;
  return r;
}

// Lane k's ClipVertex<3> (clip[0..3][k], its normal as attributes) to out[k], for k < count.
void store_vertices(const F8 (&clip)[4], F8 nx, F8 ny, F8 nz, ClipVertex<3>* out, std::size_t count) {
#if defined(__AVX__)
  static_assert(sizeof(ClipVertex<3>) == 28 && offsetof(ClipVertex<3>, attributes) == 16);
  // An 8x8 transpose puts lane k's seven values in one vector; each is stored as 32 bytes, the eighth
  // float landing on the next vertex's first, which the next store then writes. The last vertex's
  // store is masked to its 28 bytes.
  __m256 r[8] = {clip[0].v, clip[1].v, clip[2].v, clip[3].v, nx.v, ny.v, nz.v, _mm256_setzero_ps()};
  const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
  const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
  const __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]), t5 = _mm256_unpackhi_ps(r[4], r[5]);
  const __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]), t7 = _mm256_unpackhi_ps(r[6], r[7]);
  const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
  const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
  const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xEE);
  const __m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xEE);
  r[0] = _mm256_permute2f128_ps(u0, u4, 0x20), r[4] = _mm256_permute2f128_ps(u0, u4, 0x31);
  r[1] = _mm256_permute2f128_ps(u1, u5, 0x20), r[5] = _mm256_permute2f128_ps(u1, u5, 0x31);
  r[2] = _mm256_permute2f128_ps(u2, u6, 0x20), r[6] = _mm256_permute2f128_ps(u2, u6, 0x31);
  r[3] = _mm256_permute2f128_ps(u3, u7, 0x20), r[7] = _mm256_permute2f128_ps(u3, u7, 0x31);
  float* base = reinterpret_cast<float*>(out);
  for (std::size_t k = 0; k + 1 < count; ++k) _mm256_storeu_ps(base + 7 * k, r[k]);
  _mm256_maskstore_ps(base + 7 * (count - 1), _mm256_setr_epi32(-1, -1, -1, -1, -1, -1, -1, 0), r[count - 1]);
#else
  Lanes c[4], x, y, z;
  for (int row = 0; row < 4; ++row) clip[row].store(c[row]);
  nx.store(x), ny.store(y), nz.store(z);
  for (std::size_t k = 0; k < count; ++k) {
    out[k].position = glm::vec4(c[0][k], c[1][k], c[2][k], c[3][k]);
    out[k].attributes = {x[k], y[k], z[k]};
  }
#endif
}

}  // namespace

void DisplacedBsplineDS::operator()(const UniformFactorPatch&, std::span<const glm::vec3> cp,
                                    std::span<const DomainLocation> locations, std::uint32_t patch_id,
                                    std::span<ClipVertex<3>> out) const {
  const int pi = int(patch_id) / kTorusRows, pj = int(patch_id) % kTorusRows;
  V3 rows[16];
  for (std::size_t k = 0; k < 16; ++k) rows[k] = splat(cp[k]);
  const F8 zero = F8::splat(0.0f);
  for (std::size_t first = 0; first < locations.size(); first += kLanes) {
    // A short last group repeats its last point; the extra lanes are computed and dropped.
    const std::size_t count = std::min<std::size_t>(kLanes, locations.size() - first);
    std::array<const DomainLocation*, kLanes> l;
    for (std::size_t k = 0; k < kLanes; ++k) l[k] = &locations[first + std::min(k, count - 1)];
    using simd::F4;
    const F8 fu = F8::lanes(l[0]->u, l[1]->u, l[2]->u, l[3]->u, l[4]->u, l[5]->u, l[6]->u, l[7]->u);
    const F8 fv = F8::lanes(l[0]->v, l[1]->v, l[2]->v, l[3]->v, l[4]->v, l[5]->v, l[6]->v, l[7]->v);
    const BasisLanes bu = basis_lanes(fu), bv = basis_lanes(fv);
    V3 p{zero, zero, zero}, pu = p, pv = p;
    for (int r = 0; r < 4; ++r) {
      const V3* row = &rows[r * 4];
      const V3 c = ((bu.b[0] * row[0] + bu.b[1] * row[1]) + bu.b[2] * row[2]) + bu.b[3] * row[3];
      const V3 cu = ((bu.d[0] * row[0] + bu.d[1] * row[1]) + bu.d[2] * row[2]) + bu.d[3] * row[3];
      p = p + bv.b[r] * c;
      pu = pu + bv.b[r] * cu;
      pv = pv + bv.d[r] * c;
    }
    // glm::normalize(glm::cross(pu, pv)): cross in glm's order, then n * (1 / sqrt(dot(n, n))).
    const V3 cr{pu.y * pv.z - pv.y * pu.z, pu.z * pv.x - pv.z * pu.x, pu.x * pv.y - pv.x * pu.y};
    const F8 inv_len = F8::splat(1.0f) / simd::sqrt((cr.x * cr.x + cr.y * cr.y) + cr.z * cr.z);
    const V3 n{cr.x * inv_len, cr.y * inv_len, cr.z * inv_len};
    // The height texels, four lanes per texture call, at ((pi + u) / columns, (pj + v) / rows).
    Lanes s, t;
    ((F8::splat(float(pi)) + fu) / F8::splat(float(kTorusColumns))).store(s);
    ((F8::splat(float(pj)) + fv) / F8::splat(float(kTorusRows))).store(t);
    std::array<F4, 2> h4;
    for (std::size_t half = 0; half < kLanes; half += 4) {
      std::array<glm::vec2, 4> st;
      for (std::size_t k = 0; k < 4; ++k) st[k] = glm::vec2(s[half + k], t[half + k]);
      std::array<glm::vec4, 4> texels;
      height->sample_level4(sampler, st, 0.0f, texels);
      h4[half / 4] = F4::lanes(texels[0].x, texels[1].x, texels[2].x, texels[3].x);
    }
    const F8 h = join(h4[0], h4[1]);
    // p += n * scale * (h - 0.5f), grouped as glm does: (n * scale) * (h - 0.5f).
    const F8 dh = h - F8::splat(0.5f), sc = F8::splat(scale);
    p = p + V3{(n.x * sc) * dh, (n.y * sc) * dh, (n.z * sc) * dh};
    // view_projection * vec4(p, 1), in glm's order: (m0 x + m1 y) + (m2 z + m3 * 1).
    const glm::mat4& m = view_projection;
    F8 clip[4];
    for (int row = 0; row < 4; ++row) {
      const F8 m0 = F8::splat(m[0][row]), m1 = F8::splat(m[1][row]), m2 = F8::splat(m[2][row]);
      const F8 m3 = F8::splat(m[3][row]) * F8::splat(1.0f);
      clip[row] = (m0 * p.x + m1 * p.y) + (m2 * p.z + m3);
    }
    store_vertices(clip, n.x, n.y, n.z, &out[first], count);
  }
}

TorusDraw make_torus_draw(const TorusScene& scene, float factor, ts::Partitioning partitioning, int width, int height) {
  TorusDraw d;
  d.vertices = scene.cage;
  d.indices = scene.indices;
  d.control_points = 16;
  d.hs.factor = factor;
  d.ds.height = &scene.height;
  d.ds.view_projection = scene.view_projection;
  d.tessellator = {ts::Domain::quad, partitioning, ts::OutputPrimitive::triangle_cw};
  d.rasterizer.cull = CullMode::none;  // the harness does not enable face culling
  d.depth = {true, true, CompareFunc::less};
  d.viewport = {0, 0, float(width), float(height), 0, 1};
  return d;
}

}  // namespace tessera::render
