// `tessera analyze CAGE.obj [--json]`: what a control cage is made of, after the talk's nvAnalyze:
// counts, valences, tags, UV seams, and the histogram of topology combinations (topology_combinations.h)
// that says how many distinct 1-ring structures, hence stencil tables, the cage needs.
//
// The output is built as a list of sections, each writing its lines and its JSON keys into one Report;
// a new analysis (the displacement map, memory) is one more section function.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include "shaders_cpp/cage/bounding_box.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/cage/topology_combinations.h"
#include "tools/cli/analyze_memory.h"
#include "tools/cli/commands.h"
#include "tools/scene/common.h"
#include "tools/scene/model_options.h"

namespace tessera::cli {

using namespace scene;

namespace {

struct AnalyzeOptions {
  AssetSettings asset;
  std::string cage;
  bool json = false;
  MemoryOptions memory;
};

// Text for people and a JSON object for scripts, written side by side so they cannot disagree.
class Report {
 public:
  void line(const std::string& text) { text_ += text + "\n"; }
  void count(const char* key, const std::string& label, long long value) {
    line(label + " = " + std::to_string(value));
    json_[key] = value;
  }
  nlohmann::ordered_json& json() { return json_; }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  nlohmann::ordered_json json_;
};

// Everything the sections read.
struct CageAnalysis {
  Cage cage;
  Topology topology;
  TopologyCombinations combinations;
  std::optional<MemoryAnalysis> memory;  // with --memory
};

// The axis-aligned box of the control points (subdivision limit surfaces lie inside their control
// points' convex hull, so inside this box; a displacement map can push the surface out by its bound).
// Cameras and scene files are written in these units.
void bounding_box_section(Report& r, const Cage& c) {
  if (c.positions.empty()) return;
  const Box3 box = bounding_box(c.positions);
  const glm::vec3 lo = box.lo, hi = box.hi, size = hi - lo, centre = box.centre();
  const float diagonal = float(glm::length(glm::dvec3(size)));
  const auto text = [](glm::vec3 v) { return float_text(v.x) + ", " + float_text(v.y) + ", " + float_text(v.z); };
  const auto json = [](glm::vec3 v) {
    // float_text is the shortest text that reads back as the float: the JSON shows those digits.
    const auto number = [](float x) { return std::stod(float_text(x)); };
    return nlohmann::ordered_json::array({number(v.x), number(v.y), number(v.z)});
  };
  r.line("bounding box = (" + text(lo) + ") .. (" + text(hi) + "), size (" + text(size) + "), centre (" + text(centre) +
         "), diagonal " + float_text(diagonal));
  r.json()["bounding_box"] = {{"min", json(lo)},
                              {"max", json(hi)},
                              {"size", json(size)},
                              {"centre", json(centre)},
                              {"diagonal", std::stod(float_text(diagonal))}};
}

void cage_section(Report& r, const CageAnalysis& a) {
  const Cage& c = a.cage;
  const Topology& t = a.topology;
  r.json()["file"] = c.name;
  r.line("Cage: " + c.name);
  r.count("vertices", "vertex count", t.vertex_count());
  r.count("edges", "edge count", t.edge_count());
  r.count("faces", "face count", t.face_count());
  int holes = 0;
  for (int f = 0; f < t.face_count(); ++f) holes += t.is_hole(f);
  r.count("holes", "hole count", holes);
  int creased = 0;
  for (int e = 0; e < t.edge_count(); ++e) creased += t.edge_sharpness(e) > 0;
  int cornered = 0;
  for (int v = 0; v < t.vertex_count(); ++v) cornered += t.corner_sharpness(v) > 0;
  r.count("creases", "creased edge count", creased);
  r.count("corners", "corner vertex count", cornered);
  r.json()["has_uvs"] = c.has_uvs();
  const auto seams = uv_seam_edges(c, t);
  r.line(std::string("uvs = ") + (c.has_uvs() ? std::to_string(c.uvs.size()) + " coordinates" : "none"));
  r.count("uv_seam_edges", "uv seam edge count", std::count(seams.begin(), seams.end(), true));
  r.count("isolated_vertices", "isolated vertex count", static_cast<long long>(t.isolated_vertices().size()));
  bounding_box_section(r, c);
  if (!c.positions.empty()) {
    const UpAxisAdvice up = up_axis_advice(c.name, c);
    r.line(std::string("up = ") + (up.axis == 2 ? "+z" : "+y") + " (" + up.reason + ")" +
           (up.axis == 2 ? ": render with --camera-up 0,0,1" : ""));
    r.json()["up"] = {{"axis", up.axis == 2 ? "+z" : "+y"},
                      {"reason", up.reason},
                      {"camera_up", up.axis == 2 ? nlohmann::ordered_json::array({0, 0, 1})
                                                 : nlohmann::ordered_json::array({0, 1, 0})}};
  }

  std::map<int, int> valences;
  int max_valence = 0, boundary_vertices = 0;
  for (int v = 0; v < t.vertex_count(); ++v) {
    if (t.is_isolated(v)) continue;
    ++valences[t.valence(v)];
    max_valence = std::max(max_valence, t.valence(v));
    boundary_vertices += t.is_boundary_vertex(v);
  }
  r.count("boundary_vertices", "boundary vertex count", boundary_vertices);
  r.count("max_valence", "max valence", max_valence);
  r.line("Valences (vertices used by faces):");
  auto& hist = r.json()["valence_histogram"] = nlohmann::ordered_json::array();
  for (const auto& [valence, n] : valences) {
    r.line("- " + std::to_string(valence) + " : " + std::to_string(n));
    hist.push_back({{"valence", valence}, {"count", n}});
  }
}

void patch_section(Report& r, const CageAnalysis& a) {
  const CombinationStats& s = a.combinations.stats;
  r.line("");
  r.line("Patch Configuration Info:");
  r.count("patches", "patch count", s.patches);
  r.count("triangles", "triangle count", s.triangles);
  r.count("quads", "quad count", s.quads);
  r.count("polygons", "polygon count", s.polygons);
  r.count("regular_patches", "regular patch count", s.regular);
  r.count("boundary_patches", "boundary patch count", s.boundary);
  r.count("regular_boundary_patches", "regular boundary patch count", s.regular_boundary);
  r.count("combinations", "patch configuration count", static_cast<long long>(a.combinations.combinations.size()));

  // Most frequent first; ties in order of first appearance, so the output is deterministic.
  std::vector<const Combination*> sorted;
  for (const Combination& c : a.combinations.combinations) sorted.push_back(&c);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Combination* x, const Combination* y) { return x->count > y->count; });
  auto& hist = r.json()["combination_histogram"] = nlohmann::ordered_json::array();
  for (const bool boundary : {false, true}) {
    r.line("");
    r.line(boundary ? "Boundary Patches:" : "Interior Patches:");
    for (const Combination* c : sorted)
      if (c->boundary == boundary) r.line("- " + c->text + " : " + std::to_string(c->count));
  }
  static constexpr const char* kClass[] = {"hole", "regular", "regular_boundary", "boundary", "irregular"};
  for (const Combination* c : sorted) {
    const std::vector<int> sample(c->faces.begin(),
                                  c->faces.begin() + std::min<std::ptrdiff_t>(8, std::ssize(c->faces)));
    hist.push_back({{"key", c->text},
                    {"count", c->count},
                    {"face_size", c->face_size},
                    {"boundary", c->boundary},
                    {"class", kClass[static_cast<int>(c->patch_class)]},
                    {"faces_sample", sample}});
  }
}

