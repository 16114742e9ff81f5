// Exact limit surface through OpenSubdiv's Bfr, with ownership for bitwise watertightness.
//
// Why Bfr (and not Far patch tables + PatchMap): Bfr gives one self-contained Surface per face with
// its own patch points, so everything evaluation needs is precomputed per face, evaluation is a
// const read with stack-only temporaries (thread-safe, allocation-free), and its approximation
// level (Gregory end caps after L refinements near extraordinary vertices, exact B-spline patches
// elsewhere) is the same machinery as Far's adaptive tables. Bfr shares the irregular-patch trees of
// faces with identical neighbourhoods through its cache, which keeps level 10 affordable.
//
// Why ownership: each face's Surface has its own patch points and summation order, so two faces
// evaluating the same edge point differ in the last bits (subdiv.md §3.3). Points exactly on a
// shared element are therefore evaluated by one owner, at the owner's domain location of the point.
#include "shaders_cpp/subdiv/limit_surface.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "shaders_cpp/subdiv/far_patches.h"
#include "shaders_cpp/subdiv/osd_refiner.h"
#include "tessellator/check.h"

namespace tessera {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;
using Surface = osd::Bfr::Surface<double>;

namespace {

// Position and normal of a shared point, exactly as handed to every face that shares it.
struct SharedPoint {
  glm::vec3 position;
  glm::vec3 normal;
};

struct Raw {  // double-precision evaluation in one sub-patch's (s,t)
  glm::dvec3 p, ds, dt;
};

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
  return (std::uint64_t(lo) << 32) | hi;
}

}  // namespace

const char* to_string(AdaptivePatchKind k) {
  switch (k) {
    case AdaptivePatchKind::regular: return "regular";
    case AdaptivePatchKind::boundary: return "boundary";
    case AdaptivePatchKind::single_crease: return "single-crease";
    case AdaptivePatchKind::end_cap: return "end cap";
  }
  return "?";
}

struct LimitSurface::Impl {
  int level = kDefaultApproxLevel;
  bool adaptive = false;  // create_adaptive(): every face through `far`
  bool left_handed = false;
  std::unique_ptr<osd::Far::TopologyRefiner> refiner;
  std::unique_ptr<osd::Bfr::RefinerSurfaceFactory<>> factory;

  std::vector<int> sizes;         // per face
  std::vector<int> corner_base;   // per face: first entry in corners/edge_owner
  std::vector<int> corners;       // cage vertex of each face corner
  std::vector<Surface> surfaces;  // per face; invalid without a surface or when by_far
  // Faces evaluated through Far instead of Bfr (far_patches.h: OpenSubdiv 3.5.0's Bfr fails on them).
  std::vector<char> by_far;
  std::unique_ptr<subdiv::FarPatches> far;
  std::vector<std::size_t> pp_offset;
  std::vector<double> patch_points;

  struct EdgeOwner {
    int face = -1, edge = -1;
    bool reversed = false;  // the owner runs the edge the other way
  };
  std::vector<EdgeOwner> edge_owner;      // per face corner e: owner of edge e -> e+1
  std::vector<SharedPoint> vertex_limit;  // per cage vertex (unused vertices stay zero)

  glm::dvec3 lo{0.0}, hi{0.0};
  std::string label;  // the cage's, for errors

