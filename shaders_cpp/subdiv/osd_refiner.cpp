// Far::TopologyRefiner from a Cage. OpenSubdiv reports most topology errors through a global
// callback (and some not at all: out-of-range indices are undefined behaviour), so everything it
// cannot take is checked first and reported as one CageError line: by the topology's validation
// (topology.h), and here only what is OpenSubdiv's own (face size, valence).
#include "shaders_cpp/subdiv/osd_refiner.h"

#include <opensubdiv/bfr/limits.h>
#include <opensubdiv/far/error.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "shaders_cpp/cage/one_line.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/far_patches.h"
#include "shaders_cpp/subdiv/limit_surface.h"

namespace tessera::subdiv {

using osd::Far::TopologyDescriptor;
using osd::Far::TopologyRefiner;
using osd::Far::TopologyRefinerFactory;
using osd::Sdc::Options;

std::string cage_label(const Cage& cage) { return cage.name.empty() ? std::string("cage") : cage.name; }

Options sdc_options(const CageTags& tags) {
  Options o;
  switch (tags.boundary) {
    case BoundaryInterpolation::none: o.SetVtxBoundaryInterpolation(Options::VTX_BOUNDARY_NONE); break;
    case BoundaryInterpolation::edge_only: o.SetVtxBoundaryInterpolation(Options::VTX_BOUNDARY_EDGE_ONLY); break;
    case BoundaryInterpolation::edge_and_corner:
      o.SetVtxBoundaryInterpolation(Options::VTX_BOUNDARY_EDGE_AND_CORNER);
      break;
  }
  o.SetCreasingMethod(tags.crease_method == CreaseMethod::chaikin ? Options::CREASE_CHAIKIN : Options::CREASE_UNIFORM);
  o.SetTriangleSubdivision(tags.smooth_triangles ? Options::TRI_SUB_SMOOTH : Options::TRI_SUB_CATMARK);
  // Only vertex data is evaluated; face-varying options do not affect it.
  return o;
}

namespace {

// OpenSubdiv prints its warnings and errors with printf, to stdout, where they would mix with a
// command's results (--json): they go to stderr instead, one line each, prefixed.
void osd_warning(const char* message) {
  std::fprintf(stderr, "OpenSubdiv: warning: %s\n", one_line_message(message).c_str());
}
void osd_error(osd::Far::ErrorType, const char* message) {
  std::fprintf(stderr, "OpenSubdiv: error: %s\n", one_line_message(message).c_str());
}

void check_osd_limits(const Cage& cage, const Topology& topology) {
  const std::string name = cage_label(cage);
  const int max_face = osd::Bfr::Limits::MaxFaceSize(), max_valence = osd::Bfr::Limits::MaxValence();
  for (int f = 0; f < topology.face_count(); ++f)
    if (topology.face_size(f) > max_face)
      throw CageError(name + ": face " + std::to_string(f) + " has " + std::to_string(topology.face_size(f)) +
                      " vertices; OpenSubdiv takes at most " + std::to_string(max_face));
  // Any valence OpenSubdiv takes; the cost above kCostlyExactValence is make_subd_model's warning.
  for (int v = 0; v < topology.vertex_count(); ++v)
    if (topology.valence(v) > max_valence)
      throw CageError(name + ": vertex " + std::to_string(v) + " has valence " + std::to_string(topology.valence(v)) +
                      "; OpenSubdiv takes at most " + std::to_string(max_valence));
}

}  // namespace

void route_osd_messages() {
  static std::once_flag once;
  std::call_once(once, [] {
    osd::Far::SetWarningCallback(osd_warning);
    osd::Far::SetErrorCallback(osd_error);
  });
}

std::unique_ptr<TopologyRefiner> build_osd_refiner(const Cage& cage, std::vector<int>* far_faces) {
  route_osd_messages();
  const Topology topology(cage);  // validate_cage: everything but OpenSubdiv's own limits
  check_osd_limits(cage, topology);
  if (far_faces) *far_faces = needs_far_patches(topology);
  // Sharpness as the topology resolved it (creases on vertex pairs that are no edge are ignored there,
  // a tag repeated keeps its last value, as OpenSubdiv does); zero sharpness is the default anyway.
  std::vector<int> crease_pairs, corner_verts;
  std::vector<float> crease_weights, corner_weights;
  for (int e = 0; e < topology.edge_count(); ++e)
    if (topology.edge_sharpness(e) > 0.0f) {
      const int h = topology.edge_half_edges(e)[0];
      crease_pairs.push_back(topology.origin(h));
      crease_pairs.push_back(topology.destination(h));
      crease_weights.push_back(topology.edge_sharpness(e));
    }
  for (int v = 0; v < topology.vertex_count(); ++v)
    if (topology.corner_sharpness(v) > 0.0f) {
      corner_verts.push_back(v);
      corner_weights.push_back(topology.corner_sharpness(v));
    }
  // The descriptor reads faces as consecutive runs of vertex indices, which validate_cage guarantees.
  const std::vector<int>& verts = cage.face_vertices;

  TopologyDescriptor d;
  d.numVertices = cage.vertex_count();
  d.numFaces = cage.face_count();
  d.numVertsPerFace = cage.face_sizes.data();
  d.vertIndicesPerFace = verts.data();
  d.numCreases = int(crease_weights.size());
  d.creaseVertexIndexPairs = crease_pairs.data();
  d.creaseWeights = crease_weights.data();
  d.numCorners = int(corner_weights.size());
  d.cornerVertexIndices = corner_verts.data();
  d.cornerWeights = corner_weights.data();
  d.numHoles = int(cage.tags.holes.size());
  d.holeIndices = cage.tags.holes.data();
  d.isLeftHanded = false;  // see sdc_options()

  TopologyRefinerFactory<TopologyDescriptor>::Options options(osd::Sdc::SCHEME_CATMARK, sdc_options(cage.tags));
  std::unique_ptr<TopologyRefiner> refiner(TopologyRefinerFactory<TopologyDescriptor>::Create(d, options));
  if (!refiner) throw CageError(cage_label(cage) + ": OpenSubdiv rejected the topology");
  return refiner;
}

}  // namespace tessera::subdiv
