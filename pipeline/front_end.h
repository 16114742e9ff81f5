// The front end of a patch draw, shared by Device::draw (device.h) and stream_out (stream_output.h):
// IA with vertex caching by index, the VS once per unique control point, the HS phases and factor
// processing, window by window, and the cut of each window's patches into chunks by primitive count.
// What happens to a chunk's patches (DS, then setup or the caller's sink) is the caller's.
//
// Contract
// - Windows hold at most `window_patches` patches; their VS and HS outputs are the only storage that
//   grows with the draw, and it is bounded by the window.
// - Chunks are ranges of a window's patches in draw order whose primitive counts sum to at most
//   `chunk_primitives` (a chunk holds at least one patch, and at most 256); in a window's last
//   `tail_primitives`, a quarter of that (cut_chunks).
// - Everything stored is indexed by patch, so results do not depend on the thread count.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include "pipeline/draw_trace.h"
#include "pipeline/parallel.h"
#include "pipeline/pattern_cache.h"
#include "pipeline/pipeline_state.h"
#include "pipeline/stage_io.h"
#include "pipeline/statistics.h"

namespace tessera::detail {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Maps the vertex indices of a window to unique VS invocations (vertex caching by index).
struct VertexCache {
  std::vector<std::uint32_t> stamp;   // per vertex: window number that last used it
  std::vector<std::uint32_t> slot;    // per vertex: its VS output slot in that window
  std::vector<std::uint32_t> unique;  // vertex ids run through the VS this window, in first-use order
  std::vector<std::uint32_t> slots;   // per index of the window: its VS output slot
  std::uint32_t window = 0;

  // Out-of-range indices share one slot whose VS input is a zero vertex (D3D11: out-of-bounds fetch
  // returns 0); `unique` holds vertex_count for it.
  void build(std::span<const std::uint32_t> indices, std::size_t vertex_count) {
    if (stamp.size() != vertex_count + 1) {
      stamp.assign(vertex_count + 1, 0);
      slot.assign(vertex_count + 1, 0);
      window = 0;
    }
    ++window;
    unique.clear();
    slots.resize(indices.size());
    for (std::size_t i = 0; i < indices.size(); ++i) {
      const std::size_t v = std::min<std::size_t>(indices[i], vertex_count);
      if (stamp[v] != window) {
        stamp[v] = window;
        slot[v] = static_cast<std::uint32_t>(unique.size());
        unique.push_back(static_cast<std::uint32_t>(v));
      }
      slots[i] = slot[v];
    }
  }
  std::size_t bytes() const {
    return (stamp.capacity() + slot.capacity() + unique.capacity() + slots.capacity()) * sizeof(std::uint32_t);
  }
};

template <class Vertex, class Vs, class Out>
void run_vertex_shader(const Vs& vs, std::span<const Vertex> vertices, const VertexCache& cache,
                       std::vector<Out>& out) {
  out.resize(cache.unique.size());
  detail::parallel_for(tbb::blocked_range<std::size_t>(0, cache.unique.size(), 256), [&](const auto& r) {
    const Vertex zero{};
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::uint32_t id = cache.unique[i];
      out[i] = vs(id < vertices.size() ? vertices[id] : zero, id);
    }
  });
}

// IA and VS for one window of indices: vertex caching by index, then the VS once per unique vertex.
template <class Vertex, class Vs, class Out>
void assemble_and_shade_vertices(const Vs& vs, std::span<const Vertex> vertices, std::span<const std::uint32_t> indices,
                                 std::size_t primitives, VertexCache& cache, std::vector<Out>& out,
                                 DrawReport& report) {
  const auto start = Clock::now();
  cache.build(indices, vertices.size());
  run_vertex_shader(vs, vertices, cache, out);
  report.statistics.IAVertices += indices.size();
  report.statistics.IAPrimitives += primitives;
  report.statistics.VSInvocations += cache.unique.size();
  report.times.ia_vs += seconds_since(start);
}

