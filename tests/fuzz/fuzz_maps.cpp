// libFuzzer harness: image bytes through the displacement/normal map loader (OpenImageIO from memory,
// the DDS size check, channel selection, the non-finite texel check, mip building). The first byte
// picks the decoder. Bad input must be a DisplacementMapError, never a crash.
#include <cstdint>
#include <span>
#include <string>

#include "shaders_cpp/displacement/displacement_map.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kFormats[] = {".png", ".dds", ".exr", ".tga", ".hdr", ".tif", ".jpg", ".pnm"};
  const std::string format = kFormats[data[0] % 8];
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  try {
    const tessera::DisplacementImage image = tessera::DisplacementImage::read_encoded("fuzz" + format, bytes, format);
    const auto& names = image.channel_names();
    if (names.size() == 1 || names.size() == 3) (void)image.select();
    if (names.size() >= 3) (void)image.select("R,G,B", 3);
    (void)image.select(names.back(), 1);
  } catch (const tessera::DisplacementMapError&) {
  }
  return 0;
}
