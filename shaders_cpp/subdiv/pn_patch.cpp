#include "shaders_cpp/subdiv/pn_patch.h"

#include <cmath>

#include "shaders_cpp/cage/topology.h"

namespace tessera {

namespace {

using glm::dvec3;

// The PN edge point next to p toward q.
dvec3 edge_point(const dvec3& p, const dvec3& q, const dvec3& n) {
  const double w = glm::dot(q - p, n);
  return (2.0 * p + q - w * n) / 3.0;
}

// The PN normal coefficient at the middle of edge (p, q): symmetric in its ends to the bit.
dvec3 edge_normal(const dvec3& p, const dvec3& q, const dvec3& np, const dvec3& nq) {
  const dvec3 d = q - p;
  const double len2 = glm::dot(d, d);
  const dvec3 s = np + nq;
  const dvec3 m = len2 > 0.0 ? s - (2.0 * glm::dot(d, s) / len2) * d : s;
  const double len = glm::length(m);
  return len > 0.0 ? m / len : m;
}

}  // namespace

PNTriangle pn_triangle(std::span<const glm::vec3, 3> pf, std::span<const glm::vec3, 3> nf) {
  const dvec3 p[3] = {dvec3(pf[0]), dvec3(pf[1]), dvec3(pf[2])};
  const dvec3 n[3] = {dvec3(nf[0]), dvec3(nf[1]), dvec3(nf[2])};
  // Indices (j, k) of tri_index(3, j, k): corner 0 (0,0), corner 1 (3,0), corner 2 (0,3).
  const dvec3 b210 = edge_point(p[0], p[1], n[0]), b120 = edge_point(p[1], p[0], n[1]);
  const dvec3 b021 = edge_point(p[1], p[2], n[1]), b012 = edge_point(p[2], p[1], n[2]);
  const dvec3 b102 = edge_point(p[2], p[0], n[2]), b201 = edge_point(p[0], p[2], n[0]);
  const dvec3 e = (((b210 + b120) + (b021 + b012)) + (b102 + b201)) / 6.0;
  const dvec3 v = (p[0] + p[1] + p[2]) / 3.0;
  const dvec3 b111 = e + 0.5 * (e - v);
  PNTriangle t;
  // Rows in k (v power), j (u power) ascending: (0,0) (1,0) (2,0) (3,0) | (0,1) (1,1) (2,1) | (0,2) (1,2) | (0,3).
  const dvec3 b[10] = {p[0], b210, b120, p[1], b201, b111, b021, b102, b012, p[2]};
  for (int i = 0; i < 10; ++i) t.b[std::size_t(i)] = glm::vec3(b[i]);
  // (0,0) (1,0) (2,0) | (0,1) (1,1) | (0,2)
  const dvec3 m[6] = {n[0],
                      edge_normal(p[0], p[1], n[0], n[1]),
                      n[1],
                      edge_normal(p[2], p[0], n[2], n[0]),
                      edge_normal(p[1], p[2], n[1], n[2]),
                      n[2]};
  for (int i = 0; i < 6; ++i) t.n[std::size_t(i)] = glm::vec3(m[i]);
  return t;
}

PNQuad pn_quad(std::span<const glm::vec3, 4> pf, std::span<const glm::vec3, 4> nf) {
  const dvec3 p[4] = {dvec3(pf[0]), dvec3(pf[1]), dvec3(pf[2]), dvec3(pf[3])};
  const dvec3 n[4] = {dvec3(nf[0]), dvec3(nf[1]), dvec3(nf[2]), dvec3(nf[3])};
  std::array<dvec3, 16> b;
  auto at = [&](int i, int j) -> dvec3& { return b[std::size_t(i + 4 * j)]; };
  at(0, 0) = p[0], at(3, 0) = p[1], at(3, 3) = p[2], at(0, 3) = p[3];
  at(1, 0) = edge_point(p[0], p[1], n[0]), at(2, 0) = edge_point(p[1], p[0], n[1]);  // v = 0
  at(3, 1) = edge_point(p[1], p[2], n[1]), at(3, 2) = edge_point(p[2], p[1], n[2]);  // u = 1
  at(1, 3) = edge_point(p[3], p[2], n[3]), at(2, 3) = edge_point(p[2], p[3], n[2]);  // v = 1
  at(0, 1) = edge_point(p[0], p[3], n[0]), at(0, 2) = edge_point(p[3], p[0], n[3]);  // u = 0
  for (int j = 1; j <= 2; ++j)
    for (int i = 1; i <= 2; ++i) {
      const double s = i / 3.0, t = j / 3.0;
      const dvec3 ruled = ((1.0 - s) * at(0, j) + s * at(3, j)) + ((1.0 - t) * at(i, 0) + t * at(i, 3));
      const dvec3 bilinear = (1.0 - t) * ((1.0 - s) * p[0] + s * p[1]) + t * ((1.0 - s) * p[3] + s * p[2]);
      at(i, j) = ruled - bilinear;
    }
  PNQuad q;
  for (int i = 0; i < 16; ++i) q.b[std::size_t(i)] = glm::vec3(b[std::size_t(i)]);
  std::array<dvec3, 9> m;
  m[0] = n[0], m[2] = n[1], m[8] = n[2], m[6] = n[3];
  m[1] = edge_normal(p[0], p[1], n[0], n[1]);
  m[5] = edge_normal(p[1], p[2], n[1], n[2]);
  m[7] = edge_normal(p[3], p[2], n[3], n[2]);
  m[3] = edge_normal(p[0], p[3], n[0], n[3]);
  m[4] = 0.5 * ((m[1] + m[7]) + (m[3] + m[5])) - 0.25 * ((m[0] + m[2]) + (m[6] + m[8]));
  for (int i = 0; i < 9; ++i) q.n[std::size_t(i)] = glm::vec3(m[std::size_t(i)]);
  return q;
}

std::vector<glm::vec3> vertex_normals(const Cage& cage, std::span<const glm::vec3> positions, const Topology& t) {
  std::vector<dvec3> sum(positions.size(), dvec3(0.0));
  for (int f = 0; f < t.face_count(); ++f) {
    if (t.is_hole(f)) continue;
    const int n = t.face_size(f);
    // Relative to the first corner (no cancellation far from the origin): a triangle's (p1 - p0) x
    // (p2 - p0), a quad's (p2 - p0) x (p3 - p1).
    auto at = [&](int k) { return dvec3(positions[std::size_t(cage.face_vertex(f, k))]); };
    const dvec3 p0 = at(0);
    dvec3 area(0.0);
    for (int k = 1; k + 1 < n; ++k) area += glm::cross(at(k) - p0, at(k + 1) - p0);
    area *= 0.5;
    for (int k = 0; k < n; ++k) sum[std::size_t(cage.face_vertex(f, k))] += area;
  }
  std::vector<glm::vec3> out(sum.size(), glm::vec3(0.0f));
  for (std::size_t v = 0; v < sum.size(); ++v) {
    const double len = glm::length(sum[v]);
    if (len > 0.0) out[v] = glm::vec3(sum[v] / len);
  }
  return out;
}

}  // namespace tessera