// Cuts [0, count) into ranges whose summed cost stays at or below `budget` (a range holds at least one
// item) and at most `max_items` items. The items that start within the last `tail_cost` of the total
// cost are cut at a quarter of the budget: a window's last chunks are produced while the workers that
// found no chunk left wait for them, and their round's tiles wait too (the uniform displaced frog on
// 16 threads: 1.7 ms of an 11 ms frame with 2 to 8 of 16 workers busy, chunks of 0.4 ms on average).
inline void cut_chunks(std::span<const std::uint32_t> cost, std::size_t budget, std::size_t max_items,
                       std::vector<std::pair<std::uint32_t, std::uint32_t>>& out, std::size_t tail_cost = 0) {
  out.clear();
  // Where the tail begins, as a cost before an item (past every item without a tail).
  std::size_t tail_from = std::numeric_limits<std::size_t>::max();
  if (tail_cost != 0) {
    std::size_t total = 0;
    for (const std::uint32_t c : cost) total += c;
    tail_from = total > tail_cost ? total - tail_cost : 0;
  }
  const std::size_t tail_budget = std::max<std::size_t>(budget / 4, 1);
  std::uint32_t begin = 0;
  std::size_t sum = 0, before = 0;  // the current range's cost, and the cost of the items before i
  for (std::uint32_t i = 0; i < cost.size(); ++i) {
    const std::size_t b = before >= tail_from ? tail_budget : budget;
    if (i > begin && (sum + cost[i] > b || i - begin >= max_items)) {
      out.emplace_back(begin, i);
      begin = i;
      sum = 0;
    }
    sum += cost[i];
    before += cost[i];
  }
  if (begin < cost.size()) out.emplace_back(begin, static_cast<std::uint32_t>(cost.size()));
}

inline ts::FactorSet factor_set(ts::Domain domain, const TessFactors& f) {
  ts::FactorSet s;
  s.domain = domain;
  s.values = {f.edge[0], f.edge[1], f.edge[2], f.edge[3], f.inside[0], f.inside[1]};
  if (domain == ts::Domain::tri) s.values[3] = f.inside[0];
  return s;
}

// SV_DomainLocation of a tessellator point: (u, v, 0) on quads and isolines, barycentric (u, v, w) on
// triangles.
inline DomainLocation domain_location(ts::DomainPoint q, ts::Domain domain) {
  return DomainLocation{q.u, q.v, domain == ts::Domain::tri ? (1.0f - q.u) - q.v : 0.0f};
}

// Adds a thread's pattern cache counters and size to the draw's memory report.
inline void add_pattern_cache(MemoryStats& memory, const PatternCache& cache) {
  memory.pattern_cache_hits += cache.hits();
  memory.pattern_cache_misses += cache.misses();
  memory.pattern_cache_bytes += cache.bytes();
}

// The hull-shader phase of one window of patches: for each patch the control-point phase, the
// patch-constant phase, factor processing, and the pattern's primitive count (the cost that chunks
// are cut by; ts::primitive_count, from the processed factors, without tessellating). Parallel over
// patches; the results are stored by patch, so they do not depend on the thread count.
template <class VsOut, class ControlPoint, class PatchConstants>
struct HullPhase {
  std::vector<ControlPoint> control_points;  // kOut per patch
  std::vector<PatchConstants> constants;
  std::vector<ts::ProcessedFactors> processed;
  std::vector<std::uint32_t> cost;  // primitives; 0 when culled

