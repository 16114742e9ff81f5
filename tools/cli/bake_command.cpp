// `tessera bake CAGE --dense MESH -o MAP.exr`: displacement (vector or scalar), normal and occlusion maps
// of a dense mesh, baked onto the cage's base surface in the cage's UV layout (shaders_cpp/bake/).
// The maps re-render with `tessera render CAGE --displacement MAP.exr` at scale 1 and bias 0 (vector
// maps: --displacement-channel RGB --displacement-space as baked).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>

#include <tbb/task_arena.h>

#include "shaders_cpp/bake/dense_mesh.h"
#include "shaders_cpp/bake/map_baker.h"
#include "shaders_cpp/bake/map_writer.h"
#include "shaders_cpp/displacement/watertight_uv.h"
#include "tools/cli/commands.h"
#include "tools/cli/progress.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct BakeCli {
  AssetSettings asset;
  Scheme scheme = Scheme::gregory;
  int isolation = kDefaultIsolation;
  std::string cage, dense, output, kind = "vector", space = "tangent", method = "auto";
  std::string resolution = "1024", normal_map, ao, prefer = "nearest";
  float max_distance = 0.0f, ao_distance = 0.0f;
  int ao_rays = 64, threads = 0;
  bool json = false;
};

// A cage's control-point bounding box diagonal: the scale of the default distances.
double cage_diagonal(const Cage& c) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::vec3& p : c.positions) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
  return c.positions.empty() ? 0.0 : glm::length(hi - lo);
}

