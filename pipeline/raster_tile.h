// Rasterization of one screen tile: each primitive by its kind (raster_triangle.h,
// raster_multisample.h, raster_line_point.h), then early depth, the pixel shader and the output merger
// (pixel_shading.h).
//
// A tile is owned by one thread; it processes its primitives in draw order, so results do not depend
// on the thread count.
#pragma once

#include <cstdint>
#include <type_traits>

#include "pipeline/framebuffer.h"
#include "pipeline/raster_line_point.h"
#include "pipeline/raster_multisample.h"
#include "pipeline/raster_triangle.h"

namespace tessera {

namespace detail {

template <std::size_t N, class Ps, CompareFunc kDepthFunc, bool kMultisampled, class ForEach>
std::uint64_t rasterize_tile_with(const ForEach& for_each_primitive, int tx0, int ty0, int tx1, int ty1, const Ps& ps,
                                  const RasterContext& rc, Framebuffer& fb) {
  std::uint64_t invocations = 0;
  for_each_primitive([&](const ScreenPrimitive<N>& p) {
    switch (p.kind) {
      case PrimitiveKind::triangle:
        if constexpr (kMultisampled)
          invocations += rasterize_triangle_multisample<N, Ps, kDepthFunc>(p, tx0, ty0, tx1, ty1, ps, rc, fb);
        else
          invocations += rasterize_triangle_with<N, Ps, kDepthFunc>(p, tx0, ty0, tx1, ty1, ps, rc, fb);
        break;
      case PrimitiveKind::line: invocations += rasterize_line<N>(p, tx0, ty0, tx1, ty1, ps, rc, fb); break;
      case PrimitiveKind::point: invocations += rasterize_point<N>(p, tx0, ty0, tx1, ty1, ps, rc, fb); break;
    }
  });
  return invocations;
}

}  // namespace detail

// Rasterizes primitives, in draw order, inside the tile [tx0, tx1) x [ty0, ty1), which only this thread
// writes: for_each_primitive(visit) calls visit(const ScreenPrimitive<N>&) for each of them. Returns
// the pixel shader invocations. The depth function is chosen once per tile, as a template argument,
// so the per-pixel test compiles to one comparison.
template <std::size_t N, class Ps, class ForEach>
std::uint64_t rasterize_tile(const ForEach& for_each_primitive, int tx0, int ty0, int tx1, int ty1, const Ps& ps,
                             const RasterContext& rc, Framebuffer& fb) {
  // The sample count too is chosen once per tile: the single-sampled loop has no multisample branch.
  const bool multisampled = fb.samples() > 1;
  const auto with = [&](auto func) {
    return multisampled ? detail::rasterize_tile_with<N, Ps, decltype(func)::value, true>(for_each_primitive, tx0, ty0,
                                                                                          tx1, ty1, ps, rc, fb)
                        : detail::rasterize_tile_with<N, Ps, decltype(func)::value, false>(for_each_primitive, tx0, ty0,
                                                                                           tx1, ty1, ps, rc, fb);
  };
  using F = CompareFunc;
  switch (rc.depth.func) {
    case F::never: return with(std::integral_constant<F, F::never>{});
    case F::less: return with(std::integral_constant<F, F::less>{});
    case F::equal: return with(std::integral_constant<F, F::equal>{});
    case F::less_equal: return with(std::integral_constant<F, F::less_equal>{});
    case F::greater: return with(std::integral_constant<F, F::greater>{});
    case F::not_equal: return with(std::integral_constant<F, F::not_equal>{});
    case F::greater_equal: return with(std::integral_constant<F, F::greater_equal>{});
    case F::always: return with(std::integral_constant<F, F::always>{});
  }
  return 0;
}

}  // namespace tessera
