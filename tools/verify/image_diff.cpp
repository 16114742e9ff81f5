#include "tools/verify/image_diff.h"

#include "shaders_cpp/image_io/image_codec.h"
#include "tools/verify/image_diff_table.h"

// Defined (strongly) only where the codec is linked in (oiio_image_diff.cpp).
extern "C" const void* tessera_image_diff_v1() __attribute__((weak));

namespace tessera::verify {
namespace {

const ImageDiffTable& table() {
  static const auto* const t =
      static_cast<const ImageDiffTable*>(image_module_table("tessera_image_diff_v1", tessera_image_diff_v1));
  return *t;
}

}  // namespace

const char* to_string(DiffVerdict v) {
  switch (v) {
    case DiffVerdict::ok: return "pass";
    case DiffVerdict::warning: return "warning";
    case DiffVerdict::failure: return "failure";
    case DiffVerdict::different_sizes: return "different_sizes";
    case DiffVerdict::file_error: return "file_error";
  }
  return "file_error";
}

DiffReport diff_images(const std::string& path_a, const std::string& path_b, const DiffThresholds& t, bool exact,
                       DiffImages* images) {
  return table().diff(path_a, path_b, t, exact, images);
}

std::string write_difference_image(const DiffImages& images, bool absolute, float scale, const std::string& path) {
  return table().write_difference(images, absolute, scale, path);
}

std::string write_heat_map(const DiffImages& images, float scale, const std::string& path) {
  return table().write_heat_map(images, scale, path);
}

}  // namespace tessera::verify
