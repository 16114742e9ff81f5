// Displacement mapping on the subdivision schemes: map loading (EXR, TIFF, PNG 8/16, DDS), watertight
// displaced surfaces on the monster frog (welded on exact bits) and the cracks without ownership,
// determinism, and one-line errors.
#include <catch2/catch.hpp>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "cli_runner.h"
#include "shaders_cpp/render/displaced_model.h"
#include "shaders_cpp/render/displaced_render.h"
#include "test_data.h"
#include "tools/verify/weld_check.h"
#include "weld_support.h"

namespace fs = std::filesystem;
using namespace tessera;
using tessera::test::check_watertight;
using tessera::test::data;
using tessera::test::kVaryingFactors;
using tessera::test::VaryingFactors;

namespace {

const std::string kFrog = data("sdk-cages/monsterfrog_mapped_00.obj");
const std::string kFrogMap = data("sdk-cages/monsterfrog.dds");

fs::path temp_dir() { return test::cli_temp_dir(); }

// Writes w x h x c pixels of `type` (values given as floats, converted by OIIO).
std::string write_image(const std::string& name, int w, int h, int c, OIIO::TypeDesc type, const std::vector<float>& px,
                        std::vector<std::string> names = {}) {
  const std::string path = (temp_dir() / name).string();
  auto out = OIIO::ImageOutput::create(path);
  REQUIRE(out);
  OIIO::ImageSpec spec(w, h, c, type);
  if (!names.empty()) spec.channelnames = names;
  REQUIRE(out->open(path, spec));
  REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
  out->close();
  return path;
}

// A 3-channel float vector displacement map made from the frog's normal map and height, written to
// the test directory as `name` (EXR).
std::string write_vector_map(const std::string& name) {
  const auto n = DisplacementMap::load(kFrogMap, "R,G,A", 3);
  std::vector<float> px;
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) {
      const glm::vec4 t = n.texture().load(0, x, y);
      px.insert(px.end(), {t.x - 0.5f, t.y - 0.5f, t.z});
    }
  return write_image(name, 512, 512, 3, OIIO::TypeDesc::FLOAT, px);
}

std::vector<float> ramp(int n, float scale) {
  std::vector<float> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[std::size_t(i)] = float((i * 37) % 256) * scale;
  return v;
}

verify::WeldReport weld_displaced(const SubdModel& m, const Displacement& d, float factor, float vary,
                                  ts::Partitioning p, int threads = 2, std::uint64_t* digest = nullptr) {
  DeviceOptions o;
  o.threads = threads;
  o.chunk_primitives = threads == 1 ? 16384 : 777;
  Device device(o);
  verify::WeldChecker w;
  SubdFactors f;
  f.factor = factor;
  f.vary = vary;
  std::uint64_t h = 1469598103934665603ull;
  const DrawResult r =
      stream_displaced(device, m, d, f, p, [&](const PatchOutput<DisplacedPoint>& out, const PatchGroup&) {
        for (std::size_t i = 0; i + 2 < out.indices.size(); i += 3)
          w.add_triangle(out.points[out.indices[i]].position, out.points[out.indices[i + 1]].position,
                         out.points[out.indices[i + 2]].position);
        for (const DisplacedPoint& q : out.points)
          for (float x : {q.position.x, q.position.y, q.position.z, q.normal.x, q.dpdu.y, q.uv.x})
            h = (h ^ std::bit_cast<std::uint32_t>(x)) * 1099511628211ull;
      });
  REQUIRE(r.ok());
  if (digest) *digest = h;
  return w.report();
}

// A float height map that changes from every texel to the next (the frog's own map is mid-grey along
// its UV seams, so it alone could not show a seam crack): a hash of the texel.
std::string noise_map() {
  static const std::string path = [] {
    std::vector<float> px(256 * 256);
    for (std::uint32_t i = 0; i < px.size(); ++i) {
      std::uint32_t x = i * 2654435761u;
      x ^= x >> 15;
      x *= 2246822519u;
      x ^= x >> 13;
      px[i] = float(x % 1000u) / 1000.0f;
    }
    return write_image("noise.exr", 256, 256, 1, OIIO::TypeDesc::FLOAT, px);
  }();
  return path;
}

DisplacementOptions noise_options() {
  DisplacementOptions o;
  o.map = noise_map();
  o.scale = 0.8f;
  o.bias = -0.4f;
  return o;
}

