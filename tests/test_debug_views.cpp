// The debug views of `tessera render` and the per-patch statistics: every view draws, views differ,
// images are the same bytes for any thread count, statistics agree with the pipeline's counters, the
// crack finder finds open edges, overlays draw where they should, and bad options are one-line errors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <OpenImageIO/imageio.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "shaders_cpp/debug/overlay.h"
#include "test_data.h"
#include "tools/verify/weld_check.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using test::run_cli;

const std::string kFrog = test::data("sdk-cages/monsterfrog_mapped_00.obj");
const std::string kDisplaced = " --displacement " + test::data("sdk-cages/monsterfrog.dds") +
                               " --displacement-channel A --displacement-scale 1.2 --displacement-bias -0.6";
const std::string kCamera = " --camera-position 48,15,66 --camera-target -3,-2.5,2 --resolution 320x180";

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Pixels of an 8-bit image close to `rgb` (each channel within 40 of 255 * rgb).
long pixels_near(const fs::path& p, glm::vec3 rgb) {
  auto in = OIIO::ImageInput::open(p.string());
  REQUIRE(in);
  const OIIO::ImageSpec spec = in->spec();
  std::vector<unsigned char> px(std::size_t(spec.width) * std::size_t(spec.height) * 3);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  long n = 0;
  for (std::size_t i = 0; i < px.size(); i += 3) {
    bool near = true;
    for (std::size_t c = 0; c < 3; ++c) near &= std::abs(int(px[i + c]) - int(255.0f * rgb[int(c)])) <= 40;
    n += near;
  }
  return n;
}

// The box of the pixels that differ from the background (any channel by more than 8 of 255):
// {left, top, right, bottom}, inclusive; {-1, ...} when there are none. And the image's size.
struct DrawnBox {
  int left = -1, top = -1, right = -1, bottom = -1, width = 0, height = 0;
};
DrawnBox drawn_box(const fs::path& p) {
  auto in = OIIO::ImageInput::open(p.string());
  REQUIRE(in);
  const OIIO::ImageSpec spec = in->spec();
  std::vector<unsigned char> px(std::size_t(spec.width) * std::size_t(spec.height) * 3);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  DrawnBox b;
  b.width = spec.width, b.height = spec.height;
  const int bg[3] = {int(255.0f * 0.93f + 0.5f), int(255.0f * 0.94f + 0.5f), int(255.0f * 0.96f + 0.5f)};
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) {
      const unsigned char* q = &px[(std::size_t(y) * std::size_t(spec.width) + std::size_t(x)) * 3];
      bool differs = false;
      for (int c = 0; c < 3; ++c) differs |= std::abs(int(q[c]) - bg[c]) > 8;
      if (!differs) continue;
      if (b.left < 0) b = {x, y, x, y, b.width, b.height};
      b.left = std::min(b.left, x), b.right = std::max(b.right, x);
      b.top = std::min(b.top, y), b.bottom = std::max(b.bottom, y);
    }
  return b;
}

// The surface is whole (a margin on every side) and fills the image in its tighter direction.
void check_framed(const fs::path& p) {
  INFO(p.string());
  const DrawnBox b = drawn_box(p);
  INFO("drawn " << b.left << "," << b.top << " .. " << b.right << "," << b.bottom << " of " << b.width << "x"
                << b.height);
  REQUIRE(b.left >= 0);
  CHECK(b.left > 0);
  CHECK(b.top > 0);
  CHECK(b.right < b.width - 1);
  CHECK(b.bottom < b.height - 1);
  const double fill_x = double(b.right - b.left + 1) / b.width, fill_y = double(b.bottom - b.top + 1) / b.height;
  CHECK(std::max(fill_x, fill_y) > 0.75);
  // Centred: the margins on either side of the tighter direction differ by little.
  if (fill_y > fill_x)
    CHECK(std::abs(b.top - (b.height - 1 - b.bottom)) <= b.height / 10);
  else
    CHECK(std::abs(b.left - (b.width - 1 - b.right)) <= b.width / 10);
}

}  // namespace