void warnings_section(Report& r, const CageAnalysis& a) {
  std::vector<std::string> all = a.cage.warnings;
  all.insert(all.end(), a.topology.warnings().begin(), a.topology.warnings().end());
  r.json()["warnings"] = all;
  r.line("");
  r.line("Warnings: " + std::string(all.empty() ? "none" : ""));
  for (const std::string& w : all) r.line("- " + w);
}

// The tags as the topology resolved them (a crease on no edge is gone; a repeated tag keeps its last
// value): every creased edge, corner and hole with its sharpness.
void tags_section(Report& r, const CageAnalysis& a) {
  const Topology& t = a.topology;
  const auto sharpness_text = [](float s) { return s >= kSharpnessInfinite ? std::string("infinite") : float_text(s); };
  constexpr std::size_t kListed = 20;  // lines per kind in the text; the JSON lists all
  auto& tags = r.json()["tags"] = nlohmann::ordered_json::object();
  r.line("");
  r.line("Tags (exact honours all; acc, gregory and bspline those of sharpness 1 and above; pn and flat none):");
  auto& creases = tags["creases"] = nlohmann::ordered_json::array();
  std::vector<std::string> lines;
  for (int e = 0; e < t.edge_count(); ++e) {
    const float s = t.edge_sharpness(e);
    if (!(s > 0.0f)) continue;
    const int h = t.edge_half_edges(e)[0], v0 = t.origin(h), v1 = t.destination(h);
    creases.push_back({{"vertices", {v0, v1}}, {"sharpness", std::stod(float_text(s))}});
    lines.push_back("- crease " + std::to_string(v0) + " " + std::to_string(v1) + " sharpness " + sharpness_text(s));
  }
  auto& corners = tags["corners"] = nlohmann::ordered_json::array();
  for (int v = 0; v < t.vertex_count(); ++v) {
    const float s = t.corner_sharpness(v);
    if (!(s > 0.0f)) continue;
    corners.push_back({{"vertex", v}, {"sharpness", std::stod(float_text(s))}});
    lines.push_back("- corner " + std::to_string(v) + " sharpness " + sharpness_text(s));
  }
  auto& holes = tags["holes"] = nlohmann::ordered_json::array();
  for (int f = 0; f < t.face_count(); ++f)
    if (t.is_hole(f)) {
      holes.push_back(f);
      lines.push_back("- hole: face " + std::to_string(f));
    }
  if (lines.empty()) r.line("- none");
  for (std::size_t i = 0; i < std::min(lines.size(), kListed); ++i) r.line(lines[i]);
  if (lines.size() > kListed) r.line("- ... " + std::to_string(lines.size() - kListed) + " more (--json lists all)");
}

