// Render targets: one colour buffer (RGBA8 UNORM or RGBA32F) and one D32F depth buffer, row-major with
// row 0 at the top (D3D's y-down window coordinates), with 1, 2, 4, 8 or 16 samples per pixel.
//
// A single-sampled target is row-major. A multisampled one is stored by 2x2 pixel quads, row-major over
// quads, each quad's samples together: sample s of its four pixels at 4 s + 2 (y & 1) + (x & 1) (a 4x
// quad's depths are one 64-byte line). The rasterizer's quad forms address a sample's 2x2 pixels as they
// address a pixel quad of a single-sampled target (sample_site), a quad's per-sample depth tests and
// writes touch one or two lines (in separate full-image planes they were four or eight streams 8 MB
// apart on a 1080p target), and its samples load as vectors (raster_multisample.h). resolve() averages
// the samples into a single-sampled target.
//
// A clear may be pending (clear_by_tiles): the target is cut into the rasterizer's tiles, and a marked
// tile holds the clear's colour and depth whatever its bytes are, until it is written (prepare_tile,
// finish_clear) or resolved.
//
// Contract: sizes are validated on creation (1..16384 per side, D3D11's largest render target). A
// target is memory only: image files are written by shaders_cpp/image_io/image_file.h. Whole-buffer
// readers (color_bytes, depth_values) refuse a target with a clear pending, by a failed TESSERA_CHECK (a
// caller's mistake); the per-pixel forms expect no pending clear on their pixel (inside a tile the
// rasterizer prepared, or after finish_clear).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/simd4.h"
#include "tessellator/check.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

namespace tessera {

enum class ColorFormat : std::uint8_t { rgba8_unorm, rgba32_float };
// What a resolve writes into its single-sampled target.
enum class ResolvedPlanes : std::uint8_t { color_and_depth, color };

inline constexpr int kMaxRenderTargetSize = 16384;  // D3D11_REQ_RENDER_TO_BUFFER_WINDOW_WIDTH

// D3D11's FLOAT -> UNORM8 conversion: NaN -> 0, clamp to [0, 1], scale by 255, round to nearest.
// Branch-free: max(0, NaN) is 0 with this argument order.
inline std::uint8_t float_to_unorm8(float x) {
  const float c = std::min(std::max(0.0f, x), 1.0f);
  return static_cast<std::uint8_t>(c * 255.0f + 0.5f);
}

class Framebuffer {
 public:
  // Returns nullopt and a one-line reason for an unsupported size.
  static std::optional<Framebuffer> create(int width, int height, ColorFormat format, std::string* error,
                                           int samples = 1);

  int width() const { return width_; }
  int height() const { return height_; }
  ColorFormat format() const { return format_; }
  int samples() const { return samples_; }

  // The single-sampled target of the average of each pixel's samples (D3D11's ResolveSubresource with a
  // box filter): RGBA8 as the rounded mean of the samples' bytes, RGBA32F as their mean summed in sample
  // order; depth is the nearest sample's (overlays test against it). A copy when samples() == 1.
  // ResolvedPlanes::color resolves the colour alone, as ResolveSubresource does (D3D11 resolves no depth
  // format): a frame that only shows or writes its colour does not read its depth samples, half of a
  // resolve's input. The new target's depth is then 1.0 everywhere, as created.
  Framebuffer resolve(ResolvedPlanes planes = ResolvedPlanes::color_and_depth) const;
  // resolve() of rows [y0, y1) into `out`, a single-sampled target of this size and format: disjoint
  // row ranges may be resolved by different threads (Device::resolve does). With ResolvedPlanes::color,
  // out's depth is left as it was.
  void resolve_rows(Framebuffer& out, int y0, int y1, ResolvedPlanes planes = ResolvedPlanes::color_and_depth) const;

  // Ends any pending clear (its tiles are overwritten too).
  void clear(glm::vec4 color, float depth) {
    pending_.reset();
    clear_rows(0, height_, color, depth);
  }
  // Clears rows [y0, y1) only: disjoint row ranges may be cleared by different threads. No clear may
  // be pending (its tiles would later overwrite these rows).
  void clear_rows(int y0, int y1, glm::vec4 color, float depth);