TEST_CASE("The cage view colours creased edges and corners by sharpness", "[views][cli]") {
  // catmark_cube_creases2 (infinitely sharp and semi-sharp creases) against the same cage without its
  // tags: only the tagged one has red (infinite) edges, and its legend says what the colours mean.
  const fs::path dir = test::cli_temp_dir();
  const std::string tagged = test::data("osd-shapes/catmark_cube_creases2.obj");
  const fs::path plain = dir / "cube-untagged.obj";
  {
    std::ifstream in(tagged);
    std::ofstream out(plain);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("t ", 0) != 0) out << line << "\n";
  }
  const glm::vec3 red(0.85f, 0.05f, 0.05f);
  long counts[2] = {0, 0};
  int i = 0;
  for (const std::string& cage : {tagged, plain.string()}) {
    const fs::path out = dir / ("cage-view-" + std::to_string(i) + ".png");
    REQUIRE(run_cli("render " + cage + " --view cage --resolution 400x300 -o " + out.string()).exit_code == 0);
    counts[i++] = pixels_near(out, red);
  }
  CHECK(counts[0] > 500);
  CHECK(counts[1] == 0);
}

TEST_CASE("Every render view draws the displaced frog, the views differ, bytes do not depend on threads",
          "[views][cli]") {
  const fs::path dir = test::cli_temp_dir();
  std::set<std::string> images;
  const std::vector<std::string> views = {"shaded",       "wireframe",   "wire-on-shaded", "factors", "density",
                                          "patch-type",   "combination", "patch-id",       "normals", "uv",
                                          "displacement", "cage",        "cracks",         "culled"};
  for (const std::string& v : views) {
    const fs::path out = dir / ("view-" + v + ".png");
    const auto r = run_cli("render " + kFrog + " --scheme gregory --lod screen --partitioning fractional_odd" +
                           kDisplaced + kCamera + " --view " + v + " -o " + out.string());
    INFO(v << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("view " + v) != std::string::npos);
    images.insert(bytes_of(out));
  }
  CHECK(images.size() == views.size());  // every view is a different picture
  // The factors view with 1 and 2 threads: the same bytes.
  for (const int threads : {1, 2}) {
    const fs::path out = dir / ("factors-" + std::to_string(threads) + ".png");
    REQUIRE(run_cli("render " + kFrog + " --lod screen --partitioning fractional_odd" + kCamera +
                    " --view factors --threads " + std::to_string(threads) + " -o " + out.string())
                .exit_code == 0);
  }
  CHECK(bytes_of(dir / "factors-1.png") == bytes_of(dir / "factors-2.png"));
}

TEST_CASE("The crack view does not count the borders of culled patches as cracks, and two-pass views count once",
          "[views][cli]") {
  // A camera inside the displaced frog culls hundreds of patches; their neighbours' borders used to be
  // reported as 1446 open edges of a watertight surface. With --json the summary has the count.
  const fs::path dir = test::cli_temp_dir();
  const std::string inside = " --camera-position 20,5,12 --camera-target -3,-2.5,2 --resolution 320x180";
  const auto r =
      run_cli("render " + kFrog + kDisplaced + " --lod screen --partitioning fractional_odd --view cracks --json" +
              inside + " -o " + (dir / "cracks.png").string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["cracks"]["crack_edges"] == 0);
  CHECK(j["cracks"]["border_edges"] == 0);
  CHECK(j["patches_culled"].get<int>() > 100);
  // Views of two passes count the surface once: wire-on-shaded reports shaded's triangles.
  std::uint64_t triangles[2] = {0, 0};
  int k = 0;
  for (const char* v : {"shaded", "wire-on-shaded"}) {
    const auto w = run_cli("render " + kFrog + " --view " + v + " --json" + inside + " -o " +
                           (dir / (std::string(v) + ".png")).string());
    REQUIRE(w.exit_code == 0);
    triangles[k++] = nlohmann::json::parse(w.out)["triangles"].get<std::uint64_t>();
  }
  CHECK(triangles[0] > 0);
  CHECK(triangles[1] == triangles[0]);
  // An open sheet seen from behind (catmark_edgeonly from above) is named on stderr; the
  // frog, a closed surface, is not.
  const auto back = run_cli("render " + test::data("osd-shapes/catmark_edgeonly.obj") +
                            " --camera-position 0.3,6,1 --resolution 160x90 -o " + (dir / "back.png").string());
  REQUIRE(back.exit_code == 0);
  CHECK(back.err.find("faces away from the camera") != std::string::npos);
  const auto front = run_cli("render " + kFrog + " --resolution 160x90 -o " + (dir / "front.png").string());
  REQUIRE(front.exit_code == 0);
  CHECK(front.err.find("faces away") == std::string::npos);
  // An open cage has border edges in the same view, and no cracks: its boundary is where it ends.
  const auto open = run_cli("render " + test::data("osd-shapes/catmark_edgeonly.obj") +
                            " --view cracks --json --resolution 320x180 -o " + (dir / "open.png").string());
  REQUIRE(open.exit_code == 0);
  const auto cracks = nlohmann::json::parse(open.out)["cracks"];
  CHECK(cracks["border_edges"].get<int>() > 0);
  CHECK(cracks["crack_edges"] == 0);
}

