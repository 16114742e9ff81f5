#include "pipeline/device.h"

#include <thread>

namespace tessera {

Device::Device(DeviceOptions options) : options_(options) {
  const int hw = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads_ = options_.threads > 0 ? options_.threads : hw;
  options_.tile_size = std::clamp(options_.tile_size & ~1, 8, 1024);
  options_.chunk_primitives = std::max<std::size_t>(options_.chunk_primitives, 64);
  options_.window_patches = std::max(options_.window_patches, 1);
  // Enough chunks per round, and rounds at once, that every thread has chunks to produce while earlier
  // rounds rasterize and a round's slowest chunks finish (docs/performance.md has the measurements).
  if (options_.chunks_in_flight <= 0) options_.chunks_in_flight = std::max(4, 4 * threads_);
  // On two threads a third round gains no overlap, and its chunks (4 MB more at 2 x 4096 primitives)
  // push the records setup writes out of cache before they are rasterized; from four threads up the
  // third round pays for itself (docs/performance.md).
  if (options_.rounds_in_flight <= 0) options_.rounds_in_flight = threads_ <= 2 ? 2 : 3;
  options_.rounds_in_flight = std::max(options_.rounds_in_flight, 2);
  // oneTBB caps its workers at the hardware concurrency and says so on stderr when an arena asks for
  // more. A device asked for more threads than cores (to test determinism, or on an oversubscribed
  // machine) raises the cap while it lives. Active controls combine by their minimum, so two such
  // devices alive at once share the smaller raise; results do not depend on the worker count.
  if (threads_ > int(tbb::this_task_arena::max_concurrency()))
    worker_limit_ =
        std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads_));
  arena_ = std::make_unique<tbb::task_arena>(threads_);
}

void Device::clear(Framebuffer& fb, glm::vec4 color, float depth) {
  // A multisampled target (a 1080p 4x one is 66 MB) by tiles, as draws enter them: on 16 cores the
  // torus at 4x 18.9-21.0 -> 17.2-19.3 ms, 8x 26.8-29.3 -> 23.5-24.3. A single-sampled one at once: by
  // tiles its 1x frame was slower there (torus 9.6 -> 10.2-10.4 ms, frog 6.9-7.1 -> 7.3-7.7).
  if (fb.samples() > 1) {
    fb.clear_by_tiles(color, depth, options_.tile_size);
    return;
  }
  fb.cancel_clear();
  constexpr int kRows = 32;  // rows per task: large enough to amortize a task, small enough to balance
  detail::arena_execute(*arena_, [&] {
    detail::parallel_for(tbb::blocked_range<int>(0, (fb.height() + kRows - 1) / kRows, 1),
                         [&](const auto& r) { fb.clear_rows(r.begin() * kRows, r.end() * kRows, color, depth); });
  });
}

void Device::finish_clear(Framebuffer& fb) {
  if (!fb.pending_clear_tile_size()) return;
  detail::arena_execute(*arena_, [&] {
    detail::parallel_for(tbb::blocked_range<int>(0, fb.pending_clear_tiles(), 1), [&](const auto& r) {
      for (int t = r.begin(); t != r.end(); ++t) fb.prepare_tile(t);
    });
  });
  fb.finish_clear();
}

void Device::resolve(const Framebuffer& fb, Framebuffer& out, ResolvedPlanes planes) {
  // Every pixel of `out` is written below: a clear pending there is void, or, when its depth is not
  // written, that plane's clear is kept.
  if (planes == ResolvedPlanes::color_and_depth)
    out.cancel_clear();
  else
    finish_clear(out);
  constexpr int kRows = 16;  // rows per task (a row of a 1920-wide 8x target is 60 KB of colour)
  detail::arena_execute(*arena_, [&] {
    detail::parallel_for(tbb::blocked_range<int>(0, (fb.height() + kRows - 1) / kRows, 1), [&](const auto& r) {
      fb.resolve_rows(out, r.begin() * kRows, std::min(r.end() * kRows, fb.height()), planes);
    });
  });
}

std::string validate_viewport(const Viewport& vp, const Framebuffer& fb) {
  const bool finite = std::isfinite(vp.x) && std::isfinite(vp.y) && std::isfinite(vp.width) &&
                      std::isfinite(vp.height) && std::isfinite(vp.min_depth) && std::isfinite(vp.max_depth);
  if (!finite) return "viewport has a non-finite value";
  if (!(vp.width > 0) || !(vp.height > 0))
    return "viewport " + std::to_string(vp.width) + "x" + std::to_string(vp.height) + " has zero area";
  if (vp.width > float(kMaxRenderTargetSize) || vp.height > float(kMaxRenderTargetSize))
    return "viewport is larger than " + std::to_string(kMaxRenderTargetSize) + " pixels on a side";
  if (vp.x < -32768.0f || vp.y < -32768.0f || vp.x + vp.width > 32767.0f || vp.y + vp.height > 32767.0f)
    return "viewport lies outside D3D11's bounds [-32768, 32767]";
  if (vp.min_depth < 0 || vp.min_depth > 1 || vp.max_depth < 0 || vp.max_depth > 1)
    return "viewport depth range must lie in [0, 1]";
  (void)fb;
  return {};
}

std::string validate_patch_draw(std::size_t index_count, int control_points, const TessellatorState& ts) {
  if (control_points < 1 || control_points > 32)
    return "patch list with " + std::to_string(control_points) + " control points (D3D11 allows 1..32)";
  if (index_count % std::size_t(control_points) != 0)
    return "index count " + std::to_string(index_count) + " is not a multiple of " + std::to_string(control_points) +
           " control points";
  const bool triangles =
      ts.output == ts::OutputPrimitive::triangle_cw || ts.output == ts::OutputPrimitive::triangle_ccw;
  if (ts.domain == ts::Domain::isoline && triangles) return "the isoline domain outputs lines or points, not triangles";
  return {};
}

}  // namespace tessera
