// Setup of a triangle list, eight triangles at a time in AVX2 lanes (one triangle per lane).
//
// setup_triangle (primitive_setup.h) handles one triangle; at high tessellation factors it runs once per
// pixel or so and was half of a frame's instructions, most of them moving one triangle's few values
// between scalar registers. Here each step of setup_snapped_triangle (signed area, culling, the pixel box,
// edge functions, the covered centres of a small box, the plane equations, the tile of the box) is one
// vector operation for eight triangles, each lane computing the scalar expression on the same operands
// in the same order, integer arithmetic modulo 2^32 where the scalar path's values fit: every record, bin
// entry and statistic has the bits the scalar path gives (a test compares the two on triangles of every
// kind).
//
// Lanes run the common case only: all three vertices finite and inside the clipping volume (clip code 0)
// and a vertex box small enough for 32-bit edge functions (kEdges32MaxExtent). A group of eight with any
// other triangle goes through setup_triangle one triangle at a time, so the chunk keeps draw order. Builds
// without AVX2, and wireframe fill, use setup_triangle throughout. Multisampled targets take the lanes
// too, with setup_multisample_triangle's records.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "pipeline/primitive_setup.h"
#include "pipeline/simd8.h"

namespace tessera {

namespace detail {

#if defined(__AVX2__)

// r[i] holds field i of eight lanes; afterwards r[k] holds lane k's eight fields.
[[gnu::always_inline]] inline void transpose8x8(__m256i (&r)[8]) {
  const __m256i t0 = _mm256_unpacklo_epi32(r[0], r[1]), t1 = _mm256_unpackhi_epi32(r[0], r[1]);
  const __m256i t2 = _mm256_unpacklo_epi32(r[2], r[3]), t3 = _mm256_unpackhi_epi32(r[2], r[3]);
  const __m256i t4 = _mm256_unpacklo_epi32(r[4], r[5]), t5 = _mm256_unpackhi_epi32(r[4], r[5]);
  const __m256i t6 = _mm256_unpacklo_epi32(r[6], r[7]), t7 = _mm256_unpackhi_epi32(r[6], r[7]);
  const __m256i u0 = _mm256_unpacklo_epi64(t0, t2), u1 = _mm256_unpackhi_epi64(t0, t2);
  const __m256i u2 = _mm256_unpacklo_epi64(t1, t3), u3 = _mm256_unpackhi_epi64(t1, t3);
  const __m256i u4 = _mm256_unpacklo_epi64(t4, t6), u5 = _mm256_unpackhi_epi64(t4, t6);
  const __m256i u6 = _mm256_unpacklo_epi64(t5, t7), u7 = _mm256_unpackhi_epi64(t5, t7);
  r[0] = _mm256_permute2x128_si256(u0, u4, 0x20), r[4] = _mm256_permute2x128_si256(u0, u4, 0x31);
  r[1] = _mm256_permute2x128_si256(u1, u5, 0x20), r[5] = _mm256_permute2x128_si256(u1, u5, 0x31);
  r[2] = _mm256_permute2x128_si256(u2, u6, 0x20), r[6] = _mm256_permute2x128_si256(u2, u6, 0x31);
  r[3] = _mm256_permute2x128_si256(u3, u7, 0x20), r[7] = _mm256_permute2x128_si256(u3, u7, 0x31);
}

// A triangle's ScreenPrimitive as 4-byte fields, in memory order; the lanes write records whole.
template <std::size_t N>
struct TriangleRecordLayout {
  using P = ScreenPrimitive<N>;
  static constexpr std::size_t kFields = sizeof(P) / 4;
  static constexpr std::size_t kEdgeDx = offsetof(P, edges) / 4, kEdgeDy = kEdgeDx + 2, kEdgeRef = kEdgeDx + 4;
  static constexpr std::size_t kZ = offsetof(P, z) / 4, kInvW = offsetof(P, inv_w) / 4;
  static constexpr std::size_t kAttributes = offsetof(P, attributes) / 4, kOrigin = offsetof(P, origin_x) / 4;
  static constexpr std::size_t kBox = offsetof(P, min_x) / 4, kPrimitiveId = offsetof(P, primitive_id) / 4;
  static constexpr std::size_t kFlags = offsetof(P, kind) / 4, kCoverage = offsetof(P, box_coverage) / 4;
  static_assert(sizeof(P) % 4 == 0 && offsetof(P, edges) == 0);
  static_assert(offsetof(SmallTriangleEdges, dy) == 8 && offsetof(SmallTriangleEdges, ref) == 16);
  static_assert(kInvW == kZ + 3 && kAttributes == kInvW + 3 && kOrigin == kAttributes + 3 * N);
  static_assert(offsetof(P, origin_y) == 4 * kOrigin + 4 && offsetof(P, min_y) == 4 * kBox + 4);
  static_assert(offsetof(P, max_x) == 4 * kBox + 8 && offsetof(P, max_y) == 4 * kBox + 12);
  // kind, front_face and edges32 are the low three bytes of one field (little-endian x86).
  static_assert(offsetof(P, kind) % 4 == 0 && offsetof(P, front_face) == offsetof(P, kind) + 1 &&
                offsetof(P, edges32) == offsetof(P, kind) + 2 && kCoverage == kFlags + 1);
  static_assert(sizeof(PrimitiveKind) == 1 && std::uint8_t(PrimitiveKind::triangle) == 0);
  static constexpr std::size_t kBlocks = (kFields + 7) / 8;
};

// The fields setup reads from a SetupVertex V, 4 bytes each: those from x to finite (the bool read with
// the padding after it), as kBlocks loads of eight; block b starts at field start(b), the last one ending
// at the span's end (overlapping the one before when the span is not a multiple of eight).
template <class V>
struct VertexFieldSpan {
  static constexpr std::size_t kBegin = offsetof(V, x);
  static constexpr std::size_t kFields = (offsetof(V, finite) + 4 - kBegin) / 4;
  static constexpr std::size_t kBlocks = (kFields + 7) / 8;
  static constexpr std::size_t start(std::size_t b) { return b + 1 < kBlocks ? 8 * b : kFields - 8; }
  static constexpr std::size_t block_of(std::size_t i) { return i / 8 < kBlocks ? i / 8 : kBlocks - 1; }
  static_assert(kBegin % 4 == 0 && offsetof(V, finite) % 4 == 0 && sizeof(V) >= offsetof(V, finite) + 4);
  static_assert(offsetof(V, y) == kBegin + 4 && offsetof(V, plane_values) > kBegin && offsetof(V, view_code) > kBegin &&
                offsetof(V, clip_code) > kBegin && kFields >= 8);
};

// a <= b in each 32-bit lane (all ones or zero).
[[gnu::always_inline]] inline __m256i cmple(__m256i a, __m256i b) {
  return _mm256_xor_si256(_mm256_cmpgt_epi32(a, b), _mm256_set1_epi32(-1));
}

// The low 16 bits of `lo` and of `hi` in one lane each (an edge's dx or dy fits in 16 bits exactly).
[[gnu::always_inline]] inline __m256i pack16(__m256i lo, __m256i hi) {
  return _mm256_or_si256(_mm256_and_si256(lo, _mm256_set1_epi32(0xFFFF)), _mm256_slli_epi32(hi, 16));
}

// The fields x..finite of the vertices of eight triangles (indices: 24, three per triangle), loaded
// eight at a time and transposed so that block[v][b][i] holds field 8b + i (VertexFieldSpan::start) of
// vertex slot v in each lane: 48 loads and six 8x8 transposes instead of 30 gathers, which cost several
// times as much per element. The last block of eight ends at the span's end and may overlap the one
// before.
template <class V>
[[gnu::always_inline]] inline void load_vertex_fields(const char* base, const std::uint32_t* indices,
                                                      __m256i (&block)[3][VertexFieldSpan<V>::kBlocks][8]) {
  using VF = VertexFieldSpan<V>;
  for (std::size_t v = 0; v < 3; ++v) {
    const char* at[8];
    for (std::size_t k = 0; k < 8; ++k) at[k] = base + std::size_t(indices[3 * k + v]) * sizeof(V) + VF::kBegin;
    for (std::size_t b = 0; b < VF::kBlocks; ++b) {
      for (std::size_t k = 0; k < 8; ++k)
        block[v][b][k] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(at[k] + 4 * VF::start(b)));
      transpose8x8(block[v][b]);
    }
  }
}

// The covered centres of each lane's pixel box when it is at most 4x4 (ScreenPrimitive::box_coverage),
// as setup_snapped_triangle's coverage bits (0 in lanes with larger boxes). Lanes of small boxes with
// no covered centre leave `keep`. Inlined into setup_triangle_list, whose registers it shares.
[[gnu::always_inline]] inline __m256i small_box_coverage(const __m256i (&dx)[3], const __m256i (&dy)[3],
                                                         const __m256i (&ref)[3], __m256i min_x, __m256i max_x,
                                                         __m256i min_y, __m256i max_y, __m256i& keep) {
  const __m256i zero = _mm256_setzero_si256(), ones = _mm256_set1_epi32(-1);
  const __m256i three = _mm256_set1_epi32(kSmallBoxPixels - 1);
  const __m256i width_less_one = _mm256_sub_epi32(max_x, min_x), height_less_one = _mm256_sub_epi32(max_y, min_y);
  const __m256i small_box = _mm256_and_si256(cmple(width_less_one, three), cmple(height_less_one, three));
  if (_mm256_testz_si256(small_box, keep)) return zero;
  __m256i step_x[3], step_y[3], row[3];
  for (int i = 0; i < 3; ++i) {
    step_x[i] = _mm256_slli_epi32(_mm256_sub_epi32(zero, dy[i]), kSubpixelBits);
    step_y[i] = _mm256_slli_epi32(dx[i], kSubpixelBits);
    row[i] = ref[i];
  }
  __m256i found = zero;
  for (int py = 0; py < kSmallBoxPixels; ++py) {
    __m256i e[3] = {row[0], row[1], row[2]};
    for (int px = 0; px < kSmallBoxPixels; ++px) {
      const __m256i any_negative = _mm256_srai_epi32(_mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]), 31);
      found = _mm256_or_si256(found, _mm256_andnot_si256(any_negative, _mm256_set1_epi32(int(1u << (px + 8 * py)))));
      for (int i = 0; i < 3; ++i) e[i] = _mm256_add_epi32(e[i], step_x[i]);
    }
    for (int i = 0; i < 3; ++i) row[i] = _mm256_add_epi32(row[i], step_y[i]);
  }
  // setup_snapped_triangle's column and row masks; srlv gives 0 for the counts of larger boxes.
  const __m256i columns = _mm256_mullo_epi32(
      _mm256_sub_epi32(_mm256_sllv_epi32(_mm256_set1_epi32(2), width_less_one), _mm256_set1_epi32(1)),
      _mm256_set1_epi32(0x01010101));
  const __m256i rows = _mm256_srlv_epi32(ones, _mm256_slli_epi32(_mm256_sub_epi32(three, height_less_one), 3));
  const __m256i coverage = _mm256_and_si256(_mm256_and_si256(found, small_box), _mm256_and_si256(columns, rows));
  keep = _mm256_andnot_si256(_mm256_and_si256(small_box, _mm256_cmpeq_epi32(coverage, zero)), keep);
  return coverage;
}