  // Bfr's patch points of every face it draws, from `positions` (one per cage vertex).
  void place_bfr_points(std::span<const glm::vec3> positions) {
    std::vector<double> mesh(positions.size() * 3);
    for (std::size_t v = 0; v < positions.size(); ++v)
      for (int c = 0; c < 3; ++c) mesh[v * 3 + std::size_t(c)] = double(positions[v][c]);
    const Surface::PointDescriptor desc(3);
    for (std::size_t f = 0; f < surfaces.size(); ++f) {
      const Surface& s = surfaces[f];
      if (by_far[f] || !s.IsValid()) continue;
      double* first = patch_points.data() + pp_offset[f];
      s.PreparePatchPoints(mesh.data(), desc, first, desc);
      for (double* x = first; x != patch_points.data() + pp_offset[f + 1]; ++x)
        if (!std::isfinite(*x))
          throw CageError(label + ": face " + std::to_string(f) +
                          " has no finite limit surface (vertex positions that are not finite or overflow)");
    }
  }
  // What depends on the points besides the patches: each vertex's limit, evaluated once by its owner
  // (the lowest-index face with a surface, its first corner there), and the bounds of the surface from
  // a 9x9 grid on every sub-patch.
  void place_shared() {
    std::fill(vertex_limit.begin(), vertex_limit.end(), SharedPoint{glm::vec3(0.0f), glm::vec3(0.0f)});
    std::vector<char> vertex_done(vertex_limit.size(), 0);
    for (int f = 0; f < int(sizes.size()); ++f) {
      if (!has_surface(f)) continue;
      const int n = sizes[std::size_t(f)], base = corner_base[std::size_t(f)];
      for (int e = 0; e < n; ++e) {
        const int a = corners[std::size_t(base + e)];
        if (vertex_done[std::size_t(a)]) continue;
        vertex_done[std::size_t(a)] = 1;
        vertex_limit[std::size_t(a)] =
            n == 4 ? shared(f, 0, e == 1 || e == 2 ? 1.0 : 0.0, e >= 2 ? 1.0 : 0.0) : shared(f, e, 0.0, 0.0);
      }
    }
    lo = glm::dvec3(std::numeric_limits<double>::infinity());
    hi = glm::dvec3(-std::numeric_limits<double>::infinity());
    for (int f = 0; f < int(sizes.size()); ++f) {
      if (!has_surface(f)) continue;
      const int subs = sizes[std::size_t(f)] == 4 ? 1 : sizes[std::size_t(f)];
      for (int k = 0; k < subs; ++k)
        for (int i = 0; i <= 8; ++i)
          for (int j = 0; j <= 8; ++j) {
            const glm::dvec3 p = raw(f, k, i / 8.0, j / 8.0).p;
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
          }
    }
    if (lo.x > hi.x) lo = hi = glm::dvec3(0.0);
  }

  bool has_surface(int f) const { return surfaces[std::size_t(f)].IsValid() || by_far[std::size_t(f)]; }

  // Bfr evaluation of face f, sub-patch k, at (s,t) in that sub-patch's unit square; derivatives
  // with respect to (s,t). Bfr tiles the sub-faces of a non-quad in one (u,v) space; the map from
  // the normalized sub-face square into it is affine, so its Jacobian comes from three conversions.
  Raw raw(int f, int k, double s, double t) const {
    if (by_far[std::size_t(f)]) {
      const subdiv::FarPatches::Point q = far->evaluate(f, k, s, t);
      return {q.p, q.ds, q.dt};
    }
    const Surface& surf = surfaces[std::size_t(f)];
    const double* pp = patch_points.data() + pp_offset[std::size_t(f)];
    const Surface::PointDescriptor desc(3);
    double P[3], Du[3], Dv[3];
    Raw r;
    if (sizes[std::size_t(f)] == 4) {
      const double uv[2] = {s, t};
      surf.Evaluate(uv, pp, desc, P, Du, Dv);
      r.p = {P[0], P[1], P[2]};
      r.ds = {Du[0], Du[1], Du[2]};
      r.dt = {Dv[0], Dv[1], Dv[2]};
      return r;
    }
    const osd::Bfr::Parameterization param = surf.GetParameterization();
    const double st[2] = {s, t}, o[2] = {0.0, 0.0}, ex[2] = {1.0, 0.0}, ey[2] = {0.0, 1.0};
    double uv[2], uv0[2], uvx[2], uvy[2];
    param.ConvertNormalizedSubFaceToCoord(k, st, uv);
    param.ConvertNormalizedSubFaceToCoord(k, o, uv0);
    param.ConvertNormalizedSubFaceToCoord(k, ex, uvx);
    param.ConvertNormalizedSubFaceToCoord(k, ey, uvy);
    surf.Evaluate(uv, pp, desc, P, Du, Dv);
    const glm::dvec3 du(Du[0], Du[1], Du[2]), dv(Dv[0], Dv[1], Dv[2]);
    r.p = {P[0], P[1], P[2]};
    r.ds = du * (uvx[0] - uv0[0]) + dv * (uvx[1] - uv0[1]);
    r.dt = du * (uvy[0] - uv0[0]) + dv * (uvy[1] - uv0[1]);
    return r;
  }

  glm::dvec3 normal_of(const glm::dvec3& ds, const glm::dvec3& dt) const {
    const glm::dvec3 c = glm::cross(ds, dt);
    const double len = glm::length(c);
    if (!(len > 0.0) || !std::isfinite(len)) return glm::dvec3(0.0);
    return (left_handed ? -c : c) / len;
  }

