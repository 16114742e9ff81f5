// Rendering a displaced SubdModel: the shaded (normal-mapped or derived-normal), wireframe and
// wire-on-shaded views of subd_render.h, through the displaced shaders.
#pragma once

#include "shaders_cpp/render/displaced_model.h"
#include "shaders_cpp/render/subd_render.h"

namespace tessera {

DrawResult render_displaced(Device& device, const SubdModel& model, const Displacement& displacement,
                            const SubdFactors& factors, const PatchCull& cull, ts::Partitioning partitioning,
                            SubdView view, const SubdCamera& camera, Framebuffer& fb);

// render_displaced when `displacement` is given, else render_subd.
DrawResult render_surface(Device& device, const SubdModel& model, const Displacement* displacement,
                          const SubdFactors& factors, const PatchCull& cull, ts::Partitioning partitioning,
                          SubdView view, const SubdCamera& camera, Framebuffer& fb);

}  // namespace tessera
