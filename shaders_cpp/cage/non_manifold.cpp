// The split: half-edges grouped by undirected edge (a counting sort on the lower vertex, then each short
// bucket sorted by the other end), corners joined across manifold edges (union-find), one vertex per
// group of joined corners, then OpenSubdiv's sharpening as tags on the result.
#include "shaders_cpp/cage/non_manifold.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace tessera {
namespace {

// The first eight items and the last; a place on a hundred faces stays one readable line.
std::string join(const std::vector<int>& xs) {
  constexpr std::size_t kShown = 8;
  std::string s;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (xs.size() > kShown + 1 && i == kShown) {
      s += ", ...";
      i = xs.size() - 1;
    }
    s += (i ? ", " : "") + std::to_string(xs[i]);
  }
  return s;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(std::size_t(n)) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
    return x;
  }
  // The smaller root wins, so a group's root is its first corner in face order.
  void join(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
  }
};

// Half-edge h (= face corner h) of the cage: its face, and the corner after it in that face.
struct Corners {
  std::vector<int> face, next;
  explicit Corners(const Cage& cage) : face(cage.face_vertices.size()), next(cage.face_vertices.size()) {
    for (int f = 0; f < cage.face_count(); ++f) {
      const int o = cage.face_offsets[std::size_t(f)], n = cage.face_sizes[std::size_t(f)];
      for (int k = 0; k < n; ++k) face[std::size_t(o + k)] = f, next[std::size_t(o + k)] = o + (k + 1) % n;
    }
  }
};

enum class EdgeUse : std::uint8_t { boundary, manifold, non_manifold };

// Per half-edge: how its undirected edge is used, and for a manifold edge the other face's half-edge.
struct EdgeUses {
  std::vector<EdgeUse> use;
  std::vector<int> twin;
  std::vector<std::vector<int>> non_manifold;  // the half-edges of each non-manifold edge (degenerate: one)
};

