// Half-edge construction: twins through a hash of undirected vertex pairs (expected O(1) each, so a
// pole of any valence costs no more than its faces), rings by walking each vertex's fan once.
#include "shaders_cpp/cage/topology.h"

#include <cmath>
#include <cstdint>

namespace tessera {
namespace {

std::string join(const std::vector<int>& xs) {
  std::string s;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (i) s += ", ";
    s += std::to_string(xs[i]);
  }
  return s;
}

[[noreturn]] void fail(const std::string& name, const std::string& what) { throw CageError(name + ": " + what); }

}  // namespace

Topology::Topology(const Cage& cage) {
  if (cage.face_offsets.size() != cage.face_sizes.size())
    fail(cage.name, "face_offsets and face_sizes differ in length");
  read_faces(cage);
  build_edges(cage);
  build_rings(cage.name, cage.vertex_count());
  read_tags(cage);
}

// Faces: sizes, offsets, vertex range, repeated vertices (a per-vertex stamp of the last face seen), holes.
void Topology::read_faces(const Cage& cage) {
  const int nv = cage.vertex_count(), nf = cage.face_count();
  face_sizes_ = cage.face_sizes;
  face_offsets_ = cage.face_offsets;
  std::vector<int> stamp(std::size_t(nv), -1);
  int expected_offset = 0;
  for (int f = 0; f < nf; ++f) {
    const int n = face_sizes_[f];
    if (n < 3)
      fail(cage.name, "face " + std::to_string(f) + " has " + std::to_string(n) +
                          " vertices; a face needs at least 3");
    if (face_offsets_[f] != expected_offset ||
        std::size_t(expected_offset) + std::size_t(n) > cage.face_vertices.size())
      fail(cage.name, "face " + std::to_string(f) + " has an offset that does not follow the previous face");
    expected_offset += n;
    for (int k = 0; k < n; ++k) {
      const int v = cage.face_vertex(f, k);
      if (v < 0 || v >= nv)
        fail(cage.name, "face " + std::to_string(f) + " has vertex " + std::to_string(v) +
                            " (0-based), but the cage has " + std::to_string(nv) + " vertices");
      if (stamp[v] == f)
        fail(cage.name, "face " + std::to_string(f) + " is degenerate: it uses vertex " + std::to_string(v) +
                            " (0-based) twice");
      stamp[v] = f;
    }
  }
  if (std::size_t(expected_offset) != cage.face_vertices.size())
    fail(cage.name, "face_vertices has entries that no face uses");
  if (cage.has_uvs() && cage.face_uvs.size() != cage.face_vertices.size())
    fail(cage.name, "face_uvs does not have one entry per face corner");

  hole_.assign(std::size_t(nf), 0);
  for (int f : cage.tags.holes) {
    if (f < 0 || f >= nf)
      fail(cage.name, "hole names face " + std::to_string(f) + ", but the cage has " + std::to_string(nf) + " faces");
    hole_[f] = 1;
  }
}

