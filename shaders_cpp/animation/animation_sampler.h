// glTF animation samplers evaluated at a time: the node states an animation gives (rig_pose.h turns
// them into a pose).
//
// Contract (glTF 2.0 §3.11): before the first key a channel holds its first value, after the last its
// last; STEP holds the previous key; LINEAR interpolates, rotations by spherical linear interpolation
// along the shorter arc; CUBICSPLINE is the Hermite spline of the keys' values and tangents (scaled by
// the key interval), rotations normalised after. Evaluated in double; a time that is not finite is the
// caller's error (the CLI refuses it).
#pragma once

#include <string>
#include <vector>

#include "shaders_cpp/animation/cage_rig.h"
#include "shaders_cpp/animation/rig_pose.h"

namespace tessera {

// The rest nodes with animation `animation`'s channels applied at `time` seconds.
std::vector<NodeState> animate_nodes(const CageRig& rig, int animation, double time);
inline RigPose pose_at(const CageRig& rig, int animation, double time) {
  return pose_of(rig, animate_nodes(rig, animation, time));
}

// The animation named `name` (or given by its index as text); -1 when there is none such.
int find_animation(const CageRig& rig, const std::string& name);

}  // namespace tessera
