// D3D11_STANDARD_MULTISAMPLE_PATTERN: the fixed sample positions of 1, 2, 4, 8 and 16-sample render
// targets, in 1/16 pixel from the pixel's centre (x right, y down), sample 0 first. They are the
// positions the D3D11 specification fixes for that quality level (Vulkan's standard sample locations
// are the same), so a multisampled image can be held against a GPU's.
#pragma once

#include <cstdint>
#include <span>

namespace tessera {

struct SampleOffset {
  std::int8_t x, y;  // 1/16 pixel
};

inline constexpr SampleOffset kSamples1[] = {{0, 0}};
inline constexpr SampleOffset kSamples2[] = {{4, 4}, {-4, -4}};
inline constexpr SampleOffset kSamples4[] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
inline constexpr SampleOffset kSamples8[] = {{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
inline constexpr SampleOffset kSamples16[] = {{1, 1},  {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5},
                                              {5, 3},  {3, -5},  {-2, 6}, {0, -7}, {-4, -6}, {-6, 4},
                                              {-8, 0}, {7, -4},  {6, 7},  {-7, -8}};

// A supported sample count: 1, 2, 4, 8 or 16.
constexpr bool valid_sample_count(int samples) {
  return samples == 1 || samples == 2 || samples == 4 || samples == 8 || samples == 16;
}

// The pattern of a valid sample count.
constexpr std::span<const SampleOffset> standard_sample_pattern(int samples) {
  switch (samples) {
    case 2: return kSamples2;
    case 4: return kSamples4;
    case 8: return kSamples8;
    case 16: return kSamples16;
    default: return kSamples1;
  }
}

// How far a pattern's samples lie from their pixel's centre, in 1/16 pixel: the smallest and largest
// offset on each axis (0 included). A sample inside [lo, hi] on an axis belongs to a pixel whose centre
// lies in [lo - max, hi - min]: the pixels whose samples a triangle's box may reach.
struct SampleReach {
  int min_x = 0, max_x = 0, min_y = 0, max_y = 0;
};
constexpr SampleReach sample_reach(int samples) {
  SampleReach r;
  for (const SampleOffset o : standard_sample_pattern(samples)) {
    r.min_x = o.x < r.min_x ? o.x : r.min_x, r.max_x = o.x > r.max_x ? o.x : r.max_x;
    r.min_y = o.y < r.min_y ? o.y : r.min_y, r.max_y = o.y > r.max_y ? o.y : r.max_y;
  }
  return r;
}
static_assert(sample_reach(4).min_x == -6 && sample_reach(4).max_y == 6 && sample_reach(16).min_x == -8);

}  // namespace tessera
