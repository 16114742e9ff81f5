// Far::TopologyRefiner from a Cage. OpenSubdiv reports most topology errors through a global
// callback (and some not at all: out-of-range indices are undefined behaviour), so everything it
// cannot take is checked here first and reported as one CageError line.
#include "osd_refiner.h"

#include <opensubdiv/bfr/limits.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

namespace tessera::osd_detail {

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

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(a < b ? a : b), hi = static_cast<std::uint32_t>(a < b ? b : a);
  return (std::uint64_t(lo) << 32) | hi;
}

}  // namespace

void validate_for_osd(const Cage& cage) {
  const std::string name = cage_label(cage);
  const auto fail = [&](const std::string& what) { throw CageError(name + ": " + what); };
  const int nv = cage.vertex_count(), nf = cage.face_count();
  if (cage.face_offsets.size() != cage.face_sizes.size())
    fail("face_offsets has " + std::to_string(cage.face_offsets.size()) + " entries for " + std::to_string(nf) + " faces");
  for (int v = 0; v < nv; ++v) {
    const glm::vec3 p = cage.positions[std::size_t(v)];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) fail("vertex " + std::to_string(v) + " is not finite");
  }
  const int max_face = osd::Bfr::Limits::MaxFaceSize();
  std::unordered_set<std::uint64_t> edges;
  std::vector<int> valence(std::size_t(nv), 0);
  for (int f = 0; f < nf; ++f) {
    const int n = cage.face_sizes[std::size_t(f)], off = cage.face_offsets[std::size_t(f)];
    if (n < 3 || n > max_face) fail("face " + std::to_string(f) + " has " + std::to_string(n) + " vertices (3.." + std::to_string(max_face) + " allowed)");
    if (off < 0 || std::size_t(off) + std::size_t(n) > cage.face_vertices.size())
      fail("face " + std::to_string(f) + " indexes past the end of face_vertices");
    for (int k = 0; k < n; ++k) {
      const int v = cage.face_vertex(f, k);
      if (v < 0 || v >= nv) fail("face " + std::to_string(f) + " has vertex " + std::to_string(v) + " out of range (" + std::to_string(nv) + " vertices)");
      if (++valence[std::size_t(v)] > osd::Bfr::Limits::MaxValence()) fail("vertex " + std::to_string(v) + " has too many faces for OpenSubdiv");
      edges.insert(edge_key(v, cage.face_vertex(f, (k + 1) % n)));
    }
  }
  for (std::size_t i = 0; i < cage.tags.creases.size(); ++i) {
    const Crease& c = cage.tags.creases[i];
    const std::string what = "crease " + std::to_string(i) + " (vertices " + std::to_string(c.v0) + "-" + std::to_string(c.v1) + ")";
    if (c.v0 < 0 || c.v0 >= nv || c.v1 < 0 || c.v1 >= nv) fail(what + " has a vertex out of range");
    if (!std::isfinite(c.sharpness) || c.sharpness < 0) fail(what + " has sharpness " + std::to_string(c.sharpness));
    if (!edges.count(edge_key(c.v0, c.v1))) fail(what + " is not an edge of the cage");
  }
  for (std::size_t i = 0; i < cage.tags.corners.size(); ++i) {
    const Corner& c = cage.tags.corners[i];
    if (c.vertex < 0 || c.vertex >= nv) fail("corner " + std::to_string(i) + " has vertex " + std::to_string(c.vertex) + " out of range");
    if (!std::isfinite(c.sharpness) || c.sharpness < 0) fail("corner " + std::to_string(i) + " has sharpness " + std::to_string(c.sharpness));
  }
  for (std::size_t i = 0; i < cage.tags.holes.size(); ++i) {
    const int h = cage.tags.holes[i];
    if (h < 0 || h >= nf) fail("hole " + std::to_string(i) + " names face " + std::to_string(h) + " out of range");
  }
}

std::unique_ptr<TopologyRefiner> build_osd_refiner(const Cage& cage) {
  validate_for_osd(cage);
  std::vector<int> crease_pairs, corner_verts;
  std::vector<float> crease_weights, corner_weights;
  for (const Crease& c : cage.tags.creases) {
    crease_pairs.push_back(c.v0);
    crease_pairs.push_back(c.v1);
    crease_weights.push_back(c.sharpness);
  }
  for (const Corner& c : cage.tags.corners) {
    corner_verts.push_back(c.vertex);
    corner_weights.push_back(c.sharpness);
  }
  // The descriptor reads faces as consecutive runs of vertex indices; face_offsets may leave gaps
  // or reorder, so gather them.
  std::vector<int> verts;
  verts.reserve(cage.face_vertices.size());
  for (int f = 0; f < cage.face_count(); ++f)
    for (int k = 0; k < cage.face_sizes[std::size_t(f)]; ++k) verts.push_back(cage.face_vertex(f, k));

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

}  // namespace tessera::osd_detail
