// libFuzzer harness: OBJ cages with OpenSubdiv's tags (creases, corners, holes, boundary and crease
// rules) through every scheme's model, the exact scheme's OpenSubdiv limit surface included, and a
// point of every face of that surface. A cage a scheme cannot draw must be a CageError, never a
// crash, a hang or undefined behaviour (OpenSubdiv 3.5.0 crashed on a creased valence-2 cage).
#include <cmath>
#include <cstdint>
#include <string_view>

#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/render/subd_model.h"
#include "shaders_cpp/subdiv/limit_surface.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Small cages only: the exact scheme's work grows with the cage and its valences, and what breaks
  // a scheme breaks it on a few faces.
  if (size > 16384) return 0;
  tessera::Cage cage;
  try {
    cage = tessera::parse_obj_cage(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.obj");
  } catch (const tessera::CageError&) {
    return 0;
  }
  if (cage.vertex_count() > 256 || cage.face_count() > 128) return 0;
  for (int k = 0; k < tessera::kSchemeCount; ++k) {
    try {
      const tessera::SubdModel m = tessera::make_subd_model(cage, tessera::Scheme(k));
      if (!m.limit) continue;
      for (int f = 0; f < m.limit->face_count(); ++f)
        for (int s = 0; s < m.limit->sub_patch_count(f); ++s) {
          const tessera::SurfacePoint p = m.limit->evaluate(f, s, 0.5f, 0.25f);
          // A surface that was built is finite (LimitSurface::create refuses one that is not).
          if (!std::isfinite(p.position.x + p.position.y + p.position.z)) __builtin_trap();
        }
    } catch (const tessera::CageError&) {
    }
  }
  return 0;
}
