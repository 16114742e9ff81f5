// A picture of one tessellation pattern, for debugging tessellation factors: the domain, its
// triangles (or segments, or points) coloured by region, and the factors written along the edges
// with the segment counts they produce. Inverted triangles (the fractional_even fold quirk) are
// drawn red, so they stand out.
#pragma once

#include <array>
#include <string>

#include "tessellator/tessellator.h"

namespace tessera::cli {

struct PatternPicture {
  ts::Partitioning partitioning = ts::Partitioning::integer;
  ts::FactorSet raw;  // the factors as given
  ts::ProcessedFactors processed;
  const ts::Pattern* pattern = nullptr;
  int size = 1024;  // pixels, square
};

// Renders and writes a PNG (or any format the image codec knows from the extension) atomically.
// Throws InputError if the file cannot be written.
void write_pattern_image(const PatternPicture& picture, const std::string& path);

}  // namespace tessera::cli
