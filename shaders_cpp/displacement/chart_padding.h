// Chart padding (dilation): the texels of a map that no UV chart covers get values that continue the
// charts next to them, as texture bakers pad their output.
//
// Why: a map is read across a chart's edge by bilinear taps, by the finite differences of derived
// normals, and by every mip level, whose texels average both sides. Where the texels beyond a chart's
// edge hold a flat background, or a baker's staircase of half-covered texels, every UV seam shows a
// ridge in the displaced surface and a line in its derived normals. Padding rebuilds those texels from
// the chart's inside.
//
// Coverage: a texel belongs to a chart when its centre lies in one of the chart's UV quads (both
// diagonals' triangles, so any quad shape is covered), then `erode` rings of texels are taken off each
// chart's border and rebuilt too: a baker's border texels are the ones its rasterization only partly
// covered. (The frog's height channel: seam step over ordinary-edge step in derived normals 8.8 with
// erode 0, 1.9 with erode 2; its normal map is the other way round, so make_displacement pads the
// displacement map only.)
//
// Contract: deterministic (rings in a fixed order, each ring's texels computed from the texels filled
// before it); every texel is filled unless no chart covers any; covered texels are never changed.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "shaders_cpp/displacement/watertight_uv.h"

namespace tessera {

// Texels (row-major, w x h) whose centres lie in a patch's UV quad (its own corners, texture convention:
// texel (x, y) is centred at ((x + 0.5) / w, (y + 0.5) / h)), eroded by `erode` texel rings.
std::vector<std::uint8_t> chart_coverage(std::span<const PatchTexcoords> patches, int w, int h, int erode = 0);

// Fills the texels not `covered`, ring by ring outward from the charts: each gets the mean of its
// already-filled 8-neighbours, channel by channel. `texels` holds w * h * channels floats.
void pad_charts(std::vector<float>& texels, int w, int h, int channels, const std::vector<std::uint8_t>& covered);

}  // namespace tessera
