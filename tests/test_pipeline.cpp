// The whole pipeline: D3D11 statistics for known draws, lines and points, determinism across thread
// counts and chunking, bounded memory, and bad input handled as D3D11 specifies or reported.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <set>
#include <thread>

#include "pipeline/draw_trace.h"
#include "pipeline/parallel.h"
#include "pipeline/tile_schedule.h"
#include "pipeline/triangle_list_setup.h"
#include "pipeline_support.h"
#include "shaders_cpp/render/torus_scene.h"

using namespace tessera;
using namespace tessera::test;

namespace {

// Control points are NDC positions; the patch is their bilinear blend (4 control points, u across
// cp0 -> cp1, v across cp0 -> cp2).
struct NdcVS {
  glm::vec4 operator()(const glm::vec4& p, std::uint32_t) const { return p; }
};
struct Factors {
  TessFactors factors;
};
struct FactorHS {
  static constexpr int kOutputControlPoints = 4;
  TessFactors f;
  glm::vec4 control_point(std::span<const glm::vec4> in, int i, std::uint32_t) const { return in[std::size_t(i)]; }
  Factors patch_constants(std::span<const glm::vec4>, std::span<const glm::vec4>, std::uint32_t) const { return {f}; }
};
struct BilinearDS {
  ClipVertex<2> operator()(const Factors&, std::span<const glm::vec4> cp, DomainLocation l, std::uint32_t) const {
    const glm::vec4 top = cp[0] + l.u * (cp[1] - cp[0]), bottom = cp[2] + l.u * (cp[3] - cp[2]);
    ClipVertex<2> o;
    o.position = top + l.v * (bottom - top);
    o.attributes = {l.u, l.v};
    return o;
  }
};
using QuadDraw = PatchDraw<glm::vec4, NdcVS, FactorHS, BilinearDS, CountingPS<2>>;

TessFactors uniform(float f) { return {{f, f, f, f}, {f, f}}; }

struct QuadScene {
  std::vector<glm::vec4> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<int> counts;
};

// Two patches side by side covering the viewport, sharing their middle edge (6 vertices, 8 indices).
QuadScene two_patches(int w, int h) {
  QuadScene s;
  s.vertices = {{-1, 1, 0.5f, 1},  {0, 1, 0.5f, 1},  {1, 1, 0.5f, 1},
                {-1, -1, 0.5f, 1}, {0, -1, 0.5f, 1}, {1, -1, 0.5f, 1}};
  s.indices = {0, 1, 3, 4, 1, 2, 4, 5};
  s.counts.assign(std::size_t(w) * h, 0);
  return s;
}

QuadDraw quad_draw(QuadScene& s, int w, int h, float factor) {
  QuadDraw d;
  d.vertices = s.vertices;
  d.indices = s.indices;
  d.control_points = 4;
  d.hs.f = uniform(factor);
  d.ps = {&s.counts, w};
  d.tessellator = {ts::Domain::quad, ts::Partitioning::integer, ts::OutputPrimitive::triangle_cw};
  d.rasterizer.cull = CullMode::none;
  d.viewport = full_viewport(w, h);
  return d;
}

}  // namespace

TEST_CASE("pipeline: D3D11 statistics of a known draw", "[pipeline][stats]") {
  const int w = 40, h = 24;
  for (int threads : {1, 2}) {
    Device device(DeviceOptions{threads, 16});
    QuadScene s = two_patches(w, h);
    auto fb = make_target(w, h);
    const DrawResult r = device.draw(quad_draw(s, w, h, 5.0f), fb);
    REQUIRE(r.ok());
    const PipelineStatistics& st = r.report.statistics;
    CHECK(st.IAVertices == 8);
    CHECK(st.IAPrimitives == 2);
    CHECK(st.VSInvocations == 6);  // vertex caching: the shared edge's two vertices run once
    CHECK(st.HSInvocations == 2);
    CHECK(st.DSInvocations == 2 * 36);                // (5 + 1)^2 domain points per patch
    CHECK(st.CInvocations == 2 * 50);                 // 2 * 5^2 triangles per patch
    CHECK(st.CPrimitives == 2 * 50);                  // nothing clipped or culled
    CHECK(st.PSInvocations == std::uint64_t(w * h));  // every pixel exactly once (fill rule, depth less)
    CHECK(st.GSInvocations == 0);
    for (int c : s.counts) CHECK(c == 1);
  }
}

TEST_CASE("pipeline: patches with equal factors share one cached pattern per thread", "[pipeline]") {
  Device device(DeviceOptions{1, 16});
  QuadScene s = two_patches(16, 16);
  auto fb = make_target(16, 16);
  const DrawResult r = device.draw(quad_draw(s, 16, 16, 7.0f), fb);
  REQUIRE(r.ok());
  // One lookup per patch, when its domain shader needs the pattern (the HS phase counts primitives
  // from the factors, ts::primitive_count): the first tessellates, the second hits.
  CHECK(r.report.memory.pattern_cache_misses == 1);
  CHECK(r.report.memory.pattern_cache_hits == 1);
  CHECK(r.report.statistics.DSInvocations == 2 * 64u);  // 8 x 8 points per patch at factor 7
  // The device keeps its threads' caches from draw to draw, and a report counts its own draw's
  // lookups: the same draw again tessellates nothing, and gives the same bytes.
  auto again = make_target(16, 16);
  const DrawResult r2 = device.draw(quad_draw(s, 16, 16, 7.0f), again);
  REQUIRE(r2.ok());
  CHECK(r2.report.memory.pattern_cache_misses == 0);
  CHECK(r2.report.memory.pattern_cache_hits == 2);
  CHECK(image_hash(again) == image_hash(fb));
}