DisplacementOptions frog_options() {
  // Designated initializers: GCC 12's -Wrestrict misfires on assigning a literal to a std::string here.
  return DisplacementOptions{.map = kFrogMap,
                             .channel = std::string("A"),
                             .scale = 0.8f,
                             .bias = -0.4f};  // large, so that any disagreement shows
}

using test::run_cli;

}  // namespace

TEST_CASE("Displacement maps load from EXR, TIFF, PNG 8 and 16 bit with channel selection and mips", "[disp]") {
  const int w = 8, h = 4;
  SECTION("float EXR, one channel") {
    std::vector<float> px = ramp(w * h, 0.01f);
    px[5] = -2.5f;  // floats keep their sign and range
    const auto m = DisplacementMap::load(write_image("h.exr", w, h, 1, OIIO::TypeDesc::FLOAT, px));
    CHECK(m.channels() == 1);
    CHECK(m.width() == 8);
    CHECK(m.height() == 4);
    CHECK(m.levels() == 4);  // 8x4, 4x2, 2x1, 1x1
    for (int i = 0; i < w * h; ++i) CHECK(m.texture().load(0, i % w, i / w).x == px[std::size_t(i)]);
  }
  SECTION("float TIFF, three channels picked by name and reordered") {
    const std::vector<float> px = ramp(w * h * 3, 0.5f);
    const std::string path = write_image("v.tif", w, h, 3, OIIO::TypeDesc::FLOAT, px);
    const auto rgb = DisplacementMap::load(path);  // three channels: a vector by default
    CHECK(rgb.channels() == 3);
    const auto bgr = DisplacementMap::load(path, "B,G,R", 3);
    const auto g = DisplacementMap::load(path, "g", 1);
    for (int i = 0; i < w * h; ++i) {
      const glm::vec4 t = bgr.texture().load(0, i % w, i / w);
      CHECK(t.x == px[std::size_t(3 * i + 2)]);
      CHECK(t.z == px[std::size_t(3 * i)]);
      CHECK(g.texture().load(0, i % w, i / w).x == px[std::size_t(3 * i + 1)]);
    }
  }
  SECTION("8-bit PNG RGBA: the alpha by letter maps 0..255 to 0..1") {
    std::vector<float> px(std::size_t(w * h * 4));
    for (std::size_t i = 0; i < px.size(); ++i) px[i] = float((i * 53) % 256) / 255.0f;
    const std::string path = write_image("rgba8.png", w, h, 4, OIIO::TypeDesc::UINT8, px);
    const auto a = DisplacementMap::load(path, "A", 1);
    for (int i = 0; i < w * h; ++i)
      CHECK(a.texture().load(0, i % w, i / w).x == Approx(px[std::size_t(4 * i + 3)]).epsilon(1e-6));
    CHECK_THROWS_AS(DisplacementMap::load(path), DisplacementMapError);  // RGBA is ambiguous without a channel
  }
  SECTION("16-bit PNG grey") {
    std::vector<float> px(std::size_t(w * h));
    for (int i = 0; i < w * h; ++i) px[std::size_t(i)] = float(i * 2000) / 65535.0f;
    const auto m = DisplacementMap::load(write_image("h16.png", w, h, 1, OIIO::TypeDesc::UINT16, px));
    for (int i = 0; i < w * h; ++i)
      CHECK(m.texture().load(0, i % w, i / w).x == Approx(px[std::size_t(i)]).epsilon(1e-6));
    // The top mip is the mean of level 0.
    double mean = 0;
    for (float x : px) mean += x;
    CHECK(m.texture().load(m.levels() - 1, 0, 0).x == Approx(mean / double(px.size())).epsilon(1e-5));
  }
  SECTION("DDS: the monster frog's BGRA8, height in A") {
    const auto a = DisplacementMap::load(kFrogMap, "A", 1);
    CHECK(a.width() == 512);
    CHECK(a.height() == 512);
    CHECK(a.levels() == 10);
    float lo = 1, hi = 0;
    double sum = 0;
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 512; ++x) {
        const float height = a.texture().load(0, x, y).x;
        lo = std::min(lo, height), hi = std::max(hi, height), sum += height;
      }
    // What `oiiotool monsterfrog.dds --ch A -d uint8 -o a.pgm` gives: bytes 95..249, mean 135.14.
    CHECK(lo == Approx(95.0f / 255.0f));
    CHECK(hi == Approx(249.0f / 255.0f));
    CHECK(sum / (512.0 * 512.0) == Approx(135.14 / 255.0).epsilon(1e-4));
    const auto n = DisplacementMap::load(kFrogMap, "RGB", 3);
    double z = 0;
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 512; ++x) z += n.texture().load(0, x, y).z;
    CHECK(z / (512.0 * 512.0) > 0.9);  // a tangent-space normal map: blue near 1
  }
  SECTION("errors name the file") {
    const std::string path = write_image("two.exr", w, h, 2, OIIO::TypeDesc::FLOAT, ramp(w * h * 2, 1.0f), {"U", "V"});
    auto message = [&](auto f) {
      try {
        f();
      } catch (const DisplacementMapError& e) {
        return std::string(e.what());
      }
      return std::string("no error");
    };
    const std::string none = message([&] { DisplacementMap::load(path); });
    CHECK(none.rfind(path + ": ", 0) == 0);
    CHECK(none.find("U, V") != std::string::npos);
    const std::string bad = message([&] { DisplacementMap::load(path, "Q"); });
    CHECK(bad.find("no channel 'Q'") != std::string::npos);
    const std::string count = message([&] { DisplacementMap::load(path, "U,V", 3); });
    CHECK(count.find("needs 3") != std::string::npos);
    const std::string missing = message([&] { DisplacementMap::load(path + ".missing.png"); });
    CHECK(missing.rfind(path + ".missing.png: ", 0) == 0);
    const std::string text = (temp_dir() / "not-an-image.png").string();
    std::ofstream(text) << "hello\n";
    const std::string unreadable = message([&] { DisplacementMap::load(text); });
    CHECK(unreadable.rfind(text + ": ", 0) == 0);
    // A wrong channel is reported from the header, before the pixels are decoded: here they are cut
    // off, so a decode first would report that instead.
    const std::string big =
        write_image("big.exr", 512, 512, 2, OIIO::TypeDesc::FLOAT, ramp(512 * 512 * 2, 1.0f), {"U", "V"});
    fs::resize_file(big, fs::file_size(big) / 2);
    const std::string early = message([&] { DisplacementMap::load(big, "Q"); });
    CHECK(early.find("no channel 'Q'") != std::string::npos);
    const std::string truncated = message([&] { DisplacementMap::load(big, "U"); });
    CHECK(truncated.rfind(big + ": ", 0) == 0);
    CHECK(truncated.find("no channel") == std::string::npos);
    for (const auto& m : {none, bad, count, missing, unreadable, early, truncated})
      CHECK(m.find('\n') == std::string::npos);
  }
}

