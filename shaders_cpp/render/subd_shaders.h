// The subdivision schemes as shader functors (pipeline/stage_io.h shapes):
// - SubdVS: animation at control-point rate (glTF skins and morph targets posing each cage vertex,
//   rig_pose.h; or an affine transform; identity by default), and the per-vertex normal (`pn` only)
//   read by SV_VertexID from a second vertex stream.
// - SubdHS: control-point phase = the patch's stencil table applied to its 1-ring, summed in vertex
//   index order (or, for a 1-ring over 32 points, the pre-pass's rows: control_point_prepass.h), or for
//   `pn` the PN points of the face's corners (pn_patch.h); patch-constant phase =
//   tessellation factors per cage edge (SubdFactors), zero for a patch the cull policy (PatchCull) proves
//   outside the view, and the patch's orientation bound.
// - SubdDS: evaluates the patch (patch_eval.h, or the exact limit surface) and returns a SurfaceSample;
//   its batch form evaluates Gregory and ACC patches eight locations at a time (patch_eval_lanes.h).
// - ProjectingDS (ProjectDS for SurfaceSample) wraps a DS into one that returns ClipVertex for rendering.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>

#include <glm/glm.hpp>

#include "pipeline/stage_io.h"
#include "shaders_cpp/animation/rig_pose.h"
#include "shaders_cpp/lod/back_patch_cull.h"
#include "shaders_cpp/lod/frustum_cull.h"
#include "shaders_cpp/lod/subd_factors.h"
#include "shaders_cpp/render/patch_eval_lanes.h"
#include "shaders_cpp/subdiv/limit_surface.h"
#include "shaders_cpp/subdiv/patch_eval.h"
#include "shaders_cpp/subdiv/patch_stencils.h"
#include "shaders_cpp/subdiv/pn_patch.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera {

// |du x dv|^2 at or below this fraction of |du|^2 |dv|^2 (an angle under about 1e-5 radians): the two
// derivatives are parallel to round-off, and the normal is taken a step into the patch instead.
inline constexpr float kParallelDerivatives = 1e-10f;

struct SubdVertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};  // pn only
};

struct SubdVS {
  glm::mat4 transform{1.0f};
  glm::mat3 normal_transform{1.0f};  // the inverse transpose of transform's upper 3x3
  bool identity = true;
  std::span<const glm::vec3> normals;  // per cage vertex (pn, of the posed cage); empty otherwise
  // An animated cage (glTF): the vertex buffer holds bind positions, posed here (rig_pose.h).
  const CageRig* rig = nullptr;
  const RigPose* pose = nullptr;
  SubdVertex operator()(const glm::vec3& p, std::uint32_t id) const {
    SubdVertex out{p, id < normals.size() ? normals[id] : glm::vec3(0.0f)};
    if (rig) out.position = pose_vertex(*rig, *pose, id, p);
    if (identity) return out;
    out.position = glm::vec3(transform * glm::vec4(p, 1.0f));
    out.normal = glm::normalize(normal_transform * out.normal);
    return out;
  }
};

// Hull-shader output control point: a position, and for acc the matching tangent-patch points (for pn,
// du holds the normal field's coefficient of the same index).
struct SubdControlPoint {
  glm::vec3 p{0.0f}, du{0.0f}, dv{0.0f};
};

struct SubdPatchConstants {
  TessFactors factors;
  OrientationBound orientation;  // back-patch culling (pipeline/patch_orientation.h); none by default
};

struct SubdHS {
  static constexpr int kOutputControlPoints = 20;
  std::span<const SubdPatch> patches;
  std::span<const StencilTable> tables;
  SubdFactors factors;
  bool triangles = false;              // the tri domain: three edge factors, one inside factor
  std::span<const Box3> ring_boxes{};  // per face, `exact` only: the box of its 1-ring (culling)
  ts::Partitioning partitioning = ts::Partitioning::integer;
  // The control-point pre-pass's output (control_point_prepass.h): the rows of the patches whose 1-ring
  // is larger than an IA patch, read in place of the sum over `in`.
  std::span<const glm::vec3> precomputed{};
  PatchCull cull{};  // the pass's cull policy (with its depth bias); none by default

  // A Gregory patch's own rows in its table, before the crease and corner rows the rest of it holds.
  static int own_rows(const SubdPatch& patch) {
    return patch.kind == PatchKind::gregory ? kGregoryQuadStencils : kGregoryTriangleStencils;
  }

