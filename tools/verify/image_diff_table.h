// The table through which image_diff.cpp reaches its implementation in the image module
// (oiio_image_diff.cpp); see image_codec.h for why the module exists. Private to this folder.
#pragma once

#include <string>

#include "tools/verify/image_diff.h"

namespace tessera::verify {

struct ImageDiffTable {
  DiffReport (*diff)(const std::string& path_a, const std::string& path_b, const DiffThresholds& t, bool exact,
                     DiffImages* images);
  std::string (*write_difference)(const DiffImages& images, bool absolute, float scale, const std::string& path);
  std::string (*write_heat_map)(const DiffImages& images, float scale, const std::string& path);
};

}  // namespace tessera::verify
