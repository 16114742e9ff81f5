#include "shaders_cpp/lod/frustum_cull.h"

namespace tessera {

std::optional<PatchCullMode> parse_patch_cull_mode(std::string_view name) {
  for (const PatchCullMode m :
       {PatchCullMode::none, PatchCullMode::frustum, PatchCullMode::backface, PatchCullMode::all})
    if (name == to_string(m)) return m;
  return std::nullopt;
}

const char* to_string(PatchCullMode m) {
  switch (m) {
    case PatchCullMode::none: return "none";
    case PatchCullMode::frustum: return "frustum";
    case PatchCullMode::backface: return "backface";
    case PatchCullMode::all: return "all";
  }
  return "none";
}

}  // namespace tessera
