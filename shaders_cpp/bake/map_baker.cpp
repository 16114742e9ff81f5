#include "shaders_cpp/bake/map_baker.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <tbb/parallel_for.h>

#include "shaders_cpp/bake/parameter_locator.h"
#include "shaders_cpp/bake/ray_caster.h"
#include "shaders_cpp/bake/texel_sites.h"
#include "shaders_cpp/displacement/chart_padding.h"

namespace tessera {
namespace {

// The dense surface at a texel: its point and unit normal.
struct DensePoint {
  glm::dvec3 position{0.0};
  glm::vec3 normal{0.0f};
};

DensePoint interpolate(const DenseMesh& m, std::uint32_t triangle, const glm::dvec3& w) {
  const std::uint32_t* t = m.triangles.data() + 3 * std::size_t(triangle);
  DensePoint p;
  p.position =
      w.x * glm::dvec3(m.positions[t[0]]) + w.y * glm::dvec3(m.positions[t[1]]) + w.z * glm::dvec3(m.positions[t[2]]);
  const glm::dvec3 n =
      w.x * glm::dvec3(m.normals[t[0]]) + w.y * glm::dvec3(m.normals[t[1]]) + w.z * glm::dvec3(m.normals[t[2]]);
  const double len = glm::length(n);
  p.normal = len > 0.0 ? glm::vec3(n / len) : glm::vec3(0.0f);
  return p;
}

// Van der Corput's radical inverse in base 2: the second coordinate of a Hammersley point.
double radical_inverse(std::uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
  i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
  i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
  i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
  return double(i) * 0x1p-32;
}

// A per-texel offset in [0, 1) from its coordinates (a fixed integer hash: no hidden state).
double texel_hash(std::uint32_t x, std::uint32_t y, std::uint32_t salt) {
  std::uint64_t h = (std::uint64_t(x) << 32 | y) * 0x9E3779B97F4A7C15ull + salt;
  h ^= h >> 31, h *= 0xBF58476D1CE4E5B9ull, h ^= h >> 27, h *= 0x94D049BB133111EBull, h ^= h >> 31;
  return double(h >> 11) * 0x1p-53;
}

// The fraction of `rays` cosine-distributed directions about n that escape from p within `distance`.
float ambient_occlusion(const RayCaster& rays, const DensePoint& p, int count, float distance, int x, int y) {
  const glm::dvec3 n(p.normal);
  if (n == glm::dvec3(0.0)) return 1.0f;
  const glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(a, n)), b = glm::cross(n, t);
  const double su = texel_hash(std::uint32_t(x), std::uint32_t(y), 1),
               sv = texel_hash(std::uint32_t(x), std::uint32_t(y), 2);
  // Leave the surface by a hair: the dense triangles' own plane would occlude every ray.
  const double lift = 1e-4 * double(distance);
  const glm::vec3 origin(p.position + lift * n);
  int open = 0;
  for (int i = 0; i < count; ++i) {
    const double r1 = std::fmod((i + 0.5) / count + su, 1.0),
                 r2 = std::fmod(radical_inverse(std::uint32_t(i)) + sv, 1.0);
    const double r = std::sqrt(r1), phi = 2.0 * std::numbers::pi * r2;
    const glm::dvec3 d = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1.0 - r1)) * n;
    if (!rays.occluded(origin, glm::vec3(glm::normalize(d)), 0.0f, distance)) ++open;
  }
  return float(open) / float(count);
}

}  // namespace

void check_bake_inputs(const DenseMesh& dense, const BakeOptions& o) {
  if (o.method == BakeMethod::dual && !dense.parameterised())
    throw BakeError(dense.name +
                    ": --method dual needs the cage's parameterisation on each vertex (face, u, v: tessera "
                    "tessellate's PLY); use --method raycast");
}