EdgeUses classify_edges(const Cage& cage, const Corners& c) {
  const std::vector<int>& fv = cage.face_vertices;
  const std::size_t nh = fv.size();
  EdgeUses out{std::vector<EdgeUse>(nh, EdgeUse::boundary), std::vector<int>(nh, -1), {}};
  std::vector<int> start(std::size_t(cage.vertex_count()) + 1, 0), order(nh);
  auto lo = [&](std::size_t h) { return std::min(fv[h], fv[std::size_t(c.next[h])]); };
  auto hi = [&](int h) { return std::max(fv[std::size_t(h)], fv[std::size_t(c.next[std::size_t(h)])]); };
  for (std::size_t h = 0; h < nh; ++h) ++start[std::size_t(lo(h)) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (std::size_t h = 0; h < nh; ++h) order[std::size_t(fill[std::size_t(lo(h))]++)] = int(h);
  for (std::size_t v = 0; v + 1 < start.size(); ++v) {
    auto first = order.begin() + start[v], last = order.begin() + start[v + 1];
    std::sort(first, last, [&](int a, int b) { return hi(a) != hi(b) ? hi(a) < hi(b) : a < b; });
    for (auto run = first; run != last;) {
      auto end = run;
      while (end != last && hi(*end) == hi(*run)) ++end;
      const int a = *run;
      if (hi(a) == int(v)) {  // degenerate: every use is its own non-manifold edge, as in Vtr
        for (auto it = run; it != end; ++it) out.use[std::size_t(*it)] = EdgeUse::non_manifold, out.non_manifold.push_back({*it});
      } else if (end - run == 2) {
        const int b = *(run + 1);
        if (fv[std::size_t(a)] != fv[std::size_t(b)] && c.face[std::size_t(a)] != c.face[std::size_t(b)]) {
          out.use[std::size_t(a)] = out.use[std::size_t(b)] = EdgeUse::manifold;
          out.twin[std::size_t(a)] = b, out.twin[std::size_t(b)] = a;
        } else {
          out.use[std::size_t(a)] = out.use[std::size_t(b)] = EdgeUse::non_manifold;
          out.non_manifold.push_back({a, b});
        }
      } else if (end - run > 2) {
        out.non_manifold.emplace_back(run, end);
        for (auto it = run; it != end; ++it) out.use[std::size_t(*it)] = EdgeUse::non_manifold;
      }
      run = end;
    }
  }
  std::sort(out.non_manifold.begin(), out.non_manifold.end());  // by first half-edge: face order
  return out;
}

// OpenSubdiv's test for a non-manifold vertex that keeps the crease rule: the middle of a non-manifold
// crease (two non-manifold edges, no boundary edge, more face incidences than edges).
bool keeps_crease_rule(int nm_edges, int boundary_edges, int faces, int edges) {
  return nm_edges == 2 && boundary_edges == 0 && faces > edges;
}

// Per vertex, whether OpenSubdiv sharpens it to a corner were it non-manifold: counted on the original
// topology as Far::TopologyRefinerFactory counts it.
std::vector<char> sharpened_corners(const Cage& cage, const Corners& c, const EdgeUses& edges) {
  const int nv = cage.vertex_count(), nh = int(cage.face_vertices.size());
  const std::vector<int>& fv = cage.face_vertices;
  std::vector<char> first_use(std::size_t(nh), 0);
  for (const auto& hs : edges.non_manifold) first_use[std::size_t(hs[0])] = 1;
  std::vector<int> nm_edges(std::size_t(nv), 0), boundary_edges(std::size_t(nv), 0), edge_count(std::size_t(nv), 0),
      face_count(std::size_t(nv), 0);
  for (int h = 0; h < nh; ++h) {
    ++face_count[std::size_t(fv[std::size_t(h)])];
    const int a = fv[std::size_t(h)], b = fv[std::size_t(c.next[std::size_t(h)])];
    const EdgeUse u = edges.use[std::size_t(h)];
    // Count each undirected edge once: at its first half-edge (a manifold edge's lower one).
    if (u == EdgeUse::manifold && edges.twin[std::size_t(h)] < h) continue;
    if (u == EdgeUse::non_manifold && !first_use[std::size_t(h)]) continue;
    for (int x : {a, b}) {  // a degenerate edge is listed twice among its vertex's edges, as in Vtr
      ++edge_count[std::size_t(x)];
      nm_edges[std::size_t(x)] += u == EdgeUse::non_manifold;
      boundary_edges[std::size_t(x)] += u == EdgeUse::boundary;
    }
  }
  // An edge a face uses more than once is, from its second use in that face on, a new edge instance
  // to OpenSubdiv (Vtr), so it counts once more at both ends.
  for (const auto& hs : edges.non_manifold) {
    const int a = fv[std::size_t(hs[0])], b = fv[std::size_t(c.next[std::size_t(hs[0])])];
    if (a == b) continue;
    std::vector<int> fs;
    for (int h : hs) fs.push_back(c.face[std::size_t(h)]);
    std::sort(fs.begin(), fs.end());
    const int extra = int(fs.size()) - int(std::unique(fs.begin(), fs.end()) - fs.begin());
    for (int x : {a, b}) edge_count[std::size_t(x)] += extra, nm_edges[std::size_t(x)] += extra;
  }
  std::vector<char> corner(std::size_t(nv), 0);
  for (int v = 0; v < nv; ++v)
    corner[std::size_t(v)] = !keeps_crease_rule(nm_edges[std::size_t(v)], boundary_edges[std::size_t(v)],
                                                face_count[std::size_t(v)], edge_count[std::size_t(v)]);
  return corner;
}

}  // namespace

std::string describe(const NonManifoldPlace& p) {
  const std::string faces = std::to_string(p.faces.size()) + (p.faces.size() == 1 ? " face (" : " faces (") +
                            join(p.faces) + ")";
  const bool reused = std::adjacent_find(p.faces.begin(), p.faces.end()) != p.faces.end();
  switch (p.kind) {
    case NonManifoldPlace::Kind::edge:
      return "non-manifold edge between vertices " + std::to_string(p.v0) + " and " + std::to_string(p.v1) +
             " (0-based): " +
             (reused ? "used " + std::to_string(p.faces.size()) + " times, by faces (" + join(p.faces) + ")" : faces) +
             "; drawn infinitely sharp";
    case NonManifoldPlace::Kind::repeated_vertex:
      return "face " + join(p.faces) + " uses vertex " + std::to_string(p.v0) +
             " (0-based) more than once; its edges there are drawn infinitely sharp";
    case NonManifoldPlace::Kind::vertex:
      return "non-manifold vertex " + std::to_string(p.v0) + " (0-based): " + faces + " in " +
             std::to_string(p.fans) + (p.fans == 1 ? " fan" : " fans") +
             (p.corner ? "; drawn as an infinitely sharp corner" : "; keeps the crease rule (middle of a non-manifold crease)");
  }
  return {};
}

