// A cage ready to draw with one scheme: the cage, its topology, its patches (and, for `exact` and
// `adaptive`, the limit surface; for `pn`, the per-vertex normals), and the calls that run it through the pipeline as
// stream output or as a render.
//
// Contract: load_subd_model throws CageError (one line naming the file and element) for files that
// cannot be read, cages that fail validation, and faces the scheme cannot handle. The draws run the
// quad-domain patches, then the tri-domain ones; within each, patches are in face order.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "pipeline/stream_output.h"
#include "shaders_cpp/cage/cage.h"
#include "shaders_cpp/cage/topology.h"
#include "shaders_cpp/gltf/gltf_cage.h"
#include "shaders_cpp/render/subd_shaders.h"
#include "shaders_cpp/subdiv/limit_surface.h"
#include "shaders_cpp/subdiv/subd_patches.h"

namespace tessera {

// Where a model's preparation spent its time (steady clock, seconds): for `bench load` and -v.
struct PrepareTimes {
  double read_s = 0;        // the file to a Cage (load_subd_model only)
  double topology_s = 0;    // half-edges, rings, tags
  double patches_s = 0;     // build_patches: per face its patch, per topology combination its table
  double fold_check_s = 0;  // find_strayed_faces, and the rebuild when a face folds
  double precompute_s = 0;  // the control-point pre-pass and per-vertex normals
  double limit_s = 0;       // exact and adaptive: the limit surface
};

struct SubdModel {
  Cage cage;  // the rest pose
  std::unique_ptr<Topology> topology;
  SubdPatches patches;
  std::unique_ptr<LimitSurface> limit;  // exact and adaptive only (of the posed cage)
  std::vector<glm::vec3> normals;       // pn only: per cage vertex (pn_patch.h), of the posed cage
  std::vector<Box3> ring_boxes;         // exact and adaptive: per face, the box of its 1-ring (culling)
  std::vector<glm::vec3> precomputed;   // the control-point pre-pass's rows (1-rings over 32), posed
  // Animation (glTF): the rig, and once set_pose ran, the pose the vertex shader applies and its
  // result over every control point, for the passes that need positions before the draw.
  std::shared_ptr<const CageRig> rig;
  std::optional<RigPose> pose;
  std::vector<glm::vec3> posed_positions;
  // glTF: the material's normal and displacement maps (the CLI's defaults for --displacement).
  GltfMaterialMaps material;
  // Drawn from both sides (--two-sided): a draw setting kept with the model because every pass derives
  // its rasterizer state and pixel shaders' FaceSides from the model (subd_render.h).
  bool two_sided = false;
  PrepareTimes times;

