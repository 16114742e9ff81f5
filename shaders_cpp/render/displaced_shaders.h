// Displacement mapping on the subdivision schemes, as shader functors wrapping the scheme's own
// (subd_shaders.h):
// - DisplacedHS: SubdHS's control points; its patch constants add the owners' edge and corner frames
//   (displacement_frames.h: shared stencil units summed in the patch's global vertex order) and the sampling LODs.
// - DisplacedDS: SubdDS's surface point, moved by the map sampled at the watertight UV
//   (watertight_uv.h) with an explicit LOD, bilinear within the level (clamp addressing):
//   scalar: along the unit normal; vector, tangent space: x T + y B + z N (T along the texture's U
//   direction in the tangent plane, B = ±N x T following the UV orientation); vector, object space: as
//   is. value = scale * texel + bias (per component for vectors).
// - DisplacedProjectDS and DisplacedPS: rendering, shaded with a tangent-space normal map or with
//   normals derived from the height map.
//
// Watertight, bitwise, for points on a cage edge or vertex (u or v exactly 0 or 1):
// - the UV is the owner's (edge: a (1 − t) + b t at the owner's parameter; vertex: the owner's UV);
// - the normal (and the tangent frame) is the owner frame's, evaluated at the owner's parameter from
//   control vectors both patches computed from the same stencils (`exact` uses the limit surface's own
//   normals, which it already evaluates by owner; only its tangent comes from the frame);
// - the LOD is a function of shared data only (the rule, also in shaders_cpp/displacement/README.md):
//     edge point:    log2(texel length of the owner's UV edge / that edge's factor);
//     vertex point:  the same for the vertex owner's outgoing edge;
//     interior:      log2(max(Lu / inside_u, Lv / inside_v)), Lu and Lv the longer texel length of
//                    the patch's two UV edges in each direction;
//   i.e. texels per tessellated segment; factors below 1 count as 1 and the sampler clamps the LOD to
//   the map's levels. Interior points use their patch's LOD (no crack can come from it);
// - the map: with UDIM tiles (udim_tiles.h), the tile of the face whose UVs the point takes (its own
//   inside, the owner's on edges and vertices), each slot's UVs in that tile's coordinates.
// With the scheme's own watertight positions, the displaced positions are then bit-identical.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "pipeline/simd8.h"
#include "pipeline/texture.h"
#include "shaders_cpp/displacement/displacement_frames.h"
#include "shaders_cpp/displacement/displacement_map.h"
#include "shaders_cpp/displacement/watertight_uv.h"
#include "shaders_cpp/render/subd_shaders.h"
#include "shaders_cpp/subdiv/patch_eval.h"

namespace tessera {

enum class DisplacementKind : std::uint8_t { scalar, vector_tangent, vector_object };

struct DisplacementParams {
  std::span<const DisplacementMap> maps;  // per tile (PatchTexcoords' tile slots); 1 channel (scalar) or 3 (vector)
  DisplacementKind kind = DisplacementKind::scalar;
  float scale = 1.0f, bias = 0.0f;
  // Test knob: false displaces every point along its own patch's normal (cracks for acc and gregory).
  bool shared_normals = true;
  // Blend the two nearest mip levels (MIN_MAG_MIP_LINEAR) instead of taking the nearest
  // (MIN_MAG_LINEAR_MIP_POINT): under view-dependent LOD the sampling LOD moves with the camera, and
  // a nearest-level switch would move every displaced point of a patch at once (a pop).
  bool trilinear = false;
  // Test knob: false shades from the sampled UV everywhere (the seam lines of DisplacedPoint's note).
  bool own_chart_shading = true;
};

struct DisplacedPatchConstants {
  TessFactors factors;
  std::array<std::array<glm::vec3, 8>, 4> edge{};    // per patch edge: along A0..A3, cross C0..C3 (owner's)
  std::array<std::array<glm::vec3, 2>, 4> corner{};  // per patch corner: the vertex owner's two tangents
  float lod_interior = 0.0f;
  std::array<float, 4> lod_edge{}, lod_corner{};
};

// The length in texels of a UV step.
inline float texel_length(glm::vec2 duv, glm::vec2 map_size) {
  const glm::vec2 texels = duv * map_size;
  return std::sqrt(texels.x * texels.x + texels.y * texels.y);
}
// A factor below 1 (or NaN) counts as 1 segment.
inline float segments(float factor) { return factor > 1.0f ? factor : 1.0f; }
// log2 of texels per segment, floored so that a zero length gives a finite LOD.
inline float texels_per_segment_lod(float x) { return std::log2(x > 1e-20f ? x : 1e-20f); }

// log2(texels per segment) of a UV step covering `factor` segments; see the LOD rule above.
// (`map_size` is the size of the tile the step's UVs are in.)
inline float displacement_lod(glm::vec2 duv, glm::vec2 map_size, float factor) {
  return texels_per_segment_lod(texel_length(duv, map_size) / segments(factor));
}

struct DisplacedHS {
  static constexpr int kOutputControlPoints = SubdHS::kOutputControlPoints;
  SubdHS base;
  std::span<const PatchTexcoords> texcoords;
  const PatchFrames* frames = nullptr;
  std::span<const glm::vec2> map_sizes;  // per tile: level 0's width and height
  std::span<const glm::vec3> precomputed_frames{};  // precompute_rows(frames->precomputed, posed cage)