  SubdControlPoint control_point(std::span<const SubdVertex> in, int i, std::uint32_t patch_id) const {
    const SubdPatch& patch = patches[patch_id];
    SubdControlPoint cp;
    if (patch.kind == PatchKind::pn_triangle) {
      const glm::vec3 p[3] = {in[0].position, in[1].position, in[2].position};
      const glm::vec3 n[3] = {in[0].normal, in[1].normal, in[2].normal};
      const PNTriangle t = pn_triangle(p, n);
      if (i < 10) cp.p = t.b[std::size_t(i)];
      if (i < 6) cp.du = t.n[std::size_t(i)];
      return cp;
    }
    if (patch.kind == PatchKind::pn_quad) {
      const glm::vec3 p[4] = {in[0].position, in[1].position, in[2].position, in[3].position};
      const glm::vec3 n[4] = {in[0].normal, in[1].normal, in[2].normal, in[3].normal};
      const PNQuad q = pn_quad(p, n);
      if (i < 16) cp.p = q.b[std::size_t(i)];
      if (i < 9) cp.du = q.n[std::size_t(i)];
      return cp;
    }
    if (patch.table < 0) return cp;
    const StencilTable& t = tables[std::size_t(patch.table)];
    auto row = [&](int r) {
      if (patch.precomputed >= 0) return precomputed[std::size_t(patch.precomputed + r)];
      glm::dvec3 sum(0.0);
      const float* w = t.weights.data() + std::size_t(r) * std::size_t(t.ring);
      for (int k = 0; k < patch.ring_size; ++k) {
        const int j = patch.order[std::size_t(k)];
        if (w[j] != 0.0f) sum += double(w[j]) * glm::dvec3(in[std::size_t(j)].position);
      }
      return glm::vec3(sum);
    };
    if (i < t.rows) cp.p = row(i);
    if (patch.kind == PatchKind::acc && i < 12) {
      cp.du = row(16 + i);
      cp.dv = row(28 + i);
    }
    // Averaged crease edges: the neighbours' cross-derivative coefficients, kCrossRows per edge, after
    // the patch's own rows (cross_coefficient reads them back).
    if (patch.averaged_edges != 0) {
      if (patch.kind == PatchKind::acc) {  // du and dv of control points 12..19, which ACC leaves free
        if (i >= 12 && kAccStencils + (i - 12) < t.rows) cp.du = row(kAccStencils + (i - 12));
        if (i >= 12 && kAccStencils + 8 + (i - 12) < t.rows) cp.dv = row(kAccStencils + 8 + (i - 12));
      } else {
        if (own_rows(patch) + i < t.rows) cp.du = row(own_rows(patch) + i);
      }
    }
    // A fitted face's corners: the limit's derivatives (two rows per corner, after the rest), in dv.
    if (patch.limit_corners != 0) {
      const int corners = triangles ? 3 : 4;
      const int first = own_rows(patch) + (patch.averaged_edges != 0 ? kCrossRows * corners : 0);
      if (i < 2 * corners && first + i < t.rows) cp.dv = row(first + i);
    }
    return cp;
  }

  SubdPatchConstants patch_constants(std::span<const SubdVertex>, std::span<const SubdControlPoint> cp,
                                     std::uint32_t patch_id) const {
    const SubdPatch& patch = patches[patch_id];
    SubdPatchConstants pc;
    if (outside_view(patch, cp)) return pc;  // zero factors: the tessellator culls the patch
    pc.factors = edge_and_inside_factors(patch);
    pc.orientation = orientation_bound(patch, cp, pc.factors);
    return pc;
  }

  // The back-patch claim for the quad patches whose positions are a Bezier net (the others: none).
  OrientationBound orientation_bound(const SubdPatch& patch, std::span<const SubdControlPoint> cp,
                                     const TessFactors& f) const {
    if (!cull.back.enabled() || triangles) return {};
    int segments = 64;
    for (const float e : f.edge) segments = std::min(segments, max_edge_segments(e));
    if (patch.kind == PatchKind::acc || patch.kind == PatchKind::pn_quad) {
      std::array<glm::vec3, 16> net;
      for (std::size_t i = 0; i < 16; ++i) net[i] = cp[i].p;
      return cull.back.bound(net, 3, segments);
    }
    if (patch.kind == PatchKind::gregory) {
      // Polynomial where each corner's face points coincide (bspline's regular faces): the Bezier
      // net with those points inside. The blend of two equal points rounds by a few ulps at most.
      std::array<glm::vec3, 20> g;
      for (std::size_t i = 0; i < 20; ++i) g[i] = cp[i].p;
      for (std::size_t k = 0; k < 4; ++k)
        if (g[5 * k + 3] != g[5 * k + 4]) return {};
      std::array<glm::vec3, 16> net = gregory_to_bezier(g, 0.5f, 0.5f);
      net[5] = g[3], net[6] = g[8], net[10] = g[13], net[9] = g[18];
      return cull.back.bound(net, 3, segments);
    }
    if (patch.kind == PatchKind::bilinear) {  // corners around the quad; the net is row by row
      const std::array<glm::vec3, 4> net = {cp[0].p, cp[1].p, cp[3].p, cp[2].p};
      return cull.back.bound(net, 1, segments);
    }
    return {};
  }

