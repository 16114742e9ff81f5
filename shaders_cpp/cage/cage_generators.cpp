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

Cage sphere_cage(int pole_valence, int across, float radius, bool triangle_poles) {
  if (pole_valence < 3 || pole_valence > 2048 || across < 2 || across > 4096)
    throw std::invalid_argument("sphere cage: pole valence " + std::to_string(pole_valence) + " and " +
                                std::to_string(across) + " bands are outside 3..2048 and 2..4096");
  if (!(radius > 0.0f && std::isfinite(radius))) throw std::invalid_argument("sphere cage: radius must be > 0");
  Cage c;
  c.name =
      "sphere, " + std::string(triangle_poles ? "polar " : "") + "poles of valence " + std::to_string(pole_valence);
  const int around = triangle_poles ? pole_valence : 2 * pole_valence,
            rings = across - 1;  // ring vertices per latitude, latitudes
  const double pi = std::numbers::pi;
  // Vertices: the rings from south to north, then the south and north poles.
  for (int j = 1; j <= rings; ++j) {
    const double lat = -0.5 * pi + pi * j / across;
    for (int i = 0; i < around; ++i) {
      const double lon = 2.0 * pi * i / around;
      c.positions.push_back({float(radius * std::cos(lat) * std::cos(lon)), float(radius * std::sin(lat)),
                             float(-radius * std::cos(lat) * std::sin(lon))});
    }
  }
  const int south = rings * around, north = south + 1;
  c.positions.push_back({0.0f, -radius, 0.0f});
  c.positions.push_back({0.0f, radius, 0.0f});
  // UVs: an (around + 1) x (rings) grid, then one per pole quad at each pole.
  for (int j = 1; j <= rings; ++j)
    for (int i = 0; i <= around; ++i) c.uvs.push_back({float(i) / float(around), float(j) / float(across)});
  const int pole_uvs = int(c.uvs.size());
  const float span = triangle_poles ? 1.0f : 2.0f;  // longitude steps per pole face
  for (int k = 0; k < pole_valence; ++k) c.uvs.push_back({(span * float(k) + 0.5f * span) / float(around), 0.0f});
  for (int k = 0; k < pole_valence; ++k) c.uvs.push_back({(span * float(k) + 0.5f * span) / float(around), 1.0f});
  auto vertex = [&](int i, int j) { return (j - 1) * around + i % around; };
  auto uv = [&](int i, int j) { return (j - 1) * (around + 1) + i; };
  auto face = [&](std::initializer_list<std::pair<int, int>> corners) {  // (vertex, uv)
    c.face_offsets.push_back(int(c.face_vertices.size()));
    c.face_sizes.push_back(int(corners.size()));
    for (const auto& [v, t] : corners) {
      c.face_vertices.push_back(v);
      c.face_uvs.push_back(t);
    }
  };
  // Counter-clockwise seen from outside: +longitude (i) then +latitude (j); longitude runs so that
  // d/dlon x d/dlat points out (z = -sin(lon)).
  for (int j = 1; j < rings; ++j)
    for (int i = 0; i < around; ++i)
      face({{vertex(i, j), uv(i, j)},
            {vertex(i + 1, j), uv(i + 1, j)},
            {vertex(i + 1, j + 1), uv(i + 1, j + 1)},
            {vertex(i, j + 1), uv(i, j + 1)}});
  for (int k = 0; k < pole_valence && triangle_poles; ++k) {
    face({{south, pole_uvs + k}, {vertex(k + 1, 1), uv(k + 1, 1)}, {vertex(k, 1), uv(k, 1)}});
    face({{north, pole_uvs + pole_valence + k},
          {vertex(k, rings), uv(k, rings)},
          {vertex(k + 1, rings), uv(k + 1, rings)}});
  }
  for (int k = 0; k < pole_valence && !triangle_poles; ++k) {
    const int i = 2 * k;
    face({{south, pole_uvs + k},
          {vertex(i + 2, 1), uv(i + 2, 1)},
          {vertex(i + 1, 1), uv(i + 1, 1)},
          {vertex(i, 1), uv(i, 1)}});
    face({{north, pole_uvs + pole_valence + k},
          {vertex(i, rings), uv(i, rings)},
          {vertex(i + 1, rings), uv(i + 1, rings)},
          {vertex(i + 2, rings), uv(i + 2, rings)}});
  }
  return c;
}

}  // namespace tessera
