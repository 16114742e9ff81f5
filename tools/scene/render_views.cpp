#include "tools/scene/render_views.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "shaders_cpp/cage/bounding_box.h"
#include "shaders_cpp/debug/overlay.h"
#include "shaders_cpp/render/displaced_render.h"
#include "tools/scene/common.h"
#include "tools/scene/surface_weld.h"
#include "tools/verify/weld_check.h"
#include "tessellator/check.h"

namespace tessera::scene {
namespace {

// The depth slack of the cage's lines over the surface they lie on (in NDC depth): enough that a line
// on a crease the surface passes through is not hidden by it, small against the model's depth range.
constexpr float kCageDepthSlack = 1e-5f;

std::string fixed(float x, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, double(x));
  return buf;
}

template <class F>
std::vector<glm::vec3> sample_ramp(F&& color) {
  std::vector<glm::vec3> r(256);
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = color(float(i) / 255.0f);
  return r;
}

DrawResult draw_shaded(Device& device, const ViewInputs& in, Framebuffer& fb) {
  return render_surface(device, in.model, in.displacement, in.factors, in.cull, in.partitioning, SubdView::shaded,
                        in.view.camera, fb);
}

// A camera that sees the whole model and the view camera's position, from behind and above it, for
// the culled view: the view's frustum and what it culled, seen from outside.
SubdCamera overview_camera(const ViewInputs& in, int w, int h) {
  const Cage& cage = in.model.cage;
  Box3 box = bounding_box(cage.positions);
  const glm::vec3 eye = in.view.camera.eye, target = in.view.camera.target;
  box.extend(eye);
  const glm::vec3 centre = box.centre();
  const float radius = 0.5f * glm::length(box.hi - box.lo);
  // From beyond the model, above and to the side, looking back toward the view camera: what faces away
  // from the view (the back-patch test's patches) faces this camera, and the frustum reads as a
  // pyramid.
  const glm::vec3 back = glm::normalize(eye - target);
  glm::vec3 side = glm::cross(glm::vec3(0, 1, 0), back);
  side = glm::length(side) > 1e-3f ? glm::normalize(side) : glm::vec3(1, 0, 0);
  const glm::vec3 direction = glm::normalize(0.5f * side + 0.5f * glm::vec3(0, 1, 0) - back);
  Cage frame;
  frame.positions = {box.lo, box.hi};
  return frame_cage(frame, w, h, 35.0f, centre + direction * (radius / std::tan(glm::radians(17.5f)) * 1.1f), centre);
}

}  // namespace

PatchTables view_patch_tables(const ViewInputs& in) {
  const DicingCamera camera{in.view.camera.eye, pixels_per_unit(in.view.height, in.view.fov)};
  return build_patch_tables(in.model, in.displacement, in.factors, in.cull, in.partitioning, camera);
}

bool view_uses_patch_tables(ViewKind kind) {
  return kind != ViewKind::shaded && kind != ViewKind::cage && kind != ViewKind::cracks;
}