TEST_CASE("Legends are drawn with the font tessera ships, and never without their text", "[views][cli]") {
  const fs::path dir = test::cli_temp_dir() / "legend-font";
  fs::create_directories(dir);
  const fs::path with = dir / "with.png";
  REQUIRE(run_cli("render " + kFrog + " --view factors" + kCamera + " -o " + with.string()).exit_code == 0);
  CHECK(pixels_near(with, glm::vec3(0.06f, 0.06f, 0.08f)) > 100);  // the text's ink
  // An image too small for the legend at its smallest size is refused in one line, nothing written.
  const fs::path tiny = dir / "tiny.png";
  const auto small = run_cli("render " + kFrog + " --view factors --resolution 16x16 -o " + tiny.string());
  CHECK(small.exit_code == 1);
  CHECK(small.err.find("16x16 is too small for the legend") != std::string::npos);
  CHECK(std::count(small.err.begin(), small.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(tiny));
  // The binaries alone, without the share/tessera/ beside them: the legend cannot be drawn, so the view
  // fails in one line naming the font and writes nothing; a view without a legend still renders.
  const fs::path bin = dir / "bare" / "bin";
  fs::create_directories(bin);
  for (const auto& f : fs::directory_iterator(fs::path(TESSERA_BIN).parent_path()))
    if (f.is_regular_file()) fs::copy_file(f.path(), bin / f.path().filename(), fs::copy_options::overwrite_existing);
  const auto bare = [&](const std::string& view, const fs::path& out) {
    const std::string cmd = (bin / "tessera").string() + " render " + kFrog + " --view " + view + kCamera + " -o " +
                            out.string() + " >/dev/null 2>" + (dir / "err.txt").string();
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  CHECK(bare("factors", dir / "bare.png") == 1);
  const std::string err = test::slurp(dir / "err.txt");
  CHECK(err.find("DejaVuSans.ttf") != std::string::npos);
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(dir / "bare.png"));
  CHECK(bare("shaded", dir / "bare-shaded.png") == 0);
  CHECK(fs::exists(dir / "bare-shaded.png"));
  // Views with and without a legend are written alike: RGBA.
  for (const fs::path& p : {with, dir / "bare-shaded.png"}) {
    auto in = OIIO::ImageInput::open(p.string());
    REQUIRE(in);
    CHECK(in->spec().nchannels == 4);
  }
}

TEST_CASE("render --stats: a row per patch, totals that match the pipeline's counters, histograms that sum",
          "[views][cli]") {
  const fs::path dir = test::cli_temp_dir();
  const fs::path stats = dir / "frog-stats.json";
  // A camera inside the frog: some patches are culled.
  const auto r = run_cli("render " + kFrog +
                         " --lod screen --partitioning fractional_odd --camera-position 20,5,12 "
                         "--camera-target -3,-2.5,2 --resolution 480x270 -o " +
                         (dir / "s.png").string() + " --stats " + stats.string());
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(bytes_of(stats));
  const auto& rows = j["patches"];
  REQUIRE(rows.size() == 1292);
  std::uint64_t triangles = 0, drawn = 0, culled = 0, away = 0;
  for (const auto& row : rows) {
    triangles += row["triangles"].get<std::uint64_t>();
    culled += row["culled"] == "frustum" ? 1 : 0;
    away += row["culled"] == "backface" ? 1 : 0;
    drawn += row["culled"] == "backface" ? 0 : row["triangles"].get<std::uint64_t>();
    CHECK(row["raw"]["edge"].size() == 4);
  }
  CHECK(culled > 0);
  CHECK(j["totals"]["patches_culled"] == culled);
  CHECK(j["totals"]["patches_back_culled"] == away);
  CHECK(j["totals"]["triangles"] == triangles);
  CHECK(j["totals"]["triangles_drawn"] == drawn);
  // The shaded view is one pass: the clipper saw exactly the table's triangles, less the patches the
  // back-patch test skipped.
  CHECK(j["statistics"]["CInvocations"] == drawn);
  std::uint64_t binned = 0;
  for (const auto& b : j["histograms"]["triangle_area_pixels"]) binned += b["count"].get<std::uint64_t>();
  CHECK(binned + j["totals"]["triangles_behind_eye"].get<std::uint64_t>() == triangles);
  CHECK(j["totals"]["triangles_streamed"] == triangles);
  std::uint64_t edge_factors = 0;
  for (const auto& b : j["histograms"]["edge_factors"]) edge_factors += b["count"].get<std::uint64_t>();
  CHECK(edge_factors == 4 * (1292 - culled));
  CHECK(j["lod"]["mode"] == "screen");
}

TEST_CASE("tessellate --stats: the rows and totals of the triangles it writes, --cull backface refused",
          "[views][cli]") {
  const fs::path dir = test::cli_temp_dir();
  const fs::path stats = dir / "tessellate-stats.json";
  const auto r = run_cli(
      "tessellate " + kFrog +
      " --lod screen --camera-position 20,5,12 --camera-target -3,-2.5,2 --cull all --json --stats " + stats.string());
  REQUIRE(r.exit_code == 0);
  const auto summary = nlohmann::json::parse(r.out);
  const auto j = nlohmann::json::parse(bytes_of(stats));
  REQUIRE(j["patches"].size() == 1292);
  std::uint64_t triangles = 0, culled = 0;
  for (const auto& row : j["patches"]) {
    triangles += row["triangles"].get<std::uint64_t>();
    culled += row["culled"] == "frustum" ? 1 : 0;
    CHECK(row["culled"] != "backface");  // nothing is skipped: tessellate writes every patch
  }
  CHECK(culled > 0);
  CHECK(triangles == summary["triangles"].get<std::uint64_t>());
  CHECK(j["totals"]["triangles_streamed"] == triangles);
  CHECK(j["statistics"]["DSInvocations"] == summary["ds_invocations"]);
  const auto bad = run_cli("tessellate " + kFrog + " --cull backface --stats " + stats.string());
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("--cull backface") != std::string::npos);
}