TEST_CASE(
    "The displaced monster frog is watertight on exact bits: acc, gregory, exact, bspline, integer and fractional "
    "factors varying per edge",
    "[disp]") {
  for (Scheme s : {Scheme::acc, Scheme::gregory, Scheme::exact, Scheme::bspline}) {
    const SubdModel m = load_subd_model(kFrog, s);
    const Displacement d = make_displacement(m, frog_options());
    const Displacement noise = make_displacement(m, noise_options());
    CHECK(weld_displaced(m, noise, 2.3f, 1.7f, ts::Partitioning::fractional_odd).closed_manifold());
    for (const VaryingFactors c : kVaryingFactors) {
      INFO(to_string(s) << " " << ts::to_string(c.partitioning));
      check_watertight(weld_displaced(m, d, c.factor, c.vary, c.partitioning));
    }
  }
}

TEST_CASE("Owner frames are stored once per distinct unit and read back identically by every patch sharing an element",
          "[disp]") {
  for (Scheme s : {Scheme::acc, Scheme::gregory, Scheme::bspline}) {
    INFO(to_string(s));
    const SubdModel m = load_subd_model(kFrog, s);
    const Displacement d = make_displacement(m, frog_options());
    const PatchGroup& g = m.patches.quads;
    const Topology& t = *m.topology;
    const PatchFrames& f = d.frames;
    REQUIRE(f.units.size() == 8 * g.size());
    // Sharing has to pay: far fewer distinct units than patch edges and corners, and a small per-patch cost.
    CHECK(std::size_t(f.unit_count) * 4 < 8 * g.size());
    CHECK(f.bytes() < 200 * g.size());
    // Stencil r of patch p as the hull shader reads it: (global vertex, weight bits) in the patch's order.
    auto read = [&](std::size_t p, int r) {
      const SubdPatch& patch = g.patches[p];
      const std::uint32_t i = f.stencil(p, r), mask = f.masks[i];
      std::vector<std::pair<std::uint32_t, std::uint32_t>> terms;
      for (int k = 0; k < patch.ring_size; ++k) {
        const int j = patch.order[std::size_t(k)];
        if ((mask >> j & 1u) == 0) continue;
        const float w = f.weights[f.starts[i] + std::uint32_t(std::popcount(mask & ((1u << j) - 1u)))];
        terms.emplace_back(g.indices[p * std::size_t(g.control_points) + std::size_t(j)],
                           std::bit_cast<std::uint32_t>(w));
      }
      return terms;
    };
    std::map<std::pair<char, int>, std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>>> first;
    int shared = 0, differ = 0, empty = 0;
    for (std::size_t p = 0; p < g.size(); ++p) {
      const SubdPatch& patch = g.patches[p];
      for (int k = 0; k < 4; ++k) {
        const int h = t.face_offset(patch.face) + (k + patch.rotation) % 4;
        for (const auto& [key, r0, n] : {std::tuple{std::pair{'e', t.edge(h)}, 8 * k, 8},
                                         std::tuple{std::pair{'v', t.origin(h)}, 32 + 2 * k, 2}}) {
          std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> frame;
          for (int r = r0; r < r0 + n; ++r) frame.push_back(read(p, r)), empty += frame.back().empty();
          const auto [it, added] = first.emplace(key, frame);
          if (!added) ++shared, differ += it->second != frame;
        }
      }
    }
    CHECK(shared >= int(4 * g.size()));  // every edge twice, every vertex at least twice
    CHECK(differ == 0);
    CHECK(empty == 0);
  }
}

