// Internal (not part of the public API): builds an OpenSubdiv Far::TopologyRefiner from a Cage.
// Only .cpp files of tessera_shaders include this header, so no OpenSubdiv type leaks out of the
// library and osdCPU stays a PRIVATE dependency.
//
// Contract: `build_osd_refiner` validates the cage as `validate_cage` (topology.h) does, then checks
// OpenSubdiv's own limits (face size, valence), and throws a one-line tessera::CageError naming the
// element; it returns a refiner with only the base level (no refinement). Creases and corners reach
// OpenSubdiv as the topology resolved them (creases on vertex pairs that are no edge are ignored).
#pragma once

#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/sdc/options.h>

#include <memory>
#include <vector>

#include "shaders_cpp/cage/cage.h"

namespace tessera::subdiv {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;

// Sdc options from the cage's tags. Left-handedness is deliberately not passed to OpenSubdiv: it
// does not change the limit surface, and keeping the file's face order keeps Bfr's face
// parameterization aligned with the cage's corner order (our domain convention); normals are
// flipped by the caller instead.
osd::Sdc::Options sdc_options(const CageTags& tags);

// Sends OpenSubdiv's warnings and errors (printf to stdout by default) to stderr, one line each,
// prefixed "OpenSubdiv: "; once per process. build_osd_refiner calls it.
void route_osd_messages();

// `far_faces`, when given, receives needs_far_patches of the cage (far_patches.h), from the topology the
// refiner is built from (so a LimitSurface builds it once per pose).
std::unique_ptr<osd::Far::TopologyRefiner> build_osd_refiner(const Cage& cage, std::vector<int>* far_faces = nullptr);

// Cage name for messages ("cage" when empty).
std::string cage_label(const Cage& cage);

}  // namespace tessera::subdiv
