// Combination keys: per corner a self-delimiting word sequence (its length follows from the face count
// it records), the smallest rotation chosen by comparing the concatenations, and a hash map from the
// key's hash to combination so each face costs its 1-ring. Keys are read in parallel, a block of faces at a time,
// and given their combinations in face order, so the numbering does not depend on the threads.
#include "shaders_cpp/cage/topology_combinations.h"

#include <algorithm>
#include <bit>
#include <map>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace tessera {
namespace {

std::uint64_t key_hash(const std::vector<std::int32_t>& k) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::int32_t w : k) h = (h ^ std::uint32_t(w)) * 1099511628211ull;
  return h;
}

// Combinations by their key's hash (computed with the key, in parallel): the combinations whose keys
// hash alike, compared word by word; and the last face's, which most faces of a regular cage repeat.
struct KeyIndex {
  std::unordered_map<std::uint64_t, std::vector<int>> by_hash;
  std::uint64_t last_hash = 0;
  int last = -1;
};

// Where each half-edge sits in its origin's ring.
// (Each half-edge is in one ring: vertices in parallel write disjoint entries.)
std::vector<int> ring_positions(const Topology& t) {
  std::vector<int> pos(std::size_t(t.half_edge_count()), 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, t.vertex_count(), 4096), [&](const tbb::blocked_range<int>& range) {
    for (int v = range.begin(); v < range.end(); ++v) {
      const auto r = t.ring(v);
      for (std::size_t i = 0; i < r.size(); ++i) pos[std::size_t(r[i])] = int(i);
    }
  });
  return pos;
}

// The fan of the corner at half-edge h, in key order: from h for an interior vertex, from the boundary
// for a boundary one (the ring's own order).
struct Fan {
  int vertex, start, count;
  bool boundary;
};
Fan fan_of(const Topology& t, int h, int pos_in_ring) {
  const int v = t.origin(h);
  const bool b = t.is_boundary_vertex(v);
  return {v, b ? 0 : pos_in_ring, t.vertex_face_count(v), b};
}

void corner_words(const Topology& t, int h, int pos_in_ring, std::vector<std::int32_t>& out) {
  const Fan fan = fan_of(t, h, pos_in_ring);
  const auto ring = t.ring(fan.vertex);
  out.push_back(fan.boundary);
  out.push_back(fan.count);
  out.push_back(fan.boundary ? pos_in_ring : 0);
  for (int j = 0; j < fan.count; ++j) out.push_back(t.face_size(t.face(ring[(fan.start + j) % fan.count])));
  out.push_back(std::bit_cast<std::int32_t>(t.corner_sharpness(fan.vertex)));
  for (int j = 0; j < fan.count; ++j)
    out.push_back(std::bit_cast<std::int32_t>(t.edge_sharpness(t.edge(ring[(fan.start + j) % fan.count]))));
  if (fan.boundary) out.push_back(std::bit_cast<std::int32_t>(t.edge_sharpness(t.edge(t.prev(ring[fan.count - 1])))));
}

PatchClass classify(const Topology& t, int f) {
  if (t.is_hole(f)) return PatchClass::hole;
  const int n = t.face_size(f);
  bool boundary = false, all_quads = true, sharp = false, regular_corners = true, regular_boundary_corners = true;
  for (int k = 0; k < n; ++k) {
    const int v = t.origin(t.face_half_edge(f) + k);
    const bool b = t.is_boundary_vertex(v);
    const int val = t.valence(v);
    boundary |= b;
    sharp |= t.has_sharpness_at(v);
    for (int h : t.ring(v)) all_quads &= t.face_size(t.face(h)) == 4;
    regular_corners &= !b && val == 4;
    regular_boundary_corners &= b ? (val == 3 || val == 2) : val == 4;
  }
  const bool plain = n == 4 && all_quads && !sharp;
  if (!boundary) return plain && regular_corners ? PatchClass::regular : PatchClass::irregular;
  return plain && regular_boundary_corners ? PatchClass::regular_boundary : PatchClass::boundary;
}

// A face's key read from its canonical corner, and the rotation and symmetry that found it.
struct FaceKey {
  PatchClass cls = PatchClass::hole;
  int rotation = 0, period = 1;
  std::vector<std::int32_t> key;
  std::uint64_t hash = 0;
};

// Working vectors of one thread, kept between faces.
struct KeyScratch {
  std::vector<std::int32_t> words;  // the corners' words, corner 0 first
  std::vector<std::size_t> starts;  // where each corner's words start
};