TEST_CASE("The crack finder returns exactly the open and non-manifold edges", "[views]") {
  verify::WeldChecker w;
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(1, 1, 0);
  w.add_triangle(a, b, c);
  w.add_triangle(b, d, c);  // shares b-c: four open edges remain
  auto edges = w.bad_edges();
  REQUIRE(edges.size() == 4);
  for (const auto& e : edges) {
    CHECK(e.kind == verify::WeldEdgeKind::crack);
    const bool diagonal = (e.a == b && e.b == c) || (e.a == c && e.b == b);
    CHECK_FALSE(diagonal);
  }
  w.add_triangle(b, c, glm::vec3(0.5f, 0.5f, 1.0f));  // b-c used a second time the same way
  edges = w.bad_edges();
  CHECK(std::count_if(edges.begin(), edges.end(), [](const verify::WeldEdge& e) { return e.kind == verify::WeldEdgeKind::nonmanifold; }) == 1);
}

TEST_CASE("An open edge on a curve one patch drew is a border, on a curve two drew or on none a crack", "[views]") {
  // Two triangles meeting along the curve x = 0 (key 7), each with an outer edge on curve 1 or 2.
  const glm::vec3 a(0, 0, 0), b(0, 1, 0), c(1, 0, 0), d(-1, 0, 0);
  const auto weld = [&](bool shared_drawn_twice, bool crack) {
    verify::WeldChecker w;
    w.add_triangle(a, c, b);
    // The second triangle's copy of b is a float step away when `crack`: the shared edge opens.
    const glm::vec3 b2 = crack ? glm::vec3(0, std::nextafter(1.0f, 2.0f), 0) : b;
    w.add_triangle(a, b2, d);
    for (const glm::vec3& p : {a, b, b2}) w.add_curve_point(p, 7);
    for (const glm::vec3& p : {a, c}) w.add_curve_point(p, 1);
    for (const glm::vec3& p : {a, d}) w.add_curve_point(p, 2);
    w.add_curve_use(1), w.add_curve_use(2), w.add_curve_use(7);
    if (shared_drawn_twice) w.add_curve_use(7);
    return w;
  };
  // Closed along the shared curve: a-c and a-d are border (one patch each); b-c and b-d lie on no curve.
  verify::WeldReport r = weld(true, false).report();
  CHECK(r.open_edges == 4);
  CHECK(r.border_edges == 2);
  CHECK(r.crack_edges == 2);
  // The shared curve opened: both copies of it are cracks, for two patches drew that curve ...
  r = weld(true, true).report();
  CHECK(r.crack_edges == 4);
  CHECK(r.border_edges == 2);
  CHECK_FALSE(r.watertight());
  // ... and border when only one patch drew it (the other's neighbour culled, or a hole).
  r = weld(false, true).report();
  CHECK(r.crack_edges == 2);
  CHECK(r.border_edges == 4);
  const auto edges = weld(false, true).bad_edges();
  CHECK(std::count_if(edges.begin(), edges.end(),
                      [](const verify::WeldEdge& e) { return e.kind == verify::WeldEdgeKind::border; }) == 4);
}

