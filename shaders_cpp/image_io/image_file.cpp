#include "shaders_cpp/image_io/image_file.h"

#include <algorithm>
#include <filesystem>
#include <vector>

#include <OpenImageIO/filesystem.h>

#include "shaders_cpp/image_io/atomic_file.h"

namespace tessera {
namespace {

// Opens, writes and closes `out` on `name`; the writer's error on one line, or "".
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

}  // namespace

std::string write_image(const ImageTarget& target, OIIO::ImageSpec spec, OIIO::TypeDesc data_type, const void* pixels) {
  const std::string& path = target.path;
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return path + ": no image writer for this extension (" + OIIO::geterror() + ")";
  set_output_attributes(spec);
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

std::string write_image_atomically(const std::string& path, OIIO::ImageSpec spec, OIIO::TypeDesc data_type,
                                   const void* pixels) {
  return write_image(ImageTarget{path}, std::move(spec), data_type, pixels);
}

namespace {
OIIO::ImageSpec plain_spec(const std::string& path, int width, int height, int channels, bool is_float) {
  OIIO::ImageSpec spec(width, height, channels, is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (is_float && std::filesystem::path(path).extension() == ".png") spec.set_format(OIIO::TypeDesc::UINT8);
  return spec;
}
}  // namespace

std::string write_image_atomically(const std::string& path, int width, int height, int channels, bool is_float,
                                   const void* pixels) {
  return write_image_atomically(path, plain_spec(path, width, height, channels, is_float),
                                is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8, pixels);
}

std::string write_color(const Framebuffer& fb, const ImageTarget& target) {
  if (fb.samples() > 1) return write_color(fb.resolve(), target);
  const bool is_float = fb.format() == ColorFormat::rgba32_float;
  return write_image(target, plain_spec(target.path, fb.width(), fb.height(), 4, is_float),
                     is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8, fb.color_bytes().data());
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