  // The factors of a patch that is not culled.
  TessFactors edge_and_inside_factors(const SubdPatch& patch) const {
    TessFactors f;
    for (int k = 0; k < 4; ++k) f.edge[std::size_t(k)] = factors.edge(patch.edge_keys[std::size_t(k)]);
    if (triangles) {
      f.inside[0] = (f.edge[0] + f.edge[1] + f.edge[2]) / 3.0f;
    } else {
      // Inside U spans edges Veq0/Veq1 (1, 3), inside V spans Ueq0/Ueq1 (0, 2).
      f.inside[0] = (f.edge[1] + f.edge[3]) * 0.5f;
      f.inside[1] = (f.edge[0] + f.edge[2]) * 0.5f;
    }
    if (partitioning == ts::Partitioning::fractional_odd) lift_inside_factors(f);
    return f;
  }

  // fractional_odd only. An inside factor in (1, 1 + 2^-10) puts a ring of points within 2^-11 of the
  // patch boundary, where the tessellator's 16.16 fixed point can round them onto the boundary's own
  // points, and the outer edges open; with the other inside factor exactly 1, the stitch folds
  // zero-area triangles back along an outer edge (an edge used four times). Edge factors at and just
  // above 1 make such means (view-dependent LOD clamps at 1), so while either inside factor is above
  // 1, both are raised to at least 1 + 2^-10 (invisible; all-ones patches stay two triangles).
  static void lift_inside_factors(TessFactors& f) {
    constexpr float kLow = 1.0f + 0x1p-10f;
    if (!(std::max(f.inside[0], f.inside[1]) > 1.0f)) return;
    for (float& x : f.inside)
      if (x >= 1.0f && x < kLow) x = kLow;
  }

  // The frustum test on the patch's hull.
  bool outside_view(const SubdPatch& patch, std::span<const SubdControlPoint> cp) const {
    if (!cull.frustum.enabled) return false;
    return cull.frustum.outside(hull_size(patch), [&](int i) { return hull_point(patch, cp, i); });
  }
  // The points whose convex hull holds the patch's surface: its control points, or for `exact`, whose
  // IA patch is the face alone, the corners of the box of the face's 1-ring (none without the box).
  int hull_size(const SubdPatch& patch) const {
    if (patch.kind != PatchKind::exact) return hull_points(patch.kind);
    return std::size_t(patch.face) < ring_boxes.size() ? 8 : 0;
  }
  glm::vec3 hull_point(const SubdPatch& patch, std::span<const SubdControlPoint> cp, int i) const {
    if (patch.kind == PatchKind::exact) return ring_boxes[std::size_t(patch.face)].corner(i);
    return cp[std::size_t(i)].p;
  }
  // How many of a patch kind's output control points carry positions whose hull holds the surface.
  static int hull_points(PatchKind k) {
    switch (k) {
      case PatchKind::bilinear: return 4;
      case PatchKind::linear: return 3;
      case PatchKind::acc: return 16;
      case PatchKind::gregory: return 20;
      case PatchKind::gregory_triangle: return 15;
      case PatchKind::polar_triangle: return 15;  // the bicubic's 13 points and two copies of the pole
      case PatchKind::pn_triangle: return 10;
      case PatchKind::pn_quad: return 16;
      case PatchKind::exact: return 0;
    }
    return 0;
  }
};

// What the domain shader produces for one domain point: the surface point, its unit normal, and where
// it came from: the base face and the domain location in the face's own frame (a quad's (u,v) from its
// corner 0; a triangle's barycentric (u,v); for a face of more than four sides, (u,v) in its fan
// triangle SubdPatch::sub). du, dv are the partial derivatives with respect to the patch's domain
// location (DomainLocation u, v: the patch's frame, which may be rotated from the face's, see
// SubdPatch::rotation), for tangent frames.
struct SurfaceSample {  // (SurfacePoint is the limit surface's own, with derivatives)
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};
  std::uint32_t face = 0;
  float u = 0, v = 0;
  glm::vec3 du{0.0f}, dv{0.0f};
};