  // Normal at (s,t); where du x dv vanishes (degenerate cage geometry), the normal of a point a
  // hair towards the sub-patch centre, which is the limit of the normal along that path.
  // At a corner of a Far patch (adaptive, and the faces Bfr cannot take) the derivatives can also turn
  // over (a smooth corner on a concave boundary, where they are nearly parallel): there the nearby
  // normal wins when the two disagree.
  glm::dvec3 normal_at(int f, int k, double s, double t, const Raw& r) const {
    glm::dvec3 n = normal_of(r.ds, r.dt);
    const bool far_corner = by_far[std::size_t(f)] && (s == 0.0 || s == 1.0) && (t == 0.0 || t == 1.0);
    if (n == glm::dvec3(0.0) || far_corner) {
      const double h = 1.0 / 65536.0;
      const Raw r2 = raw(f, k, s + (0.5 - s) * h, t + (0.5 - t) * h);
      const glm::dvec3 near = normal_of(r2.ds, r2.dt);
      if (n == glm::dvec3(0.0) || glm::dot(n, near) < 0.0) n = near;
    }
    return n;
  }

  SharedPoint shared(int f, int k, double s, double t) const {
    const Raw r = raw(f, k, s, t);
    return {glm::vec3(r.p), glm::vec3(normal_at(f, k, s, t, r))};
  }

  // The point at parameter s (from corner e to corner e+1) of edge e of face f, in f's own domain.
  SharedPoint edge_point_of(int f, int e, double s) const {
    const int n = sizes[std::size_t(f)];
    if (n == 4) {
      switch (e) {
        case 0: return shared(f, 0, s, 0.0);
        case 1: return shared(f, 0, 1.0, s);
        case 2: return shared(f, 0, 1.0 - s, 1.0);
        default: return shared(f, 0, 0.0, 1.0 - s);
      }
    }
    if (s <= 0.5) return shared(f, e, 2.0 * s, 0.0);
    return shared(f, (e + 1) % n, 0.0, 2.0 * (1.0 - s));
  }

  // A point of cage edge e of face f at parameter t, through the edge's owner.
  SharedPoint cage_edge(int f, int e, double t) const {
    const int n = sizes[std::size_t(f)], base = corner_base[std::size_t(f)];
    if (t == 0.0) return vertex_limit[std::size_t(corners[std::size_t(base + e)])];
    if (t == 1.0) return vertex_limit[std::size_t(corners[std::size_t(base + (e + 1) % n)])];
    const EdgeOwner& o = edge_owner[std::size_t(base + e)];
    return edge_point_of(o.face, o.edge, o.reversed ? 1.0 - t : t);
  }

  SharedPoint corner(int f, int k) const {
    return vertex_limit[std::size_t(corners[std::size_t(corner_base[std::size_t(f)] + k)])];
  }

  // The owned point at (s,t) of sub-patch k, or nothing when the point is interior.
  bool owned(int f, int k, double s, double t, SharedPoint& out) const {
    const int n = sizes[std::size_t(f)];
    if (n == 4) {
      if (s == 0.0 && t == 0.0)
        out = corner(f, 0);
      else if (s == 1.0 && t == 0.0)
        out = corner(f, 1);
      else if (s == 1.0 && t == 1.0)
        out = corner(f, 2);
      else if (s == 0.0 && t == 1.0)
        out = corner(f, 3);
      else if (t == 0.0)
        out = cage_edge(f, 0, s);
      else if (s == 1.0)
        out = cage_edge(f, 1, t);
      else if (t == 1.0)
        out = cage_edge(f, 2, 1.0 - s);
      else if (s == 0.0)
        out = cage_edge(f, 3, 1.0 - t);
      else
        return false;
      return true;
    }
    if (s == 0.0 && t == 0.0)
      out = corner(f, k);
    else if (t == 0.0)
      out = cage_edge(f, k, 0.5 * s);  // first half of edge k
    else if (s == 0.0)
      out = cage_edge(f, (k + n - 1) % n, 1.0 - 0.5 * t);  // second half of edge k-1
    else if (s == 1.0 && t == 1.0)
      out = shared(f, 0, 1.0, 1.0);  // face centre
    else if (s == 1.0)
      out = shared(f, k, 1.0, t);  // sub-patch edge k | k+1
    else if (t == 1.0)
      out = shared(f, (k + n - 1) % n, 1.0, s);  // sub-patch edge k-1 | k
    else
      return false;
    return true;
  }

