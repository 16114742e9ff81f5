#include "subd_patches.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <string>

#include "corner_ring.h"
#include "patch_stencils.h"
#include "topology_combinations.h"

namespace tessera {

std::optional<Scheme> parse_scheme(std::string_view name) {
  if (name == "flat") return Scheme::flat;
  if (name == "bspline") return Scheme::bspline;
  if (name == "acc") return Scheme::acc;
  if (name == "gregory") return Scheme::gregory;
  if (name == "exact") return Scheme::exact;
  return std::nullopt;
}

const char* to_string(Scheme s) {
  switch (s) {
    case Scheme::flat: return "flat";
    case Scheme::bspline: return "bspline";
    case Scheme::acc: return "acc";
    case Scheme::gregory: return "gregory";
    case Scheme::exact: return "exact";
  }
  return "?";
}

namespace {

std::string where(const Cage& cage, int face) { return cage.name + ": face " + std::to_string(face); }

std::int64_t edge_key(int a, int b, bool half = false) { return half ? half_edge_key(a, b) : cage_edge_key(a, b); }

bool is_regular_face(const Topology& t, const std::array<CornerRing, 4>& rings) {
  for (const auto& r : rings)
    if (r.boundary || r.sharp_corner || r.valence() != 4 || !r.all_quads() || t.has_sharpness_at(r.center))
      return false;
  return true;
}

class Builder {
 public:
  Builder(const Cage& cage, const Topology& t, SubdPatches& out) : cage_(cage), t_(t), out_(out) {}

  // Adds a patch whose control points are `stencils` over the gathered ring.
  void add(PatchGroup& group, int face, int sub, PatchKind kind, const std::vector<int>& ring,
           const std::vector<Stencil>& stencils, const std::array<std::int64_t, 4>& edges, int rotation = 0) {
    if (ring.size() > std::size_t(kMaxPatchControlPoints))
      throw CageError(where(cage_, face) + ": its 1-ring has " + std::to_string(ring.size()) +
                      " vertices, more than the 32 control points of a patch (use --scheme exact)");
    std::map<int, int> position;
    for (std::size_t i = 0; i < ring.size(); ++i) position.emplace(ring[i], int(i));
    StencilTable table;
    table.rows = int(stencils.size());
    table.ring = int(ring.size());
    table.weights.assign(std::size_t(table.rows) * ring.size(), 0.0f);
    for (std::size_t r = 0; r < stencils.size(); ++r)
      for (const auto& [v, w] : stencils[r].terms) {
        const auto it = position.find(v);
        if (it == position.end())
          throw CageError(where(cage_, face) + ": internal error, a stencil reaches vertex " + std::to_string(v) +
                          " outside the face's 1-ring");
        table.weights[r * ring.size() + std::size_t(it->second)] = static_cast<float>(w);
      }
    SubdPatch p;
    p.face = face;
    p.sub = sub;
    p.kind = kind;
    p.ring_size = int(ring.size());
    p.table = intern(std::move(table));
    std::vector<int> order(ring.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return ring[std::size_t(a)] < ring[std::size_t(b)]; });
    for (std::size_t i = 0; i < order.size(); ++i) p.order[i] = std::uint8_t(order[i]);
    p.edge_keys = edges;
    p.rotation = std::uint8_t(rotation);
    group.patches.push_back(p);
    rings_.push_back(ring);
    groups_.push_back(&group);
  }

  // Fills each group's index buffer once every patch is known (the control point count is the
  // group's largest ring).
  void finish() {
    for (PatchGroup* g : {&out_.quads, &out_.tris}) {
      g->control_points = 1;
      for (const auto& p : g->patches) g->control_points = std::max(g->control_points, p.ring_size);
    }
    for (std::size_t i = 0; i < rings_.size(); ++i) {
      PatchGroup& g = *groups_[i];
      const auto& ring = rings_[i];
      for (int k = 0; k < g.control_points; ++k)
        g.indices.push_back(std::uint32_t(ring[std::size_t(k) < ring.size() ? std::size_t(k) : 0]));
    }
  }

 private:
  int intern(StencilTable&& table) {
    std::string key(reinterpret_cast<const char*>(table.weights.data()), table.weights.size() * sizeof(float));
    key += std::to_string(table.rows) + ":" + std::to_string(table.ring);
    const auto [it, added] = interned_.emplace(std::move(key), int(out_.tables.size()));
    if (added) out_.tables.push_back(std::move(table));
    return it->second;
  }

  const Cage& cage_;
  const Topology& t_;
  SubdPatches& out_;
  std::map<std::string, int> interned_;
  std::vector<std::vector<int>> rings_;
  std::vector<PatchGroup*> groups_;
};

// The IA patch: the patch's corners in order, then each corner's ring vertices not yet listed (edge
// neighbours and far vertices, counter-clockwise from the face).
std::vector<int> gather_ring(const std::vector<CornerRing>& rings) {
  const int n = int(rings.size());
  std::vector<int> ring;
  auto push = [&](int v) {
    if (std::find(ring.begin(), ring.end(), v) == ring.end()) ring.push_back(v);
  };
  for (const CornerRing& r : rings) push(r.center);
  for (int i = 0; i < n; ++i) {
    const CornerRing& r = rings[std::size_t(i)];
    for (int j = 0; j < r.valence(); ++j) {
      push(r.edges[std::size_t(j)]);
      if (j < r.face_count())
        for (int v : r.face_others[std::size_t(j)]) push(v);
    }
  }
  return ring;
}

}  // namespace

