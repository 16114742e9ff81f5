// The draw entry points: a Device owns the worker threads; draw() runs one draw call through
// IA -> VS -> HS -> tessellator -> DS -> clip/setup/bin -> rasterizer -> PS -> output merger.
//
// Contract
// - Deterministic: the framebuffer bytes and the statistics are identical for any thread count and
//   from run to run. Work is split into chunks of primitives in draw order; each tile rasterizes the
//   chunks' primitives in draw order; every computation on a primitive is a pure function of it.
// - Bounded memory: the front end (front_end.h) handles at most `window_patches` patches at a time
//   (VS and HS outputs), and cuts their output into chunks of about `chunk_primitives` primitives, in
//   rounds of up to `chunks_in_flight` (tile_schedule.h); the chunks in flight (produced while earlier
//   ones are rasterized) share rounds_in_flight x chunks_in_flight chunk buffers. Peak memory therefore
//   does not grow with the tessellation factor (one patch is at most 8192 triangles); it grows
//   linearly with the thread count (the default chunks_in_flight is 4 x threads).
// - A Device runs one draw at a time (draws on one device from several threads take turns): its chunk
//   slots are reused from draw to draw, so their storage is allocated and touched once, not per frame.
// - Bad data is reported, not crashed on: validate() errors are returned as one-line messages;
//   D3D11's own rules cover the rest (out-of-range indices fetch a zero vertex, NaN/Inf positions
//   discard the primitive, out-of-range factors are clamped or cull the patch).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <typeindex>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "pipeline/draw_trace.h"
#include "pipeline/framebuffer.h"
#include "pipeline/front_end.h"
#include "pipeline/parallel.h"
#include "pipeline/pattern_cache.h"
#include "pipeline/pipeline_state.h"
#include "pipeline/primitive_setup.h"
#include "pipeline/raster_tile.h"
#include "pipeline/stage_io.h"
#include "pipeline/patch_orientation.h"
#include "pipeline/statistics.h"
#include "pipeline/tile_schedule.h"
#include "pipeline/triangle_list_setup.h"

namespace tessera {

struct DeviceOptions {
  int threads = 0;                      // worker threads; 0 = all hardware threads
  int tile_size = 64;                   // screen tile edge in pixels (even, 8..1024)
  std::size_t chunk_primitives = 4096;  // a chunk is cut before its primitive count would pass this
  // Patches through VS and HS at once (a mesh draw: 4 x as many triangles through the VS). Each window
  // ends with the draw's pipeline drained (its last round rasterized with nothing to overlap), so a
  // window holds a whole frog (1292 patches): 16 threads, displaced frog 19.4 -> 17.9 ms, frog 7.8 ->
  // 7.6 (1024 patches before; medians of five rounds, docs/performance.md).
  int window_patches = 4096;
  // Chunks per round: a round's tiles are rasterized once all its chunks are produced (each tile once
  // its earlier rounds are; tile_schedule.h). 0: four times the thread count, at least 4.
  int chunks_in_flight = 0;
  // Rounds whose storage exists at once (produced while earlier ones are rasterized; at least 2). Chunk
  // storage is rounds_in_flight x chunks_in_flight chunk buffers. 0: the default, 2 on up to two
  // threads, else 3.
  int rounds_in_flight = 0;
};

// Called after each round of chunks of a patch draw is rasterized, one call at a time and in order (on
// a worker thread or the drawing thread): the draw's patches done (through the last chunk rasterized)
// and its total. For progress displays; it sees no pixels and cannot change any result.
using DrawProgress = std::function<void(std::size_t patches_done, std::size_t patches_total)>;

// A patch list (D3D11_PRIMITIVE_TOPOLOGY_n_CONTROL_POINT_PATCHLIST, n = control_points) through the
// stages up to the domain shader: what a draw (PatchDraw) and a stream-output pass (StreamDraw,
// stream_output.h) share.
template <class Vertex, class Vs, class Hs, class Ds>
struct PatchStages {
  std::span<const Vertex> vertices;
  std::span<const std::uint32_t> indices;
  int control_points = 0;  // per input patch, 1..32
  Vs vs;
  Hs hs;
  Ds ds;
  TessellatorState tessellator;
};

// A draw of a patch list: its stages, then the pixel shader and the fixed-function state after them.
template <class Vertex, class Vs, class Hs, class Ds, class Ps>
struct PatchDraw : PatchStages<Vertex, Vs, Hs, Ds> {
  Ps ps;
  RasterizerState rasterizer;
  DepthState depth;
  Viewport viewport;
};

// A draw of an indexed triangle list without tessellation; the vertex shader returns ClipVertex<N>.
template <class Vertex, class Vs, class Ps>
struct MeshDraw {
  std::span<const Vertex> vertices;
  std::span<const std::uint32_t> indices;
  Vs vs;
  Ps ps;
  RasterizerState rasterizer;
  DepthState depth;
  Viewport viewport;
};

struct DrawResult {
  std::string error;  // empty on success
  DrawReport report;
  bool ok() const { return error.empty(); }
};

// One-line reasons a draw's fixed-function state cannot be used, or an empty string.
std::string validate_viewport(const Viewport& vp, const Framebuffer& fb);
std::string validate_patch_draw(std::size_t index_count, int control_points, const TessellatorState& ts);

namespace detail {

// The back end: chunk slots, and the schedule (tile_schedule.h) that produces them and rasterizes their
// tiles in draw order. The slots are the device's (Device::kept): their storage outlives the draw.
template <std::size_t N, class Ps>
class Backend {
 public:
  // `slot_count` chunks per round; the slots hold `rounds` rounds in flight (at least 2): produced in
  // parallel while earlier ones are rasterized. `trace`, when given, records each chunk, round's tile lists and tile.
  Backend(const SetupContext& setup, const DepthState& depth, const Ps& ps, Framebuffer& fb,
          std::vector<ChunkBuffer<N>>& slots, int slot_count, int rounds, DrawTrace* trace = nullptr)
      : setup_(setup),
        rc_{depth, setup.min_depth, setup.max_depth},
        ps_(ps),
        fb_(fb),
        slots_(slots),
        per_round_(std::size_t(std::max(slot_count, 1))),
        sets_(std::size_t(std::max(rounds, 2))),
        trace_(trace) {
    slots_.resize(sets_ * per_round_);
  }