TEST_CASE("pipeline: isoline domain draws lines, one pixel per column, joints lit once", "[pipeline][lines]") {
  const int w = 32, h = 8;
  Device device(DeviceOptions{2, 16});
  QuadScene s;
  // u across the width; v maps the four isolines (v = 0, 1/4, 1/2, 3/4) to pixel rows 0, 2, 4, 6.
  auto ndc_y = [&](float row_centre) { return 1.0f - 2.0f * row_centre / float(h); };
  s.vertices = {
      {-1, ndc_y(0.5f), 0.5f, 1}, {1, ndc_y(0.5f), 0.5f, 1}, {-1, ndc_y(8.5f), 0.5f, 1}, {1, ndc_y(8.5f), 0.5f, 1}};
  s.indices = {0, 1, 2, 3};
  s.counts.assign(std::size_t(w) * h, 0);
  QuadDraw d = quad_draw(s, w, h, 1.0f);
  d.hs.f = {{4.0f, 8.0f, 0, 0}, {0, 0}};  // density 4 lines, detail 8 segments
  d.tessellator = {ts::Domain::isoline, ts::Partitioning::integer, ts::OutputPrimitive::line};
  auto fb = make_target(w, h);
  const DrawResult r = device.draw(d, fb);
  REQUIRE(r.ok());
  CHECK(r.report.statistics.CInvocations == 4 * 8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) CHECK(s.counts[std::size_t(y * w + x)] == (y % 2 == 0 ? 1 : 0));
  CHECK(r.report.statistics.PSInvocations == std::uint64_t(4 * w));
}

TEST_CASE("pipeline: point output lights one pixel per domain point", "[pipeline][points]") {
  const int w = 16, h = 16;
  Device device(DeviceOptions{1, 16});
  QuadScene s;
  // Domain (0..1) maps to window 1.0 .. 9.0 on both axes, so points at u = 0, 1/2, 1 land in pixels 1, 5, 9.
  auto nx = [&](float px) { return px / float(w) * 2 - 1; };
  auto ny = [&](float py) { return 1 - py / float(h) * 2; };
  s.vertices = {{nx(1.25f), ny(1.25f), 0.5f, 1},
                {nx(9.25f), ny(1.25f), 0.5f, 1},
                {nx(1.25f), ny(9.25f), 0.5f, 1},
                {nx(9.25f), ny(9.25f), 0.5f, 1}};
  s.indices = {0, 1, 2, 3};
  s.counts.assign(std::size_t(w) * h, 0);
  QuadDraw d = quad_draw(s, w, h, 2.0f);
  d.tessellator.output = ts::OutputPrimitive::point;
  auto fb = make_target(w, h);
  const DrawResult r = device.draw(d, fb);
  REQUIRE(r.ok());
  CHECK(r.report.statistics.DSInvocations == 9);
  CHECK(r.report.statistics.PSInvocations == 9);
  for (int y : {1, 5, 9})
    for (int x : {1, 5, 9}) CHECK(s.counts[std::size_t(y * w + x)] == 1);
}

TEST_CASE("pipeline: wireframe fill draws edges only", "[pipeline][lines]") {
  const int w = 48, h = 48;
  Device device(DeviceOptions{2, 16});
  QuadScene s = two_patches(w, h);
  QuadDraw d = quad_draw(s, w, h, 4.0f);
  d.rasterizer.fill = FillMode::wireframe;
  auto fb = make_target(w, h);
  const DrawResult r = device.draw(d, fb);
  REQUIRE(r.ok());
  int lit = 0;
  for (int c : s.counts) lit += c > 0;
  CHECK(lit > w);                                                  // the lines are there
  CHECK(lit < w * h / 2);                                          // and the interiors are not
  CHECK(s.counts[std::size_t((h / 2 + 3) * w + w / 4 + 3)] == 0);  // inside a cell of the 4x4 grid
}

