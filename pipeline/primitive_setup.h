// Primitive assembly's back half: clip-space primitives in, screen-space primitives binned to tiles out.
//
// For each triangle: NaN rejection, trivial rejection against the view volume, guard-band clipping
// (clipper.h), perspective division, the viewport transform, snapping to 16.8 fixed point (D3D11's
// 8 bits of sub-pixel precision), back/front culling on the snapped signed area, the pixel bounding box
// clipped to viewport, scissor and render target, and binning by that box into screen tiles.
// Everything here is a pure function of its inputs, so any thread produces the same bytes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "clipper.h"
#include "simd4.h"
#include "pipeline_state.h"
#include "statistics.h"

namespace tessera {

inline constexpr int kSubpixelBits = 8;
inline constexpr int kSubpixelOne = 1 << kSubpixelBits;

enum class PrimitiveKind : std::uint8_t { triangle, line, point };

// A primitive in window space, ready to rasterize. Triangles are stored with positive signed area
// (vertices 1 and 2 swapped if needed), so edge functions are >= 0 inside.
//
// Lines and points keep per-vertex values in z, inv_w and attributes. Triangles keep plane equations
// there instead, computed once at setup: value(x, y) = [0] + [1] * (x - origin_x) + [2] * (y - origin_y)
// in pixels, for window depth, for 1/w, and for each attribute divided by w (perspective-correct
// interpolation divides the attribute plane by the 1/w plane per pixel).
//
// A triangle whose vertex box is small enough that every edge-function value the rasterizer evaluates
// fits in 32 bits (`edges32`, kEdges32MaxExtent; nearly all of them) keeps its edge functions, set up
// once here rather than per tile, in place of its vertices (the rasterizer needs nothing else of them,
// and the record stays as small as it was: setup writes and the rasterizer reads it through memory).
// Other triangles keep their vertices; the rasterizer sets their edges up in 64-bit integers.
struct VertexPositions {
  std::array<std::int32_t, 3> x, y;  // 16.8 fixed-point window coordinates
};
// Edge i runs from vertex i to vertex i + 1 (top-left bias included); its value at the centre of pixel
// (min_x, min_y) is ref[i], and it changes by -dy[i] * 256 per pixel right and dx[i] * 256 per pixel down
// (dx, dy: vertex i + 1 minus vertex i, at most kEdges32MaxExtent in magnitude).
struct SmallTriangleEdges {
  std::array<std::int16_t, 4> dx, dy;  // [3] unused: dx and dy are one 16-byte store from setup's lanes
  std::array<std::int32_t, 3> ref;
  // Edge i's steps for one pixel right and one pixel down, and its value at the centre of pixel
  // (min_x + ox, min_y + oy), modulo 2^32: exact wherever the rasterizer evaluates it.
  std::int32_t step_x(int i) const { return -std::int32_t(dy[std::size_t(i)]) * kSubpixelOne; }
  std::int32_t step_y(int i) const { return std::int32_t(dx[std::size_t(i)]) * kSubpixelOne; }
  std::int32_t value_at(int i, int ox, int oy) const {
    return std::int32_t(std::uint32_t(ref[std::size_t(i)]) + std::uint32_t(step_x(i)) * std::uint32_t(ox) +
                        std::uint32_t(step_y(i)) * std::uint32_t(oy));
  }
};
template <std::size_t N>
struct ScreenPrimitive {
  union {
    VertexPositions xy{};      // lines, points, triangles without edges32
    SmallTriangleEdges edges;  // triangles with edges32
  };
  std::array<float, 3> z{};              // window depth (viewport-mapped), or its plane
  std::array<float, 3> inv_w{};          // 1/w, or its plane
  std::array<std::array<float, N>, 3> attributes{};  // per vertex, or planes: attributes[j][a] = coefficient j of a
  float origin_x = 0, origin_y = 0;      // triangles: where the planes are anchored (vertex 0), in pixels
  std::int32_t min_x = 0, min_y = 0, max_x = -1, max_y = -1;  // covered pixel box, inclusive
  std::uint32_t primitive_id = 0;
  PrimitiveKind kind = PrimitiveKind::triangle;
  bool front_face = true;
  bool edges32 = false;
  // Triangles whose box holds at most 4x4 pixel centres (nearly all of them from factor 16 up): bit
  // dx + 8 * dy is set when pixel (min_x + dx, min_y + dy) lies in the box and is covered, as setup
  // found when it tested those centres; the rasterizer shades these pixels without walking edges. 0
  // otherwise (setup drops a small-box triangle that covers nothing). Rows are 8 bits apart, as the
  // rasterizer's quad grid (BoxQuads) lays them out, so it only shifts them into place.
  std::uint32_t box_coverage = 0;
};

// The largest vertex box extent (16.8 units, either axis) of a triangle whose edge functions the
// rasterizer evaluates in 32-bit lanes. Every pixel centre it evaluates lies at most one pixel (256)
// outside the box (a quad's lane beside the first or last covered centre), so
// |edge| <= ext_y * (ext_x + 256) + ext_x * (ext_y + 256) + 1 < 2^31.
inline constexpr std::int32_t kEdges32MaxExtent = 32767 - 256;

// The largest pixel box (either side) whose covered centres setup finds and keeps in the record
// (ScreenPrimitive::box_coverage).
inline constexpr std::int32_t kSmallBoxPixels = 4;

// Screen tiles: the unit of parallel rasterization.
struct TileGrid {
  int tile_size = 64;
  int columns = 0, rows = 0;
  // tile_of(p) = p / tile_size by a 32-bit multiply and a shift (setup bins every primitive, eight at a
  // time in SIMD lanes where it can; a division is slow, and AVX2 has no 64-bit lane multiply): with
  // shift = 14 + ceil(log2 tile_size) and reciprocal = floor(2^shift / tile_size) + 1, p * reciprocal / 2^shift
  // exceeds p / tile_size by less than p / 2^shift < 1 / tile_size, the gap to the next integer, for every
  // pixel p < 2^14 (kMaxRenderTargetSize); and p * reciprocal < 2^14 * (2^15 + 1) < 2^31.
  std::uint32_t reciprocal = (1u << 20) / 64 + 1;
  int shift = 20;
  void set_tile_size(int size) {
    tile_size = size;
    shift = 14;
    while ((1 << (shift - 14)) < size) ++shift;
    reciprocal = (1u << shift) / std::uint32_t(size) + 1;
  }
  int count() const { return columns * rows; }
  int tile_of(std::int32_t pixel) const { return int((std::uint32_t(pixel) * reciprocal) >> shift); }
};

// What setup needs to know about the draw, computed once.
struct SetupContext {
  // Viewport transform: window = ndc * scale + offset (y flipped: D3D's y-down window space).
  float scale_x = 0, offset_x = 0, scale_y = 0, offset_y = 0, z_scale = 1, z_offset = 0;
  float min_depth = 0, max_depth = 1;
  GuardBand guard;
  // Pixels that may be written: viewport, scissor and render target intersected (inclusive).
  int clip_min_x = 0, clip_min_y = 0, clip_max_x = -1, clip_max_y = -1;
  CullMode cull = CullMode::back;
  bool front_ccw = false;
  FillMode fill = FillMode::solid;
  TileGrid tiles;
};

SetupContext make_setup_context(const Viewport& vp, const RasterizerState& rs, int target_width, int target_height,
                                int tile_size);

// One chunk of the draw's primitives, in draw order, binned to tiles. Setup appends (tile, primitive)
// pairs; finish_bins() sorts them by tile with a stable counting sort, so each tile's list keeps draw
// order. Storage is proportional to the chunk's primitives (not to tiles x capacity), and is reused.
//
// Each buffer has cache lines of its own (alignas): threads fill neighbouring slots at the same time,
// and setup updates the counters and vector ends here per primitive; sharing a line with the next
// slot made setup run at half speed whenever two threads filled neighbours.
template <std::size_t N>
struct alignas(128) ChunkBuffer {
  // primitives[0, primitive_count) are this chunk's; the rest is storage kept from earlier chunks
  // (append_primitive() hands out slots without clearing them: setup writes every field it uses).
  std::vector<ScreenPrimitive<N>> primitives;
  std::size_t primitive_count = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> entries;  // (tile, primitive) in draw order
  std::vector<std::uint32_t> tile_start;                         // per tile: first entry in `binned`, plus an end
  std::vector<std::uint32_t> binned;                             // primitive indices grouped by tile
  PipelineStatistics statistics;
  StageTimes times;

