// Writing baked maps through the image codec, atomically (a temporary, then rename) and byte-stable
// (no time stamp: image_file.h).
//
// Formats, by the path's extension: .exr holds float32; .png and .tif/.tiff hold 16-bit unsigned values
// in [0, 1]. With `stored_range`, values of any range (displacement) go to a 16-bit file as
// (value - min) / (max - min), and the file's ImageDescription says how to decode them
// (decode_description, displacement_map.h: the map reader applies it); otherwise values must lie in
// [0, 1] (normal, occlusion).
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
                            const std::vector<std::pair<std::string, std::string>>& attributes = {},
                            bool stored_range = false);

// Whether `path`'s extension holds float values (.exr), and whether it names a format
// write_baked_map writes at all.
bool map_path_holds_floats(const std::string& path);
bool map_path_supported(const std::string& path);

}  // namespace tessera
