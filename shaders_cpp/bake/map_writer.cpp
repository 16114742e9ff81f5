#include "shaders_cpp/bake/map_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "shaders_cpp/displacement/displacement_map.h"
#include "shaders_cpp/image_io/image_file.h"

namespace tessera {
namespace {

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

bool map_path_holds_floats(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".exr";
}

bool map_path_supported(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".exr" || ext == ".png" || ext == ".tif" || ext == ".tiff";
}

std::string write_baked_map(const std::string& path, int width, int height, const std::vector<std::string>& channels,
                            std::span<const float> texels,
                            const std::vector<std::pair<std::string, std::string>>& attributes, bool stored_range) {
  if (!map_path_supported(path)) return path + ": write maps as .exr, .tif or .png";
  const bool floats = map_path_holds_floats(path);
  const int n = int(channels.size());
  std::vector<std::uint16_t> quantized;
  std::string description;
  if (!floats) {
    float lo = 0.0f, scale = 1.0f;
    if (stored_range && !texels.empty()) {
      const auto [mn, mx] = std::minmax_element(texels.begin(), texels.end());
      lo = *mn, scale = *mx > *mn ? *mx - *mn : 1.0f;
      description = decode_description(scale, lo);
    }
    quantized.resize(texels.size());
    for (std::size_t i = 0; i < texels.size(); ++i) {
      const float x = stored_range ? (texels[i] - lo) / scale : texels[i];
      if (!(x >= 0.0f && x <= 1.0f))
        return path + ": a 16-bit file holds values in [0, 1], and this map has " + std::to_string(texels[i]) +
               ": write it as .exr";
      quantized[i] = std::uint16_t(std::lround(double(x) * 65535.0));
    }
  }
  ImageLayout layout{width, height, n, floats ? PixelType::f32 : PixelType::u16, channels};
  if (floats) layout.attributes.emplace_back("compression", "zip");
  for (const auto& [key, value] : attributes) layout.attributes.emplace_back(key, value);
  if (!description.empty()) layout.attributes.emplace_back("ImageDescription", description);
  return floats ? write_image(ImageTarget{path}, layout, PixelType::f32, texels.data())
                : write_image(ImageTarget{path}, layout, PixelType::u16, quantized.data());
}

}  // namespace tessera
