#include "tools/scene/check_suite.h"

#include <bit>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "shaders_cpp/displacement/udim_tiles.h"
#include "tessellator/fnv1a.h"
#include "tools/scene/check_report.h"
#include "tools/scene/common.h"
#include "tools/scene/scene_render.h"
#include "tools/scene/surface_weld.h"
#include "tools/verify/weld_check.h"

namespace tessera::scene {
namespace {

namespace fs = std::filesystem;

std::string hex64(std::uint64_t v) {
  char b[20];
  std::snprintf(b, sizeof b, "%016llx", (unsigned long long)v);
  return b;
}

void add_float(ts::Fnv1a& h, float x) { h.add(std::bit_cast<std::uint32_t>(x), 4); }

[[noreturn]] void suite_error(const std::string& path, const std::string& field, const std::string& message) {
  throw InputError(path + ": \"" + field + "\": " + message);
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

Json read_json_file(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path)) throw InputError(path + ": cannot read the " + std::string(what));
  std::stringstream text;
  text << in.rdbuf();
  try {
    return Json::parse(text.str());
  } catch (const Json::exception& e) {  // parse_error, or out_of_range for a number past double
    const std::string w = e.what();
    const auto at = w.find("] ");
    throw InputError(path + ": not JSON (" + (at == std::string::npos ? w : w.substr(at + 2)) + ")");
  }
}

float threshold(const Json& c, const char* key, float fallback, const std::string& path, const std::string& field) {
  if (!c.contains(key)) return fallback;
  if (!c[key].is_number() || !(c[key].get<double>() >= 0.0))
    suite_error(path, field + "." + key, "expected a number >= 0, got " + c[key].dump());
  return float(c[key].get<double>());
}

GeometryDigest digest_of(Device& device, const PreparedScene& scene, const SceneImage& image) {
  GeometryDigest d;
  verify::WeldChecker weld;
  const WeldCurves curves = weld_curves(scene.model.cage, *scene.model.topology);
  ts::Fnv1a ds;
  const auto sink = [&](const auto& out, const PatchGroup& g) {
    ds.add(out.patch_id, 4);
    for (const auto& p : out.points) {
      add_float(ds, p.position.x), add_float(ds, p.position.y), add_float(ds, p.position.z);
      add_float(ds, p.normal.x), add_float(ds, p.normal.y), add_float(ds, p.normal.z);
    }
    for (const std::uint32_t i : out.indices) ds.add(i, 4);
    d.triangles += out.indices.size() / 3;
    add_surface_patch(weld, out, g, curves);
  };
  const DrawResult r = stream_surface(device, scene.model, scene.displacement ? &*scene.displacement : nullptr,
                                      scene.factors, scene.cull, scene.settings.partitioning, sink);
  if (!r.ok()) throw InputError(scene.settings.cage + ": " + r.error);
  const verify::WeldReport w = weld.report();
  d.crack_edges = w.crack_edges;
  d.border_edges = w.border_edges;
  d.nonmanifold_edges = w.nonmanifold_edges;
  d.ds_hash = hex64(ds.value);
  ts::Fnv1a f;
  image.tables->for_each([&](const PatchInfo& p) {
    for (const float e : p.raw.edge) add_float(f, e);
    for (const float i : p.raw.inside) add_float(f, i);
  });
  d.factors_hash = hex64(f.value);
  return d;
}

// A file a scene names, as the scene resolves it, else the file of that name in the suite's assets
// folder (a suite copied without the tree its scenes came from); InputError naming both when neither
// exists.
// A file, or a UDIM set (udim_tiles.h) with at least one tile, at `path`.
bool asset_exists(const std::string& path) {
  return has_udim_token(path) ? !udim_tiles_on_disk(path).empty() : fs::exists(path);
}

std::string suite_asset(const Suite& suite, const SuiteCase& c, const std::string& path, const char* field) {
  if (path.empty() || asset_exists(path)) return path;
  const fs::path copy = fs::path(suite_assets_dir(suite)) / fs::path(path).filename();
  if (asset_exists(copy.string())) return copy.lexically_normal().string();
  throw InputError(c.scene + ": \"" + field + "\": " + path + " does not exist, nor " + copy.string() +
                   " (tessera check --collect-assets copies a suite's assets into it)");
}

std::string case_command(const SuiteCase& c, const std::string& out) {
  return "tessera render --scene " + fs::absolute(c.scene).lexically_normal().string() + " -o " + out;
}

}  // namespace

