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

namespace tessera::cli {
namespace {

struct RenderOptions {
  std::string cage, output, scheme = "gregory", partitioning = "integer", factors_file, view = "shaded";
  std::string resolution = "1920x1080", eye, target;
  float factor = 8.0f, vary = 0.0f, fov = 35.0f;
  int threads = 0;
  std::string stats;
  DisplacementCli displacement;
};

glm::vec3 parse_vec3(const std::string& text, const char* what) {
  const auto v = parse_float_list(text, what);
  if (v.size() != 3) throw UsageError(std::string(what) + ": expected x,y,z");
  for (float x : v)
    if (!std::isfinite(x)) throw UsageError(std::string(what) + ": not finite");
  return {v[0], v[1], v[2]};
}

int run_render(const RenderOptions& o) {
  const Scheme scheme = scheme_option(o.scheme);
  const ts::Partitioning partitioning = partitioning_option(o.partitioning);
  const SubdFactors factors = factors_option(o.factor, o.vary, o.factors_file);
  const auto [w, h] = parse_resolution(o.resolution);
  if (!(o.fov > 1.0f && o.fov < 179.0f)) throw UsageError("--fov: must be in (1, 179) degrees");
  if (o.view != "shaded" && o.view != "wireframe" && o.view != "wire-on-shaded")
    throw UsageError("--view: '" + o.view + "' is not shaded, wireframe or wire-on-shaded");
  if (o.output.empty()) throw UsageError("-o out.png is required");

  const SubdModel model = load_model(o.cage, scheme);
  const std::optional<Displacement> displacement = displacement_option(o.displacement, model);
  std::optional<glm::vec3> eye, target;
  if (!o.eye.empty()) eye = parse_vec3(o.eye, "--camera-position");
  if (!o.target.empty()) target = parse_vec3(o.target, "--camera-target");
  if (eye && target && glm::length(*eye - *target) <= 0.0f) throw UsageError("camera position and target coincide");
  const SubdCamera camera = frame_cage(model.cage, w, h, o.fov, eye, target);

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
  cmd->add_option("--resolution", o->resolution, "WxH")->capture_default_str();
  cmd->add_option("--camera-position", o->eye, "x,y,z (default: framing the model)");
  cmd->add_option("--camera-target", o->target, "x,y,z (default: the model's centre)");
  cmd->add_option("--fov", o->fov, "vertical field of view, degrees")->capture_default_str();
  cmd->add_option("--view", o->view, "shaded, wireframe or wire-on-shaded")->capture_default_str();
  add_displacement_options(*cmd, o->displacement);
  cmd->add_option("--stats", o->stats, "write D3D11 pipeline statistics, stage times, memory and peak RSS as JSON");
  return [o] { return run_render(*o); };
}

}  // namespace tessera::cli
