// Fixed-function state of a draw, in Direct3D 11's terms (D3D11_RASTERIZER_DESC, D3D11_DEPTH_STENCIL_DESC,
// D3D11_VIEWPORT, D3D11_RECT, and the hull shader's domain/partitioning/outputtopology attributes).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "tessellator/tessellator.h"

namespace tessera {

enum class CullMode : std::uint8_t { none, front, back };
enum class FillMode : std::uint8_t { solid, wireframe };
enum class CompareFunc : std::uint8_t { never, less, equal, less_equal, greater, not_equal, greater_equal, always };

std::string_view to_string(CullMode m);
std::string_view to_string(CompareFunc f);
std::optional<CullMode> parse_cull_mode(std::string_view s);
std::optional<CompareFunc> parse_compare_func(std::string_view s);

// D3D11_VIEWPORT. Maps NDC x, y in [-1, 1] to [x, x + width] and [y, y + height] (y down) and z in [0, 1]
// to [min_depth, max_depth]. A draw with a zero-area or non-finite viewport is rejected by validate().
struct Viewport {
  float x = 0, y = 0, width = 0, height = 0;
  float min_depth = 0, max_depth = 1;
};

// D3D11_RECT in pixels: left/top inclusive, right/bottom exclusive.
struct ScissorRect {
  int left = 0, top = 0, right = 0, bottom = 0;
};

struct RasterizerState {
  FillMode fill = FillMode::solid;
  CullMode cull = CullMode::back;
  // D3D11's FrontCounterClockwise: false means clockwise triangles (in screen space, y down) face front.
  bool front_counter_clockwise = false;
  std::optional<ScissorRect> scissor;  // ScissorEnable with one rectangle
};

struct DepthState {
  bool test = true;                      // DepthEnable
  bool write = true;                     // DepthWriteMask ALL
  CompareFunc func = CompareFunc::less;  // DepthFunc
};

// The hull shader's [domain], [partitioning] and [outputtopology] attributes.
struct TessellatorState {
  ts::Domain domain = ts::Domain::quad;
  ts::Partitioning partitioning = ts::Partitioning::integer;
  ts::OutputPrimitive output = ts::OutputPrimitive::triangle_cw;
};

// The comparison D3D11 applies: `incoming func stored`.
inline bool depth_passes(CompareFunc f, float incoming, float stored) {
  switch (f) {
    case CompareFunc::never: return false;
    case CompareFunc::less: return incoming < stored;
    case CompareFunc::equal: return incoming == stored;
    case CompareFunc::less_equal: return incoming <= stored;
    case CompareFunc::greater: return incoming > stored;
    case CompareFunc::not_equal: return incoming != stored;
    case CompareFunc::greater_equal: return incoming >= stored;
    case CompareFunc::always: return true;
  }
  return false;
}

}  // namespace tessera
