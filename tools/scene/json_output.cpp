#include "tools/scene/json_output.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

#include "tools/scene/common.h"

namespace tessera::scene {
namespace {

// The shortest text that reads back to the same number, without nlohmann's ".0" on integral values
// (a factor of 7 prints as 7, as the commands always printed it); JSON has no NaN or infinity, so
// those print as null, as nlohmann prints them.
template <class F>
void write_number(std::string& out, F x) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, r.ptr);
}

// nlohmann's dump() has no separator option: its compact form has no spaces and its indented form
// one value per line, neither the commands' style, so the containers are walked here; strings,
// integers and booleans are nlohmann's text.
template <class J>
void write(std::string& out, const J& v) {
  if (v.is_object()) {
    out += '{';
    bool first = true;
    for (const auto& [key, item] : v.items()) {
      if (!first) out += ", ";
      first = false;
      out += J(key).dump();
      out += ": ";
      write(out, item);
    }
    out += '}';
  } else if (v.is_array()) {
    out += '[';
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) out += ", ";
      write(out, v[i]);
    }
    out += ']';
  } else if (v.is_number_float()) {
    write_number(out, v.template get<typename J::number_float_t>());
  } else {
    out += v.dump();
  }
}

}  // namespace

double json_float(float x) { return std::strtod(float_text(x).c_str(), nullptr); }

Json json_vec3(glm::vec3 v) { return Json::array({json_float(v.x), json_float(v.y), json_float(v.z)}); }

std::string json_text(const Json& value) {
  std::string out;
  write(out, value);
  return out;
}

std::string json_text(const FloatJson& value) {
  std::string out;
  write(out, value);
  return out;
}

Json to_json(const PipelineStatistics& s) {
  return {{"IAVertices", s.IAVertices},       {"IAPrimitives", s.IAPrimitives},   {"VSInvocations", s.VSInvocations},
          {"GSInvocations", s.GSInvocations}, {"GSPrimitives", s.GSPrimitives},   {"CInvocations", s.CInvocations},
          {"CPrimitives", s.CPrimitives},     {"PSInvocations", s.PSInvocations}, {"HSInvocations", s.HSInvocations},
          {"DSInvocations", s.DSInvocations}};
}

Json to_json(const StageTimes& t) {
  return {{"ia_vs_s", t.ia_vs}, {"hs_s", t.hs},       {"tessellator_s", t.tessellator},
          {"ds_s", t.ds},       {"setup_s", t.setup}, {"raster_s", t.raster},
          {"wall_s", t.wall}};
}

Json to_json(const MemoryStats& m) {
  return {{"geometry_peak_bytes", m.geometry_peak_bytes},
          {"framebuffer_bytes", m.framebuffer_bytes},
          {"pattern_cache_bytes", m.pattern_cache_bytes},
          {"chunks", m.chunks},
          {"tiles_split", m.tiles_split},
          {"pattern_cache_hits", m.pattern_cache_hits},
          {"pattern_cache_misses", m.pattern_cache_misses}};
}

Json to_json(const verify::WeldReport& w) {
  return {{"watertight", w.watertight()},
          {"closed_manifold", w.closed_manifold()},
          {"triangles", w.triangles},
          {"welded_vertices", w.welded_vertices},
          {"edges", w.edges},
          {"open_edges", w.open_edges},
          {"border_edges", w.border_edges},
          {"crack_edges", w.crack_edges},
          {"nonmanifold_edges", w.nonmanifold_edges},
          {"cage_nonmanifold_edges", w.cage_nonmanifold_edges},
          {"degenerate_triangles", w.degenerate_triangles}};
}

}  // namespace tessera::scene
