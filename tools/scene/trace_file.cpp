#include "tools/scene/trace_file.h"

#include <cstdio>

#include "tools/scene/common.h"

namespace tessera::scene {

Json trace_event_json(const DrawTrace& trace, const std::string& label) {
  Json events = Json::array();
  events.push_back({{"name", "process_name"}, {"ph", "M"}, {"pid", 1}, {"args", {{"name", label}}}});
  for (const TraceSpan& s : trace.spans()) {
    Json args = Json::object();
    switch (s.stage) {
      case TraceStage::vertex_shader: break;
      case TraceStage::hull_shader: args = {{"first_patch", s.a}, {"end_patch", s.b}}; break;
      case TraceStage::chunk: args = {{"round", s.a}, {"chunk", s.b}}; break;
      case TraceStage::tile_lists: args = {{"round", s.a}}; break;
      case TraceStage::tile: args = {{"tile", s.a}, {"quarter", s.b}}; break;
    }
    // Microseconds, as the format counts them; the viewer places each span on its worker's row.
    events.push_back({{"name", to_string(s.stage)},
                      {"ph", "X"},
                      {"pid", 1},
                      {"tid", s.worker},
                      {"ts", s.start_s * 1e6},
                      {"dur", (s.end_s - s.start_s) * 1e6},
                      {"args", args}});
  }
  return {{"displayTimeUnit", "ms"}, {"traceEvents", events}};
}

void write_trace_file(const DrawTrace& trace, const std::string& label, const std::string& path) {
  write_text_atomically(path, json_text(trace_event_json(trace, label)) + "\n");
}

Json to_json(const TraceSummary& s) {
  return {{"wall_s", s.wall_s},
          {"busy_s", s.busy_s},
          {"workers", s.workers},
          {"busy", s.busy_fraction()},
          {"first_tile_s", s.first_tile_s},
          {"after_last_chunk_s", s.after_last_chunk_s}};
}

std::string summary_line(const TraceSummary& s) {
  char line[300];
  std::snprintf(line, sizeof line,
                "traced draw: %.2f ms on %d workers, %.0f %% busy; %.2f ms before the first tile, "
                "%.2f ms after the last chunk",
                s.wall_s * 1e3, s.workers, s.busy_fraction() * 100.0, s.first_tile_s * 1e3, s.after_last_chunk_s * 1e3);
  return line;
}

}  // namespace tessera::scene
