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

#include "device.h"

namespace tessera {

template <class Vertex, class Vs, class Hs, class Ds>
struct StreamDraw {
  std::span<const Vertex> vertices;
  std::span<const std::uint32_t> indices;
  int control_points = 0;  // per input patch, 1..32
  Vs vs;
  Hs hs;
  Ds ds;
  TessellatorState tessellator;
};

template <class DsOut>
struct PatchOutput {
  std::uint32_t patch_id = 0;           // SV_PrimitiveID
  ts::OutputPrimitive output = ts::OutputPrimitive::triangle_cw;
  std::span<const ts::DomainPoint> domain;  // where each output was evaluated
  std::span<const DsOut> points;        // one per domain point
  std::span<const std::uint32_t> indices;  // primitives (3, 2 or 1 indices each) into `points`
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
  using VsOut = vs_output_t<Vs, Vertex>;
  static_assert(HullShader<Hs, VsOut>, "the hull shader does not have the shape stage_io.h describes");
  using ControlPoint = hs_control_point_t<Hs, VsOut>;
  using PatchConstants = hs_patch_constants_t<Hs, VsOut>;
  using DsOut = decltype(d.ds(std::declval<const PatchConstants&>(), std::span<const ControlPoint>(), DomainLocation{},
                              std::uint32_t{0}));
  constexpr int kOut = Hs::kOutputControlPoints;

  DrawResult result;
  if (auto e = validate_patch_draw(d.indices.size(), d.control_points, d.tessellator); !e.empty()) return {e, {}};
  const auto draw_start = detail::Clock::now();
  DrawReport& report = result.report;
  const std::size_t n_in = std::size_t(d.control_points);
  const std::size_t patch_count = d.indices.size() / n_in;
  const TessellatorState tstate = d.tessellator;
  const DeviceOptions& options = device.options();

  detail::arena_execute(device.arena(), [&] {
    tbb::enumerable_thread_specific<PatternCache> patterns;
    tbb::enumerable_thread_specific<StageTimes> front_times;
    std::vector<detail::StreamChunk<DsOut>> slots(std::size_t(std::max(1, options.chunks_in_flight)));
    detail::VertexCache vcache;
    std::vector<VsOut> vs_out;
    detail::HullPhase<VsOut, ControlPoint, PatchConstants> hull;
    const auto& processed = hull.processed;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> chunks;
    std::size_t bytes_peak = 0;

    const std::size_t window = std::size_t(std::max(1, options.window_patches));
    for (std::size_t first = 0; first < patch_count; first += window) {
      const std::size_t n = std::min(window, patch_count - first);
      const auto indices = d.indices.subspan(first * n_in, n * n_in);
      detail::assemble_and_shade_vertices(d.vs, d.vertices, indices, n, vcache, vs_out, report);
      hull.run(d.hs, vs_out, vcache, n, n_in, first, tstate, [&]() -> PatternCache& { return patterns.local(); },
               [&]() -> StageTimes& { return front_times.local(); });
      report.statistics.HSInvocations += n;

      // Chunks cut by primitive count, produced in parallel, handed to the sink in order.
      detail::cut_chunks(hull.cost, options.chunk_primitives, 256, chunks);
      for (std::size_t c0 = 0; c0 < chunks.size(); c0 += slots.size()) {
        const std::size_t used = std::min(slots.size(), chunks.size() - c0);
        detail::parallel_for(tbb::blocked_range<std::size_t>(0, used, 1), [&](const auto& r) {
          for (std::size_t s = r.begin(); s != r.end(); ++s) {
            auto& chunk = slots[s];
            chunk.reset();
            auto& cache = patterns.local();
            const auto [begin, end] = chunks[c0 + s];
            for (std::uint32_t p = begin; p < end; ++p) {
              if (processed[p].culled) continue;
              const auto start = detail::Clock::now();
              bool hit = false;
              const ts::Pattern& pattern = cache.get(processed[p], tstate.output, hit);
              const auto tess_done = detail::Clock::now();
              if (!hit) chunk.tessellator_seconds += std::chrono::duration<double>(tess_done - start).count();
              const auto patch_id = static_cast<std::uint32_t>(first + p);
              const std::span<const ControlPoint> cps = hull.patch_control_points(p, kOut);
              const bool tri = tstate.domain == ts::Domain::tri;
              chunk.patches.push_back({patch_id, pattern.output, chunk.points.size(), pattern.points.size(),
                                       chunk.indices.size(), pattern.indices.size()});
              for (const ts::DomainPoint q : pattern.points) {
                chunk.domain.push_back(q);
                chunk.points.push_back(
                    d.ds(hull.constants[p], cps, DomainLocation{q.u, q.v, tri ? (1.0f - q.u) - q.v : 0.0f}, patch_id));
              }
              chunk.indices.insert(chunk.indices.end(), pattern.indices.begin(), pattern.indices.end());
              chunk.ds_invocations += pattern.points.size();
              chunk.ds_seconds += detail::seconds_since(tess_done);
            }
          }
        });
        std::size_t bytes = 0;
        for (const auto& s : slots) bytes += s.bytes();
        bytes_peak = std::max(bytes_peak, bytes);
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
      const std::size_t window_bytes = vcache.bytes() + vs_out.capacity() * sizeof(VsOut) + hull.bytes();
      report.memory.geometry_peak_bytes = std::max<std::uint64_t>(report.memory.geometry_peak_bytes, window_bytes + bytes_peak);
    }
    for (const auto& t : front_times) report.times += t;
    for (const auto& c : patterns) {
      report.memory.pattern_cache_hits += c.hits();
      report.memory.pattern_cache_misses += c.misses();
      report.memory.pattern_cache_bytes += c.bytes();
    }
  });
  report.times.wall = detail::seconds_since(draw_start);
  return result;
}

}  // namespace tessera
