#include "pipeline/framebuffer.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

#include "pipeline/sample_pattern.h"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace tessera {

Framebuffer::Framebuffer(int w, int h, ColorFormat f, int samples)
    : width_(w),
      height_(h),
      format_(f),
      color_(elements(w, h, samples) * (f == ColorFormat::rgba8_unorm ? 4u : 16u)),
      depth_(elements(w, h, samples), 1.0f),
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

Framebuffer::StoredClear Framebuffer::stored_clear(glm::vec4 c, float d) const {
  StoredClear v;
  v.depth = d;
  if (format_ == ColorFormat::rgba8_unorm) {
    const std::uint8_t b[4] = {float_to_unorm8(c.r), float_to_unorm8(c.g), float_to_unorm8(c.b), float_to_unorm8(c.a)};
    std::memcpy(v.color, b, 4);
  } else {
    const float f[4] = {c.r, c.g, c.b, c.a};
    std::memcpy(v.color, f, 16);
  }
  return v;
}

void Framebuffer::fill(std::size_t begin, std::size_t end, const StoredClear& v, ResolvedPlanes planes) {
  if (begin == end) return;
  const std::size_t pixel_bytes = format_ == ColorFormat::rgba8_unorm ? 4 : 16;
  if (planes == ResolvedPlanes::color_and_depth)
    std::fill(depth_.begin() + std::ptrdiff_t(begin), depth_.begin() + std::ptrdiff_t(end), v.depth);
#if defined(__AVX2__)
  // 32 bytes (8 RGBA8 pixels or 2 RGBA32F ones) a store: the copies below, a loop of 4-byte moves and
  // a memcpy, were half of a 4x frame's clear (each entered tile's 128 KB).
  __m128i pixel = _mm_loadu_si128(reinterpret_cast<const __m128i*>(v.color));  // 16 bytes: 1 or 4 pixels
  if (pixel_bytes == 4) pixel = _mm_shuffle_epi32(pixel, 0);
  const __m256i pattern = _mm256_broadcastsi128_si256(pixel);
  std::uint8_t* out = &color_[begin * pixel_bytes];
  const std::size_t bytes = (end - begin) * pixel_bytes;
  std::size_t i = 0;
  for (; i + 32 <= bytes; i += 32) _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i), pattern);
  for (; i < bytes; i += pixel_bytes) std::memcpy(out + i, v.color, pixel_bytes);
#else
  // The first pixels one by one, the rest copied from them.
  std::uint8_t* first = &color_[begin * pixel_bytes];
  const std::size_t run = std::min<std::size_t>(end - begin, 256);
  for (std::size_t i = 0; i < run; ++i) std::memcpy(first + i * pixel_bytes, v.color, pixel_bytes);
  for (std::size_t i = begin + run; i < end; i += run)
    std::memcpy(&color_[i * pixel_bytes], first, std::min(run, end - i) * pixel_bytes);
#endif
}

void Framebuffer::fill_rect(int x0, int y0, int x1, int y1, const StoredClear& v, ResolvedPlanes planes) {
  if (samples_ == 1) {
    for (int y = y0; y < y1; ++y) fill(index(x0, y), index(x0, y) + std::size_t(x1 - x0), v, planes);
    return;
  }
  // Quad rows: a row's quads [x0 / 2, (x1 + 1) / 2) are adjacent, all their samples together.
  for (int qy = y0 >> 1; 2 * qy < y1; ++qy) fill(quad_index(x0 >> 1, qy), quad_index((x1 + 1) >> 1, qy), v, planes);
}

void Framebuffer::clear_rows(int y0, int y1, glm::vec4 c, float d) {
  expect_no_pending_clear("clear_rows");
  y0 = std::clamp(y0, 0, height_);
  y1 = std::clamp(y1, y0, height_);
  if (y0 == y1) return;
  const StoredClear v = stored_clear(c, d);
  if (samples_ == 1) {
    fill_rect(0, y0, width_, y1, v);
    return;
  }
  // Multisampled: whole quad rows as one run; a quad row split by y0 or y1 (odd) pixel by pixel.
  auto partial_row = [&](int y) {
    for (int x = 0; x < width_; ++x)
      for (int s = 0; s < samples_; ++s) fill(index(x, y) + sample_offset(s), index(x, y) + sample_offset(s) + 1, v);
  };
  int first_row = y0, last_row = y1;  // [first_row, last_row): whole quad rows
  if (first_row & 1) partial_row(first_row++);
  if ((last_row & 1) && last_row < height_) partial_row(--last_row);
  if (first_row < last_row) fill(quad_index(0, first_row >> 1), quad_index(0, (last_row + 1) >> 1), v);
}

