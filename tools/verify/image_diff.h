// Image comparison with OpenImageIO's idiff (2.4) semantics, for `tessera diff` and golden checks.
//
// Contract
// - Both files are read with OpenImageIO (subimage 0, MIP level 0) as float, as idiff reads them,
//   and compared with ImageBufAlgo::compare -- the function idiff calls -- over the union of their
//   data windows (a pixel outside one image is black there), on every channel either has. The
//   verdict follows idiff 2.4's rules, quirks included, so that for any pair and any thresholds the
//   two agree:
//     nfail <= allow_failures                                        -> ok
//     nfail > fail_percent% of A's pixels, or max error > hard_fail  -> failure
//     nwarn > warn_percent% of A's pixels, or max error > hard_warn  -> warning
//     otherwise                                                      -> ok
//   (so with the default thresholds any difference fails, and warnings appear only where failures are
//   allowed by percentage; images of different sizes are compared over their union). A deep image
//   against a flat one is `different_sizes`, as idiff has it.
// - Beyond idiff: `identical` (same data window, channels and every decoded value, bit for bit) and a
//   SHA-1 of each image's decoded pixels and shape (equal decoded pixels, equal hash, whatever the
//   file format); exact mode makes `identical` the verdict (different shapes: `different_sizes`).
// - A file that cannot be read is `file_error` with the reader's message; nothing is thrown.
// - The comparison runs in the image module (image_codec.h), behind the table of image_diff_table.h.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace tessera::verify {

// idiff's options and defaults.
struct DiffThresholds {
  float fail = 1.0e-6f, fail_relative = 0.0f, fail_percent = 0.0f;
  float hard_fail = std::numeric_limits<float>::infinity();
  long long allow_failures = 0;
  float warn = 1.0e-6f, warn_relative = 0.0f, warn_percent = 0.0f;
  float hard_warn = std::numeric_limits<float>::infinity();
};

// idiff's exit codes.
enum class DiffVerdict : int { ok = 0, warning = 1, failure = 2, different_sizes = 3, file_error = 4 };
const char* to_string(DiffVerdict v);  // "pass", "warning", "failure", "different_sizes", "file_error"

struct DiffReport {
  DiffVerdict verdict = DiffVerdict::file_error;
  std::string error;                              // file_error: one line naming the file
  int width = 0, height = 0, channels = 0;        // image A
  int b_width = 0, b_height = 0, b_channels = 0;  // image B
  std::uint64_t pixels = 0;                       // compared (A's, as idiff divides by)
  double mean_error = 0, rms_error = 0, psnr = 0, max_error = 0;
  int max_x = 0, max_y = 0, max_channel = 0;
  std::string max_channel_name;                   // A's name of that channel ("B"); empty if it has none
  std::vector<float> max_values_a, max_values_b;  // both images' pixel there, every channel (as idiff prints)
  std::uint64_t over_warn = 0, over_fail = 0;
  bool identical = false;
  std::string hash_a, hash_b;  // SHA-1 of the decoded pixels and shape
};

// Both images as read (float), kept for the pictures: opaque, the image module's own.
struct DiffImages {
  std::shared_ptr<const void> decoded;
};

// Reads and compares; `images` (optional) receives both images for diff pictures.
DiffReport diff_images(const std::string& path_a, const std::string& path_b, const DiffThresholds& t, bool exact,
                       DiffImages* images = nullptr);

// The pictures are written atomically to `path` in the format its extension names (byte-stable, as
// image_file.h); each returns "" or one line naming the file (also when `images` holds nothing).
// idiff's -o picture: A - B (or |A - B| with `absolute`), times `scale`, over the union window.
std::string write_difference_image(const DiffImages& images, bool absolute, float scale, const std::string& path);
// A picture people can read: A dimmed to grey, and every pixel that differs in a heat colour: the
// bright half of inferno by its largest channel difference times `scale`, on a log scale from one
// 8-bit step to 1. 8-bit RGB.
std::string write_heat_map(const DiffImages& images, float scale, const std::string& path);

}  // namespace tessera::verify
