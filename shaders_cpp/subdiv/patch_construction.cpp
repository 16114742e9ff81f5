#include "shaders_cpp/subdiv/patch_construction.h"

#include <algorithm>
#include <utility>

#include "shaders_cpp/subdiv/crease_blend.h"
#include "shaders_cpp/subdiv/limit_fit.h"

namespace tessera::subdiv {

std::vector<int> FaceFrame::corners_from(int first) const {
  std::vector<int> ring;
  for (int k = 0; k < n; ++k) ring.push_back(corner(first + k));
  return ring;
}

std::vector<int> gather_ring(std::span<const CornerRing> rings, std::vector<std::uint8_t>* landed) {
  std::vector<int> ring;
  auto push = [&](int v) {
    const auto it = std::find(ring.begin(), ring.end(), v);
    if (landed) landed->push_back(std::uint8_t(std::min<std::ptrdiff_t>(it - ring.begin(), 255)));
    if (it == ring.end()) ring.push_back(v);
  };
  for (const CornerRing& r : rings) push(r.center);
  for (const CornerRing& r : rings) {
    for (int j = 0; j < r.valence(); ++j) {
      push(r.edges[std::size_t(j)]);
      if (j < r.face_count())
        for (int v : r.face_others[std::size_t(j)]) push(v);
    }
  }
  return ring;
}

bool gather_ring_landing(const Cage& cage, const Topology& t, const FaceFrame& face, std::vector<int>& ring,
                         std::span<const std::uint8_t> landed, std::vector<std::uint8_t>* record) {
  ring.clear();
  std::size_t step = 0;
  // gather_ring's push, its landing place recorded or checked against the expected one.
  const auto push = [&](int v) {
    const auto it = std::find(ring.begin(), ring.end(), v);
    const auto place = std::uint8_t(std::min<std::ptrdiff_t>(it - ring.begin(), 255));
    if (record != nullptr)
      record->push_back(place);
    else if (step >= landed.size() || landed[step++] != place)
      return false;
    if (it == ring.end()) ring.push_back(v);
    return true;
  };
  const int n = face.n;
  const auto half_edge = [&](int k) { return t.face_offset(face.f) + (k + face.rot) % n; };
  for (int k = 0; k < n; ++k)
    if (!push(t.origin(half_edge(k)))) return false;
  for (int k = 0; k < n; ++k) {
    // gather_corner_ring's order: the ring's edges and faces from the face's own (interior), or from
    // the first (boundary), each face's vertices between its two ring edges after its first edge.
    const int h = half_edge(k), v = t.origin(h);
    const auto r = t.ring(v);
    const std::size_t m = r.size();
    const bool boundary = t.is_boundary_vertex(v);
    std::size_t slot = 0;
    if (!boundary)
      while (slot < m && r[slot] != h) ++slot;
    for (std::size_t i = 0; i < m; ++i) {
      const int g = r[(slot + i) % m];
      if (!push(t.destination(g))) return false;
      const int f = t.face(g), size = t.face_size(f), c = t.corner(g);
      for (int j = 2; j + 1 < size; ++j)
        if (!push(cage.face_vertex(f, (c + j) % size))) return false;
    }
    if (boundary && !push(t.origin(t.prev(r.back())))) return false;
  }
  return record != nullptr || step == landed.size();
}

std::array<EdgeFactorKey, 4> fan_edge_keys(const Cage& cage, int f, int k) {
  const int n = cage.face_sizes[std::size_t(f)];
  auto vertex = [&](int j) { return cage.face_vertex(f, ((j % n) + n) % n); };
  const std::int64_t before = cage_edge_key(vertex(k - 1), vertex(k)), outer = cage_edge_key(vertex(k), vertex(k + 1)),
                     after = cage_edge_key(vertex(k + 1), vertex(k + 2));
  return {EdgeFactorKey{before, outer}, EdgeFactorKey{outer, -1}, EdgeFactorKey{outer, after}, EdgeFactorKey{}};
}

bool is_regular_face(const Topology& t, const std::array<CornerRing, 4>& rings) {
  for (const auto& r : rings)
    if (r.boundary || r.sharp_corner || r.valence() != 4 || !r.all_quads() || t.has_sharpness_at(r.center))
      return false;
  return true;
}

template <std::size_t N>
FaceRings<N> face_rings(const PatchContext& ctx, const FaceFrame& face) {
  FaceRings<N> r;
  for (std::size_t k = 0; k < N; ++k) {
    r.whole[k] = gather_corner_ring(ctx.cage, ctx.t, face.f, int((k + std::size_t(face.rot)) % N));
    if (N == 4 && ctx.scheme == Scheme::acc && !r.whole[k].all_quads())
      throw CageError(where(ctx.cage, face.f) + ": vertex " + std::to_string(r.whole[k].center) +
                      " touches a face that is not a quad; --scheme acc needs quads around every corner (use "
                      "--scheme gregory, exact or flat)");
  }
  if (!face.creased) return r;
  for (std::size_t k = 0; k < N; ++k) {
    float sharpness = 0.0f;
    r.cut[k] = gather_creased_corner_ring(ctx.cage, ctx.t, face.f, int((k + std::size_t(face.rot)) % N), &sharpness);
    r.weight[k] = crease_weight(sharpness);
  }
  return r;
}
template FaceRings<3> face_rings<3>(const PatchContext&, const FaceFrame&);
template FaceRings<4> face_rings<4>(const PatchContext&, const FaceFrame&);

void fit_boundary(PatchContext& ctx, const FaceFrame& face, std::vector<Stencil>& stencils) {
  if (!ctx.fitted.any()) return;
  const std::size_t m = std::size_t(face.n);
  for (std::size_t k = 0; k < m; ++k) ctx.fitted.fit_corner(stencils, face.corner(int(k)), 5 * k);
  for (std::size_t k = 0; k < m; ++k)
    ctx.fitted.fit_edge(stencils, face.corner(int(k)), face.corner(int(k) + 1), 5 * k, 5 * ((k + 1) % m), 5 * k + 1,
                        5 * ((k + 1) % m) + 2);
}

template <std::size_t N>
std::array<bool, N> smooth_edges(const Topology& t, const FaceFrame& face) {
  std::array<bool, N> smooth{};
  for (std::size_t k = 0; k < N; ++k) {
    const int h = t.face_offset(face.f) + int((k + std::size_t(face.rot)) % N);
    smooth[k] = t.twin(h) >= 0 && t.edge_sharpness(t.edge(h)) == 0.0f;
  }
  return smooth;
}
template std::array<bool, 3> smooth_edges<3>(const Topology&, const FaceFrame&);
template std::array<bool, 4> smooth_edges<4>(const Topology&, const FaceFrame&);

void exact_corners(const PatchContext& ctx, const FaceFrame& face, std::vector<Stencil>& stencils,
                   const std::vector<Stencil>& smooth, int corners) {
  for (int k = 0; k < corners; ++k) {
    const std::size_t r = std::size_t(5 * k);
    const int v = face.corner(k);
    exact_corner(stencils, smooth, ctx.t, v, ctx.semi_sharp[std::size_t(v)], r, {r + 1, r + 2});
  }
}

namespace {

// The neighbours' cross-derivative rows of the patch's averaged edges, appended after its own
// (kCrossRows per edge, zero rows for the others); the masks of the edges that have them and of those
// whose rows are the limit's.
std::pair<std::uint8_t, std::uint8_t> add_cross_rows(PatchContext& ctx, const FaceFrame& face,
                                                     std::vector<Stencil>& stencils) {
  std::uint8_t mask = 0, limit_mask = 0;
  std::vector<Stencil> extra;
  for (int k = 0; k < face.n; ++k) {
    CrossRows c = neighbour_cross_rows(ctx.t, face.f, face.n, face.rot, k, ctx.neighbours, ctx.fitted);
    if (c.rows.empty()) {
      c.rows.assign(kCrossRows, Stencil{});
    } else {
      mask = std::uint8_t(mask | (1u << k));
      if (c.limit) limit_mask = std::uint8_t(limit_mask | (1u << k));
    }
    extra.insert(extra.end(), c.rows.begin(), c.rows.end());
  }
  if (mask != 0) stencils.insert(stencils.end(), extra.begin(), extra.end());
  return {mask, limit_mask};
}

}  // namespace

void add_creased(PatchContext& ctx, const FaceFrame& face, PatchGroup& group, PatchKind kind,
                 const std::vector<int>& ring, std::vector<Stencil>& stencils) {
  const auto [averaged, limit_edges] =
      face.creased ? add_cross_rows(ctx, face, stencils) : std::pair<std::uint8_t, std::uint8_t>{};
  // A fitted face's corners carry the limit's derivatives there, so that the corner's normal is the
  // limit's where it bends within a fraction of the face.
  std::uint8_t corners = 0;
  if (ctx.fitted.any() && ctx.fitted.fitted(face.f)) {
    std::vector<Stencil> rows;
    for (int k = 0; k < face.n; ++k) {
      const int v = face.corner(k);
      std::optional<std::array<Stencil, 2>> d = limit_corner_derivatives(
          ctx.fitted.limit(), face.f, (k + face.rot) % face.n, !ctx.t.is_boundary_vertex(v) && ctx.t.valence(v) == 2);
      if (d) corners = std::uint8_t(corners | (1u << k));
      rows.push_back(d ? (*d)[0] : Stencil{}), rows.push_back(d ? (*d)[1] : Stencil{});
    }
    if (corners != 0) stencils.insert(stencils.end(), rows.begin(), rows.end());
  }
  SubdPatch& p = ctx.assembler.add(group, face.f, 0, kind, ring, stencils, face.edges, face.rot, face.n);
  p.averaged_edges = averaged;
  p.limit_edges = limit_edges;
  p.limit_corners = corners;
}

}  // namespace tessera::subdiv