  SubdControlPoint control_point(std::span<const SubdVertex> in, int i, std::uint32_t patch_id) const {
    return base.control_point(in, i, patch_id);
  }

  DisplacedPatchConstants patch_constants(std::span<const SubdVertex> in, std::span<const SubdControlPoint> out,
                                          std::uint32_t patch_id) const {
    DisplacedPatchConstants pc;
    pc.factors = base.patch_constants(in, out, patch_id).factors;
    const SubdPatch& patch = base.patches[patch_id];
    // In the patch's global vertex order, skipping zero weights: the bits every patch sharing the
    // element computes (displacement_frames.h).
    auto stencil = [&](int r) {
      if (patch.precomputed >= 0) return precomputed_frames[std::size_t(frames->precomputed_first[patch_id] + r)];
      const std::uint32_t s = frames->stencil(patch_id, r), mask = frames->masks[s];
      const float* w = frames->weights.data() + frames->starts[s];
      glm::dvec3 sum(0.0);
      if (mask == 0) return glm::vec3(sum);
      for (int k = 0; k < patch.ring_size; ++k) {
        const int j = patch.order[std::size_t(k)];
        if ((mask >> j & 1u) == 0) continue;
        const float weight = w[std::popcount(mask & ((std::uint32_t(1) << j) - 1u))];
        sum += double(weight) * glm::dvec3(in[std::size_t(j)].position);
      }
      return glm::vec3(sum);
    };
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 8; ++i) pc.edge[std::size_t(k)][std::size_t(i)] = stencil(8 * k + i);
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 2; ++i) pc.corner[std::size_t(k)][std::size_t(i)] = stencil(32 + 2 * k + i);

    const PatchTexcoords& tc = texcoords[patch_id];
    for (int k = 0; k < 4; ++k) {
      const auto& e = tc.edge[std::size_t(k)];
      // Patch edge k is SV_TessFactor (k + 1) % 4.
      pc.lod_edge[std::size_t(k)] = displacement_lod(e[1] - e[0], map_sizes[tc.edge_tile[std::size_t(k)]],
                                                     pc.factors.edge[std::size_t((k + 1) % 4)]);
      pc.lod_corner[std::size_t(k)] =
          displacement_lod(tc.corner_span[std::size_t(k)][0], map_sizes[tc.corner_tile[std::size_t(k)]],
                           base.factors.edge(tc.corner_key[std::size_t(k)]));
    }
    const glm::vec2 map_size = map_sizes[tc.tile];
    const auto& c = tc.interior;
    const float lu = std::max(texel_length(c[1] - c[0], map_size), texel_length(c[2] - c[3], map_size));
    const float lv = std::max(texel_length(c[3] - c[0], map_size), texel_length(c[2] - c[1], map_size));
    pc.lod_interior =
        texels_per_segment_lod(std::max(lu / segments(pc.factors.inside[0]), lv / segments(pc.factors.inside[1])));
    return pc;
  }
};

// A displaced domain point: the displaced position; the base surface's unit normal it moved along (shared
// on edges and vertices); the base face and location (SurfaceSample's); the UV the map was sampled at
// and the base surface's derivatives with respect to it (the owner's on edges and vertices: what makes
// the position watertight); and the texture coordinate and derivatives the pixel shader reads.
//
// Why two: on a UV seam the owner's UV lies in the other face's chart. Interpolated across a triangle
// whose other vertices lie in this patch's chart, it would sweep the texture between the two charts and
// shade the row of triangles along every seam from texels of neither (visible seam lines). So
// where the owner's chart is not this patch's (the non-owner side of a seam edge, a seam vertex owned
// by another chart), shading takes the patch's own UV and its own derivatives; everywhere else it takes
// exactly the sampling data, whose bits both sides of an ordinary edge share.
struct DisplacedPoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};
  std::uint32_t face = 0;
  float u = 0, v = 0;
  glm::vec3 dpdu{0.0f}, dpdv{0.0f};
  glm::vec2 uv{0.0f};
  glm::vec3 shade_dpdu{0.0f}, shade_dpdv{0.0f};
  glm::vec2 shade_uv{0.0f};
  float patch_u = 0, patch_v = 0;  // the domain location (patch corner k at (0,0),(1,0),(1,1),(0,1))
};

// dP/dU and dP/dV from the derivatives along two parameters a, b and the UV's derivatives along them.
inline void texture_derivatives(const glm::vec3& pa, const glm::vec3& pb, glm::vec2 ja, glm::vec2 jb, glm::vec3& dpdu,
                                glm::vec3& dpdv) {
  const float det = ja.x * jb.y - jb.x * ja.y;
  if (det != 0.0f && std::isfinite(det)) {
    dpdu = (pa * jb.y - pb * ja.y) / det;
    dpdv = (pb * ja.x - pa * jb.x) / det;
  } else {
    dpdu = pa, dpdv = pb;
  }
}

struct DisplacedDS {
  SubdDS base;
  std::span<const PatchTexcoords> texcoords;
  DisplacementParams params;

