// The draw entry points: a Device owns the worker threads; draw() runs one draw call through
// IA -> VS -> HS -> tessellator -> DS -> clip/setup/bin -> rasterizer -> PS -> output merger.
//
// Contract
// - Deterministic: the framebuffer bytes and the statistics are identical for any thread count and
//   from run to run. Work is split into chunks of primitives in draw order; each tile rasterizes the
//   chunks' primitives in draw order; every computation on a primitive is a pure function of it.
// - Bounded memory: the front end (front_end.h) handles at most `window_patches` patches at a time
//   (VS and HS outputs), and cuts their output into chunks of about `chunk_primitives` primitives, in
//   rounds of up to `chunks_in_flight` (tile_schedule.h); the chunks in flight (produced while earlier
//   ones are rasterized) share rounds_in_flight x chunks_in_flight chunk buffers. Peak memory therefore
//   does not grow with the tessellation factor (one patch is at most 8192 triangles); it grows
//   linearly with the thread count (the default chunks_in_flight is 4 x threads).
// - A Device runs one draw at a time (draws on one device from several threads take turns): its chunk
//   slots are reused from draw to draw, so their storage is allocated and touched once, not per frame.
// - Bad data is reported, not crashed on: validate() errors are returned as one-line messages;
//   D3D11's own rules cover the rest (out-of-range indices fetch a zero vertex, NaN/Inf positions
//   discard the primitive, out-of-range factors are clamped or cull the patch).
//
// This header is the API: the draws' descriptions (shaders as functors, stage_io.h states what each
// returns) and the Device. Its machinery is in draw_backend.h (chunks, schedule, raster) and
// device_draw.h (the draw templates), which this header includes last.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <typeindex>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "pipeline/draw_trace.h"
#include "pipeline/framebuffer.h"
#include "pipeline/pipeline_state.h"
#include "pipeline/stage_io.h"
#include "pipeline/statistics.h"

namespace tessera {

struct DeviceOptions {
  int threads = 0;                      // worker threads; 0 = all hardware threads
  int tile_size = 64;                   // screen tile edge in pixels (even, 8..1024)
  std::size_t chunk_primitives = 4096;  // a chunk is cut before its primitive count would pass this
  // Patches through VS and HS at once (a mesh draw: 4 x as many triangles through the VS). Each window
  // ends with the draw's pipeline drained (its last round rasterized with nothing to overlap), so the
  // default holds a whole asset of a few thousand faces (docs/performance.md).
  int window_patches = 4096;
  // Chunks per round: a round's tiles are rasterized once all its chunks are produced (each tile once
  // its earlier rounds are; tile_schedule.h). 0: four times the thread count, at least 4.
  int chunks_in_flight = 0;
  // Rounds whose storage exists at once (produced while earlier ones are rasterized; at least 2). Chunk
  // storage is rounds_in_flight x chunks_in_flight chunk buffers. 0: the default, 2 on up to two
  // threads, else 3.
  int rounds_in_flight = 0;
};

// Called after each round of chunks of a patch draw is rasterized, one call at a time and in order (on
// a worker thread or the drawing thread): the draw's patches done (through the last chunk rasterized)
// and its total. For progress displays; it sees no pixels and cannot change any result.
using DrawProgress = std::function<void(std::size_t patches_done, std::size_t patches_total)>;

// A patch list (D3D11_PRIMITIVE_TOPOLOGY_n_CONTROL_POINT_PATCHLIST, n = control_points) through the
// stages up to the domain shader: what a draw (PatchDraw) and a stream-output pass (StreamDraw,
// stream_output.h) share.
template <class Vertex, class Vs, class Hs, class Ds>
struct PatchStages {
  std::span<const Vertex> vertices;
  std::span<const std::uint32_t> indices;
  int control_points = 0;  // per input patch, 1..32
  Vs vs;
  Hs hs;
  Ds ds;
  TessellatorState tessellator;
};

// A draw of a patch list: its stages, then the pixel shader and the fixed-function state after them.
template <class Vertex, class Vs, class Hs, class Ds, class Ps>
struct PatchDraw : PatchStages<Vertex, Vs, Hs, Ds> {
  Ps ps;
  RasterizerState rasterizer;
  DepthState depth;
  Viewport viewport;
};

// A draw of an indexed triangle list without tessellation; the vertex shader returns ClipVertex<N>.
template <class Vertex, class Vs, class Ps>
struct MeshDraw {
  std::span<const Vertex> vertices;
  std::span<const std::uint32_t> indices;
  Vs vs;
  Ps ps;
  RasterizerState rasterizer;
  DepthState depth;
  Viewport viewport;
};

struct DrawResult {
  std::string error;  // empty on success
  DrawReport report;
  bool ok() const { return error.empty(); }
};

// One-line reasons a draw's fixed-function state cannot be used, or an empty string.
std::string validate_viewport(const Viewport& vp, const Framebuffer& fb);
std::string validate_patch_draw(std::size_t index_count, int control_points, const TessellatorState& ts);


class Device {
 public:
  explicit Device(DeviceOptions options = {});
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  int threads() const { return threads_; }
  const DeviceOptions& options() const { return options_; }
  // Sets (or, with an empty function, removes) the progress hook of the draws that follow.
  void set_progress(DrawProgress progress) { progress_ = std::move(progress); }
  // Records the patch draws that follow into `trace` (draw_trace.h), or, with nullptr, stops. The trace
  // must outlive those draws.
  void set_trace(DrawTrace* trace) { trace_ = trace; }
  // The arena the device's work runs in (stream_output.h runs there too).
  tbb::task_arena& arena() const { return *arena_; }