  void reset(int tile_count) {
    primitive_count = 0;
    entries.clear();
    binned.clear();
    tile_start.assign(std::size_t(tile_count) + 1, 0);
    statistics = {};
    times = {};
  }
  void finish_bins() {
    const std::size_t tiles = tile_start.size() - 1;
    std::fill(tile_start.begin(), tile_start.end(), 0);
    for (const auto& e : entries) ++tile_start[e.first + 1];
    for (std::size_t t = 0; t < tiles; ++t) tile_start[t + 1] += tile_start[t];
    binned.resize(entries.size());
    // Fill using a running cursor per tile; tile_start is restored afterwards.
    for (const auto& e : entries) binned[tile_start[e.first]++] = e.second;
    for (std::size_t t = tiles; t > 0; --t) tile_start[t] = tile_start[t - 1];
    tile_start[0] = 0;
  }
  // The next primitive's slot, holding whatever an earlier chunk left there.
  [[gnu::always_inline]] ScreenPrimitive<N>& append_primitive() {
    if (primitive_count == primitives.size()) primitives.resize(std::max<std::size_t>(16, 2 * primitives.size()));
    return primitives[primitive_count++];
  }
  std::span<const std::uint32_t> bin(int tile) const {
    return {binned.data() + tile_start[std::size_t(tile)], binned.data() + tile_start[std::size_t(tile) + 1]};
  }
  std::size_t capacity_bytes() const {
    return primitives.capacity() * sizeof(ScreenPrimitive<N>) + entries.capacity() * sizeof(entries[0]) +
           (tile_start.capacity() + binned.capacity()) * sizeof(std::uint32_t);
  }
};

namespace detail {

inline std::int32_t snap(float window_coordinate) {
  // Round to nearest even in 1/256 pixel; the guard band bounds the magnitude below 2^23.
  return static_cast<std::int32_t>(std::nearbyint(window_coordinate * float(kSubpixelOne)));
}

// First and last pixel whose centre (p + 0.5) lies in [lo, hi] (16.8 fixed point).
inline std::int32_t first_pixel_at_or_after(std::int32_t lo) {
  // ceil((lo - 128) / 256) = floor((lo - 128 + 255) / 256); >> is floor division (arithmetic shift).
  return (lo - kSubpixelOne / 2 + kSubpixelOne - 1) >> kSubpixelBits;
}
inline std::int32_t last_pixel_at_or_before(std::int32_t hi) {
  return (hi - kSubpixelOne / 2) >> kSubpixelBits;  // arithmetic shift = floor
}

// Edge i of a triangle with positive area runs from vertex i to vertex i + 1; it is >= 0 on the inside
// and biased by -1 unless it is a top or left edge (D3D11's top-left rule). EdgeFunction is edge i's
// value at (cx, cy) (16.8 units) and its steps for one pixel right and down, in 64-bit integers (exact
// inside the guard band); raster_tile.h walks exactly these functions, and setup's 32-bit lanes compute
// the same values for small triangles.
struct EdgeFunction {
  std::int64_t value, step_x, step_y;
};
inline EdgeFunction edge_function(const std::int32_t* x, const std::int32_t* y, int i, std::int64_t cx, std::int64_t cy) {
  const int j = i == 2 ? 0 : i + 1;
  const std::int64_t dx = x[j] - x[i], dy = y[j] - y[i];
  const bool top_left = dy < 0 || (dy == 0 && dx > 0);
  return {-dy * (cx - x[i]) + dx * (cy - y[i]) + (top_left ? 0 : -1), -dy * kSubpixelOne, dx * kSubpixelOne};
}

// The one-centre form: whether pixel (px, py)'s centre (px + 0.5, py + 0.5) is covered.
inline bool covers_centre(const std::int32_t (&x)[3], const std::int32_t (&y)[3], std::int32_t px, std::int32_t py) {
  const std::int64_t cx = std::int64_t(px) * kSubpixelOne + kSubpixelOne / 2;
  const std::int64_t cy = std::int64_t(py) * kSubpixelOne + kSubpixelOne / 2;
  std::int64_t all = 0;
  for (int i = 0; i < 3; ++i) all |= edge_function(x, y, i, cx, cy).value;
  return all >= 0;
}

// Enters the chunk's primitive `index` in the bins of the tiles its box touches.
// Inlined into setup: it runs for every primitive, and nearly every one lies in a single tile.
template <std::size_t N>
[[gnu::always_inline]] inline void bin_primitive(const SetupContext& c, ChunkBuffer<N>& chunk, std::uint32_t index) {
  const ScreenPrimitive<N>& p = chunk.primitives[index];
  const TileGrid& g = c.tiles;
  const int tx0 = g.tile_of(p.min_x), tx1 = g.tile_of(p.max_x), ty0 = g.tile_of(p.min_y), ty1 = g.tile_of(p.max_y);
  if (tx0 == tx1 && ty0 == ty1) {
    chunk.entries.emplace_back(std::uint32_t(ty0 * g.columns + tx0), index);
    return;
  }
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) chunk.entries.emplace_back(std::uint32_t(ty * g.columns + tx), index);
}
template <std::size_t N>
[[gnu::always_inline]] inline void bin_last(const SetupContext& c, ChunkBuffer<N>& chunk) {
  bin_primitive(c, chunk, static_cast<std::uint32_t>(chunk.primitive_count - 1));
}
template <std::size_t N>
void bin(const SetupContext& c, ChunkBuffer<N>& chunk, const ScreenPrimitive<N>& p) {
  chunk.append_primitive() = p;
  bin_last(c, chunk);
}

// Clips the pixel box to what may be written; false if nothing is left.
template <std::size_t N>
bool finish_box(const SetupContext& c, ScreenPrimitive<N>& p, std::int32_t lo_x, std::int32_t hi_x, std::int32_t lo_y,
                std::int32_t hi_y) {
  p.min_x = std::max(first_pixel_at_or_after(lo_x), c.clip_min_x);
  p.max_x = std::min(last_pixel_at_or_before(hi_x), c.clip_max_x);
  p.min_y = std::max(first_pixel_at_or_after(lo_y), c.clip_min_y);
  p.max_y = std::min(last_pixel_at_or_before(hi_y), c.clip_max_y);
  return p.min_x <= p.max_x && p.min_y <= p.max_y;
}

}  // namespace detail

