// Pipeline statistics as Direct3D 11 reports them (D3D11_QUERY_DATA_PIPELINE_STATISTICS), plus where
// the time and the memory went.
//
// Counting conventions (D3D leaves some to the implementation; these are Tessera's, and they do not
// depend on the thread count):
// - IAVertices: control points or vertices fetched (patch count * control points per patch).
// - IAPrimitives: patches (or triangles) assembled.
// - VSInvocations: unique vertex indices per front-end window (vertex caching by index).
// - HSInvocations: patches run through the hull shader (both phases).
// - DSInvocations: domain points evaluated.
// - CInvocations: primitives that reached the clipper; CPrimitives: primitives it emitted (after
//   culling by the view volume and NaN rejection, after splitting by clipping).
// - PSInvocations: pixels that passed the depth test and ran the pixel shader (early depth: the pixel
//   shaders here write neither depth nor discard).
#pragma once

#include <cstdint>
#include <string>

namespace tessera {

struct PipelineStatistics {
  std::uint64_t IAVertices = 0;
  std::uint64_t IAPrimitives = 0;
  std::uint64_t VSInvocations = 0;
  std::uint64_t GSInvocations = 0;  // no geometry shader stage: always 0
  std::uint64_t GSPrimitives = 0;
  std::uint64_t CInvocations = 0;
  std::uint64_t CPrimitives = 0;
  std::uint64_t PSInvocations = 0;
  std::uint64_t HSInvocations = 0;
  std::uint64_t DSInvocations = 0;

  PipelineStatistics& operator+=(const PipelineStatistics& o);
  friend bool operator==(const PipelineStatistics&, const PipelineStatistics&) = default;
};

// Seconds per stage, summed over threads (thread-seconds), plus wall-clock seconds of the draw.
struct StageTimes {
  double ia_vs = 0;        // index fetch, vertex cache, vertex shader
  double hs = 0;           // both hull shader phases and factor processing
  double tessellator = 0;  // pattern generation (cache misses only)
  double ds = 0;           // domain shader
  double setup = 0;        // primitive assembly, clipping, culling, triangle setup, binning
  double raster = 0;       // rasterization, depth test, pixel shader, output merger
  double wall = 0;

  StageTimes& operator+=(const StageTimes& o);
};

// Bytes the pipeline held at its peak during a draw, by kind. Geometry buffers are bounded: they do not
// grow with the tessellation factor (chunks are cut by primitive count, see device.h).
struct MemoryStats {
  std::uint64_t geometry_peak_bytes = 0;  // window (VS/HS outputs) + chunk buffers + per-thread scratch
  std::uint64_t framebuffer_bytes = 0;
  std::uint64_t pattern_cache_bytes = 0;
  std::uint64_t chunks = 0;  // geometry chunks flushed to the rasterizer
  std::uint64_t tiles_split = 0;  // tile flushes rasterized as four quarters, by up to four threads
  std::uint64_t pattern_cache_hits = 0;
  std::uint64_t pattern_cache_misses = 0;
};

struct DrawReport {
  PipelineStatistics statistics;
  std::uint64_t patches_culled = 0;       // patches the tessellator culled (a zero, negative or NaN factor)
  std::uint64_t patches_back_culled = 0;  // patches proven to face away and skipped (patch_orientation.h)
  StageTimes times;
  MemoryStats memory;
};

// Peak resident set size of this process, in bytes (from /proc/self/status VmHWM); 0 if unknown.
std::uint64_t peak_rss_bytes();

}  // namespace tessera
