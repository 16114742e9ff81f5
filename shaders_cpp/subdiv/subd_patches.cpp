#include "shaders_cpp/subdiv/subd_patches.h"

#include <algorithm>
#include <functional>
#include <memory>
#include <cmath>
#include <initializer_list>
#include <map>
#include <optional>
#include <numeric>
#include <span>
#include <string>

#include "shaders_cpp/cage/corner_ring.h"
#include "shaders_cpp/subdiv/face_centre_limit.h"
#include "shaders_cpp/subdiv/limit_fit.h"
#include "shaders_cpp/subdiv/polar_patch.h"
#include "shaders_cpp/subdiv/semi_sharp_limit.h"
#include "shaders_cpp/subdiv/patch_stencils.h"
#include "shaders_cpp/cage/topology_combinations.h"

namespace tessera {

const char* to_string(Scheme s) {
  switch (s) {
    case Scheme::flat: return "flat";
    case Scheme::bspline: return "bspline";
    case Scheme::acc: return "acc";
    case Scheme::gregory: return "gregory";
    case Scheme::exact: return "exact";
    case Scheme::pn: return "pn";
    case Scheme::adaptive: return "adaptive";
  }
  return "?";
}

const char* to_string(PatchKind k) {
  switch (k) {
    case PatchKind::bilinear: return "bilinear";
    case PatchKind::linear: return "linear";
    case PatchKind::acc: return "acc";
    case PatchKind::gregory: return "gregory";
    case PatchKind::gregory_triangle: return "gregory_triangle";
    case PatchKind::polar_triangle: return "polar_triangle";
    case PatchKind::pn_triangle: return "pn_triangle";
    case PatchKind::pn_quad: return "pn_quad";
    case PatchKind::exact: return "exact";
  }
  return "?";
}

std::optional<Scheme> parse_scheme(std::string_view name) {
  for (int k = 0; k < kSchemeCount; ++k)
    if (const Scheme s = Scheme(k); name == to_string(s)) return s;
  return std::nullopt;
}

namespace {

std::string where(const Cage& cage, int face) { return cage.name + ": face " + std::to_string(face); }

bool is_regular_face(const Topology& t, const std::array<CornerRing, 4>& rings) {
  for (const auto& r : rings)
    if (r.boundary || r.sharp_corner || r.valence() != 4 || !r.all_quads() || t.has_sharpness_at(r.center))
      return false;
  return true;
}

class Builder {
 public:
  Builder(const Cage& cage, SubdPatches& out) : cage_(cage), out_(out) {}