  // Barycentric (u,v) of a triangle face -> sub-patch k and its (s,t), plus d(s,t)/d(u,v).
  // Sub-patch k covers the points whose largest barycentric is b_k; with x = b_{k+1}, y = b_{k-1}
  // its bilinear map is x = s/2 - st/6, y = t/2 - st/6 (corners (0,0), (1/2,0), (1/3,1/3), (0,1/2)).
  // Inverting: x - y = (s-t)/2 and s^2 - (3+2d)s + 6x = 0 with d = x - y (the root in [0,1], in the
  // cancellation-free form).
  SurfacePoint to_point(int f, int k, double s, double t, const Raw& r) const { return to_point(f, k, s, t, r, r); }
  // `out` gives the position and the reported derivatives; the normal comes from sub-patch k's own
  // derivatives in `sub`, so it depends on (k, s, t) only.
  SurfacePoint to_point(int f, int k, double s, double t, const Raw& out, const Raw& sub) const {
    return {glm::vec3(out.p), glm::vec3(out.ds), glm::vec3(out.dt), glm::vec3(normal_at(f, k, s, t, sub))};
  }
};

namespace {

[[noreturn]] void bad_query(const std::string& what) { throw std::out_of_range("LimitSurface: " + what); }

void check_coord(float x, const char* name) {
  if (!(x >= 0.0f && x <= 1.0f)) bad_query(std::string(name) + " = " + std::to_string(x) + " is outside [0,1]");
}

}  // namespace

