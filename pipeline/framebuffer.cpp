#include "pipeline/framebuffer.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

#include "pipeline/sample_pattern.h"

namespace tessera {

Framebuffer::Framebuffer(int w, int h, ColorFormat f, int samples)
    : width_(w),
      height_(h),
      format_(f),
      color_(std::size_t(w) * std::size_t(h) * std::size_t(samples) * (f == ColorFormat::rgba8_unorm ? 4u : 16u)),
      depth_(std::size_t(w) * std::size_t(h) * std::size_t(samples), 1.0f),
      samples_(samples) {}

std::optional<Framebuffer> Framebuffer::create(int width, int height, ColorFormat format, std::string* error,
                                               int samples) {
  if (!valid_sample_count(samples)) {
    if (error) *error = "sample count " + std::to_string(samples) + " is not 1, 2, 4, 8 or 16";
    return std::nullopt;
  }
  if (width < 1 || height < 1 || width > kMaxRenderTargetSize || height > kMaxRenderTargetSize) {
    if (error)
      *error = "render target " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
               std::to_string(kMaxRenderTargetSize) + " per side";
    return std::nullopt;
  }
  // The samples' storage with the target's: refuse what would not fit in memory rather than fail on it.
  const std::uint64_t bytes = std::uint64_t(width) * std::uint64_t(height) * std::uint64_t(samples) *
                              (format == ColorFormat::rgba8_unorm ? 8u : 20u);
  if (bytes > (std::uint64_t(16) << 30)) {
    if (error)
      *error = "render target " + std::to_string(width) + "x" + std::to_string(height) + " with " +
               std::to_string(samples) + " samples needs " + std::to_string(bytes >> 30) + " GiB (limit 16)";
    return std::nullopt;
  }
  return Framebuffer(width, height, format, samples);
}

void Framebuffer::clear_rows(int y0, int y1, glm::vec4 c, float d) {
  y0 = std::clamp(y0, 0, height_);
  y1 = std::clamp(y1, y0, height_);
  if (y0 == y1) return;
  for (int s = 0; s < samples_; ++s)
    std::fill(depth_.begin() + std::ptrdiff_t(index(0, y0) + plane_offset(s)),
              depth_.begin() + std::ptrdiff_t(index(0, y1) + plane_offset(s)), d);
  const std::size_t pixel_bytes = format_ == ColorFormat::rgba8_unorm ? 4 : 16;
  std::uint8_t px[16];
  if (format_ == ColorFormat::rgba8_unorm) {
    const std::uint8_t b[4] = {float_to_unorm8(c.r), float_to_unorm8(c.g), float_to_unorm8(c.b), float_to_unorm8(c.a)};
    std::memcpy(px, b, 4);
  } else {
    const float f[4] = {c.r, c.g, c.b, c.a};
    std::memcpy(px, f, 16);
  }
  // The first row pixel by pixel, the others copied from it.
  const std::size_t row_bytes = std::size_t(width_) * pixel_bytes;
  std::uint8_t* first = &color_[index(0, y0) * pixel_bytes];
  for (std::size_t i = 0; i < row_bytes; i += pixel_bytes) std::memcpy(first + i, px, pixel_bytes);
  for (int y = y0 + 1; y < y1; ++y) std::memcpy(&color_[index(0, y) * pixel_bytes], first, row_bytes);
  for (int s = 1; s < samples_; ++s)
    for (int y = y0; y < y1; ++y) std::memcpy(&color_[(index(0, y) + plane_offset(s)) * pixel_bytes], first, row_bytes);
}

void Framebuffer::set_other_samples(int x, int y, float d) {
  for (int s = 1; s < samples_; ++s) depth_[index(x, y) + plane_offset(s)] = d;
}

void Framebuffer::set_other_samples(int x, int y, glm::vec4 c) {
  for (int s = 1; s < samples_; ++s) set_sample_color(index(x, y) + plane_offset(s), c);
}

Framebuffer Framebuffer::resolve() const {
  Framebuffer out(width_, height_, format_, 1);
  resolve_rows(out, 0, height_);
  return out;
}

void Framebuffer::resolve_rows(Framebuffer& out, int y0, int y1) const {
  // Row by row, plane by plane: each inner loop runs over contiguous values of one plane (vectorized),
  // the same sums and minima in the same sample order as one pixel at a time.
  const std::size_t row = std::size_t(width_);
  std::vector<std::uint16_t> sums(format_ == ColorFormat::rgba8_unorm ? row * 4 : 0);  // 16 x 255 fits
  std::vector<float> fsums(format_ == ColorFormat::rgba8_unorm ? 0 : row * 4);
  for (int y = y0; y < y1; ++y) {
    const std::size_t begin = index(0, y);
    float* nearest = &out.depth_[begin];
    std::copy_n(&depth_[begin], row, nearest);
    for (int s = 1; s < samples_; ++s) {
      const float* d = &depth_[begin + plane_offset(s)];
      for (std::size_t i = 0; i < row; ++i) nearest[i] = std::min(nearest[i], d[i]);
    }
    if (format_ == ColorFormat::rgba8_unorm) {
      const unsigned half = unsigned(samples_) / 2;
      std::fill(sums.begin(), sums.end(), std::uint16_t(half));
      for (int s = 0; s < samples_; ++s) {
        const std::uint8_t* c = &color_[(begin + plane_offset(s)) * 4];
        for (std::size_t i = 0; i < row * 4; ++i) sums[i] = std::uint16_t(sums[i] + c[i]);
      }
      // samples_ is a power of two: the division is a shift.
      const int shift = std::countr_zero(unsigned(samples_));
      std::uint8_t* o = &out.color_[begin * 4];
      for (std::size_t i = 0; i < row * 4; ++i) o[i] = std::uint8_t(sums[i] >> shift);
    } else {
      std::fill(fsums.begin(), fsums.end(), 0.0f);
      for (int s = 0; s < samples_; ++s) {
        const std::uint8_t* c = &color_[(begin + plane_offset(s)) * 16];
        for (std::size_t i = 0; i < row * 4; ++i) {
          float v = 0.0f;
          std::memcpy(&v, c + i * 4, 4);
          fsums[i] += v;
        }
      }
      std::uint8_t* o = &out.color_[begin * 16];
      for (std::size_t i = 0; i < row * 4; ++i) {
        const float mean = fsums[i] / float(samples_);
        std::memcpy(o + i * 4, &mean, 4);
      }
    }
  }
}

glm::vec4 Framebuffer::color(int x, int y) const {
  if (samples_ > 1) {
    glm::vec4 sum(0.0f);
    for (int s = 0; s < samples_; ++s) {
      const std::size_t i = index(x, y) + plane_offset(s);
      if (format_ == ColorFormat::rgba8_unorm) {
        const std::uint8_t* p = &color_[i * 4];
        sum += glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
      } else {
        float px[4];
        std::memcpy(px, &color_[i * 16], 16);
        sum += glm::vec4(px[0], px[1], px[2], px[3]);
      }
    }
    return sum / float(samples_);
  }
  const std::size_t i = index(x, y);
  if (format_ == ColorFormat::rgba8_unorm) {
    const std::uint8_t* p = &color_[i * 4];
    return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
  }
  float px[4];
  std::memcpy(px, &color_[i * 16], 16);
  return {px[0], px[1], px[2], px[3]};
}

}  // namespace tessera
