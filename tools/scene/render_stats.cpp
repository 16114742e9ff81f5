#include "tools/scene/render_stats.h"

#include <array>
#include <cmath>

#include "tools/scene/common.h"

namespace tessera::scene {
namespace {

Json factors_json(const std::array<float, 4>& edge, int edges, const std::array<float, 2>& inside, int insides) {
  Json e = Json::array(), i = Json::array();
  for (int k = 0; k < edges; ++k) e.push_back(json_float(edge[std::size_t(k)]));
  for (int k = 0; k < insides; ++k) i.push_back(json_float(inside[std::size_t(k)]));
  return {{"edge", e}, {"inside", i}};
}

Json segments_json(const std::array<int, 4>& edge, int edges, const std::array<int, 2>& inside, int insides) {
  Json e = Json::array(), i = Json::array();
  for (int k = 0; k < edges; ++k) e.push_back(edge[std::size_t(k)]);
  for (int k = 0; k < insides; ++k) i.push_back(inside[std::size_t(k)]);
  return {{"edge", e}, {"inside", i}};
}

// Histogram bins [2^k, 2^(k+1)) from 2^lo to 2^hi, with an underflow and an overflow bin.
struct Log2Histogram {
  int lo, hi;
  std::vector<std::uint64_t> counts;
  Log2Histogram(int l, int h) : lo(l), hi(h), counts(std::size_t(h - l + 2), 0) {}
  void add(double x) {
    const int k = x > 0.0 ? int(std::floor(std::log2(x))) : lo - 1;
    counts[std::size_t(std::clamp(k, lo - 1, hi) - (lo - 1))] += 1;
  }
  Json json() const {
    Json bins = Json::array();
    for (std::size_t i = 0; i < counts.size(); ++i) {
      const int k = int(i) + lo - 1;
      Json b = {{"from", k < lo ? 0.0 : std::exp2(double(k))},
                {"to", k >= hi ? Json(nullptr) : Json(std::exp2(double(k + 1)))},
                {"count", counts[i]}};
      bins.push_back(b);
    }
    return bins;
  }
};

}  // namespace

Json patch_row(const PatchInfo& p, std::size_t id) {
  const int edges = p.tri ? 3 : 4, insides = p.tri ? 1 : 2;
  return {{"domain", p.tri ? "tri" : "quad"},
          {"id", id},
          {"face", p.face},
          {"sub", p.sub},
          {"kind", to_string(p.kind)},
          {"type", to_string(p.type)},
          {"combination", p.combination},
          {"raw", factors_json(p.raw.edge, edges, p.raw.inside, insides)},
          {"processed", factors_json(p.edge_processed, edges, p.inside_processed, insides)},
          {"segments", segments_json(p.edge_segments, edges, p.inside_segments, insides)},
          {"triangles", p.triangles},
          {"screen_pixels", std::isfinite(p.screen_pixels) ? Json(json_float(p.screen_pixels)) : Json(nullptr)},
          {"culled", p.culled       ? Json("frustum")
                     : p.faces_away ? Json("backface")
                                    : Json(nullptr)}};
}

void add_patch_statistics(Json& stats, Device& device, const ViewInputs& in, const PatchTables& tables,
                          const LodResult& lod) {
  Json rows = Json::array();
  std::uint64_t triangles = 0, drawn = 0, culled = 0, away = 0, patches = 0;
  std::array<std::uint64_t, 64> factor_counts{};  // edge factors by [k, k+1), k = 1..63, 64 in the last
  for (const auto* t : {&tables.quads, &tables.tris}) {
    for (std::size_t id = 0; id < t->size(); ++id) {
      const PatchInfo& p = (*t)[id];
      const int edges = p.tri ? 3 : 4;
      ++patches;
      triangles += p.triangles;
      drawn += p.faces_away ? 0 : p.triangles;
      culled += p.culled ? 1 : 0;
      away += p.faces_away ? 1 : 0;
      for (int k = 0; k < edges && !p.culled; ++k) {
        const float f = p.raw.edge[std::size_t(k)];
        const int bin = std::isfinite(f) ? std::clamp(int(std::floor(f)), 1, 64) - 1 : 0;
        ++factor_counts[std::size_t(bin)];
      }
      rows.push_back(patch_row(p, id));
    }
  }
  Json factor_bins = Json::array();
  for (int k = 0; k < 64; ++k)
    if (factor_counts[std::size_t(k)] > 0)
      factor_bins.push_back({{"from", k + 1}, {"to", k + 2}, {"count", factor_counts[std::size_t(k)]}});

  // The exact screen area of every triangle the draw makes, in pixels.
  const glm::mat4& vp = in.view.camera.view_projection;
  const glm::vec2 half(0.5f * float(in.view.width), 0.5f * float(in.view.height));
  Log2Histogram areas(-8, 16);
  std::uint64_t streamed = 0, behind = 0;
  auto sink = [&](const auto& out, const PatchGroup&) {
    for (std::size_t i = 0; i + 2 < out.indices.size(); i += 3) {
      ++streamed;
      std::array<glm::dvec2, 3> s;
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        const glm::vec4 c = vp * glm::vec4(out.points[out.indices[i + std::size_t(k)]].position, 1.0f);
        if (!(c.w > 0.0f)) ok = false;
        s[std::size_t(k)] = glm::dvec2(double(c.x) / c.w * half.x, double(c.y) / c.w * half.y);
      }
      if (!ok) {
        ++behind;
        continue;
      }
      const glm::dvec2 e1 = s[1] - s[0], e2 = s[2] - s[0];
      areas.add(0.5 * std::abs(e1.x * e2.y - e1.y * e2.x));
    }
  };
  const DrawResult r = stream_surface(device, in.model, in.displacement, in.factors, in.cull, in.partitioning, sink);
  if (!r.ok()) throw InputError(in.model.cage.name + ": " + r.error);

  stats["lod"] = {{"mode", to_string(lod.settings.mode)},
                  {"edge_pixels", json_float(lod.settings.edge_pixels)},
                  {"lod_distance", json_float(lod.settings.lod_distance)},
                  {"displacement_bound", json_float(lod.settings.bound)},
                  {"cull", to_string(lod.cull)}};
  stats["totals"] = {{"patches", patches},
                     {"patches_culled", culled},
                     {"patches_back_culled", away},
                     {"triangles", triangles},
                     {"triangles_drawn", drawn},
                     {"triangles_streamed", streamed},
                     {"triangles_behind_eye", behind}};
  stats["histograms"] = {{"edge_factors", factor_bins}, {"triangle_area_pixels", areas.json()}};
  stats["patches"] = rows;
}

}  // namespace tessera::scene