TEST_CASE("pipeline: the tile schedule keeps each tile's rounds in order and reuses storage only when consumed",
          "[pipeline][parallel]") {
  using tessera::detail::TileLoad;
  // Rounds: full ones, then halving down to the smallest size, covering every chunk once.
  CHECK(tessera::detail::round_starts(162, 64, 8) == std::vector<std::size_t>{0, 64, 113, 138, 150, 158, 162});
  CHECK(tessera::detail::round_starts(256, 64, 8) == std::vector<std::size_t>{0, 64, 128, 192, 224, 240, 248, 256});
  CHECK(tessera::detail::round_starts(5, 4, 1) == std::vector<std::size_t>{0, 3, 4, 5});
  CHECK(tessera::detail::round_starts(0, 4, 1) == std::vector<std::size_t>{0});
  for (std::size_t chunks = 0; chunks < 300; chunks += 7) {
    const auto first = tessera::detail::round_starts(chunks, 16, 3);
    CHECK(first.back() == chunks);
    for (std::size_t r = 0; r + 1 < first.size(); ++r) {
      CHECK(first[r + 1] > first[r]);
      CHECK(first[r + 1] - first[r] <= 16);
    }
  }
  struct Case {
    int workers;
    std::size_t chunks, per_round, smallest, sets, tiles;  // sets: slots = sets x per_round; as many lists
    bool can_split;
  } cases[] = {{4, 40, 3, 1, 2, 9, true},  {4, 41, 4, 2, 3, 16, true}, {6, 100, 2, 1, 5, 7, true},
               {1, 23, 4, 1, 2, 9, true},  {3, 7, 8, 1, 2, 5, false},  {4, 0, 4, 1, 2, 9, true},
               {8, 90, 16, 4, 3, 12, true}};
  for (const Case& c : cases) {
    INFO("workers " << c.workers << " chunks " << c.chunks << " per round " << c.per_round << " sets " << c.sets);
    const std::vector<std::size_t> first = tessera::detail::round_starts(c.chunks, c.per_round, c.smallest);
    const std::size_t rounds = first.size() - 1;
    // Round r's busy tiles: a pseudo-random subset with uneven loads; the last round piles its load on
    // tile 0, so that a drain splits it.
    std::vector<std::vector<TileLoad>> lists(rounds);
    for (std::size_t r = 0; r < rounds; ++r)
      for (std::uint32_t t = 0; t < c.tiles; ++t)
        if ((r * 7 + t * 3) % 5 != 0) lists[r].push_back({t, std::uint32_t(1 + (r * 13 + t * 5) % 11)});
    if (rounds > 0) lists[rounds - 1].push_back({std::uint32_t(c.tiles), 100000});
    std::mutex m;
    bool ok = true;
    std::string why;
    const auto fail = [&](std::string text) {
      if (ok) why = std::move(text);
      ok = false;
    };
    std::size_t next_started = 0;
    std::vector<int> started(c.chunks, 0);
    std::vector<std::size_t> produced(rounds, 0);
    const std::size_t slots = c.sets * c.per_round;
    std::vector<long> slot_owner(slots, -1);  // the round holding each slot
    std::vector<std::uint32_t> chunk_slot(c.chunks, 0);
    std::vector<int> listed(rounds, 0), consumed(rounds, 0);
    std::vector<std::size_t> finished;
    std::vector<std::set<std::uint32_t>> given(c.tiles + 1);  // rounds rasterized per tile
    std::vector<int> running(c.tiles + 1, 0);                 // calls on a tile in progress
    std::vector<int> quarters_running(c.tiles + 1, 0);
    std::vector<int> prepared(c.tiles + 1, 0);
    const auto busy = [] { tbb::parallel_for(0, 3, [](int) { std::this_thread::yield(); }); };
    const auto produce = [&](std::size_t chunk, std::size_t r, std::size_t slot) {
      {
        const std::lock_guard<std::mutex> lock(m);
        // Chunks are handed out in draw order, but two workers' calls may begin in either order.
        ++next_started;
        if (chunk >= c.chunks || started[chunk]++) fail("chunk " + std::to_string(chunk) + " produced twice");
        if (r >= rounds || chunk < first[r] || chunk >= first[r + 1])
          fail("chunk " + std::to_string(chunk) + " given the wrong round");
        if (slot >= slots || slot_owner[slot] != -1) fail("chunk " + std::to_string(chunk) + " given a slot in use");
        if (slot < slots) slot_owner[slot] = long(r);
        chunk_slot[chunk] = std::uint32_t(slot);
        if (r >= c.sets && !consumed[r - c.sets]) fail("round " + std::to_string(r) + " reused unconsumed lists");
      }
      busy();
      const std::lock_guard<std::mutex> lock(m);
      ++produced[r];
    };
    // The round's slots, in chunk order, as its chunks were given them.
    const auto check_slots = [&](std::size_t r, std::span<const std::uint32_t> s) {
      if (s.size() != first[r + 1] - first[r]) return fail("a round's size is wrong");
      for (std::size_t i = 0; i < s.size(); ++i)
        if (s[i] != chunk_slot[first[r] + i]) fail("a round's slots are wrong");
    };
    const auto list_tiles = [&](std::size_t r, std::span<const std::uint32_t> s) -> std::span<const TileLoad> {
      const std::lock_guard<std::mutex> lock(m);
      check_slots(r, s);
      if (produced[r] != s.size()) fail("listed before produced");
      if (listed[r]++) fail("listed twice");
      return lists[r];
    };
    const auto prepare = [&](std::uint32_t t) {
      const std::lock_guard<std::mutex> lock(m);
      ++prepared[t];
      if (running[t] || quarters_running[t]) fail("prepared while rasterized");
    };
    const auto rasterize = [&](std::uint32_t t, std::span<const std::uint32_t> rs, std::uint8_t q) {
      {
        const std::lock_guard<std::mutex> lock(m);
        if (q == 0 ? running[t]++ || quarters_running[t] : running[t] || quarters_running[t]++ >= 4)
          fail("tile " + std::to_string(t) + " rasterized twice at once");
        if (q != 0 && !prepared[t]) fail("a quarter before its tile was prepared");
        for (std::size_t i = 0; i < rs.size(); ++i) {
          if (i > 0 && rs[i] <= rs[i - 1]) fail("rounds out of order");
          if (rs[i] >= rounds || !listed[rs[i]]) fail("an unlisted round");
          if (q <= 1 && !given[t].insert(rs[i]).second) fail("a round given to a tile twice");
        }
      }
      busy();
      const std::lock_guard<std::mutex> lock(m);
      --(q == 0 ? running[t] : quarters_running[t]);
    };
    const auto on_consumed = [&](std::size_t r, std::span<const std::uint32_t> s) {
      const std::lock_guard<std::mutex> lock(m);
      check_slots(r, s);
      for (const std::uint32_t slot : s) slot_owner[slot] = -1;
      for (const TileLoad& tl : lists[r])
        if (!given[tl.tile].count(std::uint32_t(r))) fail("consumed before every tile rasterized it");
      if (consumed[r]++) fail("consumed twice");
    };
    const auto on_finished = [&](std::size_t r, std::size_t end) {
      if (!consumed[r]) fail("finished before consumed");
      if (end != first[r + 1]) fail("finished with the wrong end");
      finished.push_back(r);
    };
    tessera::detail::ScheduleShape shape;
    shape.chunks = c.chunks;
    shape.per_round = c.per_round;
    shape.smallest = c.smallest;
    shape.slots = slots;
    shape.lists = c.sets;
    shape.tiles = c.tiles + 1;
    shape.workers = c.workers;
    shape.can_split = c.can_split;
    tbb::task_arena arena(c.workers);
    std::uint64_t splits = 0;
    arena.execute([&] {
      splits =
          tessera::detail::run_tile_schedule(shape, produce, list_tiles, prepare, rasterize, on_consumed, on_finished);
    });
    INFO(why);
    CHECK(ok);
    CHECK(next_started == c.chunks);
    REQUIRE(finished.size() == rounds);
    for (std::size_t r = 0; r < rounds; ++r) CHECK(finished[r] == r);
    std::size_t units = 0, given_units = 0;
    for (const auto& l : lists) units += l.size();
    for (const auto& g : given) given_units += g.size();
    CHECK(given_units == units);  // every (tile, round) pair, once
    // The heavy tile of the last round is split when several workers may take its quarters.
    CHECK(splits == (c.workers > 1 && c.can_split && rounds > 0 ? 1u : 0u));
  }
}