LimitSurface::LimitSurface(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LimitSurface::LimitSurface(LimitSurface&&) noexcept = default;
LimitSurface& LimitSurface::operator=(LimitSurface&&) noexcept = default;
LimitSurface::~LimitSurface() = default;

LimitSurface LimitSurface::create(const Cage& cage, int approx_level) {
  if (approx_level < 1 || approx_level > kMaxApproxLevel)
    throw std::invalid_argument("LimitSurface: approximation level " + std::to_string(approx_level) +
                                " is outside 1.." + std::to_string(kMaxApproxLevel));
  return build(cage, approx_level, false);
}

LimitSurface LimitSurface::create_adaptive(const Cage& cage, int isolation) {
  if (isolation < 1 || isolation > kMaxIsolation)
    throw std::invalid_argument("LimitSurface: isolation level " + std::to_string(isolation) + " is outside 1.." +
                                std::to_string(kMaxIsolation));
  return build(cage, isolation, true);
}

LimitSurface LimitSurface::build(const Cage& cage, int level, bool adaptive) {
  auto m = std::make_unique<Impl>();
  m->level = level;
  m->adaptive = adaptive;
  m->left_handed = cage.tags.left_handed;
  m->label = subdiv::cage_label(cage);
  std::vector<int> far_faces;
  if (adaptive) {
    // validate_cage and OpenSubdiv's limits are checked as the patches' refiner is built.
    m->far = std::make_unique<subdiv::FarPatches>(cage, level, std::vector<int>{}, true);
  } else {
    m->refiner = subdiv::build_osd_refiner(cage, &far_faces);  // validate_cage, then OpenSubdiv's limits
    osd::Bfr::SurfaceFactory::Options options;
    options.SetApproxLevelSmooth(level).SetApproxLevelSharp(level);
    m->factory = std::make_unique<osd::Bfr::RefinerSurfaceFactory<>>(*m->refiner, options);
  }

  const int nf = cage.face_count(), nv = cage.vertex_count();
  m->sizes = cage.face_sizes;
  m->corner_base.resize(std::size_t(nf));
  int total = 0;
  for (int f = 0; f < nf; ++f) {
    m->corner_base[std::size_t(f)] = total;
    for (int k = 0; k < cage.face_sizes[std::size_t(f)]; ++k) m->corners.push_back(cage.face_vertex(f, k));
    total += cage.face_sizes[std::size_t(f)];
  }

  m->surfaces.resize(std::size_t(nf));
  m->by_far.assign(std::size_t(nf), 0);
  m->pp_offset.assign(std::size_t(nf) + 1, 0);
  if (adaptive) {
    for (int f = 0; f < nf; ++f) m->by_far[std::size_t(f)] = m->far->has_patches(f);
  } else {
    if (!far_faces.empty()) {
      m->far = std::make_unique<subdiv::FarPatches>(cage, level, far_faces);
      for (int f : far_faces) m->by_far[std::size_t(f)] = 1;
    }
    // Bfr's surfaces and their patch points, for every other face.
    for (int f = 0; f < nf; ++f) {
      Surface& s = m->surfaces[std::size_t(f)];
      m->pp_offset[std::size_t(f)] = m->patch_points.size();
      if (m->by_far[std::size_t(f)]) continue;
      if (m->factory->FaceHasLimitSurface(f) && !m->factory->InitVertexSurface(f, &s))
        throw CageError(m->label + ": face " + std::to_string(f) + " has no OpenSubdiv limit surface");
      if (s.IsValid()) m->patch_points.resize(m->patch_points.size() + std::size_t(s.GetNumPatchPoints()) * 3);
    }
    m->pp_offset[std::size_t(nf)] = m->patch_points.size();
    m->place_bfr_points(cage.positions);
  }

  // Edge owners: lowest-index face with a surface, first occurrence within it.
  struct FirstUse {
    int face, edge, from;
  };
  std::unordered_map<std::uint64_t, FirstUse> first;
  first.reserve(std::size_t(total));
  m->edge_owner.resize(std::size_t(total));
  for (int f = 0; f < nf; ++f) {
    if (!m->has_surface(f)) continue;
    const int n = m->sizes[std::size_t(f)], base = m->corner_base[std::size_t(f)];
    for (int e = 0; e < n; ++e) {
      const int a = m->corners[std::size_t(base + e)], b = m->corners[std::size_t(base + (e + 1) % n)];
      const FirstUse& o = first.try_emplace(edge_key(a, b), FirstUse{f, e, a}).first->second;
      m->edge_owner[std::size_t(base + e)] = {o.face, o.edge, o.from != a};
    }
  }
  m->vertex_limit.resize(std::size_t(nv));
  m->place_shared();
  return LimitSurface(std::move(m));
}

void LimitSurface::repose(std::span<const glm::vec3> positions) {
  Impl& m = *impl_;
  TESSERA_CHECK_EQ(positions.size(), m.vertex_limit.size(), "LimitSurface::repose: one position per cage vertex");
  if (m.far) m.far->repose(positions);
  if (!m.adaptive) m.place_bfr_points(positions);
  m.place_shared();
}

int LimitSurface::face_count() const { return int(impl_->sizes.size()); }
int LimitSurface::face_size(int face) const {
  if (face < 0 || face >= face_count()) bad_query("face " + std::to_string(face) + " is out of range");
  return impl_->sizes[std::size_t(face)];
}
bool LimitSurface::has_surface(int face) const { return face >= 0 && face < face_count() && impl_->has_surface(face); }
int LimitSurface::sub_patch_count(int face) const {
  if (!has_surface(face)) return 0;
  const int n = impl_->sizes[std::size_t(face)];
  return n == 4 ? 1 : n;
}
int LimitSurface::approx_level() const { return impl_->level; }
bool LimitSurface::adaptive() const { return impl_->adaptive; }

namespace {
void check_patch(const LimitSurface& s, int face, int sub_patch, float u, float v) {
  if (face < 0 || face >= s.face_count()) bad_query("face " + std::to_string(face) + " is out of range");
  if (!s.has_surface(face)) bad_query("face " + std::to_string(face) + " has no surface (hole)");
  if (sub_patch < 0 || sub_patch >= s.sub_patch_count(face))
    bad_query("face " + std::to_string(face) + " has no sub-patch " + std::to_string(sub_patch));
  check_coord(u, "u");
  check_coord(v, "v");
}
}  // namespace

SurfacePoint LimitSurface::evaluate(int face, int sub_patch, float u, float v) const {
  check_patch(*this, face, sub_patch, u, v);
  const Impl& m = *impl_;
  const double s = u, t = v;
  const Raw r = m.raw(face, sub_patch, s, t);
  SharedPoint sh;
  if (!m.owned(face, sub_patch, s, t, sh)) return m.to_point(face, sub_patch, s, t, r);
  return {sh.position, glm::vec3(r.ds), glm::vec3(r.dt), sh.normal};
}

SurfacePoint LimitSurface::evaluate_unowned(int face, int sub_patch, float u, float v) const {
  check_patch(*this, face, sub_patch, u, v);
  const Raw r = impl_->raw(face, sub_patch, u, v);
  return impl_->to_point(face, sub_patch, u, v, r);
}

SurfacePoint LimitSurface::evaluate_triangle(int face, float u, float v, float w) const {
  if (face < 0 || face >= face_count()) bad_query("face " + std::to_string(face) + " is out of range");
  if (!has_surface(face)) bad_query("face " + std::to_string(face) + " has no surface (hole)");
  if (impl_->sizes[std::size_t(face)] != 3) bad_query("face " + std::to_string(face) + " is not a triangle");
  check_coord(u, "u");
  check_coord(v, "v");
  check_coord(w, "w");
  const Impl& m = *impl_;
  const double du = u, dv = v;
  const TriangleLocation tm = triangle_location(du, dv);
  const Raw r = m.raw(face, tm.sub, tm.s, tm.t);
  const glm::dvec3 pu = r.ds * tm.ds_du + r.dt * tm.dt_du, pv = r.ds * tm.ds_dv + r.dt * tm.dt_dv;
  SharedPoint sh;
  bool is_shared = true;
  if (du == 0.0 && dv == 0.0)
    sh = m.corner(face, 0);
  else if (du == 1.0)
    sh = m.corner(face, 1);
  else if (dv == 1.0)
    sh = m.corner(face, 2);
  else if (dv == 0.0)
    sh = m.cage_edge(face, 0, du);  // corner 0 -> 1
  else if (du + dv == 1.0)
    sh = m.cage_edge(face, 1, dv);  // corner 1 -> 2 (w = 0)
  else if (du == 0.0)
    sh = m.cage_edge(face, 2, 1.0 - dv);  // corner 2 -> 0
  else
    is_shared = false;
  if (is_shared) return {sh.position, glm::vec3(pu), glm::vec3(pv), sh.normal};
  glm::dvec3 n = m.normal_of(pu, pv);
  if (n == glm::dvec3(0.0)) n = m.normal_at(face, tm.sub, tm.s, tm.t, r);
  return {glm::vec3(r.p), glm::vec3(pu), glm::vec3(pv), glm::vec3(n)};
}

LimitSurface::TriangleLocation LimitSurface::triangle_location(double u, double v) {
  const double b[3] = {(1.0 - u) - v, u, v};
  int k = 0;
  if (b[1] > b[k]) k = 1;
  if (b[2] > b[k]) k = 2;
  const double x = b[(k + 1) % 3], y = b[(k + 2) % 3], d = x - y;
  const double q = 3.0 + 2.0 * d;
  const double s = std::clamp(12.0 * x / (q + std::sqrt(std::max(0.0, q * q - 24.0 * x))), 0.0, 1.0);
  const double t = std::clamp(s - 2.0 * d, 0.0, 1.0);
  // J = d(x,y)/d(s,t); K = J^-1 = d(s,t)/d(x,y); M = d(x,y)/d(u,v) depends on k.
  const double j00 = 0.5 - t / 6.0, j01 = -s / 6.0, j10 = -t / 6.0, j11 = 0.5 - s / 6.0;
  const double det = j00 * j11 - j01 * j10;  // >= 1/12 on the unit square
  const double k00 = j11 / det, k01 = -j01 / det, k10 = -j10 / det, k11 = j00 / det;
  static constexpr double M[3][2][2] = {{{1, 0}, {0, 1}}, {{0, 1}, {-1, -1}}, {{-1, -1}, {1, 0}}};
  const auto& m = M[k];
  return {k,
          s,
          t,
          k00 * m[0][0] + k01 * m[1][0],
          k00 * m[0][1] + k01 * m[1][1],
          k10 * m[0][0] + k11 * m[1][0],
          k10 * m[0][1] + k11 * m[1][1]};
}

LimitSurface::SubPatchLocation LimitSurface::fan_location(int n, int k, double u, double v) {
  // In the plane where vertex k = (0,0), vertex k+1 = (2,0) and the centre = (1,1), the triangle's point
  // is (x, y) = (2u + v, v). Sub-patch k is the unit square on vertex k, the midpoint (1,0) and the
  // centre; sub-patch k+1 meets it along x = 1 and is turned a quarter: its (s, t) = (y, 2 - x).
  const double x = 2.0 * u + v;
  if (x <= 1.0) return {k, x, v};
  return {(k + 1) % n, v, 2.0 - x};
}

SurfacePoint LimitSurface::evaluate_fan(int face, int triangle, float u, float v, float w) const {
  if (face < 0 || face >= face_count()) bad_query("face " + std::to_string(face) + " is out of range");
  if (!has_surface(face)) bad_query("face " + std::to_string(face) + " has no surface (hole)");
  const int n = impl_->sizes[std::size_t(face)];
  if (n == 4) bad_query("face " + std::to_string(face) + " is a quad (it has no fan)");
  if (triangle < 0 || triangle >= n)
    bad_query("face " + std::to_string(face) + " has no fan triangle " + std::to_string(triangle));
  check_coord(u, "u");
  check_coord(v, "v");
  check_coord(w, "w");
  const Impl& m = *impl_;
  const double du = u, dv = v;
  const SubPatchLocation l = fan_location(n, triangle, du, dv);
  const Raw r = m.raw(face, l.sub, l.s, l.t);
  // Chain rule through the affine map: (s,t) = (2u + v, v) or (v, 2 - 2u - v).
  const bool left = l.sub == triangle;
  const glm::dvec3 pu = left ? 2.0 * r.ds : -2.0 * r.dt, pv = left ? r.ds + r.dt : r.ds - r.dt;
  SharedPoint sh;
  if (dv == 0.0) {  // the cage edge
    if (du == 0.0)
      sh = m.corner(face, triangle);
    else if (du == 1.0)
      sh = m.corner(face, (triangle + 1) % n);
    else
      sh = m.cage_edge(face, triangle, du);
  } else if (dv == 1.0) {
    sh = m.shared(face, 0, 1.0, 1.0);  // the centre, as evaluate() gives it
  } else {
    return m.to_point(face, l.sub, l.s, l.t, Raw{r.p, pu, pv}, r);
  }
  return {sh.position, glm::vec3(pu), glm::vec3(pv), sh.normal};
}

LimitSurface::PatchFacts LimitSurface::patch_at_face_frame(int face, int sub, float u, float v) const {
  TESSERA_CHECK(impl_->adaptive, "LimitSurface::patch_at_face_frame: the adaptive method only");
  if (!has_surface(face)) bad_query("face " + std::to_string(face) + " has no surface");
  const int n = impl_->sizes[std::size_t(face)];
  const double du = std::clamp(double(u), 0.0, 1.0), dv = std::clamp(double(v), 0.0, 1.0);
  if (n == 4) return impl_->far->patch_at(face, 0, du, dv);
  if (n == 3) {
    const TriangleLocation tm = triangle_location(du, dv);
    return impl_->far->patch_at(face, tm.sub, tm.s, tm.t);
  }
  const SubPatchLocation l = fan_location(n, std::clamp(sub, 0, n - 1), du, dv);
  return impl_->far->patch_at(face, l.sub, std::clamp(l.s, 0.0, 1.0), std::clamp(l.t, 0.0, 1.0));
}

LimitSurface::PatchCounts LimitSurface::patch_counts() const {
  TESSERA_CHECK(impl_->adaptive, "LimitSurface::patch_counts: the adaptive method only");
  return impl_->far->counts();
}

ReferenceSample LimitSurface::sample_reference(int face, int sub_patch, double u, double v) const {
  check_patch(*this, face, sub_patch, float(u), float(v));
  const Raw r = impl_->raw(face, sub_patch, u, v);
  return {r.p, impl_->normal_at(face, sub_patch, u, v, r)};
}

glm::dvec3 LimitSurface::bounds_min() const { return impl_->lo; }
glm::dvec3 LimitSurface::bounds_max() const { return impl_->hi; }
double LimitSurface::bounding_box_diagonal() const { return glm::length(impl_->hi - impl_->lo); }

std::size_t LimitSurface::memory_bytes() const {
  const Impl& m = *impl_;
  return m.patch_points.capacity() * sizeof(double) + m.surfaces.capacity() * sizeof(Surface) +
         m.pp_offset.capacity() * sizeof(std::size_t) + m.edge_owner.capacity() * sizeof(Impl::EdgeOwner) +
         m.vertex_limit.capacity() * sizeof(SharedPoint) +
         (m.sizes.capacity() + m.corner_base.capacity() + m.corners.capacity()) * sizeof(int) +
         (m.far ? m.far->memory_bytes() : 0) + m.by_far.capacity();
}

}  // namespace tessera
