#include "pipeline/draw_trace.h"

#include <algorithm>
#include <set>

#include <tbb/task_arena.h>

namespace tessera {

const char* to_string(TraceStage stage) {
  switch (stage) {
    case TraceStage::vertex_shader: return "IA+VS";
    case TraceStage::hull_shader: return "HS";
    case TraceStage::chunk: return "chunk";
    case TraceStage::tile_lists: return "tile lists";
    case TraceStage::tile: return "tile";
  }
  return "?";
}

int trace_worker() { return std::max(0, tbb::this_task_arena::current_thread_index()); }

std::vector<TraceSpan> DrawTrace::spans() const {
  std::vector<TraceSpan> all;
  for (const auto& list : spans_) all.insert(all.end(), list.begin(), list.end());
  std::sort(all.begin(), all.end(), [](const TraceSpan& x, const TraceSpan& y) {
    return x.start_s != y.start_s ? x.start_s < y.start_s : x.worker < y.worker;
  });
  return all;
}

TraceSummary DrawTrace::summary() const {
  const std::vector<TraceSpan> all = spans();
  TraceSummary s;
  if (all.empty()) return s;
  double begin = all.front().start_s, end = begin, first_tile = -1, last_chunk = begin;
  std::set<int> workers;
  for (const TraceSpan& x : all) {
    end = std::max(end, x.end_s);
    // The drawing thread's own span (IA+VS) encloses the VS tasks forked inside it: counted as wall
    // time only, so that busy time is not counted twice.
    if (x.stage != TraceStage::vertex_shader) s.busy_s += x.end_s - x.start_s;
    workers.insert(x.worker);
    if (x.stage == TraceStage::tile && first_tile < 0) first_tile = x.start_s;
    if (x.stage == TraceStage::chunk) last_chunk = std::max(last_chunk, x.end_s);
  }
  s.wall_s = end - begin;
  s.workers = int(workers.size());
  s.first_tile_s = (first_tile < 0 ? end : first_tile) - begin;
  s.after_last_chunk_s = end - last_chunk;
  return s;
}

}  // namespace tessera
