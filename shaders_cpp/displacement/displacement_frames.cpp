#include "shaders_cpp/displacement/displacement_frames.h"

#include <array>
#include <bit>
#include <map>
#include <string>
#include <unordered_map>

#include "shaders_cpp/cage/corner_ring.h"
#include "shaders_cpp/subdiv/limit_masks.h"
#include "shaders_cpp/subdiv/patch_stencils.h"
#include "shaders_cpp/displacement/watertight_uv.h"

namespace tessera {
namespace {

static_assert(kMaxPatchControlPoints <= 32, "a frame stencil's ring positions are a 32-bit mask");

using Frame8 = std::array<Stencil, 8>;

// The cubic (Bernstein, four control vectors) equal to the quadratic q0, q1, q2.
std::array<Stencil, 4> elevate(const Stencil& q0, const Stencil& q1, const Stencil& q2) {
  return {q0, (1.0 / 3.0) * q0 + (2.0 / 3.0) * q1, (2.0 / 3.0) * q1 + (1.0 / 3.0) * q2, q2};
}

// Along and cross tangents of the edge from corner 0 to corner 1 (v = 0) of the face whose corner rings
// are `c` (corner 0 first), for the scheme's patch.
Frame8 edge_frame(Scheme scheme, const std::array<CornerRing, 4>& c) {
  Frame8 f;
  auto put = [&](const std::array<Stencil, 4>& along, const std::array<Stencil, 4>& cross) {
    for (int i = 0; i < 4; ++i)
      f[std::size_t(i)] = along[std::size_t(i)], f[std::size_t(4 + i)] = cross[std::size_t(i)];
  };
  if (scheme == Scheme::acc) {
    const auto s = acc_quad_stencils(c);
    // du[i + 3 j] at 16, dv[i + 4 j] at 28; v = 0 is j = 0.
    put(elevate(s[16], s[17], s[18]), {s[28], s[29], s[30], s[31]});
  } else if (scheme == Scheme::gregory || scheme == Scheme::bspline) {
    const auto g = gregory_quad_stencils(c);
    // Bezier row 0 and row 1 at v = 0 (patch_eval.h gregory_to_bezier): b0..b3 = P0, E+0, E-1, P1;
    // b4..b7 = E-0, F+0, F-1, E+1.
    const std::array<Stencil, 4> row0{g[0], g[1], g[7], g[5]}, row1{g[2], g[3], g[9], g[6]};
    put(elevate(3.0 * (row0[1] - row0[0]), 3.0 * (row0[2] - row0[1]), 3.0 * (row0[3] - row0[2])),
        {3.0 * (row1[0] - row0[0]), 3.0 * (row1[1] - row0[1]), 3.0 * (row1[2] - row0[2]), 3.0 * (row1[3] - row0[3])});
  } else {
    // Bilinear: along p1 − p0 everywhere, across (1 − t)(p3 − p0) + t (p2 − p1).
    const Stencil p0 = Stencil::vertex(c[0].center), p1 = Stencil::vertex(c[1].center),
                  p2 = Stencil::vertex(c[2].center), p3 = Stencil::vertex(c[3].center);
    const Stencil a = p1 - p0, x0 = p3 - p0, x1 = p2 - p1;
    put({a, a, a, a}, {x0, (2.0 / 3.0) * x0 + (1.0 / 3.0) * x1, (1.0 / 3.0) * x0 + (2.0 / 3.0) * x1, x1});
  }
  return f;
}

}  // namespace

PatchFrames build_patch_frames(const Cage& cage, const Topology& t, const PatchGroup& group, Scheme scheme) {
  std::unordered_map<int, Frame8> edges;                     // by cage edge
  std::unordered_map<int, std::array<Stencil, 2>> vertices;  // by cage vertex
  auto edge_stencils = [&](int h) -> const Frame8& {
    const int e = t.edge(h);
    auto it = edges.find(e);
    if (it != edges.end()) return it->second;
    const int ho = edge_owner(t, h), fo = t.face(ho), co = t.corner(ho);
    std::array<CornerRing, 4> c;
    for (int j = 0; j < 4; ++j) c[std::size_t(j)] = gather_corner_ring(cage, t, fo, (co + j) % 4);
    return edges.emplace(e, edge_frame(scheme, c)).first->second;
  };
  auto vertex_stencils = [&](int v) -> const std::array<Stencil, 2>& {
    auto it = vertices.find(v);
    if (it != vertices.end()) return it->second;
    const int hv = vertex_owner(t, v), fv = t.face(hv);
    const CornerRing r = gather_corner_ring(cage, t, fv, t.corner(hv));
    std::array<Stencil, 2> s;
    if (scheme == Scheme::flat) {
      s = {Stencil::vertex(t.destination(hv)) - Stencil::vertex(v),
           Stencil::vertex(t.origin(t.prev(hv))) - Stencil::vertex(v)};
    } else {
      s = {limit_tangent(r, r.slot), limit_tangent(r, r.slot + 1)};
    }
    return vertices.emplace(v, s).first->second;
  };

  PatchFrames out;
  out.units.reserve(group.size() * 8);
  std::unordered_map<std::string, std::uint32_t> interned;  // unit content -> its first stored stencil
  std::vector<std::uint32_t> masks;
  std::vector<float> weights;
  std::string key;
  // Stores the unit of `masks` / `weights` (ring-position form) once, returns its first stencil.
  auto intern = [&]() {
    key.assign(1, char(masks.size()));
    key.append(reinterpret_cast<const char*>(masks.data()), masks.size() * sizeof(std::uint32_t));
    key.append(reinterpret_cast<const char*>(weights.data()), weights.size() * sizeof(float));
    const auto [it, added] = interned.emplace(key, std::uint32_t(out.masks.size()));
    if (added) {
      std::size_t w = 0;
      for (const std::uint32_t m : masks) {
        out.masks.push_back(m);
        out.starts.push_back(std::uint32_t(out.weights.size()));
        const int n = std::popcount(m);
        out.weights.insert(out.weights.end(), weights.begin() + std::ptrdiff_t(w),
                           weights.begin() + std::ptrdiff_t(w) + n);
        w += std::size_t(n);
      }
    }
    return it->second;
  };
  out.precomputed_first.assign(group.size(), -1);
  int precomputed_rows = 0;
  for (std::size_t p = 0; p < group.size(); ++p) {
    const SubdPatch& patch = group.patches[p];
    if (patch.precomputed >= 0 && !uses_limit_surface(scheme)) {
      // The 40 stencils over the cage vertices they reach, in ascending order; empty units.
      std::vector<const Stencil*> rows;
      for (int k = 0; k < 4; ++k)
        for (const Stencil& s : edge_stencils(t.face_offset(patch.face) + (k + patch.rotation) % 4)) rows.push_back(&s);
      for (int k = 0; k < 4; ++k)
        for (const Stencil& s : vertex_stencils(t.origin(t.face_offset(patch.face) + (k + patch.rotation) % 4)))
          rows.push_back(&s);
      std::map<int, std::size_t> column;
      for (const Stencil* s : rows)
        for (const auto& [v, w] : s->terms) column.emplace(v, 0);
      PrecomputedPatch pre;
      pre.rows = int(rows.size());
      for (auto& [v, c] : column) c = pre.vertices.size(), pre.vertices.push_back(v);
      pre.weights.assign(rows.size() * pre.vertices.size(), 0.0f);
      for (std::size_t r = 0; r < rows.size(); ++r)
        for (const auto& [v, w] : rows[r]->terms) pre.weights[r * pre.vertices.size() + column[v]] = float(w);
      out.precomputed_first[p] = precomputed_rows;
      precomputed_rows += pre.rows;
      out.precomputed.push_back(std::move(pre));
      for (int k = 0; k < 8; ++k) {
        masks.assign(k < 4 ? 8 : 2, 0u), weights.clear();
        out.units.push_back(intern());
      }
      continue;
    }
    std::map<int, std::uint32_t> position;  // cage vertex -> its first ring position
    for (int i = 0; i < patch.ring_size; ++i)
      position.emplace(int(group.indices[p * std::size_t(group.control_points) + std::size_t(i)]), std::uint32_t(i));
    std::array<float, kMaxPatchControlPoints> dense{};
    auto add = [&](const Stencil& s) {
      std::uint32_t mask = 0;
      for (const auto& [v, w] : s.terms) {
        const auto it = position.find(v);
        if (it == position.end())
          throw CageError(cage.name + ": face " + std::to_string(patch.face) +
                          ": internal error, a frame stencil reaches vertex " + std::to_string(v) +
                          " outside the patch's ring");
        // A zero (or underflowed) weight adds nothing to the sum: it is left out.
        const float f = float(w);
        if (f == 0.0f) continue;
        dense[it->second] = f;
        mask |= std::uint32_t(1) << it->second;
      }
      masks.push_back(mask);
      for (std::uint32_t j = 0; j < std::uint32_t(kMaxPatchControlPoints); ++j)
        if (mask >> j & 1u) weights.push_back(dense[j]);
    };
    // One unit per corner k in the patch's rotation, from the stencils of its half-edge; `exact` and `adaptive` have no
    // frame stencils, and its units hold `empty` empty stencils.
    const Stencil none;
    auto add_units = [&](int empty, auto&& stencils_of) {
      for (int k = 0; k < 4; ++k) {
        const int h = t.face_offset(patch.face) + (k + patch.rotation) % 4;
        masks.clear(), weights.clear();
        if (uses_limit_surface(scheme))
          for (int i = 0; i < empty; ++i) add(none);
        else
          for (const Stencil& s : stencils_of(h)) add(s);
        out.units.push_back(intern());
      }
    };
    add_units(8, edge_stencils);  // the edge units
    add_units(
        2, [&](int h) -> const auto& { return vertex_stencils(t.origin(h)); });  // the corner units
  }
  out.unit_count = int(interned.size());
  return out;
}

}  // namespace tessera