// A vertex as setup sees it: the clip-space vertex, its outcodes, and (when it lies inside the guard
// band, in front of the near plane and behind the far one) its snapped window position. Computed once
// per vertex (per domain point), then shared by every primitive that uses it.
template <std::size_t N>
struct SetupVertex {
  ClipVertex<N> clip;
  std::int32_t x = 0, y = 0;  // 16.8 window position (valid when clip_code == 0)
  float z = 0, inv_w = 0;
  // What a triangle's plane equations interpolate, computed once per vertex and laid out for SIMD loads
  // (setup_snapped_triangle): z, 1/w, each attribute times 1/w, then zeros to a multiple of 4.
  std::array<float, 4 * ((N + 5) / 4)> plane_values{};
  unsigned view_code = 0;     // outside which view-volume planes
  unsigned clip_code = 0;     // outside which clipping planes (near, far, guard band)
  bool finite = true;
};

// A snapped vertex's plane_values, from its z, 1/w and attributes.
template <std::size_t N>
void set_plane_values(SetupVertex<N>& s) {
  s.plane_values[0] = s.z;
  s.plane_values[1] = s.inv_w;
  for (std::size_t a = 0; a < N; ++a) s.plane_values[2 + a] = s.clip.attributes[a] * s.inv_w;
  for (std::size_t a = N + 2; a < s.plane_values.size(); ++a) s.plane_values[a] = 0.0f;
}

