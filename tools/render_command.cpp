// `tessera render CAGE.obj --scheme S -o out.png`: the cage's surface through the whole pipeline, with
// an automatic camera that frames it (or one given), shaded, wireframe, or wireframe over shading.
#include <cmath>
#include <iostream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "cli_common.h"
#include "commands.h"
#include "subd_model.h"
#include "tessellate_options.h"

namespace tessera::cli {
namespace {

struct RenderOptions {
  std::string cage, output, scheme = "gregory", partitioning = "integer", factors_file, view = "shaded";
  std::string resolution = "1920x1080", eye, target;
  float factor = 8.0f, vary = 0.0f, fov = 35.0f;
  int threads = 0;
  std::string stats;
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
  int w = 0, h = 0;
  if (std::sscanf(o.resolution.c_str(), "%dx%d", &w, &h) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw UsageError("--resolution: '" + o.resolution + "' is not WxH with 1..16384 each");
  if (!(o.fov > 1.0f && o.fov < 179.0f)) throw UsageError("--fov: must be in (1, 179) degrees");
  if (o.view != "shaded" && o.view != "wireframe" && o.view != "wire-on-shaded")
    throw UsageError("--view: '" + o.view + "' is not shaded, wireframe or wire-on-shaded");
  if (o.output.empty()) throw UsageError("-o out.png is required");

  SubdModel model;
  try {
    model = load_subd_model(o.cage, scheme);
  } catch (const CageError& e) {
    throw InputError(e.what());
  }
  // Frame the cage's bounding sphere (the limit surface lies inside the cage's hull).
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const auto& p : model.cage.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = std::max(1e-6f, 0.5f * glm::length(hi - lo));
  const float aspect = float(w) / float(h);
  const float fov = glm::radians(o.fov);
  const float fit = std::min(fov, 2.0f * std::atan(std::tan(0.5f * fov) * aspect));
  const glm::vec3 target = o.target.empty() ? centre : parse_vec3(o.target, "--camera-target");
  const glm::vec3 eye = o.eye.empty() ? centre + glm::normalize(glm::vec3(0.35f, 0.25f, 1.0f)) * (radius / std::tan(0.5f * fit) * 0.8f)
                                      : parse_vec3(o.eye, "--camera-position");
  if (glm::length(eye - target) <= 0.0f) throw UsageError("camera position and target coincide");
  const float distance = glm::length(eye - target);
  const glm::mat4 view = glm::lookAtRH(eye, target, glm::vec3(0, 1, 0));
  const glm::mat4 proj = glm::perspectiveRH_ZO(fov, aspect, std::max(1e-4f, distance - 2.0f * radius) * 0.5f,
                                               distance + 2.0f * radius);
  const glm::mat4 vp = proj * view;

  DeviceOptions dopt;
  dopt.threads = o.threads;
  Device device(dopt);
  std::string error;
  auto fb = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, &error);
  if (!fb) throw UsageError(error);
  fb->clear(glm::vec4(0.93f, 0.94f, 0.96f, 1.0f), 1.0f);

  DrawReport total;
  const std::span<const glm::vec3> vertices(model.cage.positions);
  SubdDS ds{{}, model.limit.get(), model.cage.tags.left_handed};
  auto draw_pass = [&](bool wire) {
    for (const PatchGroup* g : {&model.patches.quads, &model.patches.tris}) {
      if (g->patches.empty()) continue;
      TessellatorState ts{g->domain, partitioning, ts::OutputPrimitive::triangle_cw};
      ds.patches = g->patches;
      ds.triangles = g->domain == ts::Domain::tri;
      RasterizerState rs;
      rs.cull = model.cage.tags.left_handed ? CullMode::front : CullMode::back;
      // Patches emit triangle_cw, which is counter-clockwise seen from outside a counter-clockwise cage;
      // after the viewport's y flip, D3D calls that winding counter-clockwise on screen.
      rs.front_counter_clockwise = true;
      if (wire) rs.fill = FillMode::wireframe;
      DepthState depth;
      depth.func = CompareFunc::less_equal;
      const Viewport viewport{0, 0, float(w), float(h), 0, 1};
      auto go = [&](const auto& hs, const auto& ps) {
        using Hs = std::decay_t<decltype(hs)>;
        using Ps = std::decay_t<decltype(ps)>;
        PatchDraw<glm::vec3, SubdVS, Hs, ProjectDS<SubdDS>, Ps> d{vertices, g->indices, g->control_points, SubdVS{}, hs,
                                                                    ProjectDS<SubdDS>{ds, vp, wire ? 2e-4f : 0.0f}, ps, ts,
                                                                    rs, depth, viewport};
        const DrawResult r = device.draw(d, *fb);
        if (!r.ok()) throw InputError(o.cage + ": " + r.error);
        total.statistics += r.report.statistics;
        total.times += r.report.times;
      };
      const glm::vec3 light = glm::normalize(eye - target);
      auto with_ps = [&](const auto& hs) {
        if (wire) go(hs, ConstantPS{glm::vec4(0.2f, 0.25f, 0.35f, 1.0f)});
        else go(hs, ClayPS{light});
      };
      if (g->domain == ts::Domain::tri) with_ps(SubdTriHS{{g->patches, model.patches.tables, factors}});
      else with_ps(SubdHS{g->patches, model.patches.tables, factors});
    }
  };
  if (o.view != "wireframe") draw_pass(false);
  if (o.view != "shaded") draw_pass(true);
  if (auto e = fb->write_color(o.output); !e.empty()) throw InputError(e);
  if (!o.stats.empty()) {
    std::ostringstream s;
    s << "{\"statistics\": " << to_json(total.statistics) << ", \"times\": " << to_json(total.times) << "}\n";
    write_text_atomically(o.stats, s.str());
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
  cmd->add_option("--stats", o->stats, "write D3D11 pipeline statistics and stage times as JSON");
  return [o] { return run_render(*o); };
}

}  // namespace tessera::cli
