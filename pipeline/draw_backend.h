// The device's back end: chunk slots, and the schedule (tile_schedule.h) that produces them and
// rasterizes their tiles in draw order; and each worker's scratch for a patch's domain points.
//
// Contract
// - Backend::run produces chunks [0, count) in rounds and rasterizes every tile's primitives in draw
//   order (rounds, then chunks within a round, then primitives within a chunk), whatever the thread
//   count: the framebuffer bytes and the statistics are the same for any number of workers.
// - The slots are the device's (Device::kept), reused from draw to draw: their storage outlives the
//   draw, and chunk memory is rounds x chunks per round chunk buffers, not a function of the factor.
// - Runs inside the device's arena; one Backend per draw, used by the drawing thread only (its workers
//   run inside run()).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include "pipeline/draw_trace.h"
#include "pipeline/framebuffer.h"
#include "pipeline/front_end.h"
#include "pipeline/pattern_cache.h"
#include "pipeline/pipeline_state.h"
#include "pipeline/primitive_setup.h"
#include "pipeline/raster_tile.h"
#include "pipeline/stage_io.h"
#include "pipeline/statistics.h"
#include "pipeline/tile_schedule.h"

namespace tessera::detail {

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

}  // namespace tessera::detail