// `clipped` marks a vertex the clipper made: it lies on a clipping plane, possibly an ulp outside, and
// is projected regardless.
template <std::size_t N>
SetupVertex<N> make_setup_vertex(const SetupContext& c, const ClipVertex<N>& v, bool clipped = false) {
  SetupVertex<N> s;
  s.clip = v;
  s.finite = finite_position(v.position);
  if (!s.finite) return s;
  s.view_code = view_outcode(v.position);
  s.clip_code = clip_outcode(v.position, c.guard);
  if (s.clip_code == 0 || clipped) {
    const float inv_w = 1.0f / v.position.w;
    s.x = detail::snap(v.position.x * inv_w * c.scale_x + c.offset_x);
    s.y = detail::snap(v.position.y * inv_w * c.scale_y + c.offset_y);
    s.z = v.position.z * inv_w * c.z_scale + c.z_offset;
    s.inv_w = inv_w;
    set_plane_values(s);
  }
  return s;
}

// make_setup_vertex for many vertices (a batch domain shader's output): the same bits, with the
// outcodes, the perspective division, the viewport transform and the snapping of four vertices in SIMD
// lanes (each lane the scalar expression; cvtps2dq rounds to nearest even like std::nearbyint in the
// default rounding mode, and every value it converts lies inside the guard band).
template <std::size_t N>
void make_setup_vertices(const SetupContext& c, std::span<const ClipVertex<N>> in, std::span<SetupVertex<N>> out) {
  std::size_t i = 0;
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps(), sign = _mm_set1_ps(-0.0f);
  const __m128i exponent = _mm_set1_epi32(0x7f800000);
  const auto bit = [](__m128 mask, unsigned b) { return _mm_and_si128(_mm_castps_si128(mask), _mm_set1_epi32(int(1u << b))); };
  for (; i + 4 <= in.size(); i += 4) {
    __m128 x = _mm_loadu_ps(&in[i].position.x), y = _mm_loadu_ps(&in[i + 1].position.x);
    __m128 z = _mm_loadu_ps(&in[i + 2].position.x), w = _mm_loadu_ps(&in[i + 3].position.x);
    _MM_TRANSPOSE4_PS(x, y, z, w);  // now lane k of x, y, z, w is vertex i + k
    // finite_position: no coordinate has an all-ones exponent.
    const __m128i inf_or_nan =
        _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(x), exponent), exponent),
                                  _mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(y), exponent), exponent)),
                     _mm_or_si128(_mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(z), exponent), exponent),
                                  _mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(w), exponent), exponent)));
    const unsigned finite = ~unsigned(_mm_movemask_ps(_mm_castsi128_ps(inf_or_nan))) & 0xFu;
    // view_outcode
    const __m128 neg_w = _mm_xor_ps(w, sign);
    const __m128i view = _mm_or_si128(
        _mm_or_si128(_mm_or_si128(bit(_mm_cmplt_ps(z, zero), kNear), bit(_mm_cmplt_ps(w, z), kFar)),
                     _mm_or_si128(bit(_mm_cmplt_ps(x, neg_w), kLeft), bit(_mm_cmplt_ps(w, x), kRight))),
        _mm_or_si128(_mm_or_si128(bit(_mm_cmplt_ps(y, neg_w), kBottom), bit(_mm_cmplt_ps(w, y), kTop)),
                     _mm_andnot_si128(_mm_castps_si128(_mm_cmpgt_ps(w, zero)), _mm_set1_epi32(int(1u << kW)))));
    // clip_outcode
    const __m128 gx = _mm_mul_ps(_mm_set1_ps(c.guard.gx), w), gy = _mm_mul_ps(_mm_set1_ps(c.guard.gy), w);
    const __m128i clip = _mm_or_si128(
        _mm_or_si128(_mm_or_si128(bit(_mm_cmplt_ps(z, zero), kNear), bit(_mm_cmplt_ps(_mm_sub_ps(w, z), zero), kFar)),
                     _mm_or_si128(bit(_mm_cmplt_ps(_mm_add_ps(gx, x), zero), kLeft),
                                  bit(_mm_cmplt_ps(_mm_sub_ps(gx, x), zero), kRight))),
        _mm_or_si128(_mm_or_si128(bit(_mm_cmplt_ps(_mm_add_ps(gy, y), zero), kBottom),
                                  bit(_mm_cmplt_ps(_mm_sub_ps(gy, y), zero), kTop)),
                     bit(_mm_cmplt_ps(_mm_sub_ps(w, _mm_set1_ps(kMinClipW)), zero), kW)));
    // Projection and snapping (used only in lanes that are finite with clip code 0).
    const __m128 inv_w = _mm_div_ps(_mm_set1_ps(1.0f), w);
    const __m128 one_pixel = _mm_set1_ps(float(kSubpixelOne));
    const __m128i sx = _mm_cvtps_epi32(_mm_mul_ps(
        _mm_add_ps(_mm_mul_ps(_mm_mul_ps(x, inv_w), _mm_set1_ps(c.scale_x)), _mm_set1_ps(c.offset_x)), one_pixel));
    const __m128i sy = _mm_cvtps_epi32(_mm_mul_ps(
        _mm_add_ps(_mm_mul_ps(_mm_mul_ps(y, inv_w), _mm_set1_ps(c.scale_y)), _mm_set1_ps(c.offset_y)), one_pixel));
    const __m128 sz = _mm_add_ps(_mm_mul_ps(_mm_mul_ps(z, inv_w), _mm_set1_ps(c.z_scale)), _mm_set1_ps(c.z_offset));
    alignas(16) std::int32_t view_codes[4], clip_codes[4], xs[4], ys[4];
    alignas(16) float zs[4], inv_ws[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(view_codes), view);
    _mm_store_si128(reinterpret_cast<__m128i*>(clip_codes), clip);
    _mm_store_si128(reinterpret_cast<__m128i*>(xs), sx);
    _mm_store_si128(reinterpret_cast<__m128i*>(ys), sy);
    _mm_store_ps(zs, sz);
    _mm_store_ps(inv_ws, inv_w);
    for (int k = 0; k < 4; ++k) {
      // Every field written in place (as make_setup_vertex leaves it): assigning a value-initialised
      // SetupVertex went through a stack temporary whose copy stalled on store forwarding.
      SetupVertex<N>& s = out[i + std::size_t(k)];
      const ClipVertex<N>& v = in[i + std::size_t(k)];
      const bool is_finite = (finite >> k) & 1u;
      const bool snapped = is_finite && clip_codes[k] == 0;
      s.clip = v;
      s.finite = is_finite;
      s.view_code = is_finite ? unsigned(view_codes[k]) : 0u;
      s.clip_code = is_finite ? unsigned(clip_codes[k]) : 0u;
      s.x = snapped ? xs[k] : 0;
      s.y = snapped ? ys[k] : 0;
      s.z = snapped ? zs[k] : 0.0f;
      s.inv_w = snapped ? inv_ws[k] : 0.0f;
      if (snapped) set_plane_values(s);
      else s.plane_values.fill(0.0f);
    }
  }