  const SetupContext& setup() const { return setup_; }

  // Produces chunks [0, count) with produce(chunk, ChunkBuffer&), in rounds of `slot_count` chunks (the
  // window's last rounds smaller: tile_schedule.h's round_starts), and
  // rasterizes each tile's primitives as the rounds holding them are produced (tile_schedule.h: one pool
  // of workers, no barrier between rounds; each tile takes its rounds, and the chunks within a round, in
  // draw order). after_round(chunks done) follows each round's rasterization, in order.
  template <class Produce, class AfterRound>
  void run(std::size_t count, Produce&& produce, DrawReport& report, AfterRound&& after_round) {
    const TileGrid& g = setup_.tiles;
    const std::size_t tiles = std::size_t(g.count());
    // Chunk storage per slot, as last seen: a slot is read only by the stage that owns it (its producer,
    // or the consumption of its round), so the others' sizes are those of their last consumption.
    std::vector<std::size_t> slot_bytes(slots_.size(), 0);
    for (std::size_t i = 0; i < slots_.size(); ++i) slot_bytes[i] = slots_[i].capacity_bytes();
    // Tile lists for twice as many rounds as full rounds fit in the slots: the window's last rounds are
    // smaller (round_starts), and their lists need not wait for an older round's to be freed.
    const std::size_t list_sets = 2 * sets_;
    lists_.resize(list_sets);
    const std::size_t workers = std::size_t(tbb::this_task_arena::max_concurrency());
    tbb::enumerable_thread_specific<std::pair<std::uint64_t, double>> local;  // PS invocations, raster seconds

    const auto produce_chunk = [&](std::size_t c, std::size_t r, std::size_t s) {
      ChunkBuffer<N>& slot = slots_[s];
      const auto start = trace_ ? Clock::now() : Clock::time_point{};
      slot.reset(setup_.tiles.count());
      produce(c, slot);
      slot.finish_bins();
      if (trace_)
        trace_->record(TraceStage::chunk, trace_worker(), start, Clock::now(), std::uint32_t(r), std::uint32_t(c));
    };
    // A round's tile lists: for each tile, the round's chunks holding its primitives, in draw order (a
    // counting sort, stable in chunk order, over the chunks' touched tiles: the work is proportional to
    // the (chunk, tile) pairs with primitives, not to chunks x tiles), and the busy tiles with their loads.
    const auto list_tiles = [&](std::size_t r,
                                std::span<const std::uint32_t> chunk_slots) -> std::span<const TileLoad> {
      const auto start = trace_ ? Clock::now() : Clock::time_point{};
      RoundLists& l = lists_[r % list_sets];
      l.slots.assign(chunk_slots.begin(), chunk_slots.end());
      const std::size_t n = chunk_slots.size();
      const auto chunk = [&](std::size_t k) -> const ChunkBuffer<N>& { return slots_[l.slots[k]]; };
      l.tile_first.assign(tiles + 1, 0);
      for (std::size_t k = 0; k < n; ++k)
        for (std::uint32_t t : chunk(k).touched) ++l.tile_first[t + 1];
      l.busy.clear();
      for (std::size_t t = 0; t < tiles; ++t) {
        if (l.tile_first[t + 1] != 0) l.busy.push_back({std::uint32_t(t), 0});
        l.tile_first[t + 1] += l.tile_first[t];
      }
      l.tile_chunks.resize(l.tile_first.back());
      l.cursor.assign(l.tile_first.begin(), l.tile_first.end() - 1);
      for (std::uint32_t k = 0; k < n; ++k)
        for (std::uint32_t t : chunk(k).touched) l.tile_chunks[l.cursor[t]++] = k;
      for (TileLoad& b : l.busy)
        for (std::uint32_t k = l.tile_first[b.tile]; k != l.tile_first[b.tile + 1]; ++k)
          b.load += std::uint32_t(chunk(l.tile_chunks[k]).bin(int(b.tile)).size());
      if (trace_) trace_->record(TraceStage::tile_lists, trace_worker(), start, Clock::now(), std::uint32_t(r));
      return l.busy;
    };
    const auto prepare = [&](std::uint32_t t) { fb_.prepare_tile(int(t)); };
    const auto rasterize = [&](std::uint32_t t, std::span<const std::uint32_t> rounds, std::uint8_t quarter) {
      auto& mine = local.local();
      const auto start = Clock::now();
      int tx0 = int(t % std::uint32_t(g.columns)) * g.tile_size, ty0 = int(t / std::uint32_t(g.columns)) * g.tile_size;
      int tx1 = tx0 + g.tile_size, ty1 = ty0 + g.tile_size;
      if (quarter == 0) {
        fb_.prepare_tile(int(t));  // a pending clear lands in this core's cache just before the tile's primitives
      } else {
        // Quarters are tile_size / 2 wide, an even number of pixels: no 2x2 quad straddles two.
        const int half = g.tile_size / 2, q = quarter - 1;
        tx0 += (q % 2) * half;
        ty0 += (q / 2) * half;
        tx1 = tx0 + half;
        ty1 = ty0 + half;
      }
      tx1 = std::min(tx1, fb_.width());
      ty1 = std::min(ty1, fb_.height());
      const auto for_each_primitive = [&](const auto& visit) {
        for (const std::uint32_t r : rounds) {
          const RoundLists& l = lists_[r % list_sets];
          for (std::uint32_t k = l.tile_first[t]; k != l.tile_first[t + 1]; ++k) {
            const ChunkBuffer<N>& chunk = slots_[l.slots[l.tile_chunks[k]]];
            for (std::uint32_t i : chunk.bin(int(t))) visit(chunk.primitives[i]);
          }
        }
      };
      if (tx0 < tx1 && ty0 < ty1)
        mine.first += rasterize_tile<N>(for_each_primitive, tx0, ty0, tx1, ty1, ps_, rc_, fb_);
      const auto end = Clock::now();
      mine.second += std::chrono::duration<double>(end - start).count();
      if (trace_) trace_->record(TraceStage::tile, trace_worker(), start, end, t, quarter);
    };
    // Under the schedule's lock, before the round's storage is reused.
    const auto consumed = [&](std::size_t, std::span<const std::uint32_t> chunk_slots) {
      for (const std::uint32_t s : chunk_slots) {
        const ChunkBuffer<N>& slot = slots_[s];
        slot_bytes[s] = slot.capacity_bytes();
        report.statistics += slot.statistics;
        report.times += slot.times;
        report.patches_back_culled += slot.patches_back_culled;
      }
      report.memory.chunks += chunk_slots.size();
      std::size_t total = 0;
      for (const std::size_t b : slot_bytes) total += b;
      chunk_bytes_peak_ = std::max(chunk_bytes_peak_, total);
    };
    const auto finished = [&](std::size_t, std::size_t end) { after_round(end); };
    ScheduleShape shape;
    shape.chunks = count;
    shape.per_round = per_round_;
    // The last rounds halve down to half a chunk per worker: smaller, their tile lists and the tiles'
    // extra visits would cost more than the raster they leave after the last chunk.
    shape.smallest = std::max<std::size_t>(1, workers / 2);
    shape.slots = slots_.size();
    shape.lists = list_sets;
    shape.tiles = tiles;
    shape.workers = int(workers);
    shape.can_split = g.tile_size % 4 == 0;
    report.memory.tiles_split +=
        run_tile_schedule(shape, produce_chunk, list_tiles, prepare, rasterize, consumed, finished);
    for (const auto& [invocations, seconds] : local) {
      report.statistics.PSInvocations += invocations;
      report.times.raster += seconds;
    }
  }
  template <class Produce>
  void run(std::size_t count, Produce&& produce, DrawReport& report) {
    run(count, std::forward<Produce>(produce), report, [](std::size_t) {});
  }