TEST_CASE("Three triangles on one edge of a fin are the cage's own, on any other curve non-manifold", "[views]") {
  // Three fins of a book hinged on a-b (curve 5), each drawn by one patch.
  const glm::vec3 a(0, 0, 0), b(0, 1, 0);
  const auto weld = [&](bool fin, int patches) {
    verify::WeldChecker w;
    for (const glm::vec3& tip : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1)}) w.add_triangle(a, b, tip);
    w.add_curve_point(a, 5), w.add_curve_point(b, 5);
    for (int i = 0; i < patches; ++i) w.add_curve_use(5);
    if (fin) w.add_fin(5), w.add_fin(5);
    return w.report();
  };
  verify::WeldReport r = weld(true, 3);
  CHECK(r.cage_nonmanifold_edges == 1);
  CHECK(r.nonmanifold_edges == 0);
  CHECK(r.crack_edges == 6);  // the fins' outer edges lie on no curve here
  CHECK(r.summary().find("1 non-manifold edges of the cage's own") != std::string::npos);
  r = weld(false, 3);  // not a fin: a fault
  CHECK(r.nonmanifold_edges == 1);
  CHECK(r.cage_nonmanifold_edges == 0);
  r = weld(true, 2);  // more triangles than the patches that drew the fin
  CHECK(r.nonmanifold_edges == 1);
  CHECK(r.cage_nonmanifold_edges == 0);
}

TEST_CASE("An open cage is watertight with its boundary as border: the pawn, a hole, a culled neighbour",
          "[views][cli]") {
  const auto weld_of = [](const std::string& args) {
    const auto r = run_cli("-q tessellate " + args + " --check-watertight --json");
    INFO(args << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out)["watertight"];
  };
  // The pawn is open at its base: 24 boundary cage edges, factor 8 segments each.
  for (const char* scheme : {"gregory", "exact", "adaptive", "bspline"}) {
    INFO(scheme);
    const auto w = weld_of(test::data("osd-shapes/catmark_pawn.obj") + " --factor 8 --scheme " + scheme);
    CHECK(w["watertight"] == true);
    CHECK(w["closed_manifold"] == false);
    CHECK(w["crack_edges"] == 0);
    CHECK(w["border_edges"] == 24 * 8);
  }
  // A hole (OpenSubdiv's hole tag) and an open sheet with creases: borders only.
  for (const char* shape : {"catmark_hole_test1", "catmark_chaikin2", "catmark_gregory_test6"}) {
    INFO(shape);
    const auto w = weld_of(test::data(std::string("osd-shapes/") + shape + ".obj") + " --factor 3");
    CHECK(w["crack_edges"] == 0);
    CHECK(w["border_edges"].get<int>() > 0);
  }
  // A camera inside the frog culls patches; their neighbours' edges are border, never cracks.
  const auto culled = weld_of(kFrog + " --cull frustum --camera-position 20,5,12 --camera-target -3,-2.5,2");
  CHECK(culled["crack_edges"] == 0);
  CHECK(culled["border_edges"].get<int>() > 0);
  const auto whole = weld_of(kFrog + " --cull none");
  CHECK(whole["closed_manifold"] == true);
}