#endif
  for (; i < in.size(); ++i) out[i] = make_setup_vertex<N>(c, in[i]);
}

namespace detail {

template <std::size_t N>
void copy_vertex(const SetupVertex<N>& v, ScreenPrimitive<N>& out, int slot) {
  out.xy.x[slot] = v.x;
  out.xy.y[slot] = v.y;
  out.z[slot] = v.z;
  out.inv_w[slot] = v.inv_w;
  out.attributes[slot] = v.clip.attributes;
}

template <std::size_t N>
void setup_line_window(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& a, const SetupVertex<N>& b,
                       std::uint32_t primitive_id) {
  ScreenPrimitive<N> p;
  p.kind = PrimitiveKind::line;
  p.primitive_id = primitive_id;
  copy_vertex(a, p, 0);
  copy_vertex(b, p, 1);
  // A line may light the pixel its end point lies in; widen the box by half a pixel.
  const std::int32_t h = kSubpixelOne / 2;
  if (!finish_box(c, p, std::min(p.xy.x[0], p.xy.x[1]) - h, std::max(p.xy.x[0], p.xy.x[1]) + h,
                  std::min(p.xy.y[0], p.xy.y[1]) - h, std::max(p.xy.y[0], p.xy.y[1]) + h))
    return;
  bin(c, chunk, p);
}

// A triangle whose three vertices are snapped: culling, bounding box, binning. `a`, `b`, `d` are in
// the primitive's order.
template <std::size_t N>
[[gnu::always_inline]] inline void setup_snapped_triangle(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& a,
                            const SetupVertex<N>& b, const SetupVertex<N>& d, std::uint32_t primitive_id) {
  const std::int64_t area = std::int64_t(b.x - a.x) * (d.y - a.y) - std::int64_t(d.x - a.x) * (b.y - a.y);
  if (area == 0) return;  // degenerate after snapping: covers nothing
  // Positive area is clockwise on screen (y down).
  const bool front = (area > 0) != c.front_ccw;
  if ((c.cull == CullMode::back && !front) || (c.cull == CullMode::front && front)) return;
  // The box test comes before the primitive is built: most micro-triangles stop here.
  const std::int32_t lx = std::min(std::min(a.x, b.x), d.x), hx = std::max(std::max(a.x, b.x), d.x);
  const std::int32_t ly = std::min(std::min(a.y, b.y), d.y), hy = std::max(std::max(a.y, b.y), d.y);
  const std::int32_t min_x = std::max(first_pixel_at_or_after(lx), c.clip_min_x);
  const std::int32_t max_x = std::min(last_pixel_at_or_before(hx), c.clip_max_x);
  if (min_x > max_x) return;
  const std::int32_t min_y = std::max(first_pixel_at_or_after(ly), c.clip_min_y);
  const std::int32_t max_y = std::min(last_pixel_at_or_before(hy), c.clip_max_y);
  if (min_y > max_y) return;
  // Stored with positive area: swap the last two vertices of a counter-clockwise triangle.
  const SetupVertex<N>* v[3] = {&a, area > 0 ? &b : &d, area > 0 ? &d : &b};
  const std::int32_t vx[3] = {v[0]->x, v[1]->x, v[2]->x}, vy[3] = {v[0]->y, v[1]->y, v[2]->y};
  // Edge functions (covers_centre's) of a triangle small enough for 32 bits: computed modulo 2^32 (unsigned
  // arithmetic wraps, defined), which gives the exact values because every value used fits
  // (kEdges32MaxExtent; the reference centre lies inside the vertex box).
  const bool edges32 = hx - lx <= kEdges32MaxExtent && hy - ly <= kEdges32MaxExtent;
#if defined(__SSE2__)
  // Edge i's reference value in lane i of one; dx of edges 0..3, then dy, in the 16-bit lanes of the other.
  __m128i edge_ref_lanes = _mm_setzero_si128(), edge_d_lanes = _mm_setzero_si128();
#else
  std::uint32_t edge_ref[4] = {}, edge_sx[4] = {}, edge_sy[4] = {};
  std::int16_t edge_d[8] = {};  // dx of edges 0..3, then dy
#endif
  const bool small_box = max_x - min_x <= kSmallBoxPixels - 1 && max_y - min_y <= kSmallBoxPixels - 1;
  bool covers = true;
  unsigned box_coverage = 0;  // for a small box: its covered centres (ScreenPrimitive::box_coverage)
  if (edges32) {
    const std::int32_t cx = min_x * kSubpixelOne + kSubpixelOne / 2, cy = min_y * kSubpixelOne + kSubpixelOne / 2;
#if defined(__SSE2__)
    // The three edges in lanes 0..2 (lane 3 repeats edge 2's direction; it is never used). A
    // SetupVertex's x and y are adjacent: one 64-bit load per vertex.
    static_assert(offsetof(SetupVertex<N>, y) == offsetof(SetupVertex<N>, x) + sizeof(std::int32_t));
    const __m128i p0 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&v[0]->x));  // x0 y0
    const __m128i p1 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&v[1]->x));
    const __m128i p2 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&v[2]->x));
    const __m128i p01 = _mm_unpacklo_epi32(p0, p1), p22 = _mm_unpacklo_epi32(p2, p2);  // x0 x1 y0 y1, x2 x2 y2 y2
    const __m128i x = _mm_unpacklo_epi64(p01, p22), y = _mm_unpackhi_epi64(p01, p22);  // x0 x1 x2 x2, y0 y1 y2 y2
    const __m128i dx = _mm_sub_epi32(_mm_shuffle_epi32(x, _MM_SHUFFLE(0, 0, 2, 1)), x);
    const __m128i dy = _mm_sub_epi32(_mm_shuffle_epi32(y, _MM_SHUFFLE(0, 0, 2, 1)), y);
    const __m128i zero = _mm_setzero_si128();
    const __m128i top_left = _mm_or_si128(_mm_cmplt_epi32(dy, zero), _mm_and_si128(_mm_cmpeq_epi32(dy, zero), _mm_cmpgt_epi32(dx, zero)));
    const __m128i bias = _mm_xor_si128(top_left, _mm_set1_epi32(-1));  // 0 on a top or left edge, else -1
    const __m128i ref = _mm_add_epi32(_mm_add_epi32(simd::mullo32(dy, _mm_sub_epi32(x, _mm_set1_epi32(cx))),
                                                    simd::mullo32(dx, _mm_sub_epi32(_mm_set1_epi32(cy), y))),
                                      bias);
    const __m128i sx = _mm_slli_epi32(_mm_sub_epi32(zero, dy), kSubpixelBits), sy = _mm_slli_epi32(dx, kSubpixelBits);
    edge_ref_lanes = ref;
    edge_d_lanes = _mm_packs_epi32(dx, dy);  // exact: |d| <= kEdges32MaxExtent
    if (small_box) {
      // A box of at most 4x4 pixel centres: each edge at the four centres (min_x + dx, min_y + dy) of
      // a row in lanes dx; the covered centres of a row are the lanes where no edge is negative. All
      // four rows, without a branch on the box's height; centres outside the box are masked off below.
      // (AVX2 builds set up most triangles in triangle_list_setup.h; this form serves the rest.)
      unsigned found = 0;  // bit dx + 8 * dy
      // The x step times dx = 0..3 as masked adds: SSE2 has no 32-bit lane multiply (simd::mullo32
      // emulates one there with twice the instructions).
      const __m128i from1 = _mm_setr_epi32(0, -1, -1, -1), from2 = _mm_setr_epi32(0, 0, -1, -1);
      const __m128i from3 = _mm_setr_epi32(0, 0, 0, -1);
      __m128i row[3], down[3];
      const auto edge = [&](auto lane) {  // edge `lane` at the first row's centres
        constexpr int k = decltype(lane)::value, broadcast = _MM_SHUFFLE(k, k, k, k);
        const __m128i step = _mm_shuffle_epi32(sx, broadcast);
        const __m128i times_dx =
            _mm_add_epi32(_mm_add_epi32(_mm_and_si128(step, from1), _mm_and_si128(step, from2)), _mm_and_si128(step, from3));
        row[k] = _mm_add_epi32(_mm_shuffle_epi32(ref, broadcast), times_dx);
        down[k] = _mm_shuffle_epi32(sy, broadcast);
      };
      edge(std::integral_constant<int, 0>{});
      edge(std::integral_constant<int, 1>{});
      edge(std::integral_constant<int, 2>{});
      for (int r = 0; r < kSmallBoxPixels; ++r) {
        const __m128i any_negative = _mm_or_si128(_mm_or_si128(row[0], row[1]), row[2]);
        found |= (~unsigned(_mm_movemask_ps(_mm_castsi128_ps(any_negative))) & 0xFu) << (8 * r);
        for (int i = 0; i < 3; ++i) row[i] = _mm_add_epi32(row[i], down[i]);
      }
      const unsigned columns = ((2u << (max_x - min_x)) - 1u) * 0x01010101u;
      const unsigned rows = 0xFFFFFFFFu >> (8 * (kSmallBoxPixels - 1 - (max_y - min_y)));
      box_coverage = found & columns & rows;
      covers = box_coverage != 0;
    }
