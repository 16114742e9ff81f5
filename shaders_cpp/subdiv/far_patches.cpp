#include "shaders_cpp/subdiv/far_patches.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "shaders_cpp/subdiv/osd_refiner.h"
#include "shaders_cpp/subdiv/single_crease_basis.h"
#include "tessellator/check.h"

namespace tessera::subdiv {

namespace far = osd::Far;

std::vector<int> needs_far_patches(const Topology& t) {
  std::vector<int> faces;
  for (int f = 0; f < t.face_count(); ++f) {
    if (t.is_hole(f)) continue;
    bool valence2 = false, boundary = false, sharp = false;
    for (int k = 0; k < t.face_size(f); ++k) {
      const int v = t.origin(t.face_half_edge(f) + k);
      valence2 |= !t.is_boundary_vertex(v) && t.vertex_face_count(v) == 2;
      boundary |= t.is_boundary_vertex(v);
      sharp |= t.has_sharpness_at(v);
    }
    if (valence2 && boundary && sharp) faces.push_back(f);
  }
  return faces;
}

struct FarPatches::Impl {
  std::unique_ptr<far::TopologyRefiner> refiner;
  std::unique_ptr<far::PatchTable> table;
  std::unique_ptr<far::PatchMap> map;
  bool single_crease = false;      // the table has a sharpness per patch
  std::vector<glm::dvec3> points;  // base vertices, refined vertices, local points
  std::string label;               // the cage's, for errors
  // Every refined vertex and local point as a stencil of the base vertices: made for the points, and
  // kept once repose() needs it again (an animated cage), so a static one does not hold it.
  std::unique_ptr<const far::StencilTableReal<double>> stencils;

  void make_stencils() {
    far::StencilTableFactoryReal<double>::Options so;
    so.generateIntermediateLevels = true;
    so.generateOffsets = true;
    std::unique_ptr<const far::StencilTableReal<double>> refined(
        far::StencilTableFactoryReal<double>::Create(*refiner, so));
    if (const auto* local = table->GetLocalPointStencilTable<double>())
      stencils.reset(
          far::StencilTableFactoryReal<double>::AppendLocalPointStencilTable(*refiner, refined.get(), local));
    else
      stencils = std::move(refined);
  }
  // The points of `positions` (one per base vertex) through the stencils.
  void place(std::span<const glm::vec3> positions) {
    const std::size_t nv = positions.size();
    points.resize(nv + std::size_t(stencils->GetNumStencils()));
    for (std::size_t v = 0; v < nv; ++v) points[v] = glm::dvec3(positions[v]);
    const auto& lengths = stencils->GetSizes();
    const auto& offsets = stencils->GetOffsets();
    const auto& indices = stencils->GetControlIndices();
    const auto& weights = stencils->GetWeights();
    for (int i = 0; i < stencils->GetNumStencils(); ++i) {
      glm::dvec3 p(0.0);
      for (int j = 0; j < lengths[std::size_t(i)]; ++j) {
        const std::size_t e = std::size_t(offsets[std::size_t(i)] + j);
        p += weights[e] * points[std::size_t(indices[e])];
      }
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw CageError(label + ": no finite limit surface (vertex positions that are not finite or overflow)");
      points[nv + std::size_t(i)] = p;
    }
  }
  std::vector<int> first_ptex_face;  // per base face; -1 where it has no patches
  std::vector<int> sizes;            // per base face

