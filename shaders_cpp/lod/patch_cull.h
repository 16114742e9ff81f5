// The hull shader's cull policy: which patches it proves invisible before the tessellator, by the
// frustum (frustum_cull.h: zero factors) and by orientation (back_patch_cull.h: a bound the device
// tests before the DS). Neither test can change a pixel.
//
// Contract: a policy is a value made once per view (apply_lod); a pass drawn with a depth bias (the
// wireframe over the shaded surface) draws with with_depth_bias(bias), so each test sees the depth the
// pass's clip positions get. The factor table (SubdFactors) is the other input of the hull shader.
#pragma once

#include "shaders_cpp/lod/back_patch_cull.h"
#include "shaders_cpp/lod/frustum_cull.h"

namespace tessera {

struct PatchCull {
  FrustumCull frustum;  // disabled by default
  BackPatchCull back;   // disabled by default

  PatchCull with_depth_bias(float z_bias) const {
    PatchCull c = *this;
    c.frustum.z_bias = z_bias;
    c.back.z_bias = z_bias;
    return c;
  }
};

}  // namespace tessera