  // times_of() returns the calling thread's StageTimes; each range of patches is a span of `trace`, if any.
  template <class Hs, class TimesOf>
  void run(const Hs& hs, const std::vector<VsOut>& vs_out, const VertexCache& vcache, std::size_t n, std::size_t n_in,
           std::size_t first, const TessellatorState& tstate, TimesOf&& times_of, DrawTrace* trace = nullptr) {
    constexpr int kOut = Hs::kOutputControlPoints;
    control_points.resize(n * kOut);
    constants.resize(n);
    processed.resize(n);
    cost.resize(n);
    detail::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16), [&](const auto& r) {
      StageTimes& times = times_of();
      const auto range_start = Clock::now();
      std::array<VsOut, 32> inputs;
      for (std::size_t p = r.begin(); p != r.end(); ++p) {
        const auto patch_id = static_cast<std::uint32_t>(first + p);
        for (std::size_t i = 0; i < n_in; ++i) inputs[i] = vs_out[vcache.slots[p * n_in + i]];
        const std::span<const VsOut> in(inputs.data(), n_in);
        ControlPoint* out = control_points.data() + p * kOut;
        for (int i = 0; i < kOut; ++i) out[i] = hs.control_point(in, i, patch_id);
        constants[p] = hs.patch_constants(in, std::span<const ControlPoint>(out, kOut), patch_id);
        processed[p] = ts::process_factors(tstate.partitioning, factor_set(tstate.domain, constants[p].factors));
        // Counted, not tessellated: the pattern is made once, when the DS needs it.
        cost[p] = static_cast<std::uint32_t>(ts::primitive_count(processed[p], tstate.output));
      }
      // Timed per range of patches: a clock read per patch cost as much as a small patch's HS.
      times.hs += seconds_since(range_start);
      if (trace)
        trace->record(TraceStage::hull_shader, trace_worker(), range_start, Clock::now(),
                      std::uint32_t(first + r.begin()), std::uint32_t(first + r.end()));
    });
  }

  std::size_t bytes() const {
    return control_points.capacity() * sizeof(ControlPoint) + constants.capacity() * sizeof(PatchConstants) +
           processed.capacity() * sizeof(ts::ProcessedFactors) + cost.capacity() * sizeof(std::uint32_t);
  }
};

// A patch of a chunk, ready for its domain shader.
template <class ControlPoint, class PatchConstants>
struct PatchWork {
  std::uint32_t patch_id = 0;  // SV_PrimitiveID
  const ts::Pattern& pattern;
  std::span<const ControlPoint> control_points;
  const PatchConstants& constants;
};

// One window's IA, VS and HS results and its chunks. A Device keeps one per type from draw to draw
// (Device::kept): made per draw, its vectors were allocated and zero-filled on one thread
// every frame, page faults included, while the other threads waited for the HS.
template <class VsOut, class ControlPoint, class PatchConstants>
struct WindowStorage {
  VertexCache vcache;
  std::vector<VsOut> vs_out;
  HullPhase<VsOut, ControlPoint, PatchConstants> hull;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> chunks;
  std::size_t bytes() const { return vcache.bytes() + vs_out.capacity() * sizeof(VsOut) + hull.bytes(); }
};

template <class Vertex, class Vs, class Hs>
class PatchFrontEnd {
 public:
  using VsOut = vs_output_t<Vs, Vertex>;
  static_assert(HullShader<Hs, VsOut>, "the hull shader does not have the shape stage_io.h describes");
  using ControlPoint = hs_control_point_t<Hs, VsOut>;
  using PatchConstants = hs_patch_constants_t<Hs, VsOut>;
  using Work = PatchWork<ControlPoint, PatchConstants>;
  using Storage = WindowStorage<VsOut, ControlPoint, PatchConstants>;
  static constexpr int kOut = Hs::kOutputControlPoints;

  // The draw's inputs must outlive the front end; validate_patch_draw() has accepted them. `storage`,
  // when given, must outlive it too and serve one front end at a time; without it the front end has
  // its own. `trace`, when given, records the VS and HS phases.
  PatchFrontEnd(std::span<const Vertex> vertices, std::span<const std::uint32_t> indices, int control_points,
                const Vs& vs, const Hs& hs, const TessellatorState& tessellator, int window_patches,
                std::size_t chunk_primitives, Storage* storage = nullptr, DrawTrace* trace = nullptr,
                std::size_t tail_primitives = 0)
      : owned_(storage ? nullptr : std::make_unique<Storage>()),
        s_(storage ? *storage : *owned_),
        vertices_(vertices),
        indices_(indices),
        n_in_(std::size_t(control_points)),
        vs_(vs),
        hs_(hs),
        tstate_(tessellator),
        window_(std::size_t(std::max(1, window_patches))),
        chunk_primitives_(chunk_primitives),
        tail_primitives_(tail_primitives),
        trace_(trace) {}

