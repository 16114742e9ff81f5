// How a cage moves: glTF's node hierarchy, skins, morph targets and animations, bound to the cage's
// control points. Plain data, filled by the glTF reader (shaders_cpp/gltf/gltf_cage.h) and evaluated by
// shaders_cpp/animation/ (a pose at a time) and the vertex shader (each control point in that pose).
//
// Contract
// - Every cage vertex v belongs to one instance (a node that draws a mesh): `vertex_instance[v]`.
//   Its position in the pose is, as glTF 2.0 defines it (§3.7.3 skins, §3.7.2.2 morph targets):
//     m = bind_positions[v] + sum over the instance's targets t of weight[t] * target_deltas[t][v]
//     rigid instance:   M(node) m                      (M = the node's world matrix)
//     skinned instance: sum_i w_i J(joint_i) m         (J = world(joint) * inverse bind matrix)
//   A skinned instance ignores its own node's transform, as the spec says.
// - Influences are normalised at load (weights sum to 1 within float rounding), with at most
//   kMaxInfluences per vertex; joints index the instance's skin's `joints`.
// - `node_order` lists every node reachable from the scene's roots with parents before children.
// - The rest pose (no animation) is the nodes' own TRS or matrix and the default morph weights; the
//   cage's positions (Cage::positions) are that pose.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace tessera {

struct RigNode {
  std::string name;
  int parent = -1;
  // As the JSON gives them (double): TRS nodes compose T * R * S.
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z)
  glm::dvec3 scale{1.0};
  // A node given by `matrix` is fixed (glTF forbids animating it).
  bool has_matrix = false;
  glm::dmat4 matrix{1.0};
  std::vector<double> weights;  // default morph weights of the mesh it draws (node's, else the mesh's)
};

struct RigSkin {
  std::string name;
  std::vector<int> joints;  // node indices
  std::vector<glm::mat4> inverse_bind;
};

// A node drawing a mesh: its vertices are a contiguous run of the cage's.
struct RigInstance {
  int node = 0;
  int skin = -1;                           // index into skins, or -1: rigid
  int first_target = 0, target_count = 0;  // its morph targets in target_deltas
};

enum class AnimationPath : std::uint8_t { translation, rotation, scale, weights };
enum class Interpolation : std::uint8_t { linear, step, cubic_spline };

// One animated property of one node. `values` holds `width` floats per key (3 translation/scale,
// 4 rotation as x y z w, the morph target count for weights); cubic_spline keys hold three such
// groups, in-tangent, value, out-tangent (glTF's layout).
struct AnimationChannel {
  int node = 0;
  AnimationPath path = AnimationPath::translation;
  Interpolation interpolation = Interpolation::linear;
  int width = 3;
  std::vector<float> times;  // strictly increasing, seconds
  std::vector<float> values;
};

struct Animation {
  std::string name;
  std::vector<AnimationChannel> channels;
  float start = 0.0f, end = 0.0f;  // first and last key time over all channels
};

struct CageRig {
  static constexpr int kMaxInfluences = 8;
  std::vector<RigNode> nodes;
  std::vector<int> node_order;
  std::vector<RigSkin> skins;
  std::vector<RigInstance> instances;
  std::vector<Animation> animations;

  // Per cage vertex.
  std::vector<glm::vec3> bind_positions;  // the mesh's own POSITION (mesh space)
  std::vector<int> vertex_instance;
  std::vector<std::array<std::uint16_t, kMaxInfluences>> joints;  // skinned vertices only (else empty)
  std::vector<std::array<float, kMaxInfluences>> weights;
  // Per morph target, per cage vertex (zero outside the target's instance).
  std::vector<std::vector<glm::vec3>> target_deltas;
  std::vector<std::string> target_names;

  bool skinned() const { return !joints.empty(); }
  // Appends, for each cage vertex from vertices() on, a copy of the per-vertex data of vertex
  // `source[v]` (the cage's Cage::vertex_source after a non-manifold split), so the copies move with it.
  void copy_vertices(const std::vector<int>& source) {
    for (std::size_t v = bind_positions.size(); v < source.size(); ++v) {
      const std::size_t s = std::size_t(source[v]);
      bind_positions.push_back(bind_positions[s]);
      vertex_instance.push_back(vertex_instance[s]);
      if (!joints.empty()) joints.push_back(joints[s]), weights.push_back(weights[s]);
      for (auto& d : target_deltas) d.push_back(d[s]);
    }
  }
  int target_count() const { return static_cast<int>(target_deltas.size()); }
};

}  // namespace tessera
