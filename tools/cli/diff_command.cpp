// `tessera diff A B`: OpenImageIO idiff (2.4) compatible image comparison -- its flags, defaults,
// exit codes and verdicts (tools/verify/image_diff.h) -- plus --json, --exact (identical decoded
// pixels, with a content hash) and --heatmap (a difference picture people can read). idiff's
// single-dash spellings (-fail 0.004) are accepted as written (main.cpp rewrites them).
#include <cmath>
#include <cstdio>
#include <iostream>

#include "shaders_cpp/image_io/stderr_capture.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/json_output.h"
#include "tools/verify/image_diff.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct DiffOptions {
  std::string a, b, output, heatmap;
  verify::DiffThresholds t;
  bool only_if_different = false, absolute = false, json = false, exact = false, perceptual = false, all = false;
  float scale = 1.0f;
};

// idiff prints non-finite values as "nan" and "inf".
std::string number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

Json json_number(double v) { return std::isfinite(v) ? Json(v) : Json(number(v)); }

int run_diff(const DiffOptions& o) {
  if (o.perceptual) throw UsageError("-p (perceptual comparison) is not supported; compare numerically");
  if (o.all) throw UsageError("-a (all subimages and MIP levels) is not supported; subimage 0, level 0 is compared");
  for (const auto& [value, name] : {std::pair{o.t.fail, "-fail"},
                                    {o.t.warn, "-warn"},
                                    {o.t.fail_relative, "-failrelative"},
                                    {o.t.warn_relative, "-warnrelative"},
                                    {o.t.fail_percent, "-failpercent"},
                                    {o.t.warn_percent, "-warnpercent"}})
    if (!(value >= 0.0f) || std::isinf(value))
      throw UsageError(std::string(name) + ": " + number(value) + " is not a finite value >= 0");
  if (std::isnan(o.t.hard_fail) || std::isnan(o.t.hard_warn)) throw UsageError("-hardfail/-hardwarn: NaN");
  if (!std::isfinite(o.scale)) throw UsageError("-scale: " + number(o.scale) + " is not finite");
  check_output_paths({{"-o", o.output}, {"--heatmap", o.heatmap}}, {o.a, o.b});

  verify::DiffImages images;
  const verify::DiffReport r = [&] {
    const StderrCapture quiet;  // libpng's own error line: the report says it once
    return verify::diff_images(o.a, o.b, o.t, o.exact, &images);
  }();
  if (r.verdict == verify::DiffVerdict::file_error) {
    std::cerr << "tessera diff: " << r.error << "\n";
    return int(r.verdict);
  }
  const bool differs = r.max_error != 0.0 || !r.identical;
  // idiff writes the difference image when asked, unless -od and nothing differs.
  try {
    if (!o.output.empty() && r.verdict != verify::DiffVerdict::different_sizes && (differs || !o.only_if_different))
      if (auto e = verify::write_difference_image(images, o.absolute, o.scale, o.output); !e.empty())
        throw InputError(e);
    if (!o.heatmap.empty() && r.verdict != verify::DiffVerdict::different_sizes)
      if (auto e = verify::write_heat_map(images, o.scale, o.heatmap); !e.empty()) throw InputError(e);
  } catch (const InputError& e) {  // a picture that cannot be written is a file error (4), as idiff's codes go
    std::cerr << "tessera diff: " << e.what() << "\n";
    return int(verify::DiffVerdict::file_error);
  }

  if (o.json) {
    const auto floats = [](const std::vector<float>& v) {
      Json a = Json::array();
      for (const float x : v) a.push_back(json_float(x));
      return a;
    };
    Json j = {{"a", o.a},
              {"b", o.b},
              {"verdict", to_string(r.verdict)},
              {"exit_code", int(r.verdict)},
              {"exact", o.exact},
              {"identical", r.identical},
              {"hash_a", r.hash_a},
              {"hash_b", r.hash_b},
              {"size_a", {r.width, r.height, r.channels}},
              {"size_b", {r.b_width, r.b_height, r.b_channels}},
              {"pixels", r.pixels},
              {"mean_error", json_number(r.mean_error)},
              {"rms_error", json_number(r.rms_error)},
              {"psnr", json_number(r.psnr)},
              {"max_error", json_number(r.max_error)},
              {"max_pixel", {r.max_x, r.max_y}},
              {"max_channel", r.max_channel},
              {"max_channel_name", r.max_channel_name},
              {"max_values", {floats(r.max_values_a), floats(r.max_values_b)}},
              {"over_warn", r.over_warn},
              {"over_fail", r.over_fail},
              {"warn", json_float(o.t.warn)},
              {"fail", json_float(o.t.fail)}};
    std::cout << json_text(j) << "\n";
    return int(r.verdict);
  }
  const bool quiet = verbosity() < 0;
  if (!quiet) {
    std::cout << "Comparing \"" << o.a << "\" and \"" << o.b << "\"\n";
    if (verbosity() > 0 || r.verdict != verify::DiffVerdict::ok) {
      const double n = double(r.pixels);
      char line[160];
      std::cout << "  Mean error = " << number(r.mean_error) << "\n  RMS error = " << number(r.rms_error)
                << "\n  Peak SNR = " << number(r.psnr) << "\n  Max error  = " << number(r.max_error);
      if (r.max_error != 0.0) {
        // idiff's line: the channel by its name, then both images' values at that pixel.
        std::cout << " @ (" << r.max_x << ", " << r.max_y << ", "
                  << (r.max_channel_name.empty() ? "channel " + std::to_string(r.max_channel) : r.max_channel_name)
                  << ")";
        if (!r.max_values_a.empty()) {
          const auto values = [](const std::vector<float>& v) {
            std::string s;
            for (const float x : v) s += (s.empty() ? "" : ", ") + float_text(x);
            return s;
          };
          std::cout << "  values are " << values(r.max_values_a) << " vs " << values(r.max_values_b);
        }
      }
      std::cout << "\n";
      std::snprintf(line, sizeof line, "  %llu pixels (%.3g%%) over %g\n  %llu pixels (%.3g%%) over %g\n",
                    (unsigned long long)r.over_warn, 100.0 * double(r.over_warn) / n, double(o.t.warn),
                    (unsigned long long)r.over_fail, 100.0 * double(r.over_fail) / n, double(o.t.fail));
      std::cout << line;
    }
    if (o.exact || verbosity() > 0)
      std::cout << "  " << (r.identical ? "identical decoded pixels" : "decoded pixels differ") << "\n  sha1 "
                << r.hash_a << "\n  sha1 " << r.hash_b << "\n";
    if (r.verdict == verify::DiffVerdict::different_sizes)
      std::cout << "  " << r.width << "x" << r.height << "x" << r.channels << " against " << r.b_width << "x"
                << r.b_height << "x" << r.b_channels << "\n";
  }
  const char* word = r.verdict == verify::DiffVerdict::ok        ? "PASS"
                     : r.verdict == verify::DiffVerdict::warning ? "WARNING"
                                                                 : "FAILURE";
  if (!quiet)
    std::cout << word << "\n";
  else if (r.verdict != verify::DiffVerdict::ok && r.verdict != verify::DiffVerdict::warning)
    std::cerr << word << "\n";
  return int(r.verdict);
}

}  // namespace