// Stores the kept lanes' records (fields `f`, TriangleRecordLayout L) to consecutive new slots of the
// chunk and bins each by its pixel box, in lane order; one-tile lanes straight from the lanes.
// Each lane's record is written whole: the other lanes go to the slot after the kept ones (storage past
// primitive_count, overwritten later). Blocks are stored last first: the last block's 32 bytes may run
// past the record into the next slot's first field, which the first block then writes. The caller
// leaves room for the eight slots, a spare one and that overrun.
template <class L, std::size_t N>
[[gnu::always_inline]] inline void store_and_bin(const TileGrid& g, ChunkBuffer<N>& chunk, __m256i (&f)[L::kBlocks * 8],
                                                 unsigned kept, __m256i min_x, __m256i max_x, __m256i min_y,
                                                 __m256i max_y) {
  const __m128i shift = _mm_cvtsi32_si128(g.shift);
  const auto tile_of = [&](__m256i p) {  // TileGrid::tile_of in each lane
    return _mm256_srl_epi32(_mm256_mullo_epi32(p, _mm256_set1_epi32(int(g.reciprocal))), shift);
  };
  const __m256i tx0 = tile_of(min_x), tx1 = tile_of(max_x), ty0 = tile_of(min_y), ty1 = tile_of(max_y);
  const std::size_t first = chunk.primitive_count, kept_count = std::size_t(std::popcount(kept));
  char* slot[8];
  for (unsigned k = 0; k < 8; ++k) {
    const bool kept_k = (kept >> k) & 1u;
    const std::size_t index = kept_k ? first + std::size_t(std::popcount(kept & ((1u << k) - 1u))) : first + kept_count;
    slot[k] = reinterpret_cast<char*>(&chunk.primitives[index]);
  }
  for (std::size_t b = L::kBlocks; b-- > 0;) {
    __m256i r[8];
    for (int k = 0; k < 8; ++k) r[k] = f[8 * b + std::size_t(k)];
    transpose8x8(r);
    for (int k = 0; k < 8; ++k) _mm256_storeu_si256(reinterpret_cast<__m256i*>(slot[k] + 32 * b), r[k]);
  }
  chunk.primitive_count = first + kept_count;
  alignas(32) std::int32_t tiles[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(tiles),
                     _mm256_add_epi32(_mm256_mullo_epi32(ty0, _mm256_set1_epi32(g.columns)), tx0));
  const unsigned one_tile = unsigned(_mm256_movemask_ps(
      _mm256_castsi256_ps(_mm256_and_si256(_mm256_cmpeq_epi32(tx0, tx1), _mm256_cmpeq_epi32(ty0, ty1)))));
  std::uint32_t index = std::uint32_t(first);
  for (unsigned rest = kept; rest != 0; rest &= rest - 1, ++index) {
    const int k = std::countr_zero(rest);
    if ((one_tile >> k) & 1u)
      chunk.entries.emplace_back(std::uint32_t(tiles[k]), index);
    else
      bin_primitive(g, chunk, index);
  }
}

