// The encoder settings of every image Tessera writes, for the code that writes through OpenImageIO
// itself (the image module's files only): byte-stable files, fast PNG (image_file.h says why).
#pragma once

#include <OpenImageIO/imageio.h>

namespace tessera {

inline void set_output_attributes(OIIO::ImageSpec& spec) {
  spec.attribute("DateTime", "");
  spec.attribute("png:compressionLevel", 1);
  spec.attribute("png:filter", 8);  // PNG_FILTER_NONE
}

}  // namespace tessera