  std::size_t chunk_bytes_peak() const { return chunk_bytes_peak_; }

 private:
  // A round's tile lists (built once its chunks are produced; held until it is consumed).
  struct RoundLists {
    std::vector<std::uint32_t> slots;  // the round's chunks' slots, in chunk order
    std::vector<std::uint32_t> tile_first, cursor, tile_chunks;
    std::vector<TileLoad> busy;
  };

  SetupContext setup_;
  RasterContext rc_;
  const Ps& ps_;
  Framebuffer& fb_;
  std::vector<ChunkBuffer<N>>& slots_;
  std::size_t per_round_;
  std::size_t sets_;
  DrawTrace* trace_;
  std::size_t chunk_bytes_peak_ = 0;
  std::vector<RoundLists> lists_;  // by round, modulo their count
};

template <std::size_t N>
struct PatchScratch {
  PatternCache patterns;
  std::vector<SetupVertex<N>> domain_outputs;
  std::vector<DomainLocation> locations;    // for a batch domain shader
  std::vector<ClipVertex<N>> clip_outputs;  // its results, before setup
  std::size_t bytes() const {
    return patterns.bytes() + domain_outputs.capacity() * sizeof(SetupVertex<N>) +
           locations.capacity() * sizeof(DomainLocation) + clip_outputs.capacity() * sizeof(ClipVertex<N>);
  }
};

}  // namespace detail

class Device {
 public:
  explicit Device(DeviceOptions options = {});
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  int threads() const { return threads_; }
  const DeviceOptions& options() const { return options_; }
  // Sets (or, with an empty function, removes) the progress hook of the draws that follow.
  void set_progress(DrawProgress progress) { progress_ = std::move(progress); }
  // Records the patch draws that follow into `trace` (draw_trace.h), or, with nullptr, stops. The trace
  // must outlive those draws.
  void set_trace(DrawTrace* trace) { trace_ = trace; }
  // The arena the device's work runs in (stream_output.h runs there too).
  tbb::task_arena& arena() const { return *arena_; }