  // A clear written tile by tile, when each is needed (Device::clear): every tile of a grid of
  // `tile_size` pixels (tile i covers x in [(i % columns) t, + t), y in [(i / columns) t, + t), as the
  // rasterizer's TileGrid; t even, 8..1024) is marked, and nothing is written yet. The rasterizer
  // writes a tile's clear just before it enters the tile (prepare_tile), so the tile is in that core's
  // cache for its first primitives rather than in memory (a 1080p 4x target is 66 MB, larger than the
  // last-level cache); resolve() writes a tile that no draw entered from the clear values without
  // reading it. Every pixel a reader sees has the bytes clear() writes. Replaces a pending clear.
  void clear_by_tiles(glm::vec4 color, float depth, int tile_size);
  // The pending clear's tile size and tile count, or 0 when no clear is pending.
  int pending_clear_tile_size() const { return pending_ ? pending_->tile_size : 0; }
  int pending_clear_tiles() const { return pending_ ? int(pending_->marked.size()) : 0; }
  // Writes tile t's pending clear if it is still marked, and unmarks it. Different threads may prepare
  // different tiles at once.
  void prepare_tile(int t);
  // Writes the tiles still marked and ends the pending clear (Device::finish_clear does the writes on
  // its threads first).
  void finish_clear();
  // Ends a pending clear without writing it, for a caller about to write every pixel (a resolve).
  void cancel_clear() { pending_.reset(); }

  // Output merger writes (the caller owns the pixel; different threads write different pixels). These
  // per-pixel forms read sample 0 and write every sample of the pixel (lines, points and overlays are
  // drawn at pixel rate).
  float depth(int x, int y) const { return depth_[index(x, y)]; }
  // The other samples are written out of line: inlined, their loop cost the single-sampled
  // rasterizer's hot loop registers (12 % more instructions on the torus).
  void set_depth(int x, int y, float d) {
    depth_[index(x, y)] = d;
    if (samples_ > 1) [[unlikely]]
      set_other_samples(x, y, d);
  }
  void set_color(int x, int y, glm::vec4 c) {
    set_sample_color(index(x, y), c);
    if (samples_ > 1) [[unlikely]]
      set_other_samples(x, y, c);
  }
  // The pixel's colour: sample 0's, or the mean of its samples on a multisampled target.
  glm::vec4 color(int x, int y) const;

  // Sample s: the index i of a pixel's sample 0 becomes i + sample_offset(s).
  std::size_t sample_offset(int s) const { return std::size_t(s) * 4u; }
  float sample_depth(int x, int y, int s) const { return depth_[index(x, y) + sample_offset(s)]; }
  void set_sample_depth(int x, int y, int s, float d) { depth_[index(x, y) + sample_offset(s)] = d; }

 private:
  [[gnu::noinline]] void set_other_samples(int x, int y, float d);
  [[gnu::noinline]] void set_other_samples(int x, int y, glm::vec4 c);
  void set_sample_color(std::size_t i, glm::vec4 c) {
    if (format_ == ColorFormat::rgba8_unorm) {
      std::uint8_t* p = &color_[i * 4];
      p[0] = float_to_unorm8(c.r);
      p[1] = float_to_unorm8(c.g);
      p[2] = float_to_unorm8(c.b);
      p[3] = float_to_unorm8(c.a);
    } else {
      const float px[4] = {c.r, c.g, c.b, c.a};
      std::memcpy(&color_[i * 16], px, 16);
    }
  }

 public:
  // The 2x2 quad whose top-left pixel is (x, y) lies wholly inside the target: the quad forms below
  // then read and write its two row pairs directly. On a multisampled target x and y are even.
  bool quad_inside(int x, int y) const { return x + 1 < width_ && y + 1 < height_; }
  // Such a quad, addressed once (its depth test and its colour and depth writes share the address):
  // the indices of its top-left pixel and of the pixel below that.
  struct QuadSite {
    std::size_t top = 0, bottom = 0;
  };
  QuadSite quad_site(int x, int y) const {
    if (samples_ == 1) return single_sample_quad_site(x, y);
    const std::size_t i = index(x, y);
    return {i, i + 2u};
  }
  // quad_site on a single-sampled target (the caller knows samples() == 1): rows are width() apart.
  // Inlined into the single-sampled rasterizer's quad loop, where GCC otherwise called quad_site out
  // of line for every quad.
  [[gnu::always_inline]] QuadSite single_sample_quad_site(int x, int y) const {
    const std::size_t i = std::size_t(y) * std::size_t(width_) + std::size_t(x);
    return {i, i + std::size_t(width_)};
  }
  // The same quad's sample s.
  QuadSite sample_site(QuadSite q, int s) const { return {q.top + sample_offset(s), q.bottom + sample_offset(s)}; }
  // Depth of the quad's pixels in lanes k = 0 (x, y), 1 (x + 1, y), 2 (x, y + 1), 3 (x + 1, y + 1).
  simd::F4 depth_quad(QuadSite q) const { return simd::F4::load_pairs(&depth_[q.top], &depth_[q.bottom]); }
  void set_depth_quad(QuadSite q, simd::F4 d) { d.store_pairs(&depth_[q.top], &depth_[q.bottom]); }
  simd::F4 depth_quad(int x, int y) const { return depth_quad(quad_site(x, y)); }
  void set_depth_quad(int x, int y, simd::F4 d) { set_depth_quad(quad_site(x, y), d); }

