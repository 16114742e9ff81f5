#include "shaders_cpp/subdiv/limit_fit.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>

#include <algorithm>
#include <cmath>

#include "shaders_cpp/subdiv/limit_surface.h"
#include "shaders_cpp/subdiv/osd_refiner.h"

namespace tessera {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;

struct LimitStencils::Impl {
  std::unique_ptr<osd::Far::TopologyRefiner> refiner;
  std::unique_ptr<osd::Bfr::RefinerSurfaceFactory<>> factory;
  std::vector<char> by_far;  // faces Bfr 3.5.0 fails on (far_patches.h): not fitted
};

LimitStencils::LimitStencils(const Cage& cage) : impl_(std::make_unique<Impl>()) {
  std::vector<int> far_faces;
  impl_->refiner = osd_detail::build_osd_refiner(cage, &far_faces);
  osd::Bfr::SurfaceFactory::Options options;
  // Bfr's cache of irregular patch trees stays on: a face's surface is built for its face points and
  // again for each of its edges (without it catmark_car loads in 0.45 s, with it 0.14 s; its peak memory
  // while loading is 46 MB against 21 MB before creased faces were fitted).
  options.SetApproxLevelSmooth(LimitSurface::kDefaultApproxLevel)
      .SetApproxLevelSharp(LimitSurface::kDefaultApproxLevel);
  impl_->factory = std::make_unique<osd::Bfr::RefinerSurfaceFactory<>>(*impl_->refiner, options);
  impl_->by_far.assign(std::size_t(cage.face_count()), 0);
  for (const int f : far_faces) impl_->by_far[std::size_t(f)] = 1;
}

LimitStencils::~LimitStencils() = default;

std::optional<std::vector<Stencil>> LimitStencils::at(int face, std::span<const std::array<double, 2>> uv,
                                                      std::vector<Stencil>* du, std::vector<Stencil>* dv) const {
  if (impl_->by_far[std::size_t(face)] || impl_->refiner->GetLevel(0).GetFaceVertices(face).size() != 4 ||
      !impl_->factory->FaceHasLimitSurface(face))
    return std::nullopt;
  osd::Bfr::Surface<double> surface;
  if (!impl_->factory->InitVertexSurface(face, &surface) || !surface.IsValid()) return std::nullopt;
  const int n = surface.GetNumControlPoints();
  std::vector<int> cvs(std::size_t(n), 0);
  surface.GetControlPointIndices(cvs.data());
  std::vector<double> w(static_cast<std::size_t>(n)), wu(static_cast<std::size_t>(n)), wv(static_cast<std::size_t>(n));
  std::vector<Stencil> out;
  out.reserve(uv.size());
  // Bfr's control points are distinct cage vertices: sorted once, each stencil takes them in that order.
  std::vector<int> by_vertex(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) by_vertex[std::size_t(i)] = i;
  std::sort(by_vertex.begin(), by_vertex.end(),
            [&](int a, int b) { return cvs[std::size_t(a)] < cvs[std::size_t(b)]; });
  auto stencil = [&](const std::vector<double>& x) {
    Stencil s;
    for (const int i : by_vertex)
      if (std::abs(x[std::size_t(i)]) > 1e-12) s.terms.emplace_back(cvs[std::size_t(i)], x[std::size_t(i)]);
    return s;
  };
  for (const auto& p : uv) {
    surface.EvaluateStencil(p.data(), w.data(), wu.data(), wv.data());
    out.push_back(stencil(w));
    if (du) du->push_back(stencil(wu));
    if (dv) dv->push_back(stencil(wv));
  }
  return out;
}

namespace {

// The weight of a smooth edge's cross-derivative equations against the interior's positions: they pull
// the two patches on an edge toward one tangent plane, the limit's. Measured on OpenSubdiv's creased
// shapes (gregory, factor 7): 0.01 lowers the mean normal error everywhere (catmark_chaikin0 3.5 -> 2.6
// degrees) and the largest distance on most; 0.1 and 1 trade distance for little more.
constexpr double kCrossWeight = 0.01;

constexpr std::array<std::array<double, 2>, 4> kCorner = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};

std::array<double, 4> bernstein(double t) {
  const double s = 1.0 - t;
  return {s * s * s, 3.0 * t * s * s, 3.0 * s * t * t, t * t * t};
}

// The weight of each of a Gregory patch's 20 points at (u, v) (patch_eval.h's gregory_to_bezier).
std::array<double, 20> gregory_weights(double u, double v) {
  const std::array<double, 4> bu = bernstein(u), bv = bernstein(v);
  auto b = [&](int i, int j) { return bu[std::size_t(i)] * bv[std::size_t(j)]; };
  std::array<double, 20> w{};
  auto P = [](int k) { return std::size_t(5 * k); };
  auto Ep = [](int k) { return std::size_t(5 * k + 1); };
  auto Em = [](int k) { return std::size_t(5 * k + 2); };
  auto Fp = [](int k) { return std::size_t(5 * k + 3); };
  auto Fm = [](int k) { return std::size_t(5 * k + 4); };
  w[P(0)] = b(0, 0), w[Ep(0)] = b(1, 0), w[Em(1)] = b(2, 0), w[P(1)] = b(3, 0);
  w[Em(0)] = b(0, 1), w[Ep(1)] = b(3, 1);
  w[Ep(3)] = b(0, 2), w[Em(2)] = b(3, 2);
  w[P(3)] = b(0, 3), w[Em(3)] = b(1, 3), w[Ep(2)] = b(2, 3), w[P(2)] = b(3, 3);
  const double s = u, t = v, s1 = 1.0 - u, t1 = 1.0 - v;
  auto blend = [&](std::size_t plus, double wp, std::size_t minus, double wm, double basis) {
    w[plus] += basis * wp / (wp + wm);
    w[minus] += basis * wm / (wp + wm);
  };
  blend(Fp(0), s, Fm(0), t, b(1, 1));
  blend(Fp(1), t, Fm(1), s1, b(2, 1));
  blend(Fp(2), s1, Fm(2), t1, b(2, 2));
  blend(Fp(3), t1, Fm(3), s, b(1, 2));
  return w;
}

// Stencils as dense rows over one sorted list of cage vertices: the fits add hundreds of stencils of the
// same few dozen vertices, which merging sparse stencils would do term list by term list.
class DenseSpace {
 public:
  void include(const Stencil& s) {  // a union of sorted lists: the limit's stencils share their vertices
    merged_.clear();
    auto a = ids_.begin();
    for (const auto& t : s.terms) {
      while (a != ids_.end() && *a < t.first) merged_.push_back(*a++);
      if (a != ids_.end() && *a == t.first) ++a;
      merged_.push_back(t.first);
    }
    merged_.insert(merged_.end(), a, ids_.end());
    ids_.swap(merged_);
  }
  void include(const std::vector<Stencil>& list) {
    for (const Stencil& s : list) include(s);
  }
  std::vector<double> zero() const { return std::vector<double>(ids_.size(), 0.0); }
  // row += w * s
  void add(std::vector<double>& row, const Stencil& s, double w) const {
    std::size_t i = 0;
    for (const auto& [v, x] : s.terms) {
      while (ids_[i] != v) ++i;  // both ascending, s's vertices among ids_
      row[i] += w * x;
    }
  }
  Stencil stencil(const std::vector<double>& row) const {
    Stencil s;
    for (std::size_t i = 0; i < ids_.size(); ++i)
      if (row[i] != 0.0) s.terms.emplace_back(ids_[i], row[i]);
    return s;
  }

