#include "shaders_cpp/displacement/displacement_map.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "shaders_cpp/cage/one_line.h"
#include "shaders_cpp/displacement/chart_padding.h"
#include "shaders_cpp/image_io/image_codec.h"
#include "shaders_cpp/image_io/stderr_capture.h"

namespace tessera {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw DisplacementMapError(path + ": " + what);
}

std::uint32_t le32(const unsigned char* p) {
  return std::uint32_t(p[0]) | p[1] << 8 | p[2] << 16 | std::uint32_t(p[3]) << 24;
}

// Bytes per 4x4 block of a block-compressed DXGI format (BC1..BC7), or per pixel of a common
// uncompressed one (negative); 0 when unknown.
int dxgi_size(std::uint32_t format) {
  if ((format >= 70 && format <= 72) || (format >= 79 && format <= 81)) return 8;  // BC1, BC4
  if ((format >= 73 && format <= 78) || (format >= 82 && format <= 84) || (format >= 94 && format <= 99)) return 16;
  if (format == 2) return -16;                                  // R32G32B32A32_FLOAT
  if (format == 10 || format == 11 || format == 16) return -8;  // R16G16B16A16, R32G32
  if ((format >= 27 && format <= 29) || format == 41 || (format >= 87 && format <= 91)) return -4;
  if (format == 54 || format == 56 || format == 34 || format == 35) return -2;  // R16, R8G8
  if (format == 61 || format == 62) return -1;                                  // R8
  return 0;
}

// OpenImageIO reads a truncated DDS as zeros without an error: the size its header implies (every mip
// level it declares) is checked against the file's.
// `h` holds the file's first `got` bytes (up to 148), `file_size` its size.
void check_dds_header(const std::string& path, const unsigned char* h, std::size_t got, std::uintmax_t file_size) {
  if (got < 4 || std::memcmp(h, "DDS ", 4) != 0) return;  // not a DDS: the codec decides
  if (got < 128) fail(path, "truncated DDS: " + std::to_string(file_size) + " bytes, shorter than its 128-byte header");
  const std::uint32_t flags = le32(h + 8), height = le32(h + 12), width = le32(h + 16), mips = le32(h + 28);
  const std::uint32_t pf_flags = le32(h + 80), four_cc = le32(h + 84), bits = le32(h + 88);
  std::uint64_t header = 128;
  int block = 0;  // > 0: bytes per 4x4 block; < 0: bytes per pixel
  auto cc = [](const char* s) { return le32(reinterpret_cast<const unsigned char*>(s)); };
  if ((pf_flags & 0x4u) != 0) {  // DDPF_FOURCC
    if (four_cc == cc("DX10")) {
      header += 20;
      if (got < 148) fail(path, "truncated DDS: " + std::to_string(file_size) + " bytes, shorter than its DX10 header");
      block = dxgi_size(le32(h + 128));
    } else if (four_cc == cc("DXT1") || four_cc == cc("ATI1") || four_cc == cc("BC4U")) {
      block = 8;
    } else if (four_cc == cc("DXT2") || four_cc == cc("DXT3") || four_cc == cc("DXT4") || four_cc == cc("DXT5") ||
               four_cc == cc("ATI2") || four_cc == cc("BC5U")) {
      block = 16;
    }
  } else if (bits % 8 == 0 && bits >= 8 && bits <= 128) {
    block = -int(bits / 8);
  } else if ((pf_flags & (0x40u | 0x20000u | 0x2u | 0x200u)) != 0) {
    // DDPF_RGB, LUMINANCE, ALPHA or YUV with a bit count no such format has: OpenImageIO 2.4 spends
    // minutes on 0 bits per pixel (a fuzzer's find), so it is refused here.
    fail(path, "unsupported DDS pixel format: " + std::to_string(bits) + " bits per pixel");
  }
  if (block == 0 || width == 0 || height == 0) return;  // a layout this check does not know: OIIO decides
  const std::uint32_t levels = (flags & 0x20000u) != 0 && mips > 0 ? std::min(mips, 32u) : 1u;
  std::uint64_t need = header;
  for (std::uint32_t l = 0; l < levels; ++l) {
    const std::uint64_t w = std::max<std::uint64_t>(1, width >> l), hgt = std::max<std::uint64_t>(1, height >> l);
    need += block > 0 ? ((w + 3) / 4) * ((hgt + 3) / 4) * std::uint64_t(block) : w * hgt * std::uint64_t(-block);
    if (need > (std::uint64_t(1) << 40)) break;
  }
  if (file_size < need)
    fail(path, "truncated DDS: its header (" + std::to_string(width) + "x" + std::to_string(height) + ", " +
                   std::to_string(levels) + " level(s)) implies " + std::to_string(need) + " bytes, the file has " +
                   std::to_string(file_size));
}

