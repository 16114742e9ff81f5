// Fork-join over oneTBB, with the happens-before edges made visible to ThreadSanitizer.
//
// Why: Debian's libtbb is not built with -fsanitize=thread, so TSan cannot see the synchronization
// inside it (task spawning, stealing, the join in wait). Every parallel_for then looks like a race
// between the thread that prepared the data and the worker that reads it. These wrappers state the
// two edges every fork-join has: the caller's writes before the fork happen before each task body,
// and each task body happens before the code after the join. TBB's own header code, inlined into
// our objects, is suppressed separately (tests/tsan.supp). Without TSan the annotations compile away.
#pragma once

#include <cstddef>

#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#if defined(__SANITIZE_THREAD__)
#include <sanitizer/tsan_interface.h>
#endif

namespace tessera::detail {

#if defined(__SANITIZE_THREAD__)
inline void happens_before(void* sync) { __tsan_release(sync); }
inline void happens_after(void* sync) { __tsan_acquire(sync); }
#else
inline void happens_before(void*) {}
inline void happens_after(void*) {}
#endif

template <class Range, class Body>
void parallel_for(const Range& range, const Body& body) {
  // Two distinct addresses serve as TSan's synchronization objects (only the addresses matter).
  char fork = 0, join = 0;
  happens_before(&fork);
  tbb::parallel_for(range, [&](const Range& sub) {
    happens_after(&fork);
    body(sub);
    happens_before(&join);
  });
  happens_after(&join);
}

// task_arena::execute with the same two edges (the functor may run on an arena thread).
template <class F>
void arena_execute(tbb::task_arena& arena, const F& f) {
  char fork = 0, join = 0;
  happens_before(&fork);
  arena.execute([&] {
    happens_after(&fork);
    f();
    happens_before(&join);
  });
  happens_after(&join);
}

// Rounds 0 .. rounds - 1 through two stages without a barrier between rounds: produce(r) runs for up to
// `in_flight` rounds at once (each may fork further), and consume(r) runs after produce(r), in round
// order, one round at a time. Round r + in_flight is not produced before consume(r) has returned, so
// r % in_flight names storage a round may own until it is consumed. Threads that finish their part of
// a round take up the next rounds' production instead of waiting for the round's slowest task.
// The edges TSan cannot see in oneTBB's pipeline are stated: the issue of a round before its
// production, the production before its consumption, and a consumption before the production of the
// round that reuses its storage.
template <class Produce, class Consume>
void pipelined_rounds(std::size_t rounds, std::size_t in_flight, const Produce& produce, const Consume& consume) {
  if (rounds == 0) return;
  std::size_t next = 0;
  char issued = 0, produced = 0, consumed = 0;  // TSan's synchronization objects (only the addresses matter)
  happens_before(&issued);
  tbb::parallel_pipeline(
      in_flight,
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) -> std::size_t {
        happens_after(&issued);
        if (next == rounds) {
          fc.stop();
          return 0;
        }
        const std::size_t r = next++;
        happens_before(&issued);
        return r;
      }) & tbb::make_filter<std::size_t, std::size_t>(tbb::filter_mode::parallel, [&](std::size_t r) {
        happens_after(&issued);
        happens_after(&consumed);
        produce(r);
        happens_before(&produced);
        return r;
      }) & tbb::make_filter<std::size_t, void>(tbb::filter_mode::serial_in_order, [&](std::size_t r) {
        happens_after(&produced);
        happens_after(&consumed);
        consume(r);
        happens_before(&consumed);
      }));
  happens_after(&consumed);
}

}  // namespace tessera::detail
