#include "shaders_cpp/cage/cage_generators.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace tessera {

Cage torus_cage(int around, int across, float major, float minor) {
  if (around < 3 || around > 4096 || across < 3 || across > 4096)
    throw std::invalid_argument("torus cage: " + std::to_string(around) + "x" + std::to_string(across) +
                                " is outside 3..4096 faces per direction");
  if (!(minor > 0.0f && minor < major && std::isfinite(major)))
    throw std::invalid_argument("torus cage: radii must satisfy 0 < minor < major");
  // The outermost vertex is at major + minor: beyond float's range it would be written as inf.
  if (!(double(major) + double(minor) <= double(std::numeric_limits<float>::max())))
    throw std::invalid_argument("torus cage: radii " + std::to_string(major) + " + " + std::to_string(minor) +
                                " overflow float coordinates");
  Cage c;
  c.name = "torus " + std::to_string(around) + "x" + std::to_string(across);
  const double two_pi = 2.0 * std::numbers::pi;
  for (int i = 0; i < around; ++i) {
    const double a = two_pi * i / around;
    for (int j = 0; j < across; ++j) {
      const double b = two_pi * j / across;
      const double ring = major + minor * std::cos(b);
      c.positions.push_back({float(ring * std::cos(a)), float(ring * std::sin(a)), float(minor * std::sin(b))});
    }
  }
  // UVs on an (around + 1) x (across + 1) grid: the last row and column repeat the first positions.
  for (int i = 0; i <= around; ++i)
    for (int j = 0; j <= across; ++j) c.uvs.push_back({float(i) / float(around), float(j) / float(across)});
  auto vertex = [&](int i, int j) { return (i % around) * across + j % across; };
  auto uv = [&](int i, int j) { return i * (across + 1) + j; };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < across; ++j) {
      // Counter-clockwise seen from outside: +around then +across (the outward normal is d/da x d/db).
      const int corners[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
      c.face_offsets.push_back(int(c.face_vertices.size()));
      c.face_sizes.push_back(4);
      for (const auto& [ci, cj] : corners) {
        c.face_vertices.push_back(vertex(ci, cj));
        c.face_uvs.push_back(uv(ci, cj));
      }
    }
  }
  return c;
}

}  // namespace tessera