  // The batch form, for ProjectingDS: out[i] = (*this)(pc, cp, locations[i], patch_id), the patch
  // evaluated in lanes where SubdDS::evaluate_lanes can, and the map sampled four points at a time
  // (Texture2D::sample_level4, the same bits) where consecutive points share their LOD (a patch's
  // interior points, an edge's points).
  void samples(const DisplacedPatchConstants& pc, std::span<const SubdControlPoint> cp,
               std::span<const DomainLocation> locations, std::uint32_t patch_id, std::span<DisplacedPoint> out) const {
    const Sampler s = sampler();
    // Points prepared, not yet displaced, all at LOD `pending_lod` in tile `pending_tile`.
    std::array<std::size_t, 4> pending{};
    std::size_t held = 0;
    float pending_lod = 0.0f;
    std::uint16_t pending_tile = 0;
    const auto displace_pending = [&] {
      const Texture2D& map = params.maps[pending_tile].texture();
      if (held == 4) {
        std::array<glm::vec2, 4> uv;
        std::array<glm::vec4, 4> texel;
        for (std::size_t k = 0; k < 4; ++k) uv[k] = out[pending[k]].uv;
        map.sample_level4(s, uv, pending_lod, texel);
        for (std::size_t k = 0; k < 4; ++k) displace(out[pending[k]], texel[k]);
      } else {
        for (std::size_t k = 0; k < held; ++k) displace(out[pending[k]], map.sample_level(s, out[pending[k]].uv, pending_lod));
      }
      held = 0;
    };
    const SubdPatch& patch = base.patches[patch_id];
    // prepare()'s interior branch runs eight points at a time where nothing per point can differ from
    // it: a quad patch evaluated in lanes (its normal is the derivatives' cross product there; corner
    // and crease-line normals apply on edges only).
    const bool interior_lanes = !base.triangles && patch.kind != PatchKind::exact;
    base.for_evaluated_blocks(patch, cp, locations, [&](std::size_t first, std::size_t n, const PatchPoint* points) {
      std::array<bool, SubdDS::kLanesBlock> prepared{};
      if (points != nullptr && interior_lanes) {
        std::array<std::size_t, 8> group{};
        std::size_t grouped = 0;
        const auto flush = [&] {
          if (grouped != 0 && prepare_interior8(patch_id, locations, first, points, group, grouped, out))
            for (std::size_t k = 0; k < grouped; ++k) prepared[group[k]] = true;
          grouped = 0;
        };
        for (std::size_t k = 0; k < n; ++k) {
          const DomainLocation& l = locations[first + k];
          if (l.u == 0.0f || l.u == 1.0f || l.v == 0.0f || l.v == 1.0f) continue;
          group[grouped++] = k;
          if (grouped == 8) flush();
        }
        flush();
      }
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = first + k;
        float lod = pc.lod_interior;
        std::uint16_t tile = texcoords[patch_id].tile;
        if (!prepared[k]) prepare(pc, cp, locations[i], patch_id, points ? &points[k] : nullptr, out[i], lod, tile);
        // A group holds one LOD's bits (a NaN LOD is its own group) in one tile.
        if (held != 0 &&
            (std::bit_cast<std::uint32_t>(lod) != std::bit_cast<std::uint32_t>(pending_lod) || tile != pending_tile))
          displace_pending();
        pending_lod = lod;
        pending_tile = tile;
        pending[held++] = i;
        if (held == 4) displace_pending();
      }
    });
    displace_pending();
  }

  // `evaluated`, when given, is the base patch's PatchPoint at `loc` (SubdDS::operator()).
  DisplacedPoint operator()(const DisplacedPatchConstants& pc, std::span<const SubdControlPoint> cp, DomainLocation loc,
                            std::uint32_t patch_id, const PatchPoint* evaluated = nullptr) const {
    float lod = 0.0f;
    std::uint16_t tile = 0;
    DisplacedPoint out;
    prepare(pc, cp, loc, patch_id, evaluated, out, lod, tile);
    displace(out, params.maps[tile].texture().sample_level(sampler(), out.uv, lod));
    return out;
  }

 private:
  Sampler sampler() const {
    Sampler s;
    s.filter = params.trilinear ? Filter::trilinear : Filter::bilinear;
    s.address_u = s.address_v = AddressMode::clamp;
    return s;
  }

  // The point before displacement, every field of `out` written: `position` is the base surface's, and
  // the map is to be sampled at `uv`, `sample_lod` and in `sample_tile` (set here); displace() then moves it. (Written in
  // place: a returned point was built on the stack and copied into the caller's array, and the copy's
  // wide loads waited on the narrow stores that built it.)
  void prepare(const DisplacedPatchConstants& pc, std::span<const SubdControlPoint> cp, DomainLocation loc,
               std::uint32_t patch_id, const PatchPoint* evaluated, DisplacedPoint& out, float& sample_lod,
               std::uint16_t& sample_tile) const {
    const SurfaceSample s = base(SubdPatchConstants{pc.factors, {}}, cp, loc, patch_id, evaluated);
    const PatchTexcoords& tc = texcoords[patch_id];
    const bool exact = base.patches[patch_id].kind == PatchKind::exact;
    const float u = loc.u, v = loc.v;
    out.face = s.face, out.u = s.u, out.v = s.v;
    out.patch_u = loc.u, out.patch_v = loc.v;
    glm::vec3 n = s.normal, pa = s.du, pb = s.dv;
    glm::vec2 ja, jb, uv;
    float lod = pc.lod_interior;
    std::uint16_t tile = tc.tile;
    const bool on_u = u == 0.0f || u == 1.0f, on_v = v == 0.0f || v == 1.0f;
    bool other_chart = false;  // the UV sampled here is in another face's chart (see DisplacedPoint)
    if (on_u && on_v) {
      const int k = v == 0.0f ? (u == 0.0f ? 0 : 1) : (u == 1.0f ? 2 : 3);
      const auto& t = pc.corner[std::size_t(k)];
      uv = tc.corner[std::size_t(k)];
      tile = tc.corner_tile[std::size_t(k)];
      other_chart = uv != tc.interior[std::size_t(k)] || tile != tc.tile;
      lod = pc.lod_corner[std::size_t(k)];
      pa = t[0], pb = t[1];
      ja = tc.corner_span[std::size_t(k)][0], jb = tc.corner_span[std::size_t(k)][1];
      if (exact)
        owner_derivatives(tc.vertex_face[std::size_t(k)], tc.vertex_corner[std::size_t(k)], 0.0f, pa, pb);
      else if (params.shared_normals)
        n = oriented(unit_or_zero(glm::cross(pa, pb)));
    } else if (on_u || on_v) {
      int k;
      float t;
      if (v == 0.0f)
        k = 0, t = u;
      else if (u == 1.0f)
        k = 1, t = v;
      else if (v == 1.0f)
        k = 2, t = 1.0f - u;
      else
        k = 3, t = 1.0f - v;
      const auto& e = tc.edge[std::size_t(k)];
      const auto& f = pc.edge[std::size_t(k)];
      // The owner's parameter: exact, tessellator parameters are multiples of 2^-16.
      const float to = tc.reversed[std::size_t(k)] ? 1.0f - t : t;
      const float so = 1.0f - to;
      uv = e[0] * so + e[1] * to;
      // This patch's own UVs at the owner's edge ends a and b.
      const glm::vec2 own_a = tc.interior[std::size_t(tc.reversed[std::size_t(k)] ? (k + 1) % 4 : k)];
      const glm::vec2 own_b = tc.interior[std::size_t(tc.reversed[std::size_t(k)] ? k : (k + 1) % 4)];
      tile = tc.edge_tile[std::size_t(k)];
      other_chart = own_a != e[0] || own_b != e[1] || tile != tc.tile;
      lod = pc.lod_edge[std::size_t(k)];
      ja = e[1] - e[0];
      jb = so * (e[3] - e[0]) + to * (e[2] - e[1]);
      if (exact) {
        owner_derivatives(tc.edge_face[std::size_t(k)], tc.edge_corner[std::size_t(k)], to, pa, pb);
      } else {
        const Cubic b = cubic_bernstein(to);
        pa = cubic_sum(b, f[0], f[1], f[2], f[3]);
        pb = cubic_sum(b, f[4], f[5], f[6], f[7]);
        if (params.shared_normals) n = oriented(unit_or_zero(glm::cross(pa, pb)));
      }
    } else {
      uv = bilerp_uv(tc.interior, u, v);
      const auto& c = tc.interior;
      ja = (1.0f - v) * (c[1] - c[0]) + v * (c[2] - c[3]);
      jb = (1.0f - u) * (c[3] - c[0]) + u * (c[2] - c[1]);
    }
    // Into locals first, then each field of `out` from them: copying one field of `out` into another
    // read back its fresh stores (a store-forwarding stall per point).
    glm::vec3 dpdu, dpdv;
    texture_derivatives(pa, pb, ja, jb, dpdu, dpdv);
    out.dpdu = dpdu, out.dpdv = dpdv;
    out.normal = n;
    out.uv = uv;
    if (other_chart && params.own_chart_shading) {
      const auto& c = tc.interior;
      out.shade_uv = bilerp_uv(c, u, v);
      texture_derivatives(s.du, s.dv, (1.0f - v) * (c[1] - c[0]) + v * (c[2] - c[3]),
                          (1.0f - u) * (c[3] - c[0]) + u * (c[2] - c[1]), out.shade_dpdu, out.shade_dpdv);
    } else {
      out.shade_uv = uv, out.shade_dpdu = dpdu, out.shade_dpdv = dpdv;
    }

    out.position = s.position;
    sample_lod = lod;
    sample_tile = tile;
  }

  // A prepared point moved by the map's `texel` (sampled at its uv and LOD) along its normal, tangent
  // frame or object axes.
  void displace(DisplacedPoint& p, const glm::vec4& texel) const {
    const glm::vec3& n = p.normal;
    switch (params.kind) {
      case DisplacementKind::scalar: p.position = p.position + (params.scale * texel.x + params.bias) * n; break;
      case DisplacementKind::vector_object:
        p.position = p.position + (params.scale * glm::vec3(texel) + params.bias);
        break;
      case DisplacementKind::vector_tangent: {
        const glm::vec3 tangent = unit_or_zero(p.dpdu - glm::dot(n, p.dpdu) * n);
        glm::vec3 bitangent = glm::cross(n, tangent);
        if (glm::dot(bitangent, p.dpdv) < 0.0f) bitangent = -bitangent;
        const glm::vec3 d = params.scale * glm::vec3(texel) + params.bias;
        p.position = p.position + ((d.x * tangent + d.y * bitangent) + d.z * n);
        break;
      }
    }
  }

  // prepare() of up to eight interior locations (0 < u, v < 1) of a quad patch, locations[first +
  // group[k]] with their PatchPoints points[group[k]], in simd::F8 lanes: each lane computes SubdDS's
  // and prepare()'s expressions on the same operands in the same order (glm's vec3 and vec2 operations
  // are per component), and their branches are taken per lane. False, with nothing written, when a
  // lane's derivatives are parallel (SubdDS then steps into the patch: left to prepare()).
  bool prepare_interior8(std::uint32_t patch_id, std::span<const DomainLocation> locations, std::size_t first,
                         const PatchPoint* points, const std::array<std::size_t, 8>& group, std::size_t count,
                         std::span<DisplacedPoint> out) const {
    using simd::F8;
    const SubdPatch& patch = base.patches[patch_id];
    // The lanes are read from the points one by one (F8::lanes): a vector load of values just stored one
    // by one would wait for the stores to reach the cache. A short group repeats its first point.
    const auto lanes_of = [&](auto value) {  // value(j) for the group's point j in each lane
      const auto at = [&](std::size_t k) { return value(group[k < count ? k : 0]); };
      return F8::lanes(at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7));
    };
    const F8 Ax = lanes_of([&](std::size_t j) { return points[j].du.x; });
    const F8 Ay = lanes_of([&](std::size_t j) { return points[j].du.y; });
    const F8 Az = lanes_of([&](std::size_t j) { return points[j].du.z; });
    const F8 Bx = lanes_of([&](std::size_t j) { return points[j].dv.x; });
    const F8 By = lanes_of([&](std::size_t j) { return points[j].dv.y; });
    const F8 Bz = lanes_of([&](std::size_t j) { return points[j].dv.z; });
    // SubdDS: n = cross(du, dv); the parallel-derivatives test on dot(n, n) against dot(du, du) *
    // dot(dv, dv); the unit normal n / length(n), or zero.
    const F8 nx = Ay * Bz - By * Az, ny = Az * Bx - Bz * Ax, nz = Ax * By - Bx * Ay;
    const F8 nn = (nx * nx + ny * ny) + nz * nz;
    const F8 scale = ((Ax * Ax + Ay * Ay) + Az * Az) * ((Bx * Bx + By * By) + Bz * Bz);
    std::array<float, 8> nn_lanes, scale_lanes;
    nn.store(nn_lanes);
    scale.store(scale_lanes);
    for (std::size_t k = 0; k < count; ++k)
      if (nn_lanes[k] <= kParallelDerivatives * scale_lanes[k]) return false;
    const F8 len = simd::sqrt(nn);
    std::array<float, 8> nx_unit, ny_unit, nz_unit, len_lanes;
    (nx / len).store(nx_unit);
    (ny / len).store(ny_unit);
    (nz / len).store(nz_unit);
    len.store(len_lanes);
    // prepare()'s interior branch: the UV bilinear in the patch's corner UVs (bilerp_uv), its
    // derivatives along u and v, and texture_derivatives' solve.
    const auto& c = texcoords[patch_id].interior;
    const F8 u = lanes_of([&](std::size_t j) { return locations[first + j].u; });
    const F8 v = lanes_of([&](std::size_t j) { return locations[first + j].v; });
    const F8 one = F8::splat(1.0f);
    const F8 su = one - u, tv = one - v;
    const auto splat2 = [](glm::vec2 a) { return std::array<F8, 2>{F8::splat(a.x), F8::splat(a.y)}; };
    const auto c0 = splat2(c[0]), c1 = splat2(c[1]), c2 = splat2(c[2]), c3 = splat2(c[3]);
    std::array<F8, 2> uv, ja, jb;
    for (std::size_t i = 0; i < 2; ++i) {
      uv[i] = tv * (su * c0[i] + u * c1[i]) + v * (su * c3[i] + u * c2[i]);
      ja[i] = tv * F8::splat(c[1][int(i)] - c[0][int(i)]) + v * F8::splat(c[2][int(i)] - c[3][int(i)]);
      jb[i] = su * F8::splat(c[3][int(i)] - c[0][int(i)]) + u * F8::splat(c[2][int(i)] - c[1][int(i)]);
    }
    const F8 det = ja[0] * jb[1] - jb[0] * ja[1];
    std::array<float, 8> dux, duy, duz, dvx, dvy, dvz, det_lanes, uv0, uv1;
    ((Ax * jb[1] - Bx * ja[1]) / det).store(dux);
    ((Ay * jb[1] - By * ja[1]) / det).store(duy);
    ((Az * jb[1] - Bz * ja[1]) / det).store(duz);
    ((Bx * ja[0] - Ax * jb[0]) / det).store(dvx);
    ((By * ja[0] - Ay * jb[0]) / det).store(dvy);
    ((Bz * ja[0] - Az * jb[0]) / det).store(dvz);
    det.store(det_lanes);
    uv[0].store(uv0);
    uv[1].store(uv1);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = first + group[k];
      DisplacedPoint& o = out[i];
      o.face = std::uint32_t(patch.face);
      base.face_location(patch, locations[i], o.u, o.v);
      const PatchPoint& p = points[group[k]];
      o.patch_u = locations[i].u, o.patch_v = locations[i].v;
      glm::vec3 n = len_lanes[k] > 0.0f ? glm::vec3(nx_unit[k], ny_unit[k], nz_unit[k]) : glm::vec3(0.0f);
      if (base.flip_normals) n = -n;
      glm::vec3 dpdu = p.du, dpdv = p.dv;
      if (det_lanes[k] != 0.0f && std::isfinite(det_lanes[k]))
        dpdu = glm::vec3(dux[k], duy[k], duz[k]), dpdv = glm::vec3(dvx[k], dvy[k], dvz[k]);
      const glm::vec2 texcoord(uv0[k], uv1[k]);
      o.normal = n;
      o.dpdu = dpdu, o.dpdv = dpdv, o.uv = texcoord;
      o.shade_dpdu = dpdu, o.shade_dpdv = dpdv, o.shade_uv = texcoord;
      // positive_zero: + 0 turns a -0 into +0.
      o.position = p.position + 0.0f;
    }
    return true;
  }

  glm::vec3 oriented(const glm::vec3& n) const { return base.flip_normals ? -n : n; }
  // The limit surface's derivatives of face f along its edge from corner c (parameter t) and across it
  // (into the face), at that edge point (exact scheme, quads: corner c at (0,0),(1,0),(1,1),(0,1)).
  void owner_derivatives(int f, int c, float t, glm::vec3& along, glm::vec3& across) const {
    const float r = 1.0f - t;
    const float u = c == 0 ? t : c == 1 ? 1.0f : c == 2 ? r : 0.0f;
    const float v = c == 0 ? 0.0f : c == 1 ? t : c == 2 ? 1.0f : r;
    const SurfacePoint l = base.limit->evaluate(f, 0, u, v);
    switch (c) {
      case 0: along = l.du, across = l.dv; break;
      case 1: along = l.dv, across = -l.du; break;
      case 2: along = -l.du, across = -l.dv; break;
      default: along = -l.dv, across = l.du; break;
    }
  }
};