#else
    for (int i = 0; i < 3; ++i) {
      const int j = i == 2 ? 0 : i + 1;
      const std::int32_t dx = vx[j] - vx[i], dy = vy[j] - vy[i];
      const std::uint32_t bias = std::uint32_t(int(dy < 0) | (int(dy == 0) & int(dx > 0))) - 1u;
      edge_ref[i] = std::uint32_t(dy) * std::uint32_t(vx[i] - cx) + std::uint32_t(dx) * std::uint32_t(cy - vy[i]) + bias;
      edge_sx[i] = std::uint32_t(-dy) * kSubpixelOne;
      edge_sy[i] = std::uint32_t(dx) * kSubpixelOne;
      edge_d[i] = std::int16_t(dx), edge_d[4 + i] = std::int16_t(dy);
    }
    if (small_box) {
      for (std::int32_t py = 0; py <= max_y - min_y; ++py)
        for (std::int32_t px = 0; px <= max_x - min_x; ++px) {
          std::uint32_t all = 0;
          for (int i = 0; i < 3; ++i) all |= edge_ref[i] + edge_sx[i] * std::uint32_t(px) + edge_sy[i] * std::uint32_t(py);
          if (std::int32_t(all) >= 0) box_coverage |= 1u << (px + 8 * py);
        }
      covers = box_coverage != 0;
    }
