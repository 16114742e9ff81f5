// The `tessera._tessera` module: Tessera from Python, over the same functions the CLI runs (so an array
// from render() has the bytes `tessera render` writes). C++ errors arrive as Python exceptions:
// tessera.InputError (a file or its contents; RuntimeError) and tessera.UsageError (a bad value;
// ValueError), with the CLI's one-line messages. Long calls release the GIL, so Dask worker threads run
// them in parallel.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "shaders_cpp/animation/animation_sampler.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/gltf/gltf_cage.h"
#include "shaders_cpp/image_io/image_codec.h"
#include "tessellator/check.h"
#include "tools/scene/check_report.h"
#include "tools/scene/check_suite.h"
#include "tools/scene/common.h"
#include "tools/scene/scene_render.h"
#include "tools/verify/image_diff.h"

namespace py = pybind11;
using namespace tessera;
using namespace tessera::scene;

namespace {

// A Python value (str, number, bool, list, dict, None) as JSON, through Python's own encoder.
Json json_of(const py::handle& value) {
  const std::string text = py::module_::import("json").attr("dumps")(value).cast<std::string>();
  return Json::parse(text);
}

// The settings of a render call: `source` is a scene file (.json), a scene object (a dict), or an
// asset (an OBJ or glTF cage); `settings` (scene fields by name, as keywords) replace its fields.
// Relative paths in a scene file are from its folder, elsewhere from the working directory.
RenderSettings settings_of(const py::object& source, const py::kwargs& settings) {
  Json root;
  std::string where = "render()", dir;
  if (py::isinstance<py::dict>(source)) {
    root = json_of(source);
  } else {
    const std::string path = py::str(source).cast<std::string>();
    if (std::filesystem::path(path).extension() == ".json") {
      if (settings.empty()) return read_scene(path);
      root = scene_json(read_scene(path), std::filesystem::path(path).parent_path().string());
      where = path, dir = std::filesystem::path(path).parent_path().string();
    } else {
      root = Json{{"tessera_scene", 1}, {"asset", path}};
    }
  }
  for (const auto& [key, value] : settings) root[key.cast<std::string>()] = json_of(value);
  return scene_settings(root, where, dir);
}

// The scene's image, drawn with `threads` workers (0: all; the bytes are the same for any count).
SceneImage render_settings(const RenderSettings& s, int threads, std::unique_ptr<PreparedScene>& prepared) {
  if (threads < 0) throw UsageError("threads: " + std::to_string(threads) + " is not >= 0");
  prepared = prepare_scene(s);
  Device device(device_options(threads));
  return render_scene(device, *prepared, false);
}

// The image `tessera render` writes as PNG (the legend of a debug view included), decoded to RGBA8.
std::vector<std::uint8_t> png_pixels(const SceneImage& image, int& width, int& height) {
  std::string png;
  write_scene_image(image, {"render.png", &png});
  std::vector<std::uint8_t> pixels;
  const ReadFailure failed = image_codec().read(
      ImageSource{"render.png",
                  std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(png.data()), png.size()), ".png"},
      PixelType::u8, [&](const ImageHeader& h) -> void* {
        TESSERA_CHECK_EQ(h.channels, 4);
        width = h.width, height = h.height;
        pixels.resize(std::size_t(h.width) * std::size_t(h.height) * 4);
        return pixels.data();
      });
  TESSERA_CHECK(!failed, failed.message);
  return pixels;
}

py::dict diff_dict(const verify::DiffReport& r) {
  py::dict d;
  d["verdict"] = verify::to_string(r.verdict);
  d["exit_code"] = int(r.verdict);
  d["identical"] = r.identical;
  d["hash_a"] = r.hash_a;
  d["hash_b"] = r.hash_b;
  d["mean_error"] = r.mean_error;
  d["rms_error"] = r.rms_error;
  d["psnr"] = r.psnr;
  d["max_error"] = r.max_error;
  d["max_pixel"] = py::make_tuple(r.max_x, r.max_y);
  d["max_channel"] = r.max_channel;
  d["over_warn"] = r.over_warn;
  d["over_fail"] = r.over_fail;
  d["pixels"] = r.pixels;
  d["error"] = r.error;
  return d;
}

}  // namespace