std::string suite_assets_dir(const Suite& suite) {
  return (fs::absolute(fs::path(suite.path)).parent_path() / "assets").lexically_normal().string();
}

RenderSettings suite_scene(const Suite& suite, const SuiteCase& c) {
  RenderSettings s = read_scene(c.scene);
  s.cage = suite_asset(suite, c, s.cage, "asset");
  s.factors_file = suite_asset(suite, c, s.factors_file, "factors_per_edge");
  if (s.displacement.map != "none") s.displacement.map = suite_asset(suite, c, s.displacement.map, "displacement.map");
  const std::string& n = s.displacement.normal_map;
  if (n != "auto" && n != "derived") s.displacement.normal_map = suite_asset(suite, c, n, "displacement.normal_map");
  return s;
}

namespace {
// Copies `from` into the assets folder as `name` (a glTF's own relative URIs keep their folders below
// it); a different file already there under that name is an InputError naming both.
void copy_asset(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (fs::exists(to)) {
    if (fs::equivalent(from, to, ec)) return;
    if (file_bytes(from) != file_bytes(to))
      throw InputError(to.string() + ": holds another file of that name than " + from.string());
    return;
  }
  fs::create_directories(to.parent_path(), ec);
  fs::copy_file(from, to, ec);
  if (ec) throw InputError(to.string() + ": cannot write (" + ec.message() + ")");
}

// The files a .gltf names by relative URI (buffers and images), as written in it.
std::vector<std::string> gltf_relative_uris(const std::string& path) {
  std::vector<std::string> out;
  if (fs::path(path).extension() != ".gltf") return out;
  const Json root = read_json_file(path, "glTF file");
  for (const char* list : {"buffers", "images"})
    if (root.contains(list) && root[list].is_array())
      for (const Json& item : root[list])
        if (item.is_object() && item.contains("uri") && item["uri"].is_string()) {
          const std::string uri = item["uri"].get<std::string>();
          if (uri.rfind("data:", 0) != 0 && uri.find("://") == std::string::npos && !fs::path(uri).is_absolute())
            out.push_back(uri);
        }
  return out;
}
}  // namespace

std::vector<std::string> collect_suite_assets(const Suite& suite) {
  const fs::path assets = suite_assets_dir(suite);
  std::vector<std::string> said;
  for (const SuiteCase& c : suite.cases) {
    RenderSettings s = suite_scene(suite, c);
    int copied = 0;
    const auto collect = [&](std::string& path) {
      if (path.empty() || path == "none" || path == "auto" || path == "derived") return;
      const fs::path from = fs::absolute(path).lexically_normal(), to = assets / from.filename();
      if (has_udim_token(path)) {  // every tile of the set
        for (int tile : udim_tiles_on_disk(from.string()))
          copy_asset(udim_tile_path(from.string(), tile), udim_tile_path(to.string(), tile));
        path = to.string();
        ++copied;
        return;
      }
      copy_asset(from, to);
      for (const std::string& uri : gltf_relative_uris(from.string()))
        copy_asset((from.parent_path() / uri).lexically_normal(), (assets / uri).lexically_normal());
      path = to.string();
      ++copied;
    };
    collect(s.cage), collect(s.factors_file), collect(s.displacement.map), collect(s.displacement.normal_map);
    write_text_atomically(c.scene, scene_json(s, fs::path(c.scene).parent_path().string()).dump(2) + "\n");
    said.push_back(c.name + ": " + std::to_string(copied) + " file(s) in " + assets.string() + ", " + c.scene +
                   " points there");
  }
  return said;
}

const char* to_string(CaseStatus s) {
  switch (s) {
    case CaseStatus::pass: return "pass";
    case CaseStatus::warning: return "warning";
    case CaseStatus::fail: return "fail";
    case CaseStatus::new_case: return "new";
    case CaseStatus::error: return "error";
  }
  return "error";
}

Json GeometryDigest::json() const {
  return {{"triangles", triangles},
          {"crack_edges", crack_edges},
          {"border_edges", border_edges},
          {"nonmanifold_edges", nonmanifold_edges},
          {"factors_hash", factors_hash},
          {"ds_hash", ds_hash}};
}

