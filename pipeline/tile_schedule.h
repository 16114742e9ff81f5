// The back end's schedule: a draw's chunks produced (DS, setup, binning) and its tiles rasterized by
// one pool of workers, with no barrier between rounds of chunks. A tile waits only for the rounds
// that hold its primitives and for its own earlier work; a round's storage is reused once every tile
// it touches has rasterized it.
//
// Why not a barrier per round (a flush of each round's tiles, one flush at a time): a round of chunks
// in draw order covers one region of the model, often a few dozen tiles, and its flush lasted as long
// as its heaviest tile while the other workers, out of rounds to produce, waited (the screen-LOD
// displaced frog at 16 threads: flushes of 18-28 tiles, 11 % of the frame idle; the uniform one, three
// rounds produced at once, then rasterized with nothing to overlap).
//
// Contract
// - Chunks are handed out in draw order (chunk c is taken after every chunk before it; two workers'
//   produce() calls may begin in either order), each once, in rounds (round_starts): `per_round`
//   chunks, except that the last rounds halve, down to `smallest`, so that the raster left after the
//   last chunk is small. Each chunk takes a free slot of `slots` (chunk storage); a round's slots are
//   freed when it is consumed. Round r's tile lists use list storage r % lists: no chunk of round
//   r + lists is taken before consumed(r) has returned. produce(chunk, round, slot) is given the
//   chunk's round and slot.
// - list_tiles(r, slots) runs once, after the chunks of round r are produced (`slots`: theirs, in
//   chunk order), and returns the round's busy tiles (valid until consumed(r)).
// - Each tile rasterizes its rounds in round order: rasterize(tile, rounds, quarter) gets rounds in
//   increasing order, all produced and listed, none of them given to that tile before. One call per
//   tile runs at a time, except the four quarters (1..4) of a split tile, which cover disjoint pixels.
//   So each pixel sees its primitives in draw order, whatever the thread count.
// - Callbacks may fork and wait (each runs isolated: its thread then takes only its own tasks).
// - consumed(r, slots) runs once every tile of round r is rasterized, before its slots are freed;
//   finished(r, end) runs for
//   r = 0, 1, ... in order, after consumed(r), with `end` the chunk after the round's last. Both under
//   the schedule's lock: one call at a time.
// - Splitting: once every chunk is produced (nothing else can run beside the raster), a tile holding
//   more than half a worker's share of the primitives pending then is rasterized as four quarters, each
//   by any worker; before its quarters, prepare(tile) runs once. With one worker, never.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <limits>
#include <mutex>
#include <span>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>

#include "pipeline/parallel.h"

namespace tessera::detail {

struct TileLoad {
  std::uint32_t tile = 0;
  std::uint32_t load = 0;  // primitives binned to the tile in the round (the rasterizer's work)
};

// Round r holds chunks [first[r], first[r + 1]): `per_round` each, then, from where fewer than two
// full rounds are left, half of what is left each round (at least `smallest`, at most `per_round`).
// Why: the tiles of the last round are rasterized with nothing left to overlap them (torus F16 on 16
// threads: 1.8 ms of a 10.8 ms frame after its last chunk, a quarter of the frame's raster work).
inline std::vector<std::size_t> round_starts(std::size_t chunks, std::size_t per_round, std::size_t smallest) {
  per_round = std::max<std::size_t>(per_round, 1);
  smallest = std::clamp<std::size_t>(smallest, 1, per_round);
  std::vector<std::size_t> first{0};
  for (std::size_t c = 0; c < chunks;) {
    const std::size_t left = chunks - c;
    const std::size_t n = left >= 2 * per_round ? per_round : std::clamp((left + 1) / 2, smallest, per_round);
    c += std::min(n, left);
    first.push_back(c);
  }
  return first;
}

struct ScheduleShape {
  std::size_t chunks = 0;     // the draw's (window's) chunks
  std::size_t per_round = 1;  // chunks per round
  std::size_t smallest = 1;   // the last rounds' smallest size
  std::size_t slots = 2;      // chunk storage (at least per_round; 2 x per_round lets rounds overlap)
  std::size_t lists = 2;      // rounds whose tile lists exist at once
  std::size_t tiles = 0;      // the screen's tiles
  int workers = 1;
  bool can_split = false;  // tiles may be rasterized as quarters (an even tile size, several workers)
};

template <class Produce, class ListTiles, class Prepare, class Rasterize, class Consumed, class Finished>
class TileSchedule {
 public:
  TileSchedule(const ScheduleShape& shape, Produce& produce, ListTiles& list_tiles, Prepare& prepare,
               Rasterize& rasterize, Consumed& consumed, Finished& finished)
      : s_(shape),
        produce_(produce),
        list_tiles_(list_tiles),
        prepare_(prepare),
        rasterize_(rasterize),
        consumed_(consumed),
        finished_(finished) {
    // A round never needs more slots than exist: only the round being handed out can be incomplete,
    // and every earlier one is consumed in time, freeing its slots.
    s_.per_round = std::max<std::size_t>(s_.per_round, 1);
    s_.lists = std::max<std::size_t>(s_.lists, 1);
    s_.slots = std::max<std::size_t>(s_.slots, s_.per_round);
    free_slots_.resize(s_.slots);
    for (std::size_t i = 0; i < s_.slots; ++i) free_slots_[i] = std::uint32_t(s_.slots - 1 - i);  // slot 0 first
    chunk_slot_.resize(s_.chunks);
    first_ = round_starts(s_.chunks, s_.per_round, s_.smallest);
    rounds_ = first_.size() - 1;
    unproduced_.resize(rounds_);
    for (std::size_t r = 0; r < rounds_; ++r) unproduced_[r] = chunks_of(r);
    listed_.assign(rounds_, 0);
    done_.assign(rounds_, 0);
    lists_.resize(rounds_);
    units_left_.assign(rounds_, 0);
    tiles_.assign(s_.tiles, TileState{});
  }

