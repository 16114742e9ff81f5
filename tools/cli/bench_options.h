// The options every `bench` scene shares, one definition each so that their ranges, help and defaults
// cannot drift apart: the device options (--tile-size, --chunks-in-flight, --rounds-in-flight),
// --msaa and --trace. Out-of-range device values are usage errors (the device would clamp them silently; a
// benchmark runs what it was asked); --msaa is checked where the target is made.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "pipeline/device.h"
#include "pipeline/draw_trace.h"
#include "tools/scene/common.h"
#include "tools/scene/trace_file.h"

namespace tessera::cli {

struct BenchDeviceOptions {
  int tile_size = DeviceOptions{}.tile_size;
  int chunks_in_flight = 0;  // 0: the device's default
  int rounds_in_flight = 0;  // 0: the device's default

  void add_options(CLI::App& cmd) {
    cmd.add_option("--tile-size", tile_size, "screen tile size in pixels (even, 8..1024)")->capture_default_str();
    cmd.add_option("--chunks-in-flight", chunks_in_flight,
                   "chunks produced per round, 0 = the device's default (4 x threads, at least 4)")
        ->capture_default_str();
    cmd.add_option("--rounds-in-flight", rounds_in_flight,
                   "chunk buffers in rounds' worth: the chunks in flight share rounds x chunks-in-flight "
                   "buffers, 0 = the device's default (2 on up to two threads, else 3)")
        ->capture_default_str();
  }
  // Checks the values (UsageError naming the option) and sets them on `o`.
  void apply(DeviceOptions& o) const {
    if (tile_size < 8 || tile_size > 1024 || tile_size % 2 != 0)
      throw scene::UsageError("--tile-size: " + std::to_string(tile_size) + " is not an even size in 8..1024");
    if (chunks_in_flight < 0 || chunks_in_flight > 4096)
      throw scene::UsageError("--chunks-in-flight: " + std::to_string(chunks_in_flight) + " is not in 0..4096");
    if (rounds_in_flight != 0 && (rounds_in_flight < 2 || rounds_in_flight > 64))
      throw scene::UsageError("--rounds-in-flight: " + std::to_string(rounds_in_flight) + " is not 0 or in 2..64");
    o.tile_size = tile_size;
    o.chunks_in_flight = chunks_in_flight;
    o.rounds_in_flight = rounds_in_flight;
  }
};

// --msaa for a benchmark whose timed frame ends with its colour's resolve.
inline void add_bench_msaa_option(CLI::App& cmd, int& msaa) {
  cmd.add_option("--msaa", msaa, "samples per pixel: 1, 2, 4, 8 or 16 (the timed frame includes its colour's resolve)")
      ->capture_default_str();
}

// --trace FILE: a timeline of one more frame, after the timed ones (which it does not disturb).
inline void add_bench_trace_option(CLI::App& cmd, std::string& path) {
  cmd.add_option("--trace", path,
                 "after the timed frames, draw one more and write its timeline (which worker ran which chunk and "
                 "tile, when) as Chrome trace JSON, for ui.perfetto.dev or chrome://tracing");
}

// Runs frame() once with `device` recording its draws, writes the timeline to `path` (labelled
// `label`) and returns its summary.
template <class Frame>
TraceSummary trace_frame(Device& device, const Frame& frame, const std::string& path, const std::string& label) {
  DrawTrace trace;
  {
    struct Recording {  // the device stops recording however frame() ends
      Device& device;
      ~Recording() { device.set_trace(nullptr); }
    } recording{device};
    device.set_trace(&trace);
    frame();
  }
  scene::write_trace_file(trace, label, path);
  return trace.summary();
}

}  // namespace tessera::cli
