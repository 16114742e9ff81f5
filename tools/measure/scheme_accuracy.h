// How far a scheme's drawn surface is from the exact Catmull-Clark limit surface, measured at the
// domain points the scheme actually produces (`tessera accuracy`).
//
// Distances are parametric (the scheme's point against the limit's point at the same face and domain
// location), an upper bound of the distance to the surface. Normal errors are angles between the two unit
// normals; on a crease a point shared by two faces carries its owner's normal (limit_surface.h), so it is
// measured against this face's and the owner's, the nearer. A sample whose error exceeds 10 degrees is
// asked whether the limit's normal is defined there: finite, and not turning by more than 30 degrees
// within 1/256 of the point inside its sub-patch. It is not on a crease line, at a cusp or at a degenerate
// vertex (valence 2, a collapsed edge), where a scheme's normal may point anywhere without a fold anyone
// sees. A sample more than 90 degrees off where the limit's normal is defined is folded: the surface
// turned over there.
// The ripple (curvature): along every edge of the tessellation, the normal curvature
// (n1 - n0) . (p1 - p0) / |p1 - p0|^2 of the scheme's points and normals against the limit's at the same
// domain points, the difference times the diagonal (a sphere's is about 3.5 whatever its size). The
// largest curvature of each surface on its own is reported too: around a vertex of high valence the
// limit itself ripples, so a large curvature error there is the limit's ripple as much as the scheme's.
//
// Contract: `reference` is the exact LimitSurface of the cage the model's vertex shader outputs (the
// posed cage), not an adaptive one. Deterministic for any thread count of `device`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shaders_cpp/render/subd_model.h"

namespace tessera::measure {

struct SchemeAccuracy {
  std::uint64_t samples = 0;
  double diagonal = 0.0;  // of the limit surface's bounding box
  double max_distance = 0.0, rms_distance = 0.0;
  double max_normal_degrees = 0.0, mean_normal_degrees = 0.0;
  double max_normal_degrees_defined = 0.0;  // over the samples whose limit normal is defined
  std::uint64_t undefined_normal_samples = 0, folded_samples = 0;
  std::vector<int> folded_faces;  // the cage faces with a folded sample, ascending
  int farthest_face = -1;         // the cage face of the largest distance
  // Per diagonal (see above).
  double max_curvature_error = 0.0, mean_curvature_error = 0.0, max_curvature_scheme = 0.0, max_curvature_limit = 0.0;
  std::string error;  // the draw's, when it failed (nothing else is set then)
  double max_relative() const { return diagonal > 0 ? max_distance / diagonal : max_distance; }
  double rms_relative() const { return diagonal > 0 ? rms_distance / diagonal : rms_distance; }
};

SchemeAccuracy measure_scheme_accuracy(Device& device, const SubdModel& model, const LimitSurface& reference,
                                       const SubdFactors& factors, ts::Partitioning partitioning);

}  // namespace tessera::measure
