// A rig in one pose: the nodes' local transforms and morph weights turned into the matrices and
// weights the vertex shader applies to each control point (cage_rig.h states the formula).
//
// Contract
// - Node and joint matrices are composed in double and rounded to float once, so a pose does not
//   accumulate float error down a deep hierarchy; the per-vertex work (pose_vertex) is float, in a
//   fixed order (targets ascending, then influences ascending), with no contraction: the same
//   control point gives the same bits on every thread and in every pass that poses it.
// - An identity node matrix and zero morph weights give back the bind position's exact bits.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include "shaders_cpp/animation/cage_rig.h"

namespace tessera {

// A node's local state: TRS (ignored for matrix nodes) and its morph weights.
struct NodeState {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 scale{1.0};
  std::vector<double> weights;
};

struct RigPose {
  std::vector<glm::mat4> instance_matrices;            // per instance: its node's world matrix
  std::vector<std::vector<glm::mat4>> joint_matrices;  // per instance: world(joint) * inverse bind (skinned)
  std::vector<float> target_weights;                   // per morph target
};

// The nodes as the file gives them (no animation).
std::vector<NodeState> rest_nodes(const CageRig& rig);
// The pose of the given node states (one per rig node).
RigPose pose_of(const CageRig& rig, std::span<const NodeState> nodes);
inline RigPose rest_pose(const CageRig& rig) { return pose_of(rig, rest_nodes(rig)); }

// Control point v, whose bind position is `bind` (rig.bind_positions[v]), in the pose.
inline glm::vec3 pose_vertex(const CageRig& rig, const RigPose& pose, std::size_t v, const glm::vec3& bind) {
  const std::size_t i = std::size_t(rig.vertex_instance[v]);
  const RigInstance& inst = rig.instances[i];
  glm::vec3 m = bind;
  for (int t = inst.first_target; t < inst.first_target + inst.target_count; ++t) {
    const float w = pose.target_weights[std::size_t(t)];
    if (w != 0.0f) m += w * rig.target_deltas[std::size_t(t)][v];
  }
  const glm::vec4 h(m, 1.0f);
  if (inst.skin < 0) return glm::vec3(pose.instance_matrices[i] * h);
  const std::vector<glm::mat4>& joints = pose.joint_matrices[i];
  glm::vec3 out(0.0f);
  for (int k = 0; k < CageRig::kMaxInfluences; ++k) {
    const float w = rig.weights[v][std::size_t(k)];
    if (w != 0.0f) out += w * glm::vec3(joints[rig.joints[v][std::size_t(k)]] * h);
  }
  return out;
}

// Every control point in the pose (the vertex shader's outputs, for the passes that need them before
// the draw: LOD, culling bounds, PN normals, the exact limit surface, overlays).
std::vector<glm::vec3> pose_positions(const CageRig& rig, const RigPose& pose);

}  // namespace tessera