void face_key(const Topology& t, const std::vector<int>& pos, int f, KeyScratch& w, FaceKey& out) {
  out.cls = classify(t, f);
  if (out.cls == PatchClass::hole) return;
  const int n = t.face_size(f), h0 = t.face_half_edge(f);
  w.words.clear();
  w.starts.resize(std::size_t(n));
  for (int k = 0; k < n; ++k) {
    w.starts[std::size_t(k)] = w.words.size();
    corner_words(t, h0 + k, pos[std::size_t(h0 + k)], w.words);
  }
  // Read from corner r, the key is the words from corner r's on, round to the start: the words twice
  // over hold every rotation as one run, compared in place; only the chosen one is written out.
  const std::size_t size = w.words.size();
  w.words.insert(w.words.end(), w.words.begin(), w.words.end());
  const auto run = [&](int r) { return w.words.begin() + std::ptrdiff_t(w.starts[std::size_t(r)]); };
  const auto compare = [&](int a, int b) {  // < 0, 0, > 0 as rotation a's key is below, equal to, above b's
    const auto x = run(a), y = run(b);
    if (std::equal(x, x + std::ptrdiff_t(size), y)) return 0;
    return std::lexicographical_compare(x, x + std::ptrdiff_t(size), y, y + std::ptrdiff_t(size)) ? -1 : 1;
  };
  out.rotation = 0;
  for (int r = 1; r < n; ++r)
    if (compare(r, out.rotation) < 0) out.rotation = r;
  // The face's symmetry: the smallest shift from the canonical corner that reads the same key.
  out.period = n;
  for (int p = 1; p < n; ++p)
    if (compare((out.rotation + p) % n, out.rotation) == 0) {
      out.period = p;
      break;
    }
  out.key.assign(1, n);
  out.key.insert(out.key.end(), run(out.rotation), run(out.rotation) + std::ptrdiff_t(size));
  out.hash = key_hash(out.key);
}

// Face f's combination (a new one for a new key), its rotation and symmetry, and the counts.
void add_face(const Topology& t, int f, FaceKey& k, KeyIndex& index, TopologyCombinations& out) {
  out.face_class[std::size_t(f)] = k.cls;
  if (k.cls == PatchClass::hole) return;
  const int n = t.face_size(f);
  out.face_period[std::size_t(f)] = k.period;
  int found = -1;
  if (index.last >= 0 && index.last_hash == k.hash && out.combinations[std::size_t(index.last)].key == k.key) {
    found = index.last;
  } else {
    std::vector<int>& alike = index.by_hash[k.hash];
    for (int i : alike)
      if (out.combinations[std::size_t(i)].key == k.key) found = i;
    if (found < 0) {
      found = int(out.combinations.size());
      alike.push_back(found);
      Combination c;
      c.key = std::move(k.key);
      c.text = combination_text(t, f, k.rotation);
      c.face_size = n;
      c.patch_class = k.cls;
      c.boundary = k.cls == PatchClass::boundary || k.cls == PatchClass::regular_boundary;
      out.combinations.push_back(std::move(c));
    }
    index.last = found, index.last_hash = k.hash;
  }
  Combination& c = out.combinations[std::size_t(found)];
  ++c.count;
  c.faces.push_back(f);
  out.face_combination[std::size_t(f)] = found;
  out.face_rotation[std::size_t(f)] = k.rotation;

  CombinationStats& s = out.stats;
  ++s.patches;
  if (n == 3)
    ++s.triangles;
  else if (n == 4)
    ++s.quads;
  else
    ++s.polygons;
  if (k.cls == PatchClass::regular) ++s.regular;
  if (k.cls == PatchClass::boundary || k.cls == PatchClass::regular_boundary) ++s.boundary;
  if (k.cls == PatchClass::regular_boundary) ++s.regular_boundary;
}

}  // namespace

TopologyCombinations analyze_combinations(const Topology& t) {
  TopologyCombinations out;
  const int nf = t.face_count();
  out.face_combination.assign(std::size_t(nf), -1);
  out.face_rotation.assign(std::size_t(nf), 0);
  out.face_period.assign(std::size_t(nf), 1);
  out.face_class.assign(std::size_t(nf), PatchClass::hole);
  const std::vector<int> pos = ring_positions(t);
  KeyIndex index;
  // The keys a block of faces at a time, in parallel; then, in face order, each key's combination.
  constexpr int kBlock = 8192;
  std::vector<FaceKey> keys(std::size_t(std::min(nf, kBlock)));
  tbb::enumerable_thread_specific<KeyScratch> scratch;
  for (int first = 0; first < nf; first += kBlock) {
    const int count = std::min(kBlock, nf - first);
    tbb::parallel_for(tbb::blocked_range<int>(0, count, 256), [&](const tbb::blocked_range<int>& r) {
      KeyScratch& w = scratch.local();
      for (int i = r.begin(); i < r.end(); ++i) face_key(t, pos, first + i, w, keys[std::size_t(i)]);
    });
    for (int i = 0; i < count; ++i) {
      const int f = first + i;
      add_face(t, f, keys[std::size_t(i)], index, out);
    }
  }
  return out;
}

std::string combination_text(const Topology& t, int f, int rotation) {
  const int n = t.face_size(f), h0 = t.face_half_edge(f);
  std::string s = n == 3 ? "0" : "";
  for (int i = 0; i < n; ++i) {
    const int h = h0 + (rotation + i) % n;
    const int v = t.origin(h);
    const auto ring = t.ring(v);
    const int count = int(ring.size());
    const bool b = t.is_boundary_vertex(v);
    const int start = b ? 0 : int(std::find(ring.begin(), ring.end(), h) - ring.begin());
    if (!s.empty()) s += ' ';
    s += std::to_string(t.valence(v));
    if (b) s += 'b';
    if (t.has_sharpness_at(v)) s += '*';
    bool quads = true;
    for (int j = 0; j < count; ++j) quads &= t.face_size(t.face(ring[j])) == 4;
    if (!quads) {
      s += '(';
      for (int j = 0; j < count; ++j) {
        if (j) s += ' ';
        s += std::to_string(t.face_size(t.face(ring[(start + j) % count])));
      }
      s += ')';
    }
  }
  return s;
}

}  // namespace tessera