TEST_CASE("Vector displacement (tangent and object space) on the frog is watertight too", "[disp]") {
  const std::string path = write_vector_map("vector.exr");
  for (Scheme s : {Scheme::acc, Scheme::gregory, Scheme::exact}) {
    const SubdModel m = load_subd_model(kFrog, s);
    for (DisplacementSpace space : {DisplacementSpace::tangent, DisplacementSpace::object}) {
      DisplacementOptions o;
      o.map = path;
      o.scale = 0.5f;
      o.space = space;
      const Displacement d = make_displacement(m, o);
      CHECK(d.kind ==
            (space == DisplacementSpace::tangent ? DisplacementKind::vector_tangent : DisplacementKind::vector_object));
      INFO(to_string(s) << (space == DisplacementSpace::tangent ? " tangent" : " object"));
      const auto r = weld_displaced(m, d, 2.5f, 1.5f, ts::Partitioning::fractional_odd);
      CHECK(r.closed_manifold());
    }
  }
}

TEST_CASE("Without ownership the displaced frog cracks: per-face UVs at the seams, per-patch normals on edges",
          "[disp]") {
  for (Scheme s : {Scheme::acc, Scheme::gregory, Scheme::exact}) {
    const SubdModel m = load_subd_model(kFrog, s);
    DisplacementOptions o = noise_options();
    o.ownership = UvOwnership::per_face;
    const auto naive_uv = weld_displaced(m, make_displacement(m, o), 3.0f, 1.0f, ts::Partitioning::integer);
    INFO(to_string(s) << ": per-face UVs give " << naive_uv.open_edges << " open edges");
    CHECK(naive_uv.open_edges > 0);
    if (s == Scheme::exact) continue;  // the limit surface's normals are owned already
    o = noise_options();
    o.shared_normals = false;
    const auto own_normals = weld_displaced(m, make_displacement(m, o), 3.0f, 1.0f, ts::Partitioning::integer);
    INFO(to_string(s) << ": per-patch normals give " << own_normals.open_edges << " open edges");
    CHECK(own_normals.open_edges > 0);
  }
}

// The scalar displaced DS, keeping each patch's constants and control points (one thread: a test's
// stream output on a one-thread device) so that the batch form can be run on the same inputs.
struct KeepingDS {
  DisplacedDS ds;
  std::map<std::uint32_t, std::pair<DisplacedPatchConstants, std::vector<SubdControlPoint>>>* kept;
  DisplacedPoint operator()(const DisplacedPatchConstants& pc, std::span<const SubdControlPoint> cp, DomainLocation loc,
                            std::uint32_t id) const {
    kept->try_emplace(id, pc, std::vector<SubdControlPoint>(cp.begin(), cp.end()));
    return ds(pc, cp, loc, id);
  }
};