  // Clears the colour and depth buffers as Framebuffer::clear does. A multisampled target is cleared
  // tile by tile when needed (Framebuffer::clear_by_tiles, in this device's tiles): the draws write each
  // tile's clear as they enter it, resolve() writes the tiles they did not enter from the clear values,
  // and finish_clear writes what is left. A single-sampled one is cleared at once, in bands of rows.
  void clear(Framebuffer& fb, glm::vec4 color, float depth);
  // Writes fb's pending clear, if any, on the device's threads (tile by tile).
  void finish_clear(Framebuffer& fb);
  // Framebuffer::resolve into `out` (single-sampled, of fb's size and format) on the device's threads
  // (bands of rows); the same bytes. A clear pending on `out` is dropped where every pixel is written
  // (both planes), else written first (its depth stays).
  void resolve(const Framebuffer& fb, Framebuffer& out, ResolvedPlanes planes = ResolvedPlanes::color_and_depth);

  template <class Vertex, class Vs, class Hs, class Ds, class Ps>
  DrawResult draw(const PatchDraw<Vertex, Vs, Hs, Ds, Ps>& d, Framebuffer& fb);

  template <class Vertex, class Vs, class Ps>
  DrawResult draw(const MeshDraw<Vertex, Vs, Ps>& d, Framebuffer& fb);

 private:
  // Storage the device keeps from draw to draw, one object per type: the chunk slots
  // (std::vector<ChunkBuffer<N>>), each thread's patch scratch (pattern cache, DS buffers) and the
  // front end's window storage (front_end.h). Kept, it is mapped and faulted in once, not every frame,
  // and each thread's patterns stay tessellated.
  template <class T>
  T& kept() {
    std::shared_ptr<void>& object = kept_[std::type_index(typeid(T))];
    if (!object) object = std::make_shared<T>();
    return *static_cast<T*>(object.get());
  }

  // The part every draw shares: validates the viewport (and `invalid`, the draw's own check), takes the
  // one-draw lock, finishes a foreign clear, and in the device's arena makes the setup context and the
  // back end and calls body(backend, report); then the report's framebuffer bytes and wall time.
  template <std::size_t N, class Ps, class Body>
  DrawResult run_draw(const Viewport& viewport, const RasterizerState& rasterizer, const DepthState& depth,
                      const Ps& ps, Framebuffer& fb, const std::string& invalid, Body&& body);

  // A clear pending in another grid's tiles is written whole before a draw, which prepares its own
  // tiles only.
  void finish_foreign_clear(Framebuffer& fb) {
    if (fb.pending_clear_tile_size() != 0 && fb.pending_clear_tile_size() != options_.tile_size) finish_clear(fb);
  }

  DeviceOptions options_;
  DrawProgress progress_;
  DrawTrace* trace_ = nullptr;
  int threads_ = 1;
  std::mutex draw_mutex_;                                     // one draw at a time: they share the slots
  std::map<std::type_index, std::shared_ptr<void>> kept_;     // kept(), by type
  std::unique_ptr<tbb::global_control> worker_limit_;         // only when threads_ exceeds the default limit
  std::unique_ptr<tbb::task_arena> arena_;
};

}  // namespace tessera

#include "pipeline/device_draw.h"