std::vector<NonManifoldPlace> split_non_manifold(Cage& cage) {
  const int nv = cage.vertex_count(), nh = int(cage.face_vertices.size());
  const std::vector<int>& fv = cage.face_vertices;
  for (int v : fv)
    if (v < 0 || v >= nv) return {};  // Topology names the bad index
  const Corners c(cage);
  const EdgeUses edges = classify_edges(cage, c);

  // Corners joined across manifold edges; a vertex whose corners form more than one group is split.
  UnionFind groups(nh);
  for (int h = 0; h < nh; ++h) {
    const int t = edges.twin[std::size_t(h)];
    if (t > h) groups.join(h, c.next[std::size_t(t)]), groups.join(c.next[std::size_t(h)], t);
  }
  std::vector<int> copy(std::size_t(nh), -1), first_root(std::size_t(nv), -1), fans(std::size_t(nv), 0);
  std::vector<char> nm_vertex(std::size_t(nv), 0);
  std::vector<NonManifoldPlace> places;
  for (int h = 0; h < nh; ++h) {
    const int v = fv[std::size_t(h)], r = groups.find(h);
    if (first_root[std::size_t(v)] < 0) first_root[std::size_t(v)] = r;
    if (r == h) ++fans[std::size_t(v)];
  }
  for (const auto& hs : edges.non_manifold) {
    NonManifoldPlace p;
    p.v0 = fv[std::size_t(hs[0])], p.v1 = fv[std::size_t(c.next[std::size_t(hs[0])])];
    nm_vertex[std::size_t(p.v0)] = nm_vertex[std::size_t(p.v1)] = 1;
    if (p.v0 == p.v1) continue;  // a degenerate edge: named with its face's repeated vertex below
    for (int h : hs) p.faces.push_back(c.face[std::size_t(h)]);
    places.push_back(std::move(p));
  }
  for (int v = 0; v < nv; ++v)
    if (fans[std::size_t(v)] > 1) nm_vertex[std::size_t(v)] = 1;
  // A vertex repeated in a face is non-manifold too (Vtr gives the face's edges there their own instances).
  for (int f = 0; f < cage.face_count(); ++f) {
    const int o = cage.face_offsets[std::size_t(f)], n = cage.face_sizes[std::size_t(f)];
    for (int i = 0; i < n; ++i) {
      const int v = fv[std::size_t(o + i)];
      bool first = true, repeated = false;
      for (int j = 0; j < n; ++j)
        if (j != i && fv[std::size_t(o + j)] == v) repeated = true, first = first && j > i;
      if (!repeated || !first) continue;
      nm_vertex[std::size_t(v)] = 1;
      NonManifoldPlace p;
      p.kind = NonManifoldPlace::Kind::repeated_vertex, p.v0 = v, p.faces = {f};
      places.push_back(std::move(p));
    }
  }
  if (std::find(nm_vertex.begin(), nm_vertex.end(), 1) == nm_vertex.end()) return {};

  // One vertex per group: the first keeps the index, the others are appended.
  if (cage.vertex_source.empty()) {
    cage.vertex_source.resize(std::size_t(nv));
    std::iota(cage.vertex_source.begin(), cage.vertex_source.end(), 0);
  }
  std::vector<int> group_vertex(std::size_t(nh), -1);
  for (int h = 0; h < nh; ++h) {
    const int v = fv[std::size_t(h)], r = groups.find(h);
    int& g = group_vertex[std::size_t(r)];
    if (g < 0) {
      g = r == first_root[std::size_t(v)] ? v : cage.vertex_count();
      if (g != v) {
        cage.positions.push_back(cage.positions[std::size_t(v)]);
        cage.vertex_source.push_back(cage.vertex_source[std::size_t(v)]);
      }
    }
    copy[std::size_t(h)] = g;
  }
  for (int f = 0; f < cage.face_count(); ++f) {
    const int o = cage.face_offsets[std::size_t(f)], n = cage.face_sizes[std::size_t(f)];
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (copy[std::size_t(o + i)] == copy[std::size_t(o + j)])
          throw CageError(cage.name + ": face " + std::to_string(f) + " uses vertex " +
                          std::to_string(fv[std::size_t(o + i)]) +
                          " (0-based) twice within one fan; no manifold cage draws it as OpenSubdiv does");
  }

  const std::vector<char> corner = sharpened_corners(cage, c, edges);
  std::vector<std::vector<int>> vertex_faces(static_cast<std::size_t>(nv));
  for (int h = 0; h < nh; ++h)
    if (nm_vertex[std::size_t(fv[std::size_t(h)])]) vertex_faces[std::size_t(fv[std::size_t(h)])].push_back(c.face[std::size_t(h)]);
  for (int v = 0; v < nv; ++v) {
    if (!nm_vertex[std::size_t(v)]) continue;
    NonManifoldPlace p;
    p.kind = NonManifoldPlace::Kind::vertex, p.v0 = v, p.fans = fans[std::size_t(v)];
    p.faces = vertex_faces[std::size_t(v)];
    p.faces.erase(std::unique(p.faces.begin(), p.faces.end()), p.faces.end());
    p.corner = corner[std::size_t(v)] != 0;
    places.push_back(std::move(p));
  }

  // The cage's own tags move to every copy; the split edges and vertices are sharpened.
  std::vector<std::vector<int>> copies(static_cast<std::size_t>(nv));
  for (int v = 0; v < cage.vertex_count(); ++v) copies[std::size_t(cage.vertex_source[std::size_t(v)])].push_back(v);
  std::vector<Corner> tagged_corners;
  for (const Corner& k : cage.tags.corners) {
    if (k.vertex < 0 || k.vertex >= nv) { tagged_corners.push_back(k); continue; }
    for (int v : copies[std::size_t(k.vertex)]) tagged_corners.push_back({v, k.sharpness});
  }
  for (const NonManifoldPlace& p : places)
    if (p.kind == NonManifoldPlace::Kind::vertex && p.corner)
      for (int v : copies[std::size_t(p.v0)]) tagged_corners.push_back({v, 10.0f});
  std::vector<Crease> creases;
  auto copy_pairs = [&](int a, int b, auto&& emit) {
    for (int h = 0; h < nh; ++h) {
      const int x = fv[std::size_t(h)], y = fv[std::size_t(c.next[std::size_t(h)])];
      if ((x == a && y == b) || (x == b && y == a)) emit(copy[std::size_t(h)], copy[std::size_t(c.next[std::size_t(h)])]);
    }
  };
  for (const Crease& k : cage.tags.creases)
    if (k.v0 >= 0 && k.v0 < nv && k.v1 >= 0 && k.v1 < nv && (nm_vertex[std::size_t(k.v0)] || nm_vertex[std::size_t(k.v1)]))
      copy_pairs(k.v0, k.v1, [&](int x, int y) { creases.push_back({x, y, k.sharpness}); });
    else
      creases.push_back(k);
  for (const auto& hs : edges.non_manifold)
    for (int h : hs) creases.push_back({copy[std::size_t(h)], copy[std::size_t(c.next[std::size_t(h)])], 10.0f});
  cage.tags.corners = std::move(tagged_corners);
  cage.tags.creases = std::move(creases);
  cage.face_vertices = copy;

  std::stable_sort(places.begin(), places.end(), [](const NonManifoldPlace& a, const NonManifoldPlace& b) {
    return a.faces.front() != b.faces.front() ? a.faces.front() < b.faces.front() : int(a.kind) < int(b.kind);
  });
  cage.non_manifold.clear();
  for (const NonManifoldPlace& p : places) cage.non_manifold.push_back(describe(p));
  cage.warnings.push_back(cage.name + ": " + std::to_string(places.size()) +
                          " non-manifold places drawn by OpenSubdiv's rules (first: " + cage.non_manifold.front() +
                          "); `tessera analyze` lists them");
  return places;
}

}  // namespace tessera