#endif
  } else if (small_box) {
    covers = false;
    for (std::int32_t py = min_y; py <= max_y && !covers; ++py)
      for (std::int32_t px = min_x; px <= max_x && !covers; ++px) covers = covers_centre(vx, vy, px, py);
  }
  // A box of at most 4x4 pixel centres (kSmallBoxPixels; nearly every triangle at high factors) whose
  // centres the triangle does not cover (tested exactly, as the rasterizer will) is dropped before its
  // planes are built and it is binned. The image and the PS invocations cannot change; only the work does.
  if (!covers) return;
  // Built in place; every field the rasterizer reads of a triangle is written.
  ScreenPrimitive<N>& p = chunk.append_primitive();
  p.kind = PrimitiveKind::triangle;
  p.min_x = min_x, p.max_x = max_x, p.min_y = min_y, p.max_y = max_y;
  if (edges32) {
#if defined(__SSE2__)
    // Straight from the lanes: reading back a vector store in pieces stalls store forwarding.
    static_assert(offsetof(SmallTriangleEdges, dy) == offsetof(SmallTriangleEdges, dx) + 8);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p.edges.dx.data()), edge_d_lanes);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(p.edges.ref.data()), edge_ref_lanes);
    p.edges.ref[2] = _mm_cvtsi128_si32(_mm_shuffle_epi32(edge_ref_lanes, _MM_SHUFFLE(2, 2, 2, 2)));
#else
    for (int i = 0; i < 3; ++i) {
      p.edges.ref[i] = std::int32_t(edge_ref[i]);
      p.edges.dx[i] = edge_d[i];
      p.edges.dy[i] = edge_d[4 + i];
    }
#endif
  } else {
    for (int i = 0; i < 3; ++i) {
      p.xy.x[i] = vx[i];
      p.xy.y[i] = vy[i];
    }
  }
  p.edges32 = edges32;
  p.box_coverage = box_coverage;
  // Plane equations from the snapped positions, in pixels.
  const float inv_sub = 1.0f / float(kSubpixelOne);
  const float x1 = float(vx[1] - vx[0]) * inv_sub, y1 = float(vy[1] - vy[0]) * inv_sub;
  const float x2 = float(vx[2] - vx[0]) * inv_sub, y2 = float(vy[2] - vy[0]) * inv_sub;
  const float inv_area = 1.0f / (x1 * y2 - x2 * y1);
  // For z, 1/w and each attribute / w: the value at vertex 0 and its x and y slopes, four values at a
  // time in lanes, each lane the scalar expression
  //   (a0, ((a1 - a0) * y2 - (a2 - a0) * y1) * inv_area, ((a2 - a0) * x1 - (a1 - a0) * x2) * inv_area).
  // (The values come straight from the vertices' plane_values: assembling them here lane by lane and
  // loading them as vectors stalls on store forwarding.)
  constexpr std::size_t kGroups = (N + 5) / 4;
  const float* value[3] = {v[0]->plane_values.data(), v[1]->plane_values.data(), v[2]->plane_values.data()};
  std::array<float, 4 * kGroups> slope_x, slope_y;
  {
    using simd::F4;
    const F4 fx1 = F4::splat(x1), fy1 = F4::splat(y1), fx2 = F4::splat(x2), fy2 = F4::splat(y2);
    const F4 fia = F4::splat(inv_area);
    for (std::size_t g = 0; g < kGroups; ++g) {
      const F4 a0 = F4::load_at(&value[0][4 * g]), a1 = F4::load_at(&value[1][4 * g]), a2 = F4::load_at(&value[2][4 * g]);
      const F4 d1 = a1 - a0, d2 = a2 - a0;
      ((d1 * fy2 - d2 * fy1) * fia).store_at(&slope_x[4 * g]);
      ((d2 * fx1 - d1 * fx2) * fia).store_at(&slope_y[4 * g]);
    }
  }
  p.origin_x = float(vx[0]) * inv_sub;
  p.origin_y = float(vy[0]) * inv_sub;
  p.z = {value[0][0], slope_x[0], slope_y[0]};
  p.inv_w = {value[0][1], slope_x[1], slope_y[1]};
  for (std::size_t k = 0; k < N; ++k) {
    p.attributes[0][k] = value[0][2 + k];
    p.attributes[1][k] = slope_x[2 + k];
    p.attributes[2][k] = slope_y[2 + k];
  }
  p.front_face = front;
  p.primitive_id = primitive_id;
  bin_last(c, chunk);
}

