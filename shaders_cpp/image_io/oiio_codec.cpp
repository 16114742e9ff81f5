// The image codec (image_codec.h) on OpenImageIO: the only code of this room that includes it. It is
// built into the image module and into binaries that link the codec in.
#include <algorithm>
#include <memory>
#include <optional>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "shaders_cpp/image_io/atomic_file.h"
#include "shaders_cpp/image_io/image_codec.h"
#include "shaders_cpp/image_io/oiio_attributes.h"

namespace tessera {
namespace {

OIIO::TypeDesc type_of(PixelType t) {
  switch (t) {
    case PixelType::u8: return OIIO::TypeDesc::UINT8;
    case PixelType::u16: return OIIO::TypeDesc::UINT16;
    case PixelType::f32: return OIIO::TypeDesc::FLOAT;
  }
  return OIIO::TypeDesc::UNKNOWN;
}

// Opens, writes and closes `out` on `name`; the writer's error on one line naming `shown`, or "".
std::string encode(OIIO::ImageOutput& out, const std::string& name, const std::string& shown,
                   const OIIO::ImageSpec& spec, OIIO::TypeDesc data_type, const void* pixels) {
  bool ok = out.open(name, spec);
  if (ok) ok = out.write_image(data_type, pixels);
  if (ok) ok = out.close();
  if (ok) return {};
  std::string err = out.geterror();
  std::replace(err.begin(), err.end(), '\n', ' ');
  return shown + ": cannot write image: " + err;
}

std::string write(const ImageTarget& target, const ImageLayout& layout, PixelType data, const void* pixels) {
  const std::string& path = target.path;
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return path + ": no image writer for this extension (" + OIIO::geterror() + ")";
  OIIO::ImageSpec spec(layout.width, layout.height, layout.channels, type_of(layout.stored));
  if (!layout.channel_names.empty()) spec.channelnames = layout.channel_names;
  for (const auto& [key, value] : layout.attributes) spec.attribute(key, value);
  set_output_attributes(spec);
  const OIIO::TypeDesc data_type = type_of(data);
  if (target.memory) {
    if (!out->supports("ioproxy")) return path + ": this format's writer cannot encode to memory";
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput sink(bytes);
    out->set_ioproxy(&sink);
    if (std::string e = encode(*out, path, path, spec, data_type, pixels); !e.empty()) return e;
    target.memory->assign(bytes.begin(), bytes.end());
    return {};
  }
  return write_atomically(
      path, [&](const std::string& temp) -> std::string { return encode(*out, temp, path, spec, data_type, pixels); });
}

ReadFailure read(const ImageSource& source, PixelType as, const std::function<void*(const ImageHeader&)>& destination) {
  std::optional<OIIO::Filesystem::IOMemReader> reader;
  std::unique_ptr<OIIO::ImageInput> in;
  if (source.bytes) {
    reader.emplace(source.bytes->data(), source.bytes->size());
    // The extension picks the decoder; OpenImageIO reads through the proxy instead of a file.
    in = OIIO::ImageInput::create("embedded" + source.format, /*do_open=*/true, nullptr, &*reader);
  } else {
    in = OIIO::ImageInput::open(source.path);
  }
  if (!in) return {ReadStep::open, OIIO::geterror()};
  const OIIO::ImageSpec& s = in->spec();
  ImageHeader header;
  header.width = s.width, header.height = s.height, header.depth = s.depth, header.channels = s.nchannels;
  header.channel_names = s.channelnames;
  header.stored_pixel_bytes = s.pixel_bytes(true);
  header.compression = s.get_string_attribute("compression");
  header.description = s.get_string_attribute("ImageDescription");
  void* pixels = destination(header);
  if (!in->read_image(0, 0, 0, s.nchannels, type_of(as), pixels)) return {ReadStep::pixels, in->geterror()};
  in->close();
  return {};
}

std::string draw_text(const FloatImageView& image, int x, int y, const std::string& text, int size,
                      const std::string& font, std::span<const float> color, TextAlignX align_x, TextAlignY align_y) {
  // An ImageBuf over the caller's pixels: render_text draws into them in place.
  OIIO::ImageBuf buf(OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT), image.pixels);
  using AX = OIIO::ImageBufAlgo::TextAlignX;
  using AY = OIIO::ImageBufAlgo::TextAlignY;
  const AX ax = align_x == TextAlignX::left ? AX::Left : align_x == TextAlignX::center ? AX::Center : AX::Right;
  const AY ay = align_y == TextAlignY::baseline ? AY::Baseline : AY::Center;
  const OIIO::cspan<float> ink(color.data(), OIIO::cspan<float>::size_type(color.size()));
  if (OIIO::ImageBufAlgo::render_text(buf, x, y, text, size, font, ink, ax, ay)) return {};
  return buf.geterror();
}

}  // namespace
}  // namespace tessera

// The module's entry (image_module_table finds it by this name).
extern "C" __attribute__((visibility("default"))) const void* tessera_image_codec_v1() {
  static const tessera::ImageCodec codec{&tessera::write, &tessera::read, &tessera::draw_text};
  return &codec;
}
