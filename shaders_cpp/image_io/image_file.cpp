#include "shaders_cpp/image_io/image_file.h"

#include <filesystem>
#include <vector>

namespace tessera {

std::string write_image(const ImageTarget& target, const ImageLayout& layout, PixelType data, const void* pixels) {
  return image_codec().write(target, layout, data, pixels);
}

namespace {
ImageLayout plain_layout(const std::string& path, int width, int height, int channels, bool is_float) {
  const bool png = std::filesystem::path(path).extension() == ".png";
  return ImageLayout{width, height, channels, is_float && !png ? PixelType::f32 : PixelType::u8};
}
}  // namespace

std::string write_image_atomically(const std::string& path, int width, int height, int channels, bool is_float,
                                   const void* pixels) {
  return write_image(ImageTarget{path}, plain_layout(path, width, height, channels, is_float),
                     is_float ? PixelType::f32 : PixelType::u8, pixels);
}

std::string write_color(const Framebuffer& fb, const ImageTarget& target) {
  if (fb.samples() > 1) return write_color(fb.resolve(ResolvedPlanes::color), target);
  const bool is_float = fb.format() == ColorFormat::rgba32_float;
  return write_image(target, plain_layout(target.path, fb.width(), fb.height(), 4, is_float),
                     is_float ? PixelType::f32 : PixelType::u8, fb.color_bytes().data());
}

std::string write_depth(const Framebuffer& fb, const std::string& path) {
  if (fb.samples() > 1) return write_depth(fb.resolve(), path);
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".exr" || ext == ".EXR" || ext == ".tif" || ext == ".tiff")
    return write_image_atomically(path, fb.width(), fb.height(), 1, true, fb.depth_values().data());
  std::vector<std::uint8_t> preview(fb.depth_values().size());
  for (std::size_t i = 0; i < preview.size(); ++i) preview[i] = float_to_unorm8(fb.depth_values()[i]);
  return write_image_atomically(path, fb.width(), fb.height(), 1, false, preview.data());
}

}  // namespace tessera
