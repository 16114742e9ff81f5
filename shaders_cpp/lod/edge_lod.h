// View-dependent tessellation factors, one per cage edge (the talk's continuous, view-dependent LOD).
//
// Contract
// - A factor is a pure function of one cage edge's own data (its two end control points, the dicing
//   camera and the settings), computed once per edge and stored by cage_edge_key (subd_patches.h):
//   the two patches that share the edge read the same bits, so no crack can come from the factors.
//   Inside factors follow from the edge factors in SubdHS::patch_constants (the mean of the opposite
//   edges; a triangle's, of its three edges).
// - uniform: every edge gets `factor`.
//   distance: factor * lod_distance / |midpoint - eye|, clamped to [1, 64].
//   screen: the projected diameter, in pixels, of the edge's bounding sphere over `edge_pixels`,
//   clamped to [1, 64]. The sphere is centred on the midpoint of the two end control points with
//   radius half their distance, grown by the displacement bound. Why the end points and not a bound
//   of the limit curve: the limit curve of a cage edge stays within the hull of the 1-rings at both
//   ends, and is shorter than the cage edge except at creases; the chord is what both faces have
//   without evaluating anything, and a sphere (rather than the projected chord) keeps an edge seen
//   end-on, on a silhouette, from collapsing to factor 1 (OpenSubdiv's rule).
//   The projected diameter is 2 r / sqrt(d^2 - r^2) * pixels_per_unit (the silhouette's angular size),
//   d the distance from the eye to the centre (rotation invariant: turning the camera does not
//   retessellate); it grows without bound as the eye nears the sphere, so the factor reaches 64
//   continuously, and an eye inside the sphere gives 64.
// - The result is continuous in the camera position, so with fractional partitioning a moving camera
//   changes the tessellation without popping.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <unordered_map>

#include <glm/glm.hpp>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"

namespace tessera {

enum class LodMode : std::uint8_t { uniform, distance, screen };
std::optional<LodMode> parse_lod_mode(std::string_view name);
const char* to_string(LodMode m);

inline constexpr float kMaxLodFactor = 64.0f;

// Where factors are measured from: RenderMan's "dicing camera". It may differ from the view camera
// (a frozen tessellation the view flies around).
struct DicingCamera {
  glm::vec3 eye{0.0f};
  // Pixels that one object unit covers at unit distance: (viewport height / 2) / tan(fov_y / 2).
  float pixels_per_unit = 1.0f;
};
float pixels_per_unit(int viewport_height, float fov_y_degrees);

struct LodSettings {
  LodMode mode = LodMode::uniform;
  float factor = 8.0f;        // uniform: every edge; distance: the factor at lod_distance
  float edge_pixels = 8.0f;   // screen: target pixels per segment
  float lod_distance = 1.0f;  // distance: where an edge gets `factor`
  float bound = 0.0f;         // grows every edge's sphere (the displacement bound, object units)
  DicingCamera camera;
};

// The diameter in pixels of the silhouette of a sphere seen from the camera: 2 r / sqrt(d^2 - r^2)
// pixels per unit; infinite when the eye is inside the sphere.
float projected_diameter(const glm::vec3& centre, float radius, const DicingCamera& camera);

// The factor of the cage edge from p0 to p1 (either order gives the same bits).
float edge_lod_factor(const glm::vec3& p0, const glm::vec3& p1, const LodSettings& s);

// Every cage edge's factor, keyed by cage_edge_key(origin, destination), from the control points as
// the vertex shader outputs them (SubdModel::positions(): the posed cage when animated).
using EdgeFactorTable = std::unordered_map<std::int64_t, float>;
std::shared_ptr<const EdgeFactorTable> edge_lod_factors(std::span<const glm::vec3> positions, const Topology& topology,
                                                        const LodSettings& s);

}  // namespace tessera
