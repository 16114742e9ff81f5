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

}  // namespace tessera::detail