TEST_CASE("The displaced DS's batch form gives every point the scalar form's bits", "[disp]") {
  // Scalar, tangent-space and object-space maps (the map sampled four points at a time where they share
  // a LOD, the patch in lanes where its kind allows), bilinear and trilinear, varying factors, on
  // every patch of the frog under each scheme the render path batches, and one it does not.
  const std::string vector_path = write_vector_map("batch-vector.exr");
  std::size_t compared = 0, mismatched = 0;
  for (const Scheme scheme : {Scheme::gregory, Scheme::acc, Scheme::bspline, Scheme::exact}) {
    const SubdModel m = load_subd_model(kFrog, scheme);
    for (int variant = 0; variant < 3; ++variant) {
      DisplacementOptions o = frog_options();
      if (variant > 0) {
        o.map = vector_path;
        o.channel.clear();
        o.scale = 0.5f;
        o.bias = 0.0f;
        o.space = variant == 1 ? DisplacementSpace::tangent : DisplacementSpace::object;
      }
      Displacement d = make_displacement(m, o);
      for (const bool trilinear : {false, true}) {
        if (scheme == Scheme::exact && trilinear) continue;  // slow, and its DS is not batched
        d.trilinear = trilinear;
        SubdFactors f;
        f.factor = 5.0f;
        f.vary = 1.5f;
        std::map<std::uint32_t, std::pair<DisplacedPatchConstants, std::vector<SubdControlPoint>>> kept;
        Device device(DeviceOptions{1});
        const DrawResult r = with_displaced_group(
            m, d, f, PatchCull{}, ts::Partitioning::fractional_odd,
            [&](const PatchGroup& g, const TessellatorState& ts, const DisplacedHS& hs, const DisplacedDS& ds) {
              const StreamDraw<glm::vec3, SubdVS, DisplacedHS, KeepingDS> draw{
                  m.vertex_buffer(), g.indices, g.control_points, m.vertex_shader(), hs, KeepingDS{ds, &kept}, ts};
              return stream_out(device, draw, [&](const PatchOutput<DisplacedPoint>& p) {
                const auto& [pc, cp] = kept.at(p.patch_id);
                std::vector<DomainLocation> locations;
                for (const ts::DomainPoint& q : p.domain) locations.push_back(detail::domain_location(q, ts.domain));
                std::vector<DisplacedPoint> batch(locations.size());
                ds.samples(pc, cp, locations, p.patch_id, batch);
                for (std::size_t i = 0; i < batch.size(); ++i) {
                  ++compared;
                  if (std::memcmp(&batch[i], &p.points[i], sizeof(DisplacedPoint)) != 0) ++mismatched;
                }
              });
            });
        INFO(to_string(scheme) << " variant " << variant << (trilinear ? " trilinear" : " bilinear"));
        REQUIRE(r.ok());
        CHECK(mismatched == 0);
      }
    }
  }
  CHECK(compared > 200000);
}

// DisplacedPS without its quad form: the pipeline shades each pixel through operator().
struct PerPixelDisplacedPS {
  DisplacedPS ps;
  glm::vec4 operator()(const PixelInput<kDisplacedAttributes>& in) const { return ps(in); }
};

TEST_CASE("The displaced pixel shader's quad form gives the per-pixel form's bits", "[disp]") {
  // The frog's normal map (one sample_grad4 per quad) and derived normals (the height's taps), seam
  // blending on and off, single-sampled and 4x: render_displaced (the quad form) against the same
  // draw shading pixel by pixel.
  static_assert(QuadPixelShader<DisplacedPS, kDisplacedAttributes> &&
                !QuadPixelShader<PerPixelDisplacedPS, kDisplacedAttributes>);
  const SubdModel m = load_subd_model(kFrog, Scheme::gregory);
  for (const bool derived : {false, true}) {
    DisplacementOptions o = frog_options();
    if (derived) o.normal_map = "derived";
    for (const bool seams : {true, false}) {
      o.seam_blending = seams;
      const Displacement d = make_displacement(m, o);
      REQUIRE(d.normal_maps.empty() == derived);
      for (const int samples : {1, 4}) {
        const int w = 256, h = 160;
        const SubdCamera camera = frame_cage(m.cage, w, h, 35.0f, std::nullopt, std::nullopt);
        SubdFactors f;
        f.factor = 6.0f;
        Device device(DeviceOptions{2});
        auto quad = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, nullptr, samples);
        auto pixel = Framebuffer::create(w, h, ColorFormat::rgba8_unorm, nullptr, samples);
        REQUIRE((quad && pixel));
        quad->clear(glm::vec4(0.0f), 1.0f);
        pixel->clear(glm::vec4(0.0f), 1.0f);
        REQUIRE(render_displaced(device, m, d, f, PatchCull{}, ts::Partitioning::integer, SubdView::shaded, camera, *quad).ok());
        const DrawResult r = with_displaced_group(
            m, d, f, PatchCull{}, ts::Partitioning::integer,
            [&](const PatchGroup& g, const TessellatorState& ts, const DisplacedHS& hs, const DisplacedDS& ds) {
              const SubdPassState st = subd_pass_state(m, *pixel, false);
              const DisplacedProjectDS<DisplacedDS> project{ds, camera.view_projection, st.z_bias};
              PerPixelDisplacedPS per_pixel;
              DisplacedPS& ps = per_pixel.ps;
              ps.light = glm::normalize(camera.eye - camera.target);
              ps.sides = face_sides(m);
              ps.texcoords = d.texcoords;
              ps.seam_blending = d.seam_blending;
              if (!d.normal_maps.empty()) {
                ps.normal_maps = d.normal_maps;
                ps.flip_green = d.flip_v;
              } else {
                ps.heights = d.maps;
                ps.height_scale = d.scale;
              }
              return draw_group_pass(device, m, g, ts, hs, project, per_pixel, st, *pixel);
            });
        REQUIRE(r.ok());
        INFO((derived ? "derived" : "normal map") << (seams ? ", seams blended" : "") << ", " << samples << "x");
        const Framebuffer a = quad->resolve(), b = pixel->resolve();
        CHECK(a.color_bytes() == b.color_bytes());
        CHECK(std::count_if(a.color_bytes().begin(), a.color_bytes().end(), [](std::uint8_t x) { return x != 0; }) >
              10000);
      }
    }
  }
}