Json CaseResult::json() const {
  Json j = {{"name", name},           {"status", to_string(status)},  {"message", message},
            {"new_image", new_image}, {"golden_image", golden_image}, {"diff_image", diff_image},
            {"checks", checks},       {"command", command},           {"seconds", seconds}};
  if (!warnings.empty()) j["warnings"] = warnings;
  if (!scene_changes.is_null()) j["scene_changes"] = scene_changes;
  if (diff) {
    j["compare"] = {{"verdict", verify::to_string(diff->verdict)},
                    {"identical", diff->identical},
                    {"max_error", diff->max_error},
                    {"mean_error", diff->mean_error},
                    {"rms_error", diff->rms_error},
                    {"psnr", std::isfinite(diff->psnr) ? Json(diff->psnr) : Json(nullptr)},
                    {"max_pixel", {diff->max_x, diff->max_y}},
                    {"over_warn", diff->over_warn},
                    {"over_fail", diff->over_fail},
                    {"pixels", diff->pixels},
                    {"hash_new", diff->hash_b},
                    {"hash_golden", diff->hash_a}};
  }
  return j;
}

Suite read_suite(const std::string& path) {
  const Json root = read_json_file(path, "suite file");
  if (!root.is_object()) throw InputError(path + ": expected a JSON object");
  const std::set<std::string> known = {"tessera_suite", "name", "golden", "cases"};
  for (const auto& [k, v] : root.items())
    if (!known.count(k)) suite_error(path, k, "not a suite field (tessera_suite, name, golden, cases)");
  if (!root.contains("tessera_suite") || root["tessera_suite"] != 1)
    suite_error(path, "tessera_suite", "must be 1 (this format's version)");
  Suite s;
  s.path = path;
  const fs::path dir = fs::path(path).parent_path();
  // Absolute: results name files the same way whatever the working directory (check, batch, merge).
  const auto resolve = [&](const std::string& p) { return fs::absolute(dir / p).lexically_normal().string(); };
  s.name = root.contains("name") && root["name"].is_string() ? root["name"].get<std::string>()
                                                             : fs::path(path).stem().string();
  if (root.contains("golden") && !root["golden"].is_string()) suite_error(path, "golden", "expected a directory path");
  s.golden_dir = resolve(root.contains("golden") ? root["golden"].get<std::string>() : s.name);
  if (!root.contains("cases") || !root["cases"].is_array() || root["cases"].empty())
    suite_error(path, "cases", "expected a non-empty list of cases");
  const std::regex safe("[A-Za-z0-9._-]{1,100}");
  std::set<std::string> names;
  for (std::size_t i = 0; i < root["cases"].size(); ++i) {
    const Json& c = root["cases"][i];
    const std::string field = "cases[" + std::to_string(i) + "]";
    if (!c.is_object()) suite_error(path, field, "expected an object");
    for (const auto& [k, v] : c.items())
      if (k != "name" && k != "scene" && k != "compare" && k != "checks")
        suite_error(path, field + "." + k, "not a case field (name, scene, compare, checks)");
    SuiteCase sc;
    if (!c.contains("name") || !c["name"].is_string() || !std::regex_match(c["name"].get<std::string>(), safe))
      suite_error(path, field + ".name", "expected a name of letters, digits, '.', '_' or '-'");
    sc.name = c["name"].get<std::string>();
    if (!names.insert(sc.name).second) suite_error(path, field + ".name", "'" + sc.name + "' is used twice");
    if (!c.contains("scene") || !c["scene"].is_string()) suite_error(path, field + ".scene", "expected a scene file");
    sc.scene = resolve(c["scene"].get<std::string>());
    if (c.contains("compare")) {
      const Json& m = c["compare"];
      if (m == "exact") {
        sc.exact = true;
      } else if (m.is_object()) {
        for (const auto& [k, v] : m.items())
          if (k != "fail" && k != "failrelative" && k != "failpercent" && k != "hardfail" && k != "allowfailures" &&
              k != "warn" && k != "warnrelative" && k != "warnpercent" && k != "hardwarn")
            suite_error(path, field + ".compare." + k, "not an idiff threshold");
        const std::string f = field + ".compare";
        verify::DiffThresholds& t = sc.thresholds;
        t.fail = threshold(m, "fail", t.fail, path, f);
        t.fail_relative = threshold(m, "failrelative", t.fail_relative, path, f);
        t.fail_percent = threshold(m, "failpercent", t.fail_percent, path, f);
        t.hard_fail = threshold(m, "hardfail", t.hard_fail, path, f);
        t.allow_failures = (long long)threshold(m, "allowfailures", 0.0f, path, f);
        t.warn = threshold(m, "warn", t.warn, path, f);
        t.warn_relative = threshold(m, "warnrelative", t.warn_relative, path, f);
        t.warn_percent = threshold(m, "warnpercent", t.warn_percent, path, f);
        t.hard_warn = threshold(m, "hardwarn", t.hard_warn, path, f);
      } else {
        suite_error(path, field + ".compare", "expected \"exact\" or an object of idiff thresholds");
      }
    }
    if (c.contains("checks")) {
      if (!c["checks"].is_array()) suite_error(path, field + ".checks", "expected a list");
      for (const Json& k : c["checks"]) {
        if (!k.is_string() || (k != "watertight" && k != "triangles" && k != "factors_hash" && k != "ds_hash"))
          suite_error(path, field + ".checks", k.dump() + " is not watertight, triangles, factors_hash or ds_hash");
        sc.checks.push_back(k.get<std::string>());
      }
    }
    s.cases.push_back(std::move(sc));
  }
  return s;
}