#endif

}  // namespace detail

// Sets up `count` triangles of a list: triangle t has vertices vertices[indices[3t]], [3t + 1] and
// [3t + 2] (each below vertex_count) and primitive id first_id + t * id_step. The chunk gets what
// calling setup_triangle on each triangle in order gives it: the same records, bin entries and
// statistics.
// The loads, the small-box coverage and the record stores are always-inline helpers: the group's
// transposed vertex fields and lane masks stay in registers from the vertex loads to the stores.
template <std::size_t N>
void setup_triangle_list(const SetupContext& c, ChunkBuffer<N>& chunk, const SetupVertex<N>* vertices,
                         [[maybe_unused]] std::size_t vertex_count, const std::uint32_t* indices, std::size_t count,
                         std::uint32_t first_id, std::uint32_t id_step) {
  const auto one_by_one = [&](std::size_t k) {
    setup_triangle<N>(c, chunk, vertices[indices[3 * k]], vertices[indices[3 * k + 1]], vertices[indices[3 * k + 2]],
                      first_id + std::uint32_t(k) * id_step);
  };
  std::size_t t = 0;
#if defined(__AVX2__)
  using L = detail::TriangleRecordLayout<N>;
  using V = SetupVertex<N>;
  const bool lanes = c.fill == FillMode::solid;
  // A multisampled target's triangles (setup_multisample_triangle's records, with their edges kept in
  // 32 bits): the box of the pixels whose samples the vertex box may reach (sample_reach, at most half
  // a pixel from their pixel's centre), no coverage test here (raster_multisample.h tests each sample).
  // Every sample point then lies within a pixel of the vertex box, inside kEdges32MaxExtent's margin.
  const bool multisampled = c.samples > 1;
  const SampleReach reach = sample_reach(c.samples);  // all 0 for one sample
  const __m256i reach_min_x = _mm256_set1_epi32(16 * reach.min_x), reach_max_x = _mm256_set1_epi32(16 * reach.max_x);
  const __m256i reach_min_y = _mm256_set1_epi32(16 * reach.min_y), reach_max_y = _mm256_set1_epi32(16 * reach.max_y);
  const char* const base = reinterpret_cast<const char*>(vertices);
  // A vertex's fields from x to finite, 4 bytes each (`finite` read with the padding after it), one
  // vector per field and vertex slot (load_vertex_fields).
  using VF = detail::VertexFieldSpan<V>;
  const __m256i zero = _mm256_setzero_si256(), ones = _mm256_set1_epi32(-1);
  const __m256i id_lanes =
      _mm256_mullo_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32(int(id_step)));
  constexpr std::size_t kSlack = 10;  // eight lanes' slots, a spare slot, and the last block's overrun
  for (; lanes && t + 8 <= count; t += 8) {
    __m256i block[3][VF::kBlocks][8];
    detail::load_vertex_fields<V>(base, indices + 3 * t, block);
    const auto field = [&](std::size_t v, std::size_t offset) {
      const std::size_t i = (offset - VF::kBegin) / 4, b = VF::block_of(i);
      return block[v][b][i - VF::start(b)];
    };
    // setup_triangle's tests. `finite` is a bool; its field holds the padding after it too.
    const __m256i clip_or =
        _mm256_or_si256(_mm256_or_si256(field(0, offsetof(V, clip_code)), field(1, offsetof(V, clip_code))),
                        field(2, offsetof(V, clip_code)));
    const __m256i finite = _mm256_and_si256(
        _mm256_and_si256(_mm256_and_si256(field(0, offsetof(V, finite)), field(1, offsetof(V, finite))),
                         field(2, offsetof(V, finite))),
        _mm256_set1_epi32(0xFF));
    const __m256i x0 = field(0, offsetof(V, x)), y0 = field(0, offsetof(V, y));
    const __m256i xb = field(1, offsetof(V, x)), yb = field(1, offsetof(V, y));
    const __m256i xd = field(2, offsetof(V, x)), yd = field(2, offsetof(V, y));
    const __m256i lx = _mm256_min_epi32(_mm256_min_epi32(x0, xb), xd),
                  hx = _mm256_max_epi32(_mm256_max_epi32(x0, xb), xd);
    const __m256i ly = _mm256_min_epi32(_mm256_min_epi32(y0, yb), yd),
                  hy = _mm256_max_epi32(_mm256_max_epi32(y0, yb), yd);
    const __m256i max_extent = _mm256_set1_epi32(kEdges32MaxExtent);
    // Lanes for setup_triangle: clipped, not finite, or too large for 32-bit edges.
    const __m256i scalar = _mm256_or_si256(
        _mm256_or_si256(_mm256_xor_si256(_mm256_cmpeq_epi32(clip_or, zero), ones), _mm256_cmpeq_epi32(finite, zero)),
        _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_sub_epi32(hx, lx), max_extent),
                        _mm256_cmpgt_epi32(_mm256_sub_epi32(hy, ly), max_extent)));
    // A group also goes one triangle at a time when the chunk's storage has no room for the lanes'
    // records (below): append_primitive() then grows it as setup_triangle alone would, so the chunk
    // holds no more storage than the scalar path needs.
    if (!_mm256_testz_si256(scalar, scalar) || chunk.primitives.size() < chunk.primitive_count + kSlack) {
      for (std::size_t k = t; k < t + 8; ++k) one_by_one(k);
      continue;
    }
    const __m256i view_and =
        _mm256_and_si256(_mm256_and_si256(field(0, offsetof(V, view_code)), field(1, offsetof(V, view_code))),
                         field(2, offsetof(V, view_code)));
    const __m256i inside = _mm256_cmpeq_epi32(view_and, zero);  // not wholly outside one view-volume plane
    chunk.statistics.CInvocations += 8;
    chunk.statistics.CPrimitives += unsigned(std::popcount(unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(inside)))));
    // setup_snapped_triangle, lane by lane, its integer and plane steps shared (primitive_setup.h's
    // templates over the lane type). The area fits in 32 bits: every extent is at most kEdges32MaxExtent.
    const __m256i area = _mm256_sub_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(xb, x0), _mm256_sub_epi32(yd, y0)),
                                          _mm256_mullo_epi32(_mm256_sub_epi32(xd, x0), _mm256_sub_epi32(yb, y0)));
    const __m256i positive = _mm256_cmpgt_epi32(area, zero);
    const __m256i front = c.front_ccw ? _mm256_xor_si256(positive, ones) : positive;
    __m256i keep = _mm256_andnot_si256(_mm256_cmpeq_epi32(area, zero), inside);
    if (c.cull == CullMode::back) keep = _mm256_and_si256(keep, front);
    if (c.cull == CullMode::front) keep = _mm256_andnot_si256(front, keep);
    using simd::I8;
    const detail::PixelBox<I8> box =
        detail::clipped_pixel_box(c, I8(_mm256_sub_epi32(lx, reach_max_x)), I8(_mm256_sub_epi32(hx, reach_min_x)),
                                  I8(_mm256_sub_epi32(ly, reach_max_y)), I8(_mm256_sub_epi32(hy, reach_min_y)));
    const __m256i min_x = box.min_x.v, max_x = box.max_x.v, min_y = box.min_y.v, max_y = box.max_y.v;
    keep = _mm256_and_si256(keep, _mm256_and_si256(detail::cmple(min_x, max_x), detail::cmple(min_y, max_y)));
    if (_mm256_testz_si256(keep, keep)) continue;
    // Stored with positive area: vertices 1 and 2 swap places in lanes with negative area.
    const __m256i x1 = _mm256_blendv_epi8(xd, xb, positive), x2 = _mm256_blendv_epi8(xb, xd, positive);
    const __m256i y1 = _mm256_blendv_epi8(yd, yb, positive), y2 = _mm256_blendv_epi8(yb, yd, positive);
    // Edge i from vertex i to vertex i + 1, at the centre of pixel (min_x, min_y), with its top-left bias.
    const __m256i half = _mm256_set1_epi32(kSubpixelOne / 2);
    const I8 cx(_mm256_add_epi32(_mm256_slli_epi32(min_x, kSubpixelBits), half));
    const I8 cy(_mm256_add_epi32(_mm256_slli_epi32(min_y, kSubpixelBits), half));
    const I8 ex[3] = {I8(x0), I8(x1), I8(x2)}, ey[3] = {I8(y0), I8(y1), I8(y2)};
    __m256i dx[3], dy[3], ref[3];
    for (int i = 0; i < 3; ++i) {
      const int j = i == 2 ? 0 : i + 1;
      const detail::Edge32<I8> e = detail::edge32(ex[i], ey[i], ex[j], ey[j], cx, cy);
      dx[i] = e.dx.v, dy[i] = e.dy.v, ref[i] = e.ref.v;
    }
    const __m256i coverage = multisampled ? zero : detail::small_box_coverage(dx, dy, ref, min_x, max_x, min_y, max_y, keep);
    const unsigned kept = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(keep)));
    if (kept == 0) continue;
    // Plane equations from the snapped positions, in pixels (setup_snapped_triangle's expressions).
    __m256i f[L::kBlocks * 8];
    {
      const __m256 inv_sub = _mm256_set1_ps(1.0f / float(kSubpixelOne));
      const auto pixels = [&](__m256i v) { return _mm256_mul_ps(_mm256_cvtepi32_ps(v), inv_sub); };
      const __m256 fx1 = pixels(_mm256_sub_epi32(x1, x0)), fy1 = pixels(_mm256_sub_epi32(y1, y0));
      const __m256 fx2 = pixels(_mm256_sub_epi32(x2, x0)), fy2 = pixels(_mm256_sub_epi32(y2, y0));
      const __m256 inv_area =
          _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sub_ps(_mm256_mul_ps(fx1, fy2), _mm256_mul_ps(fx2, fy1)));
      const auto plane = [&](std::size_t value, std::size_t at0, std::size_t at_x, std::size_t at_y) {
        const std::size_t at = offsetof(V, plane_values) + 4 * value;
        const __m256i b1 = field(1, at), b2 = field(2, at);
        const __m256 a0 = _mm256_castsi256_ps(field(0, at)),
                     a1 = _mm256_castsi256_ps(_mm256_blendv_epi8(b2, b1, positive)),
                     a2 = _mm256_castsi256_ps(_mm256_blendv_epi8(b1, b2, positive));
        using simd::F8;
        const detail::PlaneSlopes<F8> s =
            detail::plane_slopes(F8{a0}, F8{a1}, F8{a2}, F8{fx1}, F8{fy1}, F8{fx2}, F8{fy2}, F8{inv_area});
        f[at0] = _mm256_castps_si256(a0);
        f[at_x] = _mm256_castps_si256(s.x.v);
        f[at_y] = _mm256_castps_si256(s.y.v);
      };
      plane(0, L::kZ, L::kZ + 1, L::kZ + 2);
      plane(1, L::kInvW, L::kInvW + 1, L::kInvW + 2);
      for (std::size_t a = 0; a < N; ++a)
        plane(2 + a, L::kAttributes + a, L::kAttributes + N + a, L::kAttributes + 2 * N + a);
      f[L::kOrigin] = _mm256_castps_si256(pixels(x0));
      f[L::kOrigin + 1] = _mm256_castps_si256(pixels(y0));
    }
    // The edges as setup_snapped_triangle stores them: dx and dy in 16 bits (exact), [3] repeating [2].
    f[L::kEdgeDx] = detail::pack16(dx[0], dx[1]), f[L::kEdgeDx + 1] = detail::pack16(dx[2], dx[2]);
    f[L::kEdgeDy] = detail::pack16(dy[0], dy[1]), f[L::kEdgeDy + 1] = detail::pack16(dy[2], dy[2]);
    for (int i = 0; i < 3; ++i) f[L::kEdgeRef + std::size_t(i)] = ref[i];
    f[L::kBox] = min_x, f[L::kBox + 1] = min_y, f[L::kBox + 2] = max_x, f[L::kBox + 3] = max_y;
    f[L::kPrimitiveId] = _mm256_add_epi32(_mm256_set1_epi32(int(first_id + std::uint32_t(t) * id_step)), id_lanes);
    // kind = triangle (0), front_face, edges32 = true.
    f[L::kFlags] = _mm256_or_si256(_mm256_and_si256(front, _mm256_set1_epi32(1 << 8)), _mm256_set1_epi32(1 << 16));
    f[L::kCoverage] = coverage;
    for (std::size_t k = L::kFields; k < L::kBlocks * 8; ++k) f[k] = zero;
    detail::store_and_bin<L>(c.tiles, chunk, f, kept, min_x, max_x, min_y, max_y);
  }
#endif
  for (; t < count; ++t) one_by_one(t);
}

}  // namespace tessera