 private:
  std::vector<int> ids_, merged_;
};

// Solves the symmetric positive definite system m x = rhs for dense right-hand sides (Gauss-Jordan on
// the matrix, the same combination of the rows), returned as stencils.
template <std::size_t N>
std::array<Stencil, N> solve(std::array<std::array<double, N>, N> m, const std::array<std::vector<double>, N>& rhs,
                             const DenseSpace& space) {
  std::array<std::array<double, N>, N> inv{};
  for (std::size_t i = 0; i < N; ++i) inv[i][i] = 1.0;
  for (std::size_t c = 0; c < N; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < N; ++r)
      if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
    std::swap(m[c], m[pivot]), std::swap(inv[c], inv[pivot]);
    const double d = m[c][c];
    for (std::size_t k = 0; k < N; ++k) m[c][k] /= d, inv[c][k] /= d;
    for (std::size_t r = 0; r < N; ++r) {
      if (r == c || m[r][c] == 0.0) continue;
      const double f = m[r][c];
      for (std::size_t k = 0; k < N; ++k) m[r][k] -= f * m[c][k], inv[r][k] -= f * inv[c][k];
    }
  }
  std::array<Stencil, N> x;
  for (std::size_t i = 0; i < N; ++i) {
    std::vector<double> row = space.zero();
    for (std::size_t j = 0; j < N; ++j)
      for (std::size_t k = 0; k < row.size(); ++k) row[k] += inv[i][j] * rhs[j][k];
    x[i] = space.stencil(row);
  }
  return x;
}

}  // namespace