// Positions leave the domain shader with -0 turned into +0 (x + 0 is x for every other x): a point
// that is exactly zero in some coordinate, such as a cage vertex on a coordinate plane evaluated at a
// patch corner, may otherwise carry the sign of a zero-weighted term, which differs between the edges
// and patches that meet there.
inline glm::vec3 positive_zero(const glm::vec3& p) { return p + glm::vec3(0.0f); }

struct SubdDS {
  // Coefficient j (kCrossRows per edge) of the neighbours' cross derivatives, where SubdHS put it.
  static glm::vec3 cross_coefficient(const SubdPatch& patch, std::span<const SubdControlPoint> cp, int j) {
    if (patch.kind != PatchKind::acc) return cp[std::size_t(j)].du;
    return j < 8 ? cp[std::size_t(12 + j)].du : cp[std::size_t(4 + j)].dv;
  }

  // The patch corner a domain location is, or -1: a quad's (0,0), (1,0), (1,1), (0,1); a triangle's
  // w = 1, u = 1, v = 1.
  int patch_corner(DomainLocation at) const {
    if (triangles) return at.u == 0.0f && at.v == 0.0f ? 0 : at.u == 1.0f ? 1 : at.v == 1.0f ? 2 : -1;
    if ((at.u != 0.0f && at.u != 1.0f) || (at.v != 0.0f && at.v != 1.0f)) return -1;
    return at.v == 0.0f ? (at.u == 0.0f ? 0 : 1) : (at.u == 1.0f ? 2 : 3);
  }

  // A point on a semi-sharp crease edge (SubdPatch::averaged_edges) takes the mean of this patch's unit
  // normal `n` and the unit normals of the patches across its averaged edges (a patch corner may lie on
  // two): each from the neighbour's inward cross derivative D (a cubic from corner k, kCrossRows
  // coefficients, cross_coefficient) and the edge's direction T k -> k+1, as D x T (the neighbour runs the
  // edge the other way, its interior on its left). Returns `n` unchanged elsewhere.
  glm::vec3 crease_line_normal(const SubdPatch& patch, std::span<const SubdControlPoint> cp, DomainLocation at,
                               const PatchPoint& p, glm::vec3 n) const {
    const int edges = triangles ? 3 : 4;
    glm::vec3 sum = unit_or_zero(n), limit_sum(0.0f);
    bool any = false, any_limit = false;
    for (int k = 0; k < edges; ++k) {
      if (!(patch.averaged_edges & (1u << k))) continue;
      float t = 0.0f;
      glm::vec3 along(0.0f);
      bool on = false;
      if (triangles) {  // patch corners 0, 1, 2 at w = 1, u = 1, v = 1
        if (k == 0) on = at.v == 0.0f, t = at.u, along = p.du;
        if (k == 1) on = at.w <= 0.0f, t = at.v, along = p.dv - p.du;
        if (k == 2) on = at.u == 0.0f, t = 1.0f - at.v, along = -p.dv;
      } else {  // corners (0,0), (1,0), (1,1), (0,1)
        if (k == 0) on = at.v == 0.0f, t = at.u, along = p.du;
        if (k == 1) on = at.u == 1.0f, t = at.v, along = p.dv;
        if (k == 2) on = at.v == 1.0f, t = 1.0f - at.u, along = -p.du;
        if (k == 3) on = at.u == 0.0f, t = 1.0f - at.v, along = -p.dv;
      }
      if (!on) continue;
      const int r = kCrossRows * k;
      const float s = 1.0f - t;
      const glm::vec3 d =
          (s * s * s) * cross_coefficient(patch, cp, r) + (3.0f * t * s * s) * cross_coefficient(patch, cp, r + 1) +
          (3.0f * t * t * s) * cross_coefficient(patch, cp, r + 2) + (t * t * t) * cross_coefficient(patch, cp, r + 3);
      const glm::vec3 across = unit_or_zero(glm::cross(d, along));
      if (patch.limit_edges & (1u << k)) {
        limit_sum += across;
        any_limit = true;
      } else {
        sum += across;
        any = true;
      }
    }
    return any_limit ? limit_sum : any ? sum : n;
  }