// For rendering: clip-space position and 13 attributes: the base normal (0..2), and for shading (in the
// patch's own chart where the sampled UV is another's: DisplacedPoint) dP/dU (3..5), dP/dV (6..8), the
// texture coordinates (9, 10); the patch's domain location (11, 12: seam blending in DisplacedPS).
inline constexpr std::size_t kDisplacedAttributes = 13;

struct DisplacedAttributes {
  std::array<float, kDisplacedAttributes> operator()(const DisplacedPoint& s) const {
    return {s.normal.x,     s.normal.y,     s.normal.z,     s.shade_dpdu.x, s.shade_dpdu.y,
            s.shade_dpdu.z, s.shade_dpdv.x, s.shade_dpdv.y, s.shade_dpdv.z, s.shade_uv.x,
            s.shade_uv.y,   s.patch_u,      s.patch_v};
  }
};
template <class Inner>
using DisplacedProjectDS = ProjectingDS<Inner, DisplacedAttributes>;

// Clay with a headlight (clay(), subd_shaders.h) on the displaced surface's shading normal: from a
// tangent-space normal map (RGB = (n + 1) / 2, x along dP/dU, y along dP/dV, z along the normal,
// Gram-Schmidt orthonormalized; `flip_green` for maps whose y points along −V: OBJ cages, whose v points
// up the image), or derived from the height map (the normal of P + h N with h's texture gradient by
// central differences one level-0 texel apart, sampled with the pixel's UV derivatives), or the base
// normal when neither is given.
//
// Seam blending (with `texcoords`): the two charts of a UV seam hold the same surface, but their texels
// at the seam rarely decode to the same normal (the frog's differ by 5 degrees at the median and 17 at
// the 90th percentile: its bake's chart borders do not follow the cage's UV edges). Within
// `seam_band_texels` of a seam edge the normal moves toward the mean of the two charts' normals at the
// nearest seam point: fully at the seam, fading to nothing at the band's edge. Both sides move to the
// same mean, so the seam's step goes, and no pixel away from a seam changes. The other chart's tangent
// frame there is this one's carried across by the similarity that maps this chart's edge onto the
// other's (mirrored when the charts' orientations differ): exact for conformal charts, and the same
// rule on both sides.
//
// With UDIM tiles a pixel reads its patch's tile (the texture coordinates it interpolates are the
// patch's own, DisplacedPoint), the other chart of a seam the twin face's.
struct DisplacedPS {
  std::span<const DisplacementMap> normal_maps;  // per tile
  std::span<const DisplacementMap> heights;      // per tile, one channel; used when normal_maps is empty
  float height_scale = 1.0f;
  bool flip_green = false;
  glm::vec3 light{0.0f, 0.0f, 1.0f};
  glm::vec3 color = kClayColor;
  // Per patch of the draw: each patch's tile and, with `seam_blending`, its seams. Empty: every patch
  // in tile 0, no seam blending.
  std::span<const PatchTexcoords> texcoords{};
  bool seam_blending = true;
  float seam_band_texels = 8.0f;
  FaceSides sides;