  // Clears the colour and depth buffers as Framebuffer::clear does. A multisampled target is cleared
  // tile by tile when needed (Framebuffer::clear_by_tiles, in this device's tiles): the draws write each
  // tile's clear as they enter it, resolve() writes the tiles they did not enter from the clear values,
  // and finish_clear writes what is left. A single-sampled one is cleared at once, in bands of rows.
  void clear(Framebuffer& fb, glm::vec4 color, float depth);
  // Writes fb's pending clear, if any, on the device's threads (tile by tile).
  void finish_clear(Framebuffer& fb);
  // Framebuffer::resolve into `out` (single-sampled, of fb's size and format) on the device's threads
  // (bands of rows); the same bytes. A clear pending on `out` is dropped where every pixel is written
  // (both planes), else written first (its depth stays).
  void resolve(const Framebuffer& fb, Framebuffer& out, ResolvedPlanes planes = ResolvedPlanes::color_and_depth);

  template <class Vertex, class Vs, class Hs, class Ds, class Ps>
  DrawResult draw(const PatchDraw<Vertex, Vs, Hs, Ds, Ps>& d, Framebuffer& fb);

  template <class Vertex, class Vs, class Ps>
  DrawResult draw(const MeshDraw<Vertex, Vs, Ps>& d, Framebuffer& fb);