TEST_CASE("Displaced stream output and rendering give the same bytes for 1 and 2 threads", "[disp]") {
  const SubdModel m = load_subd_model(kFrog, Scheme::gregory);
  const Displacement d = make_displacement(m, frog_options());
  std::uint64_t one = 0, two = 0;
  weld_displaced(m, d, 3.5f, 1.0f, ts::Partitioning::fractional_odd, 1, &one);
  weld_displaced(m, d, 3.5f, 1.0f, ts::Partitioning::fractional_odd, 2, &two);
  CHECK(one == two);
  auto image = [&](int threads) {
    DeviceOptions o;
    o.threads = threads;
    Device device(o);
    auto fb = Framebuffer::create(160, 120, ColorFormat::rgba8_unorm, nullptr);
    REQUIRE(fb);
    fb->clear(glm::vec4(0.0f), 1.0f);
    SubdFactors f;
    f.factor = 4.0f;
    const SubdCamera cam = frame_cage(m.cage, 160, 120, 35.0f, std::nullopt, std::nullopt);
    REQUIRE(render_displaced(device, m, d, f, PatchCull{}, ts::Partitioning::integer, SubdView::shaded, cam, *fb).ok());
    return fb->color_bytes();
  };
  const auto a = image(1);
  CHECK(std::count_if(a.begin(), a.end(), [](std::uint8_t x) { return x != 0; }) > 1000);  // the frog is drawn
  CHECK(image(2) == a);
}

