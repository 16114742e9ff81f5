#pragma once
// Metadata and encoder settings Tessera sets on every image it writes.
//
// OpenImageIO's EXR and TIFF writers stamp the time of writing (EXR `capDate`, TIFF `DateTime`) into a
// file whose spec names no DateTime, so two renders of the same scene would differ in their bytes. An
// empty DateTime makes the EXR writer store an empty capDate and the TIFF writer omit the tag: the
// file is then a function of the pixels alone.
//
// PNG: zlib level 1 and no row filter. At OpenImageIO's default (level 6, adaptive filters) encoding a
// 1280x720 frame took about 55 ms, longer than drawing it, which `tessera view` pays on every still
// frame; at level 1 without filters it takes about 13 ms, for files about 25 % larger (measured with
// `tessera bench view`: 182 KiB against 227 KiB a frame of the displaced frog).

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

namespace tessera {

inline void set_output_attributes(OIIO::ImageSpec& spec) {
  spec.attribute("DateTime", "");
  spec.attribute("png:compressionLevel", 1);
  spec.attribute("png:filter", 8);  // PNG_FILTER_NONE
}

inline void set_output_attributes(OIIO::ImageBuf& image) { set_output_attributes(image.specmod()); }

// Writes `pixels` (`data_type` values, interleaved, row 0 at the top; OpenImageIO converts them to
// spec.format) as `spec` describes, atomically (temporary + rename), with set_output_attributes
// applied. Returns an empty string on success, else a one-line error naming the file.
std::string write_image_atomically(const std::string& path, OIIO::ImageSpec spec, OIIO::TypeDesc data_type,
                                   const void* pixels);

}  // namespace tessera