TEST_CASE("pipeline: the torus renders bit-identically for 1, 2 and 7 threads and any chunking or pipelining",
          "[pipeline][determinism]") {
  const int w = 320, h = 180;
  const render::TorusScene scene = render::make_torus_scene(w, h);
  const auto draw = render::make_torus_draw(scene, 7.3f, ts::Partitioning::fractional_odd, w, h);
  std::uint64_t reference = 0;
  PipelineStatistics reference_stats;
  // The last three pipeline many small rounds: one or three chunks a round, up to 7 rounds in flight,
  // windows of 5 and 100 patches.
  struct Config {
    int threads, tile;
    std::size_t chunk;
    int chunks_in_flight = 0, rounds_in_flight = 0, window = 1024;
  } configs[] = {{1, 64, 16384}, {2, 64, 16384},          {7, 64, 16384},       {2, 16, 300},
                 {3, 128, 5000}, {7, 32, 300, 3, 7, 100}, {5, 64, 64, 1, 3, 5}, {2, 64, 4096, 1, 2, 1}};
  for (const auto& c : configs) {
    DeviceOptions o;
    o.threads = c.threads;
    o.tile_size = c.tile;
    o.chunk_primitives = c.chunk;
    o.chunks_in_flight = c.chunks_in_flight;
    o.rounds_in_flight = c.rounds_in_flight;
    o.window_patches = c.window;
    Device device(o);
    auto fb = make_target(w, h);
    const DrawResult r = device.draw(draw, fb);
    REQUIRE(r.ok());
    const std::uint64_t hash = image_hash(fb);
    INFO("threads " << c.threads << " tile " << c.tile << " chunk " << c.chunk << " chunks in flight "
                    << c.chunks_in_flight << " rounds in flight " << c.rounds_in_flight << " window " << c.window);
    // In a flush that drains, a tile holding more than half a thread's share is rasterized in
    // quarters (device.h); on 7 threads some of this small target's 15 tiles are, and the bytes must
    // not change.
    if (c.threads == 1) CHECK(r.report.memory.tiles_split == 0);
    if (c.threads == 7 && c.tile == 64) CHECK(r.report.memory.tiles_split > 0);
    if (reference == 0) {
      reference = hash;
      reference_stats = r.report.statistics;
      CHECK(r.report.statistics.PSInvocations > 10000);  // the torus is really on screen
    } else {
      CHECK(hash == reference);
      // Vertex caching is per window (statistics.h): a smaller window shades shared vertices again.
      PipelineStatistics stats = r.report.statistics;
      if (c.window != 1024) {
        CHECK(stats.VSInvocations > reference_stats.VSInvocations);
        stats.VSInvocations = reference_stats.VSInvocations;
      }
      CHECK(stats == reference_stats);
    }
  }
  // A device keeps its chunk slots from draw to draw: after a draw that filled them with other
  // primitives, the same bytes again.
  Device device(DeviceOptions{2});
  auto other = make_target(w, h), fb = make_target(w, h);
  REQUIRE(device.draw(render::make_torus_draw(scene, 23.0f, ts::Partitioning::integer, w, h), other).ok());
  const DrawResult plain = device.draw(draw, fb);
  REQUIRE(plain.ok());
  CHECK(image_hash(fb) == reference);
  CHECK(image_hash(other) != reference);
  // Recording a timeline changes no byte and no statistic; it holds a span for every chunk.
  DrawTrace trace;
  device.set_trace(&trace);
  auto traced = make_target(w, h);
  const DrawResult t = device.draw(draw, traced);
  device.set_trace(nullptr);
  REQUIRE(t.ok());
  CHECK(image_hash(traced) == reference);
  CHECK(t.report.statistics == plain.report.statistics);
  std::size_t chunks = 0, tiles = 0;
  for (const TraceSpan& span : trace.spans()) {
    CHECK(span.end_s >= span.start_s);
    CHECK(span.worker >= 0);
    CHECK(span.worker < 2);
    chunks += span.stage == TraceStage::chunk;
    tiles += span.stage == TraceStage::tile;
  }
  CHECK(chunks == t.report.memory.chunks);
  CHECK(tiles > 0);
  const TraceSummary summary = trace.summary();
  CHECK(summary.busy_fraction() > 0);
  CHECK(summary.busy_fraction() <= 1.0);
  CHECK(summary.first_tile_s < summary.wall_s);
  // Draws after set_trace(nullptr) add nothing.
  const std::size_t spans = trace.spans().size();
  REQUIRE(device.draw(draw, traced).ok());
  CHECK(trace.spans().size() == spans);
}

// The torus's shaders have SIMD forms (a quad pixel shader and a batch domain shader) that must give
// the bits of their per-pixel and per-point forms; hiding the SIMD forms behind wrappers makes the
// pipeline use the scalar ones.
struct PerPixelPS {
  render::NormalColorPS ps;
  glm::vec4 operator()(const PixelInput<3>& in) const { return ps(in); }
};
struct PerPointDS {
  render::DisplacedBsplineDS ds;
  ClipVertex<3> operator()(const render::UniformFactorPatch& pc, std::span<const glm::vec3> cp, DomainLocation l,
                           std::uint32_t id) const {
    return ds(pc, cp, l, id);
  }
};

TEST_CASE("pipeline: SIMD quad pixel shader and batch domain shader match their scalar forms", "[pipeline][simd]") {
  const int w = 320, h = 180;
  const render::TorusScene scene = render::make_torus_scene(w, h);
  for (const auto& [factor, partitioning] :
       {std::pair{7.3f, ts::Partitioning::fractional_odd}, std::pair{5.0f, ts::Partitioning::integer}}) {
    const auto draw = render::make_torus_draw(scene, factor, partitioning, w, h);
    PatchDraw<glm::vec3, render::PassThroughVS, render::UniformFactorHS, PerPointDS, PerPixelPS> scalar;
    scalar.vertices = draw.vertices;
    scalar.indices = draw.indices;
    scalar.control_points = draw.control_points;
    scalar.hs = draw.hs;
    scalar.ds.ds = draw.ds;
    scalar.tessellator = draw.tessellator;
    scalar.rasterizer = draw.rasterizer;
    scalar.depth = draw.depth;
    scalar.viewport = draw.viewport;
    static_assert(QuadPixelShader<render::NormalColorPS, 3> && !QuadPixelShader<PerPixelPS, 3>);
    static_assert(BatchDomainShader<render::DisplacedBsplineDS, render::UniformFactorPatch, glm::vec3, 3> &&
                  !BatchDomainShader<PerPointDS, render::UniformFactorPatch, glm::vec3, 3>);
    Device device(DeviceOptions{2});
    auto a = make_target(w, h), b = make_target(w, h);
    REQUIRE(device.draw(draw, a).ok());
    REQUIRE(device.draw(scalar, b).ok());
    CHECK(a.color_bytes() == b.color_bytes());
    CHECK(a.depth_values() == b.depth_values());
  }
}