  // Runs the schedule on `workers` workers of the current arena; returns when every round is finished.
  void run() {
    if (rounds_ == 0) return;
    const std::size_t workers = std::size_t(std::max(1, s_.workers));
    // Qualified: an unqualified call would find oneTBB's own (more constrained) parallel_for by ADL, without
    // the edges parallel.h states for ThreadSanitizer.
    detail::parallel_for(tbb::blocked_range<std::size_t>(0, workers, 1), [&](const auto& range) {
      for (std::size_t w = range.begin(); w != range.end(); ++w) work();
    });
  }

  std::uint64_t tiles_split() const { return tiles_split_; }

 private:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  struct TileState {
    std::uint32_t head = kNone, tail = kNone;  // its pending rounds: a list through nodes_
    std::uint64_t pending_load = 0;
    bool active = false;  // queued in ready_ or being rasterized
  };
  struct Node {
    std::uint32_t round, next;
  };
  struct Ready {  // a tile (or a quarter of one) ready to rasterize; the smallest key goes first
    std::uint64_t major, minor;
    std::uint32_t tile;
    std::uint32_t split;   // for a quarter: its entry in splits_
    std::uint8_t quarter;  // 0: the whole tile with its pending rounds
  };
  struct Split {
    std::vector<std::uint32_t> rounds;
    int left = 0;
  };
  static bool later(const Ready& a, const Ready& b) {
    return a.major != b.major ? a.major > b.major : a.minor > b.minor;
  }

  // Runs a callback so that, if it forks and waits, its thread takes only the callback's own tasks:
  // not another worker's loop of this schedule, which would hold the thread (and the callback's
  // unfinished work, on its stack) until the whole schedule ended, a deadlock.
  template <class F>
  static decltype(auto) isolated(F&& f) {
    return tbb::this_task_arena::isolate(std::forward<F>(f));
  }

  std::size_t chunks_of(std::size_t r) const { return first_[r + 1] - first_[r]; }

  // Ordering: while chunks are still produced, the oldest pending round first (its storage is what
  // production waits for), heaviest first within it; once every chunk is produced, the tile with the
  // most primitives left first (the frame ends when its last tile does). Quarters go before either.
  Ready ready_entry(std::uint32_t t) const {
    const TileState& ts = tiles_[t];
    const std::uint64_t heavier_first = ~ts.pending_load;
    if (draining_) return {1, heavier_first, t, 0, 0};
    return {1 + std::uint64_t(nodes_[ts.head].round), heavier_first, t, 0, 0};
  }
  void push_ready(const Ready& r) {
    ready_.push_back(r);
    std::push_heap(ready_.begin(), ready_.end(), later);
    news_ = true;
  }
  Ready pop_ready() {
    std::pop_heap(ready_.begin(), ready_.end(), later);
    const Ready r = ready_.back();
    ready_.pop_back();
    return r;
  }

  // A chunk of round r may start: a slot is free, and so is the round's list storage.
  bool may_start(std::size_t r) const { return !free_slots_.empty() && (r < s_.lists || done_[r - s_.lists]); }
  std::span<const std::uint32_t> slots_of(std::size_t r) const {
    return std::span<const std::uint32_t>(chunk_slot_.data() + first_[r], chunks_of(r));
  }

