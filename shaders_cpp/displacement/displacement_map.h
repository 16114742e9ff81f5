// Displacement (and normal) maps read from image files through OpenImageIO: float EXR and TIFF, 8- and
// 16-bit PNG, DDS, anything else OIIO reads. One channel (scalar displacement along the normal) or
// three (vector displacement), chosen by name or letter; the mip chain is built once, at load.
//
// Contract
// - load() reads the first subimage's top mip level, converts it to float (unsigned integer formats map
//   to [0, 1], as OIIO converts them), keeps only the selected channels, in the order given, and builds
//   a Texture2D with its full mip chain (texture.h: box filter, row 0 at v = 0). The result is
//   immutable; any number of threads may sample it.
// - Channel selection (`spec`): empty → the map's only channel for a one-channel map, R,G,B for a
//   three-channel map, and an error naming the channels otherwise (RGBA or two-channel maps are
//   ambiguous: say which). Otherwise a comma-separated list of channel names as the file spells them
//   ("A", "height", "R,G,B"), or a run of single letters each naming a channel ("RGB", "a"); letters
//   match the file's names case-insensitively, and R/G/B/A (or X/Y/Z/W) also match channels 0..3 by
//   position when the file names them differently. `count` is how many channels the caller needs
//   (1 or 3; 0 accepts 1 or 3).
// - Errors throw DisplacementMapError whose message is one line starting with the file's path:
//   missing or unreadable file, a channel the file does not have, the wrong number of channels, a
//   size the texture cannot hold.
// - Stored encodings: an image whose ImageDescription reads decode_description(scale, bias) holds its
//   values as stored = (value - bias) / scale (how `tessera bake` writes displacement into 16-bit PNG
//   and TIFF, whose texels read as [0, 1]); every channel is decoded back to scale * stored + bias at
//   load, so the map means what was baked at --displacement-scale 1 and bias 0.
#pragma once

#include <stdexcept>
#include <optional>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/texture.h"

namespace tessera {

struct DisplacementMapError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The ImageDescription of a map stored as (value - bias) / scale; see the contract above.
std::string decode_description(float scale, float bias);

class DisplacementMap {
 public:
  // DisplacementImage::read(path).select(spec, count).
  static DisplacementMap load(const std::string& path, std::string_view spec = {}, int count = 0);
  // DisplacementImage::read_encoded(name, bytes, format).select(spec, count).
  static DisplacementMap load_encoded(const std::string& name, std::span<const std::uint8_t> bytes,
                                      const std::string& format, std::string_view spec = {}, int count = 0);

  const Texture2D& texture() const { return texture_; }
  const std::string& path() const { return path_; }
  int width() const { return texture_.width(0); }
  int height() const { return texture_.height(0); }
  int channels() const { return texture_.channels(); }
  int levels() const { return texture_.levels(); }
  // The file's names of the selected channels, in texture order.
  const std::vector<std::string>& selected() const { return selected_; }
  // Bytes of texel storage, all mip levels.
  std::size_t bytes() const { return texture_.bytes(); }

  // The map with the texels outside `covered` (chart_coverage at this map's size) padded from the
  // charts (chart_padding.h), its mip levels rebuilt.
  DisplacementMap padded(const std::vector<std::uint8_t>& covered) const;

 private:
  friend class DisplacementImage;
  DisplacementMap(Texture2D t, std::string path, std::vector<std::string> selected)
      : texture_(std::move(t)), path_(std::move(path)), selected_(std::move(selected)) {}
  Texture2D texture_;
  std::string path_;
  std::vector<std::string> selected_;
};

// An image file's pixels, every channel as float, read once: maps of different channels of one file
// (the frog's height in A and its normal map in RGB) are selected from one decode.
class DisplacementImage {
 public:
  // A channel selection as select() takes it.
  struct Selection {
    std::string_view spec;
    int count = 0;
  };
  // Throws DisplacementMapError as load(). With `check`, the selection is tested against the file's
  // channel names before the pixels are decoded: a wrong channel fails at once, not after a large
  // image has been read.
  static DisplacementImage read(const std::string& path, std::optional<Selection> check = std::nullopt);
  // The same for an encoded image held in memory (a glTF's embedded image): `name` names it in
  // messages, `format` is a file extension that picks the decoder (".png", ".jpg", ".exr", ...).
  static DisplacementImage read_encoded(const std::string& name, std::span<const std::uint8_t> bytes,
                                        const std::string& format, std::optional<Selection> check = std::nullopt);
  DisplacementMap select(std::string_view spec = {}, int count = 0) const;
  // Every channel name of the file, in order.
  const std::vector<std::string>& channel_names() const { return names_; }

 private:
  friend struct DisplacementImageDecoder;  // the codec's side, in the .cpp
  std::string path_;
  int width_ = 0, height_ = 0;
  std::vector<std::string> names_;
  std::vector<float> texels_;  // names_.size() per pixel, row by row
};

}  // namespace tessera
