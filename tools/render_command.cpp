// `tessera render CAGE.obj --scheme S -o out.png`: the cage's surface through the whole pipeline, with
// an automatic camera that frames it (or one given), shaded, wireframe, or wireframe over shading.
#include <cmath>
#include <iostream>
#include <sstream>

#include "tools/cli_common.h"
#include "tools/commands.h"
#include "tools/json_output.h"
#include "shaders_cpp/displaced_render.h"
#include "shaders_cpp/subd_render.h"
#include "tools/tessellate_options.h"
#include "tools/view_options.h"

namespace tessera::cli {
namespace {

struct RenderOptions {
  std::string cage, output, scheme = "gregory", partitioning = "integer", factors_file, view = "shaded";
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
  if (o.view != "shaded" && o.view != "wireframe" && o.view != "wire-on-shaded")
    throw UsageError("--view: '" + o.view + "' is not shaded, wireframe or wire-on-shaded");
  if (o.output.empty()) throw UsageError("-o out.png is required");

  const SubdModel model = load_model(o.cage, scheme);
  const std::optional<Displacement> displacement = displacement_option(o.displacement, model);
  const ViewSetup view_setup = view_option(o.camera, model.cage);
  const int w = view_setup.width, h = view_setup.height;
  const SubdCamera& camera = view_setup.camera;
  apply_lod_options(o.lod, view_setup, o.camera.fov, model, displacement ? displacement->bound : 0.0f, factors);

  Device device(device_options(o.threads));
  std::string error;
  auto fb = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error);
  if (!fb) throw UsageError(error);
  fb->clear(glm::vec4(0.93f, 0.94f, 0.96f, 1.0f), 1.0f);
  const SubdView view = o.view == "shaded"      ? SubdView::shaded
                        : o.view == "wireframe" ? SubdView::wireframe
                                                : SubdView::wire_on_shaded;
  const DrawResult result =
      displacement ? render_displaced(device, model, *displacement, factors, partitioning, view, camera, *fb)
                   : render_subd(device, model, factors, partitioning, view, camera, *fb);
  if (!result.ok()) throw InputError(o.cage + ": " + result.error);
  const DrawReport& total = result.report;
  if (auto e = fb->write_color(o.output); !e.empty()) throw InputError(e);
  if (!o.stats.empty()) {
    const Json s = {{"statistics", to_json(total.statistics)},
                    {"times", to_json(total.times)},
                    {"memory", to_json(total.memory)},
                    {"peak_rss_bytes", peak_rss_bytes()}};
    write_text_atomically(o.stats, json_text(s) + "\n");
  }
  std::cout << o.output << ": " << w << "x" << h << ", scheme " << to_string(scheme) << ", "
            << total.statistics.CInvocations << " triangles, " << total.statistics.PSInvocations << " pixels shaded\n";
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
  cmd->add_option("--view", o->view, "shaded, wireframe or wire-on-shaded")->capture_default_str();
  add_displacement_options(*cmd, o->displacement);
  cmd->add_option("--stats", o->stats, "write D3D11 pipeline statistics, stage times, memory and peak RSS as JSON");
  return [o] { return run_render(*o); };
}

}  // namespace tessera::cli