void Framebuffer::clear_by_tiles(glm::vec4 color, float depth, int tile_size) {
  TESSERA_CHECK(tile_size >= 8 && tile_size <= 1024 && tile_size % 2 == 0, "Framebuffer::clear_by_tiles: tile size",
                tile_size, "is not even and in 8..1024");
  PendingClear p;
  p.value = stored_clear(color, depth);
  p.tile_size = tile_size;
  p.columns = (width_ + tile_size - 1) / tile_size;
  p.marked.assign(std::size_t(p.columns) * std::size_t((height_ + tile_size - 1) / tile_size), 1);
  pending_ = std::move(p);
}

void Framebuffer::prepare_tile(int t) {
  if (!pending_ || !pending_->marked[std::size_t(t)]) return;
  const int size = pending_->tile_size, x0 = (t % pending_->columns) * size, y0 = (t / pending_->columns) * size;
  fill_rect(x0, y0, std::min(x0 + size, width_), std::min(y0 + size, height_), pending_->value);
  pending_->marked[std::size_t(t)] = 0;
}

void Framebuffer::finish_clear() {
  if (!pending_) return;
  for (std::size_t t = 0; t < pending_->marked.size(); ++t) prepare_tile(int(t));
  pending_.reset();
}

void Framebuffer::set_other_samples(int x, int y, float d) {
  for (int s = 1; s < samples_; ++s) depth_[index(x, y) + sample_offset(s)] = d;
}

void Framebuffer::set_other_samples(int x, int y, glm::vec4 c) {
  for (int s = 1; s < samples_; ++s) set_sample_color(index(x, y) + sample_offset(s), c);
}

Framebuffer Framebuffer::resolve(ResolvedPlanes planes) const {
  Framebuffer out(width_, height_, format_, 1);
  resolve_rows(out, 0, height_, planes);
  return out;
}

void Framebuffer::resolve_rows(Framebuffer& out, int y0, int y1, ResolvedPlanes planes) const {
  if (y0 >= y1) return;
  if (!pending_) {
    resolve_block(out, 0, width_, y0, y1, planes);
    return;
  }
  // Under a pending clear, band by band of tile rows (tiles are an even number of pixels from 0, so
  // no quad row straddles two): a marked tile's pixels are the resolve of its clear values, written
  // without reading its samples; the other tiles resolve as without a clear.
  const int size = pending_->tile_size;
  const StoredClear resolved = resolved_clear(pending_->value);
  for (int band = y0; band < y1;) {
    const int row = band / size, band_end = std::min(y1, (row + 1) * size);
    for (int column = 0; column < pending_->columns; ++column) {
      const int x0 = column * size, x1 = std::min(x0 + size, width_);
      if (pending_->marked[std::size_t(row * pending_->columns + column)])
        out.fill_rect(x0, band, x1, band_end, resolved, planes);
      else
        resolve_block(out, x0, x1, band, band_end, planes);
    }
    band = band_end;
  }
}

Framebuffer::StoredClear Framebuffer::resolved_clear(const StoredClear& v) const {
  // resolve_block's arithmetic on a pixel whose samples all hold v: the nearest depth is v's, the
  // colour the same sums in sample order.
  StoredClear r = v;
  if (samples_ == 1) return r;
  if (format_ == ColorFormat::rgba8_unorm) {
    const int shift = std::countr_zero(unsigned(samples_));
    for (std::size_t i = 0; i < 4; ++i) {
      std::uint16_t sum = std::uint16_t(unsigned(samples_) / 2);
      for (int s = 0; s < samples_; ++s) sum = std::uint16_t(sum + v.color[i]);
      r.color[i] = std::uint8_t(sum >> shift);
    }
  } else {
    for (std::size_t i = 0; i < 4; ++i) {
      float c = 0.0f, sum = 0.0f;
      std::memcpy(&c, v.color + 4 * i, 4);
      for (int s = 0; s < samples_; ++s) sum += c;
      const float mean = sum / float(samples_);
      std::memcpy(r.color + 4 * i, &mean, 4);
    }
  }
  return r;
}

