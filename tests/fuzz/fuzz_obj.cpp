// libFuzzer harness: OBJ text through the cage reader and the half-edge topology (cage validation).
// Bad input must be a CageError, never a crash, a hang or undefined behaviour.
#include <cstdint>
#include <string_view>

#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/cage/topology_combinations.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const tessera::Cage cage =
        tessera::parse_obj_cage(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.obj");
    const tessera::Topology topology(cage);
    (void)tessera::analyze_combinations(topology);
    // What the reader accepted, the writer writes and the reader reads back the same.
    const tessera::Cage again = tessera::parse_obj_cage(tessera::format_obj_cage(cage), "again.obj");
    if (again.face_vertices != cage.face_vertices || again.positions.size() != cage.positions.size()) __builtin_trap();
  } catch (const tessera::CageError&) {
  }
  return 0;
}
