#include "tools/verify/image_compare.h"

#include <cstdlib>
#include <vector>

#include "shaders_cpp/image_io/image_codec.h"

namespace tessera::verify {
namespace {

struct Rgb8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> px;
};

Rgb8 read_rgb8(const std::string& path) {
  Rgb8 img;
  int channels = 0;
  std::vector<std::uint8_t> all;
  const ReadFailure f = image_codec().read(ImageSource{path}, PixelType::u8, [&](const ImageHeader& h) -> void* {
    img.width = h.width, img.height = h.height, channels = h.channels;
    all.resize(std::size_t(img.width) * std::size_t(img.height) * std::size_t(channels));
    return all.data();
  });
  if (f.step == ReadStep::open) throw ImageError(path + ": cannot read image (" + f.message + ")");
  if (f) throw ImageError(path + ": cannot decode image (" + f.message + ")");
  img.px.resize(std::size_t(img.width) * std::size_t(img.height) * 3);
  for (std::size_t i = 0; i < std::size_t(img.width) * std::size_t(img.height); ++i)
    for (int c = 0; c < 3; ++c)
      img.px[i * 3 + std::size_t(c)] = all[i * std::size_t(channels) + std::size_t(std::min(c, channels - 1))];
  return img;
}

}  // namespace

ImageDiff compare_images(const std::string& a, const std::string& b, int threshold) {
  const Rgb8 x = read_rgb8(a), y = read_rgb8(b);
  if (x.width != y.width || x.height != y.height)
    throw ImageError(a + " is " + std::to_string(x.width) + "x" + std::to_string(x.height) + " but " + b + " is " +
                     std::to_string(y.width) + "x" + std::to_string(y.height));
  ImageDiff d;
  d.width = x.width;
  d.height = x.height;
  d.pixels = std::uint64_t(x.width) * std::uint64_t(x.height);
  for (std::size_t i = 0; i < d.pixels; ++i) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(x.px[i * 3 + c]) - int(y.px[i * 3 + c])));
    if (worst > threshold) ++d.over_threshold;
    d.max_difference = std::max(d.max_difference, worst);
  }
  return d;
}

}  // namespace tessera::verify
