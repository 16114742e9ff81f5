// `tessera optimize CAGE -o OUT.obj`: the same cage with start corners rotated for the fewest stored
// topology combinations and consistent adjacency, and faces and vertices reordered for locality
// (shaders_cpp/optimize/cage_optimize.h). Before -> after on stderr, or as JSON.
#include <iostream>

#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/optimize/cage_optimize.h"
#include "shaders_cpp/render/subd_model.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct OptimizeCli {
  AssetSettings asset;
  std::string cage, output;
  bool no_rotate = false, no_reorder = false, json = false;
};

int run_optimize(const OptimizeCli& o) {
  check_output_paths({{"-o", o.output}}, {o.cage});
  Cage cage;
  OptimizedCage result;
  try {
    cage = load_cage(o.cage, gltf_selection(o.cage, o.asset));
    result = optimize_cage(cage, {!o.no_rotate, !o.no_reorder});
  } catch (const CageError& e) {
    throw InputError(e.what());
  }
  for (const std::string& w : cage.warnings) log_info(w);
  Cage& out = result.cage;
  // OBJ's texture v points up the image; a glTF cage's points down.
  if (out.uv_v_down)
    for (glm::vec2& t : out.uvs) t.y = 1.0f - t.y;
  write_text_atomically(o.output, format_obj_cage(out));
  const CageOptimizeReport& r = result.report;
  if (o.json) {
    const Json j = {
        {"cage", o.cage},
        {"output", o.output},
        {"faces", r.faces},
        {"combinations", r.combinations},
        {"stored_combinations", {{"before", r.stored_before}, {"after", r.stored_after}}},
        {"quad_edges", r.quad_edges},
        {"consistent_edges",
         {{"before", r.consistent_before}, {"canonical", r.consistent_canonical}, {"after", r.consistent_after}}},
        {"acmr", {{"before", r.acmr_before}, {"after", r.acmr_after}}},
        {"atvr", {{"before", r.atvr_before}, {"after", r.atvr_after}}}};
    std::cout << json_text(j) << "\n";
  } else {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s -> %s: %d faces; stored combinations %d -> %d (%d distinct); consistent edges %d -> %d of %d "
                  "(canonical corners alone: %d); "
                  "ACMR %.3f -> %.3f, ATVR %.3f -> %.3f\n",
                  o.cage.c_str(), o.output.c_str(), r.faces, r.stored_before, r.stored_after, r.combinations,
                  r.consistent_before, r.consistent_after, r.quad_edges, r.consistent_canonical, double(r.acmr_before),
                  double(r.acmr_after), double(r.atvr_before), double(r.atvr_after));
    std::cout << line;
  }
  return kExitOk;
}

}  // namespace

Runner add_optimize_command(CLI::App& app) {
  auto o = std::make_shared<OptimizeCli>();
  CLI::App* cmd = app.add_subcommand(
      "optimize", "rotate start corners and reorder faces and vertices of a cage (same limit surface), as OBJ");
  cmd->add_option("cage", o->cage, "the cage: OBJ (OpenSubdiv tags kept) or glTF (.gltf, .glb)")->required();
  cmd->add_option("-o,--output", o->output, "the optimized cage (OBJ)")->required();
  cmd->add_flag("--no-rotate", o->no_rotate, "keep every face's start corner");
  cmd->add_flag("--no-reorder", o->no_reorder, "keep the face and vertex order");
  add_asset_options(*cmd, o->asset, false);
  cmd->add_flag("--json", o->json, "print before and after as JSON");
  return [o] { return run_optimize(*o); };
}

}  // namespace tessera::cli