// Non-manifold places, each drawn by OpenSubdiv's rules (shaders_cpp/cage/non_manifold.h); vertex indices
// are the file's.
void non_manifold_section(Report& r, const CageAnalysis& a) {
  const Cage& c = a.cage;
  constexpr std::size_t kListed = 20;
  r.json()["non_manifold"] = c.non_manifold;
  int copies = 0;  // vertices added by the split
  for (int v = 0; v < c.vertex_count(); ++v) copies += c.source_vertex(v) != v;
  r.json()["vertex_copies"] = copies;
  if (c.non_manifold.empty()) return;
  r.line("");
  r.line("Non-manifold places (drawn as OpenSubdiv draws them; " + std::to_string(copies) + " vertex copies):");
  for (std::size_t i = 0; i < std::min(c.non_manifold.size(), kListed); ++i) r.line("- " + c.non_manifold[i]);
  if (c.non_manifold.size() > kListed)
    r.line("- ... " + std::to_string(c.non_manifold.size() - kListed) + " more (--json lists all)");
}

void memory_section(Report& r, const CageAnalysis& a) {
  if (!a.memory) return;
  r.line("");
  std::string text = memory_text(*a.memory);
  text.pop_back();  // its last line's newline: r.line() ends the line
  r.line(text);
  r.json()["memory"] = memory_json(*a.memory);
}

using Section = void (*)(Report&, const CageAnalysis&);
constexpr Section kSections[] = {cage_section,   patch_section,  tags_section, non_manifold_section,
                                 memory_section, warnings_section};

int run_analyze(const AnalyzeOptions& o) {
  if (!o.memory.enabled && !(o.memory == MemoryOptions{}))
    throw UsageError("--displacement, --levels, --measure and the other memory-table options need --memory");
  std::optional<CageAnalysis> a;
  try {
    Cage cage = load_cage(o.cage, gltf_selection(o.cage, o.asset));
    Topology topology(cage);
    TopologyCombinations combinations = analyze_combinations(topology);
    a.emplace(CageAnalysis{std::move(cage), std::move(topology), std::move(combinations), std::nullopt});
  } catch (const CageError& e) {
    throw InputError(e.what());
  }
  if (o.memory.enabled) a->memory = analyze_memory(o.cage, a->cage, a->topology, o.memory);
  log_info("analyze: " + o.cage + ": " + std::to_string(a->topology.face_count()) + " faces");
  Report report;
  for (Section s : kSections) s(report, *a);
  if (o.json)
    std::cout << report.json().dump(2) << "\n";
  else
    std::cout << report.text();
  return kExitOk;
}

}  // namespace

Runner add_analyze_command(CLI::App& app) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* cmd =
      app.add_subcommand("analyze", "Describe a control cage (OBJ): topology, tags, UVs, patch combinations");
  cmd->add_option("cage", o->cage, "the cage: OBJ (OpenSubdiv tags accepted) or glTF (.gltf, .glb)")->required();
  add_asset_options(*cmd, o->asset, false);
  cmd->add_flag("--json", o->json, "print one JSON object instead of text");
  add_memory_options(*cmd, o->memory);
  return [o]() { return run_analyze(*o); };
}

}  // namespace tessera::cli
