#include "shaders_cpp/animation/rig_pose.h"

#include <glm/gtc/matrix_transform.hpp>

namespace tessera {

std::vector<NodeState> rest_nodes(const CageRig& rig) {
  std::vector<NodeState> nodes(rig.nodes.size());
  for (std::size_t n = 0; n < rig.nodes.size(); ++n) {
    const RigNode& r = rig.nodes[n];
    nodes[n].translation = r.translation;
    nodes[n].rotation = r.rotation;
    nodes[n].scale = r.scale;
    nodes[n].weights = r.weights;
  }
  return nodes;
}

RigPose pose_of(const CageRig& rig, std::span<const NodeState> nodes) {
  std::vector<glm::dmat4> world(rig.nodes.size(), glm::dmat4(1.0));
  for (const int n : rig.node_order) {
    const RigNode& r = rig.nodes[std::size_t(n)];
    const NodeState& s = nodes[std::size_t(n)];
    glm::dmat4 local = r.matrix;
    if (!r.has_matrix)
      local = glm::translate(glm::dmat4(1.0), s.translation) * glm::mat4_cast(glm::normalize(s.rotation)) *
              glm::scale(glm::dmat4(1.0), s.scale);
    world[std::size_t(n)] = r.parent >= 0 ? world[std::size_t(r.parent)] * local : local;
  }
  RigPose pose;
  pose.instance_matrices.resize(rig.instances.size());
  pose.joint_matrices.resize(rig.instances.size());
  pose.target_weights.assign(std::size_t(rig.target_count()), 0.0f);
  for (std::size_t i = 0; i < rig.instances.size(); ++i) {
    const RigInstance& inst = rig.instances[i];
    pose.instance_matrices[i] = glm::mat4(world[std::size_t(inst.node)]);
    if (inst.skin >= 0) {
      const RigSkin& skin = rig.skins[std::size_t(inst.skin)];
      for (std::size_t j = 0; j < skin.joints.size(); ++j)
        pose.joint_matrices[i].push_back(
            glm::mat4(world[std::size_t(skin.joints[j])] * glm::dmat4(skin.inverse_bind[j])));
    }
    const std::vector<double>& w = nodes[std::size_t(inst.node)].weights;
    for (int t = 0; t < inst.target_count && t < int(w.size()); ++t)
      pose.target_weights[std::size_t(inst.first_target + t)] = float(w[std::size_t(t)]);
  }
  return pose;
}

std::vector<glm::vec3> pose_positions(const CageRig& rig, const RigPose& pose) {
  std::vector<glm::vec3> out(rig.bind_positions.size());
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = pose_vertex(rig, pose, v, rig.bind_positions[v]);
  return out;
}

}  // namespace tessera