  // The limit's normal at fitted corner k, from the derivatives SubdHS stored there; zero where they are
  // parallel, as at a vertex of valence 2 (its two edges leave along one line), so that the patch's own
  // normal stands. Out of line: rare, and kept off the domain shader's common path.
  [[gnu::noinline]] static glm::vec3 fitted_corner_normal(std::span<const SubdControlPoint> cp, int k) {
    const glm::vec3 &a = cp[std::size_t(2 * k)].dv, &b = cp[std::size_t(2 * k + 1)].dv;
    const glm::vec3 n = glm::cross(a, b);
    return glm::dot(n, n) > kParallelDerivatives * (glm::dot(a, a) * glm::dot(b, b)) ? n : glm::vec3(0.0f);
  }

  std::span<const SubdPatch> patches;
  const LimitSurface* limit = nullptr;
  bool flip_normals = false;  // left-handed cages (the limit surface flips its own)
  bool triangles = false;     // the tri domain

  // The patch's PatchPoint at each location (u[i], v[i], w[i]) of a patch of kind acc, gregory or
  // gregory_triangle, eight locations at a time (patch_eval_lanes.h: the bits of evaluate() below).
  // False, with nothing written, for other patches.
  bool evaluate_lanes(const SubdPatch& patch, std::span<const SubdControlPoint> cp, std::span<const float> u,
                      std::span<const float> v, std::span<const float> w, std::span<PatchPoint> out) const {
    if (triangles) {
      if (patch.kind != PatchKind::gregory_triangle) return false;
      std::array<glm::vec3, 15> g;
      for (std::size_t i = 0; i < 15; ++i) g[i] = cp[i].p;
      PatchLanes::gregory_triangle(g, u, v, w, out);
      return true;
    }
    if (patch.kind == PatchKind::acc) {
      std::array<glm::vec3, 16> b;
      std::array<glm::vec3, 12> du, dv;
      for (std::size_t i = 0; i < 16; ++i) b[i] = cp[i].p;
      for (std::size_t i = 0; i < 12; ++i) du[i] = cp[i].du, dv[i] = cp[i].dv;
      PatchLanes::acc(b, du, dv, u, v, out);
      return true;
    }
    if (patch.kind == PatchKind::gregory) {
      std::array<glm::vec3, 20> g;
      for (std::size_t i = 0; i < 20; ++i) g[i] = cp[i].p;
      PatchLanes::gregory(g, u, v, out);
      return true;
    }
    return false;
  }

  // The batch form, for ProjectingDS: out[i] = (*this)(pc, cp, locations[i], patch_id), the patch
  // evaluated in lanes where evaluate_lanes can.
  void samples(const SubdPatchConstants& pc, std::span<const SubdControlPoint> cp,
               std::span<const DomainLocation> locations, std::uint32_t patch_id, std::span<SurfaceSample> out) const {
    for_evaluated(patches[patch_id], cp, locations, [&](std::size_t i, const PatchPoint* evaluated) {
      sample(pc, cp, locations[i], patch_id, evaluated, out[i]);
    });
  }

  // Calls visit(first, n, evaluated) for each block of up to kLanesBlock locations [first, first + n),
  // `evaluated` their PatchPoints from evaluate_lanes (n of them) or null.
  static constexpr std::size_t kLanesBlock = 64;
  template <class Visit>
  void for_evaluated_blocks(const SubdPatch& patch, std::span<const SubdControlPoint> cp,
                            std::span<const DomainLocation> locations, const Visit& visit) const {
    std::array<float, kLanesBlock> u, v, w;
    std::array<PatchPoint, kLanesBlock> points;
    for (std::size_t first = 0; first < locations.size(); first += kLanesBlock) {
      const std::size_t n = std::min(kLanesBlock, locations.size() - first);
      for (std::size_t k = 0; k < n; ++k)
        u[k] = locations[first + k].u, v[k] = locations[first + k].v, w[k] = locations[first + k].w;
      const bool lanes =
          evaluate_lanes(patch, cp, std::span<const float>(u.data(), n), std::span<const float>(v.data(), n),
                         std::span<const float>(w.data(), n), std::span<PatchPoint>(points.data(), n));
      visit(first, n, lanes ? points.data() : nullptr);
    }
  }
  // visit(i, evaluated) for each location i, `evaluated` its PatchPoint from evaluate_lanes or null.
  template <class Visit>
  void for_evaluated(const SubdPatch& patch, std::span<const SubdControlPoint> cp,
                     std::span<const DomainLocation> locations, const Visit& visit) const {
    for_evaluated_blocks(patch, cp, locations, [&](std::size_t first, std::size_t n, const PatchPoint* points) {
      for (std::size_t k = 0; k < n; ++k) visit(first + k, points ? &points[k] : nullptr);
    });
  }

