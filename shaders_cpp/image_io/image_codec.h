// The image codec: every image file Tessera reads or writes is decoded or encoded through this table
// of plain functions. Its one implementation (oiio_codec.cpp) is OpenImageIO, and Debian's
// OpenImageIO loads about 260 shared libraries (video, DICOM, HEIF, OpenVDB, RAW codecs) that cost a
// command about 0.3 s and 90 MB before it does anything. So the table lives in a module,
// tessera-image-io.so, loaded on the first call of image_codec() -- a command that reads or writes no
// image never loads it -- unless the binary links the codec in (the tests, the Python module and the
// fuzzers do: tessera_link_image_codec() in the top CMakeLists.txt).
//
// The table holds no OpenImageIO type, so nothing above it includes OpenImageIO. `write` and
// `draw_text` return "" on success, else the error (write's names the file).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace tessera {

// The pixel types Tessera writes and reads.
enum class PixelType : std::uint8_t { u8, u16, f32 };

// Where an encoded image goes. With `memory` set, the encoder picked by `path`'s extension writes into
// *memory and nothing touches the file system; otherwise the file at `path`, atomically.
struct ImageTarget {
  std::string path;
  std::string* memory = nullptr;
};

// What an image file holds, for writing.
struct ImageLayout {
  int width = 0, height = 0, channels = 0;
  PixelType stored = PixelType::u8;                                  // in the file (a format without it converts)
  std::vector<std::string> channel_names = {};                       // empty: the writer's own (R, G, B, A)
  std::vector<std::pair<std::string, std::string>> attributes = {};  // metadata, e.g. {"compression", "zip"}
};

// Where an image is read from: the file at `path`, or (with `bytes`) those encoded bytes, decoded by
// the reader that `format` (an extension: ".png", ".dds") names.
struct ImageSource {
  std::string path;
  std::optional<std::span<const std::uint8_t>> bytes = {};
  std::string format = {};
};

// What an image file's header says (subimage 0, MIP level 0).
struct ImageHeader {
  int width = 0, height = 0, depth = 1, channels = 0;
  std::vector<std::string> channel_names;  // as the file has them (an entry may be empty)
  std::uint64_t stored_pixel_bytes = 0;    // bytes of one pixel as stored, all channels
  std::string compression;                 // the "compression" attribute ("none" when uncompressed)
  std::string description;                 // the "ImageDescription" attribute
};

// Which step of a read failed, so that callers keep their own words for each.
enum class ReadStep : std::uint8_t { none, open, pixels };
struct ReadFailure {
  ReadStep step = ReadStep::none;
  std::string message;  // the codec's, as it gave it (it may hold line breaks)
  explicit operator bool() const { return step != ReadStep::none; }
};

// Float pixels, interleaved, row 0 at the top: text is drawn into them in place.
struct FloatImageView {
  float* pixels = nullptr;
  int width = 0, height = 0, channels = 0;
};
enum class TextAlignX : std::uint8_t { left, center, right };
enum class TextAlignY : std::uint8_t { baseline, center };

struct ImageCodec {
  // Encodes `pixels` (values of `data`, layout.channels interleaved, row 0 at the top) as `layout`
  // says; the file's DateTime is left empty and PNG is written at zlib level 1 without row filters
  // (image_file.h says why), so the bytes are a function of the pixels alone.
  std::string (*write)(const ImageTarget& target, const ImageLayout& layout, PixelType data, const void* pixels);
  // Opens `source` and hands its header to `destination`, which returns where the decoded values go
  // (room for width * height * channels values of `as`), or throws to refuse the image before any
  // pixel is decoded (the exception leaves read unchanged).
  ReadFailure (*read)(const ImageSource& source, PixelType as,
                      const std::function<void*(const ImageHeader&)>& destination);
  // Draws `text` in the TrueType `font` at `size` pixels, in `color` (one value per channel).
  std::string (*draw_text)(const FloatImageView& image, int x, int y, const std::string& text, int size,
                           const std::string& font, std::span<const float> color, TextAlignX align_x,
                           TextAlignY align_y);
};

// The codec linked into this binary, else the module's (loaded once; thread-safe). Throws
// std::runtime_error naming the module when it cannot be loaded (a broken installation).
const ImageCodec& image_codec();

// A table the image module exports by the extern "C" name `symbol` (each table's front passes its
// own, and the table linked in, if any, as `linked`): `linked` when set, else the module's.
const void* image_module_table(const char* symbol, const void* (*linked)());

}  // namespace tessera
