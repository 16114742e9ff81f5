// The faces whose per-face patch strays from the limit surface: what `gregory`, `bspline` and `acc` find
// when a cage is loaded, so that build_patches fits those faces to the limit (`refit`, fitted_faces.h)
// rather than draw a patch that folds over or bulges away from the surface OpenSubdiv defines.
//
// The masks (Loop, Schaefer, Ni and Castano's Gregory points) only approximate the limit near an
// extraordinary vertex: next to a valence-2 vertex, a cusp, a pole whose faces are nearly collapsed or
// two faces back to back, the approximation can turn the surface over (a black slit in a picture) or
// stand a large fraction of the face away. Such a face is found by drawing it: its patch, through the
// model's own hull and domain shaders, at its corners and a grid of interior domain points, against the limit's
// normal there (Bfr's stencils over the cage, limit_fit.h). A face strays when a sample's normal is more than 90
// degrees from a defined limit normal (folded). Distance alone does not make a face strayed: a fitted
// face's points are fitted in least squares, not under the G1 condition the masks meet, so refitting a
// face that is merely far (the pyramid's triangles, 4.1e-2 of the diagonal) would trade that distance for
// a crease in the shading along its edges (0.4-0.7 rad on the pyramid).
//
// Contract
// - Only the triangles and quads of the per-face schemes are looked at, and of those only faces that are
//   not regular (a regular quad's patch is its B-spline patch, the limit itself). A face fitted already
//   (a tagged corner, fits_limit) may stray too: refit, all its edges are fitted, not only those at a
//   tag. n-gon fans and the other schemes give no faces.
// - The rest pose: a fitted face is a stencil, so it follows any pose.
// - Deterministic; the cost is one Bfr surface per irregular face (the frog: docs/reference-renders.md, "Faces that
//   fold are fitted too").
#pragma once

#include <vector>

#include "shaders_cpp/render/subd_model.h"

namespace tessera {

struct StrayedFaces {
  std::vector<char> faces;  // per cage face: 1 when strayed (empty when no face was looked at)
  int count() const;
};

StrayedFaces find_strayed_faces(const SubdModel& model);

}  // namespace tessera
