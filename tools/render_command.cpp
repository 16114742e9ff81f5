// `tessera render CAGE.obj --scheme S -o out.png`: the cage's surface through the whole pipeline, with
// an automatic camera that frames it (or one given), in one of the views of render_views.h: shaded,
// wireframes, and the debug views of factors, density, patch types, UVs, the cage, cracks and culling.
// --stats writes the pipeline statistics and a row per patch (render_stats.h).
#include <iostream>

#include "tools/cli_common.h"
#include "tools/commands.h"
#include "tools/json_output.h"
#include "tools/render_stats.h"
#include "tools/render_views.h"
#include "tools/tessellate_options.h"
#include "tools/view_options.h"

namespace tessera::cli {
namespace {

struct RenderOptions {
  std::string cage, output, scheme = "gregory", partitioning = "integer", factors_file, view = "shaded";
  std::string factor_kind = "raw";
  CameraCli camera;
  LodCli lod;
  float factor = 8.0f, vary = 0.0f;
  int threads = 0;
  std::string stats;
  DisplacementCli displacement;
};

int run_render(const RenderOptions& o) {
  const Scheme scheme = scheme_option(o.scheme);
  const ts::Partitioning partitioning = partitioning_option(o.partitioning);
  SubdFactors factors = factors_option(o.factor, o.vary, o.factors_file);
  const auto kind = parse_view(o.view);
  if (!kind) throw UsageError("--view: '" + o.view + "' is not one of " + view_names());
  if (o.factor_kind != "raw" && o.factor_kind != "processed")
    throw UsageError("--factor-kind: '" + o.factor_kind + "' is not raw or processed");
  if (o.output.empty()) throw UsageError("-o out.png is required");

  const SubdModel model = load_model(o.cage, scheme);
  std::optional<Displacement> displacement = displacement_option(o.displacement, model);
  const ViewSetup view = view_option(o.camera, model.cage);
  const LodResult lod = apply_lod_options(o.lod, view, model, displacement ? &*displacement : nullptr, factors);

  Device device(device_options(o.threads));
  std::string error;
  auto fb = Framebuffer::create(view.width, view.height, ColorFormat::rgba8_unorm, &error);
  if (!fb) throw UsageError(error);
  const ViewInputs inputs{model,
                          displacement ? &*displacement : nullptr,
                          factors,
                          partitioning,
                          view,
                          o.lod.edge_pixels,
                          o.factor_kind == "processed"};
  // Per-patch facts, replayed once for the view and the statistics.
  std::optional<PatchTables> tables;
  if (view_uses_patch_tables(*kind) || !o.stats.empty()) tables = view_patch_tables(inputs);
  const ViewOutput out = render_view(device, *kind, inputs, tables ? &*tables : nullptr, *fb);
  if (!out.result.ok()) throw InputError(o.cage + ": " + out.result.error);
  const DrawReport& total = out.result.report;
  if (out.has_legend) {
    write_with_legend(*fb, out.legend, o.output);
  } else if (auto e = fb->write_color(o.output); !e.empty()) {
    throw InputError(e);
  }
  if (!o.stats.empty()) {
    Json s = {{"statistics", to_json(total.statistics)},
              {"times", to_json(total.times)},
              {"memory", to_json(total.memory)},
              {"peak_rss_bytes", peak_rss_bytes()}};
    add_patch_statistics(s, device, inputs, *tables, lod);
    if (*kind == ViewKind::cracks)
      s["cracks"] = {{"open_edges", out.open_edges}, {"nonmanifold_edges", out.nonmanifold_edges}};
    write_text_atomically(o.stats, json_text(s) + "\n");
  }
  std::cout << o.output << ": " << view.width << "x" << view.height << ", scheme " << to_string(scheme) << ", view "
            << to_string(*kind) << ", " << total.statistics.CInvocations << " triangles, " << total.patches_culled
            << " patches culled, " << total.patches_back_culled << " facing away, " << total.statistics.PSInvocations
            << " pixels shaded";
  if (*kind == ViewKind::cracks) std::cout << ", " << out.open_edges << " open edges";
  std::cout << "\n";
  return kExitOk;
}

}  // namespace

Runner add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "render a cage's subdivision surface to an image");
  cmd->add_option("cage", o->cage, "the cage (OBJ, OpenSubdiv tags allowed)")->required();
  cmd->add_option("-o,--output", o->output, "output image (PNG or EXR)");
  add_scheme_options(*cmd, o->scheme, o->factor, o->vary, o->factors_file, o->partitioning, o->threads);
  add_camera_options(*cmd, o->camera);
  add_lod_options(*cmd, o->lod, "all");
  cmd->add_option("--view", o->view, view_names())->capture_default_str();
  cmd->add_option("--factor-kind", o->factor_kind, "--view factors: raw (as the hull shader gave them) or processed")
      ->capture_default_str();
  add_displacement_options(*cmd, o->displacement);
  cmd->add_option("--stats", o->stats,
                  "write D3D11 pipeline statistics, stage times, memory, a row per patch and histograms as JSON");
  return [o] { return run_render(*o); };
}

}  // namespace tessera::cli
