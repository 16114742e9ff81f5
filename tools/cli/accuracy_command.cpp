// `tessera accuracy CAGE.obj --scheme S`: how far a scheme's surface is from the exact Catmull-Clark
// limit surface (OpenSubdiv at its highest isolation level), measured at the domain points the scheme
// actually produces (scheme_accuracy.h says how), relative to the limit surface's bounding-box diagonal.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "shaders_cpp/render/subd_model.h"
#include "tools/measure/scheme_accuracy.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/scene/model_options.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct AccuracyOptions {
  RenderSettings s = [] {
    RenderSettings d;
    d.factor = 7.0f;
    return d;
  }();  // the cage, scheme, factors, partitioning, threads and glTF asset, as render's
  bool json = false;
};

int run_accuracy(const AccuracyOptions& o) {
  const Scheme scheme = o.s.scheme;
  const ts::Partitioning partitioning = o.s.partitioning;
  const SubdModel model = load_model(o.s.cage, scheme, o.s.asset, o.s.isolation);
  const SubdFactors factors = factors_option(o.s.factor, o.s.vary, o.s.factors_file, model.cage);
  std::unique_ptr<LimitSurface> own_reference;
  try {
    // The limit of the cage the vertex shader outputs (the posed cage of an animated asset).
    Cage posed = model.cage;
    posed.positions = model.positions();
    // exact measures against its own surface; adaptive's is not the reference.
    if (!model.limit || model.limit->adaptive())
      own_reference = std::make_unique<LimitSurface>(LimitSurface::create(posed));
  } catch (const CageError& e) {
    throw InputError(e.what());
  }
  const LimitSurface& reference = own_reference ? *own_reference : *model.limit;
  Device device(device_options(o.s.threads));
  const measure::SchemeAccuracy a = measure::measure_scheme_accuracy(device, model, reference, factors, partitioning);
  if (!a.error.empty()) throw InputError(o.s.cage + ": " + a.error);
  if (o.json) {
    const Json j = {{"cage", o.s.cage},
                    {"scheme", to_string(scheme)},
                    {"factor", json_float(o.s.factor)},
                    {"samples", a.samples},
                    {"diagonal", a.diagonal},
                    {"max_distance", a.max_distance},
                    {"rms_distance", a.rms_distance},
                    {"max_relative", a.max_relative()},
                    {"rms_relative", a.rms_relative()},
                    {"max_normal_degrees", a.max_normal_degrees},
                    {"mean_normal_degrees", a.mean_normal_degrees},
                    {"max_normal_degrees_defined", a.max_normal_degrees_defined},
                    {"undefined_normal_samples", a.undefined_normal_samples},
                    {"folded_samples", a.folded_samples},
                    {"folded_faces", a.folded_faces},
                    {"farthest_face", a.farthest_face},
                    {"max_curvature_error", a.max_curvature_error},
                    {"mean_curvature_error", a.mean_curvature_error},
                    {"max_curvature_scheme", a.max_curvature_scheme},
                    {"max_curvature_limit", a.max_curvature_limit},
                    {"fallback_faces", model.patches.fallback_faces},
                    {"refit_faces", model.patches.refit_faces}};
    std::cout << json_text(j) << "\n";
  } else {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s: scheme %s vs exact limit, %llu samples: max %.3e, rms %.3e of the diagonal (%.4g); normals max "
                  "%.3f deg (%.3f where the limit's is defined; %llu samples where it is not), mean %.4f deg; "
                  "%llu folded samples; curvature error max %.3g, mean %.3g; largest curvature: scheme %.3g, "
                  "limit %.3g (per diagonal)\n",
                  o.s.cage.c_str(), to_string(scheme), (unsigned long long)a.samples, a.max_relative(),
                  a.rms_relative(), a.diagonal, a.max_normal_degrees, a.max_normal_degrees_defined,
                  (unsigned long long)a.undefined_normal_samples, a.mean_normal_degrees,
                  (unsigned long long)a.folded_samples, a.max_curvature_error, a.mean_curvature_error,
                  a.max_curvature_scheme, a.max_curvature_limit);
    std::cout << line;
    if (!a.folded_faces.empty()) {
      std::string faces;
      for (std::size_t i = 0; i < a.folded_faces.size() && i < 16; ++i) faces += " " + std::to_string(a.folded_faces[i]);
      if (a.folded_faces.size() > 16) faces += " ...";
      std::cout << o.s.cage << ": " << a.folded_faces.size() << " faces with folded samples:" << faces << "\n";
    }
  }
  return kExitOk;
}

}  // namespace

Runner add_accuracy_command(CLI::App& app) {
  auto o = std::make_shared<AccuracyOptions>();
  CLI::App* cmd = app.add_subcommand("accuracy", "distance of a scheme's surface to the exact limit surface");
  cmd->add_option("cage", o->s.cage, "the cage: OBJ (OpenSubdiv tags allowed) or glTF (.gltf, .glb)")->required();
  add_scheme_options(*cmd, o->s);
  add_asset_options(*cmd, o->s.asset);
  cmd->add_flag("--json", o->json, "print the result as JSON");
  return [o] { return run_accuracy(*o); };
}

}  // namespace tessera::cli