std::optional<EdgePoints> fit_edge_points(const LimitStencils& limit, int face, int e, const Stencil& pa,
                                          const Stencil& pb) {
  constexpr int kSamples = 16;
  const auto& c0 = kCorner[std::size_t(e % 4)];
  const auto& c1 = kCorner[std::size_t((e + 1) % 4)];
  std::vector<std::array<double, 2>> uv;
  std::vector<double> ts;
  for (int i = 0; i < kSamples; ++i) {
    const double t = (i + 0.5) / kSamples;
    ts.push_back(t);
    uv.push_back({c0[0] + t * (c1[0] - c0[0]), c0[1] + t * (c1[1] - c0[1])});
  }
  const std::optional<std::vector<Stencil>> l = limit.at(face, uv);
  if (!l) return std::nullopt;
  DenseSpace space;
  space.include(*l), space.include(pa), space.include(pb);
  std::array<std::array<double, 2>, 2> m{};
  std::array<std::vector<double>, 2> rhs{space.zero(), space.zero()};
  for (int i = 0; i < kSamples; ++i) {
    const std::array<double, 4> b = bernstein(ts[std::size_t(i)]);
    // The limit less the fixed corners' share, weighted by each unknown's basis function.
    for (std::size_t a = 0; a < 2; ++a) {
      space.add(rhs[a], (*l)[std::size_t(i)], b[a + 1]);
      space.add(rhs[a], pa, -b[0] * b[a + 1]);
      space.add(rhs[a], pb, -b[3] * b[a + 1]);
    }
    m[0][0] += b[1] * b[1], m[0][1] += b[1] * b[2], m[1][1] += b[2] * b[2];
  }
  m[1][0] = m[0][1];
  const std::array<Stencil, 2> x = solve(m, rhs, space);
  return EdgePoints{x[0], x[1]};
}

std::optional<std::array<Stencil, 4>> fit_inward_derivative(const LimitStencils& limit, int face, int e) {
  constexpr int kSamples = 16;
  const auto& c0 = kCorner[std::size_t(e % 4)];
  const auto& c1 = kCorner[std::size_t((e + 1) % 4)];
  const double dx = c1[0] - c0[0], dy = c1[1] - c0[1];
  std::vector<std::array<double, 2>> uv;
  for (int i = 0; i < kSamples; ++i) {
    const double t = (i + 0.5) / kSamples;
    uv.push_back({c0[0] + t * dx, c0[1] + t * dy});
  }
  std::vector<Stencil> du, dv;
  if (!limit.at(face, uv, &du, &dv)) return std::nullopt;
  // Inward: the edge's direction turned a quarter counter-clockwise.
  const double ix = -dy, iy = dx;
  DenseSpace space;
  space.include(du), space.include(dv);
  std::array<std::array<double, 4>, 4> m{};
  std::array<std::vector<double>, 4> rhs{space.zero(), space.zero(), space.zero(), space.zero()};
  for (int i = 0; i < kSamples; ++i) {
    const std::array<double, 4> b = bernstein((i + 0.5) / kSamples);
    for (std::size_t a = 0; a < 4; ++a) {
      space.add(rhs[a], du[std::size_t(i)], ix * b[a]);
      space.add(rhs[a], dv[std::size_t(i)], iy * b[a]);
      for (std::size_t c = 0; c < 4; ++c) m[a][c] += b[a] * b[c];
    }
  }
  return solve(m, rhs, space);
}

