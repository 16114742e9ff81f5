#include "shaders_cpp/optimize/cage_optimize.h"

#include <algorithm>
#include <deque>
#include <numeric>
#include <map>
#include <set>

#include <meshoptimizer.h>

#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/cage/topology_combinations.h"

namespace tessera {
namespace {

// Whether a quad's parameter runs along its edge k in the edge's own direction.
bool runs_forward(int k) { return k < 2; }

// Fan triangles of every face, and per triangle its face.
std::vector<unsigned> fan_triangles(const Cage& c, std::vector<int>* triangle_face = nullptr) {
  std::vector<unsigned> out;
  for (int f = 0; f < c.face_count(); ++f)
    for (int k = 1; k + 1 < c.face_sizes[std::size_t(f)]; ++k) {
      out.insert(out.end(),
                 {unsigned(c.face_vertex(f, 0)), unsigned(c.face_vertex(f, k)), unsigned(c.face_vertex(f, k + 1))});
      if (triangle_face) triangle_face->push_back(f);
    }
  return out;
}

// Consistent quad-quad edges when face f starts at its corner shift[f].
int consistent_edges(const Topology& t, const std::vector<int>& shift) {
  int n = 0;
  for (int e = 0; e < t.edge_count(); ++e) {
    const auto [a, b] = t.edge_half_edges(e);
    if (b < 0 || t.face_size(t.face(a)) != 4 || t.face_size(t.face(b)) != 4) continue;
    const int ka = (t.corner(a) - shift[std::size_t(t.face(a))] + 4) % 4;
    const int kb = (t.corner(b) - shift[std::size_t(t.face(b))] + 4) % 4;
    n += runs_forward(ka) != runs_forward(kb);
  }
  return n;
}

// Start corners: face f of combination c starts at its canonical corner + offset[c] + m period, m chosen
// greedily in breadth-first order for the most edges consistent with the faces already placed.
std::vector<int> start_corners(const Topology& t, const TopologyCombinations& tc, const std::vector<int>& offset) {
  const int nf = t.face_count();
  std::vector<int> shift(static_cast<std::size_t>(nf), 0);
  for (int f = 0; f < nf; ++f) {
    const int c = tc.face_combination[std::size_t(f)];
    if (c >= 0) shift[std::size_t(f)] = (tc.face_rotation[std::size_t(f)] + offset[std::size_t(c)]) % t.face_size(f);
  }
  std::vector<std::uint8_t> placed(std::size_t(nf), 0), queued(std::size_t(nf), 0);
  std::deque<int> queue;
  for (int seed = 0; seed < nf; ++seed) {
    if (queued[std::size_t(seed)]) continue;
    queue.push_back(seed), queued[std::size_t(seed)] = 1;
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      const int n = t.face_size(f), h0 = t.face_half_edge(f), period = tc.face_period[std::size_t(f)];
      if (n == 4 && period < n && tc.face_combination[std::size_t(f)] >= 0) {
        const int first = shift[std::size_t(f)];
        int best = first, best_score = -1;
        for (int m = 0, s = first; m < n / period; ++m, s = (s + period) % n) {
          int score = 0;
          for (int k = 0; k < n; ++k) {
            const int tw = t.twin(h0 + k);
            if (tw < 0 || !placed[std::size_t(t.face(tw))] || t.face_size(t.face(tw)) != 4) continue;
            const int mine = (k - s + n) % n, theirs = (t.corner(tw) - shift[std::size_t(t.face(tw))] + 4) % 4;
            score += runs_forward(mine) != runs_forward(theirs);
          }
          if (score > best_score) best_score = score, best = s;
        }
        shift[std::size_t(f)] = best;
      }
      placed[std::size_t(f)] = 1;
      for (int k = 0; k < n; ++k) {
        const int tw = t.twin(h0 + k);
        if (tw >= 0 && !queued[std::size_t(t.face(tw))])
          queue.push_back(t.face(tw)), queued[std::size_t(t.face(tw))] = 1;
      }
    }
  }
  return shift;
}

struct Measures {
  int combinations = 0, stored = 0, quad_edges = 0, consistent = 0;
  float acmr = 0, atvr = 0;
};

Measures measure(const Cage& c, const Topology& t, const TopologyCombinations& tc, unsigned cache_size) {
  Measures m;
  m.combinations = int(tc.combinations.size());
  std::set<std::pair<int, int>> stored;
  for (int f = 0; f < t.face_count(); ++f)
    if (tc.face_combination[std::size_t(f)] >= 0)
      stored.insert({tc.face_combination[std::size_t(f)], tc.face_rotation[std::size_t(f)]});
  m.stored = int(stored.size());
  for (int e = 0; e < t.edge_count(); ++e) {
    const auto [a, b] = t.edge_half_edges(e);
    if (b < 0 || t.face_size(t.face(a)) != 4 || t.face_size(t.face(b)) != 4) continue;
    ++m.quad_edges;
    m.consistent += runs_forward(t.corner(a)) != runs_forward(t.corner(b));
  }
  const std::vector<unsigned> tris = fan_triangles(c);
  const auto s = meshopt_analyzeVertexCache(tris.data(), tris.size(), c.positions.size(), cache_size, 0, 0);
  m.acmr = s.acmr, m.atvr = s.atvr;
  return m;
}

}  // namespace

