// libFuzzer harness: glTF (JSON or GLB bytes) through the glTF reader, the rest pose, a pose of its
// first animation and the topology. Bad input must be a CageError, never a crash or a hang.
#include <cmath>
#include <cstdint>
#include <span>

#include "shaders_cpp/animation/animation_sampler.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/gltf/gltf_cage.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const tessera::GltfCage g =
        tessera::parse_gltf_cage(std::span<const std::uint8_t>(data, size), "/nonexistent/fuzz.gltf");
    if (g.rig) {
      const auto& rig = *g.rig;
      for (const double t : {-1.0, 0.0, 0.37, 1e6}) {
        const auto posed = tessera::pose_positions(rig, tessera::pose_at(rig, rig.animations.empty() ? -1 : 0, t));
        if (posed.size() != g.cage.positions.size()) __builtin_trap();
      }
    }
    const tessera::Topology topology(g.cage);
    (void)topology;
  } catch (const tessera::CageError&) {
  }
  return 0;
}
