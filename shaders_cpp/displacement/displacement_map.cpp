#include "shaders_cpp/displacement/displacement_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace tessera {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw DisplacementMapError(path + ": " + what);
}

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

std::unique_ptr<OIIO::ImageInput> open(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "a directory, not an image file");
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  auto in = OIIO::ImageInput::open(path);
  if (!in) fail(path, "cannot read as an image (" + one_line(OIIO::geterror()) + ")");
  return in;
}

std::vector<std::string> names_of(const OIIO::ImageSpec& spec) {
  std::vector<std::string> names;
  for (int c = 0; c < spec.nchannels; ++c) {
    std::string n = c < int(spec.channelnames.size()) ? spec.channelnames[std::size_t(c)] : std::string();
    names.push_back(n.empty() ? "channel" + std::to_string(c) : n);
  }
  return names;
}

std::string list(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

bool same_letters(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

// One channel token: an exact name, a name matching case-insensitively, or a letter R/G/B/A (X/Y/Z/W)
// standing for channel 0..3. -1 when nothing matches.
int find_channel(const std::vector<std::string>& names, std::string_view token) {
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == token) return int(c);
  for (std::size_t c = 0; c < names.size(); ++c)
    if (same_letters(names[c], token)) return int(c);
  if (token.size() == 1) {
    const char l = char(std::toupper(static_cast<unsigned char>(token[0])));
    const std::string_view rgba = "RGBA", xyzw = "XYZW";
    const auto i = rgba.find(l) != std::string_view::npos ? rgba.find(l) : xyzw.find(l);
    if (i != std::string_view::npos && int(i) < int(names.size())) return int(i);
  }
  return -1;
}

std::vector<int> select_channels(const std::string& path, const std::vector<std::string>& names, std::string_view spec,
                                 int count) {
  std::vector<int> chosen;
  if (spec.empty()) {
    if (names.size() == 1 && count != 3) return {0};
    if (names.size() == 3 && count != 1) return {0, 1, 2};
    fail(path, "has " + std::to_string(names.size()) + " channels (" + list(names) +
                   "); choose the displacement with --displacement-channel");
  }
  std::vector<std::string> tokens;
  for (std::size_t start = 0;;) {
    const std::size_t comma = spec.find(',', start);
    tokens.emplace_back(spec.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  // A single token that names no channel but whose letters each do: "RGB", "a".
  if (tokens.size() == 1 && tokens[0].size() > 1 && find_channel(names, tokens[0]) < 0) {
    std::vector<std::string> letters;
    for (char ch : tokens[0]) letters.emplace_back(1, ch);
    if (std::all_of(letters.begin(), letters.end(), [&](const std::string& l) { return find_channel(names, l) >= 0; }))
      tokens = letters;
  }
  for (const auto& t : tokens) {
    const int c = find_channel(names, t);
    if (c < 0) fail(path, "has no channel '" + t + "' (it has " + list(names) + ")");
    chosen.push_back(c);
  }
  if (count != 0 && int(chosen.size()) != count)
    fail(path, "channel selection '" + std::string(spec) + "' gives " + std::to_string(chosen.size()) +
                   " channels, the displacement needs " + std::to_string(count) + " (it has " + list(names) + ")");
  if (count == 0 && chosen.size() != 1 && chosen.size() != 3)
    fail(path, "channel selection '" + std::string(spec) + "' gives " + std::to_string(chosen.size()) +
                   " channels; a displacement takes 1 (scalar) or 3 (vector)");
  return chosen;
}

}  // namespace

struct DisplacementImageDecoder {
  static DisplacementImage decode(std::unique_ptr<OIIO::ImageInput> in, const std::string& path,
                                  std::optional<DisplacementImage::Selection> check);
};

DisplacementImage DisplacementImage::read(const std::string& path, std::optional<Selection> check) {
  return DisplacementImageDecoder::decode(open(path), path, check);
}

DisplacementImage DisplacementImage::read_encoded(const std::string& name, std::span<const std::uint8_t> bytes,
                                                  const std::string& format, std::optional<Selection> check) {
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  // The extension picks the decoder; OpenImageIO reads through the proxy instead of a file.
  auto in = OIIO::ImageInput::create("embedded" + format, true, nullptr, &reader);
  if (!in) fail(name, "cannot decode the embedded image as " + format + " (" + one_line(OIIO::geterror()) + ")");
  return DisplacementImageDecoder::decode(std::move(in), name, check);
}

DisplacementImage DisplacementImageDecoder::decode(std::unique_ptr<OIIO::ImageInput> in, const std::string& path,
                                                   std::optional<DisplacementImage::Selection> check) {
  const OIIO::ImageSpec s = in->spec();
  if (s.width < 1 || s.height < 1 || s.width > kMaxTextureSize || s.height > kMaxTextureSize)
    fail(path, "size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is outside 1.." +
                   std::to_string(kMaxTextureSize));
  if (s.depth > 1) fail(path, "is a volume image; a displacement map is 2D");
  DisplacementImage image;
  image.path_ = path;
  image.width_ = s.width, image.height_ = s.height;
  image.names_ = names_of(s);
  if (check) select_channels(path, image.names_, check->spec, check->count);  // throws on a wrong choice
  image.texels_.resize(std::size_t(s.width) * std::size_t(s.height) * std::size_t(s.nchannels));
  if (!in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, image.texels_.data()))
    fail(path, "cannot read pixels (" + one_line(in->geterror()) + ")");
  in->close();
  return image;
}

DisplacementMap DisplacementImage::select(std::string_view spec, int count) const {
  const std::vector<int> chosen = select_channels(path_, names_, spec, count);
  const std::size_t pixels = std::size_t(width_) * std::size_t(height_), stride = names_.size();
  std::vector<float> texels(pixels * chosen.size());
  for (std::size_t p = 0; p < pixels; ++p)
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      const float v = texels_[p * stride + std::size_t(chosen[k])];
      // A NaN or infinite texel would displace points to NaN (and a PLY of NaN vertices): refused.
      if (!std::isfinite(v))
        fail(path_, "texel (" + std::to_string(p % std::size_t(width_)) + ", " +
                        std::to_string(p / std::size_t(width_)) + ") of channel " + names_[std::size_t(chosen[k])] +
                        " is " + (std::isnan(v) ? "NaN" : "infinite") + "; a map must be finite");
      texels[p * chosen.size() + k] = v;
    }
  std::string error;
  auto t = Texture2D::create(width_, height_, int(chosen.size()), std::move(texels), true, &error);
  if (!t) fail(path_, error);
  std::vector<std::string> selected;
  for (int c : chosen) selected.push_back(names_[std::size_t(c)]);
  return DisplacementMap(std::move(*t), path_, std::move(selected));
}

DisplacementMap DisplacementMap::load_encoded(const std::string& name, std::span<const std::uint8_t> bytes,
                                              const std::string& format, std::string_view spec, int count) {
  return DisplacementImage::read_encoded(name, bytes, format, DisplacementImage::Selection{spec, count})
      .select(spec, count);
}

DisplacementMap DisplacementMap::load(const std::string& path, std::string_view spec, int count) {
  return DisplacementImage::read(path, DisplacementImage::Selection{spec, count}).select(spec, count);
}

}  // namespace tessera