  glm::vec4 operator()(const PixelInput<kDisplacedAttributes>& in) const {
    const glm::vec2 ddx = in.ddx_attributes ? glm::vec2(in.ddx(9), in.ddx(10)) : glm::vec2(0.0f);
    const glm::vec2 ddy = in.ddy_attributes ? glm::vec2(in.ddy(9), in.ddy(10)) : glm::vec2(0.0f);
    return shade(in.attributes, ddx, ddy, in.front_face, in.primitive_id, nullptr);
  }

  // The quad form (pipeline/stage_io.h): each written lane operator()'s bits. The quad's pixels share
  // their UV derivatives, so the normal map's LOD (sample_grad's log2) is found once a quad; only the
  // written lanes are sampled.
  void shade_quad(const QuadInput<kDisplacedAttributes>& q, QuadColor& out) const {
    const glm::vec2 ddx(q.ddx(9), q.ddx(10)), ddy(q.ddy(9), q.ddy(10));
    const Texture2D* normal_map = texture(normal_maps, tile_of(q.primitive_id));
    const float lod = normal_map ? normal_map->grad_lod(ddx, ddy) : 0.0f;
    for (std::size_t k = 0; k < 4; ++k) {
      if (!(q.mask >> k & 1u)) continue;
      std::array<float, kDisplacedAttributes> a;
      for (std::size_t i = 0; i < kDisplacedAttributes; ++i) a[i] = q.attributes[i][k];
      glm::vec4 texel(0.0f);
      if (normal_map) texel = normal_map->sample_level(sampler(), glm::vec2(a[9], a[10]), lod);
      const glm::vec4 c = shade(a, ddx, ddy, q.front_face, q.primitive_id, normal_map ? &texel : nullptr);
      for (std::size_t ch = 0; ch < 4; ++ch) out.c[ch][k] = c[int(ch)];
    }
  }

