// `tessera pattern`: one patch through the fixed-function tessellator, as JSON and/or a picture.
#include <iostream>
#include <memory>

#include "tessellator/tessellator.h"
#include "tools/cli/commands.h"
#include "tools/cli/pattern_image.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct PatternOptions {
  std::string domain = "quad", partitioning = "integer", output;  // output: by domain unless given
  std::string outer, inner;
  bool json = false;
  std::string image;
  int image_size = 1024;
};

// Float32 JSON: each coordinate prints as the shortest text that reads back to the same float.
FloatJson pattern_json(const ts::Pattern& p) {
  FloatJson points = FloatJson::array(), primitives = FloatJson::array();
  for (const auto& point : p.points) points.push_back({point.u, point.v});
  const auto per = std::size_t(p.vertices_per_primitive());
  for (std::size_t i = 0; i + per <= p.indices.size(); i += per) {
    FloatJson primitive = FloatJson::array();
    for (std::size_t k = 0; k < per; ++k) primitive.push_back(p.indices[i + k]);
    primitives.push_back(std::move(primitive));
  }
  return {{"culled", p.culled}, {"points", std::move(points)}, {"primitives", std::move(primitives)}};
}

int run_pattern(const PatternOptions& o) {
  const auto domain = ts::parse_domain(o.domain);
  if (!domain) throw UsageError("--domain: unknown domain '" + o.domain + "' (quad, tri, isoline)");
  const auto partitioning = ts::parse_partitioning(o.partitioning);
  if (!partitioning)
    throw UsageError("--partitioning: unknown partitioning '" + o.partitioning +
                     "' (integer, pow2, fractional_odd, fractional_even)");
  const std::string output_name = !o.output.empty()                ? o.output
                                  : *domain == ts::Domain::isoline ? "line"
                                                                   : "triangle_cw";
  const auto output = ts::parse_output_primitive(output_name);
  if (!output)
    throw UsageError("--output: unknown output primitive '" + o.output + "' (point, line, triangle_cw, triangle_ccw)");
  if (*domain == ts::Domain::isoline &&
      (*output == ts::OutputPrimitive::triangle_cw || *output == ts::OutputPrimitive::triangle_ccw))
    throw UsageError("--output: the isoline domain makes lines or points, not " + o.output);

  const auto outer = parse_float_list(o.outer, "--outer");
  const std::size_t want_outer = std::size_t(ts::outer_factor_count(*domain));
  const std::size_t want_inner = std::size_t(ts::inside_factor_count(*domain));
  if (outer.size() != want_outer)
    throw UsageError("--outer: the " + o.domain + " domain takes " + std::to_string(want_outer) +
                     " outer factors, got " + std::to_string(outer.size()));
  std::vector<float> inner;
  if (!o.inner.empty()) inner = parse_float_list(o.inner, "--inner");
  if (want_inner == 0 && !inner.empty()) throw UsageError("--inner: the isoline domain takes no inside factors");
  if (want_inner > 0 && inner.size() != want_inner)
    throw UsageError("--inner: the " + o.domain + " domain takes " + std::to_string(want_inner) + " inside factor" +
                     (want_inner > 1 ? "s" : "") + ", got " + std::to_string(inner.size()));
  if (o.image_size < 64 || o.image_size > 8192)
    throw UsageError("--image-size: must be in 64..8192, got " + std::to_string(o.image_size));

  ts::FactorSet factors;
  factors.domain = *domain;
  std::size_t k = 0;
  for (float x : outer) factors.values[k++] = x;
  for (float x : inner) factors.values[k++] = x;

  const ts::ProcessedFactors processed = ts::process_factors(*partitioning, factors);
  ts::Pattern pattern;
  ts::generate(processed, *output, pattern);
  log_debug(std::to_string(pattern.points.size()) + " points, " + std::to_string(pattern.primitive_count()) +
            " primitives" + (pattern.culled ? " (culled)" : ""));

  if (!o.image.empty()) {
    write_pattern_image({*partitioning, factors, processed, &pattern, o.image_size}, o.image);
    log_info("wrote " + o.image);
  }
  if (o.json) {
    std::cout << json_text(pattern_json(pattern)) << "\n";
  } else if (o.image.empty()) {
    std::cout << (pattern.culled ? "culled"
                                 : std::to_string(pattern.points.size()) + " points, " +
                                       std::to_string(pattern.primitive_count()) + " primitives")
              << "\n";
  }
  return kExitOk;
}

}  // namespace

Runner add_pattern_command(CLI::App& app) {
  auto o = std::make_shared<PatternOptions>();
  CLI::App* cmd = app.add_subcommand("pattern", "Tessellate one patch with the D3D11 fixed-function tessellator");
  cmd->footer(
      "Factors are floats; nan, inf, -inf and -0 are accepted. quad: 4 outer (Ueq0,Veq0,Ueq1,Veq1) and 2 inner (U,V);\n"
      "tri: 3 outer (Ueq0,Veq0,Weq0) and 1 inner; isoline: 2 outer (density,detail) and none.\n"
      "Example: tessera pattern --domain tri --partitioning fractional_odd --outer 3.5,2,5 --inner 4 --image tri.png");
  cmd->add_option("--domain", o->domain, "quad | tri | isoline")->capture_default_str();
  cmd->add_option("--partitioning", o->partitioning, "integer | pow2 | fractional_odd | fractional_even")
      ->capture_default_str();
  cmd->add_option("--outer", o->outer, "outer (edge) factors, comma-separated")->required();
  cmd->add_option("--inner", o->inner, "inside factors, comma-separated");
  cmd->add_option("--output", o->output,
                  "point | line | triangle_cw | triangle_ccw (default: line for isolines, else triangle_cw)");
  cmd->add_flag("--json", o->json, "print {\"culled\", \"points\", \"primitives\"} in the tessellator's order");
  cmd->add_option("--image", o->image, "draw the pattern to this PNG");
  cmd->add_option("--image-size", o->image_size, "picture size in pixels")->capture_default_str();
  return [o] { return run_pattern(*o); };
}

}  // namespace tessera::cli
