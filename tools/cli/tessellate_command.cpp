// `tessera tessellate CAGE.obj --scheme S -o out.ply`: IA -> VS -> HS -> TS -> DS over a cage, and what
// the domain shader produced written as binary PLY. Each patch writes its own vertices (nothing is
// merged across patches), so crack-freedom can be checked from outside by welding on exact float bits;
// `--check-watertight` does that here too.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include "shaders_cpp/render/subd_model.h"
#include "tools/cli/commands.h"
#include "tools/cli/progress.h"
#include "tools/cli/glb_writer.h"
#include "tools/cli/ply_writer.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"
#include "tools/scene/render_stats.h"
#include "tools/scene/scene_render.h"
#include "tools/scene/surface_weld.h"
#include "tools/scene/view_options.h"
#include "tools/verify/weld_check.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct TessellateOptions {
  RenderSettings s;    // the model, factors, view and LOD, as render's
  std::string format;  // ply or glb; empty: from the output's extension
  std::string output, stats;
  bool check = false, json = false;
};

int run_tessellate(const TessellateOptions& o) {
  const Scheme scheme = o.s.scheme;
  const ts::Partitioning partitioning = o.s.partitioning;
  if (o.output.empty() && !o.check && o.stats.empty())
    throw UsageError("nothing to do: give -o out.ply, --check-watertight and/or --stats FILE.json");
  std::string format = o.format;
  if (format.empty()) {
    std::string ext = std::filesystem::path(o.output).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    format = ext == ".glb" ? "glb" : "ply";
  }
  if (format != "ply" && format != "glb") throw UsageError("--format: '" + o.format + "' is not ply or glb");
  if (!o.format.empty() && o.output.empty()) throw UsageError("--format needs -o FILE");

  check_output_paths({{"-o", o.output}, {"--stats", o.stats}},
                     {o.s.cage, o.s.factors_file, o.s.displacement.map, o.s.displacement.normal_map});
  // The scene library's one route from settings to a model, its view and factors.
  StepProgress preparing("preparing " + o.s.cage);
  const std::unique_ptr<PreparedScene> scene = prepare_scene(o.s, preparing.hook());
  preparing.finish();
  const SubdModel& model = scene->model;
  std::optional<Displacement>& displacement = scene->displacement;
  if (model.patches.fallback_faces > 0)
    log_info("bspline: " + std::to_string(model.patches.fallback_faces) +
             " faces are not regular and are drawn as Gregory patches");
  const ViewSetup& view = scene->view;
  const LodResult& lod = scene->lod;
  const SubdFactors& factors = scene->factors;
  PatchCull cull = scene->cull;
  // Back-patch culling skips what a rasterizer would cull; tessellate writes every patch.
  if (lod.cull == PatchCullMode::backface)
    throw UsageError(
        "--cull backface: tessellate writes every patch's triangles (nothing rasterizes them); "
        "use none, frustum or all (= frustum here)");
  cull.back = {};
  log_debug(std::to_string(model.patches.quads.size() + model.patches.tris.size()) + " patches, " +
            std::to_string(model.patches.tables.size()) + " stencil tables");

  Device device(device_options(o.s.threads));
  verify::WeldChecker weld;
  const scene::WeldCurves curves = scene::weld_curves(model.cage, *model.topology);
  std::uint64_t vertices = 0, triangles = 0;
  DrawResult result;
  std::string vbuf, fbuf;  // one patch's vertex and face records
  std::vector<glm::vec3> positions, normals;
  std::vector<std::uint32_t> glb_triangles;
  auto tessellate = [&](PlyStreamWriter* ply, GlbStreamWriter* glb) {
    auto sink = [&](const auto& p, const PatchGroup& g) {
      const std::uint64_t base = vertices;
      vbuf.clear(), fbuf.clear();
      if (glb) {
        positions.clear(), normals.clear(), glb_triangles.assign(p.indices.begin(), p.indices.end());
        for (const auto& s : p.points) positions.push_back(s.position), normals.push_back(s.normal);
        glb->append(positions, normals, glb_triangles);
      }
      if (ply)
        for (const auto& s : p.points) {
          PlyStreamWriter::put(vbuf, s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z,
                               std::int32_t(s.face), s.u, s.v);
        }
      std::uint64_t faces = 0;
      for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3, ++faces) {
        if (ply)
          PlyStreamWriter::put_triangle(fbuf, std::int32_t(base + p.indices[i]), std::int32_t(base + p.indices[i + 1]),
                                        std::int32_t(base + p.indices[i + 2]));
      }
      if (o.check) add_surface_patch(weld, p, g, curves);
      if (ply) ply->append(vbuf, p.points.size(), fbuf, faces);
      triangles += faces;
      vertices += p.points.size();
    };
    result = stream_surface(device, model, displacement ? &*displacement : nullptr, factors, cull, partitioning, sink);
    if (!result.ok()) throw InputError(o.s.cage + ": " + result.error);
  };

  const std::string made_by =
      "tessera tessellate " + std::filesystem::path(o.s.cage).filename().string() + " scheme " + to_string(scheme) +
      (displacement ? " displacement " + std::filesystem::path(o.s.displacement.map).filename().string()
                    : std::string()) +
      " factor " + float_text(o.s.factor) + " lod " + to_string(o.s.lod.mode) +
      " partitioning " + std::string(ts::to_string(partitioning));
  if (!o.output.empty() && format == "glb") {
    write_file_atomically(o.output, [&](const std::string& temp) {
      GlbStreamWriter glb(temp, o.output);
      tessellate(nullptr, &glb);
      // The settings, without the asset's name, so OBJ and glTF inputs of one cage give the same bytes.
      const Json extras = {{"scheme", to_string(scheme)},
                           {"factor", json_float(o.s.factor)},
                           {"lod", to_string(o.s.lod.mode)},
                           {"partitioning", std::string(ts::to_string(partitioning))},
                           {"displaced", displacement.has_value()},
                           {"note", "each patch writes its own vertices (weld on exact bits to join them)"}};
      glb.finish("tessera tessellate", extras.dump());
    });
  } else if (!o.output.empty()) {
    write_file_atomically(o.output, [&](const std::string& temp) {
      PlyStreamWriter ply(temp, o.output,
                          {{"float", "x"},
                           {"float", "y"},
                           {"float", "z"},
                           {"float", "nx"},
                           {"float", "ny"},
                           {"float", "nz"},
                           {"int", "face"},
                           {"float", "u"},
                           {"float", "v"}});
      tessellate(&ply, nullptr);
      ply.finish({made_by, "each patch writes its own vertices; face = base face, u v = domain location"});
    });
  } else {
    tessellate(nullptr, nullptr);
  }

  if (!o.stats.empty()) {
    const ViewInputs inputs{
        model, displacement ? &*displacement : nullptr, factors, cull, partitioning, view, o.s.lod.edge_pixels, false};
    const PatchTables tables = view_patch_tables(inputs);
    // Counts only, the same bytes on any thread count; times and memory are in --json.
    Json s = {{"statistics", to_json(result.report.statistics)}, {"warnings", model.cage.warnings}};
    add_patch_statistics(s, device, inputs, tables, lod);
    write_text_atomically(o.stats, json_text(s) + "\n");
  }

  const auto& st = result.report.statistics;
  std::ostringstream text;
  text << o.s.cage << ": scheme " << to_string(scheme) << ", " << model.patches.quads.size() + model.patches.tris.size()
       << " patches, " << model.patches.tables.size() << " stencil tables, " << st.DSInvocations << " domain points, "
       << triangles << " triangles";
  verify::WeldReport w;
  if (o.check) w = weld.report();
  if (o.json) {
    Json j = {{"cage", o.s.cage},
              {"scheme", to_string(scheme)},
              {"patches", model.patches.quads.size() + model.patches.tris.size()},
              {"stencil_tables", model.patches.tables.size()},
              {"fallback_faces", model.patches.fallback_faces},
              {"vertices", vertices},
              {"triangles", triangles},
              {"hs_invocations", st.HSInvocations},
              {"ds_invocations", st.DSInvocations},
              {"seconds", result.report.times.wall},
              {"times", to_json(result.report.times)},
              {"memory", to_json(result.report.memory)},
              {"peak_rss_bytes", peak_rss_bytes()},
              {"warnings", model.cage.warnings}};
    if (o.check) j["watertight"] = to_json(w);
    std::cout << json_text(j) << "\n";
  } else {
    std::cout << text.str() << "\n";
    if (o.check) std::cout << w.summary() << "\n";
  }
  // A failed check says so on stderr too, where -q leaves errors.
  if (o.check && !w.watertight())
    std::cerr << "tessera tessellate: " << o.s.cage << ": not watertight (" << w.crack_edges << " crack edges, "
              << w.nonmanifold_edges << " non-manifold edges)\n";
  return o.check && !w.watertight() ? kExitFailure : kExitOk;
}

}  // namespace

Runner add_tessellate_command(CLI::App& app) {
  auto o = std::make_shared<TessellateOptions>();
  CLI::App* cmd = app.add_subcommand("tessellate", "run IA..DS over a cage and write the DS output as PLY");
  cmd->add_option("cage", o->s.cage, "the cage: OBJ (OpenSubdiv tags allowed) or glTF (.gltf, .glb)")->required();
  cmd->add_option("-o,--output", o->output,
                  "output PLY (binary; each patch its own vertices), or binary glTF (.glb) for any glTF viewer");
  cmd->add_option("--format", o->format, "ply or glb (default: from the output's extension, .glb or else PLY)");
  add_model_settings_options(*cmd, o->s, PatchCullMode::none);
  cmd->add_option("--stats", o->stats,
                  "write per-patch statistics (factors raw and processed, triangles, screen size, culling), "
                  "histograms and totals as JSON (as render --stats; screen sizes for the --camera view)");
  cmd->add_flag("--check-watertight", o->check,
                "weld on exact bits: exit 1 on a crack or a non-manifold edge (the surface's own border is no crack)");
  cmd->add_flag("--json", o->json, "print the summary as JSON");
  return [o] { return run_tessellate(*o); };
}

}  // namespace tessera::cli