namespace {
// The golden's digest and scene: <golden dir>/<name>.json.
std::string golden_digest_path(const Suite& suite, const SuiteCase& c) {
  return (fs::path(suite.golden_dir) / (c.name + ".json")).string();
}

void flatten_scene(const Json& j, const std::string& prefix, std::vector<std::pair<std::string, Json>>& out) {
  if (j.is_object() && !j.empty()) {
    for (const auto& [k, v] : j.items()) flatten_scene(v, prefix.empty() ? k : prefix + "." + k, out);
  } else {
    out.emplace_back(prefix, j);
  }
}
}  // namespace

// Files are named relative to the golden directory, which a copied or moved suite changes: they are
// compared by file name.
bool same_scene_value(const std::string& field, const Json& a, const Json& b) {
  static const std::set<std::string> files = {"asset", "factors_per_edge", "displacement.map",
                                              "displacement.normal_map"};
  if (files.count(field) && a.is_string() && b.is_string())
    return fs::path(a.get<std::string>()).filename() == fs::path(b.get<std::string>()).filename();
  return a == b;
}

Json scene_differences(const Json& golden, const Json& now) {
  std::vector<std::pair<std::string, Json>> a, b;
  flatten_scene(golden, "", a);
  flatten_scene(now, "", b);
  const auto find = [](const std::vector<std::pair<std::string, Json>>& v, const std::string& k) -> const Json* {
    for (const auto& [key, value] : v)
      if (key == k) return &value;
    return nullptr;
  };
  Json out = Json::array();
  for (const auto& [k, v] : b) {
    const Json* g = find(a, k);
    if (!g || !same_scene_value(k, *g, v))
      out.push_back({{"field", k}, {"golden", g ? *g : Json(nullptr)}, {"new", v}});
  }
  for (const auto& [k, v] : a)
    if (!find(b, k)) out.push_back({{"field", k}, {"golden", v}, {"new", nullptr}});
  return out;
}

