#include "torus_scene.h"

#include <cmath>
#include <numbers>

namespace tessera::scenes {

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
        for (int c = 0; c < 4; ++c)
          indices.push_back(std::uint32_t(((i + c - 1 + M) % M) * N + (j + r - 1 + N) % N));

  std::vector<float> texels(std::size_t(T) * T);
  for (int y = 0; y < T; ++y)
    for (int x = 0; x < T; ++x) {
      const double u = (x + 0.5) / T, v = (y + 0.5) / T;
      texels[std::size_t(y) * T + std::size_t(x)] =
          float(0.5 + 0.25 * std::sin(2 * pi * 8 * u) * std::sin(2 * pi * 8 * v) + 0.25 * std::sin(2 * pi * (37 * u + 23 * v)));
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
  const double view[16] = {sv[0], uv[0], -f[0], 0, sv[1], uv[1], -f[1], 0, sv[2], uv[2], -f[2], 0,
                           -(sv[0] * eye[0] + sv[1] * eye[1] + sv[2] * eye[2]),
                           -(uv[0] * eye[0] + uv[1] * eye[1] + uv[2] * eye[2]),
                           (f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2]), 1};
  const double fy = 1.0 / std::tan(pi / 8), aspect = double(width) / height, zn = 0.1, zf = 10;
  const double proj[16] = {fy / aspect, 0, 0, 0, 0, fy, 0, 0, 0, 0, (zf + zn) / (zn - zf), -1, 0, 0, 2 * zf * zn / (zn - zf), 0};
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

}  // namespace tessera::scenes
