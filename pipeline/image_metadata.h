#pragma once
// Metadata Tessera sets on every image it writes.
//
// OpenImageIO's EXR and TIFF writers stamp the time of writing (EXR `capDate`, TIFF `DateTime`) into a
// file whose spec names no DateTime, so two renders of the same scene would differ in their bytes. An
// empty DateTime makes the EXR writer store an empty capDate and the TIFF writer omit the tag: the
// file is then a function of the pixels alone.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

namespace tessera {

inline void omit_capture_time(OIIO::ImageSpec& spec) { spec.attribute("DateTime", ""); }

inline void omit_capture_time(OIIO::ImageBuf& image) { omit_capture_time(image.specmod()); }

}  // namespace tessera