 private:
  static Sampler sampler() {
    Sampler s;  // trilinear
    s.address_u = s.address_v = AddressMode::clamp;
    return s;
  }
  std::uint16_t tile_of(std::uint32_t primitive_id) const {
    return primitive_id < texcoords.size() ? texcoords[primitive_id].tile : std::uint16_t(0);
  }
  static const Texture2D* texture(std::span<const DisplacementMap> maps, std::uint16_t tile) {
    return tile < maps.size() ? &maps[tile].texture() : nullptr;
  }

  // One pixel; `texel`, when given, is the normal map's sample at its UV (sample_grad with ddx, ddy).
  glm::vec4 shade(const std::array<float, kDisplacedAttributes>& a, glm::vec2 ddx, glm::vec2 ddy, bool front_face,
                  std::uint32_t primitive_id, const glm::vec4* texel) const {
    const glm::vec3 n0 = unit_or_zero(glm::vec3(a[0], a[1], a[2]));
    const glm::vec3 dpdu(a[3], a[4], a[5]), dpdv(a[6], a[7], a[8]);
    const glm::vec2 uv(a[9], a[10]);
    const std::uint16_t tile = tile_of(primitive_id);
    const Texture2D* map = normal_maps.empty() ? texture(heights, tile) : texture(normal_maps, tile);
    if (map == nullptr) return clay(sides.facing(n0, front_face), light, color);
    glm::vec3 n = texel ? mapped_normal(*texel, n0, dpdu, dpdv) : surface_normal(tile, n0, uv, dpdu, dpdv, ddx, ddy);
    if (seam_blending && primitive_id < texcoords.size())
      n = blend_seams(n, n0, a[11], a[12], dpdu, dpdv, ddx, ddy, texcoords[primitive_id], *map);
    return clay(sides.facing(n, front_face), light, color);
  }

