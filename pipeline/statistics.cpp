#include "pipeline/statistics.h"

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