  // The location in the face's own frame (corner 0 at (0,0), or at w = 1): the patch's rotation undone.
  // Patch corner k is face corner k + r; on the tri domain face corner c takes the barycentric of patch
  // corner c - r (corner 0: w, 1: u, 2: v).
  void face_location(const SubdPatch& patch, DomainLocation loc, float& u, float& v) const {
    if (triangles) {
      switch (patch.rotation) {
        case 1: u = loc.w, v = loc.u; break;
        case 2: u = loc.v, v = loc.w; break;
        default: u = loc.u, v = loc.v; break;
      }
    } else {
      switch (patch.rotation) {
        case 1: u = 1.0f - loc.v, v = loc.u; break;
        case 2: u = 1.0f - loc.u, v = 1.0f - loc.v; break;
        case 3: u = loc.v, v = 1.0f - loc.u; break;
        default: u = loc.u, v = loc.v; break;
      }
    }
  }

  // `evaluated`, when given, is evaluate(loc)'s PatchPoint, computed in lanes (evaluate_lanes).
  SurfaceSample operator()(const SubdPatchConstants& pc, std::span<const SubdControlPoint> cp, DomainLocation loc,
                           std::uint32_t patch_id, const PatchPoint* evaluated = nullptr) const {
    SurfaceSample s;
    sample(pc, cp, loc, patch_id, evaluated, s);
    return s;
  }
  // The same, written into `s` in place: the batch form's array element is written field by field, not
  // built on the stack and copied (GCC's narrow stores, then the copy's wide loads, stall on store
  // forwarding: a third more domain-shader time on the frog).
  void sample(const SubdPatchConstants&, std::span<const SubdControlPoint> cp, const DomainLocation& loc,
              std::uint32_t patch_id, const PatchPoint* evaluated, SurfaceSample& s) const {
    const SubdPatch& patch = patches[patch_id];
    s.face = std::uint32_t(patch.face);
    face_location(patch, loc, s.u, s.v);
    if (patch.kind == PatchKind::exact) {
      const SurfacePoint l = !triangles ? limit->evaluate(patch.face, patch.sub, loc.u, loc.v)
                             : limit->face_size(patch.face) == 3
                                 ? limit->evaluate_triangle(patch.face, loc.u, loc.v, loc.w)
                                 : limit->evaluate_fan(patch.face, patch.sub, loc.u, loc.v, loc.w);
      s.position = positive_zero(l.position);
      s.normal = l.normal;
      s.du = l.du, s.dv = l.dv;
      return;
    }
    std::optional<glm::vec3> field_normal;
    const auto evaluate = [&](const DomainLocation& at) {
      PatchPoint p;
      switch (patch.kind) {
        case PatchKind::bilinear: p = bilinear_patch(cp[0].p, cp[1].p, cp[2].p, cp[3].p, at.u, at.v); break;
        case PatchKind::linear: {
          p = linear_triangle(cp[0].p, cp[1].p, cp[2].p, at.u, at.v, at.w);
          break;
        }
        case PatchKind::acc: {
          std::array<glm::vec3, 16> b;
          std::array<glm::vec3, 12> du, dv;
          for (int i = 0; i < 16; ++i) b[std::size_t(i)] = cp[std::size_t(i)].p;
          for (int i = 0; i < 12; ++i)
            du[std::size_t(i)] = cp[std::size_t(i)].du, dv[std::size_t(i)] = cp[std::size_t(i)].dv;
          p = bezier_patch(b, at.u, at.v);
          acc_tangents(du, dv, at.u, at.v, p.du, p.dv);
          break;
        }
        case PatchKind::gregory: {
          std::array<glm::vec3, 20> g;
          for (int i = 0; i < 20; ++i) g[std::size_t(i)] = cp[std::size_t(i)].p;
          const auto b = gregory_to_bezier(g, at.u, at.v);
          p = bezier_patch(b, at.u, at.v);
          break;
        }
        case PatchKind::gregory_triangle: {
          std::array<glm::vec3, 15> g;
          for (int i = 0; i < 15; ++i) g[std::size_t(i)] = cp[std::size_t(i)].p;
          p = gregory_triangle(g, at.u, at.v, at.w);
          break;
        }
        case PatchKind::polar_triangle: {
          std::array<glm::vec3, 15> g;
          for (int i = 0; i < 15; ++i) g[std::size_t(i)] = cp[std::size_t(i)].p;
          p = polar_triangle(g, at.u, at.v, at.w);
          break;
        }
        case PatchKind::pn_triangle: {
          std::array<glm::vec3, 10> b;
          std::array<glm::vec3, 6> n;
          for (int i = 0; i < 10; ++i) b[std::size_t(i)] = cp[std::size_t(i)].p;
          for (int i = 0; i < 6; ++i) n[std::size_t(i)] = cp[std::size_t(i)].du;
          p = cubic_triangle(b, at.u, at.v, at.w);
          field_normal = quadratic_triangle_normal(n, at.u, at.v, at.w);
          break;
        }
        case PatchKind::pn_quad: {
          std::array<glm::vec3, 16> b;
          std::array<glm::vec3, 9> n;
          for (int i = 0; i < 16; ++i) b[std::size_t(i)] = cp[std::size_t(i)].p;
          for (int i = 0; i < 9; ++i) n[std::size_t(i)] = cp[std::size_t(i)].du;
          p = bezier_patch(b, at.u, at.v);
          field_normal = biquadratic_normal(n, at.u, at.v);
          break;
        }
        case PatchKind::exact: break;  // evaluated above
      }
      return p;
    };
    const PatchPoint p = evaluated ? *evaluated : evaluate(loc);
    s.position = positive_zero(p.position);
    s.du = p.du, s.dv = p.dv;
    // PN patches carry their own normal field; the others' normal is that of the surface.
    if (field_normal) {
      s.normal = *field_normal;
    } else {
      glm::vec3 n = glm::cross(p.du, p.dv);
      // Where the two derivatives are parallel (a patch corner at a vertex with one face, whose two
      // edges leave along the one boundary tangent), their cross product is round-off and its sign is
      // anyone's: the normal is taken a step into the patch, where the surface's tangent plane is
      // spanned (the limit of the normal there). Such a corner belongs to one patch only. The same holds
      // where a derivative vanishes: along a collapsed edge (a face that repeats a vertex) or at a pole.
      const float scale = glm::dot(p.du, p.du) * glm::dot(p.dv, p.dv);
      if (!(scale > 0.0f) || glm::dot(n, n) <= kParallelDerivatives * scale) {
        constexpr float step = 1.0f / 1024.0f;
        DomainLocation inner = loc;
        if (triangles) {
          inner.u = loc.u + (1.0f / 3.0f - loc.u) * step;
          inner.v = loc.v + (1.0f / 3.0f - loc.v) * step;
          inner.w = 1.0f - inner.u - inner.v;
        } else {
          inner.u = loc.u + (0.5f - loc.u) * step;
          inner.v = loc.v + (0.5f - loc.v) * step;
        }
        const PatchPoint q = evaluate(inner);
        n = glm::cross(q.du, q.dv);
      }
      // At a fitted face's corner, the limit's own normal (SubdPatch::limit_corners); then, on a semi-sharp
      // crease line, the mean with the neighbours' normals.
      const int k = patch.limit_corners != 0 ? patch_corner(loc) : -1;
      const glm::vec3 corner_n =
          k >= 0 && (patch.limit_corners & (1u << k)) ? fitted_corner_normal(cp, k) : glm::vec3(0.0f);
      if (glm::dot(corner_n, corner_n) > 0.0f)
        n = corner_n;
      else if (patch.averaged_edges != 0)
        n = crease_line_normal(patch, cp, loc, p, n);
      s.normal = unit_or_zero(n);
    }
    if (flip_normals) s.normal = -s.normal;
  }
};