  // The tangent-space normal map's texel `t` in the frame of n0, du, dv (Gram-Schmidt).
  glm::vec3 mapped_normal(const glm::vec4& t, const glm::vec3& n0, const glm::vec3& du, const glm::vec3& dv) const {
    const glm::vec3 m(2.0f * t.x - 1.0f, (2.0f * t.y - 1.0f) * (flip_green ? -1.0f : 1.0f), 2.0f * t.z - 1.0f);
    const glm::vec3 tangent = unit_or_zero(du - glm::dot(n0, du) * n0);
    const glm::vec3 bitangent = unit_or_zero(dv - glm::dot(n0, dv) * n0 - glm::dot(tangent, dv) * tangent);
    const glm::vec3 shaded = unit_or_zero(m.x * tangent + m.y * bitangent + m.z * n0);
    return shaded != glm::vec3(0.0f) ? shaded : n0;
  }

  // The shading normal at `uv` of tile `tile` in a chart whose dP/dU, dP/dV are `du`, `dv` (the base
  // normal where the map gives none).
  glm::vec3 surface_normal(std::uint16_t tile, const glm::vec3& n0, glm::vec2 uv, const glm::vec3& du,
                           const glm::vec3& dv, glm::vec2 ddx, glm::vec2 ddy) const {
    const Sampler sampler = DisplacedPS::sampler();
    if (const Texture2D* normal_map = texture(normal_maps, tile))
      return mapped_normal(normal_map->sample_grad(sampler, uv, ddx, ddy), n0, du, dv);
    const Texture2D* height = texture(heights, tile);
    if (height == nullptr) return n0;
    const float su = 1.0f / float(height->width()), sv = 1.0f / float(height->height());
    // The four central-difference taps share the pixel's derivatives, so one LOD: sampled at once.
    std::array<glm::vec4, 4> h;
    height->sample_grad4(
        sampler,
        {uv + glm::vec2(su, 0.0f), uv - glm::vec2(su, 0.0f), uv + glm::vec2(0.0f, sv), uv - glm::vec2(0.0f, sv)}, ddx,
        ddy, h);
    const float dhdu = height_scale * (h[0].x - h[1].x) / (2.0f * su);
    const float dhdv = height_scale * (h[2].x - h[3].x) / (2.0f * sv);
    glm::vec3 d = unit_or_zero(glm::cross(du + dhdu * n0, dv + dhdv * n0));
    if (glm::dot(d, n0) < 0.0f) d = -d;
    return d != glm::vec3(0.0f) ? d : n0;
  }