  const far::PatchTable::PatchHandle& find(int face, int k, double s, double t) const {
    const int first = face >= 0 && face < int(sizes.size()) ? first_ptex_face[std::size_t(face)] : -1;
    TESSERA_CHECK(first >= 0, "FarPatches: face", face, "has no patches");
    const far::PatchTable::PatchHandle* h = map->FindPatch(first + (sizes[std::size_t(face)] == 4 ? 0 : k), s, t);
    TESSERA_CHECK(h, "FarPatches: no patch at face", face, "s", s, "t", t);
    return *h;
  }
  // A regular patch's single crease (0: none). Far keeps a sharpness for end caps too; they ignore it.
  float sharpness(const far::PatchTable::PatchHandle& h) const {
    if (!single_crease || table->GetPatchArrayDescriptor(h.arrayIndex).GetType() != far::PatchDescriptor::REGULAR)
      return 0.0f;
    return table->GetSingleCreasePatchSharpnessValue(h);
  }
  AdaptivePatchKind kind(const far::PatchTable::PatchHandle& h) const {
    return kind_of(h.arrayIndex, sharpness(h), table->GetPatchParam(h));
  }
  AdaptivePatchKind kind_of(int array, float sharp, const far::PatchParam& param) const {
    if (table->GetPatchArrayDescriptor(array).GetType() != far::PatchDescriptor::REGULAR)
      return AdaptivePatchKind::end_cap;
    if (sharp > 0.0f) return AdaptivePatchKind::single_crease;
    return param.GetBoundary() ? AdaptivePatchKind::boundary : AdaptivePatchKind::regular;
  }
};

FarPatches::FarPatches(const Cage& cage, int level, const std::vector<int>& faces, bool single_crease)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.refiner = build_osd_refiner(cage);
  m.sizes = cage.face_sizes;
  m.single_crease = single_crease;
  far::PatchTableFactory::Options options{static_cast<unsigned>(level)};
  options.SetEndCapType(far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  options.SetPatchPrecision<double>();
  options.useInfSharpPatch = true;
  options.useSingleCreasePatch = single_crease;
  options.generateVaryingTables = false;
  options.generateLegacySharpCornerPatches = false;  // the true limit at smooth corners, as Bfr gives it
  const far::ConstIndexArray selected(faces.data(), int(faces.size()));
  m.refiner->RefineAdaptive(options.GetRefineAdaptiveOptions(), selected);
  m.table.reset(far::PatchTableFactory::Create(*m.refiner, options, selected));
  if (!m.table) throw CageError(cage_label(cage) + ": OpenSubdiv gave no patch table");

  m.label = cage_label(cage);
  m.make_stencils();
  m.place(cage.positions);
  m.stencils.reset();
  m.map = std::make_unique<far::PatchMap>(*m.table);
  const far::PtexIndices ptex(*m.refiner);
  m.first_ptex_face.assign(m.sizes.size(), -1);
  auto choose = [&](int f) {
    // Holes, and boundary faces under boundary interpolation "none", have no patches.
    const int first = ptex.GetFaceId(f);
    if (m.map->FindPatch(first, 0.5, 0.5)) m.first_ptex_face[std::size_t(f)] = first;
  };
  if (faces.empty())
    for (int f = 0; f < cage.face_count(); ++f) choose(f);
  for (int f : faces) choose(f);
}

FarPatches::~FarPatches() = default;

void FarPatches::repose(std::span<const glm::vec3> positions) {
  Impl& m = *impl_;
  TESSERA_CHECK_EQ(positions.size(), std::size_t(m.refiner->GetLevel(0).GetNumVertices()),
                   "FarPatches::repose: one position per cage vertex");
  if (!m.stencils) m.make_stencils();
  m.place(positions);
}

bool FarPatches::has_patches(int face) const {
  return face >= 0 && face < int(impl_->sizes.size()) && impl_->first_ptex_face[std::size_t(face)] >= 0;
}

FarPatches::Point FarPatches::evaluate(int face, int k, double s, double t) const {
  const Impl& m = *impl_;
  const far::PatchTable::PatchHandle& h = m.find(face, k, s, t);
  const far::PatchParam param = m.table->GetPatchParam(h);
  const far::ConstIndexArray cvs = m.table->GetPatchVertices(h);
  // Far scales derivatives by 2^depth; a non-quad's sub-face starts at depth 1, its (s,t) spanning the
  // sub-face: derivatives with respect to it are half that.
  double scale = param.NonQuadRoot() ? 0.5 : 1.0;
  Point r{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
  if (m.table->GetPatchArrayDescriptor(h.arrayIndex).GetType() == far::PatchDescriptor::REGULAR) {
    // B-spline and single-crease patches: two curves' tensor product, summed a row at a time.
    double u = s, v = t;
    param.Normalize(u, v);
    const float sharp = m.sharpness(h);
    const RegularCurves c =
        sharp > 0.0f ? single_crease_curves(std::countr_zero(unsigned(param.GetBoundary())), double(sharp), u, v)
                     : regular_patch_curves(param.GetBoundary(), u, v);
    for (int i = 0; i < 4; ++i) {
      if (c.t[i] == 0.0 && c.dt[i] == 0.0) continue;  // a folded phantom row (its indices may be none)
      glm::dvec3 row(0.0), drow(0.0);
      for (int j = 0; j < 4; ++j) {
        if (c.s[j] == 0.0 && c.ds[j] == 0.0) continue;  // a folded phantom column (its index may be none)
        const glm::dvec3& p = m.points[std::size_t(cvs[4 * i + j])];
        row += c.s[j] * p;
        drow += c.ds[j] * p;
      }
      r.p += c.t[i] * row;
      r.ds += c.t[i] * drow;
      r.dt += c.dt[i] * row;
    }
    scale *= double(1 << param.GetDepth());
    r.ds *= scale;
    r.dt *= scale;
    return r;
  }
  double w[20], ws[20], wt[20];
  m.table->EvaluateBasis(h, s, t, w, ws, wt);
  for (int i = 0; i < cvs.size(); ++i) {
    const glm::dvec3& c = m.points[std::size_t(cvs[i])];
    r.p += w[i] * c;
    r.ds += ws[i] * c;
    r.dt += wt[i] * c;
  }
  r.ds *= scale;
  r.dt *= scale;
  return r;
}

FarPatches::PatchInfo FarPatches::patch_at(int face, int k, double s, double t) const {
  const Impl& m = *impl_;
  const far::PatchTable::PatchHandle& h = m.find(face, k, s, t);
  return {m.kind(h), int(m.table->GetPatchParam(h).GetDepth())};
}

FarPatches::Counts FarPatches::counts() const {
  const Impl& m = *impl_;
  Counts c;
  for (int a = 0; a < m.table->GetNumPatchArrays(); ++a)
    for (int p = 0; p < m.table->GetNumPatches(a); ++p) {
      const far::PatchParam param = m.table->GetPatchParam(a, p);
      const float sharp = m.single_crease ? m.table->GetSingleCreasePatchSharpnessValue(a, p) : 0.0f;
      ++c.by_kind[int(m.kind_of(a, sharp, param))];
      ++c.by_level[std::min(15, int(param.GetDepth()))];
      ++c.total;
    }
  return c;
}

std::size_t FarPatches::memory_bytes() const {
  const Impl& m = *impl_;
  std::size_t cvs = 0;
  for (int a = 0; a < m.table->GetNumPatchArrays(); ++a)
    cvs += std::size_t(m.table->GetNumPatches(a)) *
           std::size_t(m.table->GetPatchArrayDescriptor(a).GetNumControlVertices());
  std::size_t stencils = 0;  // kept only once reposed
  // The points, and per patch its control point indices, PatchParam (8 bytes) and sharpness index.
  if (m.stencils)
    stencils =
        m.stencils->GetWeights().size() * sizeof(double) +
        (m.stencils->GetControlIndices().size() + m.stencils->GetSizes().size() + m.stencils->GetOffsets().size()) *
            sizeof(int);
  return m.points.capacity() * sizeof(glm::dvec3) + cvs * sizeof(int) +
         std::size_t(m.table->GetNumPatchesTotal()) * (8 + (m.single_crease ? sizeof(int) : 0)) +
         m.first_ptex_face.capacity() * sizeof(int) + stencils;
}

}  // namespace tessera::subdiv