// Half-edges and edges: each undirected vertex pair once; non-manifold edges are refused first (they
// also look like orientation errors), then two half-edges running the same way.
// Edges are numbered in the order of their first half-edge. The half-edges are bucketed by their lower
// vertex (counting sort, ascending half-edge within a bucket), so a half-edge finds the earlier ones of
// its edge among the few of its bucket: no hash map, and linear in the cage.
void Topology::build_edges(const Cage& cage) {
  const int nf = cage.face_count(), nh = int(cage.face_vertices.size()), nv = cage.vertex_count();
  origin_.assign(cage.face_vertices.begin(), cage.face_vertices.end());
  face_.resize(std::size_t(nh));
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < face_sizes_[f]; ++k) face_[face_offsets_[f] + k] = f;
  edge_.assign(std::size_t(nh), -1);
  twin_.assign(std::size_t(nh), -1);
  std::vector<int> start(std::size_t(nv) + 1, 0);
  for (int h = 0; h < nh; ++h) ++start[std::size_t(std::min(origin_[h], destination(h))) + 1];
  for (int v = 0; v < nv; ++v) start[std::size_t(v) + 1] += start[std::size_t(v)];
  std::vector<int> bucket(static_cast<std::size_t>(nh));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int h = 0; h < nh; ++h) bucket[std::size_t(fill[std::size_t(std::min(origin_[h], destination(h)))]++)] = h;
  }
  // first[h]: the first half-edge of h's edge.
  std::vector<int> first(static_cast<std::size_t>(nh));
  for (int v = 0; v < nv; ++v)
    for (int i = start[std::size_t(v)]; i < start[std::size_t(v) + 1]; ++i) {
      const int h = bucket[std::size_t(i)], far = std::max(origin_[h], destination(h));
      first[std::size_t(h)] = h;
      for (int j = start[std::size_t(v)]; j < i; ++j) {
        const int g = bucket[std::size_t(j)];
        if (std::max(origin_[g], destination(g)) == far) {
          first[std::size_t(h)] = first[std::size_t(g)];
          break;
        }
      }
    }
  std::vector<int> uses;  // per edge: half-edges on it (beyond 2 means non-manifold)
  for (int h = 0; h < nh; ++h) {
    const int f = first[std::size_t(h)];
    if (f == h) {
      edge_[h] = edge_count();
      edge_half_edges_.push_back({h, -1});
      uses.push_back(1);
      continue;
    }
    const int e = edge_[f];
    edge_[h] = e;
    if (uses[e] == 1) edge_half_edges_[e][1] = h;
    ++uses[e];
  }
  for (int e = 0; e < edge_count(); ++e)
    if (uses[e] > 2) {
      std::vector<int> faces;
      for (int h = 0; h < nh; ++h)
        if (edge_[h] == e) faces.push_back(face_[h]);
      const int h0 = edge_half_edges_[e][0];
      fail(cage.name, "non-manifold edge between vertices " + std::to_string(origin_[h0]) + " and " +
                          std::to_string(destination(h0)) + " (0-based): used by " + std::to_string(uses[e]) +
                          " faces (" + join(faces) + "); an edge may have at most two");
    }
  for (int e = 0; e < edge_count(); ++e) {
    const auto [h0, h1] = edge_half_edges_[e];
    if (h1 < 0) continue;
    if (origin_[h0] == origin_[h1])
      fail(cage.name, "faces " + std::to_string(face_[h0]) + " and " + std::to_string(face_[h1]) +
                          " both use the edge from vertex " + std::to_string(origin_[h0]) + " to " +
                          std::to_string(destination(h0)) + " (0-based) in the same direction (inconsistent orientation)");
    twin_[h0] = h1;
    twin_[h1] = h0;
  }
}

int Topology::edge_between(int a, int b) const {
  for (int h : ring(a))
    if (destination(h) == b) return edge_[h];
  for (int h : ring(b))
    if (destination(h) == a) return edge_[h];
  return -1;
}

// Rings: outgoing half-edges grouped by vertex (CSR), then each fan walked counter-clockwise.
void Topology::build_rings(const std::string& name, int nv) {
  const int nh = int(origin_.size());
  ring_offsets_.assign(std::size_t(nv) + 1, 0);
  for (int h = 0; h < nh; ++h) ++ring_offsets_[origin_[h] + 1];
  for (int v = 0; v < nv; ++v) ring_offsets_[v + 1] += ring_offsets_[v];
  std::vector<int> outgoing(static_cast<std::size_t>(nh));
  {
    std::vector<int> fill(ring_offsets_.begin(), ring_offsets_.end() - 1);
    for (int h = 0; h < nh; ++h) outgoing[fill[origin_[h]]++] = h;  // ascending h per vertex
  }
  ring_.resize(std::size_t(nh));
  valence_.assign(std::size_t(nv), 0);
  boundary_.assign(std::size_t(nv), 0);
  for (int v = 0; v < nv; ++v) {
    const int begin = ring_offsets_[v], count = ring_offsets_[v + 1] - begin;
    if (count == 0) {
      isolated_.push_back(v);
      continue;
    }
    int start = outgoing[begin], boundary_starts = 0;
    for (int i = begin; i < begin + count; ++i)
      if (twin_[outgoing[i]] < 0) {
        if (boundary_starts++ == 0) start = outgoing[i];
      }
    // A manifold vertex has one fan: closed (no boundary edge leaving it) or open with exactly one.
    int walked = 0;
    for (int h = start; h >= 0 && walked <= count;) {
      if (walked < count) ring_[begin + walked] = h;
      ++walked;
      h = twin_[prev(h)];
      if (h == start) break;
    }
    if (boundary_starts > 1 || walked != count)
      fail(name, "non-manifold vertex " + std::to_string(v) + " (0-based): its " + std::to_string(count) +
                     " faces form more than one fan");
    boundary_[v] = boundary_starts == 1;
    valence_[v] = count + (boundary_starts == 1 ? 1 : 0);
  }
  if (!isolated_.empty())
    warnings_.push_back(name + ": " + std::to_string(isolated_.size()) +
                        " isolated vertices (used by no face; ignored), first " + std::to_string(isolated_.front()) +
                        " (0-based)");
}

