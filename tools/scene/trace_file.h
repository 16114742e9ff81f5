// A DrawTrace (pipeline/draw_trace.h) as a file a timeline viewer opens: the Chrome trace event format
// (JSON, "X" complete events, microseconds), read by Perfetto (ui.perfetto.dev) and chrome://tracing.
// One row per worker; each span named by its stage, with its round, chunk or tile in `args`.
#pragma once

#include <string>

#include "pipeline/draw_trace.h"
#include "tools/scene/json_output.h"

namespace tessera::scene {

// The trace as Chrome trace event JSON; `label` names the process row (the scene, its thread count).
Json trace_event_json(const DrawTrace& trace, const std::string& label);
// Writes trace_event_json to `path` atomically; throws InputError naming the path on failure.
void write_trace_file(const DrawTrace& trace, const std::string& label, const std::string& path);
// The summary's numbers in seconds: {"wall_s", "busy_s", "workers", "busy", "first_tile_s",
// "after_last_chunk_s"}.
Json to_json(const TraceSummary& s);
// One line: wall, busy share, and the wall time before the first tile and after the last chunk.
std::string summary_line(const TraceSummary& s);

}  // namespace tessera::scene