int run_bake(const BakeCli& o) {
  BakeOptions b;
  if (o.kind != "vector" && o.kind != "scalar") throw UsageError("--kind: '" + o.kind + "' is not vector or scalar");
  if (o.space != "tangent" && o.space != "object")
    throw UsageError("--space: '" + o.space + "' is not tangent or object");
  if (o.method != "auto" && o.method != "dual" && o.method != "raycast")
    throw UsageError("--method: '" + o.method + "' is not auto, dual or raycast");
  if (o.prefer != "nearest" && o.prefer != "outward")
    throw UsageError("--prefer: '" + o.prefer + "' is not nearest or outward");
  b.preference = o.prefer == "nearest" ? RayPreference::nearest : RayPreference::outward;
  b.kind = o.kind == "vector" ? BakeKind::vector : BakeKind::scalar;
  b.space = o.space == "tangent" ? DisplacementSpace::tangent : DisplacementSpace::object;
  if (b.kind == BakeKind::scalar && o.space == "object") throw UsageError("--space object: a scalar map has no space");
  const auto [w, h] =
      parse_size(o.resolution.find('x') == std::string::npos ? o.resolution + "x" + o.resolution : o.resolution,
                 "--resolution", 1, 16384);
  if (std::int64_t(w) * h > (std::int64_t(1) << 28))
    throw UsageError("--resolution " + o.resolution + ": more than 2^28 texels");
  b.width = w, b.height = h;
  if (!(o.ao_rays >= 1 && o.ao_rays <= 4096))
    throw UsageError("--ao-rays: " + std::to_string(o.ao_rays) + " is not in 1..4096");
  for (const auto& [name, x] : {std::pair{"--max-distance", o.max_distance}, std::pair{"--ao-distance", o.ao_distance}})
    if (!(x >= 0.0f && std::isfinite(x)))
      throw UsageError(std::string(name) + ": " + float_text(x) + " is not a finite distance >= 0");
  for (const std::string* p : {&o.output, &o.normal_map, &o.ao})
    if (!p->empty() && !map_path_supported(*p)) throw UsageError(*p + ": write maps as .exr, .tif or .png");
  check_output_paths({{"-o", o.output}, {"--normal-map", o.normal_map}, {"--ao", o.ao}}, {o.cage, o.dense});
  b.normal_map = !o.normal_map.empty();
  b.ao = !o.ao.empty();
  b.ao_rays = o.ao_rays;

  const Scheme scheme = o.scheme;
  const SubdModel model = load_model(o.cage, scheme, o.asset, o.isolation);
  std::vector<PatchTexcoords> texcoords;
  try {
    texcoords = displacement_texcoords(model, o.output);
  } catch (const CageError& e) {
    throw InputError(e.what());
  } catch (const DisplacementMapError& e) {
    throw InputError(e.what());
  }
  const double diagonal = cage_diagonal(model.cage);
  b.max_distance = o.max_distance > 0.0f ? o.max_distance : float(0.02 * diagonal);
  b.ao_distance = o.ao_distance > 0.0f ? o.ao_distance : float(0.1 * diagonal);

  const auto start = std::chrono::steady_clock::now();
  DenseMesh dense;
  try {
    dense = load_dense_mesh(o.dense);
  } catch (const BakeError& e) {
    throw InputError(e.what());
  }
  b.method = o.method == "dual"      ? BakeMethod::dual
             : o.method == "raycast" ? BakeMethod::raycast
             : dense.parameterised() ? BakeMethod::dual
                                     : BakeMethod::raycast;
  try {
    check_bake_inputs(dense, b);
  } catch (const BakeError& e) {
    throw InputError(e.what());
  }
  log_info("bake: " + std::to_string(dense.triangle_count()) + " dense triangles from " + o.dense + ", " +
           (b.method == BakeMethod::dual ? "dual parameterisation" : "ray casting") + ", " + std::to_string(w) + "x" +
           std::to_string(h) + " texels");
  const auto loaded = std::chrono::steady_clock::now();

  BakedMaps maps;
  {
    Progress progress("bake", "rows", std::uint64_t(h));
    tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
    try {
      arena.execute([&] {
        maps = bake_maps(model, texcoords, dense, b,
                         [&](double f) { progress.update(std::uint64_t(f * h), std::uint64_t(h)); });
      });
    } catch (const BakeError& e) {
      throw InputError(e.what());
    }
  }
  const auto baked = std::chrono::steady_clock::now();

  const std::string method = b.method == BakeMethod::dual ? "dual" : "raycast";
  const std::vector<std::pair<std::string, std::string>> about = {
      {"tessera:bake", "cage " + std::filesystem::path(o.cage).filename().string() + " dense " +
                           std::filesystem::path(o.dense).filename().string() + " scheme " + to_string(scheme) +
                           " method " + method + " kind " + o.kind +
                           (b.kind == BakeKind::vector ? " space " + o.space : "")}};
  std::vector<std::string> names =
      b.kind == BakeKind::vector ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"Y"};
  // All maps or none: each is written to a temporary and renamed; a later failure removes the earlier.
  std::vector<std::string> written;
  auto write = [&](const std::string& path, const std::vector<std::string>& channels, const std::vector<float>& texels,
                   bool stored_range) {
    const std::string err = write_baked_map(path, w, h, channels, texels, about, stored_range);
    if (!err.empty()) {
      for (const std::string& p : written) std::filesystem::remove(p);
      throw InputError(err);
    }
    written.push_back(path);
  };
  write(o.output, names, maps.displacement, true);
  if (b.normal_map) write(o.normal_map, {"R", "G", "B"}, maps.normal, false);
  if (b.ao) write(o.ao, {"Y"}, maps.ao, false);
  const auto done = std::chrono::steady_clock::now();

  auto seconds = [](auto a, auto z) { return std::chrono::duration<double>(z - a).count(); };
  const std::uint64_t texels = std::uint64_t(w) * std::uint64_t(h);
  if (o.json) {
    const Json j = {
        {"cage", o.cage},
        {"dense", o.dense},
        {"output", o.output},
        {"scheme", to_string(scheme)},
        {"method", method},
        {"kind", o.kind},
        {"space", b.kind == BakeKind::vector ? o.space : "normal"},
        {"width", w},
        {"height", h},
        {"dense_triangles", dense.triangle_count()},
        {"texels", texels},
        {"texels_covered", maps.texels_covered},
        {"texels_missed", maps.texels_missed},
        {"texels_padded", maps.texels_padded},
        {"max_displacement", maps.max_displacement},
        {"max_distance", b.method == BakeMethod::raycast ? Json(b.max_distance) : Json(nullptr)},
        {"seconds",
         {{"load", seconds(start, loaded)}, {"bake", seconds(loaded, baked)}, {"write", seconds(baked, done)}}}};
    std::cout << json_text(j) << "\n";
  } else {
    log_info("bake: " + std::to_string(maps.texels_covered) + " of " + std::to_string(texels) + " texels on charts, " +
             std::to_string(maps.texels_missed) + " missed, " + std::to_string(maps.texels_padded) +
             " padded; largest displacement " + std::to_string(maps.max_displacement) + "; " +
             std::to_string(seconds(loaded, baked)) + " s");
  }
  if (maps.texels_missed > 0)
    log_info("bake: " + std::to_string(maps.texels_missed) + " texels found no dense surface (" +
             (b.method == BakeMethod::raycast ? "no hit within --max-distance"
                                              : "no dense triangle at their face and (u, v)") +
             "); filled from their neighbours");
  return kExitOk;
}

}  // namespace

