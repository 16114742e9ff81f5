#include "statistics.h"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace tessera {

PipelineStatistics& PipelineStatistics::operator+=(const PipelineStatistics& o) {
  IAVertices += o.IAVertices;
  IAPrimitives += o.IAPrimitives;
  VSInvocations += o.VSInvocations;
  GSInvocations += o.GSInvocations;
  GSPrimitives += o.GSPrimitives;
  CInvocations += o.CInvocations;
  CPrimitives += o.CPrimitives;
  PSInvocations += o.PSInvocations;
  HSInvocations += o.HSInvocations;
  DSInvocations += o.DSInvocations;
  return *this;
}

StageTimes& StageTimes::operator+=(const StageTimes& o) {
  ia_vs += o.ia_vs;
  hs += o.hs;
  tessellator += o.tessellator;
  ds += o.ds;
  setup += o.setup;
  raster += o.raster;
  wall += o.wall;
  return *this;
}

std::string to_json(const PipelineStatistics& s) {
  std::ostringstream o;
  o << "{\"IAVertices\": " << s.IAVertices << ", \"IAPrimitives\": " << s.IAPrimitives
    << ", \"VSInvocations\": " << s.VSInvocations << ", \"GSInvocations\": " << s.GSInvocations
    << ", \"GSPrimitives\": " << s.GSPrimitives << ", \"CInvocations\": " << s.CInvocations
    << ", \"CPrimitives\": " << s.CPrimitives << ", \"PSInvocations\": " << s.PSInvocations
    << ", \"HSInvocations\": " << s.HSInvocations << ", \"DSInvocations\": " << s.DSInvocations << "}";
  return o.str();
}

std::string to_json(const StageTimes& t) {
  char buf[384];
  std::snprintf(buf, sizeof buf,
                "{\"ia_vs_s\": %.6f, \"hs_s\": %.6f, \"tessellator_s\": %.6f, \"ds_s\": %.6f, \"setup_s\": %.6f, "
                "\"raster_s\": %.6f, \"wall_s\": %.6f}",
                t.ia_vs, t.hs, t.tessellator, t.ds, t.setup, t.raster, t.wall);
  return buf;
}

std::string to_json(const MemoryStats& m) {
  std::ostringstream o;
  o << "{\"geometry_peak_bytes\": " << m.geometry_peak_bytes << ", \"framebuffer_bytes\": " << m.framebuffer_bytes
    << ", \"pattern_cache_bytes\": " << m.pattern_cache_bytes << ", \"chunks\": " << m.chunks
    << ", \"pattern_cache_hits\": " << m.pattern_cache_hits << ", \"pattern_cache_misses\": " << m.pattern_cache_misses
    << "}";
  return o.str();
}

std::uint64_t peak_rss_bytes() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream fields(line.substr(6));
      std::uint64_t kb = 0;
      fields >> kb;
      return kb * 1024;
    }
  }
  return 0;
}

}  // namespace tessera