// Sharpness from the tags; a crease on two vertices that share no edge is left out with a warning.
void Topology::read_tags(const Cage& cage) {
  const int nv = cage.vertex_count();
  corner_sharpness_.assign(std::size_t(nv), 0.0f);
  edge_sharpness_.assign(std::size_t(edge_count()), 0.0f);
  sharp_at_.assign(std::size_t(nv), 0);
  auto check_sharpness = [&](float s, const std::string& what) {
    if (!std::isfinite(s) || s < 0)
      fail(cage.name, what + " has sharpness " + std::to_string(s) + "; it must be finite and >= 0");
  };
  for (const Corner& c : cage.tags.corners) {
    if (c.vertex < 0 || c.vertex >= nv)
      fail(cage.name, "corner names vertex " + std::to_string(c.vertex) + ", but the cage has " +
                          std::to_string(nv) + " vertices");
    check_sharpness(c.sharpness, "corner at vertex " + std::to_string(c.vertex));
    corner_sharpness_[c.vertex] = c.sharpness;
    if (c.sharpness > 0) sharp_at_[c.vertex] = 1;
  }
  int missing = 0;
  std::string first_missing;
  for (const Crease& c : cage.tags.creases) {
    if (c.v0 < 0 || c.v0 >= nv || c.v1 < 0 || c.v1 >= nv)
      fail(cage.name, "crease names vertices " + std::to_string(c.v0) + " and " + std::to_string(c.v1) +
                          ", but the cage has " + std::to_string(nv) + " vertices");
    check_sharpness(c.sharpness, "crease " + std::to_string(c.v0) + "-" + std::to_string(c.v1));
    const int e = c.v0 == c.v1 ? -1 : edge_between(c.v0, c.v1);
    if (e < 0) {
      if (missing++ == 0) first_missing = std::to_string(c.v0) + "-" + std::to_string(c.v1);
      continue;
    }
    edge_sharpness_[e] = c.sharpness;
    if (c.sharpness > 0) sharp_at_[c.v0] = sharp_at_[c.v1] = 1;
  }
  if (missing)
    warnings_.push_back(cage.name + ": " + std::to_string(missing) +
                        " creases name two vertices that share no edge (ignored), first " + first_missing);
}

int Topology::corner_of(int f, int v) const {
  for (int k = 0; k < face_sizes_[f]; ++k)
    if (origin_[face_offsets_[f] + k] == v) return k;
  return -1;
}

void validate_cage(const Cage& cage) { (void)Topology(cage); }

std::vector<bool> uv_seam_edges(const Cage& cage, const Topology& t) {
  std::vector<bool> seam(std::size_t(t.edge_count()), false);
  if (!cage.has_uvs()) return seam;
  for (int e = 0; e < t.edge_count(); ++e) {
    const auto [h0, h1] = t.edge_half_edges(e);
    if (h1 < 0) continue;
    // h0 goes a -> b, h1 goes b -> a: a's UV on the two sides is at h0 and next(h1).
    seam[e] = cage.face_uvs[h0] != cage.face_uvs[t.next(h1)] || cage.face_uvs[t.next(h0)] != cage.face_uvs[h1];
  }
  return seam;
}

}  // namespace tessera