TEST_CASE("tessera with --displacement: watertight frog, render, and one-line errors naming the file", "[disp][cli]") {
  const std::string out = (temp_dir() / "displaced-frog.png").string();
  auto r = run_cli("tessellate " + kFrog +
                   " --scheme acc --factor 3 --vary-factors 1 --partitioning fractional_odd "
                   "--displacement " +
                   kFrogMap +
                   " --displacement-channel A --displacement-scale 0.6 "
                   "--displacement-bias -0.3 --check-watertight --json");
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("\"closed_manifold\": true") != std::string::npos);
  r = run_cli("render " + kFrog + " --scheme gregory --factor 3 --resolution 96x64 --displacement " + kFrogMap +
              " --displacement-channel A -o " + out);
  CHECK(r.exit_code == 0);
  CHECK(fs::exists(out));

  const std::string two = write_image("cli-two.exr", 4, 4, 2, OIIO::TypeDesc::FLOAT, ramp(32, 1.0f));
  struct Bad {
    std::string args, names;
  };
  for (const Bad& b :
       {Bad{"--displacement " + kFrogMap + ".missing.dds", kFrogMap + ".missing.dds"},
        Bad{"--displacement " + kFrogMap + " --displacement-channel Q", kFrogMap},
        Bad{"--displacement " + kFrogMap, kFrogMap},  // RGBA: which channel?
        Bad{"--displacement " + two, two},            // two channels: neither scalar nor vector
        Bad{"--displacement " + kFrogMap + " --displacement-channel R,G", kFrogMap},
        // A height has no object-space direction.
        Bad{"--displacement " + kFrogMap + " --displacement-channel A --displacement-space object", kFrogMap}}) {
    INFO(b.args);
    const auto e = run_cli("tessellate " + kFrog + " --scheme exact --check-watertight " + b.args);
    CHECK(e.exit_code != 0);
    CHECK(e.err.find(b.names) != std::string::npos);
    CHECK(std::count(e.err.begin(), e.err.end(), '\n') == 1);
  }
  // A cage without UVs, and a map whose UVs do not fit: both name the file.
  auto e = run_cli("tessellate " + data("sdk-cages/cube.obj") + " --scheme gregory --check-watertight --displacement " +
                   kFrogMap + " --displacement-channel A");
  CHECK(e.exit_code != 0);
  CHECK(e.err.find("cube.obj") != std::string::npos);
  CHECK(e.err.find("texture coordinates") != std::string::npos);
  const std::string shifted = (temp_dir() / "shifted.obj").string();
  {
    std::ifstream in(kFrog);
    std::ofstream o(shifted);
    std::string line;
    bool done = false;
    while (std::getline(in, line)) {
      if (!done && line.rfind("vt ", 0) == 0) line = "vt 1.5 0.5", done = true;
      o << line << "\n";
    }
  }
  e = run_cli("render " + shifted + " --scheme gregory --resolution 32x32 -o " + out + ".bad.png --displacement " +
              kFrogMap + " --displacement-channel A");
  CHECK(e.exit_code != 0);
  CHECK(e.err.find(kFrogMap) != std::string::npos);
  CHECK(e.err.find("vt 1") != std::string::npos);
  CHECK(!fs::exists(out + ".bad.png"));
  // Schemes whose patches hold only their face cannot carry the shared frames: a clear refusal.
  for (const char* scheme : {"flat", "pn"}) {
    e = run_cli("tessellate " + kFrog + " --scheme " + scheme + " --factor 2 --check-watertight --displacement " +
                kFrogMap + " --displacement-channel A");
    CHECK(e.exit_code == 1);
    CHECK(std::count(e.err.begin(), e.err.end(), '\n') == 1);
    CHECK(e.err.find("cannot be displaced") != std::string::npos);
  }
}

namespace {

// The frog with its UVs doubled (u, v in [0, 2]: UDIM tiles 1001, 1002, 1011, 1012), written once.
std::string frog_in_four_tiles() {
  static const std::string path = [] {
    const std::string p = (temp_dir() / "frog-udim.obj").string();
    std::ifstream in(kFrog);
    std::ofstream o(p);
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("vt ", 0) == 0) {
        std::istringstream s(line.substr(3));
        float u = 0, v = 0;
        s >> u >> v;
        o << "vt " << std::setprecision(9) << 2.0f * u << " " << 2.0f * v << "\n";
      } else {
        o << line << "\n";
      }
    }
    return p;
  }();
  return path;
}

// A hash-noise height tile (as noise_map) seeded by `seed`, written as `folder/noise.<tile>.exr`.
void write_noise_tile(const fs::path& folder, int tile, std::uint32_t seed, int size = 128) {
  fs::create_directories(folder);
  std::vector<float> px(std::size_t(size * size));
  for (std::uint32_t i = 0; i < px.size(); ++i) {
    std::uint32_t x = (i + seed * 7919u) * 2654435761u;
    x ^= x >> 15;
    x *= 2246822519u;
    x ^= x >> 13;
    px[i] = float(x % 1000u) / 1000.0f;
  }
  write_image((folder / ("noise." + std::to_string(tile) + ".exr")).lexically_relative(temp_dir()).string(), size,
              size, 1, OIIO::TypeDesc::FLOAT, px);
}

}  // namespace

TEST_CASE("UDIM: one tile 1001 draws the single map's bits", "[disp][udim]") {
  const fs::path folder = temp_dir() / "udim-one";
  fs::create_directories(folder);
  fs::copy_file(noise_map(), folder / "noise.1001.exr", fs::copy_options::overwrite_existing);
  for (Scheme s : {Scheme::gregory, Scheme::exact}) {
    INFO(to_string(s));
    const SubdModel m = load_subd_model(kFrog, s);
    DisplacementOptions o = noise_options();
    const Displacement single = make_displacement(m, o);
    o.map = (folder / "noise.<UDIM>.exr").string();
    const Displacement tiled = make_displacement(m, o);
    REQUIRE(tiled.udim == std::vector<int>{1001});
    CHECK(tiled.maps.size() == 1);
    std::uint64_t a = 0, b = 0;
    weld_displaced(m, single, 2.3f, 1.7f, ts::Partitioning::fractional_odd, 2, &a);
    weld_displaced(m, tiled, 2.3f, 1.7f, ts::Partitioning::fractional_odd, 2, &b);
    CHECK(a == b);
  }
}