// A world-space point in clip space, pulled toward the camera by `z_bias` of w (for wireframe drawn
// over shading).
inline glm::vec4 clip_position(const glm::mat4& view_projection, float z_bias, const glm::vec3& p) {
  glm::vec4 c = view_projection * glm::vec4(p, 1.0f);
  c.z -= z_bias * c.w;
  return c;
}

// Wraps a DS for rendering: its point's `position` in clip space, pulled toward the camera by `z_bias`
// of w (for wireframe drawn over shading), and the attributes AttributesOf{}(point) (std::array<float, N>)
// for the pixel shader.
template <class Inner, class AttributesOf>
struct ProjectingDS {
  Inner inner;
  glm::mat4 view_projection{1.0f};
  float z_bias = 0.0f;
  template <class PC, class CP>
  auto operator()(const PC& pc, std::span<const CP> cps, DomainLocation loc, std::uint32_t patch_id) const {
    return project(inner(pc, cps, loc, patch_id));
  }
  // The batch form (pipeline/stage_io.h's BatchDomainShader), where Inner has one: Inner::samples(pc,
  // cps, locations, patch_id, out), a block of points at a time, each projected as above.
  template <class PC, class CP, std::size_t N>
  requires requires(const Inner& d, const PC& pc, std::span<const CP> cps, std::span<const DomainLocation> l,
                    std::uint32_t id) {
    d.samples(pc, cps, l, id, std::span<decltype(d(pc, cps, DomainLocation{}, id))>());
  }
  void operator()(const PC& pc, std::span<const CP> cps, std::span<const DomainLocation> locations,
                  std::uint32_t patch_id, std::span<ClipVertex<N>> out) const {
    using Sample = decltype(inner(pc, cps, DomainLocation{}, patch_id));
    static_assert(std::is_same_v<decltype(project(Sample{})), ClipVertex<N>>);
    constexpr std::size_t kBlock = 64;
    std::array<Sample, kBlock> samples;
    for (std::size_t first = 0; first < locations.size(); first += kBlock) {
      const std::size_t n = std::min(kBlock, locations.size() - first);
      inner.samples(pc, cps, locations.subspan(first, n), patch_id, std::span<Sample>(samples.data(), n));
      for (std::size_t k = 0; k < n; ++k) project(samples[k], out[first + k]);
    }
  }
  template <class Sample>
  auto project(const Sample& s) const {
    ClipVertex<std::tuple_size_v<decltype(AttributesOf{}(s))>> out;
    project(s, out);
    return out;
  }
  // Written in place, field by field: a whole vertex built on the stack and copied into the batch's
  // array stalled on store forwarding (its narrow stores, then the copy's wide loads).
  template <class Sample, std::size_t N>
  void project(const Sample& s, ClipVertex<N>& out) const {
    out.position = clip_position(view_projection, z_bias, s.position);
    out.attributes = AttributesOf{}(s);
  }
};

