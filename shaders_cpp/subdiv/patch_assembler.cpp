#include "shaders_cpp/subdiv/patch_assembler.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shaders_cpp/subdiv/patch_construction.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "tessellator/check.h"

namespace tessera::subdiv {
namespace {

// The patch's summation order: its IA patch's positions by ascending cage vertex index.
void set_order(SubdPatch& p, const std::vector<int>& ia) {
  std::array<std::uint8_t, kMaxPatchControlPoints> order{};
  std::iota(order.begin(), order.begin() + std::ptrdiff_t(ia.size()), std::uint8_t(0));
  std::sort(order.begin(), order.begin() + std::ptrdiff_t(ia.size()),
            [&](std::uint8_t a, std::uint8_t b) { return ia[a] < ia[b]; });
  for (std::size_t i = 0; i < ia.size(); ++i) p.order[i] = order[i];
}

}  // namespace

SubdPatch& PatchAssembler::add(PatchGroup& group, int face, int sub, PatchKind kind, const std::vector<int>& ring,
                               const std::vector<Stencil>& stencils, const std::array<EdgeFactorKey, 4>& edges,
                               int rotation, int corners) {
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
      // A weight this small is the round-off left where a mask's terms cancel (exactly zero in exact
      // arithmetic), and whether it is left depends on the order the cage's vertex numbering gave the
      // terms: kept, two faces of one topology combination would get tables that differ in it.
      if (std::abs(w) >= kResidualWeight) table.weights[r * ring.size() + std::size_t(it->second)] = static_cast<float>(w);
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
  set_order(p, ia);
  p.edge_keys = edges;
  p.rotation = std::uint8_t(rotation);
  if (into_ >= 0) {
    const std::size_t slot = std::size_t(std::exchange(into_, -1));
    TESSERA_CHECK(groups_[slot] == &group, "PatchAssembler::add_into: slot", slot, "of another group");
    rings_[slot] = ia;
    return group.patches[index_[slot]] = p;
  }
  group.patches.push_back(p);
  rings_.push_back(ia);
  groups_.push_back(&group);
  index_.push_back(group.patches.size() - 1);
  return group.patches.back();
}

int PatchAssembler::reserve(PatchGroup& group) {
  group.patches.emplace_back();
  rings_.emplace_back();
  groups_.push_back(&group);
  index_.push_back(group.patches.size() - 1);
  return int(rings_.size() - 1);
}

void PatchAssembler::place(int slot, int face, PatchKind kind, std::vector<int> ring, int table,
                           const std::array<EdgeFactorKey, 4>& edges, int rotation) {
  const std::size_t s = std::size_t(slot);
  SubdPatch& p = groups_[s]->patches[index_[s]];
  p = SubdPatch{};
  p.face = face;
  p.kind = kind;
  p.ring_size = int(ring.size());
  p.table = table;
  set_order(p, ring);
  p.edge_keys = edges;
  p.rotation = std::uint8_t(rotation);
  rings_[s] = std::move(ring);
}

void PatchAssembler::finish() {
  // Tables numbered in the order the patches (in slot order: face order) first use them, as add()
  // alone would have numbered them: a slot filled by add_into() later interns its table late.
  std::vector<int> number(out_.tables.size(), -1);
  int next = 0;
  for (std::size_t i = 0; i < rings_.size(); ++i)
    if (const int t = groups_[i]->patches[index_[i]].table; t >= 0 && number[std::size_t(t)] < 0)
      number[std::size_t(t)] = next++;
  std::vector<StencilTable> tables(static_cast<std::size_t>(next));
  for (std::size_t t = 0; t < number.size(); ++t)
    if (number[t] >= 0) tables[std::size_t(number[t])] = std::move(out_.tables[t]);
  out_.tables = std::move(tables);
  for (PatchGroup* g : {&out_.quads, &out_.tris})
    for (SubdPatch& p : g->patches)
      if (p.table >= 0) p.table = number[std::size_t(p.table)];
  interned_.clear();
  for (PatchGroup* g : {&out_.quads, &out_.tris}) {
    g->control_points = 1;
    for (const auto& p : g->patches) g->control_points = std::max(g->control_points, p.ring_size);
  }
  // Slot i is patch index_[i] of its group: its indices' place is known, so the slots fill in parallel.
  for (PatchGroup* g : {&out_.quads, &out_.tris}) g->indices.resize(g->patches.size() * std::size_t(g->control_points));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rings_.size(), 4096), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      PatchGroup& g = *groups_[i];
      const auto& ring = rings_[i];
      const std::size_t cp = std::size_t(g.control_points);
      std::uint32_t* out = g.indices.data() + index_[i] * cp;
      for (std::size_t k = 0; k < cp; ++k) out[k] = std::uint32_t(ring[k < ring.size() ? k : 0]);
    }
  });
}

int PatchAssembler::intern(StencilTable&& table) {
  std::string key(reinterpret_cast<const char*>(table.weights.data()), table.weights.size() * sizeof(float));
  key += std::to_string(table.rows) + ":" + std::to_string(table.ring);
  const auto [it, added] = interned_.emplace(std::move(key), int(out_.tables.size()));
  if (added) out_.tables.push_back(std::move(table));
  return it->second;
}

}  // namespace tessera::subdiv
