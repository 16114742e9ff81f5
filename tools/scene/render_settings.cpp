#include "tools/scene/render_settings.h"

#include <array>
#include <charconv>
#include <cmath>
#include <utility>

#include "pipeline/sample_pattern.h"
#include "tools/scene/common.h"

namespace tessera::scene {
namespace {

constexpr std::array<std::pair<ViewKind, const char*>, 14> kViews = {{
    {ViewKind::shaded, "shaded"},
    {ViewKind::wireframe, "wireframe"},
    {ViewKind::wire_on_shaded, "wire-on-shaded"},
    {ViewKind::factors, "factors"},
    {ViewKind::density, "density"},
    {ViewKind::patch_type, "patch-type"},
    {ViewKind::combination, "combination"},
    {ViewKind::patch_id, "patch-id"},
    {ViewKind::normals, "normals"},
    {ViewKind::uv, "uv"},
    {ViewKind::displacement, "displacement"},
    {ViewKind::cage, "cage"},
    {ViewKind::cracks, "cracks"},
    {ViewKind::culled, "culled"},
}};

[[noreturn]] void refuse(const std::string& what, std::string_view text, const std::string& allowed) {
  throw UsageError(what + ": '" + std::string(text) + "' is not " + allowed);
}

// A name that is none of `names`: what is allowed, and the closest name when the text looks like a
// misspelling of one.
[[noreturn]] void refuse_name(const std::string& what, std::string_view text, const std::string& allowed,
                              const std::vector<std::string>& names) {
  throw UsageError(what + ": '" + std::string(text) + "' is not " + allowed + did_you_mean(text, names));
}

}  // namespace

Scheme scheme_option(std::string_view text, const std::string& what) {
  if (const auto s = parse_scheme(text)) return *s;
  std::vector<std::string> names;
  std::string list;
  for (int k = 0; k < kSchemeCount; ++k) {
    names.push_back(to_string(Scheme(k)));
    list += std::string(k ? ", " : "") + names.back();
  }
  refuse_name(what, text, "one of " + list, names);
}

int isolation_option(std::string_view text, const std::string& what) {
  int level = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), level);
  if (ec != std::errc() || end != text.data() + text.size() || level < 1 || level > kMaxIsolation)
    refuse(what, text, "an isolation level from 1 to " + std::to_string(kMaxIsolation));
  return level;
}

ts::Partitioning partitioning_option(std::string_view text, const std::string& what) {
  if (const auto p = ts::parse_partitioning(text)) return *p;
  refuse_name(what, text, "one of integer, pow2, fractional_odd, fractional_even",
              {"integer", "pow2", "fractional_odd", "fractional_even"});
}

ViewKind view_kind_option(std::string_view text) {
  for (const auto& [kind, name] : kViews)
    if (text == name) return kind;
  std::vector<std::string> names;
  for (const auto& [kind, name] : kViews) names.push_back(name);
  refuse_name("--view", text, "one of " + view_names(), names);
}

FactorKind factor_kind_option(std::string_view text) {
  if (text == "raw") return FactorKind::raw;
  if (text == "processed") return FactorKind::processed;
  refuse("--factor-kind", text, "raw or processed");
}

LodMode lod_mode_option(std::string_view text) {
  if (const auto m = parse_lod_mode(text)) return *m;
  refuse_name("--lod", text, "uniform, distance or screen", {"uniform", "distance", "screen"});
}

PatchCullMode cull_option(std::string_view text) {
  if (const auto m = parse_patch_cull_mode(text)) return *m;
  refuse_name("--cull", text, "none, frustum, backface or all", {"none", "frustum", "backface", "all"});
}

DisplacementSpace displacement_space_option(std::string_view text) {
  if (text == "tangent") return DisplacementSpace::tangent;
  if (text == "object") return DisplacementSpace::object;
  refuse("--displacement-space", text, "tangent or object");
}

UvSeams uv_seams_option(std::string_view text) {
  if (text == "blend") return UvSeams::blend;
  if (text == "raw") return UvSeams::raw;
  refuse("--uv-seams", text, "blend or raw");
}

glm::vec3 vec3_option(std::string_view text, const std::string& what) {
  const auto v = parse_float_list(text, what);
  if (v.size() != 3) throw UsageError(what + ": expected x,y,z");
  for (float x : v)
    if (!std::isfinite(x)) throw UsageError(what + ": not finite");
  return {v[0], v[1], v[2]};
}

bool has_direction(glm::vec3 v) {
  const double length = glm::length(glm::dvec3(v));
  return length > 1e-12 && std::isfinite(length);
}

glm::vec3 direction_option(std::string_view text, const std::string& what) {
  const glm::vec3 v = vec3_option(text, what);
  if (!has_direction(v))
    throw UsageError(what + ": " + std::string(text) + " has no direction (give a non-zero x,y,z)");
  return v;
}

std::pair<int, int> resolution_option(std::string_view text) { return parse_resolution(std::string(text)); }

int msaa_option(int msaa) {
  if (!valid_sample_count(msaa)) throw UsageError("--msaa: " + std::to_string(msaa) + " is not 1, 2, 4, 8 or 16");
  return msaa;
}

std::string view_names() {
  std::string s;
  for (const auto& [kind, name] : kViews) s += (s.empty() ? "" : ", ") + std::string(name);
  return s;
}

const char* to_string(ViewKind v) {
  for (const auto& [kind, name] : kViews)
    if (kind == v) return name;
  return "?";
}

const char* to_string(FactorKind k) { return k == FactorKind::processed ? "processed" : "raw"; }
const char* to_string(UvSeams u) { return u == UvSeams::raw ? "raw" : "blend"; }
const char* to_string(DisplacementSpace s) { return s == DisplacementSpace::object ? "object" : "tangent"; }

std::string vec3_text(glm::vec3 v) { return float_text(v.x) + "," + float_text(v.y) + "," + float_text(v.z); }

std::string resolution_text(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

}  // namespace tessera::scene