// A SurfaceSample's normal, the 3 attributes of the plain renders.
struct NormalAttributes {
  std::array<float, 3> operator()(const SurfaceSample& s) const { return {s.normal.x, s.normal.y, s.normal.z}; }
};
template <class Inner>
using ProjectDS = ProjectingDS<Inner, NormalAttributes>;

// Clay shading with a headlight (the light comes from the camera direction): ambient plus diffuse on
// a unit normal (zero shades as ambient only).
inline glm::vec4 clay(const glm::vec3& unit_normal, const glm::vec3& light, const glm::vec3& color) {
  const float diffuse = std::max(0.0f, glm::dot(unit_normal, light));
  return {color * (0.18f + 0.82f * diffuse), 1.0f};
}
inline constexpr glm::vec3 kClayColor{0.78f, 0.74f, 0.68f};

// Two-sided drawing (D3D11's CullMode NONE): a pixel of the surface's inner side is shaded with its
// normal turned toward the viewer. `outward_front` is SV_IsFrontFace on the outer side: false on a
// left-handed cage, whose outer side the rasterizer sees as its back. One-sided drawing culls the inner
// side, so its pixels never reach a pixel shader and `two_sided` false changes nothing.
struct FaceSides {
  bool two_sided = false;
  bool outward_front = true;
  glm::vec3 facing(const glm::vec3& n, bool front_face) const {
    return two_sided && front_face != outward_front ? -n : n;
  }
};

struct ClayPS {
  glm::vec3 light{0.0f, 0.0f, 1.0f};  // toward the light, world space
  glm::vec3 color = kClayColor;
  FaceSides sides;
  glm::vec4 operator()(const PixelInput<3>& in) const {
    const glm::vec3 n = unit_or_zero(glm::vec3(in.attributes[0], in.attributes[1], in.attributes[2]));
    return clay(sides.facing(n, in.front_face), light, color);
  }
};

// One colour for every pixel (wireframe passes), for any attribute count.
inline constexpr glm::vec4 kWireColor{0.2f, 0.25f, 0.35f, 1.0f};
template <std::size_t N = 3>
struct ConstantPS {
  glm::vec4 color = kWireColor;
  glm::vec4 operator()(const PixelInput<N>&) const { return color; }
};

}  // namespace tessera
