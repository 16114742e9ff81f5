// The image comparison of image_diff.h on OpenImageIO: built into the image module (image_codec.h)
// and into binaries that link the codec in.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <vector>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagecache.h>

#include "shaders_cpp/image_io/atomic_file.h"
#include "shaders_cpp/image_io/oiio_attributes.h"
#include "tools/verify/image_diff_table.h"

namespace tessera::verify {
namespace {

// What DiffImages holds.
struct DecodedPair {
  OIIO::ImageBuf a, b;
};

bool read_float(const std::string& path, OIIO::ImageBuf& img, std::string& error) {
  // ImageBuf reads through OpenImageIO's shared ImageCache, which keys files by name and notices a
  // rewrite only by its modification time: a file written again within that time's resolution (the
  // same path diffed twice in one process, as Python or a viewer session does) would be read stale.
  OIIO::ImageCache::create(/*shared=*/true)->invalidate(OIIO::ustring(path));
  img.reset(path);
  if (img.read(0, 0, /*force=*/true, OIIO::TypeFloat)) return true;
  std::string message = img.geterror();
  std::replace(message.begin(), message.end(), '\n', ' ');
  error = path + ": cannot read image (" + message + ")";
  return false;
}

// Decoded pixels and shape: the data window, channel count, then the float values.
std::string pixel_hash(const OIIO::ImageBuf& img) {
  const OIIO::ImageSpec& s = img.spec();
  const std::string shape = std::to_string(s.x) + "," + std::to_string(s.y) + "," + std::to_string(s.width) + "x" +
                            std::to_string(s.height) + "x" + std::to_string(s.depth) + "," +
                            std::to_string(s.nchannels) + (img.deep() ? ",deep" : "");
  return OIIO::ImageBufAlgo::computePixelHashSHA1(img, shape);
}

bool same_decoded_pixels(const OIIO::ImageBuf& a, const OIIO::ImageBuf& b) {
  const OIIO::ImageSpec &sa = a.spec(), &sb = b.spec();
  if (a.deep() || b.deep()) return false;  // not compared value by value here
  if (sa.x != sb.x || sa.y != sb.y || sa.z != sb.z || sa.width != sb.width || sa.height != sb.height ||
      sa.depth != sb.depth || sa.nchannels != sb.nchannels)
    return false;
  const std::size_t n =
      std::size_t(sa.width) * std::size_t(sa.height) * std::size_t(sa.depth) * std::size_t(sa.nchannels);
  std::vector<float> pa(n), pb(n);
  if (!a.get_pixels(a.roi(), OIIO::TypeFloat, pa.data()) || !b.get_pixels(b.roi(), OIIO::TypeFloat, pb.data()))
    return false;
  return n == 0 || std::memcmp(pa.data(), pb.data(), n * sizeof(float)) == 0;  // bits: NaN == same NaN
}

DiffReport compare(const std::string& path_a, const std::string& path_b, const DiffThresholds& t, bool exact,
                   DiffImages* images) {
  DiffReport r;
  const auto pair = std::make_shared<DecodedPair>();
  if (images) images->decoded = pair;
  DecodedPair& im = *pair;
  if (!read_float(path_a, im.a, r.error) || !read_float(path_b, im.b, r.error)) return r;  // file_error
  const OIIO::ImageSpec &sa = im.a.spec(), &sb = im.b.spec();
  r.width = sa.width, r.height = sa.height, r.channels = sa.nchannels;
  r.b_width = sb.width, r.b_height = sb.height, r.b_channels = sb.nchannels;
  r.hash_a = pixel_hash(im.a);
  r.hash_b = pixel_hash(im.b);
  r.identical = same_decoded_pixels(im.a, im.b);
  if (im.a.deep() != im.b.deep()) {
    r.verdict = DiffVerdict::different_sizes;
    return r;
  }
  // idiff divides counts by A's pixel count (1 for an empty image).
  std::uint64_t npels = std::uint64_t(sa.width) * std::uint64_t(sa.height) * std::uint64_t(sa.depth);
  if (npels == 0) npels = 1;
  r.pixels = npels;
  const OIIO::ImageBufAlgo::CompareResults cr =
      OIIO::ImageBufAlgo::compare(im.a, im.b, t.fail, t.warn, t.fail_relative, t.warn_relative);
  // (cr.error is set whenever a value fails -- compare's own result, not a read error: idiff ignores it.)
  r.mean_error = cr.meanerror, r.rms_error = cr.rms_error, r.psnr = cr.PSNR, r.max_error = cr.maxerror;
  r.max_x = cr.maxx, r.max_y = cr.maxy, r.max_channel = cr.maxc;
  if (cr.maxc >= 0 && cr.maxc < int(sa.channelnames.size())) r.max_channel_name = sa.channelnames[std::size_t(cr.maxc)];
  if (cr.maxerror != 0.0 && !im.a.deep()) {
    r.max_values_a.resize(std::size_t(sa.nchannels));
    r.max_values_b.resize(std::size_t(sb.nchannels));
    im.a.getpixel(cr.maxx, cr.maxy, cr.maxz, r.max_values_a.data(), sa.nchannels);
    im.b.getpixel(cr.maxx, cr.maxy, cr.maxz, r.max_values_b.data(), sb.nchannels);
  }
  r.over_warn = cr.nwarn, r.over_fail = cr.nfail;

  if (exact) {
    const bool same_shape = sa.x == sb.x && sa.y == sb.y && sa.width == sb.width && sa.height == sb.height &&
                            sa.depth == sb.depth && sa.nchannels == sb.nchannels;
    r.verdict = r.identical ? DiffVerdict::ok : same_shape ? DiffVerdict::failure : DiffVerdict::different_sizes;
    return r;
  }
  // idiff 2.4's decision, in its order (the percentages are of A's pixels, in double).
  const double fail_allowed = double(t.fail_percent) / 100.0 * double(npels);
  const double warn_allowed = double(t.warn_percent) / 100.0 * double(npels);
  if (t.allow_failures >= 0 && cr.nfail <= std::uint64_t(t.allow_failures))
    r.verdict = DiffVerdict::ok;
  else if (double(cr.nfail) > fail_allowed || cr.maxerror > double(t.hard_fail))
    r.verdict = DiffVerdict::failure;
  else if (double(cr.nwarn) > warn_allowed || cr.maxerror > double(t.hard_warn))
    r.verdict = DiffVerdict::warning;
  else
    r.verdict = DiffVerdict::ok;
  return r;
}

OIIO::ImageBuf difference_image(const DecodedPair& images, bool absolute, float scale) {
  OIIO::ImageBuf diff =
      absolute ? OIIO::ImageBufAlgo::absdiff(images.a, images.b) : OIIO::ImageBufAlgo::sub(images.a, images.b);
  if (scale != 1.0f) diff = OIIO::ImageBufAlgo::mul(diff, scale);
  return diff;
}

OIIO::ImageBuf heat_map_image(const DecodedPair& images, float scale) {
  namespace iba = OIIO::ImageBufAlgo;
  const OIIO::ROI roi = OIIO::roi_union(images.a.roi(), images.b.roi());
  // Largest channel difference per pixel, times `scale`, on a log scale from one 8-bit step (1/255)
  // to 1 over the bright half of inferno: 0.55 + 0.45 log2(1 + 255 d) / 8, so a single-step
  // difference is as visible as a large one is distinct from it.
  const OIIO::ImageBuf diff = iba::absdiff(images.a, images.b, roi);
  OIIO::ImageBuf largest = iba::maxchan(diff);
  largest = iba::mul(largest, scale);
  OIIO::ImageBuf level(largest.spec());
  for (OIIO::ImageBuf::Iterator<float> it(level, roi); !it.done(); ++it) {
    const float d = largest.getchannel(it.x(), it.y(), 0, 0);
    it[0] = d > 0.0f ? 0.55f + 0.45f * std::min(1.0f, std::log2(1.0f + 255.0f * d) / 8.0f) : 0.0f;
  }
  const OIIO::ImageBuf heat = iba::color_map(level, 0, "inferno");
  // A's luminance (first three channels, or the one), dimmed: where the pixels are.
  const int ca = images.a.nchannels();
  OIIO::ImageBuf grey;
  if (ca >= 3) {
    const float weights[3] = {0.2126f, 0.7152f, 0.0722f};
    grey = iba::channel_sum(images.a, weights, roi);
  } else {
    grey = iba::channels(images.a, 1, {}, {}, {}, true);
  }
  grey = iba::clamp(iba::mul(grey, 0.3f), 0.0f, 1.0f);
  OIIO::ImageSpec spec(roi.width(), roi.height(), 3, OIIO::TypeDesc::UINT8);
  spec.x = roi.xbegin, spec.y = roi.ybegin;
  OIIO::ImageBuf out(spec);
  for (int y = roi.ybegin; y < roi.yend; ++y)
    for (int x = roi.xbegin; x < roi.xend; ++x) {
      float px[3];
      if (level.getchannel(x, y, 0, 0) > 0.0f) {
        heat.getpixel(x, y, px, 3);
      } else {
        grey.getpixel(x, y, px, 1);
        px[1] = px[2] = px[0];
      }
      out.setpixel(x, y, px, 3);
    }
  return out;
}

// Writes `img` atomically in the format `path`'s extension names.
std::string write_picture(OIIO::ImageBuf img, const std::string& path) {
  set_output_attributes(img.specmod());
  return write_atomically(path, [&](const std::string& temp) -> std::string {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (img.write(temp, OIIO::TypeUnknown, ext.empty() ? std::string() : ext.substr(1))) return {};
    std::string message = img.geterror();
    std::replace(message.begin(), message.end(), '\n', ' ');
    return path + ": cannot write image (" + message + ")";
  });
}

const DecodedPair* decoded(const DiffImages& images, const std::string& path, std::string& error) {
  if (!images.decoded) error = path + ": no compared images to draw (a programming error)";
  return static_cast<const DecodedPair*>(images.decoded.get());
}

std::string write_difference(const DiffImages& images, bool absolute, float scale, const std::string& path) {
  std::string error;
  const DecodedPair* pair = decoded(images, path, error);
  return pair ? write_picture(difference_image(*pair, absolute, scale), path) : error;
}

std::string write_heat(const DiffImages& images, float scale, const std::string& path) {
  std::string error;
  const DecodedPair* pair = decoded(images, path, error);
  return pair ? write_picture(heat_map_image(*pair, scale), path) : error;
}

}  // namespace
}  // namespace tessera::verify

// The module's entry (image_module_table finds it by this name).
extern "C" __attribute__((visibility("default"))) const void* tessera_image_diff_v1() {
  static const tessera::verify::ImageDiffTable table{&tessera::verify::compare, &tessera::verify::write_difference,
                                                     &tessera::verify::write_heat};
  return &table;
}