SubdPatches build_patches(const Cage& cage, const Topology& t, Scheme scheme) {
  SubdPatches out;
  out.scheme = scheme;
  out.quads.domain = ts::Domain::quad;
  out.tris.domain = ts::Domain::tri;
  Builder builder(cage, t, out);
  const TopologyCombinations combinations = analyze_combinations(t);
  for (int f = 0; f < t.face_count(); ++f) {
    if (t.is_hole(f)) {
      ++out.holes;
      continue;
    }
    const int n = t.face_size(f);
    auto corner = [&](int k) { return cage.face_vertex(f, ((k % n) + n) % n); };
    // Edge keys in SV_TessFactor order: face edge k (corner k -> k+1) is factor (k + 1) % n.
    std::array<std::int64_t, 4> edges{-1, -1, -1, -1};
    if (n <= 4)
      for (int k = 0; k < n; ++k) edges[std::size_t((k + 1) % n)] = edge_key(corner(k), corner(k + 1));

    if (scheme == Scheme::exact) {
      // The limit surface is evaluated in the domain shader; the IA patch is just the face.
      std::vector<int> ring;
      for (int k = 0; k < n; ++k) ring.push_back(corner(k));
      if (n == 3 || n == 4) {
        builder.add(n == 3 ? out.tris : out.quads, f, 0, PatchKind::exact, ring, {}, edges);
      } else {
        for (int k = 0; k < n; ++k) {
          // Sub-patch k: corner k, the middle of edge k -> k+1, the centre, the middle of edge k-1 -> k.
          const std::array<std::int64_t, 4> sub_edges{edge_key(corner(k), corner(k - 1), true),
                                                      edge_key(corner(k), corner(k + 1), true), -1, -1};
          builder.add(out.quads, f, k, PatchKind::exact, ring, {}, sub_edges);
        }
      }
      continue;
    }
    if (scheme == Scheme::flat) {
      std::vector<int> ring;
      for (int k = 0; k < n; ++k) ring.push_back(corner(k));
      if (n == 3) {
        builder.add(out.tris, f, 0, PatchKind::linear, ring,
                    {Stencil::vertex(corner(0)), Stencil::vertex(corner(1)), Stencil::vertex(corner(2))}, edges);
      } else if (n == 4) {
        builder.add(out.quads, f, 0, PatchKind::bilinear, ring,
                    {Stencil::vertex(corner(0)), Stencil::vertex(corner(1)), Stencil::vertex(corner(2)),
                     Stencil::vertex(corner(3))},
                    edges);
      } else {
        Stencil centre;
        for (int k = 0; k < n; ++k) centre.add_vertex(corner(k), 1.0 / n);
        for (int k = 0; k < n; ++k) {
          const Stencil next_mid = Stencil{}.add_vertex(corner(k), 0.5).add_vertex(corner(k + 1), 0.5);
          const Stencil prev_mid = Stencil{}.add_vertex(corner(k), 0.5).add_vertex(corner(k - 1), 0.5);
          const std::array<std::int64_t, 4> sub_edges{edge_key(corner(k), corner(k - 1), true),
                                                      edge_key(corner(k), corner(k + 1), true), -1, -1};
          builder.add(out.quads, f, k, PatchKind::bilinear, ring, {Stencil::vertex(corner(k)), next_mid, centre, prev_mid},
                      sub_edges);
        }
      }
      continue;
    }
    // acc, gregory, bspline: quads whose corner rings are all quads.
    if (n != 4)
      throw CageError(where(cage, f) + " has " + std::to_string(n) + " sides; --scheme " + to_string(scheme) +
                      " handles quads only (use --scheme exact or flat)");
    // The patch starts at the face's canonical corner, so faces of one topology combination share
    // one stencil table (the talk's reordering of faces).
    const int rot = combinations.face_rotation[std::size_t(f)];
    std::array<std::int64_t, 4> rotated{};
    for (int k = 0; k < 4; ++k) rotated[std::size_t((k + 1) % 4)] = edge_key(corner(k + rot), corner(k + rot + 1));
    std::vector<CornerRing> rings;
    for (int k = 0; k < 4; ++k) {
      rings.push_back(gather_corner_ring(cage, t, f, (k + rot) % 4));
      if (!rings.back().all_quads())
        throw CageError(where(cage, f) + ": vertex " + std::to_string(rings.back().center) +
                        " touches a face that is not a quad; --scheme " + to_string(scheme) +
                        " needs quads around every corner (use --scheme exact or flat)");
    }
    const std::array<CornerRing, 4> corners{rings[0], rings[1], rings[2], rings[3]};
    const std::vector<int> ring = gather_ring(rings);
    if (scheme == Scheme::acc) {
      builder.add(out.quads, f, 0, PatchKind::acc, ring, acc_quad_stencils(corners), rotated, rot);
    } else {
      if (scheme == Scheme::bspline && !is_regular_face(t, corners)) ++out.fallback_faces;
      builder.add(out.quads, f, 0, PatchKind::gregory, ring, gregory_quad_stencils(corners), rotated, rot);
    }
  }
  builder.finish();
  return out;
}

}  // namespace tessera