// Colour from the coarse derivatives of the normal attributes, in both forms: QuadInput computes them
// from its lanes when asked, PixelInput is handed them.
struct DerivativePixelPS {
  static float channel(float d) { return 0.5f + 8.0f * d; }
  glm::vec4 operator()(const PixelInput<3>& in) const {
    return {channel(in.ddx(0)), channel(in.ddy(1)), channel(in.ddx(2) - in.ddy(2)), 1.0f};
  }
};
struct DerivativeQuadPS : DerivativePixelPS {
  void shade_quad(const QuadInput<3>& q, QuadColor& out) const {
    for (std::size_t k = 0; k < 4; ++k) {
      out.c[0][k] = channel(q.ddx(0));
      out.c[1][k] = channel(q.ddy(1));
      out.c[2][k] = channel(q.ddx(2) - q.ddy(2));
      out.c[3][k] = 1.0f;
    }
  }
};

TEST_CASE("pipeline: a quad shader's derivatives are the per-pixel form's", "[pipeline][simd]") {
  const int w = 320, h = 180;
  const render::TorusScene scene = render::make_torus_scene(w, h);
  const auto torus = render::make_torus_draw(scene, 6.0f, ts::Partitioning::integer, w, h);
  const auto with_ps = [&](auto ps) {
    PatchDraw<glm::vec3, render::PassThroughVS, render::UniformFactorHS, render::DisplacedBsplineDS, decltype(ps)> d;
    d.vertices = torus.vertices;
    d.indices = torus.indices;
    d.control_points = torus.control_points;
    d.hs = torus.hs;
    d.ds = torus.ds;
    d.ps = ps;
    d.tessellator = torus.tessellator;
    d.rasterizer = torus.rasterizer;
    d.depth = torus.depth;
    d.viewport = torus.viewport;
    return d;
  };
  static_assert(QuadPixelShader<DerivativeQuadPS, 3> && !QuadPixelShader<DerivativePixelPS, 3>);
  Device device(DeviceOptions{2});
  auto quad = make_target(w, h), pixel = make_target(w, h);
  REQUIRE(device.draw(with_ps(DerivativeQuadPS{}), quad).ok());
  REQUIRE(device.draw(with_ps(DerivativePixelPS{}), pixel).ok());
  CHECK(quad.color_bytes() == pixel.color_bytes());
  // The derivatives are not all zero: the image has more than a few colours.
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i + 3 < quad.color_bytes().size(); i += 4) {
    std::uint32_t c = 0;
    std::memcpy(&c, &quad.color_bytes()[i], 4);
    colours.insert(c);
  }
  CHECK(colours.size() > 100);
}

TEST_CASE("pipeline: batch vertex setup gives make_setup_vertex's bits, also for vertices it rejects",
          "[pipeline][simd]") {
  RasterizerState rs;
  const SetupContext c = make_setup_context(Viewport{0, 0, 1920, 1080, 0, 1}, rs, 1920, 1080, 64);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  // Special values in every coordinate, points on and beside each plane (view volume, guard band, near,
  // far, w = 0 and negative w), and ordinary points; 4k + 3 of them, so the scalar tail runs too.
  const float specials[] = {0.0f,  -0.0f, 1.0f,  -1.0f, 0.5f, 2.0f, -3.0f, 1e-7f,
                            1e-6f, 8.6f,  -8.6f, 9.0f,  inf,  -inf, nan};
  Rng rng(5);
  std::vector<ClipVertex<3>> in;
  for (int i = 0; i < 1023; ++i) {
    ClipVertex<3> v;
    for (int k = 0; k < 4; ++k)
      v.position[k] =
          rng.uniform(0, 1) < 0.3 ? specials[std::size_t(rng.uniform(0, 15)) % 15] : float(rng.uniform(-1.2, 1.2));
    if (i % 3 == 0) v.position.w = std::abs(v.position.w) + 0.5f;  // mostly projectable
    v.attributes = {float(rng.uniform(-1, 1)), float(rng.uniform(-1, 1)),
                    i % 17 == 0 ? nan : float(rng.uniform(-1, 1))};
    in.push_back(v);
  }
  std::vector<SetupVertex<3>> batch(in.size());
  make_setup_vertices<3>(c, in, batch);
  int projected = 0, rejected = 0, non_finite = 0;
  const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
  for (std::size_t i = 0; i < in.size(); ++i) {
    const SetupVertex<3> one = make_setup_vertex<3>(c, in[i]);
    const SetupVertex<3>& b = batch[i];
    INFO("vertex " << i << ": " << in[i].position.x << " " << in[i].position.y << " " << in[i].position.z << " "
                   << in[i].position.w);
    CHECK(b.finite == one.finite);
    CHECK(b.view_code == one.view_code);
    CHECK(b.clip_code == one.clip_code);
    CHECK(b.x == one.x);
    CHECK(b.y == one.y);
    CHECK(bits(b.z) == bits(one.z));
    CHECK(bits(b.inv_w) == bits(one.inv_w));
    for (std::size_t k = 0; k < one.plane_values.size(); ++k)
      CHECK(bits(b.plane_values[k]) == bits(one.plane_values[k]));
    for (int k = 0; k < 4; ++k) CHECK(bits(b.clip.position[k]) == bits(one.clip.position[k]));
    (!one.finite ? non_finite : one.clip_code ? rejected : projected) += 1;
  }
  CHECK(projected > 100);
  CHECK(rejected > 100);
  CHECK(non_finite > 50);
}