bool fit_face_points(const LimitStencils& limit, int face, int rotation, std::vector<Stencil>& rows,
                     std::array<bool, 4> smooth_edges) {
  // Patch (u, v) -> the face's frame: patch corner k is face corner k + rotation (a bilinear map).
  auto face_uv = [&](double u, double v) {
    std::array<double, 2> f{0.0, 0.0};
    const double wk[4] = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 2; ++c) f[std::size_t(c)] += wk[k] * kCorner[std::size_t((k + rotation) % 4)][std::size_t(c)];
    return f;
  };
  // One equation: sum over the rows r of w[r] * row r = target (a limit stencil in `term`, weighted).
  struct Equation {
    std::array<double, 20> w;
    const Stencil* term;
    double scale;  // of `term`
    const Stencil* term2 = nullptr;
    double scale2 = 0.0;
    double weight = 1.0;
  };
  std::vector<Equation> equations;
  constexpr int kGrid = 10;
  std::vector<std::array<double, 2>> uv, patch_uv;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const double u = (i + 0.5) / kGrid, v = (j + 0.5) / kGrid;
      patch_uv.push_back({u, v});
      uv.push_back(face_uv(u, v));
    }
  const std::optional<std::vector<Stencil>> l = limit.at(face, uv);
  if (!l) return false;
  for (std::size_t i = 0; i < uv.size(); ++i)
    equations.push_back({gregory_weights(patch_uv[i][0], patch_uv[i][1]), &(*l)[i], 1.0});
  // Smooth edges: the cross derivative along the edge, 3 (inner row - boundary row), is the limit's.
  const double lambda = kCrossWeight;
  constexpr int kSamples = 16;
  std::array<std::vector<Stencil>, 4> du, dv;
  for (int k = 0; k < 4 && lambda > 0.0; ++k) {
    if (!smooth_edges[std::size_t(k)]) continue;
    const int e = (k + rotation) % 4, k1 = (k + 1) % 4;
    const auto& c0 = kCorner[std::size_t(e)];
    const auto& c1 = kCorner[std::size_t((e + 1) % 4)];
    const double dx = c1[0] - c0[0], dy = c1[1] - c0[1];
    std::vector<std::array<double, 2>> euv;
    for (int i = 0; i < kSamples; ++i) {
      const double t = (i + 0.5) / kSamples;
      euv.push_back({c0[0] + t * dx, c0[1] + t * dy});
    }
    if (!limit.at(face, euv, &du[std::size_t(k)], &dv[std::size_t(k)])) return false;
    for (int i = 0; i < kSamples; ++i) {
      const std::array<double, 4> b = bernstein((i + 0.5) / kSamples);
      Equation q{{}, &du[std::size_t(k)][std::size_t(i)], -dy, &dv[std::size_t(k)][std::size_t(i)], dx, lambda};
      const std::size_t boundary[4] = {std::size_t(5 * k), std::size_t(5 * k + 1), std::size_t(5 * k1 + 2),
                                       std::size_t(5 * k1)};
      const std::size_t inner[4] = {std::size_t(5 * k + 2), std::size_t(5 * k + 3), std::size_t(5 * k1 + 4),
                                    std::size_t(5 * k1 + 1)};
      for (std::size_t a = 0; a < 4; ++a) q.w[boundary[a]] -= 3 * b[a], q.w[inner[a]] += 3 * b[a];
      equations.push_back(q);
    }
  }
  constexpr std::array<std::size_t, 8> kFree = {3, 4, 8, 9, 13, 14, 18, 19};
  auto is_free = [&](std::size_t r) { return std::find(kFree.begin(), kFree.end(), r) != kFree.end(); };
  DenseSpace space;
  for (const Equation& q : equations) {
    space.include(*q.term);
    if (q.term2) space.include(*q.term2);
  }
  for (std::size_t r = 0; r < 20; ++r)
    if (!is_free(r)) space.include(rows[r]);
  std::array<std::array<double, 8>, 8> m{};
  std::array<std::vector<double>, 8> rhs;
  for (auto& r : rhs) r = space.zero();
  std::vector<double> target;
  for (const Equation& q : equations) {
    // The limit less the fixed points' share, weighted by each face point's coefficient.
    target = space.zero();
    space.add(target, *q.term, q.scale);
    if (q.term2) space.add(target, *q.term2, q.scale2);
    for (std::size_t r = 0; r < 20; ++r)
      if (!is_free(r) && q.w[r] != 0.0) space.add(target, rows[r], -q.w[r]);
    for (std::size_t a = 0; a < 8; ++a) {
      const double wa = q.weight * q.w[kFree[a]];
      if (wa == 0.0) continue;
      for (std::size_t k = 0; k < target.size(); ++k) rhs[a][k] += wa * target[k];
      for (std::size_t b = 0; b < 8; ++b) m[a][b] += wa * q.w[kFree[b]];
    }
  }
  const std::array<Stencil, 8> x = solve(m, rhs, space);
  for (std::size_t a = 0; a < 8; ++a) rows[kFree[a]] = x[a];
  return true;
}

}  // namespace tessera
