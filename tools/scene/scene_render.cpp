#include "tools/scene/scene_render.h"

#include "shaders_cpp/image_io/image_file.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"
#include "tools/scene/view_legend.h"

namespace tessera::scene {

ViewInputs PreparedScene::inputs() const {
  return ViewInputs{model,
                    displacement ? &*displacement : nullptr,
                    factors,
                    cull,
                    settings.partitioning,
                    view,
                    settings.lod.edge_pixels,
                    settings.factor_kind == FactorKind::processed};
}

namespace {
// The model and its displacement, not yet configured (prepare_scene, prepare_bench_scene).
std::unique_ptr<PreparedScene> load_scene(const RenderSettings& s, const PrepareStep& step = {}) {
  auto p = std::make_unique<PreparedScene>();
  p->model = load_model(s.cage, s.scheme, s.asset, s.isolation, step);
  p->settings.asset = s.asset;  // the pose load_model gave the model: configure_scene keeps it
  p->displacement = displacement_option(s.displacement, p->model);
  if (const UpAxisAdvice up = up_axis_advice(s.cage, p->model.cage); up.axis == 2) {
    p->suggested_up = glm::vec3(0.0f, 0.0f, 1.0f);
    p->suggested_up_reason = up.reason;
  }
  return p;
}
}  // namespace

std::unique_ptr<PreparedScene> prepare_scene(const RenderSettings& s, const PrepareStep& step) {
  auto p = load_scene(s, step);
  if (step) step("framing and factors");
  configure_scene(*p, s);
  return p;
}

std::unique_ptr<PreparedScene> prepare_bench_scene(RenderSettings s) {
  s.cage = cage_or_shipped_frog(s.cage);
  auto p = load_scene(s);
  if (!s.camera.up) s.camera.up = p->suggested_up;
  // A benchmark's camera must not move when framing improves, or its times stop being comparable
  // across versions: without --camera-position it is the one the benchmarks were first measured
  // with (80 % of the rest cage's bounding sphere, frame_cage).
  if (!s.camera.eye && s.camera.width > 0 && s.camera.height > 0) {
    const SubdCamera c = frame_cage(p->model.cage, s.camera.width, s.camera.height, s.camera.fov, std::nullopt,
                                    s.camera.target, unit_up(s.camera));
    s.camera.eye = c.eye;
    s.camera.target = c.target;
  }
  configure_scene(*p, s);
  return p;
}

void configure_scene(PreparedScene& p, const RenderSettings& given) {
  RenderSettings s = given;
  if (!s.camera.up) s.camera.up = p.suggested_up;
  msaa_option(s.msaa);
  (void)device_options(s.threads);  // refused here, before the scene says anything
  // The pose first, and only when it changes (the exact scheme rebuilds its limit surface per pose):
  // a model is posed from its rig alone, so the result does not depend on the pose it had.
  // settings.asset always names the model's pose, even when a later step of this call throws.
  if (!(p.settings.asset == s.asset)) {
    pose_or_refuse(p.model, s.cage, s.asset);
    p.settings.asset = s.asset;
  }
  // The base factors depend on --factor, --vary-factors and the factors file alone: a scene already
  // configured with the same ones keeps them (the viewer's every frame would re-read the file). The
  // view, factors and LOD follow those, the camera, LOD and cull settings, and the pose.
  const bool same_base = p.configured && p.settings.factor == s.factor && p.settings.vary == s.vary &&
                         p.settings.factors_file == s.factors_file;
  const bool same_view = same_base && p.derived_from && p.derived_from->camera == s.camera &&
                         p.derived_from->lod == s.lod && p.derived_from->asset == s.asset &&
                         p.derived_from->two_sided == s.two_sided &&
                         legend_band(p.derived_from->view, s.camera.height) == legend_band(s.view, s.camera.height) &&
                         (p.derived_from->view == ViewKind::cage) == (s.view == ViewKind::cage);
  // Before the LOD: back-patch culling follows the rasterizer's cull mode.
  p.model.two_sided = s.two_sided;
  if (!same_view) {
    SubdFactors base = same_base ? p.base_factors : factors_option(s.factor, s.vary, s.factors_file, p.model.cage);
    ViewSetup view =
        view_option(s.camera, p.model, legend_band(s.view, s.camera.height), s.view == ViewKind::cage);
    SubdFactors factors = base;
    PatchCull cull;
    LodResult lod =
        apply_lod_options(s.lod, view, p.model, p.displacement ? &*p.displacement : nullptr, factors, cull);
    p.base_factors = std::move(base);
    p.factors = std::move(factors);
    p.cull = cull;
    p.view = view;
    p.lod = std::move(lod);
  }
  // Said once, when the scene first draws (a bad setting's error stays the only line).
  if (!p.configured && !given.camera.up && p.suggested_up)
    log_info(s.cage + ": seen +z up, as its shape suggests (" + p.suggested_up_reason + "); --camera-up 0,1,0 for +y");
  p.settings = s;
  p.configured = true;
  p.derived_from = s;
}

void pose_scene(PreparedScene& p, double time) {
  pose_model(p.model, p.settings.asset, time);
  p.settings.asset.time = time;
  p.derived_from.reset();
  p.factors = p.base_factors;
  p.cull = {};
  p.lod = apply_lod_options(p.settings.lod, p.view, p.model, p.displacement ? &*p.displacement : nullptr, p.factors,
                            p.cull);
}

void view_scene(PreparedScene& p, const ViewSetup& view) {
  p.view = view;
  p.derived_from.reset();
  p.factors = p.base_factors;
  p.cull = {};
  p.lod = apply_lod_options(p.settings.lod, p.view, p.model, p.displacement ? &*p.displacement : nullptr, p.factors,
                            p.cull);
}

std::string describe_scene(const PreparedScene& p) {
  const Cage& cage = p.model.cage;
  const auto vec = [](glm::vec3 v) { return float_text(v.x) + "," + float_text(v.y) + "," + float_text(v.z); };
  std::string s = "loaded " + p.settings.cage + ": " + std::to_string(cage.vertex_count()) + " vertices, " +
                  std::to_string(cage.face_count()) + " faces, " +
                  std::to_string(p.model.patches.quads.size() + p.model.patches.tris.size()) + " patches (" +
                  std::to_string(p.model.patches.quads.size()) + " quad, " +
                  std::to_string(p.model.patches.tris.size()) + " triangle), scheme " + to_string(p.settings.scheme);
  if (p.model.rig) s += ", animated (t " + float_text(float(p.settings.asset.time)) + " s)";
  if (p.displacement && !p.displacement->maps.empty()) {
    const Displacement& d = *p.displacement;
    s += ", displacement " + std::to_string(d.maps.front().width()) + "x" + std::to_string(d.maps.front().height());
    if (!d.udim.empty())
      s += " x " + std::to_string(d.udim.size()) + " UDIM tile" + (d.udim.size() > 1 ? "s " : " ") +
           std::to_string(d.udim.front()) + (d.udim.size() > 1 ? "-" + std::to_string(d.udim.back()) : "");
    s += " (bound " + float_text(d.bound) + ")";
  }
  if (p.displacement && !p.displacement->normal_maps.empty()) s += ", normal map";
  s += "; view " + std::to_string(p.view.width) + "x" + std::to_string(p.view.height) + " from " +
       vec(p.view.camera.eye) + " to " + vec(p.view.camera.target) + ", up " + vec(p.view.camera.up);
  return s;
}

std::string describe_times(const DrawReport& r) {
  const StageTimes& t = r.times;
  const auto ms = [](double s) { return float_text(float(s * 1e3)); };
  return "draw " + ms(t.wall) + " ms wall; thread-ms: IA+VS " + ms(t.ia_vs) + ", HS " + ms(t.hs) + ", tessellator " +
         ms(t.tessellator) + ", DS " + ms(t.ds) + ", setup " + ms(t.setup) + ", raster+PS " + ms(t.raster) + "; " +
         std::to_string(r.statistics.CInvocations) + " triangles, " + std::to_string(r.statistics.PSInvocations) +
         " pixels shaded, geometry peak " + std::to_string(r.memory.geometry_peak_bytes / 1024) + " KiB";
}

SceneImage render_scene(Device& device, const PreparedScene& scene, bool want_tables,
                        std::optional<Framebuffer> reuse) {
  SceneImage image;
  if (reuse && reuse->width() == scene.view.width && reuse->height() == scene.view.height &&
      reuse->samples() == scene.settings.msaa && reuse->format() == ColorFormat::rgba8_unorm) {
    image.fb = std::move(reuse);
  } else {
    std::string error;
    image.fb =
        Framebuffer::create(scene.view.width, scene.view.height, ColorFormat::rgba8_unorm, &error, scene.settings.msaa);
    if (!image.fb) throw UsageError(error);
  }
  const ViewInputs inputs = scene.inputs();
  // Per-patch facts, replayed once for the view and the statistics.
  if (view_uses_patch_tables(scene.settings.view) || want_tables) image.tables = view_patch_tables(inputs);
  image.out = render_view(device, scene.settings.view, inputs, image.tables ? &*image.tables : nullptr, *image.fb);
  if (!image.out.result.ok()) throw InputError(scene.settings.cage + ": " + image.out.result.error);
  // The overlays drew at pixel rate into every sample; what follows (legends, files, hashes) reads
  // the resolved image (the resolve also writes the tiles no draw entered: Device::clear).
  if (image.fb->samples() > 1) image.fb = image.fb->resolve();
  return image;
}

Json scene_summary(const std::string& path, const PreparedScene& scene, const SceneImage& image) {
  const DrawReport& total = image.out.result.report;
  Json j = {
      {"output", path},
      {"width", scene.view.width},
      {"height", scene.view.height},
      {"scheme", to_string(scene.settings.scheme)},
      {"view", to_string(scene.settings.view)},
      {"camera", {{"position", json_vec3(scene.view.camera.eye)}, {"target", json_vec3(scene.view.camera.target)}}},
      {"patches", scene.model.patches.quads.size() + scene.model.patches.tris.size()},
      {"patches_culled", total.patches_culled},
      {"patches_facing_away", total.patches_back_culled},
      {"triangles", total.statistics.CInvocations},
      {"pixels_shaded", total.statistics.PSInvocations},
      {"statistics", to_json(total.statistics)},
      {"times", to_json(total.times)},
      {"memory", to_json(total.memory)}};
  if (scene.settings.view == ViewKind::cracks)
    j["cracks"] = {{"crack_edges", image.out.crack_edges},
                   {"border_edges", image.out.border_edges},
                   {"nonmanifold_edges", image.out.nonmanifold_edges}};
  if (Json a = adaptive_patches_json(scene.model); !a.is_null()) j["adaptive"] = a;
  j["warnings"] = scene.model.cage.warnings;  // what the loader and the scheme left out, one line each
  return j;
}

Json adaptive_patches_json(const SubdModel& model) {
  if (!model.limit || !model.limit->adaptive()) return nullptr;
  const LimitSurface::PatchCounts c = model.limit->patch_counts();
  Json kinds = Json::object(), levels = Json::object();
  for (int k = 0; k < kAdaptivePatchKinds; ++k) kinds[to_string(AdaptivePatchKind(k))] = c.by_kind[k];
  for (int l = 0; l < 16; ++l)
    if (c.by_level[l] > 0) levels[std::to_string(l)] = c.by_level[l];
  return {{"isolation", model.limit->approx_level()},
          {"patches", c.total},
          {"by_kind", kinds},
          {"by_level", levels},
          {"bytes", model.limit->memory_bytes()}};
}

void write_scene_image(const SceneImage& image, const ImageTarget& target) {
  if (image.out.has_legend) {
    write_with_legend(*image.fb, image.out.legend, target);
  } else if (auto e = write_color(*image.fb, target); !e.empty()) {
    throw InputError(e);
  }
}

}  // namespace tessera::scene