namespace {

// The control cage over the shaded surface (drawn already), depth-tested, faint where hidden. Tagged
// edges and corners are coloured by sharpness, as OpenSubdiv's viewer does: what only --scheme exact
// honours, and where.
void draw_cage_view(const ViewInputs& in, Framebuffer& fb, Legend& legend) {
  const Topology& t = *in.model.topology;
  const glm::mat4& vp = in.view.camera.view_projection;
  const std::vector<glm::vec3>& positions = in.model.positions();
  // Smooth edges, then creases of sharpness up to 1, up to 10, and infinite (10 and above).
  struct Kind {
    glm::vec3 color;
    float width;
    std::vector<OverlayLine> lines;
  };
  std::array<Kind, 4> kinds = {{{glm::vec3(0.1f, 0.3f, 0.75f), 1.6f, {}},
                                {glm::vec3(0.95f, 0.8f, 0.1f), 2.6f, {}},
                                {glm::vec3(0.95f, 0.5f, 0.05f), 2.6f, {}},
                                {glm::vec3(0.85f, 0.05f, 0.05f), 2.6f, {}}}};
  for (int e = 0; e < t.edge_count(); ++e) {
    const int h = t.edge_half_edges(e)[0];
    const float s = t.edge_sharpness(e);
    const std::size_t k = !(s > 0.0f) ? 0 : s <= 1.0f ? 1 : s < 10.0f ? 2 : 3;
    kinds[k].lines.push_back({positions[std::size_t(t.origin(h))], positions[std::size_t(t.destination(h))]});
  }
  std::vector<glm::vec3> corners;
  for (int v = 0; v < t.vertex_count(); ++v)
    if (t.corner_sharpness(v) > 0.0f) corners.push_back(positions[std::size_t(v)]);
  // The cage lies off the surface; where the surface hides it, it is drawn faintly.
  for (const Kind& k : kinds) draw_lines(fb, vp, k.lines, OverlayStyle{k.color, 1.0f, 0.25f, false, 0.0f});
  for (const Kind& k : kinds) draw_lines(fb, vp, k.lines, OverlayStyle{k.color, k.width, 0.9f, true, kCageDepthSlack});
  OverlayStyle visible{kinds[0].color, 4.0f, 0.9f, true, kCageDepthSlack};
  draw_points(fb, vp, positions, visible);
  visible.color = kinds[3].color;
  visible.width = 7.0f;
  draw_points(fb, vp, corners, visible);
  legend.title = "control cage over the surface (" + std::string(to_string(in.model.patches.scheme)) + ")";
  legend.lines = {std::to_string(t.edge_count()) + " cage edges, " + std::to_string(t.vertex_count()) +
                  " vertices; faint where the surface hides them"};
  const std::size_t creased = kinds[1].lines.size() + kinds[2].lines.size() + kinds[3].lines.size();
  if (creased > 0 || !corners.empty())
    legend.lines.push_back(std::to_string(creased) +
                           " creased edges by sharpness: yellow up to 1, orange up to 10, "
                           "red infinite; " +
                           std::to_string(corners.size()) + " sharp corners (red dots)");
}

// The tessellation welded on exact bits over the shaded surface (drawn already); cracks and non-manifold
// edges drawn thick, the surface's own border thin in a quiet colour (surface_weld.h). Welded with
// culling off, so the culled patches are checked too: every edge factor is a function of its cage edge
// alone (the LOD does not depend on the cull), so the visible patches have the same triangles either
// way.
void draw_cracks_view(Device& device, const ViewInputs& in, Framebuffer& fb, ViewOutput& out) {
  verify::WeldChecker weld;
  const WeldCurves curves = weld_curves(in.model.cage, *in.model.topology);
  PatchCull all = in.cull;
  all.frustum.enabled = false;
  const DrawResult s = stream_surface(device, in.model, in.displacement, in.factors, all, in.partitioning,
                                      [&](const auto& p, const PatchGroup& g) { add_surface_patch(weld, p, g, curves); });
  if (!s.ok()) {
    out.result = s;
    return;
  }
  std::vector<OverlayLine> cracks, border, nonmanifold;
  std::vector<OverlayLine> fins;  // the cage's own non-manifold edges
  for (const verify::WeldEdge& e : weld.bad_edges())
    (e.kind == verify::WeldEdgeKind::crack              ? cracks
     : e.kind == verify::WeldEdgeKind::border           ? border
     : e.kind == verify::WeldEdgeKind::cage_nonmanifold ? fins
                                                        : nonmanifold)
        .push_back({e.a, e.b});
  out.crack_edges = cracks.size(), out.border_edges = border.size(), out.nonmanifold_edges = nonmanifold.size();
  const glm::mat4& vp = in.view.camera.view_projection;
  draw_lines(fb, vp, border, OverlayStyle{glm::vec3(0.35f, 0.55f, 0.75f), 1.5f, 1.0f, false, 0.0f});
  draw_lines(fb, vp, fins, OverlayStyle{glm::vec3(0.55f, 0.35f, 0.75f), 1.5f, 1.0f, false, 0.0f});
  draw_lines(fb, vp, cracks, OverlayStyle{glm::vec3(0.9f, 0.05f, 0.05f), 3.0f, 1.0f, false, 0.0f});
  draw_lines(fb, vp, nonmanifold, OverlayStyle{glm::vec3(0.95f, 0.5f, 0.0f), 3.0f, 1.0f, false, 0.0f});
  const verify::WeldReport r = weld.report();
  out.legend.title = "cracks: the tessellation welded on exact float bits";
  out.legend.lines = {
      std::to_string(r.triangles) + " triangles, " + std::to_string(r.welded_vertices) + " welded vertices",
      std::to_string(out.crack_edges) + " cracks (red), " + std::to_string(out.nonmanifold_edges) +
          " non-manifold (orange): " + (r.watertight() ? "watertight" : "NOT watertight")};
  if (out.border_edges > 0)
    out.legend.lines.push_back(std::to_string(out.border_edges) + " border edges (blue): where the surface ends");
  if (!fins.empty())
    out.legend.lines.push_back(std::to_string(fins.size()) + " non-manifold edges of the cage (violet): its own fins");
  if (in.cull.frustum.enabled) out.legend.lines.push_back("welded with culling off: culled patches are checked too");
}

void factors_legend(const ViewInputs& in, const PatchTables& tables, Legend& legend) {
  float lo = INFINITY, hi = -INFINITY;
  tables.for_each([&](const PatchInfo& p) {
    if (p.culled) return;
    for (int k = 0; k < (p.tri ? 3 : 4); ++k) {
      const float f = in.processed ? p.edge_processed[std::size_t(k)] : p.raw.edge[std::size_t(k)];
      lo = std::min(lo, f), hi = std::max(hi, f);
    }
  });
  legend.title = std::string("tessellation factor, ") + (in.processed ? "processed" : "raw") + " (" +
                 std::string(ts::to_string(in.partitioning)) + ")";
  legend.lines = {"outer rings: their edge's factor; interior: the larger inside factor",
                  std::isfinite(lo) ? "edges drawn: " + fixed(lo, 2) + " to " + fixed(hi, 2) : "no patch drawn"};
  legend.ramp = sample_ramp([](float t) { return heat_color(t); });
  for (int k = 0; k <= 6; ++k) legend.ticks.emplace_back(float(k) / 6.0f, std::to_string(1 << k));
}

void patch_type_legend(Scheme scheme, const PatchTables& tables, Legend& legend) {
  std::array<int, kPatchTypeCount> count{};
  tables.for_each([&](const PatchInfo& p) { ++count[std::size_t(p.type)]; });
  legend.title = "patch type, scheme " + std::string(to_string(scheme));
  for (int k = 0; k < kPatchTypeCount; ++k)
    if (count[std::size_t(k)] > 0)
      legend.swatches.emplace_back(category_color(k), std::string(to_string(PatchType(k))) + ": " +
                                                          std::to_string(count[std::size_t(k)]) + " patches");
}

// The adaptive scheme's patches: Far's patch table, by kind and by isolation level.
void adaptive_patch_legend(const LimitSurface& limit, Legend& legend) {
  const LimitSurface::PatchCounts c = limit.patch_counts();
  legend.title = "adaptive patches, isolation " + std::to_string(limit.approx_level()) + ": " +
                 std::to_string(c.total) + " patches";
  for (int k = 0; k < kAdaptivePatchKinds; ++k)
    if (c.by_kind[k] > 0)
      legend.swatches.emplace_back(adaptive_patch_color(AdaptivePatchKind(k), 0),
                                   std::string(to_string(AdaptivePatchKind(k))) + ": " + std::to_string(c.by_kind[k]));
  std::string levels;
  for (int l = 0; l < 16; ++l)
    if (c.by_level[l] > 0)
      levels += (levels.empty() ? "" : ", ") + std::to_string(l) + ": " + std::to_string(c.by_level[l]);
  legend.lines = {"per level " + levels, "darker: deeper level; thin lines: sub-patch borders"};
}

void combination_legend(const TopologyCombinations& combos, Legend& legend) {
  legend.title = std::to_string(combos.combinations.size()) + " topology combinations (as tessera analyze)";
  std::vector<int> order(combos.combinations.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return combos.combinations[std::size_t(a)].count > combos.combinations[std::size_t(b)].count;
  });
  for (std::size_t i = 0; i < std::min<std::size_t>(8, order.size()); ++i) {
    const Combination& c = combos.combinations[std::size_t(order[i])];
    legend.swatches.emplace_back(category_color(order[i]), c.text + " : " + std::to_string(c.count));
  }
  if (order.size() > 8) legend.lines = {"the 8 most frequent:"};
}

