// Shared helpers for the pipeline tests: pass-through shaders, a coverage-counting pixel shader,
// and small draws built directly in clip space.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pipeline/device.h"
#include "test_support.h"

namespace tessera::test {

// Vertices are already clip-space vertices.
template <std::size_t N>
struct ClipPassVS {
  ClipVertex<N> operator()(const ClipVertex<N>& v, std::uint32_t) const { return v; }
};

// Counts how often each pixel is shaded; returns attribute 0..2 as colour. Tiles own disjoint
// pixels, so counting from several threads does not race.
template <std::size_t N>
struct CountingPS {
  std::vector<int>* counts = nullptr;
  int width = 0;
  glm::vec4 operator()(const PixelInput<N>& in) const {
    const int x = int(in.position.x), y = int(in.position.y);
    ++(*counts)[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    glm::vec4 c(0, 0, 0, 1);
    for (std::size_t i = 0; i < N && i < 3; ++i) c[int(i)] = in.attributes[i];
    return c;
  }
};

inline Viewport full_viewport(int w, int h) { return {0, 0, float(w), float(h), 0, 1}; }

inline Framebuffer make_target(int w, int h, ColorFormat f = ColorFormat::rgba8_unorm) {
  std::string error;
  auto fb = Framebuffer::create(w, h, f, &error);
  fb->clear(glm::vec4(0, 0, 0, 0), 1.0f);
  return std::move(*fb);
}

template <std::size_t N>
ClipVertex<N> clip_vertex(float x, float y, float z, float w) {
  ClipVertex<N> v;
  v.position = {x, y, z, w};
  return v;
}

// Hash of the colour and depth bytes (FNV-1a), for determinism checks.
inline std::uint64_t image_hash(const Framebuffer& fb) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : fb.color_bytes()) h = (h ^ b) * 1099511628211ull;
  for (float d : fb.depth_values()) {
    std::uint32_t bits;
    std::memcpy(&bits, &d, 4);
    for (int k = 0; k < 4; ++k) h = (h ^ ((bits >> (8 * k)) & 0xFF)) * 1099511628211ull;
  }
  return h;
}

}  // namespace tessera::test