OptimizedCage optimize_cage(const Cage& cage, const CageOptimizeOptions& o) {
  const Topology t(cage);
  const TopologyCombinations tc = analyze_combinations(t);
  const int nf = cage.face_count();
  OptimizedCage out;
  const Measures before = measure(cage, t, tc, o.cache_size);

  // 1. Start corners (see the header).
  std::vector<int> shift(static_cast<std::size_t>(nf), 0);
  if (o.rotate) {
    // One offset per combination from its canonical corner keeps one stored key per combination; each
    // is chosen in turn (coordinate descent, up to three passes) for the most consistent edges.
    std::vector<int> offset(tc.combinations.size(), 0), period(tc.combinations.size(), 1);
    for (int f = 0; f < nf; ++f)
      if (tc.face_combination[std::size_t(f)] >= 0)
        period[std::size_t(tc.face_combination[std::size_t(f)])] = tc.face_period[std::size_t(f)];
    std::vector<int> canonical(static_cast<std::size_t>(nf), 0);
    for (int f = 0; f < nf; ++f) canonical[std::size_t(f)] = tc.face_rotation[std::size_t(f)];
    out.report.consistent_canonical = consistent_edges(t, canonical);
    shift = start_corners(t, tc, offset);
    int best = consistent_edges(t, shift);
    for (int pass = 0; pass < 3; ++pass) {
      bool improved = false;
      for (std::size_t c = 0; c < offset.size(); ++c) {
        if (tc.combinations[c].face_size != 4) continue;
        for (int rho = 0; rho < period[c]; ++rho) {
          if (rho == offset[c]) continue;
          std::vector<int> trial = offset;
          trial[c] = rho;
          std::vector<int> s = start_corners(t, tc, trial);
          const int score = consistent_edges(t, s);
          if (score > best) best = score, offset = trial, shift = std::move(s), improved = true;
        }
      }
      if (!improved) break;
    }
  }
  Cage rotated = cage;
  for (int f = 0; f < nf; ++f) {
    const int n = cage.face_sizes[std::size_t(f)], off = cage.face_offsets[std::size_t(f)], s = shift[std::size_t(f)];
    for (int k = 0; k < n; ++k) {
      rotated.face_vertices[std::size_t(off + k)] = cage.face_vertices[std::size_t(off + (k + s) % n)];
      if (cage.has_uvs()) rotated.face_uvs[std::size_t(off + k)] = cage.face_uvs[std::size_t(off + (k + s) % n)];
    }
  }

  // 2. Face order: each face where meshoptimizer's vertex-cache order first reaches one of its triangles.
  std::vector<int> face_of(static_cast<std::size_t>(nf));
  std::iota(face_of.begin(), face_of.end(), 0);
  if (o.reorder) {
    std::vector<int> triangle_face;
    const std::vector<unsigned> tris = fan_triangles(rotated, &triangle_face);
    std::vector<unsigned> ordered(tris.size());
    meshopt_optimizeVertexCache(ordered.data(), tris.data(), tris.size(), rotated.positions.size());
    // meshoptimizer keeps each triangle's vertices in cyclic order; find its face by the rotation that
    // puts the smallest index first.
    auto key = [](const unsigned* v) {
      const int i = v[0] <= v[1] && v[0] <= v[2] ? 0 : v[1] <= v[2] ? 1 : 2;
      return std::array<unsigned, 3>{v[i], v[(i + 1) % 3], v[(i + 2) % 3]};
    };
    std::map<std::array<unsigned, 3>, std::vector<int>> by_key;
    for (std::size_t i = 0; i * 3 < tris.size(); ++i) by_key[key(&tris[3 * i])].push_back(triangle_face[i]);
    std::vector<std::uint8_t> taken(std::size_t(nf), 0);
    face_of.clear();
    for (std::size_t i = 0; i * 3 < ordered.size(); ++i) {
      auto& faces = by_key[key(&ordered[3 * i])];
      for (int f : faces)
        if (!taken[std::size_t(f)]) {
          taken[std::size_t(f)] = 1, face_of.push_back(f);
          break;
        }
    }
    for (int f = 0; f < nf; ++f)
      if (!taken[std::size_t(f)]) face_of.push_back(f);  // no triangle reached it (cannot happen for n >= 3)
  }
  std::vector<int> new_face(static_cast<std::size_t>(nf));
  for (int g = 0; g < nf; ++g) new_face[std::size_t(face_of[std::size_t(g)])] = g;

  Cage& c = out.cage;
  c.name = cage.name;
  c.uv_v_down = cage.uv_v_down;
  c.tags = cage.tags;
  for (int g = 0; g < nf; ++g) {
    const int f = face_of[std::size_t(g)], n = rotated.face_sizes[std::size_t(f)],
              off = rotated.face_offsets[std::size_t(f)];
    c.face_offsets.push_back(int(c.face_vertices.size()));
    c.face_sizes.push_back(n);
    for (int k = 0; k < n; ++k) {
      c.face_vertices.push_back(rotated.face_vertices[std::size_t(off + k)]);
      if (cage.has_uvs()) c.face_uvs.push_back(rotated.face_uvs[std::size_t(off + k)]);
    }
  }

  // 3. Vertices and texture coordinates by first use (meshoptimizer's fetch remap); unused ones last.
  const std::size_t nv = cage.positions.size();
  std::vector<unsigned> remap(nv, ~0u);
  if (o.reorder) {
    const std::vector<unsigned> tris = fan_triangles(c);
    meshopt_optimizeVertexFetchRemap(remap.data(), tris.data(), tris.size(), nv);
  } else {
    std::iota(remap.begin(), remap.end(), 0u);
  }
  unsigned next = 0;
  for (unsigned r : remap)
    if (r != ~0u) next = std::max(next, r + 1);
  for (unsigned& r : remap)
    if (r == ~0u) r = next++;
  out.vertex_of.assign(nv, 0);
  c.positions.assign(nv, glm::vec3(0.0f));
  for (std::size_t v = 0; v < nv; ++v) out.vertex_of[remap[v]] = int(v), c.positions[remap[v]] = cage.positions[v];
  for (int& v : c.face_vertices) v = int(remap[std::size_t(v)]);
  if (cage.has_uvs()) {
    std::vector<int> uv_remap(cage.uvs.size(), -1);
    int next_uv = 0;
    for (int& i : c.face_uvs) {
      if (uv_remap[std::size_t(i)] < 0) uv_remap[std::size_t(i)] = next_uv++;
      i = uv_remap[std::size_t(i)];
    }
    for (int& r : uv_remap)
      if (r < 0) r = next_uv++;
    c.uvs.assign(cage.uvs.size(), glm::vec2(0.0f));
    for (std::size_t i = 0; i < cage.uvs.size(); ++i) c.uvs[std::size_t(uv_remap[i])] = cage.uvs[i];
  }
  for (Crease& e : c.tags.creases) e.v0 = int(remap[std::size_t(e.v0)]), e.v1 = int(remap[std::size_t(e.v1)]);
  for (Corner& k : c.tags.corners) k.vertex = int(remap[std::size_t(k.vertex)]);
  for (int& h : c.tags.holes) h = new_face[std::size_t(h)];

  out.face_of = face_of;
  out.shift.resize(std::size_t(nf));
  for (int g = 0; g < nf; ++g) out.shift[std::size_t(g)] = shift[std::size_t(face_of[std::size_t(g)])];

  const Topology t2(c);
  const Measures after = measure(c, t2, analyze_combinations(t2), o.cache_size);
  CageOptimizeReport& r = out.report;
  r.faces = nf;
  r.combinations = before.combinations;
  r.stored_before = before.stored, r.stored_after = after.stored;
  r.quad_edges = before.quad_edges;
  r.consistent_before = before.consistent, r.consistent_after = after.consistent;
  r.acmr_before = before.acmr, r.acmr_after = after.acmr;
  r.atvr_before = before.atvr, r.atvr_after = after.atvr;
  return out;
}

}  // namespace tessera