// The debug pixel shader's settings for `kind`, and its legend (none for the wireframes).
DebugRender debug_view_setup(ViewKind kind, const ViewInputs& in, const PatchTables& tables, ViewOutput& out) {
  DebugRender r;
  r.ps.processed = in.processed;
  r.ps.edge_pixels = in.edge_pixels;
  out.has_legend = true;
  Legend& legend = out.legend;
  switch (kind) {
    case ViewKind::wireframe:
    case ViewKind::wire_on_shaded:
      r.ps.view = DebugView::wire;
      r.ps.paper = kind == ViewKind::wireframe;
      r.wire_pass = true;
      out.has_legend = false;
      break;
    case ViewKind::factors:
      r.ps.view = DebugView::factors;
      factors_legend(in, tables, legend);
      break;
    case ViewKind::density:
      r.ps.view = DebugView::density;
      legend.title = "pixels per segment, target " + fixed(in.edge_pixels, 1) + " (--edge-pixels)";
      legend.lines = {"blue: finer than the target; red: coarser"};
      legend.ramp = sample_ramp([](float t) { return diverging_color(t); });
      for (int k = -3; k <= 3; ++k)
        legend.ticks.emplace_back(float(k + 3) / 6.0f, fixed(in.edge_pixels * std::exp2(float(k)), k < 0 ? 1 : 0));
      break;
    case ViewKind::patch_type:
      r.ps.view = DebugView::patch_type;
      if (in.model.limit && in.model.limit->adaptive()) {
        r.ps.adaptive = in.model.limit.get();
        adaptive_patch_legend(*in.model.limit, legend);
      } else {
        patch_type_legend(in.model.patches.scheme, tables, legend);
      }
      break;
    case ViewKind::combination:
      r.ps.view = DebugView::combination;
      combination_legend(tables.combinations, legend);
      break;
    case ViewKind::patch_id:
      r.ps.view = DebugView::patch_id;
      legend.title = "patch id (SV_PrimitiveID): one colour per patch";
      legend.lines = {std::to_string(tables.quads.size()) + " quad-domain, " + std::to_string(tables.tris.size()) +
                      " tri-domain patches"};
      break;
    case ViewKind::normals:
      r.ps.view = DebugView::normals;
      legend.title = "surface normal, world space: RGB = (x, y, z) / 2 + 1/2";
      break;
    case ViewKind::uv: {
      r.ps.view = DebugView::uv;
      if (!in.model.cage.has_uvs()) throw UsageError("--view uv: " + in.model.cage.name + " has no UVs");
      if (in.displacement) r.ps.heights = in.displacement->maps;
      std::size_t seams = 0;
      tables.for_each([&](const PatchInfo& p) { seams += std::size_t(std::popcount(unsigned(p.seam_edges))); });
      legend.title = "texture coordinates: 16 x 16 checks, red = u, green = v";
      legend.lines = {"UV seams in red (" + std::to_string(seams / 2) + " seam edges)"};
      break;
    }
    case ViewKind::displacement: {
      r.ps.view = DebugView::displacement;
      const Displacement& d = *in.displacement;
      if (d.kind != DisplacementKind::scalar) throw UsageError("--view displacement shows scalar maps only");
      r.ps.heights = d.maps, r.ps.texcoords = d.texcoords;
      r.ps.height_scale = d.scale, r.ps.height_bias = d.bias, r.ps.height_range = d.bound;
      legend.title = "signed displacement (scale * texel + bias), object units";
      legend.ramp = sample_ramp([](float t) { return diverging_color(t); });
      legend.ticks = {{0.0f, "-" + fixed(d.bound, 3)}, {0.5f, "0"}, {1.0f, "+" + fixed(d.bound, 3)}};
      break;
    }
    case ViewKind::culled: {
      r.ps.view = DebugView::culled;
      std::size_t culled = 0, away = 0, total = 0;
      tables.for_each([&](const PatchInfo& p) { culled += p.culled ? 1 : 0, away += p.faces_away ? 1 : 0, ++total; });
      legend.title = "patch culling, seen from outside the view";
      legend.swatches = {
          {kCulledColor, std::to_string(culled) + " of " + std::to_string(total) + " patches outside the frustum"},
          {kBackCulledColor, std::to_string(away) + " proven to face away (back-patch test)"},
          {glm::vec3(0.1f, 0.1f, 0.1f), "the view camera's frustum"}};
      break;
    }
    case ViewKind::shaded:
    case ViewKind::cage:
    case ViewKind::cracks: break;  // not debug-shader views
  }
  return r;
}

}  // namespace