// setup_triangle's path for a triangle that needs clipping (or is drawn as wireframe): clipped to a
// fan, each piece set up as setup_snapped_triangle does.
template <std::size_t N>
[[gnu::noinline]] void setup_clipped_triangle(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& v0,
                                              const SetupVertex<N>& v1, const SetupVertex<N>& v2, unsigned needs,
                                              std::uint32_t primitive_id) {
  ClipPolygon<N> poly;
  poly.v[0] = v0.clip, poly.v[1] = v1.clip, poly.v[2] = v2.clip;
  poly.count = 3;
  if (needs) clip_polygon(poly, needs, c.guard);
  SetupVertex<N> s[std::tuple_size_v<decltype(poly.v)>];
  for (int k = 0; k < poly.count; ++k) s[k] = make_setup_vertex(c, poly.v[k], true);
  for (int k = 1; k + 1 < poly.count; ++k) {
    ++chunk.statistics.CPrimitives;
    if (c.fill == FillMode::wireframe) {
      // Only the polygon's own edges: the fan's inner diagonals are not drawn.
      const SetupVertex<N>* t[3] = {&s[0], &s[k], &s[k + 1]};
      for (int e = 0; e < 3; ++e) {
        const bool inner = (e == 0 && k > 1) || (e == 2 && k + 2 < poly.count);
        if (!inner) setup_line_window(c, chunk, *t[e], *t[(e + 1) % 3], primitive_id);
      }
      continue;
    }
    setup_snapped_triangle(c, chunk, s[0], s[k], s[k + 1], primitive_id);
  }
}

}  // namespace detail

// Triangle: counts one CInvocation and a CPrimitive per emitted triangle; appends to `chunk`. Inlined
// into the caller's loop over a pattern's triangles; the rare clipping path is a call.
template <std::size_t N>
[[gnu::always_inline]] inline void setup_triangle(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& v0,
                                                  const SetupVertex<N>& v1, const SetupVertex<N>& v2,
                                                  std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  // D3D11 discards primitives with a NaN or infinite position coordinate.
  if (!v0.finite || !v1.finite || !v2.finite) return;
  if (v0.view_code & v1.view_code & v2.view_code) return;  // wholly outside one plane of the view volume
  const unsigned needs = v0.clip_code | v1.clip_code | v2.clip_code;
  if (needs == 0 && c.fill == FillMode::solid) {
    ++chunk.statistics.CPrimitives;
    detail::setup_snapped_triangle(c, chunk, v0, v1, v2, primitive_id);
    return;
  }
  detail::setup_clipped_triangle(c, chunk, v0, v1, v2, needs, primitive_id);
}

template <std::size_t N>
void setup_line(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& a, const SetupVertex<N>& b,
                std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  if (!a.finite || !b.finite) return;
  if (a.view_code & b.view_code) return;
  const unsigned needs = a.clip_code | b.clip_code;
  if (needs == 0) {
    ++chunk.statistics.CPrimitives;
    detail::setup_line_window(c, chunk, a, b, primitive_id);
    return;
  }
  ClipVertex<N> ca = a.clip, cb = b.clip;
  if (!clip_segment(ca, cb, needs, c.guard)) return;
  ++chunk.statistics.CPrimitives;
  detail::setup_line_window(c, chunk, make_setup_vertex(c, ca, true), make_setup_vertex(c, cb, true), primitive_id);
}

template <std::size_t N>
void setup_point(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>& a, std::uint32_t primitive_id) {
  ++chunk.statistics.CInvocations;
  if (!a.finite || a.view_code) return;
  ++chunk.statistics.CPrimitives;
  ScreenPrimitive<N> p;
  p.kind = PrimitiveKind::point;
  p.primitive_id = primitive_id;
  detail::copy_vertex(a, p, 0);
  // A point lights the one pixel it lies in.
  const std::int32_t px = p.xy.x[0] >> kSubpixelBits, py = p.xy.y[0] >> kSubpixelBits;
  p.min_x = std::max(px, c.clip_min_x), p.max_x = std::min(px, c.clip_max_x);
  p.min_y = std::max(py, c.clip_min_y), p.max_y = std::min(py, c.clip_max_y);
  if (p.min_x > p.max_x || p.min_y > p.max_y) return;
  detail::bin(c, chunk, p);
}

}  // namespace tessera
