// A timeline of a device's work: which worker ran which part of a draw, from when to when. For seeing
// where a frame's wall time goes at many threads (workers idle while a round's heaviest tile finishes,
// the rasterizer waiting for the first round, the last tiles alone), which the per-stage thread times
// of DrawReport cannot show.
//
// Contract
// - A Device records into a DrawTrace only while one is set (Device::set_trace); otherwise a span
//   costs one pointer test. Recording one costs two clock reads and a push onto the calling thread's
//   own list: no lock, nothing shared written.
// - Tracing changes no pixel and no statistic: it only reads the clock around work already done.
// - events() may be called only while no draw records into the trace.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

namespace tessera {

// What a span covers. The names (to_string) are the ones a trace viewer shows.
enum class TraceStage : std::uint8_t {
  vertex_shader,  // IA and the VS of a window (on the drawing thread; the VS forks inside it)
  hull_shader,    // both HS phases and factor processing for a range of a window's patches
  chunk,          // a chunk's patches: tessellator (cache misses), DS and setup, binning. a: round, b: chunk
  tile_lists,     // a round's chunks gathered by tile, once the round is produced. a: round
  tile,           // a tile (or a quarter of one) through its binned primitives. a: tile, b: quarter (0: whole)
};
const char* to_string(TraceStage stage);

struct TraceSpan {
  TraceStage stage;
  int worker;                  // the arena's thread index, 0..threads - 1 (0 also the drawing thread)
  double start_s, end_s;       // seconds since the trace began
  std::uint32_t a = 0, b = 0;  // as TraceStage says
};

// Wall time against the workers' busy time, from a trace's spans.
struct TraceSummary {
  double wall_s = 0;              // first span's start to last span's end
  double busy_s = 0;              // the spans' summed durations (thread-seconds)
  int workers = 0;                // distinct worker indices seen
  double first_tile_s = 0;        // wall time before the first tile was rasterized (front end, first round)
  double after_last_chunk_s = 0;  // wall time after the last chunk was produced (raster alone)
  double busy_fraction() const { return wall_s > 0 && workers > 0 ? busy_s / (wall_s * workers) : 0.0; }
};

class DrawTrace {
 public:
  using Clock = std::chrono::steady_clock;
  DrawTrace() : origin_(Clock::now()) {}
  DrawTrace(const DrawTrace&) = delete;
  DrawTrace& operator=(const DrawTrace&) = delete;

  void record(TraceStage stage, int worker, Clock::time_point start, Clock::time_point end, std::uint32_t a = 0,
              std::uint32_t b = 0) {
    spans_.local().push_back({stage, worker, seconds(start), seconds(end), a, b});
  }
  // Every span recorded, by start time (then worker).
  std::vector<TraceSpan> spans() const;
  TraceSummary summary() const;

 private:
  double seconds(Clock::time_point t) const { return std::chrono::duration<double>(t - origin_).count(); }
  Clock::time_point origin_;
  tbb::enumerable_thread_specific<std::vector<TraceSpan>> spans_;
};

// The calling worker's index in the current arena (0 outside one).
int trace_worker();

}  // namespace tessera
