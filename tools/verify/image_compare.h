// Pixel comparison of two images, as render CI needs it: how many pixels differ by more than a
// threshold in any colour channel (on a 0..255 scale), and the largest difference.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace tessera::verify {

struct ImageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ImageDiff {
  int width = 0, height = 0;
  std::uint64_t pixels = 0;
  std::uint64_t over_threshold = 0;  // pixels with some RGB channel differing by more than the threshold
  int max_difference = 0;            // largest channel difference, 0..255
  double share() const { return pixels ? double(over_threshold) / double(pixels) : 0.0; }
};

// Reads both images through the image codec (any format OpenImageIO reads; PPM included) as 8-bit RGB and compares
// them. Throws ImageError naming the file that cannot be read, or both sizes if they differ.
ImageDiff compare_images(const std::string& a, const std::string& b, int threshold);

}  // namespace tessera::verify
