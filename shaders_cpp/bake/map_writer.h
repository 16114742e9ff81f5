// Writing baked maps through OpenImageIO, atomically (a temporary, then rename) and byte-stable (no
// time stamp: image_metadata.h).
//
// Formats, by the path's extension: .exr and .tif/.tiff hold float32 (any values: displacement);
// .png holds 16-bit unsigned values, so only maps in [0, 1] (normal, occlusion) may go there.
// `attributes` are written as string metadata (the bake's settings, for whoever reads the file later).
//
// Contract: returns an empty string on success, else one line naming the file.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

namespace tessera {

std::string write_baked_map(const std::string& path, int width, int height, const std::vector<std::string>& channels,
                            std::span<const float> texels,
                            const std::vector<std::pair<std::string, std::string>>& attributes = {});

// Whether `path`'s extension holds float values (.exr, .tif, .tiff), and whether it names a format
// write_baked_map writes at all.
bool map_path_holds_floats(const std::string& path);
bool map_path_supported(const std::string& path);

}  // namespace tessera