TEST_CASE("pipeline: triangle list setup in lanes gives setup_triangle's records, bins and statistics",
          "[pipeline][simd]") {
  // setup_triangle_list sets up eight triangles at a time in SIMD lanes (AVX2 builds) and hands groups
  // with a clipped, non-finite or large triangle to setup_triangle; either way the chunk must get what
  // setup_triangle gives it one triangle at a time. Triangles of 0..14 pixels around a jittered grid that
  // reaches past the viewport, scissor and tile edges, in both windings, some degenerate; a quarter of
  // the groups of eight hold one triangle with a vertex behind the near plane, past the guard band, at
  // NaN, or far away (too large for 32-bit edges). (Without AVX2, setup_triangle_list is the plain loop
  // over setup_triangle, and this checks only its indexing and primitive ids.)
  // Multisampled targets (4 and 8 samples) take the lanes too, with setup_multisample_triangle's records.
  const auto [cull, front_ccw, scissor, tile_size, id_step, samples] =
      GENERATE(std::tuple{CullMode::none, false, false, 64, 0u, 1}, std::tuple{CullMode::back, false, true, 8, 1u, 1},
               std::tuple{CullMode::front, true, false, 16, 1u, 1}, std::tuple{CullMode::back, true, true, 64, 0u, 1},
               std::tuple{CullMode::back, false, true, 8, 1u, 4}, std::tuple{CullMode::none, true, false, 16, 0u, 8});
  CAPTURE(int(cull), front_ccw, scissor, tile_size, id_step, samples);
  RasterizerState rs;
  rs.cull = cull;
  rs.front_counter_clockwise = front_ccw;
  if (scissor) rs.scissor = ScissorRect{37, 21, 201, 150};
  const SetupContext c = make_setup_context(Viewport{3.25f, 5.5f, 240, 170, 0, 1}, rs, 256, 192, tile_size, samples);
  Rng rng(17);
  constexpr int kCols = 160, kRows = 120;
  std::vector<ClipVertex<3>> clip;
  for (int j = 0; j < kRows; ++j)
    for (int i = 0; i < kCols; ++i) {
      // NDC from -1.1 to 1.1: the grid reaches past the viewport on every side; points about 1.6 pixels apart.
      const float x = -1.1f + 2.2f * (float(i) + float(rng.uniform(-0.4, 0.4))) / float(kCols - 1);
      const float y = -1.1f + 2.2f * (float(j) + float(rng.uniform(-0.4, 0.4))) / float(kRows - 1);
      const float w = float(rng.uniform(0.8, 1.3));
      clip.push_back(ClipVertex<3>{glm::vec4(x * w, y * w, float(rng.uniform(0.05, 0.95)) * w, w),
                                   {float(rng.uniform(-1, 1)), float(rng.uniform(0, 2)), float(rng.uniform(-3, 3))}});
    }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::uint32_t grid_count = std::uint32_t(clip.size());
  const glm::vec4 specials[] = {
      {0.1f, 0.1f, -0.5f, 1.0f}, {40.0f, 0.2f, 0.5f, 1.0f}, {0.3f, nan, 0.5f, 1.0f}, {0.9f, -0.95f, 0.5f, 1.0f}};
  for (const glm::vec4& p : specials) clip.push_back(ClipVertex<3>{p, {0.5f, 0.5f, 0.5f}});
  std::vector<SetupVertex<3>> vertices(clip.size());
  make_setup_vertices<3>(c, clip, vertices);
  std::vector<std::uint32_t> indices;
  const auto near_vertex = [&](std::uint32_t v, int reach) {
    const int i = std::clamp(int(v % kCols) + int(std::floor(rng.uniform(-reach, reach + 1))), 0, kCols - 1);
    const int j = std::clamp(int(v / kCols) + int(std::floor(rng.uniform(-reach, reach + 1))), 0, kRows - 1);
    return std::uint32_t(j * kCols + i);
  };
  for (int group = 0; group < 600; ++group) {
    const int special_lane = rng.uniform(0, 1) < 0.25 ? int(rng.uniform(0, 8)) : -1;
    for (int k = 0; k < 8; ++k) {
      const std::uint32_t a = std::uint32_t(rng.uniform(0, grid_count)) % grid_count;
      const int reach = rng.uniform(0, 1) < 0.8 ? 1 : 4;  // most 1..3 pixels, some up to 12
      std::uint32_t t[3] = {a, near_vertex(a, reach), near_vertex(a, reach)};
      if (k == special_lane) t[std::size_t(rng.uniform(0, 3)) % 3] = grid_count + std::uint32_t(rng.uniform(0, 4)) % 4;
      indices.insert(indices.end(), t, t + 3);
    }
  }
  indices.insert(indices.end(), {0, 1, kCols, 1, kCols + 1, kCols});  // a tail of two triangles
  const std::size_t count = indices.size() / 3;

  ChunkBuffer<3> lanes, one_by_one;
  lanes.reset(c.tiles.count());
  one_by_one.reset(c.tiles.count());
  setup_triangle_list<3>(c, lanes, vertices.data(), vertices.size(), indices.data(), count, 1000, id_step);
  for (std::size_t t = 0; t < count; ++t)
    setup_triangle<3>(c, one_by_one, vertices[indices[3 * t]], vertices[indices[3 * t + 1]],
                      vertices[indices[3 * t + 2]], 1000 + std::uint32_t(t) * id_step);

  CHECK(lanes.statistics.CInvocations == one_by_one.statistics.CInvocations);
  CHECK(lanes.statistics.CPrimitives == one_by_one.statistics.CPrimitives);
  REQUIRE(lanes.primitive_count == one_by_one.primitive_count);
  CHECK(lanes.entries == one_by_one.entries);
  const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
  int mismatched = 0, small_boxes = 0, edges32 = 0;
  for (std::size_t i = 0; i < lanes.primitive_count; ++i) {
    const ScreenPrimitive<3>& a = lanes.primitives[i];
    const ScreenPrimitive<3>& b = one_by_one.primitives[i];
    bool same = a.kind == b.kind && a.front_face == b.front_face && a.edges32 == b.edges32 && a.min_x == b.min_x &&
                a.min_y == b.min_y && a.max_x == b.max_x && a.max_y == b.max_y && a.primitive_id == b.primitive_id &&
                a.box_coverage == b.box_coverage && bits(a.origin_x) == bits(b.origin_x) &&
                bits(a.origin_y) == bits(b.origin_y);
    for (int k = 0; k < 3; ++k) {
      same = same && bits(a.z[k]) == bits(b.z[k]) && bits(a.inv_w[k]) == bits(b.inv_w[k]);
      for (int m = 0; m < 3; ++m) same = same && bits(a.attributes[k][m]) == bits(b.attributes[k][m]);
      // The union holds edges (small triangles) or vertices; [3] of dx and dy is unused.
      if (b.edges32)
        same = same && a.edges.dx[k] == b.edges.dx[k] && a.edges.dy[k] == b.edges.dy[k] &&
               a.edges.ref[k] == b.edges.ref[k];
      else
        same = same && a.xy.x[k] == b.xy.x[k] && a.xy.y[k] == b.xy.y[k];
    }
    if (!same && mismatched++ < 5) INFO("record " << i << " of primitive " << b.primitive_id << " differs");
    small_boxes += b.box_coverage != 0;
    edges32 += b.edges32;
  }
  CHECK(mismatched == 0);
  INFO(lanes.primitive_count << " records of " << count << " triangles, " << small_boxes << " with small boxes, "
                             << edges32 << " with 32-bit edges");
  // The draw must have exercised what it is meant to: kept small and larger triangles, and rejections.
  if (samples == 1) {
    CHECK(small_boxes > 300);
    CHECK(lanes.primitive_count - std::size_t(small_boxes) > 100);
  } else {
    CHECK(small_boxes == 0);  // multisampled coverage is tested per sample by the rasterizer
#if defined(__AVX2__)
    CHECK(std::size_t(edges32) > lanes.primitive_count / 2);  // most kept their 32-bit edges
#endif
  }
  CHECK(lanes.primitive_count < count);
  CHECK(std::size_t(edges32) < lanes.primitive_count);  // some large triangles went through setup_triangle
}