  // The control points as the vertex shader outputs them (the posed cage, or the cage).
  const std::vector<glm::vec3>& positions() const { return pose ? posed_positions : cage.positions; }
  // What the input assembler reads: bind positions when posed, else the cage's.
  std::span<const glm::vec3> vertex_buffer() const {
    return pose ? std::span<const glm::vec3>(rig->bind_positions) : std::span<const glm::vec3>(cage.positions);
  }
  // The vertex shader: the pose, if any; the normals as a second vertex stream.
  SubdVS vertex_shader() const {
    SubdVS vs;
    vs.normals = normals;
    if (pose) vs.rig = rig.get(), vs.pose = &*pose;
    return vs;
  }
};

// Called as each step of a model's preparation starts, with its name ("reading", "topology",
// "patches", "fold check", "pre-pass", "limit surface"), for progress output; it cannot change the model.
using PrepareStep = std::function<void(const char* step)>;

// The cage of an OBJ file, or of a glTF one (`.gltf`, `.glb`; its rest pose).
Cage load_cage(const std::string& path, const GltfSelection& selection = {});
// Reads an OBJ cage, or a glTF one (`.gltf`, `.glb`: gltf_cage.h with `selection`, its rig kept).
// `isolation`: the adaptive scheme's level (1..kMaxIsolation; others ignore it).
SubdModel load_subd_model(const std::string& path, Scheme scheme, const GltfSelection& selection = {},
                          int isolation = kDefaultIsolation, const PrepareStep& step = {});
SubdModel make_subd_model(Cage cage, Scheme scheme, int isolation = kDefaultIsolation,
                          const PrepareStep& step = {});
// Why `scheme` would refuse the cage (displaced or not), in words, or empty when it draws it: the
// faces it cannot take (pn: more than 4 sides; acc: other than 4; flat, exact, adaptive: more than
// kMaxPatchControlPoints) and, displaced, the schemes whose patches carry no 1-ring (flat, pn). What
// make_subd_model and displacement_texcoords refuse with a CageError, answered without building, so a
// caller can offer only the schemes that work (the viewer's list).
std::string scheme_refusal(const Cage& cage, Scheme scheme, bool displaced);

// Poses an animated model: the vertex shader will apply `pose`, and what depends on positions before
// the draw (PN normals, the exact limit surface, culling boxes, the control-point pre-pass) follows it.
// The model must have a rig.
void set_pose(SubdModel& m, RigPose pose);

// Adds one draw's report to a total: statistics and stage times summed, geometry peak the largest.
inline void add_draw_report(DrawReport& total, const DrawReport& part) {
  total.statistics += part.statistics;
  total.patches_culled += part.patches_culled;
  total.patches_back_culled += part.patches_back_culled;
  total.times += part.times;
  total.memory.geometry_peak_bytes = std::max(total.memory.geometry_peak_bytes, part.memory.geometry_peak_bytes);
}

// The shaders and state of each non-empty patch group (quad domain first, then tri), handed to
// draw(group, tessellator_state, hs, ds) -> DrawResult; stops at the first error. Returns the
// statistics and stage times summed, and the largest geometry peak.
template <class Draw>
DrawResult for_each_patch_group(const SubdModel& m, const SubdFactors& factors, const PatchCull& cull,
                                ts::Partitioning partitioning, Draw&& draw) {
  DrawResult total;
  for (const PatchGroup* g : {&m.patches.quads, &m.patches.tris}) {
    if (g->patches.empty()) continue;
    const bool tri = g->domain == ts::Domain::tri;
    const TessellatorState ts{g->domain, partitioning, ts::OutputPrimitive::triangle_cw};
    const SubdHS hs{g->patches, m.patches.tables, factors, tri, m.ring_boxes, partitioning, m.precomputed, cull};
    const SubdDS ds{g->patches, m.limit.get(), m.cage.tags.left_handed, tri};
    DrawResult r = draw(*g, ts, hs, ds);
    if (!r.ok()) return r;
    add_draw_report(total.report, r.report);
  }
  return total;
}

// Runs IA..DS over both patch groups and hands each patch's SurfaceSamples to sink(PatchOutput, group);
// without a cull policy, every patch.
template <class Sink>
DrawResult stream_subd(Device& device, const SubdModel& m, const SubdFactors& factors, const PatchCull& cull,
                       ts::Partitioning partitioning, Sink&& sink) {
  return for_each_patch_group(m, factors, cull, partitioning,
                              [&](const PatchGroup& g, const TessellatorState& ts, const SubdHS& hs, const SubdDS& ds) {
                                const StreamDraw<glm::vec3, SubdVS, SubdHS, SubdDS> d{
                                    m.vertex_buffer(), g.indices, g.control_points, m.vertex_shader(), hs, ds, ts};
                                return stream_out(device, d, [&](const PatchOutput<SurfaceSample>& p) { sink(p, g); });
                              });
}

template <class Sink>
DrawResult stream_subd(Device& device, const SubdModel& m, const SubdFactors& factors, ts::Partitioning partitioning,
                       Sink&& sink) {
  return stream_subd(device, m, factors, PatchCull{}, partitioning, std::forward<Sink>(sink));
}

}  // namespace tessera
