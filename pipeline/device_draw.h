// The draw templates behind Device::draw (device.h includes this header last; include device.h).
//
// A patch draw: the front end (front_end.h) runs IA, VS and HS over a window of patches and cuts their
// tessellated output into chunks in draw order; each chunk's patches go through the tessellator's
// pattern (cached per thread), back-patch culling, the DS (its batch form when it has one) and setup
// into the chunk's bins; the back end (draw_backend.h) rasterizes the chunks' tiles in draw order.
// A mesh draw: the VS per vertex (a vertex cache), then the same setup and back end.
#pragma once

#include <algorithm>
#include <chrono>
#include <span>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include "pipeline/device.h"
#include "pipeline/draw_backend.h"
#include "pipeline/front_end.h"
#include "pipeline/parallel.h"
#include "pipeline/patch_orientation.h"
#include "pipeline/triangle_list_setup.h"

namespace tessera {
namespace detail {

// One patch of a draw through back-patch culling (patch_orientation.h: the pattern's shape is computed
// only for a bound that can hold, on a draw whose rasterizer culls one orientation), the DS and
// setup_vertex, then its primitives through setup into the chunk.
template <std::size_t N, class Work, class Ds>
void patch_to_chunk(const SetupContext& setup, bool culls_an_orientation, ts::Domain domain, const Ds& ds,
                    const Work& w, PatchScratch<N>& local, ChunkBuffer<N>& chunk) {
  using PatchConstants = std::remove_cvref_t<decltype(w.constants)>;
  using ControlPoint = typename std::remove_cvref_t<decltype(w.control_points)>::value_type;
  const ts::Pattern& pattern = w.pattern;
  if constexpr (HasOrientationBound<PatchConstants>) {
    const OrientationBound& bound = w.constants.orientation;
    if (culls_an_orientation && bound.may_hold()) {
      const auto start = Clock::now();
      const ts::PatternShape& shape = local.patterns.shape(pattern);
      const bool away = bound.holds(shape) && rasterizer_culls(setup, pattern_screen_sign(bound, shape));
      chunk.times.tessellator += seconds_since(start);
      if (away) {
        ++chunk.patches_back_culled;
        return;
      }
    }
  }
  // The orientation test above is the tessellator's time, not the DS's (so that the stages' times add
  // up to at most the threads' time).
  const auto start = Clock::now();
  auto& outs = local.domain_outputs;
  outs.resize(pattern.points.size());
  if constexpr (BatchDomainShader<Ds, PatchConstants, std::remove_const_t<ControlPoint>, N>) {
    auto& locations = local.locations;
    auto& clips = local.clip_outputs;
    locations.resize(pattern.points.size());
    clips.resize(pattern.points.size());
    for (std::size_t i = 0; i < pattern.points.size(); ++i) locations[i] = domain_location(pattern.points[i], domain);
    ds(w.constants, w.control_points, std::span<const DomainLocation>(locations), w.patch_id,
       std::span<ClipVertex<N>>(clips));
    make_setup_vertices<N>(setup, std::span<const ClipVertex<N>>(clips), std::span<SetupVertex<N>>(outs));
  } else {
    for (std::size_t i = 0; i < pattern.points.size(); ++i)
      outs[i] = make_setup_vertex<N>(
          setup, ds(w.constants, w.control_points, domain_location(pattern.points[i], domain), w.patch_id));
  }
  chunk.statistics.DSInvocations += pattern.points.size();
  const auto ds_done = Clock::now();
  chunk.times.ds += std::chrono::duration<double>(ds_done - start).count();
  const auto& idx = pattern.indices;
  switch (pattern.output) {
    case ts::OutputPrimitive::triangle_cw:
    case ts::OutputPrimitive::triangle_ccw:
      setup_triangle_list<N>(setup, chunk, outs.data(), outs.size(), idx.data(), idx.size() / 3, w.patch_id, 0);
      break;
    case ts::OutputPrimitive::line:
      for (std::size_t i = 0; i + 1 < idx.size(); i += 2) setup_line<N>(setup, chunk, outs[idx[i]], outs[idx[i + 1]], w.patch_id);
      break;
    case ts::OutputPrimitive::point:
      for (std::uint32_t i : idx) setup_point<N>(setup, chunk, outs[i], w.patch_id);
      break;
  }
  chunk.times.setup += seconds_since(ds_done);
}

}  // namespace detail

template <std::size_t N, class Ps, class Body>
DrawResult Device::run_draw(const Viewport& viewport, const RasterizerState& rasterizer, const DepthState& depth,
                            const Ps& ps, Framebuffer& fb, const std::string& invalid, Body&& body) {
  DrawResult result;
  if (auto e = validate_viewport(viewport, fb); !e.empty()) return {e, {}};
  if (!invalid.empty()) return {invalid, {}};
  const auto draw_start = detail::Clock::now();
  const std::lock_guard<std::mutex> one_draw(draw_mutex_);
  finish_foreign_clear(fb);
  detail::arena_execute(*arena_, [&] {
    const SetupContext setup =
        make_setup_context(viewport, rasterizer, fb.width(), fb.height(), options_.tile_size, fb.samples());
    detail::Backend<N, Ps> backend(setup, depth, ps, fb, kept<std::vector<ChunkBuffer<N>>>(), options_.chunks_in_flight,
                                   options_.rounds_in_flight, trace_);
    body(backend, result.report);
  });
  result.report.memory.framebuffer_bytes = fb.bytes();
  result.report.times.wall = detail::seconds_since(draw_start);
  return result;
}

template <class Vertex, class Vs, class Hs, class Ds, class Ps>
DrawResult Device::draw(const PatchDraw<Vertex, Vs, Hs, Ds, Ps>& d, Framebuffer& fb) {
  using FrontEnd = detail::PatchFrontEnd<Vertex, Vs, Hs>;
  using ControlPoint = typename FrontEnd::ControlPoint;
  using PatchConstants = typename FrontEnd::PatchConstants;
  using DsOut = decltype(d.ds(std::declval<const PatchConstants&>(), std::span<const ControlPoint>(), DomainLocation{},
                              std::uint32_t{0}));
  static_assert(is_clip_vertex<DsOut>::value, "the domain shader must return ClipVertex<N>");
  constexpr std::size_t N = is_clip_vertex<DsOut>::attribute_count;
  const std::string invalid = validate_patch_draw(d.indices.size(), d.control_points, d.tessellator);
  return run_draw<N>(d.viewport, d.rasterizer, d.depth, d.ps, fb, invalid, [&](auto& backend, DrawReport& report) {
    const SetupContext& setup = backend.setup();
    const TessellatorState tstate = d.tessellator;
    auto& scratch = kept<tbb::enumerable_thread_specific<detail::PatchScratch<N>>>();
    for (auto& s : scratch) s.patterns.reset_counters();  // the report counts this draw's hits and misses
    const bool culls_an_orientation = rasterizer_culls(setup, 1) || rasterizer_culls(setup, -1);
    // A window's last chunk per worker, in quarters (cut_chunks): less left for few workers at its end.
    // The cut does not change what is drawn (chunks are cut and drawn in draw order).
    const std::size_t tail_primitives = threads_ > 1 ? std::size_t(threads_) * options_.chunk_primitives : 0;
    FrontEnd front(d.vertices, d.indices, d.control_points, d.vs, d.hs, tstate, options_.window_patches,
                   options_.chunk_primitives, &kept<typename FrontEnd::Storage>(), trace_, tail_primitives);
    std::size_t scratch_bytes_peak = 0;
    front.run(report, [&] {
      backend.run(
          front.chunk_count(),
          [&](std::size_t c, ChunkBuffer<N>& chunk) {
            auto& local = scratch.local();
            front.for_each_patch(c, local.patterns, chunk.times.tessellator, [&](const typename FrontEnd::Work& w) {
              detail::patch_to_chunk<N>(setup, culls_an_orientation, tstate.domain, d.ds, w, local, chunk);
            });
          },
          report,
          [&](std::size_t chunks_done) {
            if (progress_) progress_(front.patches_through_chunk(chunks_done - 1), front.patch_count());
          });
      std::size_t bytes = 0;
      for (const auto& s : scratch) bytes += s.bytes();
      scratch_bytes_peak = std::max(scratch_bytes_peak, bytes);
    });
    for (const auto& s : scratch) detail::add_pattern_cache(report.memory, s.patterns);
    report.memory.geometry_peak_bytes = front.window_bytes_peak() + scratch_bytes_peak + backend.chunk_bytes_peak();
  });
}

template <class Vertex, class Vs, class Ps>
DrawResult Device::draw(const MeshDraw<Vertex, Vs, Ps>& d, Framebuffer& fb) {
  using VsOut = vs_output_t<Vs, Vertex>;
  static_assert(is_clip_vertex<VsOut>::value, "a mesh draw's vertex shader must return ClipVertex<N>");
  constexpr std::size_t N = is_clip_vertex<VsOut>::attribute_count;
  const std::string invalid =
      d.indices.size() % 3 == 0
          ? std::string()
          : "triangle list has " + std::to_string(d.indices.size()) + " indices, not a multiple of 3";
  return run_draw<N>(d.viewport, d.rasterizer, d.depth, d.ps, fb, invalid, [&](auto& backend, DrawReport& report) {
    const SetupContext& setup = backend.setup();
    const std::size_t triangle_count = d.indices.size() / 3;
    detail::VertexCache vcache;
    std::vector<VsOut> vs_out;
    std::vector<SetupVertex<N>> setup_vertices;
    std::vector<std::uint32_t> cost;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> chunks;
    const std::size_t window = std::size_t(std::max(1, options_.window_patches)) * 4;
    std::size_t window_bytes_peak = 0;
    for (std::size_t first = 0; first < triangle_count; first += window) {
      const std::size_t n = std::min(window, triangle_count - first);
      const auto indices = d.indices.subspan(first * 3, n * 3);
      detail::assemble_and_shade_vertices(d.vs, d.vertices, indices, n, vcache, vs_out, report);
      const auto t0 = detail::Clock::now();
      setup_vertices.resize(vs_out.size());
      detail::parallel_for(tbb::blocked_range<std::size_t>(0, vs_out.size(), 1024), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) setup_vertices[i] = make_setup_vertex<N>(setup, vs_out[i]);
      });
      report.times.setup += detail::seconds_since(t0);
      cost.assign(n, 1);
      detail::cut_chunks(cost, options_.chunk_primitives, options_.chunk_primitives, chunks);
      backend.run(
          chunks.size(),
          [&](std::size_t c, ChunkBuffer<N>& chunk) {
            const auto start = detail::Clock::now();
            const auto [begin, end] = chunks[c];
            setup_triangle_list<N>(setup, chunk, setup_vertices.data(), setup_vertices.size(),
                                   vcache.slots.data() + std::size_t(begin) * 3, end - begin,
                                   static_cast<std::uint32_t>(first + begin), 1);
            chunk.times.setup += detail::seconds_since(start);
          },
          report);
      window_bytes_peak = std::max(window_bytes_peak, vcache.bytes() + vs_out.capacity() * sizeof(VsOut) +
                                                          setup_vertices.capacity() * sizeof(SetupVertex<N>) +
                                                          cost.capacity() * sizeof(std::uint32_t));
    }
    report.memory.geometry_peak_bytes = window_bytes_peak + backend.chunk_bytes_peak();
  });
}

}  // namespace tessera