Runner add_bake_command(CLI::App& app) {
  auto o = std::make_shared<BakeCli>();
  CLI::App* cmd =
      app.add_subcommand("bake", "bake displacement, normal and occlusion maps of a dense mesh onto a cage");
  cmd->add_option("cage", o->cage, "the cage (OBJ or glTF, quads with UVs): the base surface and its UV layout")
      ->required();
  cmd->add_option("--dense", o->dense,
                  "the dense mesh: PLY (tessera tessellate's carries the parameterisation), OBJ or glTF")
      ->required();
  cmd->add_option("-o,--output", o->output,
                  "the displacement map: .exr (float), or .png or .tif (16-bit, its range in the file)")
      ->required();
  add_setting_option(
      *cmd, "--scheme", o->scheme, [](const std::string& text) { return scheme_option(text); },
      "the base surface: acc, gregory, bspline, exact or adaptive (default gregory)");
  add_setting_option(
      *cmd, "--isolation", o->isolation, [](const std::string& text) { return isolation_option(text); },
      "--scheme adaptive: the isolation level, 1 to " + std::to_string(kMaxIsolation) + " (default " +
          std::to_string(kDefaultIsolation) + ")");
  cmd->add_option("--resolution", o->resolution, "texels: N (square) or WxH (default 1024)");
  cmd->add_option("--kind", o->kind, "vector (default) or scalar (along the normal)");
  cmd->add_option("--space", o->space, "vector maps: tangent (default) or object");
  cmd->add_option("--method", o->method,
                  "dual (the dense mesh's parameterisation), raycast, or auto (default: dual where the mesh has it)");
  cmd->add_option("--max-distance", o->max_distance,
                  "ray casting: how far along the normal to look, both ways (default 2% of the cage's diagonal: set it "
                  "a little beyond the deepest detail)");
  cmd->add_option(
      "--prefer", o->prefer,
      "ray casting: nearest (default) hit either way, or outward (the hit ahead along the normal when there is one)");
  cmd->add_option("--normal-map", o->normal_map,
                  "also write a tangent-space normal map (.png or .tif 16-bit, or .exr)");
  cmd->add_option("--ao", o->ao, "also write ambient occlusion (.png or .tif 16-bit, or .exr)");
  cmd->add_option("--ao-rays", o->ao_rays, "occlusion rays per texel (default 64)");
  cmd->add_option("--ao-distance", o->ao_distance, "how far an occluder counts (default 10% of the cage's diagonal)");
  cmd->add_option("--threads", o->threads, "worker threads (0 = all; the maps are the same bytes for any count)");
  add_asset_options(*cmd, o->asset);
  cmd->add_flag("--json", o->json, "print a summary as JSON");
  return [o] { return run_bake(*o); };
}

}  // namespace tessera::cli
