// Render targets: one colour buffer (RGBA8 UNORM or RGBA32F) and one D32F depth buffer, row-major with
// row 0 at the top (D3D's y-down window coordinates).
//
// Contract: sizes are validated on creation (1..16384 per side, D3D11's largest render target);
// writes to an image file go through OpenImageIO into a temporary beside the target, renamed over it
// only when complete, so a failed write never leaves a half-written file.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

enum class ColorFormat : std::uint8_t { rgba8_unorm, rgba32_float };

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
  static std::optional<Framebuffer> create(int width, int height, ColorFormat format, std::string* error);

  int width() const { return width_; }
  int height() const { return height_; }
  ColorFormat format() const { return format_; }

  void clear(glm::vec4 color, float depth);

  // Output merger writes (the caller owns the pixel; different threads write different pixels).
  float depth(int x, int y) const { return depth_[index(x, y)]; }
  void set_depth(int x, int y, float d) { depth_[index(x, y)] = d; }
  void set_color(int x, int y, glm::vec4 c) {
    const std::size_t i = index(x, y);
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
  glm::vec4 color(int x, int y) const;

  // The output merger for one 2x2 quad whose top-left pixel is (x, y): pixel (x + (k & 1), y + (k >> 1))
  // gets colour c[.][k] where bit k of `mask` is set (only those pixels need to exist). The format is
  // checked once per quad and the 16 conversions are one loop, which vectorizes.
  void write_quad(int x, int y, unsigned mask, const std::array<std::array<float, 4>, 4>& c) {
    if (format_ == ColorFormat::rgba8_unorm) {
      std::uint8_t bytes[4][4];  // [lane][channel]
#if defined(__SSE2__)
      // float_to_unorm8 on 16 values: max(x, 0) and min(., 1) with std::max/std::min's NaN behaviour
      // (maxps returns its second operand for NaN), then truncation, as the scalar cast does.
      const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), scale = _mm_set1_ps(255.0f), half = _mm_set1_ps(0.5f);
      __m128i ints[4];
      for (std::size_t ch = 0; ch < 4; ++ch) {
        const __m128 v = _mm_min_ps(one, _mm_max_ps(_mm_loadu_ps(c[ch].data()), zero));
        ints[ch] = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, scale), half));
      }
      alignas(16) std::int32_t lanes[4][4];
      for (std::size_t ch = 0; ch < 4; ++ch) _mm_store_si128(reinterpret_cast<__m128i*>(lanes[ch]), ints[ch]);
      for (int ch = 0; ch < 4; ++ch)
        for (int k = 0; k < 4; ++k) bytes[k][ch] = static_cast<std::uint8_t>(lanes[ch][k]);
#else
      for (int ch = 0; ch < 4; ++ch)
        for (int k = 0; k < 4; ++k) bytes[k][ch] = float_to_unorm8(c[std::size_t(ch)][std::size_t(k)]);
#endif
      for (int k = 0; k < 4; ++k)
        if (mask & (1u << k)) std::memcpy(&color_[index(x + (k & 1), y + (k >> 1)) * 4], bytes[k], 4);
    } else {
      for (int k = 0; k < 4; ++k)
        if (mask & (1u << k)) {
          const float px[4] = {c[0][std::size_t(k)], c[1][std::size_t(k)], c[2][std::size_t(k)], c[3][std::size_t(k)]};
          std::memcpy(&color_[index(x + (k & 1), y + (k >> 1)) * 16], px, 16);
        }
    }
  }

  // Raw storage, for hashing and image output: RGBA8 is 4 bytes per pixel, RGBA32F 16.
  const std::vector<std::uint8_t>& color_bytes() const { return color_; }
  const std::vector<float>& depth_values() const { return depth_; }
  std::size_t bytes() const { return color_.size() + depth_.size() * sizeof(float); }

  // Writes the colour buffer: PNG (8-bit), EXR (half/float), or anything else OpenImageIO knows by
  // extension. Returns an empty string on success, else a one-line error naming the file.
  std::string write_color(const std::string& path) const;
  // Writes the depth buffer as a one-channel float EXR (or 16-bit PNG, depth scaled to 0..65535).
  std::string write_depth(const std::string& path) const;

 private:
  Framebuffer(int w, int h, ColorFormat f);
  std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width_) + std::size_t(x); }

  int width_ = 0, height_ = 0;
  ColorFormat format_ = ColorFormat::rgba8_unorm;
  std::vector<std::uint8_t> color_;
  std::vector<float> depth_;
};


// Writes an image through OpenImageIO atomically (temporary + rename). `pixels` are `channels`
// interleaved values per pixel, row 0 at the top; `is_float` selects float32 data, else uint8.
// Returns an empty string on success, else a one-line error naming the file.
std::string write_image_atomically(const std::string& path, int width, int height, int channels, bool is_float,
                                   const void* pixels);

}  // namespace tessera