CaseResult run_case(const Suite& suite, const SuiteCase& c, const std::string& report_dir, int threads) {
  const auto start = std::chrono::steady_clock::now();
  CaseResult r;
  r.name = c.name;
  r.new_image = "new/" + c.name + ".png";
  r.golden_image = (fs::path(suite.golden_dir) / (c.name + ".png")).string();
  const std::string new_path = (fs::path(report_dir) / r.new_image).string();
  r.command = case_command(c, c.name + ".png");
  try {
    const RenderSettings settings = suite_scene(suite, c);
    r.scene = scene_json(settings, suite.golden_dir);
    const std::string digest_path = golden_digest_path(suite, c);
    Json golden;
    if (fs::exists(digest_path)) golden = read_json_file(digest_path, "golden digest");
    if (golden.is_object() && golden.contains("scene")) r.scene_changes = scene_differences(golden["scene"], r.scene);
    const std::unique_ptr<PreparedScene> scene = prepare_scene(settings);
    r.warnings = scene->model.cage.warnings;
    Device device(device_options(threads >= 0 ? threads : scene->settings.threads));
    const bool geometry = !c.checks.empty();
    const SceneImage image = render_scene(device, *scene, geometry);
    fs::create_directories(fs::path(new_path).parent_path());
    write_scene_image(image, {new_path});
    if (geometry) r.digest = digest_of(device, *scene, image);

    std::vector<std::string> problems;
    bool is_new = false;
    if (!fs::exists(r.golden_image)) {
      is_new = true;
      problems.push_back("no golden image");
    } else {
      verify::DiffImages images;  // kept for the difference picture: the images are read once
      r.diff = verify::diff_images(r.golden_image, new_path, c.thresholds, c.exact, &images);
      const verify::DiffVerdict v = r.diff->verdict;
      if (!r.diff->identical && v != verify::DiffVerdict::file_error && v != verify::DiffVerdict::different_sizes) {
        r.diff_image = "diff/" + c.name + ".png";
        const fs::path diff_path = fs::path(report_dir) / r.diff_image;
        fs::create_directories(diff_path.parent_path());
        if (auto e = verify::write_heat_map(images, 1.0f, diff_path.string()); !e.empty()) throw InputError(e);
      }
      if (v == verify::DiffVerdict::file_error)
        problems.push_back("golden image: " + r.diff->error);
      else if (v == verify::DiffVerdict::different_sizes)
        problems.push_back("image sizes differ");
      else if (v == verify::DiffVerdict::failure)
        problems.push_back("image: " + std::to_string(r.diff->over_fail) + " pixels over " +
                           float_text(c.thresholds.fail) + ", max error " + metric_text(r.diff->max_error));
    }
    if (geometry) {
      const Json now = r.digest.json();
      for (const std::string& k : c.checks) {
        // Watertight is a property, not a comparison: no crack and no non-manifold edge, whatever the
        // golden has; the surface's border is not a crack (surface_weld.h).
        if (k == "watertight") {
          for (const char* key : {"crack_edges", "nonmanifold_edges"}) {
            const bool zero = now[key] == 0;
            r.checks[key] = {{"golden", 0}, {"new", now[key]}, {"pass", zero}};
            if (!zero) problems.push_back(std::string(key) + ": " + now[key].dump() + ", expected 0 (not watertight)");
          }
          continue;
        }
        const bool known = golden.is_object() && golden.contains(k);
        const bool same = known && golden[k] == now[k];
        r.checks[k] = {{"golden", known ? golden[k] : Json(nullptr)}, {"new", now[k]}, {"pass", same}};
        if (!known) {
          is_new = true;
          problems.push_back(k + ": no golden value");
        } else if (!same) {
          problems.push_back(k + ": " + now[k].dump() + ", golden " + golden[k].dump());
        }
      }
    }
    const bool failed = std::any_of(problems.begin(), problems.end(),
                                    [](const std::string& p) { return p.find("no golden") == std::string::npos; });
    r.status = failed                                                      ? CaseStatus::fail
               : is_new                                                    ? CaseStatus::new_case
               : r.diff && r.diff->verdict == verify::DiffVerdict::warning ? CaseStatus::warning
                                                                           : CaseStatus::pass;
    for (const std::string& p : problems) r.message += (r.message.empty() ? "" : "; ") + p;
    // A failure whose scene changed since the golden was blessed says which fields, first of all.
    if (r.status == CaseStatus::fail && r.scene_changes.is_array() && !r.scene_changes.empty()) {
      std::string fields;
      for (const Json& d : r.scene_changes) fields += (fields.empty() ? "" : ", ") + d["field"].get<std::string>();
      r.message += "; the scene differs from the golden's in " + fields;
    }
  } catch (const std::exception& e) {
    r.status = CaseStatus::error;
    r.message = e.what();
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

void bless_case(const Suite& suite, const SuiteCase& c, const CaseResult& r, const std::string& report_dir) {
  fs::create_directories(suite.golden_dir);
  const fs::path from = fs::path(report_dir) / r.new_image;
  write_file_atomically(r.golden_image, [&](const std::string& temp) {
    std::error_code ec;
    fs::copy_file(from, temp, fs::copy_options::overwrite_existing, ec);
    if (ec) throw InputError(r.golden_image + ": cannot write (" + ec.message() + ")");
  });
  Json digest = c.checks.empty() ? Json::object() : r.digest.json();
  digest["scene"] = r.scene;  // what the golden was rendered from: a later failure names the fields that changed
  write_text_atomically(golden_digest_path(suite, c), digest.dump(2) + "\n");
}

void record_golden_scene(const Suite& suite, const SuiteCase& c, const CaseResult& r) {
  const std::string path = golden_digest_path(suite, c);
  Json digest = fs::exists(path) ? read_json_file(path, "golden digest") : Json::object();
  if (!digest.is_object()) throw InputError(path + ": expected a JSON object");
  digest["scene"] = r.scene;
  write_text_atomically(path, digest.dump(2) + "\n");
}

}  // namespace tessera::scene