std::vector<std::string> idiff_arguments(int argc, char** argv) {
  std::vector<std::string> args(argv, argv + argc);
  if (args.size() < 2 || args[1] != "diff") return args;
  static const char* const kLong[] = {"-fail",          "-failrelative", "-failpercent",  "-hardfail",
                                      "-allowfailures", "-warn",         "-warnrelative", "-warnpercent",
                                      "-hardwarn",      "-od",           "-abs",          "-scale"};
  for (std::size_t i = 2; i < args.size(); ++i)
    for (const char* name : kLong)
      if (args[i] == name) args[i] = std::string("-") + name;
  return args;
}

Runner add_diff_command(CLI::App& app) {
  auto o = std::make_shared<DiffOptions>();
  CLI::App* cmd = app.add_subcommand(
      "diff",
      "compare two images as OpenImageIO's idiff 2.4 does (same flags, defaults, exit codes: 0 pass, 1 warning, "
      "2 failure (images of different sizes are compared over their union, as idiff does), 3 deep against "
      "flat (with --exact: any difference of shape), 4 file error); idiff's -fail style flags work as written");
  cmd->add_option("a", o->a, "first image (any format OpenImageIO reads)")->required();
  cmd->add_option("b", o->b, "second image")->required();
  cmd->add_option("--fail", o->t.fail, "failure absolute difference threshold")->capture_default_str();
  cmd->add_option("--failrelative", o->t.fail_relative, "failure relative threshold")->capture_default_str();
  cmd->add_option("--failpercent", o->t.fail_percent, "allow this percentage of failures")->capture_default_str();
  cmd->add_option("--hardfail", o->t.hard_fail, "fail if any one pixel exceeds this error")->capture_default_str();
  cmd->add_option("--allowfailures", o->t.allow_failures, "OK for this number of pixels to fail by any amount")
      ->capture_default_str();
  cmd->add_option("--warn", o->t.warn, "warning absolute difference threshold")->capture_default_str();
  cmd->add_option("--warnrelative", o->t.warn_relative, "warning relative threshold")->capture_default_str();
  cmd->add_option("--warnpercent", o->t.warn_percent, "allow this percentage of warnings")->capture_default_str();
  cmd->add_option("--hardwarn", o->t.hard_warn, "warn if any one pixel exceeds this error")->capture_default_str();
  cmd->add_flag("-p", o->perceptual, "(idiff's perceptual test: not supported, refused)");
  cmd->add_flag("-a", o->all, "(idiff's all subimages: not supported, refused)");
  cmd->add_option("-o", o->output, "write the difference image A - B (format from the extension)");
  cmd->add_flag("--od", o->only_if_different, "write -o only if the images differ");
  cmd->add_flag("--abs", o->absolute, "-o holds |A - B|");
  cmd->add_option("--scale", o->scale, "scale -o (and --heatmap) by this factor")->capture_default_str();
  cmd->add_option("--heatmap", o->heatmap,
                  "write a readable difference picture: A dimmed, differing pixels in inferno by their largest "
                  "channel difference times -scale (8-bit RGB)");
  cmd->add_flag("--exact", o->exact,
                "pass only for identical decoded pixels (same size, channels and every value, bit for bit)");
  cmd->add_flag("--json", o->json,
                "print verdict, exit code, errors (mean, RMS, PSNR, max and where), pixels over each threshold, "
                "identical, and each image's SHA-1 as JSON");
  return [o, cmd]() -> int { return cmd->parsed() ? run_diff(*o) : -1; };
}

}  // namespace tessera::cli