TEST_CASE("pipeline: chunks cover the window in order, within budget, a quarter of it in the tail", "[pipeline][bins]") {
  test::Rng rng(777);
  const auto next = [&](std::uint32_t n) { return std::uint32_t(rng.integer(0, int(n) - 1)); };
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<std::uint32_t> cost(trial == 0 ? 0 : next(400) + 1);
    for (auto& c : cost) c = next(6) == 0 ? next(9000) : next(600);  // some patches past the budget
    const std::size_t budget = 4096, max_items = 256;
    const std::size_t tail = trial % 3 == 0 ? 0 : std::size_t(next(6)) * budget;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> chunks;
    detail::cut_chunks(cost, budget, max_items, chunks, tail);
    std::size_t total = 0;
    for (const auto c : cost) total += c;
    const std::size_t tail_from = tail == 0 ? total + 1 : (total > tail ? total - tail : 0);
    INFO("trial " << trial << ": " << cost.size() << " items, cost " << total << ", tail " << tail);
    std::uint32_t at = 0;
    std::size_t before = 0, in_tail = 0;
    for (const auto& [begin, end] : chunks) {
      REQUIRE(begin == at);
      REQUIRE(end > begin);
      CHECK(end - begin <= max_items);
      std::size_t sum = 0;
      for (std::uint32_t i = begin; i < end; ++i) sum += cost[i];
      // A chunk over its budget is one item; a chunk that starts in the tail keeps to a quarter.
      const std::size_t b = before >= tail_from ? budget / 4 : budget;
      if (end - begin > 1) CHECK(sum <= b);
      if (before >= tail_from) ++in_tail;
      // Greedy: the next item would not have fitted (or the chunk is full, or the window ends).
      if (end < cost.size() && end - begin < max_items && before + sum < tail_from) CHECK(sum + cost[end] > budget);
      before += sum;
      at = end;
    }
    CHECK(at == cost.size());
    if (tail == 0) CHECK(in_tail == 0);
  }
  // 100 patches of 512 primitives with a tail of 16384: eight chunks of eight, the four patches before
  // the tail, then sixteen chunks of two.
  const std::vector<std::uint32_t> even(100, 512);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> chunks;
  detail::cut_chunks(even, 4096, 256, chunks, 16384);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
  for (std::uint32_t c = 0; c < 8; ++c) expected.emplace_back(8 * c, 8 * c + 8);
  expected.emplace_back(64, 68);
  for (std::uint32_t c = 0; c < 16; ++c) expected.emplace_back(68 + 2 * c, 70 + 2 * c);
  CHECK(chunks == expected);
  detail::cut_chunks(even, 4096, 256, chunks);  // no tail: thirteen chunks of eight and one of four
  CHECK(chunks.size() == 13);
  CHECK(chunks.back() == std::pair<std::uint32_t, std::uint32_t>(96, 100));
}