PYBIND11_MODULE(_tessera, m) {
  m.doc() = "Tessera: a deterministic CPU implementation of the Direct3D 11 tessellation pipeline";
  py::register_exception<InputError>(m, "InputError", PyExc_RuntimeError);
  py::register_exception<UsageError>(m, "UsageError", PyExc_ValueError);
  m.attr("__version__") = "0.1.0";

  m.def(
      "load_cage",
      [](const std::string& path, std::optional<double> time, const std::string& animation, const std::string& mesh) {
        Cage c;
        try {
          if (is_gltf_path(path)) {
            GltfSelection selection;
            selection.mesh = mesh;
            GltfCage g = load_gltf_cage(path, selection);
            c = std::move(g.cage);
            if (time) {
              if (!g.rig) throw UsageError(path + " is not animated");
              int a = g.rig->animations.empty() ? -1 : 0;
              if (!animation.empty() && (a = find_animation(*g.rig, animation)) < 0)
                throw UsageError(path + " has no animation '" + animation + "'");
              c.positions = pose_positions(*g.rig, pose_at(*g.rig, a, *time));
            }
          } else {
            if (time || !animation.empty() || !mesh.empty()) throw UsageError(path + ": OBJ cages are static");
            c = load_obj_cage(path);
          }
        } catch (const CageError& e) {
          throw InputError(e.what());
        }
        py::array_t<float> positions({py::ssize_t(c.positions.size()), py::ssize_t(3)});
        auto p = positions.mutable_unchecked<2>();
        for (std::size_t i = 0; i < c.positions.size(); ++i)
          for (int k = 0; k < 3; ++k) p(py::ssize_t(i), k) = c.positions[i][k];
        py::dict d;
        d["name"] = c.name;
        d["positions"] = positions;
        d["face_sizes"] = py::array_t<int>(py::ssize_t(c.face_sizes.size()), c.face_sizes.data());
        d["face_vertices"] = py::array_t<int>(py::ssize_t(c.face_vertices.size()), c.face_vertices.data());
        d["warnings"] = c.warnings;
        return d;
      },
      py::arg("path"), py::arg("time") = py::none(), py::arg("animation") = "", py::arg("mesh") = "",
      "A cage (OBJ or glTF): positions (N x 3 float32; a glTF asset posed at `time` seconds of `animation` when "
      "given, else its rest pose), face_sizes, face_vertices, warnings.");

  m.def(
      "render",
      [](const py::object& source, int threads, const py::kwargs& settings) {
        const RenderSettings s = settings_of(source, settings);
        std::vector<std::uint8_t> pixels;
        int width = 0, height = 0;
        {
          py::gil_scoped_release unlocked;
          std::unique_ptr<PreparedScene> prepared;
          const SceneImage image = render_settings(s, threads, prepared);
          pixels = png_pixels(image, width, height);
        }
        py::array_t<std::uint8_t> out({py::ssize_t(height), py::ssize_t(width), py::ssize_t(4)});
        std::copy(pixels.begin(), pixels.end(), out.mutable_data());
        return out;
      },
      py::arg("source"), py::arg("threads") = 0,
      "Renders a scene file (.json), a scene dict, or an asset (OBJ, glTF), with scene fields as keywords "
      "(scheme='exact', factor=4, view='factors', resolution=[640, 480], camera={...}); the image `tessera "
      "render` writes as PNG (a debug view's legend included) as an H x W x 4 uint8 array (RGBA).");

  m.def(
      "render_to_file",
      [](const py::object& source, const std::string& output, int threads, const py::kwargs& settings) {
        const RenderSettings s = settings_of(source, settings);
        py::gil_scoped_release unlocked;
        std::unique_ptr<PreparedScene> prepared;
        const SceneImage image = render_settings(s, threads, prepared);
        write_scene_image(image, {output});
      },
      py::arg("source"), py::arg("output"), py::arg("threads") = 0,
      "Renders as render() does, to an image file, as `tessera render --scene SCENE -o OUTPUT` does.");

  m.def(
      "diff",
      [](const std::string& a, const std::string& b, float fail, float failrelative, float failpercent, float hardfail,
         long long allowfailures, float warn, float warnrelative, float warnpercent, float hardwarn, bool exact) {
        verify::DiffThresholds t{fail, failrelative, failpercent, hardfail, allowfailures,
                                 warn, warnrelative, warnpercent, hardwarn};
        verify::DiffReport r;
        {
          py::gil_scoped_release unlocked;
          r = verify::diff_images(a, b, t, exact);
        }
        return diff_dict(r);
      },
      py::arg("a"), py::arg("b"), py::arg("fail") = 1e-6f, py::arg("failrelative") = 0.0f,
      py::arg("failpercent") = 0.0f, py::arg("hardfail") = std::numeric_limits<float>::infinity(),
      py::arg("allowfailures") = 0, py::arg("warn") = 1e-6f, py::arg("warnrelative") = 0.0f,
      py::arg("warnpercent") = 0.0f, py::arg("hardwarn") = std::numeric_limits<float>::infinity(),
      py::arg("exact") = false, "Compares two image files as `tessera diff` (idiff 2.4's rules) does.");

  m.def(
      "suite_cases",
      [](const std::string& suite) {
        std::vector<std::string> names;
        for (const SuiteCase& c : read_suite(suite).cases) names.push_back(c.name);
        return names;
      },
      py::arg("suite"), "The case names of a golden suite, in order.");

  m.def(
      "suite_name", [](const std::string& suite) { return read_suite(suite).name; }, py::arg("suite"));

  m.def(
      "run_case",
      [](const std::string& suite_path, const std::string& name, const std::string& report_dir, int threads) {
        std::string text;
        {
          py::gil_scoped_release unlocked;
          const Suite suite = read_suite(suite_path);
          const auto it =
              std::find_if(suite.cases.begin(), suite.cases.end(), [&](const SuiteCase& c) { return c.name == name; });
          if (it == suite.cases.end()) throw UsageError(suite_path + ": no case named '" + name + "'");
          CaseResult r = run_case(suite, *it, report_dir, threads);
          Json j = r.json();
          j["index"] = std::size_t(it - suite.cases.begin());
          j["report_golden"] = std::filesystem::exists(r.golden_image);
          text = j.dump();
        }
        return text;
      },
      py::arg("suite"), py::arg("name"), py::arg("report_dir"), py::arg("threads") = 1,
      "Runs one case of a suite as `tessera check` does, into report_dir; its result as JSON text.");

  m.def(
      "write_check_reports",
      [](const std::string& summary, const std::string& dir) {
        Json j = Json::parse(summary);
        j["counts"] = count_statuses(j["cases"]);
        write_check_reports(j, dir);
      },
      py::arg("summary"), py::arg("dir"), "Writes report.html, junit.xml and summary.json from a summary (JSON text).");
}