TEST_CASE("UDIM: the frog over four tiles is watertight on exact bits across tile borders", "[disp][udim]") {
  const fs::path folder = temp_dir() / "udim-four";
  for (const int tile : {1001, 1002, 1011, 1012}) write_noise_tile(folder, tile, std::uint32_t(tile));
  DisplacementOptions o = noise_options();
  o.map = (folder / "noise.<UDIM>.exr").string();
  for (Scheme s : {Scheme::gregory, Scheme::acc, Scheme::exact}) {
    const SubdModel m = load_subd_model(frog_in_four_tiles(), s);
    const Displacement d = make_displacement(m, o);
    REQUIRE(d.udim == std::vector<int>{1001, 1002, 1011, 1012});
    // Charts meet across the tile borders along seams of their own: some patch edges take their owner's
    // tile, another than the patch's.
    std::size_t other_tile = 0;
    for (const PatchTexcoords& tc : d.texcoords)
      for (int k = 0; k < 4; ++k) other_tile += tc.edge_tile[std::size_t(k)] != tc.tile ? 1 : 0;
    CHECK(other_tile > 0);
    for (const VaryingFactors c : kVaryingFactors) {
      INFO(to_string(s) << " " << ts::to_string(c.partitioning));
      check_watertight(weld_displaced(m, d, c.factor, c.vary, c.partitioning));
    }
  }
  // Each tile is read: another tile 1012 moves the surface.
  const SubdModel m = load_subd_model(frog_in_four_tiles(), Scheme::gregory);
  std::uint64_t before = 0, after = 0;
  weld_displaced(m, make_displacement(m, o), 3.0f, 0.0f, ts::Partitioning::integer, 2, &before);
  write_noise_tile(folder, 1012, 99u);
  weld_displaced(m, make_displacement(m, o), 3.0f, 0.0f, ts::Partitioning::integer, 2, &after);
  CHECK(before != after);
}

TEST_CASE("UDIM from the command line: render, scene file, and one-line errors naming the missing tiles",
          "[disp][udim][cli]") {
  const fs::path folder = temp_dir() / "udim-cli";
  for (const int tile : {1001, 1002, 1011, 1012}) write_noise_tile(folder, tile, std::uint32_t(tile), 32);
  const std::string pattern = (folder / "noise.<UDIM>.exr").string();
  const std::string out = (folder / "frog.png").string();
  auto r = run_cli("render '" + frog_in_four_tiles() + "' --scheme gregory --factor 3 --resolution 96x64 -v " +
                   "--displacement '" + pattern + "' --displacement-scale 0.8 --displacement-bias -0.4 -o " + out);
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("4 UDIM tiles 1001-1012") != std::string::npos);
  CHECK(fs::exists(out));
  // A scene file names the set relative to itself.
  const std::string scene = (folder / "frog.tessera.json").string();
  {
    std::ofstream s(scene);
    s << R"({"tessera_scene": 1, "asset": ")" << frog_in_four_tiles() << R"(", "scheme": "gregory", "factor": 3,
      "resolution": [96, 64], "displacement": {"map": "noise.<UDIM>.exr", "scale": 0.8, "bias": -0.4}})";
  }
  r = run_cli("render --scene " + scene + " -o " + out + ".scene.png");
  CHECK(r.exit_code == 0);
  CHECK(test::slurp(out + ".scene.png") == test::slurp(out));

  fs::remove(folder / "noise.1011.exr");
  fs::remove(folder / "noise.1002.exr");
  r = run_cli("render '" + frog_in_four_tiles() + "' --resolution 32x32 --displacement '" + pattern + "' -o " + out +
              ".bad.png");
  CHECK(r.exit_code == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find("2 tiles") != std::string::npos);
  CHECK(r.err.find("1002, 1011") != std::string::npos);
  CHECK(!fs::exists(out + ".bad.png"));
  // The doubled UVs with a single map: the error says how to name tiles.
  r = run_cli("render '" + frog_in_four_tiles() + "' --resolution 32x32 --displacement " + noise_map() + " -o " + out +
              ".bad.png");
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("<UDIM>") != std::string::npos);
  // A normal map must be a tile set too.
  r = run_cli("render " + kFrog + " --resolution 32x32 --displacement '" + (folder / "noise.<UDIM>.exr").string() +
              "' --normal-map " + kFrogMap + " -o " + out + ".bad.png");
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("needs the <UDIM> token") != std::string::npos);
}
