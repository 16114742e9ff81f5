// Curved PN triangles (Vlachos, Peters, Boyd, Mitchell, "Curved PN Triangles", I3D 2001) and their
// quad analogue: a patch built from its corners' positions and normals only, no neighbours.
//
// PN triangle (corners P0, P1, P2 with unit normals N0, N1, N2; the paper's b300, b030, b003):
// - edge point near P_i toward P_j: b_ij = (2 P_i + P_j - w_ij N_i) / 3, w_ij = (P_j - P_i) . N_i
//   (the third of the edge projected into P_i's tangent plane);
// - centre: b111 = E + (E - V) / 2, E the mean of the six edge points, V the mean of the corners
//   (this choice reproduces quadratics);
// - normals: a separate quadratic field, n200 = N0 ... and at the edge midpoints
//   n_ij = normalize(N_i + N_j - v_ij (P_j - P_i)), v_ij = 2 (P_j - P_i) . (N_i + N_j) / |P_j - P_i|^2
//   (N_i + N_j reflected in the plane normal to the edge).
// PN quad (this project's analogue for quad faces): a bicubic Bezier patch whose four boundary curves
// are built by the same edge rule (so a quad and a triangle sharing an edge share the curve bit for
// bit), and whose four interior points are those of the bilinearly blended Coons patch of the
// boundary (discrete form, exact for cubic boundaries):
//   b_ij = (1 - i/3) b_0j + (i/3) b_3j + (1 - j/3) b_i0 + (j/3) b_i3 - bilinear(b00, b30, b03, b33)(i/3, j/3).
// Like the triangle's centre rule it reproduces quadratics (it reproduces every surface
// f(u) + g(v) + bilinear), and a planar quad with equal normals gives the bilinear patch. Normals: the
// biquadratic field with the triangle's corner and edge coefficients and the Coons centre
// n11 = (n10 + n01 + n21 + n12) / 2 - (n00 + n20 + n02 + n22) / 4.
//
// Determinism: computed in double from the float inputs, rounded once. An edge's points and normal
// coefficient depend on that edge's two corners only, by expressions that give the same bits from
// either end (n_ij = n_ji exactly: swapping the ends negates v_ij and P_j - P_i exactly).
#pragma once

#include <array>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "shaders_cpp/cage/cage.h"

namespace tessera {

class Topology;

struct PNTriangle {
  std::array<glm::vec3, 10> b;  // b[tri_index(3, j, k)] (patch_eval.h): w^i u^j v^k, corner 0 at w = 1
  std::array<glm::vec3, 6> n;   // n[tri_index(2, j, k)]
};
struct PNQuad {
  std::array<glm::vec3, 16> b;  // b[i + 4 j], corners 0..3 at (0,0), (1,0), (1,1), (0,1)
  std::array<glm::vec3, 9> n;   // n[i + 3 j]
};

PNTriangle pn_triangle(std::span<const glm::vec3, 3> p, std::span<const glm::vec3, 3> n);
PNQuad pn_quad(std::span<const glm::vec3, 4> p, std::span<const glm::vec3, 4> n);

// Per-vertex unit normals: the sum of the area vectors (half the sum of (p_k - p_0) x (p_k+1 - p_0)) of the
// non-hole faces around each vertex, accumulated in double in face order, normalized and rounded once.
// A vertex without faces (or with cancelling ones) gets the zero vector. `positions` are the cage's, or
// a pose of them (one per cage vertex); the faces are the cage's.
std::vector<glm::vec3> vertex_normals(const Cage& cage, std::span<const glm::vec3> positions, const Topology& topology);

}  // namespace tessera
