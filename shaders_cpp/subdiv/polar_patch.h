// Polar configurations drawn without Catmull-Clark's ripple: the talk's "approximate polar subdivision"
// for gregory and bspline.
//
// A pole is an interior, untagged vertex of valence n >= kPolarMinValence whose faces are all triangles
// (P, Q_j, Q_j+1), each ring vertex Q_j of valence 4 and untagged, with a quad across every ring edge
// Q_j Q_j+1: the cap of a latitude-longitude mesh, an extruded tip (OpenSubdiv's catmark_pole8/64/360).
// Catmull-Clark's limit ripples around such a vertex, more the higher n (its subdominant eigenvalues
// split; a valence-32 sphere's largest curvature is nine times a valence-4 one's), and the Gregory
// triangles, which follow its face-point masks, ripple with it.
//
// Each triangle becomes one bicubic Bezier patch with its row at the pole collapsed (Myles, Karciauskas
// and Peters, "Pairs of bi-cubic surface constructions supporting polar connectivity", CAGD 2008: a
// singularly parameterised bicubic can stand for polar subdivision), s around the pole and t outward:
// - row 0: the pole's limit position (the Gregory corner point, shared by every sector);
// - row 1: a closed uniform cubic B-spline around the pole in its tangent plane. Its values at the
//   meridians are the Gregory edge points on the spokes, p + T_j / 3, which Loop and Schaefer's tangent
//   mask makes one pure harmonic in j, T_j = A cos(2 pi j / n) + B sin(2 pi j / n); its B-spline control
//   points are then p + T_j / (3 h), h = (2 + cos(2 pi / n)) / 3, and its sectors' inner Bezier points
//   follow. Only the first harmonic reaches the patches, which is what keeps the ripple out;
// - row 3: the ring edge's cubic, the Gregory edge points the quad across it shares (watertight);
// - row 2: at the spokes, the Gregory edge points on the spoke at Q_j (shared by the two sectors);
//   inside, the quad's inner row mirrored across the ring edge, 2 E - F, so the two patches join with
//   one tangent plane along it where the quad's face points do.
// Every boundary cubic is a Gregory edge (patch_eval.h's polar_triangle), so the mesh stays watertight
// to the bit under any factors. The surface leaves Catmull-Clark's limit near the pole by design.
#pragma once

#include <vector>

#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/subdiv/stencil.h"

namespace tessera {

// From valence 6 the polar patch is nearer the limit than the Gregory triangles on every measure
// (latitude-longitude spheres, `accuracy --factor 29`: valence 6 rms distance 1.0e-3 against 1.2e-3,
// largest curvature 6.8 against 10.1, the limit's 7.4); below it the Gregory triangles stay nearer
// (valence 4: rms 8.5e-4 against 1.2e-3) and the limit barely ripples.
inline constexpr int kPolarMinValence = 6;

// Per face: its pole vertex when the face is a triangle of a polar configuration, else -1.
std::vector<int> polar_poles(const Topology& t);

// The polar patch's 15 rows, in place, from a Gregory triangle's (gregory_triangle_stencils) whose
// corner 0 is the pole of valence `n`, and the Gregory rows of the quad across its edge 1 -> 2 from
// that quad's corner 0 (`quad`), in which the triangle's corner 2 is quad corner `a` and its corner 1
// quad corner a + 1.
void polar_triangle_rows(std::vector<Stencil>& rows, int n, const std::vector<Stencil>& quad, int a);

}  // namespace tessera