void check_dds_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[148] = {};
  in.read(reinterpret_cast<char*>(h), sizeof h);
  check_dds_header(path, h, std::size_t(in.gcount()), std::filesystem::file_size(path));
}

void check_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "a directory, not an image file");
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  check_dds_size(path);
}

std::vector<std::string> names_of(const ImageHeader& header) {
  std::vector<std::string> names;
  for (int c = 0; c < header.channels; ++c) {
    std::string n = c < int(header.channel_names.size()) ? header.channel_names[std::size_t(c)] : std::string();
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
  static DisplacementImage decode(const ImageSource& source, std::uintmax_t file_size,
                                  std::optional<DisplacementImage::Selection> check);
};

DisplacementImage DisplacementImage::read(const std::string& path, std::optional<Selection> check) {
  const StderrCapture quiet;  // the codec's own error lines: our message says it once
  check_file(path);
  return DisplacementImageDecoder::decode(ImageSource{path}, std::filesystem::file_size(path), check);
}

DisplacementImage DisplacementImage::read_encoded(const std::string& name, std::span<const std::uint8_t> bytes,
                                                  const std::string& format, std::optional<Selection> check) {
  const StderrCapture quiet;
  check_dds_header(name, bytes.data(), std::min<std::size_t>(bytes.size(), 148), bytes.size());
  return DisplacementImageDecoder::decode(ImageSource{name, bytes, format}, bytes.size(), check);
}

namespace {
constexpr std::uint64_t kMaxDecodeRatio = 4096;
constexpr std::string_view kDecodePrefix = "tessera decode: value = stored * ";
constexpr std::string_view kDecodeMiddle = " + ";
}  // namespace

std::string decode_description(float scale, float bias) {
  char a[32], b[32];
  const auto ra = std::to_chars(a, a + sizeof a, scale), rb = std::to_chars(b, b + sizeof b, bias);
  return std::string(kDecodePrefix) + std::string(a, ra.ptr) + std::string(kDecodeMiddle) + std::string(b, rb.ptr);
}

DisplacementImage DisplacementImageDecoder::decode(const ImageSource& source, std::uintmax_t file_size,
                                                   std::optional<DisplacementImage::Selection> check) {
  const std::string& path = source.path;
  DisplacementImage image;
  std::string description;
  // The header is checked before any pixel is decoded; a refusal throws out of the read.
  const auto accept = [&](const ImageHeader& s) -> void* {
    if (s.width < 1 || s.height < 1 || s.width > kMaxTextureSize || s.height > kMaxTextureSize)
      fail(path, "size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is outside 1.." +
                     std::to_string(kMaxTextureSize));
    if (s.depth > 1) fail(path, "is a volume image; a displacement map is 2D");
    // Texels are held as float: a header claiming more than 2^28 of them (1 GiB) is refused before any
    // allocation (a corrupt or hostile header otherwise asks for up to 16 GiB).
    if (std::uint64_t(s.width) * std::uint64_t(s.height) * std::uint64_t(std::max(1, s.channels)) > (1ull << 28))
      fail(path, std::to_string(s.width) + "x" + std::to_string(s.height) + " with " + std::to_string(s.channels) +
                     " channels is more than 2^28 texel values, the most a map may hold");
    // An uncompressed image's pixels are in the file: a header that claims more than the file holds is
    // truncated or hostile (OpenImageIO would fill the rest, spending seconds on a 400-byte TIFF that
    // claims 5638x27909: a fuzzer's find).
    const std::uint64_t pixel_bytes = std::uint64_t(s.width) * std::uint64_t(s.height) * s.stored_pixel_bytes;
    if (s.compression == "none" && file_size < pixel_bytes)
      fail(path, "truncated: its header (" + std::to_string(s.width) + "x" + std::to_string(s.height) +
                     ", uncompressed) implies " + std::to_string(pixel_bytes) + " bytes of pixels, the file has " +
                     std::to_string(file_size));
    // A compressed image holds at most so many pixel bytes per file byte: deflate (PNG, TIFF, EXR zip)
    // expands at most 1032:1, LZW about 2730:1, RLE and JPEG less. A header claiming more than 4096
    // times the file (plus 64 KiB) is hostile: a fuzzer's 250-byte TIFF claiming 20230x1029 RGB kept
    // the decoder busy 1.8 s and 950 MB here (30 s under ASan) before failing.
    if (pixel_bytes > std::uint64_t(kMaxDecodeRatio) * file_size + (64u << 10))
      fail(path, std::to_string(s.width) + "x" + std::to_string(s.height) + " (" + std::to_string(pixel_bytes) +
                     " bytes of pixels) cannot come from a " + std::to_string(file_size) + "-byte file: more than " +
                     std::to_string(kMaxDecodeRatio) + " times its size");
    image.path_ = path;
    image.width_ = s.width, image.height_ = s.height;
    image.names_ = names_of(s);
    if (check) select_channels(path, image.names_, check->spec, check->count);  // throws on a wrong choice
    image.texels_.resize(std::size_t(s.width) * std::size_t(s.height) * std::size_t(s.channels));
    description = s.description;
    return image.texels_.data();
  };
  if (const ReadFailure f = image_codec().read(source, PixelType::f32, accept)) {
    if (f.step == ReadStep::pixels) fail(path, "cannot read pixels (" + one_line_message(f.message) + ")");
    if (source.bytes)
      fail(path, "cannot decode the embedded image as " + source.format + " (" + one_line_message(f.message) + ")");
    fail(path, "cannot read as an image (" + one_line_message(f.message) + ")");
  }
  if (description.starts_with(kDecodePrefix)) {
    // A stored encoding (decode_description): parsed strictly, applied to every texel.
    const std::string_view rest = std::string_view(description).substr(kDecodePrefix.size());
    const std::size_t middle = rest.find(kDecodeMiddle);
    float scale = 0, bias = 0;
    const auto ok = [](std::string_view t, float& x) {
      const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
      return r.ec == std::errc() && r.ptr == t.data() + t.size() && std::isfinite(x);
    };
    if (middle == std::string_view::npos || !ok(rest.substr(0, middle), scale) ||
        !ok(rest.substr(middle + kDecodeMiddle.size()), bias))
      fail(path, "ImageDescription \"" + description.substr(0, 80) + "\" is not a valid stored encoding");
    for (float& t : image.texels_) t = scale * t + bias;
  }
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

DisplacementMap DisplacementMap::padded(const std::vector<std::uint8_t>& covered) const {
  const int w = width(), h = height(), c = channels();
  std::vector<float> texels(std::size_t(w) * std::size_t(h) * std::size_t(c));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec4 t = texture_.load(0, x, y);
      for (int k = 0; k < c; ++k)
        texels[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * std::size_t(c) + std::size_t(k)] = t[k];
    }
  pad_charts(texels, w, h, c, covered);
  std::string error;
  auto t = Texture2D::create(w, h, c, std::move(texels), true, &error);
  if (!t) fail(path_, error);
  return DisplacementMap(std::move(*t), path_, selected_);
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
