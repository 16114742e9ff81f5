// Image files: every image Tessera writes goes through here, to a file or to memory, with the same
// encoder settings, so a frame the viewer encodes in memory is the bytes `tessera render` writes.
//
// Byte stability: OpenImageIO's EXR and TIFF writers stamp the time of writing (EXR `capDate`, TIFF
// `DateTime`) into a file whose spec names no DateTime, so two renders of the same scene would differ
// in their bytes. An empty DateTime makes the EXR writer store an empty capDate and the TIFF writer
// omit the tag: the file is then a function of the pixels alone.
//
// PNG: zlib level 1 and no row filter. At OpenImageIO's default (level 6, adaptive filters) encoding a
// 1280x720 frame took about 55 ms, longer than drawing it, which `tessera view` pays on every still
// frame; at level 1 without filters it takes about 13 ms, for files about 25 % larger (measured with
// `tessera bench view`: 182 KiB against 227 KiB a frame of the displaced frog).
//
// Errors: every function returns an empty string on success, else one line naming the file (or, for
// memory, the format). A file is written to a temporary beside it and renamed (atomic_file.h).
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include "pipeline/framebuffer.h"

namespace tessera {

inline void set_output_attributes(OIIO::ImageSpec& spec) {
  spec.attribute("DateTime", "");
  spec.attribute("png:compressionLevel", 1);
  spec.attribute("png:filter", 8);  // PNG_FILTER_NONE
}

inline void set_output_attributes(OIIO::ImageBuf& image) { set_output_attributes(image.specmod()); }

// Where an encoded image goes. With `memory` set, the encoder picked by `path`'s extension writes into
// *memory and nothing touches the file system; otherwise the file at `path`, atomically.
struct ImageTarget {
  std::string path;
  std::string* memory = nullptr;
};

// Writes `pixels` (`data_type` values, interleaved, row 0 at the top; OpenImageIO converts them to
// spec.format) as `spec` describes, with set_output_attributes applied.
std::string write_image(const ImageTarget& target, OIIO::ImageSpec spec, OIIO::TypeDesc data_type, const void* pixels);
// The same for a file path (the form most callers want).
std::string write_image_atomically(const std::string& path, OIIO::ImageSpec spec, OIIO::TypeDesc data_type,
                                   const void* pixels);
// `channels` interleaved values per pixel, float32 when `is_float`, else uint8; a float image to a
// format without float (PNG) is converted by the writer.
std::string write_image_atomically(const std::string& path, int width, int height, int channels, bool is_float,
                                   const void* pixels);

// The framebuffer's colour (resolved, when multisampled): PNG (8-bit), EXR (half/float), or anything
// else OpenImageIO knows by extension.
std::string write_color(const Framebuffer& fb, const ImageTarget& target);
// The depth buffer as a one-channel float EXR or TIFF; other formats get an 8-bit preview (depth
// scaled to 0..255), since they would lose almost all its precision.
std::string write_depth(const Framebuffer& fb, const std::string& path);

}  // namespace tessera