BakedMaps bake_maps(const SubdModel& model, std::span<const PatchTexcoords> texcoords, const DenseMesh& dense,
                    const BakeOptions& o, const std::function<void(double)>& progress) {
  check_bake_inputs(dense, o);
  const int w = o.width, h = o.height;
  const BaseSurface base(model, texcoords);
  const std::vector<TexelSite> sites = texel_sites(texcoords, w, h);
  std::optional<ParameterLocator> locator;
  if (o.method == BakeMethod::dual) locator.emplace(dense, model.cage.face_count());
  std::optional<RayCaster> rays;
  if (o.method == BakeMethod::raycast || o.ao) rays.emplace(dense);

  BakedMaps out;
  out.width = w, out.height = h;
  out.displacement_channels = o.kind == BakeKind::vector ? 3 : 1;
  const std::size_t texels = std::size_t(w) * std::size_t(h);
  out.displacement.assign(texels * std::size_t(out.displacement_channels), 0.0f);
  if (o.normal_map) out.normal.assign(texels * 3, 0.5f);
  if (o.ao) out.ao.assign(texels, 1.0f);
  std::vector<std::uint8_t> found(texels, 0);
  std::vector<double> row_max(std::size_t(h), 0.0);

  auto bake_row = [&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      const TexelSite& site = sites[i];
      if (site.patch < 0) continue;
      const BaseFrame f = base.evaluate(std::uint32_t(site.patch), site.u, site.v);
      std::optional<DensePoint> p;
      double along = 0.0;  // ray casting: the signed distance along the normal
      if (locator) {
        if (const auto l = locator->locate(f.face, glm::vec2(f.face_u, f.face_v)))
          p = interpolate(dense, l->triangle, l->weights);
      } else if (const auto hit = rays->hit_on_line(f.position, f.normal, o.max_distance, o.preference)) {
        p = interpolate(dense, hit->triangle, hit->weights);
        p->position = hit->point;
        along = hit->t;
      }
      if (!p) continue;
      found[i] = 1;
      const glm::dvec3 d = p->position - glm::dvec3(f.position);
      row_max[std::size_t(y)] = std::max(row_max[std::size_t(y)], glm::length(d));
      float* out_d = out.displacement.data() + i * std::size_t(out.displacement_channels);
      if (o.kind == BakeKind::scalar) {
        out_d[0] = float(locator ? glm::dot(d, glm::dvec3(f.normal)) : along);
      } else if (o.space == DisplacementSpace::object) {
        out_d[0] = float(d.x), out_d[1] = float(d.y), out_d[2] = float(d.z);
      } else {
        out_d[0] = float(glm::dot(d, glm::dvec3(f.tangent)));
        out_d[1] = float(glm::dot(d, glm::dvec3(f.bitangent)));
        out_d[2] = float(glm::dot(d, glm::dvec3(f.normal)));
      }
      if (o.normal_map) {
        const glm::vec3 n = p->normal;
        const float nx = glm::dot(n, f.shade_tangent), ny = glm::dot(n, f.shade_bitangent), nz = glm::dot(n, f.normal);
        float* out_n = out.normal.data() + 3 * i;
        // Encoded as (n + 1) / 2, clamped: rounding can take a unit component a hair past 1.
        auto encode = [](float c) { return std::clamp(0.5f * (c + 1.0f), 0.0f, 1.0f); };
        out_n[0] = encode(nx), out_n[1] = encode(o.flip_green ? -ny : ny), out_n[2] = encode(nz);
      }
      if (o.ao) out.ao[i] = ambient_occlusion(*rays, *p, o.ao_rays, o.ao_distance, x, y);
    }
  };
  // Batches of rows, each spread over the threads; progress between batches, on this thread.
  constexpr int kBatches = 64;
  for (int b = 0; b < kBatches; ++b) {
    const int y0 = int(std::int64_t(h) * b / kBatches), y1 = int(std::int64_t(h) * (b + 1) / kBatches);
    tbb::parallel_for(y0, y1, bake_row);
    if (progress) progress(double(b + 1) / kBatches);
  }

  for (std::size_t i = 0; i < texels; ++i) {
    out.texels_covered += sites[i].patch >= 0;
    out.texels_missed += sites[i].patch >= 0 && !found[i];
  }
  out.texels_padded = texels - (out.texels_covered - out.texels_missed);
  out.max_displacement = *std::max_element(row_max.begin(), row_max.end());
  pad_charts(out.displacement, w, h, out.displacement_channels, found);
  if (o.normal_map) pad_charts(out.normal, w, h, 3, found);
  if (o.ao) pad_charts(out.ao, w, h, 1, found);
  return out;
}

}  // namespace tessera