  // Rounds listed in order become pending on their tiles.
  void publish() {
    while (published_ < rounds_ && listed_[published_]) {
      const std::size_t r = published_++;
      units_left_[r] = lists_[r].size();
      for (const TileLoad& tl : lists_[r]) {
        TileState& ts = tiles_[tl.tile];
        std::uint32_t n;
        if (free_node_ != kNone) {
          n = free_node_;
          free_node_ = nodes_[n].next;
        } else {
          n = std::uint32_t(nodes_.size());
          nodes_.push_back({});
        }
        nodes_[n] = {std::uint32_t(r), kNone};
        (ts.tail == kNone ? ts.head : nodes_[ts.tail].next) = n;
        ts.tail = n;
        ts.pending_load += tl.load;
        remaining_load_ += tl.load;
        if (!ts.active) {
          ts.active = true;
          push_ready(ready_entry(tl.tile));
        }
      }
      if (units_left_[r] == 0) round_done(r);
    }
    if (published_ == rounds_ && !draining_) {
      draining_ = true;
      split_above_ = remaining_load_ / (2 * std::uint64_t(std::max(1, s_.workers)));
      for (Ready& e : ready_)
        if (e.quarter == 0) e = ready_entry(e.tile);
      std::make_heap(ready_.begin(), ready_.end(), later);
    }
  }

  void round_done(std::size_t r) {
    isolated([&] { consumed_(r, slots_of(r)); });
    for (const std::uint32_t slot : slots_of(r)) free_slots_.push_back(slot);
    done_[r] = 1;
    news_ = true;  // its slots and list storage may take the next chunks
    for (; finished_count_ < rounds_ && done_[finished_count_]; ++finished_count_)
      isolated([&] { finished_(finished_count_, first_[finished_count_ + 1]); });
  }

  // The tile's rounds are rasterized: each round may be done; the tile goes back to the queue if more
  // rounds arrived meanwhile.
  void tile_done(std::uint32_t t, std::span<const std::uint32_t> rounds) {
    for (const std::uint32_t r : rounds)
      if (--units_left_[r] == 0) round_done(r);
    TileState& ts = tiles_[t];
    if (ts.head != kNone)
      push_ready(ready_entry(t));
    else
      ts.active = false;
  }

  // Ends a change under the lock: if work became available (or the schedule ended), workers spinning
  // see the epoch move, and sleeping ones are woken.
  void wake() {
    if (!news_) return;
    news_ = false;
    epoch_.fetch_add(1, std::memory_order_release);
    if (sleeping_ > 0) wakeup_.notify_all();
  }

  // Waits, the lock held on entry and on return, until the epoch moves past `seen`. A worker first
  // spins unlocked for a while (work usually arrives within a tile's or a chunk's time, and a sleep and
  // wake-up costs more than that), then sleeps.
  void wait_for_news(std::unique_lock<std::mutex>& lock) {
    const std::uint64_t seen = epoch_.load(std::memory_order_relaxed);
    lock.unlock();
    for (int i = 0; i < kSpins && epoch_.load(std::memory_order_acquire) == seen; ++i) spin_pause();
    lock.lock();
    ++sleeping_;
    while (epoch_.load(std::memory_order_relaxed) == seen) wakeup_.wait(lock);
    --sleeping_;
  }
  static void spin_pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  // About 10-50 microseconds of pause instructions before a worker sleeps: long enough to catch work
  // that appears within a round, short enough not to hold a core (docs/performance.md).
  static constexpr int kSpins = 2000;