  // A multisampled quad's samples, 4 * samples() of each from its site's top (sample s of its pixel k
  // at 4 s + k): depths, and colours of an RGBA8 target (4 bytes each).
  float* quad_samples_depth(QuadSite q) { return &depth_[q.top]; }
  std::uint8_t* quad_samples_rgba8(QuadSite q) { return &color_[q.top * 4]; }

  // The output merger for one 2x2 quad: pixel k (as in depth_quad) gets colour c[.][k] where bit k of
  // `mask` is set. The format is checked once per quad and the 16 conversions to RGBA8 are one packed
  // sequence. This form takes a quad inside the target; the (x, y) form below any quad whose masked
  // pixels exist.
  [[gnu::always_inline]] void write_quad(QuadSite q, unsigned mask, const std::array<std::array<float, 4>, 4>& c) {
#if defined(__SSE2__)
    if (format_ == ColorFormat::rgba8_unorm) {
      write_quad_rgba8(q, mask, quad_to_rgba8(c));
      return;
    }
#endif
    write_pixels(q, mask, c);
  }
#if defined(__SSE2__)
  // write_quad on an RGBA8 target of a quad inside it, its colours already packed by quad_to_rgba8 (a
  // multisampled quad writes one shaded colour to several samples, converted once).
  [[gnu::always_inline]] void write_quad_rgba8(QuadSite q, unsigned mask, __m128i px) {
    std::uint8_t* r0 = &color_[q.top * 4];
    std::uint8_t* r1 = &color_[q.bottom * 4];
    __m128i out = px;
    if (mask != 0xFu) {
      const __m128i m = simd::lane_mask(mask);
      const __m128i old = _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r0)),
                                             _mm_loadl_epi64(reinterpret_cast<const __m128i*>(r1)));
      out = _mm_or_si128(_mm_and_si128(m, px), _mm_andnot_si128(m, old));
    }
    _mm_storel_epi64(reinterpret_cast<__m128i*>(r0), out);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(r1), _mm_srli_si128(out, 8));
  }
#endif
  // A quad at `q` (of any sample) that is inside the target or not.
  [[gnu::always_inline]] void write_quad(QuadSite q, bool inside, unsigned mask,
                                         const std::array<std::array<float, 4>, 4>& c) {
    if (inside)
      write_quad(q, mask, c);
    else
      write_pixels(q, mask, c);
  }
  [[gnu::always_inline]] void write_quad(int x, int y, unsigned mask, const std::array<std::array<float, 4>, 4>& c) {
    // Past the last row or column the site's pixels do not exist, and are not in `mask`.
    const QuadSite q = quad_site(x, y);
    if (quad_inside(x, y))
      write_quad(q, mask, c);
    else
      write_pixels(q, mask, c);
  }

#if defined(__SSE2__)
  // float_to_unorm8 on a quad's 16 values, as RGBA8 bytes in pixel order: max(x, 0) and min(., 1) with
  // std::max/std::min's NaN behaviour (maxps returns its second operand for NaN), scale and add 0.5,
  // then (after a transpose to pixel order, which moves bits only) truncation, as the scalar cast does.
  // The results are in 0..255, so the saturating packs to 16 and 8 bits keep them unchanged. Public: a
  // multisampled quad converts its colour once for all its samples (write_quad_rgba8).
  [[gnu::always_inline]] static __m128i quad_to_rgba8(const std::array<std::array<float, 4>, 4>& c) {
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), scale = _mm_set1_ps(255.0f),
                 half = _mm_set1_ps(0.5f);
    __m128 v[4];
    for (std::size_t ch = 0; ch < 4; ++ch)
      v[ch] = _mm_add_ps(_mm_mul_ps(_mm_min_ps(one, _mm_max_ps(_mm_loadu_ps(c[ch].data()), zero)), scale), half);
    _MM_TRANSPOSE4_PS(v[0], v[1], v[2], v[3]);  // v[k]: pixel k's r, g, b, a
    return _mm_packus_epi16(_mm_packs_epi32(_mm_cvttps_epi32(v[0]), _mm_cvttps_epi32(v[1])),
                            _mm_packs_epi32(_mm_cvttps_epi32(v[2]), _mm_cvttps_epi32(v[3])));
  }