TEST_CASE("pipeline: a chunk's bins are a stable sort of its entries by tile, runs or not", "[pipeline][bins]") {
  // finish_bins counts and places runs of one tile at a time: compare it with std::stable_sort on entry
  // lists of long runs, single entries, a tile revisited after others, the first and last tiles, and none.
  constexpr int kTiles = 37;
  test::Rng rng(12345);
  const auto next = [&](std::uint32_t n) { return std::uint32_t(rng.integer(0, int(n) - 1)); };
  for (int trial = 0; trial < 200; ++trial) {
    ChunkBuffer<3> chunk;
    chunk.reset(kTiles);
    const std::uint32_t count = trial == 0 ? 0 : next(600) + 1;
    std::uint32_t tile = next(kTiles);
    for (std::uint32_t p = 0; p < count; ++p) {
      if (next(trial % 4 == 0 ? 2 : 10) == 0) tile = next(5) == 0 ? (next(2) ? 0u : kTiles - 1u) : next(kTiles);
      chunk.entries.emplace_back(tile, p);
      if (next(7) == 0) chunk.entries.emplace_back(next(kTiles), p);  // a primitive in two tiles
    }
    auto expected = chunk.entries;
    std::stable_sort(expected.begin(), expected.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    chunk.finish_bins();
    INFO("trial " << trial << ", " << chunk.entries.size() << " entries");
    REQUIRE(chunk.binned.size() == expected.size());
    std::vector<std::uint32_t> touched;
    std::size_t at = 0;
    for (int t = 0; t < kTiles; ++t) {
      const auto bin = chunk.bin(t);
      if (!bin.empty()) touched.push_back(std::uint32_t(t));
      for (const std::uint32_t p : bin) {
        REQUIRE(at < expected.size());
        CHECK(expected[at].first == std::uint32_t(t));
        CHECK(expected[at].second == p);
        ++at;
      }
    }
    CHECK(at == expected.size());
    CHECK(chunk.touched == touched);
  }
}

TEST_CASE("pipeline: default rounds follow the thread count, and a window holds a 2048-patch draw",
          "[pipeline][memory]") {
  // Two rounds of chunks on up to two threads, three from three up; a value given is kept.
  for (const int threads : {1, 2, 3, 4, 16}) {
    INFO("threads " << threads);
    CHECK(Device(DeviceOptions{threads}).options().rounds_in_flight == (threads <= 2 ? 2 : 3));
    DeviceOptions o{threads};
    o.rounds_in_flight = 5;
    CHECK(Device(o).options().rounds_in_flight == 5);
  }
  // The torus's 2048 patches in one window: each of its 64 x 32 cage vertices is shaded once (vertex
  // caching is per window); in windows of 1024 patches the seam's vertices are shaded twice.
  const int w = 256, h = 144;
  const render::TorusScene scene = render::make_torus_scene(w, h);
  const auto draw = render::make_torus_draw(scene, 4.0f, ts::Partitioning::integer, w, h);
  const auto vs_invocations = [&](DeviceOptions o) {
    Device device(o);
    auto fb = make_target(w, h);
    const DrawResult r = device.draw(draw, fb);
    REQUIRE(r.ok());
    return r.report.statistics.VSInvocations;
  };
  CHECK(vs_invocations(DeviceOptions{2}) == std::uint64_t(render::kTorusColumns * render::kTorusRows));
  DeviceOptions half{2};
  half.window_patches = 1024;
  CHECK(vs_invocations(half) > std::uint64_t(render::kTorusColumns * render::kTorusRows));
}

TEST_CASE("pipeline: geometry memory does not grow with the tessellation factor", "[pipeline][memory]") {
  const int w = 256, h = 144;
  const render::TorusScene scene = render::make_torus_scene(w, h);
  auto peak = [&](float factor) {
    // A device per factor: a device keeps its chunk slots' storage from draw to draw, so a second
    // draw's report would include what the first one grew.
    Device device(DeviceOptions{2});
    auto fb = make_target(w, h);
    const DrawResult r = device.draw(render::make_torus_draw(scene, factor, ts::Partitioning::integer, w, h), fb);
    REQUIRE(r.ok());
    return double(r.report.memory.geometry_peak_bytes + r.report.memory.framebuffer_bytes);
  };
  const double at8 = peak(8.0f), at64 = peak(64.0f);
  INFO("factor 8: " << at8 << " bytes, factor 64: " << at64 << " bytes");
  CHECK(at64 <= 1.25 * at8);
}

TEST_CASE("pipeline: bad draws are rejected with a message", "[pipeline][bad-input]") {
  Device device(DeviceOptions{1});
  QuadScene s = two_patches(8, 8);
  auto fb = make_target(8, 8);
  QuadDraw d = quad_draw(s, 8, 8, 2.0f);
  d.viewport.width = 0;
  DrawResult r = device.draw(d, fb);
  CHECK_FALSE(r.ok());
  CHECK_THAT(r.error, Catch::Contains("zero area"));
  d.viewport = full_viewport(8, 8);
  d.viewport.x = std::numeric_limits<float>::quiet_NaN();
  CHECK_THAT(device.draw(d, fb).error, Catch::Contains("non-finite"));
  d.viewport = full_viewport(8, 8);
  d.control_points = 33;
  CHECK_THAT(device.draw(d, fb).error, Catch::Contains("1..32"));
  d.control_points = 3;
  CHECK_THAT(device.draw(d, fb).error, Catch::Contains("not a multiple"));
  d.control_points = 4;
  d.tessellator.domain = ts::Domain::isoline;
  CHECK_THAT(device.draw(d, fb).error, Catch::Contains("isoline"));

  std::string error;
  CHECK_FALSE(Framebuffer::create(0, 10, ColorFormat::rgba8_unorm, &error));
  CHECK_THAT(error, Catch::Contains("0x10"));
  CHECK_FALSE(Framebuffer::create(100000, 100000, ColorFormat::rgba8_unorm, &error));
  CHECK_THAT(error, Catch::Contains("16384"));
}

TEST_CASE("pipeline: out-of-range factors are culled or clamped as D3D11 does", "[pipeline][bad-input]") {
  Device device(DeviceOptions{2});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  struct Case {
    float factor;
    std::uint64_t domain_points;
  } cases[] = {{nan, 0},  {-1.0f, 0}, {0.0f, 0}, {1e30f, 65 * 65}, {std::numeric_limits<float>::infinity(), 65 * 65},
               {0.25f, 4}};
  for (const auto& c : cases) {
    INFO("factor " << c.factor);
    QuadScene s = two_patches(16, 16);
    auto fb = make_target(16, 16);
    const DrawResult r = device.draw(quad_draw(s, 16, 16, c.factor), fb);
    REQUIRE(r.ok());
    CHECK(r.report.statistics.HSInvocations == 2);
    CHECK(r.report.statistics.DSInvocations == 2 * c.domain_points);
  }
}

TEST_CASE("pipeline: NaN positions discard their primitives, bad indices fetch a zero vertex",
          "[pipeline][bad-input]") {
  Device device(DeviceOptions{2, 16});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<ClipVertex<1>> v = {clip_vertex<1>(-1, -1, 0.5f, 1), clip_vertex<1>(-1, 1, 0.5f, 1),
                                  clip_vertex<1>(1, -1, 0.5f, 1), clip_vertex<1>(nan, 0, 0.5f, 1)};
  auto draw = [&](std::vector<std::uint32_t> idx, std::vector<int>& counts) {
    auto fb = make_target(8, 8);
    MeshDraw<ClipVertex<1>, ClipPassVS<1>, CountingPS<1>> d;
    d.vertices = v;
    d.indices = idx;
    d.ps = {&counts, 8};
    d.rasterizer.cull = CullMode::none;
    d.viewport = full_viewport(8, 8);
    const DrawResult r = device.draw(d, fb);
    REQUIRE(r.ok());
    return r.report.statistics;
  };
  std::vector<int> counts(64, 0);
  // A NaN coordinate discards the whole triangle.
  PipelineStatistics st = draw({0, 3, 2}, counts);
  CHECK(st.CInvocations == 1);
  CHECK(st.CPrimitives == 0);
  CHECK(st.PSInvocations == 0);
  // Index 1000 is past the buffer: the VS sees a zero vertex (w = 0), which the clipper cuts away at
  // w = kMinClipW; nothing reaches the pixels and nothing crashes.
  st = draw({0, 1, 1000}, counts);
  CHECK(st.CInvocations == 1);
  CHECK(st.VSInvocations == 3);
  CHECK(st.PSInvocations == 0);
  // The intact triangle is the lower-left half of the target: the 28 pixel centres strictly below the
  // diagonal. The 8 centres on the diagonal lie on a right edge, which the top-left rule excludes.
  st = draw({0, 1, 2}, counts);
  CHECK(st.CPrimitives == 1);
  int lit = 0;
  for (int c : counts) lit += c;
  CHECK(lit == 28);
}
