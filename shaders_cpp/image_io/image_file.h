// Image files: every image Tessera writes goes through here, to a file or to memory, with the same
// encoder settings, so a frame the viewer encodes in memory is the bytes `tessera render` writes.
// The encoding itself is the image codec's (image_codec.h), loaded on the first image written.
//
// Byte stability: OpenImageIO's EXR and TIFF writers stamp the time of writing (EXR `capDate`, TIFF
// `DateTime`) into a file whose spec names no DateTime, so two renders of the same scene would differ
// in their bytes. The codec writes an empty DateTime: the EXR writer then stores an empty capDate and
// the TIFF writer omits the tag, and the file is a function of the pixels alone.
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

#include "pipeline/framebuffer.h"
#include "shaders_cpp/image_io/image_codec.h"

namespace tessera {

// Writes `pixels` (`data` values, interleaved, row 0 at the top; converted to layout.stored) as
// `layout` describes.
std::string write_image(const ImageTarget& target, const ImageLayout& layout, PixelType data, const void* pixels);
// `channels` interleaved values per pixel, float32 when `is_float`, else uint8, to a file; a float
// image to a format without float (PNG) is stored as 8 bits.
std::string write_image_atomically(const std::string& path, int width, int height, int channels, bool is_float,
                                   const void* pixels);

// The framebuffer's colour (resolved, when multisampled): PNG (8-bit), EXR (half/float), or anything
// else OpenImageIO knows by extension.
std::string write_color(const Framebuffer& fb, const ImageTarget& target);
// The depth buffer as a one-channel float EXR or TIFF; other formats get an 8-bit preview (depth
// scaled to 0..255), since they would lose almost all its precision.
std::string write_depth(const Framebuffer& fb, const std::string& path);

}  // namespace tessera