#endif

  // Raw storage, for hashing and image output: RGBA8 is 4 bytes per pixel, RGBA32F 16. No clear may be
  // pending.
  const std::vector<std::uint8_t>& color_bytes() const {
    expect_no_pending_clear("color_bytes");
    return color_;
  }
  const std::vector<float>& depth_values() const {
    expect_no_pending_clear("depth_values");
    return depth_;
  }
  std::size_t bytes() const { return color_.size() + depth_.size() * sizeof(float); }

 private:
  Framebuffer(int w, int h, ColorFormat f, int samples);
  // The element of pixel (x, y), sample 0 (the layouts above).
  std::size_t index(int x, int y) const {
    if (samples_ == 1) return std::size_t(y) * std::size_t(width_) + std::size_t(x);
    return quad_index(x >> 1, y >> 1) + std::size_t(2 * (y & 1) + (x & 1));
  }
  // A multisampled target's first element of quad (qx, qy) (pixels 2 qx.., 2 qy..).
  std::size_t quad_index(int qx, int qy) const {
    return (std::size_t(qy) * std::size_t(quads_per_row()) + std::size_t(qx)) * std::size_t(4 * samples_);
  }
  int quads_per_row() const { return (width_ + 1) / 2; }
  // Elements of storage: a multisampled target's quads pad an odd width or height.
  static std::size_t elements(int w, int h, int samples) {
    return samples == 1 ? std::size_t(w) * std::size_t(h)
                        : std::size_t((w + 1) / 2) * std::size_t((h + 1) / 2) * std::size_t(4 * samples);
  }

  // Pixel k of the quad at `q` gets colour c[.][k] where bit k of `mask` is set, pixel by pixel.
  void write_pixels(QuadSite q, unsigned mask, const std::array<std::array<float, 4>, 4>& c) {
    const std::size_t pixel[4] = {q.top, q.top + 1, q.bottom, q.bottom + 1};
    if (format_ == ColorFormat::rgba8_unorm) {
#if defined(__SSE2__)
      alignas(16) std::uint8_t bytes[4][4];  // [pixel][channel]
      _mm_store_si128(reinterpret_cast<__m128i*>(bytes), quad_to_rgba8(c));
#else
      std::uint8_t bytes[4][4];  // [pixel][channel]
      for (int ch = 0; ch < 4; ++ch)
        for (int k = 0; k < 4; ++k) bytes[k][ch] = float_to_unorm8(c[std::size_t(ch)][std::size_t(k)]);
#endif
      for (int k = 0; k < 4; ++k)
        if (mask & (1u << k)) std::memcpy(&color_[pixel[k] * 4], bytes[k], 4);
    } else {
      for (int k = 0; k < 4; ++k)
        if (mask & (1u << k)) {
          const float px[4] = {c[0][std::size_t(k)], c[1][std::size_t(k)], c[2][std::size_t(k)], c[3][std::size_t(k)]};
          std::memcpy(&color_[pixel[k] * 16], px, 16);
        }
    }
  }

  // A clear's values as the target stores them: the colour's bytes (4 or 16) and the depth.
  struct StoredClear {
    std::uint8_t color[16] = {};
    float depth = 1.0f;
  };
  StoredClear stored_clear(glm::vec4 c, float d) const;
  // Elements [begin, end) of the colour buffer, and of the depth buffer unless `planes` is colour
  // only, set to `v`.
  void fill(std::size_t begin, std::size_t end, const StoredClear& v,
            ResolvedPlanes planes = ResolvedPlanes::color_and_depth);
  // Pixels [x0, x1) x [y0, y1) set to `v`, as fill; on a multisampled target x0 and y0 are even (whole
  // quads: a quad padding an odd width or height is filled with its pixels).
  void fill_rect(int x0, int y0, int x1, int y1, const StoredClear& v,
                 ResolvedPlanes planes = ResolvedPlanes::color_and_depth);
  // What resolve_block makes of a pixel whose samples all hold `v`.
  StoredClear resolved_clear(const StoredClear& v) const;
  // resolve_rows of pixels [x0, x1) x [y0, y1), ignoring any pending clear; x0 even on a multisampled
  // target.
  void resolve_block(Framebuffer& out, int x0, int x1, int y0, int y1, ResolvedPlanes planes) const;
  void expect_no_pending_clear(const char* reader) const {
    TESSERA_CHECK(!pending_, "Framebuffer::", reader, "with a clear pending");
  }

  struct PendingClear {
    StoredClear value;
    int tile_size = 64, columns = 0;
    std::vector<std::uint8_t> marked;  // by tile
  };

  int width_ = 0, height_ = 0;
  ColorFormat format_ = ColorFormat::rgba8_unorm;
  std::vector<std::uint8_t> color_;
  std::vector<float> depth_;
  int samples_ = 1;
  std::optional<PendingClear> pending_;
};

}  // namespace tessera
