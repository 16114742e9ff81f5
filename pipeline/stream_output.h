// Stream output: IA -> VS -> HS -> tessellator -> DS, and the domain shader's outputs handed to the
// caller patch by patch in draw order, instead of going on to the rasterizer. It is what
// `tessera tessellate` writes to PLY, and how tests look at exactly what the DS produced.
//
// Contract
// - The sink is called once per patch that was not culled, in patch order, on the calling thread,
//   with the patch's DS outputs (in the tessellator's point order) and the pattern's indices into them.
//   The data it sees are only valid during the call.
// - Deterministic and bounded like Device::draw: windows of `window_patches` patches, chunks cut by
//   primitive count, `chunks_in_flight` chunks in parallel, then handed over in order.
// - The domain shader may return any copyable type.
#pragma once

#include <span>
#include <vector>

#include "pipeline/device.h"

namespace tessera {

// A stream-output pass: the patch list's stages (device.h), with no rasterizer after them.
template <class Vertex, class Vs, class Hs, class Ds>
using StreamDraw = PatchStages<Vertex, Vs, Hs, Ds>;

template <class DsOut>
struct PatchOutput {
  std::uint32_t patch_id = 0;  // SV_PrimitiveID
  ts::OutputPrimitive output = ts::OutputPrimitive::triangle_cw;
  std::span<const ts::DomainPoint> domain;  // where each output was evaluated
  std::span<const DsOut> points;            // one per domain point
  std::span<const std::uint32_t> indices;   // primitives (3, 2 or 1 indices each) into `points`
};

namespace detail {

template <class DsOut>
struct StreamChunk {
  struct Patch {
    std::uint32_t patch_id;
    ts::OutputPrimitive output;
    std::size_t point_begin, point_count, index_begin, index_count;
  };
  std::vector<Patch> patches;
  std::vector<ts::DomainPoint> domain;
  std::vector<DsOut> points;
  std::vector<std::uint32_t> indices;
  std::uint64_t ds_invocations = 0;
  double tessellator_seconds = 0, ds_seconds = 0;

  void reset() {
    patches.clear();
    domain.clear();
    points.clear();
    indices.clear();
    ds_invocations = 0;
    tessellator_seconds = ds_seconds = 0;
  }
  std::size_t bytes() const {
    return patches.capacity() * sizeof(Patch) + domain.capacity() * sizeof(ts::DomainPoint) +
           points.capacity() * sizeof(DsOut) + indices.capacity() * sizeof(std::uint32_t);
  }
};

}  // namespace detail

template <class Vertex, class Vs, class Hs, class Ds, class Sink>
DrawResult stream_out(Device& device, const StreamDraw<Vertex, Vs, Hs, Ds>& d, Sink&& sink) {
  using FrontEnd = detail::PatchFrontEnd<Vertex, Vs, Hs>;
  using ControlPoint = typename FrontEnd::ControlPoint;
  using PatchConstants = typename FrontEnd::PatchConstants;
  using DsOut = decltype(d.ds(std::declval<const PatchConstants&>(), std::span<const ControlPoint>(), DomainLocation{},
                              std::uint32_t{0}));

  DrawResult result;
  if (auto e = validate_patch_draw(d.indices.size(), d.control_points, d.tessellator); !e.empty()) return {e, {}};
  const auto draw_start = detail::Clock::now();
  DrawReport& report = result.report;
  const TessellatorState tstate = d.tessellator;
  const DeviceOptions& options = device.options();

  detail::arena_execute(device.arena(), [&] {
    tbb::enumerable_thread_specific<PatternCache> patterns;
    std::vector<detail::StreamChunk<DsOut>> slots(std::size_t(std::max(1, options.chunks_in_flight)));
    FrontEnd front(d.vertices, d.indices, d.control_points, d.vs, d.hs, tstate, options.window_patches,
                   options.chunk_primitives);
    std::size_t slot_bytes_peak = 0;

    // Chunks produced in parallel, `slots` at a time, then handed to the sink in order.
    const auto stream_window = [&] {
      for (std::size_t c0 = 0; c0 < front.chunk_count(); c0 += slots.size()) {
        const std::size_t used = std::min(slots.size(), front.chunk_count() - c0);
        detail::parallel_for(tbb::blocked_range<std::size_t>(0, used, 1), [&](const auto& r) {
          for (std::size_t s = r.begin(); s != r.end(); ++s) {
            auto& chunk = slots[s];
            chunk.reset();
            front.for_each_patch(
                c0 + s, patterns.local(), chunk.tessellator_seconds, [&](const typename FrontEnd::Work& w) {
                  const auto start = detail::Clock::now();
                  const ts::Pattern& pattern = w.pattern;
                  chunk.patches.push_back({w.patch_id, pattern.output, chunk.points.size(), pattern.points.size(),
                                           chunk.indices.size(), pattern.indices.size()});
                  for (const ts::DomainPoint q : pattern.points) {
                    chunk.domain.push_back(q);
                    chunk.points.push_back(
                        d.ds(w.constants, w.control_points, detail::domain_location(q, tstate.domain), w.patch_id));
                  }
                  chunk.indices.insert(chunk.indices.end(), pattern.indices.begin(), pattern.indices.end());
                  chunk.ds_invocations += pattern.points.size();
                  chunk.ds_seconds += detail::seconds_since(start);
                });
          }
        });
        std::size_t bytes = 0;
        for (const auto& s : slots) bytes += s.bytes();
        slot_bytes_peak = std::max(slot_bytes_peak, bytes);
        for (std::size_t s = 0; s < used; ++s) {
          const auto& chunk = slots[s];
          report.statistics.DSInvocations += chunk.ds_invocations;
          report.times.tessellator += chunk.tessellator_seconds;
          report.times.ds += chunk.ds_seconds;
          for (const auto& p : chunk.patches) {
            PatchOutput<DsOut> out;
            out.patch_id = p.patch_id;
            out.output = p.output;
            out.domain = std::span<const ts::DomainPoint>(chunk.domain.data() + p.point_begin, p.point_count);
            out.points = std::span<const DsOut>(chunk.points.data() + p.point_begin, p.point_count);
            out.indices = std::span<const std::uint32_t>(chunk.indices.data() + p.index_begin, p.index_count);
            sink(out);
          }
        }
        report.memory.chunks += used;
      }
    };
    front.run(report, stream_window);
    for (const auto& c : patterns) detail::add_pattern_cache(report.memory, c);
    report.memory.geometry_peak_bytes = front.window_bytes_peak() + slot_bytes_peak;
  });
  report.times.wall = detail::seconds_since(draw_start);
  return result;
}

}  // namespace tessera