  glm::vec3 blend_seams(glm::vec3 n, const glm::vec3& n0, float u, float v, const glm::vec3& du, const glm::vec3& dv,
                        glm::vec2 ddx, glm::vec2 ddy, const PatchTexcoords& tc, const Texture2D& map) const {
    if (tc.seam_edges == 0) return n;
    const glm::vec2 size(float(map.width()), float(map.height()));
    const auto& c = tc.interior;
    for (int k = 0; k < 4; ++k) {
      if ((tc.seam_edges >> k & 1) == 0) continue;
      // The domain distance from edge k, and the parameter along it (corner k -> k + 1).
      const float dist = k == 0 ? v : k == 1 ? 1.0f - u : k == 2 ? 1.0f - v : u;
      const float t = k == 0 ? u : k == 1 ? v : k == 2 ? 1.0f - u : 1.0f - v;
      const glm::vec2 a0 = c[std::size_t(k)], a1 = c[std::size_t((k + 1) % 4)];
      // The patch's extent across the edge, in texels, at this t: it and so the band are continuous
      // from patch to patch along the seam (neighbours share the UV edge between them).
      const float span =
          texel_length((1.0f - t) * (c[std::size_t((k + 3) % 4)] - a0) + t * (c[std::size_t((k + 2) % 4)] - a1), size);
      const float band = std::min(seam_band_texels, 0.5f * span);  // texels
      if (!(dist * span < band)) continue;
      const glm::vec2 b0 = tc.twin[std::size_t(k)][0], b1 = tc.twin[std::size_t(k)][1];
      const glm::vec2 es = a1 - a0, eo = b1 - b0;  // the edge in this chart and in the other (per unit t)
      // The seam's target, the same on both sides: each chart's normal at the seam point decoded in a
      // frame both sides can build alike, the conformal one that maps the chart's edge onto the edge's
      // world tangent E (from this side's frame; the other side's E is the same vector, or its negative
      // with its edge's UVs negated too), then averaged.
      const glm::vec3 edge = es.x * du + es.y * dv;
      const float le = glm::length(edge), ls = glm::length(es), lo = glm::length(eo);
      if (!(le > 0.0f) || !(ls > 0.0f) || !(lo > 0.0f)) continue;
      const glm::vec3 ex = edge / le, ey = glm::cross(n0, ex);
      const float orient = glm::dot(glm::cross(du, dv), n0) < 0.0f ? -1.0f : 1.0f;
      const float orient_other = (tc.twin_mirrored >> k & 1) ? -orient : orient;
      const auto conformal = [&](glm::vec2 e, float len, float o, glm::vec3& fu, glm::vec3& fv) {
        const glm::vec2 d = e / len;
        fu = (le / len) * (d.x * ex - o * d.y * ey);
        fv = (le / len) * (d.y * ex + o * d.x * ey);
      };
      glm::vec3 us, vs, uo, vo;
      conformal(es, ls, orient, us, vs);
      conformal(eo, lo, orient_other, uo, vo);
      // The pixel's UV derivatives carried into the other chart by the same similarity.
      const glm::vec2 xs = es / ls, ys(-xs.y, xs.x), xo = eo / lo, yo(-xo.y, xo.x);
      const float mirror = orient_other * orient, r = lo / ls;
      const auto to_other = [&](glm::vec2 d) { return r * (glm::dot(d, xs) * xo + mirror * glm::dot(d, ys) * yo); };
      const glm::vec2 at_s = a0 + t * es, at_o = b0 + t * eo;
      const glm::vec3 mean =
          unit_or_zero(surface_normal(tc.tile, n0, at_s, us, vs, ddx, ddy) +
                       surface_normal(tc.twin_tile[std::size_t(k)], n0, at_o, uo, vo, to_other(ddx), to_other(ddy)));
      if (mean == glm::vec3(0.0f)) continue;
      // This side's own normal at the seam point, in its own frame: the pixel's normal tends to it.
      const glm::vec3 ns = surface_normal(tc.tile, n0, at_s, du, dv, ddx, ddy);
      const float s = dist * span / band, w = 1.0f - s * s * (3.0f - 2.0f * s);
      n += w * (mean - ns);
    }
    const glm::vec3 out = unit_or_zero(n);
    return out != glm::vec3(0.0f) ? out : n0;
  }
};

}  // namespace tessera