ViewOutput render_view(Device& device, ViewKind kind, const ViewInputs& in, const PatchTables* given, Framebuffer& fb) {
  ViewOutput out;
  device.clear(fb, kBackgroundColor, 1.0f);  // by tiles: each written as a draw enters it (framebuffer.h)
  if (kind == ViewKind::displacement && !in.displacement)
    throw UsageError("--view displacement needs --displacement MAP");
  if (kind == ViewKind::shaded || kind == ViewKind::cage || kind == ViewKind::cracks) {
    out.result = draw_shaded(device, in, fb);
    if (!out.result.ok() || kind == ViewKind::shaded) return out;
    out.has_legend = true;
    if (kind == ViewKind::cage)
      draw_cage_view(in, fb, out.legend);
    else
      draw_cracks_view(device, in, fb, out);
    return out;
  }
  TESSERA_CHECK(given != nullptr, "render_view: --view", to_string(kind), "needs the patch tables");
  DebugRender r = debug_view_setup(kind, in, *given, out);
  // The culled view draws what the view culled, from outside, with the view's frustum.
  PatchCull cull = in.cull;
  SubdCamera camera = in.view.camera;
  if (kind == ViewKind::culled) {
    cull = {};  // its claims are about the view camera, not this one
    camera = overview_camera(in, fb.width(), fb.height());
  }
  r.ps.light = glm::normalize(camera.eye - camera.target);
  out.result = render_debug(device, in.model, in.displacement, in.factors, cull, in.partitioning, r, *given, camera, fb);
  if (out.result.ok() && kind == ViewKind::culled) {
    std::vector<OverlayLine> lines;
    frustum_lines(in.view.camera.view_projection, lines);
    draw_lines(fb, camera.view_projection, lines, OverlayStyle{glm::vec3(0.1f), 1.5f, 1.0f, false, 0.0f});
  }
  return out;
}

DrawResult render_pick_buffer(Device& device, ViewKind kind, const ViewInputs& in, const PatchTables& tables,
                              Framebuffer& fb) {
  fb.clear(glm::vec4(0.0f), 1.0f);
  DebugRender r;
  r.ps.view = DebugView::pick;
  PatchCull cull = in.cull;
  SubdCamera camera = in.view.camera;
  if (kind == ViewKind::culled) {
    cull = {};
    camera = overview_camera(in, fb.width(), fb.height());
  }
  return render_debug(device, in.model, in.displacement, in.factors, cull, in.partitioning, r, tables, camera, fb);
}

const PatchInfo* picked_patch(const PatchTables& tables, std::uint32_t code, std::size_t* index) {
  if (code == 0 || code >= kPickOverflow) return nullptr;
  const std::size_t i = (code - 1u) / 2u;
  const std::vector<PatchInfo>& rows = (code - 1u) % 2u ? tables.tris : tables.quads;
  if (i >= rows.size()) return nullptr;
  if (index != nullptr) *index = i;
  return &rows[i];
}

}  // namespace tessera::scene
