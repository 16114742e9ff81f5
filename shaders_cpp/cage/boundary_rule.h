// OpenSubdiv's boundary interpolation rule `none` (Sdc::Options::VTX_BOUNDARY_NONE) as faces without a
// surface: Far::TopologyRefinerFactory makes a face a hole when one of its vertices has an incident
// boundary edge (one face) that is not infinitely sharp. The other faces keep the surface they have under
// `edge_only` (the faces made holes still take part in the refinement), so a scheme honours the rule by
// drawing nothing for these faces, exactly as for tagged holes.
//
// Cost: O(face corners).
#pragma once

#include <vector>

#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"

namespace tessera {

// Per face: true when the cage's boundary rule gives it no surface (always false unless the rule is
// `none`). Tagged holes are not included (Topology::is_hole).
std::vector<bool> faces_without_surface(const Cage& cage, const Topology& topology);

}  // namespace tessera