TEST_CASE("An open sheet is framed from its front: seen, not edge-on or from behind", "[views][cli]") {
  const fs::path dir = test::cli_temp_dir() / "sheet-framing";
  fs::create_directories(dir);
  for (const char* shape : {"catmark_gregory_test6", "catmark_val2_interior", "catmark_edgeonly"}) {
    const auto r = run_cli("-q render " + test::data(std::string("osd-shapes/") + shape + ".obj") +
                           " --scheme exact --resolution 160x120 --json -o " + (dir / (std::string(shape) + ".png")).string());
    INFO(shape << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    // Most of the framed image is surface, lit from the front: no patch proven to face away.
    CHECK(j["pixels_shaded"].get<int>() > 160 * 120 / 4);
    CHECK(j["patches_facing_away"] == 0);
  }
}

TEST_CASE("Overlay lines draw where they project, and stay hidden behind the depth buffer", "[views]") {
  auto fb = Framebuffer::create(64, 32, ColorFormat::rgba8_unorm, nullptr);
  REQUIRE(fb);
  fb->clear(glm::vec4(1.0f), 0.5f);
  // Identity view-projection: clip = world. A horizontal segment at y = 0 (the middle row), depth 0.25.
  const std::vector<OverlayLine> front = {{glm::vec3(-0.5f, 0.0f, 0.25f), glm::vec3(0.5f, 0.0f, 0.25f)}};
  draw_lines(*fb, glm::mat4(1.0f), front, OverlayStyle{glm::vec3(0.0f), 2.0f, 1.0f, true, 0.0f});
  CHECK(fb->color(32, 15).r < 0.1f);  // on the line
  CHECK(fb->color(32, 4).r == 1.0f);  // far from it
  CHECK(fb->color(4, 15).r == 1.0f);  // past its end
  // The same line behind the depth buffer (depth 0.75 > 0.5): nothing is drawn.
  fb->clear(glm::vec4(1.0f), 0.5f);
  const std::vector<OverlayLine> behind = {{glm::vec3(-0.5f, 0.0f, 0.75f), glm::vec3(0.5f, 0.0f, 0.75f)}};
  draw_lines(*fb, glm::mat4(1.0f), behind, OverlayStyle{glm::vec3(0.0f), 2.0f, 1.0f, true, 0.0f});
  CHECK(fb->color(32, 15).r == 1.0f);
}

TEST_CASE("bench dolly: with fractional_odd, vertices move in proportion to the camera step", "[views][cli]") {
  auto run = [&](int frames, const std::string& extra) {
    const auto r = run_cli("bench dolly --cage " + kFrog + extra +
                           " --camera-position 48,15,66 --camera-target -3,-2.5,2 --resolution 320x180 --frames " +
                           std::to_string(frames) + " --json");
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["per_frame"].size() == std::size_t(frames));
    CHECK(j["per_frame"][0]["largest_move_pixels"] == 0.0);
    return j["median_move_pixels"].get<double>();
  };
  const double coarse = run(8, ""), fine = run(16, "");
  CHECK(coarse > 0.0);
  CHECK(fine < 0.75 * coarse);  // half the step, about half the move: no popping
  // Displaced: the map's mip levels are blended, so the displaced points do not pop between levels.
  const double displaced_coarse = run(8, kDisplaced), displaced_fine = run(16, kDisplaced);
  CHECK(displaced_fine < 0.75 * displaced_coarse);
}