void Framebuffer::resolve_block(Framebuffer& out, int x0, int x1, int y0, int y1, ResolvedPlanes planes) const {
  // Quad by quad: its samples are adjacent, sample s of its four pixels at 4 s, summed (and the
  // nearest depth taken) in sample order, the same sums and minima as one pixel at a time.
  const bool bytes = format_ == ColorFormat::rgba8_unorm;
  const bool with_depth = planes == ResolvedPlanes::color_and_depth;
  if (samples_ == 1) {  // the same layout: a copy, row by row
    const std::size_t pixel_bytes = bytes ? 4 : 16;
    for (int y = y0; y < y1; ++y) {
      const std::size_t begin = index(x0, y), end = begin + std::size_t(x1 - x0);
      if (with_depth)
        std::copy(depth_.begin() + std::ptrdiff_t(begin), depth_.begin() + std::ptrdiff_t(end),
                  out.depth_.begin() + std::ptrdiff_t(begin));
      std::copy(color_.begin() + std::ptrdiff_t(begin * pixel_bytes),
                color_.begin() + std::ptrdiff_t(end * pixel_bytes),
                out.color_.begin() + std::ptrdiff_t(begin * pixel_bytes));
    }
    return;
  }
  const int shift = std::countr_zero(unsigned(samples_));  // samples_ is a power of two
  for (int qy = y0 >> 1; 2 * qy < y1; ++qy)
    for (int qx = x0 >> 1; 2 * qx < x1; ++qx) {
      const std::size_t q = quad_index(qx, qy);
#if defined(__AVX2__)
      // A whole quad of an RGBA8 target in lanes: the sixteen bytes of each sample widened to 16 bits
      // and summed, the depths' minimum as std::min takes it ((d < n) ? d : n is minps(d, n)).
      if (bytes && 2 * qx + 1 < width_ && 2 * qy >= y0 && 2 * qy + 1 < y1) {
        __m256i sum = _mm256_set1_epi16(std::int16_t(samples_ / 2));
        for (int s = 0; s < samples_; ++s) {
          const std::size_t e = q + sample_offset(s);
          sum = _mm256_add_epi16(
              sum, _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(&color_[e * 4]))));
        }
        const __m256i mean = _mm256_srli_epi16(sum, shift);
        const __m128i rgba = _mm_packus_epi16(_mm256_castsi256_si128(mean), _mm256_extracti128_si256(mean, 1));
        const std::size_t top = out.index(2 * qx, 2 * qy), bottom = top + std::size_t(width_);
        _mm_storel_epi64(reinterpret_cast<__m128i*>(&out.color_[top * 4]), rgba);
        _mm_storel_epi64(reinterpret_cast<__m128i*>(&out.color_[bottom * 4]), _mm_srli_si128(rgba, 8));
        if (with_depth) {
          __m128 near = _mm_loadu_ps(&depth_[q]);
          for (int s = 1; s < samples_; ++s) near = _mm_min_ps(_mm_loadu_ps(&depth_[q + sample_offset(s)]), near);
          _mm_storel_pi(reinterpret_cast<__m64*>(&out.depth_[top]), near);
          _mm_storeh_pi(reinterpret_cast<__m64*>(&out.depth_[bottom]), near);
        }
        continue;
      }
#endif
      float nearest[4] = {};
      if (with_depth) {
        std::copy_n(&depth_[q], 4, nearest);
        for (int s = 1; s < samples_; ++s)
          for (std::size_t k = 0; k < 4; ++k) nearest[k] = std::min(nearest[k], depth_[q + sample_offset(s) + k]);
      }
      alignas(16) std::uint8_t rgba8[16];  // [pixel][channel]
      alignas(16) float mean[16];
      if (bytes) {
        std::uint16_t sums[16];  // 16 x 255 fits
        std::fill_n(sums, 16, std::uint16_t(unsigned(samples_) / 2));
        for (int s = 0; s < samples_; ++s) {
          const std::uint8_t* c = &color_[(q + sample_offset(s)) * 4];
          for (std::size_t i = 0; i < 16; ++i) sums[i] = std::uint16_t(sums[i] + c[i]);
        }
        for (std::size_t i = 0; i < 16; ++i) rgba8[i] = std::uint8_t(sums[i] >> shift);
      } else {
        float sums[16] = {};
        for (int s = 0; s < samples_; ++s) {
          const std::uint8_t* c = &color_[(q + sample_offset(s)) * 16];
          for (std::size_t i = 0; i < 16; ++i) {
            float v = 0.0f;
            std::memcpy(&v, c + i * 4, 4);
            sums[i] += v;
          }
        }
        for (std::size_t i = 0; i < 16; ++i) mean[i] = sums[i] / float(samples_);
      }
      for (int k = 0; k < 4; ++k) {
        const int x = 2 * qx + (k & 1), y = 2 * qy + (k >> 1);
        if (x >= width_ || y < y0 || y >= y1) continue;
        const std::size_t o = out.index(x, y);
        if (with_depth) out.depth_[o] = nearest[k];
        if (bytes)
          std::memcpy(&out.color_[o * 4], &rgba8[4 * k], 4);
        else
          std::memcpy(&out.color_[o * 16], &mean[4 * k], 16);
      }
    }
}

glm::vec4 Framebuffer::color(int x, int y) const {
  if (samples_ > 1) {
    glm::vec4 sum(0.0f);
    for (int s = 0; s < samples_; ++s) {
      const std::size_t i = index(x, y) + sample_offset(s);
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
