#include "shaders_cpp/subdiv/far_patches.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "shaders_cpp/subdiv/osd_refiner.h"

namespace tessera::osd_detail {

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
  std::vector<glm::dvec3> points;               // base vertices, refined vertices, local points
  std::unordered_map<int, int> first_ptex_face;  // per chosen face
  std::vector<int> sizes;                        // per base face
};

FarPatches::FarPatches(const Cage& cage, int level, const std::vector<int>& faces) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.refiner = build_osd_refiner(cage);
  m.sizes = cage.face_sizes;
  far::PatchTableFactory::Options options(level);
  options.SetEndCapType(far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  options.SetPatchPrecision<double>();
  options.useInfSharpPatch = true;
  const far::ConstIndexArray selected(faces.data(), int(faces.size()));
  m.refiner->RefineAdaptive(options.GetRefineAdaptiveOptions(), selected);
  m.table.reset(far::PatchTableFactory::Create(*m.refiner, options, selected));
  if (!m.table) throw CageError(cage_label(cage) + ": OpenSubdiv gave no patch table");

  // Every refined vertex and local (end cap) point as a stencil of the base vertices.
  far::StencilTableFactoryReal<double>::Options so;
  so.generateIntermediateLevels = true;
  so.generateOffsets = true;
  std::unique_ptr<const far::StencilTableReal<double>> refined(
      far::StencilTableFactoryReal<double>::Create(*m.refiner, so));
  std::unique_ptr<const far::StencilTableReal<double>> all;
  if (const auto* local = m.table->GetLocalPointStencilTable<double>())
    all.reset(far::StencilTableFactoryReal<double>::AppendLocalPointStencilTable(*m.refiner, refined.get(), local));
  const far::StencilTableReal<double>& stencils = all ? *all : *refined;
  const int nv = cage.vertex_count();
  m.points.resize(std::size_t(nv) + std::size_t(stencils.GetNumStencils()));
  for (int v = 0; v < nv; ++v) m.points[std::size_t(v)] = glm::dvec3(cage.positions[std::size_t(v)]);
  const auto& sizes = stencils.GetSizes();
  const auto& offsets = stencils.GetOffsets();
  const auto& indices = stencils.GetControlIndices();
  const auto& weights = stencils.GetWeights();
  for (int i = 0; i < stencils.GetNumStencils(); ++i) {
    glm::dvec3 p(0.0);
    for (int j = 0; j < sizes[std::size_t(i)]; ++j) {
      const std::size_t e = std::size_t(offsets[std::size_t(i)] + j);
      p += weights[e] * m.points[std::size_t(indices[e])];
    }
    m.points[std::size_t(nv + i)] = p;
  }
  m.map = std::make_unique<far::PatchMap>(*m.table);
  const far::PtexIndices ptex(*m.refiner);
  for (int f : faces) m.first_ptex_face[f] = ptex.GetFaceId(f);
}

FarPatches::~FarPatches() = default;

FarPatches::Point FarPatches::evaluate(int face, int k, double s, double t) const {
  const Impl& m = *impl_;
  const auto it = m.first_ptex_face.find(face);
  if (it == m.first_ptex_face.end())
    throw std::logic_error("FarPatches: face " + std::to_string(face) + " was not chosen");
  const int ptex_face = it->second + (m.sizes[std::size_t(face)] == 4 ? 0 : k);
  const far::PatchTable::PatchHandle* h = m.map->FindPatch(ptex_face, s, t);
  if (!h)
    throw std::logic_error("FarPatches: no patch at face " + std::to_string(face) + " (" + std::to_string(s) + ", " +
                           std::to_string(t) + ")");
  double w[20], ws[20], wt[20];
  m.table->EvaluateBasis(*h, s, t, w, ws, wt);
  const far::ConstIndexArray cvs = m.table->GetPatchVertices(*h);
  Point r{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
  for (int i = 0; i < cvs.size(); ++i) {
    const glm::dvec3& c = m.points[std::size_t(cvs[i])];
    r.p += w[i] * c;
    r.ds += ws[i] * c;
    r.dt += wt[i] * c;
  }
  return r;
}

std::size_t FarPatches::memory_bytes() const { return impl_->points.capacity() * sizeof(glm::dvec3); }

}  // namespace tessera::osd_detail