  // Runs the front end window by window; after each window's HS phase, on_window() handles its
  // chunk_count() chunks (with for_each_patch).
  template <class OnWindow>
  void run(DrawReport& report, OnWindow&& on_window) {
    tbb::enumerable_thread_specific<StageTimes> front_times;
    const std::size_t patch_count = indices_.size() / n_in_;
    for (first_ = 0; first_ < patch_count; first_ += window_) {
      const std::size_t n = std::min(window_, patch_count - first_);
      const auto vs_start = Clock::now();
      assemble_and_shade_vertices(vs_, vertices_, indices_.subspan(first_ * n_in_, n * n_in_), n, s_.vcache, s_.vs_out,
                                  report);
      if (trace_) trace_->record(TraceStage::vertex_shader, trace_worker(), vs_start, Clock::now());
      s_.hull.run(
          hs_, s_.vs_out, s_.vcache, n, n_in_, first_, tstate_, [&]() -> StageTimes& { return front_times.local(); },
          trace_);
      report.statistics.HSInvocations += n;
      for (std::size_t p = 0; p < n; ++p) report.patches_culled += s_.hull.processed[p].culled ? 1u : 0u;
      cut_chunks(s_.hull.cost, chunk_primitives_, 256, s_.chunks, tail_primitives_);
      on_window();
      window_bytes_peak_ = std::max(window_bytes_peak_, window_bytes());
    }
    for (const auto& t : front_times) report.times += t;
  }

  std::size_t chunk_count() const { return s_.chunks.size(); }
  std::size_t patch_count() const { return indices_.size() / n_in_; }
  // Patches of the draw before the end of the current window's chunk `c` (for progress reports).
  std::size_t patches_through_chunk(std::size_t c) const { return first_ + s_.chunks[c].second; }

  // Calls visit(const Work&) for each patch of the current window's chunk `c` that is not culled, in
  // draw order. Patterns come from `cache`; the time of a miss is added to `tessellator_seconds`.
  template <class Visit>
  void for_each_patch(std::size_t c, PatternCache& cache, double& tessellator_seconds, Visit&& visit) const {
    const auto [begin, end] = s_.chunks[c];
    for (std::uint32_t p = begin; p < end; ++p) {
      if (s_.hull.processed[p].culled) continue;
      bool hit = false;
      const ts::Pattern& pattern = cache.get(s_.hull.processed[p], tstate_.output, hit, &tessellator_seconds);
      visit(Work{static_cast<std::uint32_t>(first_ + p), pattern,
                 std::span<const ControlPoint>(s_.hull.control_points.data() + p * kOut, kOut), s_.hull.constants[p]});
    }
  }

  // Bytes of the current window's IA, VS and HS storage, and their peak over the windows so far.
  std::size_t window_bytes() const { return s_.bytes(); }
  std::size_t window_bytes_peak() const { return window_bytes_peak_; }

 private:
  std::unique_ptr<Storage> owned_;
  Storage& s_;
  std::span<const Vertex> vertices_;
  std::span<const std::uint32_t> indices_;
  std::size_t n_in_;
  const Vs& vs_;
  const Hs& hs_;
  TessellatorState tstate_;
  std::size_t window_;
  std::size_t chunk_primitives_;
  std::size_t tail_primitives_;  // each window's last primitives, cut into smaller chunks (cut_chunks)
  DrawTrace* trace_;

  std::size_t first_ = 0;  // the current window's first patch
  std::size_t window_bytes_peak_ = 0;
};

}  // namespace tessera::detail
