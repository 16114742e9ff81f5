// What flows between the programmable stages, and the shapes shader functors must have.
//
// Shaders are C++ functors bound at compile time. A draw (device.h) names their types; the pipeline
// calls them directly, so every call inlines: there is no virtual call per vertex, point or pixel.
//
//   vertex shader   Out  operator()(const Vertex& v, std::uint32_t vertex_id) const
//   hull shader     static constexpr int kOutputControlPoints (1..32);
//                   ControlPoint control_point(std::span<const VsOut> patch, int i, std::uint32_t patch_id) const
//                   PatchConstants patch_constants(std::span<const VsOut> patch,
//                                                  std::span<const ControlPoint> outputs, std::uint32_t patch_id) const
//                   PatchConstants has a member `TessFactors factors` (SV_TessFactor, SV_InsideTessFactor).
//   domain shader   ClipVertex<N> operator()(const PatchConstants&, std::span<const ControlPoint>,
//                                            DomainLocation, std::uint32_t patch_id) const
//                   optionally also a batch form (BatchDomainShader below):
//                   void operator()(const PatchConstants&, std::span<const ControlPoint>,
//                                   std::span<const DomainLocation>, std::uint32_t patch_id,
//                                   std::span<ClipVertex<N>> out) const
//   pixel shader    glm::vec4 operator()(const PixelInput<N>&) const
//                   optionally also void shade_quad(const QuadInput<N>&, QuadColor&) const (below)
//
// The last stage before the rasterizer returns ClipVertex<N>: SV_Position in clip space plus N float
// attributes, interpolated perspective-correctly for the pixel shader.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include <glm/glm.hpp>

namespace tessera {

template <std::size_t N>
struct ClipVertex {
  glm::vec4 position{0.0f};  // SV_Position, clip space (D3D: 0 <= z <= w inside)
  std::array<float, N> attributes{};
};

// SV_TessFactor and SV_InsideTessFactor, in the tessellator's order (tessellator.h): quad uses
// edge[0..3] and inside[0..1]; tri uses edge[0..2] and inside[0]; isoline uses edge[0] (density) and
// edge[1] (detail).
struct TessFactors {
  std::array<float, 4> edge{};
  std::array<float, 2> inside{};
};

// SV_DomainLocation. For the tri domain w = (1 - u) - v (exact); for quads and isolines w = 0.
struct DomainLocation {
  float u = 0, v = 0, w = 0;
};

// What a pixel shader invocation sees. Derivatives are coarse (one per 2x2 quad, as ddx_coarse):
// ddx = attribute at (x+1) minus at x along the quad's top row; ddy along its left column. Helper
// pixels (uncovered pixels of a partly covered quad) are interpolated too, so derivatives exist on
// triangle edges. Lines and points have zero derivatives.
template <std::size_t N>
struct PixelInput {
  glm::vec4 position{0.0f};  // SV_Position: pixel centre (x + 0.5, y + 0.5), depth, 1/w
  std::array<float, N> attributes{};
  const std::array<float, N>* ddx_attributes = nullptr;
  const std::array<float, N>* ddy_attributes = nullptr;
  bool front_face = true;  // SV_IsFrontFace
  std::uint32_t primitive_id = 0;

  float ddx(std::size_t i) const { return (*ddx_attributes)[i]; }
  float ddy(std::size_t i) const { return (*ddy_attributes)[i]; }
};

// The optional quad form of a pixel shader: the four pixels of a 2x2 quad at once, in lanes
// (k = 0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right), so one call does the work of four and
// the lane loops vectorize. Lane k must produce exactly the bits operator() gives for that pixel: the
// pipeline uses whichever form exists, and tests compare the two. Lanes outside `mask` are helpers or
// failed the depth test; their results are discarded.
template <std::size_t N>
struct QuadInput {
  std::array<float, 4> x{}, y{}, z{}, inv_w{};       // SV_Position per lane
  std::array<std::array<float, 4>, N> attributes{};  // attributes[a][k]: attribute a at lane k
  bool front_face = true;
  std::uint32_t primitive_id = 0;
  unsigned mask = 0;  // bit k: lane k is written

  // The quad's derivatives of attribute a (coarse, the same for its four pixels, and what the per-pixel
  // form's PixelInput::ddx/ddy return): computed when asked, since most shaders never ask.
  float ddx(std::size_t a) const { return attributes[a][1] - attributes[a][0]; }
  float ddy(std::size_t a) const { return attributes[a][2] - attributes[a][0]; }
};

// A quad's colours: c[channel][lane].
struct QuadColor {
  std::array<std::array<float, 4>, 4> c{};
};

template <class Ps, std::size_t N>
concept QuadPixelShader = requires(const Ps& ps, const QuadInput<N>& q, QuadColor& out) {
  ps.shade_quad(q, out);
};

// The optional batch form of a domain shader: all of a patch's domain points in one call, so a shader
// can evaluate several points at once (in SIMD lanes) or share work between points with equal u or v.
// out[i] must be exactly the bits the per-point form returns for locations[i]; the pipeline calls the
// batch form when present.
template <class Ds, class PatchConstants, class ControlPoint, std::size_t N>
concept BatchDomainShader = requires(const Ds& ds, const PatchConstants& pc, std::span<const ControlPoint> cps,
                                     std::span<const DomainLocation> locations, std::span<ClipVertex<N>> out) {
  ds(pc, cps, locations, std::uint32_t{0}, out);
};

template <class T>
struct is_clip_vertex : std::false_type {};
template <std::size_t N>
struct is_clip_vertex<ClipVertex<N>> : std::true_type {
  static constexpr std::size_t attribute_count = N;
};

template <class Vs, class Vertex>
using vs_output_t = std::invoke_result_t<const Vs&, const Vertex&, std::uint32_t>;

template <class Vs, class Vertex>
concept VertexShader = requires(const Vs& vs, const Vertex& v) {
  {vs(v, std::uint32_t{0})};
};

template <class Hs, class VsOut>
concept HullShader = requires(const Hs& hs, std::span<const VsOut> in, std::uint32_t id) {
  { Hs::kOutputControlPoints } -> std::convertible_to<int>;
  {hs.control_point(in, 0, id)};
  requires Hs::kOutputControlPoints >= 1 && Hs::kOutputControlPoints <= 32;
};

template <class Hs, class VsOut>
using hs_control_point_t =
    decltype(std::declval<const Hs&>().control_point(std::declval<std::span<const VsOut>>(), 0, 0u));

template <class Hs, class VsOut>
using hs_patch_constants_t = decltype(std::declval<const Hs&>().patch_constants(
    std::declval<std::span<const VsOut>>(), std::declval<std::span<const hs_control_point_t<Hs, VsOut>>>(), 0u));

}  // namespace tessera
