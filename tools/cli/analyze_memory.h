// `tessera analyze CAGE --memory [--displacement MAP] [--levels 8,16,32,64] [--measure]`: the talk's
// memory table for one cage (memory_model.h holds the model and its assumptions), and with --measure
// the real peak memory of rendering it at each level, each render in a child `tessera render` so that
// every level's peak is its own.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/limit_surface.h"
#include "tools/measure/memory_model.h"

namespace tessera::cli {

struct MemoryOptions {
  bool enabled = false;
  std::string scheme = "gregory", levels = "8,16,32,64";
  int isolation = kDefaultIsolation;            // --memory-scheme adaptive's level
  std::string displacement, channel;            // the map, and the channel that holds the height (displacement_map.h)
  int texel_bytes = 0, mesh_vertex_bytes = 32;  // texel_bytes 0: as the map is kept
  bool measure = false;
  std::string resolution = "1920x1080";
  int threads = 0;
  friend bool operator==(const MemoryOptions&, const MemoryOptions&) = default;
};

void add_memory_options(CLI::App& cmd, MemoryOptions& o);

// One render's memory, as the child reported it.
struct MeasuredMemory {
  std::uint64_t peak_rss_bytes = 0, geometry_peak_bytes = 0, framebuffer_bytes = 0;
  double seconds = 0.0;
};

struct MemoryAnalysis {
  MemoryOptions options;
  std::string map_description;  // "monsterfrog.dds 512x512 (channel A)" or the assumption made without one
  int texel_bytes = 0;          // as used
  measure::MemoryTable table;
  std::vector<MeasuredMemory> measured;  // per level, with --measure
  std::uint64_t base_rss_bytes = 0;      // with --measure: peak RSS of a tessera that draws nothing
};

// Throws UsageError for bad options and InputError for an unreadable map or a failed child render.
MemoryAnalysis analyze_memory(const std::string& cage_path, const Cage& cage, const Topology& topology,
                              const MemoryOptions& options);
std::string memory_text(const MemoryAnalysis& a);
nlohmann::ordered_json memory_json(const MemoryAnalysis& a);

}  // namespace tessera::cli