  void work() {
    std::vector<std::uint32_t> rounds;  // the tile's rounds taken from its list
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      if (!ready_.empty()) {
        const Ready item = pop_ready();
        if (item.quarter != 0) {
          Split& sp = splits_[item.split];
          lock.unlock();
          isolated([&] { rasterize_(item.tile, std::span<const std::uint32_t>(sp.rounds), item.quarter); });
          lock.lock();
          if (--sp.left == 0) {
            tile_done(item.tile, sp.rounds);
            free_splits_.push_back(item.split);
            wake();
          }
          continue;
        }
        TileState& ts = tiles_[item.tile];
        rounds.clear();
        for (std::uint32_t n = ts.head; n != kNone;) {
          rounds.push_back(nodes_[n].round);
          const std::uint32_t next = nodes_[n].next;
          nodes_[n].next = free_node_;
          free_node_ = n;
          n = next;
        }
        ts.head = ts.tail = kNone;
        const std::uint64_t load = ts.pending_load;
        ts.pending_load = 0;
        remaining_load_ -= load;
        if (draining_ && s_.can_split && s_.workers > 1 && load > split_above_) {
          std::uint32_t id;
          if (!free_splits_.empty()) {
            id = free_splits_.back();
            free_splits_.pop_back();
          } else {
            id = std::uint32_t(splits_.size());
            splits_.emplace_back();
          }
          splits_[id].rounds = rounds;
          splits_[id].left = 4;
          ++tiles_split_;
          lock.unlock();
          isolated([&] { prepare_(item.tile); });  // before its quarters, which may run at once
          lock.lock();
          for (std::uint8_t q = 1; q <= 4; ++q) push_ready({0, 0, item.tile, id, q});
          wake();
          continue;
        }
        lock.unlock();
        isolated([&] { rasterize_(item.tile, std::span<const std::uint32_t>(rounds), 0); });
        lock.lock();
        tile_done(item.tile, rounds);
        wake();
        continue;
      }
      if (next_chunk_ < s_.chunks && may_start(next_round_)) {
        const std::size_t c = next_chunk_++, r = next_round_;
        if (next_chunk_ == first_[r + 1]) ++next_round_;
        const std::uint32_t slot = free_slots_.back();
        free_slots_.pop_back();
        chunk_slot_[c] = slot;
        lock.unlock();
        isolated([&] { produce_(c, r, std::size_t(slot)); });
        lock.lock();
        if (--unproduced_[r] == 0) {
          lock.unlock();
          const std::span<const TileLoad> list = isolated([&] { return list_tiles_(r, slots_of(r)); });
          lock.lock();
          lists_[r] = list;
          listed_[r] = 1;
          publish();
          wake();
        }
        continue;
      }
      if (finished_count_ == rounds_) break;
      wait_for_news(lock);
    }
    news_ = true;  // the last round is finished: every waiting worker leaves
    wake();
  }

  ScheduleShape s_;
  Produce& produce_;
  ListTiles& list_tiles_;
  Prepare& prepare_;
  Rasterize& rasterize_;
  Consumed& consumed_;
  Finished& finished_;
  std::vector<std::size_t> first_;  // round_starts
  std::size_t rounds_ = 0;

  // Guarded by mutex_.
  std::mutex mutex_;
  std::condition_variable wakeup_;
  int sleeping_ = 0;
  bool news_ = false;                    // work became available since the last wake()
  std::atomic<std::uint64_t> epoch_{0};  // moved by wake(); read unlocked by spinning workers
  std::size_t next_chunk_ = 0, next_round_ = 0;  // the next chunk to produce, and its round
  std::vector<std::uint32_t> free_slots_;        // a stack: the most recently freed (cache-warm) first
  std::vector<std::uint32_t> chunk_slot_;        // per chunk
  std::vector<std::size_t> unproduced_;  // per round: chunks not yet produced
  std::vector<char> listed_, done_;
  std::vector<std::span<const TileLoad>> lists_;
  std::vector<std::size_t> units_left_;  // per round: its tiles not yet rasterized
  std::size_t published_ = 0, finished_count_ = 0;
  std::vector<TileState> tiles_;
  std::vector<Node> nodes_;
  std::uint32_t free_node_ = kNone;
  std::vector<Ready> ready_;  // a heap
  std::deque<Split> splits_;  // a deque: a quarter's worker reads its entry unlocked while others add entries
  std::vector<std::uint32_t> free_splits_;
  std::uint64_t remaining_load_ = 0;  // primitives pending on tiles, not yet taken
  bool draining_ = false;             // every round is published: nothing left to produce
  std::uint64_t split_above_ = 0;     // the load over which a tile is split: half a worker's share at the drain's start
  std::uint64_t tiles_split_ = 0;
};

// Runs a TileSchedule (see its contract above) and returns how many tiles were split into quarters.
template <class Produce, class ListTiles, class Prepare, class Rasterize, class Consumed, class Finished>
std::uint64_t run_tile_schedule(const ScheduleShape& shape, Produce&& produce, ListTiles&& list_tiles,
                                Prepare&& prepare, Rasterize&& rasterize, Consumed&& consumed, Finished&& finished) {
  TileSchedule<std::remove_reference_t<Produce>, std::remove_reference_t<ListTiles>, std::remove_reference_t<Prepare>,
               std::remove_reference_t<Rasterize>, std::remove_reference_t<Consumed>, std::remove_reference_t<Finished>>
      schedule(shape, produce, list_tiles, prepare, rasterize, consumed, finished);
  schedule.run();
  return schedule.tiles_split();
}

}  // namespace tessera::detail