  // Adds a patch whose control points are `stencils` over the gathered ring. A ring larger than an IA
  // patch (only the stencil schemes' rings can be) makes a precomputed patch: its IA patch is the face's
  // `corners` (the ring's first entries) and its rows go to the pre-pass.
  void add(PatchGroup& group, int face, int sub, PatchKind kind, const std::vector<int>& ring,
           const std::vector<Stencil>& stencils, const std::array<EdgeFactorKey, 4>& edges, int rotation = 0,
           int corners = 0) {
    const bool precompute = ring.size() > std::size_t(kMaxPatchControlPoints);
    if (precompute && (corners == 0 || stencils.empty()))
      throw CageError(where(cage_, face) + ": internal error, a 1-ring of " + std::to_string(ring.size()) +
                      " vertices for a patch that cannot be precomputed");
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
    const std::vector<int> ia = precompute ? std::vector<int>(ring.begin(), ring.begin() + corners) : ring;
    p.ring_size = int(ia.size());
    if (precompute) {
      // The rows over the whole ring, its vertices in ascending order (the hull shader's order).
      PrecomputedPatch pre;
      pre.rows = table.rows;
      std::vector<int> by_vertex(ring.size());
      std::iota(by_vertex.begin(), by_vertex.end(), 0);
      std::sort(by_vertex.begin(), by_vertex.end(),
                [&](int a, int b) { return ring[std::size_t(a)] < ring[std::size_t(b)]; });
      for (const int i : by_vertex) pre.vertices.push_back(ring[std::size_t(i)]);
      pre.weights.resize(table.weights.size());
      for (std::size_t r = 0; r < std::size_t(table.rows); ++r)
        for (std::size_t k = 0; k < ring.size(); ++k)
          pre.weights[r * ring.size() + k] = table.weights[r * ring.size() + std::size_t(by_vertex[k])];
      p.precomputed = out_.precomputed_rows;
      out_.precomputed_rows += pre.rows;
      out_.precomputed.push_back(std::move(pre));
    }
    // Patches evaluated without control points (exact) need no table. A precomputed patch's table
    // (over its whole ring) still names its topology combination and row count.
    p.table = stencils.empty() ? -1 : intern(std::move(table));
    std::vector<int> order(ia.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return ia[std::size_t(a)] < ia[std::size_t(b)]; });
    for (std::size_t i = 0; i < order.size(); ++i) p.order[i] = std::uint8_t(order[i]);
    p.edge_keys = edges;
    p.rotation = std::uint8_t(rotation);
    group.patches.push_back(p);
    rings_.push_back(ia);
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
  SubdPatches& out_;
  std::map<std::string, int> interned_;
  std::vector<std::vector<int>> rings_;
  std::vector<PatchGroup*> groups_;
};

// Creases in the per-face schemes (acc, gregory, bspline's fallback). gregory, bspline and acc fit a
// triangle or quad with a tagged corner to the exact limit (limit_fit.h): its corner points are the
// limit's, its edge points and face points least-squares fits, an edge's points computed once and read
// by both of its faces (any kind: triangles, fans and acc quads beside a fitted face take them too).
// What follows is the masks' own crease construction: the fans', and where Bfr gives no surface.
// Each patch is built twice, from
// the whole corner rings (smooth) and from the rings cut open at every crease (corner_ring.h:
// Catmull-Clark's crease and corner rules are the boundary rules on each side, so an infinitely sharp
// crease is exact where a boundary is), and the control points near corner k are blended by the
// sharpness s of its vertex: w = 1 - 2^-s (1 for infinitely sharp). A semi-sharp crease of sharpness s
// stays sharp for s subdivision steps and then relaxes over what is left, a band of width 2^-s of the
// face; the blend gives the sharp patch that share. Rows shared with a neighbour (P and E points) come
// from the same vertex's rings and weight on both faces, so they stay bit-identical.
double crease_weight(float s) { return s >= kSharpnessInfinite ? 1.0 : s > 0.0f ? 1.0 - std::exp2(-double(s)) : 0.0; }

// Row r of a patch's stencils -> the corner whose sharpness blends it, or -1 for the mean of two
// (ACC's tangent rows between corners). Gregory quads and triangles: five rows per corner.
template <std::size_t N>
std::vector<Stencil> blend_by_corner(const std::vector<Stencil>& smooth, const std::vector<Stencil>& sharp,
                                     const std::array<double, N>& w, bool acc) {
  std::vector<Stencil> out(smooth.size());
  for (std::size_t r = 0; r < smooth.size(); ++r) {
    double weight = 0.0;
    if (!acc) {
      weight = w[r / 5];
    } else if (r < 16) {  // b(i, j): the corner of its quadrant
      const std::size_t i = r % 4, j = r / 4;
      weight = w[i < 2 ? (j < 2 ? 0 : 3) : (j < 2 ? 1 : 2)];
    } else if (r < 28) {  // du(i, j), i = 0..2 along u
      const std::size_t i = (r - 16) % 3, j = (r - 16) / 3;
      const double left = w[j < 2 ? 0 : 3], right = w[j < 2 ? 1 : 2];
      weight = i == 0 ? left : i == 2 ? right : 0.5 * (left + right);
    } else {  // dv(i, j), j = 0..2 along v
      const std::size_t i = (r - 28) % 4, j = (r - 28) / 4;
      const double low = w[i < 2 ? 0 : 1], high = w[i < 2 ? 3 : 2];
      weight = j == 0 ? low : j == 2 ? high : 0.5 * (low + high);
    }
    if (weight == 0.0) {
      out[r] = smooth[r];
    } else if (weight == 1.0) {
      out[r] = sharp[r];
    } else {
      out[r].add(smooth[r], 1.0 - weight).add(sharp[r], weight);
    }
  }
  return out;
}

// The Gregory stencils of face g (a triangle or a quad) from its corner 0, blended at its creases as
// its own patch is: the rows a neighbour reads its cross derivative from.
void exact_corner(std::vector<Stencil>& stencils, const std::vector<Stencil>& smooth, const Topology& t, int vertex,
                  const std::optional<Stencil>& exact, std::size_t p_row, std::initializer_list<std::size_t> e_rows);

std::vector<Stencil> face_gregory_stencils(const Cage& cage, const Topology& t, int g,
                                           const std::vector<std::optional<Stencil>>& semi_sharp) {
  const int m = t.face_size(g);
  bool creased = false;
  for (int k = 0; k < m; ++k) creased |= t.has_sharpness_at(cage.face_vertex(g, k));
  auto build = [&]<std::size_t N>(std::array<CornerRing, N>& c, auto&& stencils) {
    std::array<CornerRing, N> cut;
    std::array<double, N> w{};
    for (std::size_t k = 0; k < N; ++k) {
      c[k] = gather_corner_ring(cage, t, g, int(k));
      float sharpness = 0.0f;
      if (creased) cut[k] = gather_creased_corner_ring(cage, t, g, int(k), &sharpness);
      w[k] = crease_weight(sharpness);
    }
    std::vector<Stencil> s = stencils(c);
    if (!creased) return s;
    std::vector<Stencil> blended = blend_by_corner(s, stencils(cut), w, false);
    for (std::size_t k = 0; k < N; ++k) {
      const int v = cage.face_vertex(g, int(k));
      exact_corner(blended, s, t, v, semi_sharp[std::size_t(v)], 5 * k, {5 * k + 1, 5 * k + 2});
    }
    return blended;
  };
  if (m == 3) {
    std::array<CornerRing, 3> c;
    return build(c, [](const std::array<CornerRing, 3>& r) { return gregory_triangle_stencils(r); });
  }
  std::array<CornerRing, 4> c;
  return build(c, [](const std::array<CornerRing, 4>& r) { return gregory_quad_stencils(r); });
}

// The limit on an edge, and its derivatives there, read the faces at the edge's two vertices only: the
// vertices of those faces, sorted.
std::vector<int> edge_neighbourhood(const Cage& cage, const Topology& t, int a, int b) {
  std::vector<int> near;
  for (const int v : {a, b})
    for (const int h : t.ring(v)) {
      const int fh = t.face(h);
      for (int c = 0; c < t.face_size(fh); ++c) near.push_back(cage.face_vertex(fh, c));
    }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  return near;
}

// Drops a fitted stencil's terms outside `near` (what Bfr's approximation of an irregular surface puts
// there, below round-off), so that the rows fit both faces' rings; false when a dropped weight is not
// negligible.
bool restrict_to(const std::vector<int>& near, Stencil& s) {
  double dropped = 0.0;
  std::erase_if(s.terms, [&](const std::pair<int, double>& term) {
    if (std::binary_search(near.begin(), near.end(), term.first)) return false;
    dropped = std::max(dropped, std::abs(term.second));
    return true;
  });
  return dropped < 1e-9;
}

// The kCrossRows rows of patch edge k of face f (patch corner k is face corner k + rot) when the edge is
// a semi-sharp crease between f and a triangle or quad; empty otherwise. The neighbour g traverses the
// edge from its corner j (our corner k + 1) to j + 1 (our corner k); its inward cross derivative there,
// in its Gregory points (P, E+, E-, F+, F- at 5 j), is the cubic 3 (E-_j - P_j), d (F+_j - E+_j),
// d (F-_{j+1} - E-_{j+1}), 3 (E+_{j+1} - P_{j+1}), d the patch degree across the edge (3 quad, 4 triangle;
// gregory_stencils' G1 condition on the quad view). Returned from our corner k: reversed.
// `gregory_rows` gives a neighbour's rows (face_gregory_stencils), built once per neighbour. Where
// `limit_cross` has the limit's own derivative into g (a fitted quad), that is returned instead, marked
// `limit`: the limit is smooth across the line, so the domain shader takes that normal alone.
// A smooth edge with a tag at one end, between two fitted faces, takes the limit's derivative too: the
// limit bends there within a fraction of the face (a corner tag's cone), which no bicubic follows, and
// its own normal on the edge was the worst of the face (catmark_cube_corner4, gregory: 8 degrees along
// both edges from the corner; mean 3.5 -> 2.8 degrees, largest 30 -> 8). Positions are untouched.
struct CrossRows {
  std::vector<Stencil> rows;  // empty: not an averaged edge
  bool limit = false;         // the limit's own derivative into the neighbour (SubdPatch::limit_edges)
};
CrossRows neighbour_cross_rows(const Topology& t, int f, int n, int rot, int k,
                               const std::function<const std::vector<Stencil>&(int)>& gregory_rows,
                               const std::function<std::optional<std::array<Stencil, 4>>(int, int)>& limit_cross) {
  const int h = t.face_offset(f) + (k + rot) % n;
  const int twin = t.twin(h);
  const float s = t.edge_sharpness(t.edge(h));
  if (twin < 0 || s >= kSharpnessInfinite) return {};
  const bool smooth_at_tag = s == 0.0f && (t.has_sharpness_at(t.origin(h)) || t.has_sharpness_at(t.destination(h)));
  if (!(s >= kCutSharpness) && !smooth_at_tag) return {};
  const int g = t.face(twin), m = t.face_size(g);
  if ((m != 3 && m != 4) || t.is_hole(g)) return {};
  const int a = twin - t.face_offset(g), b = (a + 1) % m;
  if (const std::optional<std::array<Stencil, 4>> c = limit_cross(g, a))
    return {{(*c)[3], (*c)[2], (*c)[1], (*c)[0]}, true};
  if (smooth_at_tag) return {};
  const std::vector<Stencil>& rows = gregory_rows(g);
  const double d = m == 3 ? 4.0 : 3.0;
  auto row = [&](int corner, int r) -> const Stencil& { return rows[std::size_t(5 * corner + r)]; };
  auto diff = [](double scale, const Stencil& x, const Stencil& y) {
    Stencil out;
    return out.add(x, scale).add(y, -scale);
  };
  return {{diff(3.0, row(b, 1), row(b, 0)), diff(d, row(b, 4), row(b, 2)), diff(d, row(a, 3), row(a, 1)),
           diff(3.0, row(a, 2), row(a, 0))}};
}

// A semi-sharp vertex's corner: row `p_row` becomes the exact limit (semi_sharp_limit.h). Its edge points
// (rows `e_rows`, a fan's spoke among them): at a crease vertex the crease runs the length of its edges
// and the blended points stand; a corner tag alone pulls the surface only within about 2^-s of the
// vertex, so its edge points, a third along the edges, are the smooth ones (`smooth`, the unblended
// rows) moved by that share of P's move (catmark_cube_corner2: 6.6e-2 of the diagonal blended, 2.0e-2
// so). Every face at the vertex makes the same rows from the same stencils: shared points share bits.
void exact_corner(std::vector<Stencil>& stencils, const std::vector<Stencil>& smooth, const Topology& t, int vertex,
                  const std::optional<Stencil>& exact, std::size_t p_row, std::initializer_list<std::size_t> e_rows) {
  if (!exact) return;
  const Stencil shift = *exact - smooth[p_row];
  stencils[p_row] = *exact;
  for (const int h : t.ring(vertex))
    if (t.edge_sharpness(t.edge(h)) > 0.0f) return;
  const double fade = std::exp2(-double(t.corner_sharpness(vertex)));
  for (const std::size_t r : e_rows) stencils[r] = smooth[r] + fade * shift;
}

// The SV_TessFactor keys of fan triangle k of face f (vertex k, vertex k + 1, centre): Ueq0 is the spoke
// to vertex k, keyed by the two cage edges there; Veq0 the cage edge k -> k+1; Weq0 the spoke to
// vertex k + 1. Both triangles beside a spoke name its two edges in the same order.
std::array<EdgeFactorKey, 4> fan_edge_keys(const Cage& cage, int f, int k) {
  const int n = cage.face_sizes[std::size_t(f)];
  auto vertex = [&](int j) { return cage.face_vertex(f, ((j % n) + n) % n); };
  const std::int64_t before = cage_edge_key(vertex(k - 1), vertex(k)), outer = cage_edge_key(vertex(k), vertex(k + 1)),
                     after = cage_edge_key(vertex(k + 1), vertex(k + 2));
  return {EdgeFactorKey{before, outer}, EdgeFactorKey{outer, -1}, EdgeFactorKey{outer, after}, EdgeFactorKey{}};
}

// The IA patch: the patch's corners in order, then each corner's ring vertices not yet listed (edge
// neighbours and far vertices, counter-clockwise from the face).
std::vector<int> gather_ring(std::span<const CornerRing> rings) {
  std::vector<int> ring;
  auto push = [&](int v) {
    if (std::find(ring.begin(), ring.end(), v) == ring.end()) ring.push_back(v);
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

}  // namespace

bool fits_limit(const Cage& cage, const Topology& t, Scheme scheme, int face) {
  const int m = t.face_size(face);
  if ((scheme != Scheme::gregory && scheme != Scheme::bspline && scheme != Scheme::acc) || t.is_hole(face) ||
      (m != 3 && m != 4))
    return false;
  for (int k = 0; k < m; ++k)
    if (t.has_sharpness_at(cage.face_vertex(face, k))) return true;
  return false;
}

SubdPatches build_patches(const Cage& cage, const Topology& t, Scheme scheme) {
  SubdPatches out;
  out.scheme = scheme;
  out.quads.domain = ts::Domain::quad;
  out.tris.domain = ts::Domain::tri;
  Builder builder(cage, out);
  const bool stencil_scheme = scheme == Scheme::acc || scheme == Scheme::gregory || scheme == Scheme::bspline;
  // Stencil schemes start each patch at its face's canonical corner, so faces of one topology
  // combination share one stencil table (the talk's reordering of faces).
  const std::vector<int> rotation =
      stencil_scheme ? analyze_combinations(t).face_rotation : std::vector<int>(std::size_t(t.face_count()), 0);
  // The exact limit at semi-sharp vertices (semi_sharp_limit.h), once per vertex: every face around it
  // puts the same bits at its corner.
  std::map<int, std::vector<Stencil>> neighbour_rows;  // neighbour_cross_rows' faces, built once each
  std::vector<std::optional<Stencil>> semi_sharp(static_cast<std::size_t>(stencil_scheme ? t.vertex_count() : 0));
  // The triangles of polar configurations (polar_patch.h), gregory's and bspline's: per face, its pole.
  const std::vector<int> pole =
      scheme == Scheme::gregory || scheme == Scheme::bspline ? polar_poles(t) : std::vector<int>{};
  for (std::size_t v = 0; v < semi_sharp.size(); ++v)
    if (t.has_sharpness_at(int(v))) semi_sharp[v] = semi_sharp_limit_position(cage, t, int(v));
  // Fitted faces (limit_fit.h): triangles and quads with a tagged corner, and the edges they fit, kept
  // per cage edge so that both faces on an edge read the same rows. An edge is fitted when a tag or the
  // boundary is at one of its ends. With neither, its limit curve is the smooth one (a tag changes only
  // vertex points, and the curve reads the edge and face points around its ends), which the masks' edge
  // points follow with face points made for them: fitting it too cost the creased cubes' normals
  // (catmark_cube_corner3, gregory: mean 3.2 -> 2.8 degrees without it, the smooth faces back at the
  // smooth cube's 2.2). At the boundary the masks are further from the limit than the fit
  // (catmark_gregory_test3: 2.0e-2 of the diagonal with the masks' edge, 3.9e-3 fitted).
  std::unique_ptr<LimitStencils> limit;
  std::vector<char> fitted(std::size_t(t.face_count()), 0);
  std::map<std::int64_t, int> fitted_edge_owner;  // edge key -> the lowest fitted face on it
  for (int f = 0; f < t.face_count(); ++f) {
    if (!fits_limit(cage, t, scheme, f)) continue;
    fitted[std::size_t(f)] = 1;
    const int m = t.face_size(f);
    for (int k = 0; k < m; ++k) {
      const int a = cage.face_vertex(f, k), b = cage.face_vertex(f, (k + 1) % m);
      if (t.has_sharpness_at(a) || t.has_sharpness_at(b) || t.is_boundary_vertex(a) || t.is_boundary_vertex(b))
        fitted_edge_owner.try_emplace(cage_edge_key(a, b), f);
    }
  }
  if (!fitted_edge_owner.empty()) limit = std::make_unique<LimitStencils>(cage);
  // Faces whose face points are fitted: the fitted faces and every triangle or quad beside one, whose
  // fitted edge would otherwise meet face points the masks built for their own edge points (the smooth
  // faces of catmark_cube_corner2 were 5.8 degrees off on their edges, against the smooth cube's 3.0).
  std::vector<char> fit_points = fitted;
  for (int f = 0; f < t.face_count() && limit; ++f) {
    const int m = t.face_size(f);
    if (t.is_hole(f) || (m != 3 && m != 4)) continue;
    for (int k = 0; k < m; ++k)
      if (fitted_edge_owner.contains(cage_edge_key(cage.face_vertex(f, k), cage.face_vertex(f, (k + 1) % m))))
        fit_points[std::size_t(f)] = 1;
  }
  // A tagged vertex's corner point, where a fitted face has it: the exact limit there from Bfr (the
  // masks' corner is exact for uniform creasing, semi_sharp_limit.h, but not for Chaikin's rule), from the
  // lowest-index fitted face at the vertex, read by every face at it.
  std::map<int, std::optional<Stencil>> fitted_corners;
  auto fit_corner = [&](std::vector<Stencil>& rows, int v, std::size_t p_row) {
    if (!limit || !t.has_sharpness_at(v)) return;
    auto it = fitted_corners.find(v);
    if (it == fitted_corners.end()) {
      std::optional<Stencil> p;
      int g = -1;
      for (const int h : t.ring(v))
        if (fitted[std::size_t(t.face(h))] && (g < 0 || t.face(h) < g)) g = t.face(h);
      if (g >= 0) p = limit_at_corner(*limit, g, t.corner_of(g, v));
      if (p && !restrict_to(edge_neighbourhood(cage, t, v, v), *p)) p.reset();
      it = fitted_corners.emplace(v, std::move(p)).first;
    }
    if (it->second) rows[p_row] = *it->second;
  };
  struct FittedEdge {
    bool ok = false;
    int a = -1;  // near_a lies beside vertex a
    EdgePoints points;
  };
  std::map<std::int64_t, FittedEdge> fitted_edges;
  // Replaces the edge points of patch edge k (vertices va -> vb, P rows pa, pb; E rows ea beside va, eb
  // beside vb) by the fitted ones when the edge is fitted.
  auto fit_edge = [&](std::vector<Stencil>& rows, int va, int vb, std::size_t pa, std::size_t pb, std::size_t ea,
                      std::size_t eb) {
    const std::int64_t key = cage_edge_key(va, vb);
    const auto owner = fitted_edge_owner.find(key);
    if (owner == fitted_edge_owner.end()) return;
    auto it = fitted_edges.find(key);
    if (it == fitted_edges.end()) {
      FittedEdge e;
      const int g = owner->second, m = t.face_size(g);
      for (int j = 0; j < m; ++j) {
        const int x = cage.face_vertex(g, j), y = cage.face_vertex(g, (j + 1) % m);
        if (cage_edge_key(x, y) != key) continue;
        const Stencil& px = x == va ? rows[pa] : rows[pb];
        const Stencil& py = x == va ? rows[pb] : rows[pa];
        if (std::optional<EdgePoints> fit = fit_edge_points(*limit, g, j, px, py)) {
          const std::vector<int> near = edge_neighbourhood(cage, t, x, y);
          if (restrict_to(near, fit->near_a) && restrict_to(near, fit->near_b))
            e.ok = true, e.a = x, e.points = std::move(*fit);
        }
        break;
      }
      it = fitted_edges.emplace(key, std::move(e)).first;
    }
    if (!it->second.ok) return;
    const bool forward = it->second.a == va;
    rows[ea] = forward ? it->second.points.near_a : it->second.points.near_b;
    rows[eb] = forward ? it->second.points.near_b : it->second.points.near_a;
  };
  // A neighbour's Gregory points from its corner 0, as its own patch has them (neighbour_cross_rows).
  const std::function<const std::vector<Stencil>&(int)> rows_of = [&](int g) -> const std::vector<Stencil>& {
    auto it = neighbour_rows.find(g);
    if (it != neighbour_rows.end()) return it->second;
    std::vector<Stencil> rows = face_gregory_stencils(cage, t, g, semi_sharp);
    return neighbour_rows.emplace(g, std::move(rows)).first->second;
  };
  // The limit's derivative into face g across its edge e, where Bfr evaluates g (a fitted quad).
  const std::function<std::optional<std::array<Stencil, 4>>(int, int)> limit_cross =
      [&](int g, int e) -> std::optional<std::array<Stencil, 4>> {
    if (!limit || !fitted[std::size_t(g)]) return std::nullopt;
    std::optional<std::array<Stencil, 4>> c = fit_inward_derivative(*limit, g, e);
    if (!c) return std::nullopt;
    const std::vector<int> near =
        edge_neighbourhood(cage, t, cage.face_vertex(g, e), cage.face_vertex(g, (e + 1) % t.face_size(g)));
    for (Stencil& r : *c)
      if (!restrict_to(near, r)) return std::nullopt;
    return c;
  };
  for (int f = 0; f < t.face_count(); ++f) {
    if (t.is_hole(f)) {
      ++out.holes;
      continue;
    }
    const int n = t.face_size(f);
    const int polar = pole.empty() ? -1 : pole[std::size_t(f)];
    // A polar triangle starts at its pole, the corner its patch collapses to.
    const int rot = polar >= 0 ? t.corner_of(f, polar) : rotation[std::size_t(f)];
    // Patch corner k is face corner k + rot.
    auto corner = [&](int k) { return cage.face_vertex(f, (((k + rot) % n) + n) % n); };
    // The fitted corner and edge points of a triangle's or quad's rows (limit_fit.h), and which of its
    // patch edges are smooth (interior, untagged): those fit the limit's cross derivative too.
    auto fit_boundary = [&](std::vector<Stencil>& stencils) {
      if (!limit) return;
      const std::size_t m = std::size_t(n);
      for (std::size_t k = 0; k < m; ++k) fit_corner(stencils, corner(int(k)), 5 * k);
      for (std::size_t k = 0; k < m; ++k)
        fit_edge(stencils, corner(int(k)), corner(int(k) + 1), 5 * k, 5 * ((k + 1) % m), 5 * k + 1,
                 5 * ((k + 1) % m) + 2);
    };
    auto smooth_edges = [&]<std::size_t N>() {
      std::array<bool, N> smooth{};
      for (std::size_t k = 0; k < N; ++k) {
        const int h = t.face_offset(f) + int((k + std::size_t(rot)) % N);
        smooth[k] = t.twin(h) >= 0 && t.edge_sharpness(t.edge(h)) == 0.0f;
      }
      return smooth;
    };
    // The face's corners from patch corner `first` on: the IA patch of a patch made of the face alone.
    auto corners_from = [&](int first) {
      std::vector<int> ring;
      for (int k = 0; k < n; ++k) ring.push_back(corner(first + k));
      return ring;
    };
    // Edge keys in SV_TessFactor order: patch edge k (corner k -> k+1) is factor (k + 1) % n.
    std::array<EdgeFactorKey, 4> edges{};
    if (n <= 4)
      for (int k = 0; k < n; ++k) edges[std::size_t((k + 1) % n)] = {cage_edge_key(corner(k), corner(k + 1)), -1};

    if (scheme == Scheme::pn) {
      // The IA patch is the face; the hull shader builds the PN points from its corners (pn_patch.h).
      if (n > 4)
        throw CageError(where(cage, f) + " has " + std::to_string(n) +
                        " sides; --scheme pn handles triangles and quads only (use --scheme adaptive, exact or flat)");
      builder.add(n == 3 ? out.tris : out.quads, f, 0, n == 3 ? PatchKind::pn_triangle : PatchKind::pn_quad,
                  corners_from(0), {}, edges);
      continue;
    }
    if (!stencil_scheme) {
      // flat, exact and adaptive: the IA patch is the face itself.
      if (n > kMaxPatchControlPoints)
        throw CageError(where(cage, f) + " has " + std::to_string(n) + " sides; --scheme " + to_string(scheme) +
                        " draws faces of up to " + std::to_string(kMaxPatchControlPoints) +
                        " (the face is the patch's control points)");
      const PatchKind tri_kind = uses_limit_surface(scheme) ? PatchKind::exact : PatchKind::linear;
      if (n == 3 || n == 4) {
        std::vector<Stencil> corners;
        if (scheme == Scheme::flat)
          for (int k = 0; k < n; ++k) corners.push_back(Stencil::vertex(corner(k)));
        const PatchKind kind = n == 3 ? tri_kind : uses_limit_surface(scheme) ? PatchKind::exact : PatchKind::bilinear;
        builder.add(n == 3 ? out.tris : out.quads, f, 0, kind, corners_from(0), corners, edges);
        continue;
      }
      // Larger faces: the fan of n triangles k = (corner k, corner k+1, centre). The ring starts at corner
      // k, so every fan triangle of every n-gon shares one flat table; the centre is summed in vertex
      // order (SubdPatch::order), so the n triangles compute the same bits for it.
      Stencil centre;
      for (int k = 0; k < n; ++k) centre.add_vertex(corner(k), 1.0 / n);
      for (int k = 0; k < n; ++k) {
        const std::array<EdgeFactorKey, 4> fan_edges = fan_edge_keys(cage, f, k);
        std::vector<Stencil> points;
        if (scheme == Scheme::flat) points = {Stencil::vertex(corner(k)), Stencil::vertex(corner(k + 1)), centre};
        builder.add(out.tris, f, k, tri_kind, corners_from(k), points, fan_edges);
      }
      continue;
    }
    // acc: quads whose corner rings are all quads. gregory and bspline: every face; faces of other sizes
    // in a corner ring act through their virtual quad point (limit_masks.h).
    if (n != 4 && scheme == Scheme::acc)
      throw CageError(where(cage, f) + " has " + std::to_string(n) + " sides; --scheme acc handles quads only" +
                      " (use --scheme gregory, adaptive, exact or flat)");
    // The rings cut at creases, and each corner's blend weight (crease_weight), for a face with a
    // tagged corner (`creased`); a smooth face is built once, as before creases were drawn.
    bool creased = false;
    for (int k = 0; k < n; ++k) creased |= t.has_sharpness_at(cage.face_vertex(f, k));
    if (n > 4) {
      // The fan of the exact scheme: triangle k = (face corner k, corner k + 1, centre), unrotated (the
      // limit surface's fan_location names it by k), with the same edge keys (spokes take the mean of
      // the cage edges beside them). Its ring is the union of every corner's ring, which the centre reads.
      if (scheme == Scheme::bspline) ++out.fallback_faces;  // never a regular face
      std::vector<CornerRing> rings, cut(static_cast<std::size_t>(n));
      std::vector<double> w(static_cast<std::size_t>(n), 0.0);
      for (int k = 0; k < n; ++k) {
        rings.push_back(gather_corner_ring(cage, t, f, k));
        float sharpness = 0.0f;
        if (creased) cut[std::size_t(k)] = gather_creased_corner_ring(cage, t, f, k, &sharpness);
        w[std::size_t(k)] = crease_weight(sharpness);
      }
      const FaceCentre centre = face_centre_limit(cage, t, f);
      auto at = [&](int k) { return std::size_t(((k % n) + n) % n); };
      for (int k = 0; k < n; ++k) {
        const std::array<EdgeFactorKey, 4> fan_edges = fan_edge_keys(cage, f, k);
        std::vector<Stencil> stencils = gregory_fan_stencils(rings[at(k)], rings[at(k + 1)], centre, k);
        if (creased) {
          const std::vector<Stencil> smooth = stencils;
          stencils = blend_by_corner(stencils, gregory_fan_stencils(cut[at(k)], cut[at(k + 1)], centre, k),
                                     std::array<double, 3>{w[at(k)], w[at(k + 1)], 0.0}, false);
          // Corner a's rows: P 0, outer edge point 1, spoke 2; corner b's: P 5, spoke 6, outer edge point 7.
          const int va = cage.face_vertex(f, int(at(k))), vb = cage.face_vertex(f, int(at(k + 1)));
          exact_corner(stencils, smooth, t, va, semi_sharp[std::size_t(va)], 0, {1, 2});
          exact_corner(stencils, smooth, t, vb, semi_sharp[std::size_t(vb)], 5, {6, 7});
        }
        if (limit) {
          fit_corner(stencils, cage.face_vertex(f, int(at(k))), 0);
          fit_corner(stencils, cage.face_vertex(f, int(at(k + 1))), 5);
          fit_edge(stencils, cage.face_vertex(f, int(at(k))), cage.face_vertex(f, int(at(k + 1))), 0, 5, 1, 7);
        }
        // The ring from corner k on, so the fans of one face (and of faces alike) share a table.
        std::vector<CornerRing> from_k;
        for (int j = 0; j < n; ++j) from_k.push_back(rings[at(k + j)]);
        builder.add(out.tris, f, k, PatchKind::gregory_triangle, gather_ring(from_k), stencils, fan_edges, 0, n);
      }
      continue;
    }
    auto exact_corners = [&](std::vector<Stencil>& stencils, const std::vector<Stencil>& smooth, int corners) {
      for (int k = 0; k < corners; ++k) {
        const std::size_t r = std::size_t(5 * k);
        exact_corner(stencils, smooth, t, corner(k), semi_sharp[std::size_t(corner(k))], r, {r + 1, r + 2});
      }
    };
    // The neighbours' cross-derivative rows of the patch's semi-sharp crease edges, appended after its
    // own (kCrossRows per edge, zero rows for the others); the mask of the edges that have them.
    auto add_cross_rows = [&](std::vector<Stencil>& stencils, int corners) {
      std::uint8_t mask = 0, limit_mask = 0;
      std::vector<Stencil> extra;
      for (int k = 0; k < corners; ++k) {
        CrossRows c = neighbour_cross_rows(t, f, n, rot, k, rows_of, limit_cross);
        if (c.rows.empty()) {
          c.rows.assign(kCrossRows, Stencil{});
        } else {
          mask = std::uint8_t(mask | (1u << k));
          if (c.limit) limit_mask = std::uint8_t(limit_mask | (1u << k));
        }
        extra.insert(extra.end(), c.rows.begin(), c.rows.end());
      }
      if (mask != 0) stencils.insert(stencils.end(), extra.begin(), extra.end());
      return std::pair{mask, limit_mask};
    };
    // Adds a triangle's or quad's patch with its crease edges' cross rows (none on a smooth face).
    auto add_creased = [&](PatchGroup& group, PatchKind kind, const std::vector<int>& ring,
                           std::vector<Stencil>& stencils) {
      const auto [averaged, limit_edges] =
          creased ? add_cross_rows(stencils, n) : std::pair<std::uint8_t, std::uint8_t>{};
      // A fitted face's corners: the limit's derivatives there (SubdPatch::limit_corners), so that the
      // corner's normal is the limit's (catmark_cube_corner4's corners were 19 degrees off on average).
      std::uint8_t corners = 0;
      if (limit && fitted[std::size_t(f)]) {
        std::vector<Stencil> rows;
        for (int k = 0; k < n; ++k) {
          std::optional<std::array<Stencil, 2>> d = limit_corner_derivatives(*limit, f, (k + rot) % n);
          if (d) corners = std::uint8_t(corners | (1u << k));
          rows.push_back(d ? (*d)[0] : Stencil{}), rows.push_back(d ? (*d)[1] : Stencil{});
        }
        if (corners != 0) stencils.insert(stencils.end(), rows.begin(), rows.end());
      }
      builder.add(group, f, 0, kind, ring, stencils, edges, rot, n);
      group.patches.back().averaged_edges = averaged;
      group.patches.back().limit_edges = limit_edges;
      group.patches.back().limit_corners = corners;
    };
    auto cut_rings = [&]<std::size_t N>(std::array<CornerRing, N>& cut, std::array<double, N>& w) {
      if (!creased) return;
      for (std::size_t k = 0; k < N; ++k) {
        float sharpness = 0.0f;
        cut[k] = gather_creased_corner_ring(cage, t, f, int((k + std::size_t(rot)) % N), &sharpness);
        w[k] = crease_weight(sharpness);
      }
    };
    if (n == 3) {
      std::array<CornerRing, 3> corners, cut;
      std::array<double, 3> w{};
      for (int k = 0; k < 3; ++k) corners[std::size_t(k)] = gather_corner_ring(cage, t, f, (k + rot) % 3);
      cut_rings(cut, w);
      if (scheme == Scheme::bspline) ++out.fallback_faces;  // never a regular face
      std::vector<Stencil> stencils = gregory_triangle_stencils(corners);
      if (polar >= 0) {
        fit_boundary(stencils);  // a fitted quad across the ring edge gives that edge's points
        const int across = t.twin(t.face_offset(f) + (1 + rot) % 3);  // the ring edge, from the quad
        polar_triangle_rows(stencils, t.valence(polar), rows_of(t.face(across)), t.corner(across));
        add_creased(out.tris, PatchKind::polar_triangle, gather_ring(corners), stencils);
        continue;
      }
      if (creased) {
        const std::vector<Stencil> smooth = stencils;
        stencils = blend_by_corner(stencils, gregory_triangle_stencils(cut), w, false);
        exact_corners(stencils, smooth, 3);
      }
      fit_boundary(stencils);
      if (limit && fit_points[std::size_t(f)])
        fit_triangle_face_points(*limit, f, rot, stencils, smooth_edges.operator()<3>());
      add_creased(out.tris, PatchKind::gregory_triangle, gather_ring(corners), stencils);
      continue;
    }
    std::array<CornerRing, 4> corners;
    for (int k = 0; k < 4; ++k) {
      corners[std::size_t(k)] = gather_corner_ring(cage, t, f, (k + rot) % 4);
      if (scheme == Scheme::acc && !corners[std::size_t(k)].all_quads())
        throw CageError(where(cage, f) + ": vertex " + std::to_string(corners[std::size_t(k)].center) +
                        " touches a face that is not a quad; --scheme acc needs quads around every corner (use "
                        "--scheme gregory, exact or flat)");
    }
    std::array<CornerRing, 4> cut;
    std::array<double, 4> w{};
    cut_rings(cut, w);
    const std::vector<int> ring = gather_ring(corners);
    if (scheme == Scheme::acc && !fitted[std::size_t(f)]) {
      std::vector<Stencil> stencils = acc_quad_stencils(corners);
      if (creased) {
        stencils = blend_by_corner(stencils, acc_quad_stencils(cut), w, true);
        // A semi-sharp vertex's corner point b(0,0), b(3,0), b(3,3), b(0,3) is its exact limit; ACC's
        // edge points and tangent patches keep the blend (moving them would need the tangent patches
        // moved with them).
        constexpr std::size_t kCornerRow[4] = {0, 3, 15, 12};
        for (int k = 0; k < 4; ++k)
          if (const std::optional<Stencil>& p = semi_sharp[std::size_t(corner(k))]) stencils[kCornerRow[k]] = *p;
      }
      // An edge shared with a fitted face but not fitted itself (no tag and no boundary at either end)
      // takes that face's Gregory edge points, so the two meet on the same bits: their corners are
      // already the same rows (limit_position of the same rings, unblended at untagged vertices).
      auto gregory_edge = [&](std::vector<Stencil>& rows, int k, const std::size_t(&a)[4]) {
        const int h = t.face_offset(f) + (k + rot) % 4, twin = t.twin(h);
        if (twin < 0 || !fitted[std::size_t(t.face(twin))]) return;
        if (fitted_edge_owner.contains(cage_edge_key(corner(k), corner(k + 1)))) return;
        const int g = t.face(twin), m = t.face_size(g), j = twin - t.face_offset(g);
        const std::vector<Stencil>& gr = rows_of(g);
        rows[a[1]] = gr[std::size_t(5 * ((j + 1) % m) + 2)];
        rows[a[2]] = gr[std::size_t(5 * j + 1)];
      };
      if (limit) {
        // An edge shared with a fitted face takes its fitted (or Gregory) points, and the tangent patch's
        // three points along that edge become the new boundary's derivative (acc's own boundary rows are
        // that derivative: the corners' limit tangents are 3 (E - P)).
        constexpr std::size_t kAlong[4][4] = {{0, 1, 2, 3}, {3, 7, 11, 15}, {15, 14, 13, 12}, {12, 8, 4, 0}};
        // Tangent rows along each edge from its first corner, and their sign (d/du or d/dv runs backward
        // on edges 2 and 3).
        constexpr std::size_t kTangent[4][3] = {{16, 17, 18}, {31, 35, 39}, {27, 26, 25}, {36, 32, 28}};
        constexpr double kSign[4] = {1.0, 1.0, -1.0, -1.0};
        for (int k = 0; k < 4; ++k) {
          const auto& a = kAlong[k];
          const std::array<Stencil, 4> before = {stencils[a[0]], stencils[a[1]], stencils[a[2]], stencils[a[3]]};
          fit_edge(stencils, corner(k), corner(k + 1), a[0], a[3], a[1], a[2]);
          gregory_edge(stencils, k, a);
          if (stencils[a[1]].terms == before[1].terms && stencils[a[2]].terms == before[2].terms) continue;
          for (std::size_t i = 0; i < 3; ++i)
            stencils[kTangent[k][i]] = (3.0 * kSign[k]) * (stencils[a[i + 1]] - stencils[a[i]]);
        }
      }
      add_creased(out.quads, PatchKind::acc, ring, stencils);
    } else {
      if (scheme == Scheme::bspline && !is_regular_face(t, corners)) ++out.fallback_faces;
      std::vector<Stencil> stencils = gregory_quad_stencils(corners);
      if (creased) {
        const std::vector<Stencil> smooth = stencils;
        stencils = blend_by_corner(stencils, gregory_quad_stencils(cut), w, false);
        exact_corners(stencils, smooth, 4);
      }
      fit_boundary(stencils);
      if (limit && fit_points[std::size_t(f)]) fit_face_points(*limit, f, rot, stencils, smooth_edges.operator()<4>());
      add_creased(out.quads, PatchKind::gregory, ring, stencils);
    }
  }
  builder.finish();
  return out;
}

}  // namespace tessera
