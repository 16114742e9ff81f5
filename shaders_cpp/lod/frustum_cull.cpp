#include "shaders_cpp/lod/frustum_cull.h"

namespace tessera {

std::optional<PatchCullMode> parse_patch_cull_mode(std::string_view name) {
  if (name == "none") return PatchCullMode::none;
  if (name == "frustum" || name == "all") return PatchCullMode::frustum;
  return std::nullopt;
}

const char* to_string(PatchCullMode m) { return m == PatchCullMode::frustum ? "frustum" : "none"; }

}  // namespace tessera
