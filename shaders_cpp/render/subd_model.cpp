#include "shaders_cpp/render/subd_model.h"
#include "shaders_cpp/cage/boundary_rule.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "shaders_cpp/cage/bounding_box.h"
#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/cage/corner_ring.h"
#include "shaders_cpp/cage/one_line.h"
#include "shaders_cpp/render/strayed_faces.h"
#include "shaders_cpp/subdiv/control_point_prepass.h"
#include "shaders_cpp/subdiv/pn_patch.h"
#include "tessellator/check.h"

namespace tessera {
namespace {

// Seconds since the last lap (or construction).
class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// Removes the patches of faces `keep` rejects, with their IA indices; returns how many went.
template <class Keep>
int remove_patches(PatchGroup& g, Keep&& keep) {
  const std::size_t cp = std::size_t(g.control_points);
  std::size_t kept = 0;
  for (std::size_t p = 0; p < g.patches.size(); ++p) {
    if (!keep(g.patches[p])) continue;
    g.patches[kept] = g.patches[p];
    std::copy_n(g.indices.begin() + std::ptrdiff_t(p * cp), cp, g.indices.begin() + std::ptrdiff_t(kept * cp));
    ++kept;
  }
  const int removed = int(g.patches.size() - kept);
  g.patches.resize(kept);
  g.indices.resize(kept * cp);
  return removed;
}

// Per face, the box of every vertex of the faces around its corners: the limit surface of the face is
// a convex combination of them (Catmull-Clark's rules, creased or not, have non-negative weights).
std::vector<Box3> face_ring_boxes(std::span<const glm::vec3> positions, const Topology& t) {
  std::vector<Box3> boxes(std::size_t(t.face_count()));
  for (int f = 0; f < t.face_count(); ++f) {
    Box3 b = Box3::empty();
    for (int k = 0; k < t.face_size(f); ++k) {
      const int v = t.origin(t.face_half_edge(f) + k);
      for (const int h : t.ring(v))
        for (int g = t.face(h), j = 0; j < t.face_size(g); ++j) {
          b.extend(positions[std::size_t(t.origin(t.face_half_edge(g) + j))]);
        }
    }
    boxes[std::size_t(f)] = b;
  }
  return boxes;
}

}  // namespace

namespace {

// The creased edges (not on the boundary) and sharp corners (of used vertices) whose sharpness `pick`
// takes: how many, how many of the edges are semi-sharp, and the highest sharpness among them.
struct TagCount {
  int creased = 0, semi_sharp = 0, corners = 0;
  float most = 0.0f;
  int total() const { return creased + corners; }
};
// `drawn_edge` / `drawn_vertex`: elements whose tags the scheme draws whatever their sharpness.
template <class Pick, class Edge = bool (*)(int), class Vertex = bool (*)(int)>
TagCount count_tags(
    const Topology& t, Pick&& pick, Edge&& drawn_edge = [](int) { return false; },
    Vertex&& drawn_vertex = [](int) { return false; }) {
  TagCount c;
  for (int e = 0; e < t.edge_count(); ++e)
    if (const float s = t.edge_sharpness(e); !t.is_boundary_edge(e) && pick(s) && !drawn_edge(e)) {
      ++c.creased;
      if (s < kSharpnessInfinite) ++c.semi_sharp;
      c.most = std::max(c.most, s);
    }
  for (int v = 0; v < t.vertex_count(); ++v)
    if (const float s = t.corner_sharpness(v); pick(s) && !t.is_isolated(v) && !drawn_vertex(v))
      ++c.corners, c.most = std::max(c.most, s);
  return c;
}

// "12 creased edges (12 semi-sharp) and 1 sharp corner"; the semi-sharp count when asked.
std::string tag_phrase(const TagCount& c, bool semi_sharp) {
  std::string what;
  if (c.creased > 0)
    what = std::to_string(c.creased) + " creased edge" + (c.creased == 1 ? "" : "s") +
           (semi_sharp && c.semi_sharp > 0 ? " (" + std::to_string(c.semi_sharp) + " semi-sharp)" : "");
  if (c.corners > 0)
    what += (what.empty() ? "" : " and ") + std::to_string(c.corners) + " sharp corner" + (c.corners == 1 ? "" : "s");
  return what;
}

// One line when `scheme` draws a surface without some of the creases and corners the cage tags, so no
// approximation goes unsaid: pn and flat draw them all smooth; acc those of sharpness below
// kCutSharpness (subd_patches.cpp cuts and blends the others); gregory and bspline those below it on
// n-gons only (their triangles and quads with a tagged corner are fitted to the limit, limit_fit.h,
// which has every tag); adaptive draws semi-sharp
// sharpness above its isolation level as that level (Far clamps it to the levels left); exact honours
// every one.
std::optional<std::string> dropped_sharpness(const Cage& cage, const Topology& t, Scheme scheme, int isolation) {
  if (scheme == Scheme::exact) return std::nullopt;
  if (scheme == Scheme::adaptive) {
    const TagCount c = count_tags(t, [&](float s) { return s > float(isolation) && s < kSharpnessInfinite; });
    if (c.total() == 0) return std::nullopt;
    const int needed = std::min(kMaxIsolation, int(std::ceil(c.most)));
    return cage.name + ": --scheme adaptive --isolation " + std::to_string(isolation) + " draws the cage's " +
           tag_phrase(c, false) + " of sharpness above " + std::to_string(isolation) + " as sharpness " +
           std::to_string(isolation) + "; " +
           (needed > isolation ? "--isolation " + std::to_string(needed) + " or " : std::string()) +
           "--scheme exact honours " + (c.total() == 1 ? "it" : "them");
  }
  const bool per_face = scheme == Scheme::acc || scheme == Scheme::gregory || scheme == Scheme::bspline;
  const float below = per_face ? kCutSharpness : INFINITY;
  // Tags at a face build_patches fits to the limit are drawn.
  auto fitted_face = [&](int f) { return fits_limit(cage, t, scheme, f); };
  auto fitted_edge = [&](int e) {
    const std::array<int, 2> h = t.edge_half_edges(e);
    return fitted_face(t.face(h[0])) || (h[1] >= 0 && fitted_face(t.face(h[1])));
  };
  auto fitted_vertex = [&](int v) {
    for (const int h : t.ring(v))
      if (fitted_face(t.face(h))) return true;
    return false;
  };
  const TagCount c = count_tags(
      t, [&](float s) { return s > 0.0f && s < below; }, fitted_edge, fitted_vertex);
  if (c.total() == 0) return std::nullopt;
  std::string what = tag_phrase(c, !per_face);
  if (per_face) what += " of sharpness below " + float_text(kCutSharpness);
  return cage.name + ": --scheme " + to_string(scheme) + " draws the cage's " + what +
         " smooth; --scheme adaptive or exact honours " + (c.total() == 1 ? "it" : "them");
}

}  // namespace

SubdModel make_subd_model(Cage cage, Scheme scheme, int isolation, const PrepareStep& step) {
  auto starting = [&](const char* name) {
    if (step) step(name);
  };
  SubdModel m;
  Stopwatch clock;
  starting("topology");
  m.cage = std::move(cage);
  m.topology = std::make_unique<Topology>(m.cage);
  m.times.topology_s = clock.lap();
  starting("patches");
  m.patches = build_patches(m.cage, *m.topology, scheme);
  if (auto w = dropped_sharpness(m.cage, *m.topology, scheme, isolation)) m.cage.warnings.push_back(std::move(*w));
  m.times.patches_s = clock.lap();
  starting("pre-pass");
  if (scheme == Scheme::pn) m.normals = vertex_normals(m.cage, m.cage.positions, *m.topology);
  m.precomputed = precompute_control_points(m.patches, m.cage.positions);
  m.times.precompute_s = clock.lap();
  starting("fold check");
  // Faces whose masks' patch folds are fitted to the limit (strayed_faces.h).
  if (const StrayedFaces strayed = find_strayed_faces(m); strayed.count() > 0) {
    m.patches = build_patches(m.cage, *m.topology, scheme, strayed.faces);
    m.precomputed = precompute_control_points(m.patches, m.cage.positions);
  }
  m.times.fold_check_s = clock.lap();
  if (uses_limit_surface(scheme)) {
    starting("limit surface");
    int pole = 0;  // the vertex of highest valence
    for (int v = 1; v < m.topology->vertex_count(); ++v)
      if (m.topology->valence(v) > m.topology->valence(pole)) pole = v;
    if (m.topology->vertex_count() > 0 && m.topology->valence(pole) > kCostlyExactValence)
      m.cage.warnings.push_back(m.cage.name + ": vertex " + std::to_string(pole) + " has valence " +
                                std::to_string(m.topology->valence(pole)) + "; --scheme " + to_string(scheme) +
                                " builds the surface around it in about " +
                                float_text(float(std::round(exact_build_seconds(m.topology->valence(pole)) * 10.0) / 10.0)) +
                                " s (the cost grows as valence^2.4; gregory draws it at once)");
    m.limit = std::make_unique<LimitSurface>(
        scheme == Scheme::adaptive ? LimitSurface::create_adaptive(m.cage, isolation) : LimitSurface::create(m.cage));
    // Faces OpenSubdiv gives no surface besides holes: boundary faces under `t interpolateboundary`
    // none. They draw nothing, like holes.
    auto has_surface = [&](const SubdPatch& p) { return m.limit->has_surface(p.face); };
    for (PatchGroup* g : {&m.patches.quads, &m.patches.tris}) m.patches.holes += remove_patches(*g, has_surface);
    m.ring_boxes = face_ring_boxes(m.cage.positions, *m.topology);
    m.times.limit_s = clock.lap();
  } else if (m.cage.tags.boundary == BoundaryInterpolation::none) {
    // The per-face schemes honour `none` as OpenSubdiv does: those boundary faces draw nothing.
    const std::vector<bool> none = faces_without_surface(m.cage, *m.topology);
    auto has_surface = [&](const SubdPatch& p) { return !none[std::size_t(p.face)]; };
    for (PatchGroup* g : {&m.patches.quads, &m.patches.tris}) m.patches.holes += remove_patches(*g, has_surface);
  }
  return m;
}

void set_pose(SubdModel& m, RigPose pose) {
  TESSERA_CHECK(m.rig, "set_pose: the model of", m.cage.name, "has no rig");
  m.posed_positions = pose_positions(*m.rig, pose);
  m.pose = std::move(pose);
  // The passes before the draw see the surface the vertex shader will output: normals and ring boxes
  // from the posed positions.
  if (!m.normals.empty()) m.normals = vertex_normals(m.cage, m.posed_positions, *m.topology);
  m.precomputed = precompute_control_points(m.patches, m.posed_positions);
  if (m.limit) {
    // The limit surface keeps its topology (Bfr's surfaces, Far's refinement and patch table) and moves
    // its points: the bits a surface built from the posed cage would have.
    m.limit->repose(m.posed_positions);
    m.ring_boxes = face_ring_boxes(m.posed_positions, *m.topology);
  }
}

Cage load_cage(const std::string& path, const GltfSelection& selection) {
  return is_gltf_path(path) ? load_gltf_cage(path, selection).cage : load_obj_cage(path);
}

SubdModel load_subd_model(const std::string& path, Scheme scheme, const GltfSelection& selection, int isolation,
                          const PrepareStep& step) {
  if (step) step("reading");
  Stopwatch clock;
  if (!is_gltf_path(path)) {
    Cage cage = load_obj_cage(path);
    const double read_s = clock.lap();
    SubdModel m = make_subd_model(std::move(cage), scheme, isolation, step);
    m.times.read_s = read_s;
    return m;
  }
  GltfCage g = load_gltf_cage(path, selection);
  const double read_s = clock.lap();
  SubdModel m = make_subd_model(std::move(g.cage), scheme, isolation, step);
  m.times.read_s = read_s;
  m.rig = std::move(g.rig);
  m.material = std::move(g.maps);
  return m;
}

std::string scheme_refusal(const Cage& cage, Scheme scheme, bool displaced) {
  if (displaced && (scheme == Scheme::flat || scheme == Scheme::pn))
    return std::string("--scheme ") + to_string(scheme) +
           " cannot be displaced (its patches carry no 1-ring for the shared normals)";
  for (int f = 0; f < cage.face_count(); ++f) {
    const int n = cage.face_sizes[std::size_t(f)];
    const bool refused = scheme == Scheme::pn    ? n > 4
                         : scheme == Scheme::acc ? n != 4
                         : (scheme == Scheme::flat || scheme == Scheme::exact || scheme == Scheme::adaptive)
                             ? n > kMaxPatchControlPoints
                             : false;
    if (refused)
      return "face " + std::to_string(f) + " has " + std::to_string(n) + " sides, which --scheme " + to_string(scheme) +
             " does not draw";
  }
  return {};
}

}  // namespace tessera