 private:
  // Storage the device keeps from draw to draw, one object per type: the chunk slots
  // (std::vector<ChunkBuffer<N>>), each thread's patch scratch (pattern cache, DS buffers) and the
  // front end's window storage (front_end.h). Made per draw, a chunk's half megabyte of primitive
  // storage was mapped and faulted in again every frame (7 % of a factor-8 frame), every thread
  // faulted its DS buffers in and tessellated its patterns again, and one thread zero-filled the
  // window's HS outputs while the others waited.
  template <class T>
  T& kept() {
    std::shared_ptr<void>& object = kept_[std::type_index(typeid(T))];
    if (!object) object = std::make_shared<T>();
    return *static_cast<T*>(object.get());
  }

  // A clear pending in another grid's tiles is written whole before a draw, which prepares its own
  // tiles only.
  void finish_foreign_clear(Framebuffer& fb) {
    if (fb.pending_clear_tile_size() != 0 && fb.pending_clear_tile_size() != options_.tile_size) finish_clear(fb);
  }

  DeviceOptions options_;
  DrawProgress progress_;
  DrawTrace* trace_ = nullptr;
  int threads_ = 1;
  std::mutex draw_mutex_;                                     // one draw at a time: they share the slots
  std::map<std::type_index, std::shared_ptr<void>> kept_;     // kept(), by type
  std::unique_ptr<tbb::global_control> worker_limit_;         // only when threads_ exceeds the default limit
  std::unique_ptr<tbb::task_arena> arena_;
};

template <class Vertex, class Vs, class Hs, class Ds, class Ps>
DrawResult Device::draw(const PatchDraw<Vertex, Vs, Hs, Ds, Ps>& d, Framebuffer& fb) {
  using FrontEnd = detail::PatchFrontEnd<Vertex, Vs, Hs>;
  using ControlPoint = typename FrontEnd::ControlPoint;
  using PatchConstants = typename FrontEnd::PatchConstants;
  using DsOut = decltype(d.ds(std::declval<const PatchConstants&>(), std::span<const ControlPoint>(), DomainLocation{},
                              std::uint32_t{0}));
  static_assert(is_clip_vertex<DsOut>::value, "the domain shader must return ClipVertex<N>");
  constexpr std::size_t N = is_clip_vertex<DsOut>::attribute_count;

  DrawResult result;
  if (auto e = validate_viewport(d.viewport, fb); !e.empty()) return {e, {}};
  if (auto e = validate_patch_draw(d.indices.size(), d.control_points, d.tessellator); !e.empty()) return {e, {}};
  const auto draw_start = detail::Clock::now();
  DrawReport& report = result.report;
  const TessellatorState tstate = d.tessellator;

  const std::lock_guard<std::mutex> one_draw(draw_mutex_);
  finish_foreign_clear(fb);
  detail::arena_execute(*arena_, [&] {
    const SetupContext setup =
        make_setup_context(d.viewport, d.rasterizer, fb.width(), fb.height(), options_.tile_size, fb.samples());
    detail::Backend<N, Ps> backend(setup, d.depth, d.ps, fb, kept<std::vector<ChunkBuffer<N>>>(),
                                   options_.chunks_in_flight, options_.rounds_in_flight, trace_);
    tbb::enumerable_thread_specific<detail::PatchScratch<N>>& scratch =
        kept<tbb::enumerable_thread_specific<detail::PatchScratch<N>>>();
    for (auto& s : scratch) s.patterns.reset_counters();  // the report counts this draw's hits and misses
    const bool culls_an_orientation = rasterizer_culls(setup, 1) || rasterizer_culls(setup, -1);
    // A window's last chunk per worker, in quarters (cut_chunks): less left for few workers at its end.
    // The cut does not change what is drawn (chunks are cut and drawn in draw order).
    const std::size_t tail_primitives = threads_ > 1 ? std::size_t(threads_) * options_.chunk_primitives : 0;
    FrontEnd front(d.vertices, d.indices, d.control_points, d.vs, d.hs, tstate, options_.window_patches,
                   options_.chunk_primitives, &kept<typename FrontEnd::Storage>(), trace_, tail_primitives);
    std::size_t scratch_bytes_peak = 0;

    // A patch through the DS (in its batch form when it has one) and setup_vertex, then its primitives
    // through setup into the chunk.
    const auto patch_to_chunk = [&](const typename FrontEnd::Work& w, detail::PatchScratch<N>& local,
                                    ChunkBuffer<N>& chunk) {
      const ts::Pattern& pattern = w.pattern;
      if constexpr (detail::HasOrientationBound<PatchConstants>) {
        // Back-patch culling (patch_orientation.h): the pattern's shape is computed only for a bound
        // that can hold, on a draw whose rasterizer culls one orientation.
        const OrientationBound& bound = w.constants.orientation;
        if (culls_an_orientation && bound.may_hold()) {
          const auto start = detail::Clock::now();
          const ts::PatternShape& shape = local.patterns.shape(pattern);
          const bool away = bound.holds(shape) && rasterizer_culls(setup, pattern_screen_sign(bound, shape));
          chunk.times.tessellator += detail::seconds_since(start);
          if (away) {
            ++chunk.patches_back_culled;
            return;
          }
        }
      }
      // The orientation test above is the tessellator's time, not the DS's (so that the stages' times
      // add up to at most the threads' time).
      const auto start = detail::Clock::now();
      auto& outs = local.domain_outputs;
      outs.resize(pattern.points.size());
      if constexpr (BatchDomainShader<Ds, PatchConstants, ControlPoint, N>) {
        auto& locations = local.locations;
        auto& clips = local.clip_outputs;
        locations.resize(pattern.points.size());
        clips.resize(pattern.points.size());
        for (std::size_t i = 0; i < pattern.points.size(); ++i)
          locations[i] = detail::domain_location(pattern.points[i], tstate.domain);
        d.ds(w.constants, w.control_points, std::span<const DomainLocation>(locations), w.patch_id,
             std::span<ClipVertex<N>>(clips));
        make_setup_vertices<N>(setup, std::span<const ClipVertex<N>>(clips), std::span<SetupVertex<N>>(outs));
      } else {
        for (std::size_t i = 0; i < pattern.points.size(); ++i)
          outs[i] =
              make_setup_vertex<N>(setup, d.ds(w.constants, w.control_points,
                                               detail::domain_location(pattern.points[i], tstate.domain), w.patch_id));
      }
      chunk.statistics.DSInvocations += pattern.points.size();
      const auto ds_done = detail::Clock::now();
      chunk.times.ds += std::chrono::duration<double>(ds_done - start).count();
      const auto& idx = pattern.indices;
      switch (pattern.output) {
        case ts::OutputPrimitive::triangle_cw:
        case ts::OutputPrimitive::triangle_ccw:
          setup_triangle_list<N>(setup, chunk, outs.data(), outs.size(), idx.data(), idx.size() / 3, w.patch_id, 0);
          break;
        case ts::OutputPrimitive::line:
          for (std::size_t i = 0; i + 1 < idx.size(); i += 2)
            setup_line<N>(setup, chunk, outs[idx[i]], outs[idx[i + 1]], w.patch_id);
          break;
        case ts::OutputPrimitive::point:
          for (std::uint32_t i : idx) setup_point<N>(setup, chunk, outs[i], w.patch_id);
          break;
      }
      chunk.times.setup += detail::seconds_since(ds_done);
    };

    front.run(report, [&] {
      backend.run(
          front.chunk_count(),
          [&](std::size_t c, ChunkBuffer<N>& chunk) {
            auto& local = scratch.local();
            front.for_each_patch(c, local.patterns, chunk.times.tessellator,
                                 [&](const typename FrontEnd::Work& w) { patch_to_chunk(w, local, chunk); });
          },
          report,
          [&](std::size_t chunks_done) {
            if (progress_) progress_(front.patches_through_chunk(chunks_done - 1), front.patch_count());
          });
      std::size_t bytes = 0;
      for (const auto& s : scratch) bytes += s.bytes();
      scratch_bytes_peak = std::max(scratch_bytes_peak, bytes);
    });
    for (const auto& s : scratch) detail::add_pattern_cache(report.memory, s.patterns);
    report.memory.geometry_peak_bytes = front.window_bytes_peak() + scratch_bytes_peak + backend.chunk_bytes_peak();
  });
  report.memory.framebuffer_bytes = fb.bytes();
  report.times.wall = detail::seconds_since(draw_start);
  return result;
}

template <class Vertex, class Vs, class Ps>
DrawResult Device::draw(const MeshDraw<Vertex, Vs, Ps>& d, Framebuffer& fb) {
  using VsOut = vs_output_t<Vs, Vertex>;
  static_assert(is_clip_vertex<VsOut>::value, "a mesh draw's vertex shader must return ClipVertex<N>");
  constexpr std::size_t N = is_clip_vertex<VsOut>::attribute_count;

  DrawResult result;
  if (auto e = validate_viewport(d.viewport, fb); !e.empty()) return {e, {}};
  if (d.indices.size() % 3 != 0)
    return {"triangle list has " + std::to_string(d.indices.size()) + " indices, not a multiple of 3", {}};
  const auto draw_start = detail::Clock::now();
  DrawReport& report = result.report;
  const std::size_t triangle_count = d.indices.size() / 3;

  const std::lock_guard<std::mutex> one_draw(draw_mutex_);
  finish_foreign_clear(fb);
  detail::arena_execute(*arena_, [&] {
    const SetupContext setup =
        make_setup_context(d.viewport, d.rasterizer, fb.width(), fb.height(), options_.tile_size, fb.samples());
    detail::Backend<N, Ps> backend(setup, d.depth, d.ps, fb, kept<std::vector<ChunkBuffer<N>>>(),
                                   options_.chunks_in_flight, options_.rounds_in_flight, trace_);
    detail::VertexCache vcache;
    std::vector<VsOut> vs_out;
    std::vector<SetupVertex<N>> setup_vertices;
    std::vector<std::uint32_t> cost;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> chunks;
    const std::size_t window = std::size_t(std::max(1, options_.window_patches)) * 4;
    std::size_t window_bytes_peak = 0;
    for (std::size_t first = 0; first < triangle_count; first += window) {
      const std::size_t n = std::min(window, triangle_count - first);
      const auto indices = d.indices.subspan(first * 3, n * 3);
      detail::assemble_and_shade_vertices(d.vs, d.vertices, indices, n, vcache, vs_out, report);
      const auto t0 = detail::Clock::now();
      setup_vertices.resize(vs_out.size());
      detail::parallel_for(tbb::blocked_range<std::size_t>(0, vs_out.size(), 1024), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) setup_vertices[i] = make_setup_vertex<N>(setup, vs_out[i]);
      });
      report.times.setup += detail::seconds_since(t0);
      cost.assign(n, 1);
      detail::cut_chunks(cost, options_.chunk_primitives, options_.chunk_primitives, chunks);
      backend.run(
          chunks.size(),
          [&](std::size_t c, ChunkBuffer<N>& chunk) {
            const auto start = detail::Clock::now();
            const auto [begin, end] = chunks[c];
            setup_triangle_list<N>(backend.setup(), chunk, setup_vertices.data(), setup_vertices.size(),
                                   vcache.slots.data() + std::size_t(begin) * 3, end - begin,
                                   static_cast<std::uint32_t>(first + begin), 1);
            chunk.times.setup += detail::seconds_since(start);
          },
          report);
      window_bytes_peak = std::max(window_bytes_peak, vcache.bytes() + vs_out.capacity() * sizeof(VsOut) +
                                                          setup_vertices.capacity() * sizeof(SetupVertex<N>) +
                                                          cost.capacity() * sizeof(std::uint32_t));
    }
    report.memory.geometry_peak_bytes = window_bytes_peak + backend.chunk_bytes_peak();
  });
  report.memory.framebuffer_bytes = fb.bytes();
  report.times.wall = detail::seconds_since(draw_start);
  return result;
}

}  // namespace tessera