TEST_CASE("View, LOD and cull options: bad values are one-line usage errors", "[views][cli]") {
  const std::string out = " -o " + (test::cli_temp_dir() / "bad.png").string();
  for (const std::string args :
       {"--view bogus", "--view displacement", "--lod bogus", "--lod screen --edge-pixels 0",
        "--lod screen --edge-pixels nan", "--cull bogus", "--edge-pixels 4", "--lod screen --vary-factors 1",
        "--factor-kind cooked", "--lod distance --lod-distance -1", "--camera-position 1,2"}) {
    const auto r = run_cli("render " + kFrog + " --resolution 64x36 " + args + out);
    INFO(args << ": " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  CHECK_FALSE(fs::exists(test::cli_temp_dir() / "bad.png"));
}

TEST_CASE("Automatic framing fits the posed surface, whole and centred, in every orbit view", "[views][cli]") {
  // A tall piece (the bishop, +z up) in a wide image, seen from three sides; a glTF skin at t = 0 and a
  // morph (which used to be a small blob at the bottom): each whole, with a margin, filling the image
  // in its tighter direction. The frog is the control the old framing already held.
  const fs::path dir = test::cli_temp_dir() / "framing";
  fs::create_directories(dir);
  const auto bishop =
      run_cli("-q render " + test::data("osd-shapes/catmark_bishop.obj") +
              " --camera-up 0,0,1 --factor 2 --resolution 320x180 --orbit 3 -o " + (dir / "bishop_%d.png").string());
  INFO(bishop.err);
  REQUIRE(bishop.exit_code == 0);
  for (int i = 0; i < 3; ++i) check_framed(dir / ("bishop_" + std::to_string(i) + ".png"));
  for (const char* asset : {"SimpleSkin.gltf", "SimpleMorph.gltf"}) {
    const fs::path out = dir / (std::string(asset) + ".png");
    const auto r = run_cli("-q render " + test::data(std::string("gltf-samples/") + asset) +
                           " --factor 2 --resolution 320x180 --time 0.5 -o " + out.string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    check_framed(out);
  }
  const fs::path frog = dir / "frog.png";
  REQUIRE(run_cli("-q render " + kFrog + " --factor 2 --resolution 320x180 -o " + frog.string()).exit_code == 0);
  check_framed(frog);
  // A single view is framed on its own (a turntable keeps the distance its widest view needs).
  const std::string single = "-q render " + test::data("osd-shapes/catmark_bishop.obj") +
                             " --camera-up 0,0,1 --factor 2 --resolution 320x180 ";
  REQUIRE(run_cli(single + "-o " + (dir / "bishop.png").string()).exit_code == 0);
  check_framed(dir / "bishop.png");
  // --print-scene writes the framed camera; rendering that scene gives the same bytes.
  const fs::path scene = dir / "bishop.json";
  REQUIRE(run_cli(single + "--print-scene " + scene.string()).exit_code == 0);
  REQUIRE(run_cli("-q render --scene " + scene.string() + " -o " + (dir / "again.png").string()).exit_code == 0);
  CHECK(bytes_of(dir / "again.png") == bytes_of(dir / "bishop.png"));
}

TEST_CASE("render and analyze say which axis a cage's shape suggests is up", "[views][cli]") {
  // The bishop stands on a flat base at its lowest z: +z. The frog's lowest y holds its belly: +y, and
  // render says nothing. A glTF asset is +y by definition.
  const fs::path dir = test::cli_temp_dir() / "up-hint";
  fs::create_directories(dir);
  const std::string bishop = test::data("osd-shapes/catmark_bishop.obj");
  const auto a = run_cli("analyze " + bishop + " --json");
  REQUIRE(a.exit_code == 0);
  const auto j = nlohmann::json::parse(a.out);
  CHECK(j["up"]["axis"] == "+z");
  CHECK(j["up"]["camera_up"] == nlohmann::json::array({0, 0, 1}));
  CHECK(nlohmann::json::parse(run_cli("analyze " + kFrog + " --json").out)["up"]["axis"] == "+y");
  CHECK(nlohmann::json::parse(
            run_cli("analyze " + test::data("gltf-samples/SimpleSkin.gltf") + " --json").out)["up"]["reason"] ==
        "glTF is +y up");
  // The hint is used, and said in one line; the image is the one an explicit +z up gives, and
  // --print-scene writes that up into the scene.
  const auto r = run_cli("render " + bishop + " --resolution 64x36 -o " + (dir / "b.png").string());
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("seen +z up, as its shape suggests") != std::string::npos);
  CHECK(r.err.find("--camera-up 0,1,0 for +y") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  const auto given = run_cli("render " + bishop + " --camera-up 0,0,1 --resolution 64x36 -o " + (dir / "c.png").string());
  CHECK(given.err.find("seen +z up") == std::string::npos);
  CHECK(bytes_of(dir / "b.png") == bytes_of(dir / "c.png"));
  const auto y_up = run_cli("render " + bishop + " --camera-up 0,1,0 --resolution 64x36 -o " + (dir / "y.png").string());
  REQUIRE(y_up.exit_code == 0);
  CHECK(bytes_of(dir / "b.png") != bytes_of(dir / "y.png"));
  const auto scene = nlohmann::json::parse(run_cli("-q render " + bishop + " --print-scene -").out);
  CHECK(scene["camera"]["up"] == nlohmann::json::array({0.0, 0.0, 1.0}));
  const auto frog = run_cli("render " + kFrog + " --resolution 64x36 -o " + (dir / "f.png").string());
  CHECK(frog.err.find("seen +z up") == std::string::npos);
  // glTF is +y up by definition: never turned.
  const auto gltf = run_cli("render " + test::data("gltf-cages/cube.gltf") + " --resolution 64x36 -o " +
                            (dir / "g.png").string());
  CHECK(gltf.err.find("seen +z up") == std::string::npos);
}

TEST_CASE(
    "Two-sided drawing draws an open sheet seen from behind, lit, and changes next to nothing on a closed surface",
    "[views][cli]") {
  // catmark_edgeonly's sheets seen from above show their inner side: one-sided, nothing is drawn and
  // render warns; two-sided, the sheets are drawn with their normals turned to the viewer (lit clay, not
  // the dark ambient of a normal facing away), and the warning is gone.
  const fs::path dir = test::cli_temp_dir() / "two-sided";
  fs::create_directories(dir);
  const std::string sheet =
      test::data("osd-shapes/catmark_edgeonly.obj") + " --camera-position 0.3,6,1 --resolution 160x90 --json -o ";
  const auto one = run_cli("render " + sheet + (dir / "one.png").string());
  REQUIRE(one.exit_code == 0);
  CHECK(nlohmann::json::parse(one.out)["pixels_shaded"] == 0);
  CHECK(one.err.find("faces away") != std::string::npos);
  const auto two = run_cli("render --two-sided " + sheet + (dir / "two.png").string());
  INFO(two.err);
  REQUIRE(two.exit_code == 0);
  const long drawn = nlohmann::json::parse(two.out)["pixels_shaded"].get<long>();
  CHECK(drawn > 1000);
  CHECK(two.err.find("faces away") == std::string::npos);
  // Seen face on, lit clay is bright: no pixel is as dark as the ambient term alone (0.18 of the clay
  // colour), which is what a normal facing away would give.
  CHECK(pixels_near(dir / "two.png", glm::vec3(0.78f, 0.74f, 0.68f) * 0.18f) == 0);
  CHECK(pixels_near(dir / "two.png", glm::vec3(0.78f, 0.74f, 0.68f) * 0.95f) > drawn / 2);
  // On the frog (closed) the inner side hides behind the outer: the image differs at most where a
  // back-facing triangle of the tessellation pokes out on the silhouette (a pixel or two).
  const std::string frog = " --camera-position 48,15,66 --camera-target -3,-2.5,2 --factor 3 --resolution 160x90 -o ";
  REQUIRE(run_cli("render " + kFrog + frog + (dir / "f1.png").string()).exit_code == 0);
  REQUIRE(run_cli("render " + kFrog + " --two-sided" + frog + (dir / "f2.png").string()).exit_code == 0);
  const auto d = run_cli("diff " + (dir / "f1.png").string() + " " + (dir / "f2.png").string() + " --json");
  CHECK(nlohmann::json::parse(d.out)["over_fail"].get<long>() <= 8);
  // A scene file carries it.
  const fs::path scene = dir / "two.json";
  REQUIRE(run_cli("render --two-sided " + test::data("osd-shapes/catmark_edgeonly.obj") +
                  " --camera-position 0.3,6,1 --resolution 160x90 --print-scene " + scene.string())
              .exit_code == 0);
  CHECK(nlohmann::json::parse(bytes_of(scene))["two_sided"] == true);
  REQUIRE(run_cli("render --scene " + scene.string() + " -o " + (dir / "two-scene.png").string()).exit_code == 0);
  CHECK(bytes_of(dir / "two-scene.png") == bytes_of(dir / "two.png"));
}

}  // namespace tessera
