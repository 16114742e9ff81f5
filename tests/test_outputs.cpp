// Hostile command lines: a command writes all of its outputs or none, never over one
// of its inputs, never two outputs on one path, never to "-"; empty values and unknown commands are
// named; a failed watertight check says so on stderr even with -q.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <catch2/catch.hpp>

#include "cli_runner.h"
#include "test_data.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
const std::string kCube = test::data("sdk-cages/cube.obj");

void one_line(const test::CliResult& r, const std::string& message) {
  INFO(r.err);
  CHECK(r.err.find(message) != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

}  // namespace

TEST_CASE("Outputs: all or none, never over an input, never two on one path, never '-'", "[cli][outputs]") {
  const fs::path dir = test::cli_temp_dir() / "outputs";
  fs::create_directories(dir);
  const std::string png = (dir / "out.png").string();
  fs::remove(png);

  auto r = test::run_cli("render " + kCube + " --resolution 64x64 -o " + png + " --stats " +
                         (dir / "missing/s.json").string());
  CHECK(r.exit_code == 2);
  one_line(r, "directory '" + (dir / "missing").string() + "' does not exist");
  CHECK_FALSE(fs::exists(png));  // nothing written

  r = test::run_cli("render " + kCube + " --resolution 64x64 -o " + png + " --stats " + png);
  CHECK(r.exit_code == 2);
  one_line(r, "name one file");
  CHECK_FALSE(fs::exists(png));

  const fs::path cage = dir / "in.obj";
  fs::copy_file(kCube, cage, fs::copy_options::overwrite_existing);
  const std::string before = test::slurp(cage);
  r = test::run_cli("tessellate " + cage.string() + " -o " + cage.string());
  CHECK(r.exit_code == 2);
  one_line(r, "that is an input of this command");
  CHECK(test::slurp(cage) == before);
  // The same file by another spelling is the same file.
  r = test::run_cli("tessellate " + cage.string() + " -o " + (dir / "." / "in.obj").string());
  CHECK(r.exit_code == 2);
  CHECK(test::slurp(cage) == before);

  r = test::run_cli("render " + kCube + " -o -");
  CHECK(r.exit_code == 2);
  one_line(r, "stdout is not supported");
  CHECK_FALSE(fs::exists("-"));

  r = test::run_cli("render " + kCube + " -o " + dir.string());
  CHECK(r.exit_code == 2);
  one_line(r, "a directory, not a file");

  r = test::run_cli("bench torus --frames 1 --factor 2 --resolution 64x64 -o " + (dir / "nope/t.png").string());
  CHECK(r.exit_code == 2);
  one_line(r, "does not exist");
  // A bad --stats path is found before the image is written: nothing is left behind.
  r = test::run_cli("-q bench torus --frames 1 --factor 2 --resolution 64x64 -o " + (dir / "t.png").string() +
                    " --stats " + (dir / "nope/stats.json").string());
  CHECK(r.exit_code == 2);
  one_line(r, "does not exist");
  CHECK_FALSE(fs::exists(dir / "t.png"));

  const std::string a = (dir / "a.png").string();
  REQUIRE(test::run_cli("render " + kCube + " --resolution 32x32 -o " + a).exit_code == 0);
  const std::string image = test::slurp(a);
  r = test::run_cli("diff " + a + " " + a + " -o " + a);
  CHECK(r.exit_code == 2);
  CHECK(test::slurp(a) == image);
}

TEST_CASE("Empty values, unknown commands and quiet failures are named", "[cli][outputs]") {
  auto r = test::run_cli("render " + kCube + " --factor \"\" -o x.png");
  CHECK(r.exit_code == 2);
  one_line(r, "--factor: an empty value");
  r = test::run_cli("render " + kCube + " --factor= -o x.png");
  CHECK(r.exit_code == 2);
  one_line(r, "--factor: an empty value");
  r = test::run_cli("frobnicate");
  CHECK(r.exit_code == 2);
  one_line(r, "'frobnicate' is not a command (");
  r = test::run_cli("render " + kCube + " --factor 100 -o x.png");
  CHECK(r.exit_code == 2);
  one_line(r, "--factor: 100 is not in (0, 64]");
  // -q keeps errors: a cage that cannot be read says so on stderr.
  r = test::run_cli("-q tessellate /nonexistent/missing.obj --check-watertight");
  CHECK(r.exit_code == 1);
  one_line(r, "missing.obj: cannot open the file");
}

TEST_CASE("Misspelt commands, options and names get the closest one and the command's own help",
          "[cli][outputs]") {
  auto r = test::run_cli("render " + kCube + " --samples 4 -o x.png");
  CHECK(r.exit_code == 2);
  one_line(r, "tessera render: unknown option --samples; did you mean --msaa? (see tessera render --help)");
  r = test::run_cli("-q render " + kCube + " --resolutoin 32x32 -o x.png");
  CHECK(r.exit_code == 2);
  one_line(r, "unknown option --resolutoin; did you mean --resolution? (see tessera render --help)");
  r = test::run_cli("tessellate " + kCube + " --frobnicate");
  CHECK(r.exit_code == 2);
  one_line(r, "tessera tessellate: unknown option --frobnicate (see tessera tessellate --help)");
  r = test::run_cli("rendr " + kCube);
  CHECK(r.exit_code == 2);
  one_line(r, "'rendr' is not a command; did you mean render? (");
  r = test::run_cli("render " + kCube + " --scheme gregry -o x.png");
  CHECK(r.exit_code == 2);
  one_line(r, "'gregry' is not one of flat, bspline, acc, gregory, exact, pn, adaptive; did you mean gregory?");
  r = test::run_cli("render " + kCube + " --view wirefrme -o x.png");
  one_line(r, "did you mean wireframe?");
  // A value CLI11 cannot convert names the option and the command's help; --orbit 0 is --orbit's error.
  r = test::run_cli("render " + kCube + " --two-sided=maybe -o x.png");
  CHECK(r.exit_code == 2);
  one_line(r, "tessera render: --two-sided: cannot read 'maybe' (see tessera render --help)");
  r = test::run_cli("render " + kCube + " --orbit 0 -o x_%d.png");
  CHECK(r.exit_code == 2);
  one_line(r, "--orbit: 0 is not in 1..100000");
  // Nothing close: no guess.
  r = test::run_cli("render " + kCube + " --scheme loop -o x.png");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("did you mean") == std::string::npos);
  CHECK_FALSE(fs::exists("x.png"));
}

TEST_CASE("Silent successes refused: cameras along the up axis, factor files that do not fit, maps named right",
          "[cli][outputs]") {
  const fs::path dir = test::cli_temp_dir() / "silent";
  fs::create_directories(dir);
  const std::string out = " --resolution 64x64 -o " + (dir / "x.png").string();
  auto r = test::run_cli("render " + kCube + " --camera-position 0,10,0 --camera-target 0,0,0" + out);
  CHECK(r.exit_code == 2);
  one_line(r, "looks straight along the up axis");
  CHECK_FALSE(fs::exists(dir / "x.png"));

  r = test::run_cli("render " + kCube + " --factors-per-edge " + dir.string() + out);
  CHECK(r.exit_code == 1);
  one_line(r, "a directory, not a factors file");
  std::ofstream(dir / "f.txt") << "# v0 v1 factor\n0 1 4\n0 99 4\n";
  r = test::run_cli("render " + kCube + " --factors-per-edge " + (dir / "f.txt").string() + out);
  CHECK(r.exit_code == 1);
  one_line(r, "f.txt:3: 0 99 is not an edge of");
  CHECK(r.err.find("indices count from 0") != std::string::npos);
  std::ofstream(dir / "g.txt") << "0 1 4\n";
  CHECK(test::run_cli("render " + kCube + " --factors-per-edge " + (dir / "g.txt").string() + out).exit_code == 0);

  const std::string frog = test::data("sdk-cages/monsterfrog_mapped_00.obj");
  const std::string map = test::data("sdk-cages/monsterfrog.dds");
  r = test::run_cli("render " + frog + " --displacement " + map + " --displacement-channel A --normal-map " +
                    (dir / "missing.png").string() + out);
  CHECK(r.exit_code == 1);
  one_line(r, "missing.png: no such file (normal map)");
  r = test::run_cli("render " + frog + " --displacement " + dir.string() + out);
  CHECK(r.exit_code == 1);
  one_line(r, "a directory, not an image file (displacement map)");
  // A NaN texel: refused, naming it (it would have displaced vertices to NaN).
  OIIO::ImageBuf nan_map(OIIO::ImageSpec(8, 8, 1, OIIO::TypeFloat));
  const float one = 0.5f, bad = NAN;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) nan_map.setpixel(x, y, x == 3 && y == 5 ? &bad : &one, 1);
  REQUIRE(nan_map.write((dir / "nan.exr").string()));
  r = test::run_cli("tessellate " + frog + " --displacement " + (dir / "nan.exr").string() + " -o " +
                    (dir / "x.ply").string());
  CHECK(r.exit_code == 1);
  one_line(r, "texel (3, 5) of channel");
  CHECK(r.err.find("is NaN") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "x.ply"));
}

TEST_CASE("Edge cases that used to fail or write garbage: an all-culled tessellation, huge torus radii",
          "[cli][outputs]") {
  const fs::path dir = test::cli_temp_dir() / "edges";
  fs::create_directories(dir);
  // Every patch outside the view: an empty PLY, not "write failed".
  const fs::path ply = dir / "empty.ply";
  auto r =
      test::run_cli("tessellate " + kCube +
                    " --cull frustum --camera-position 100,100,100 --camera-target 200,200,200 -o " + ply.string());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  const std::string bytes = test::slurp(ply);
  CHECK(bytes.find("element vertex 0\n") != std::string::npos);
  CHECK(bytes.find("element face 0\n") != std::string::npos);
  // Radii whose sum overflows float: refused, nothing written.
  const fs::path big = dir / "big.obj";
  r = test::run_cli("make-cage --major-radius 3e38 --minor-radius 1e38 --grid 4x4 -o " + big.string());
  CHECK(r.exit_code != 0);
  one_line(r, "overflow float coordinates");
  CHECK_FALSE(fs::exists(big));
}

}  // namespace tessera

namespace tessera {

TEST_CASE("Truncated images fail in one line: a DDS shorter than its header implies, a cut PNG", "[cli][outputs]") {
  const fs::path dir = test::cli_temp_dir() / "truncated";
  fs::create_directories(dir);
  const std::string frog = test::data("sdk-cages/monsterfrog_mapped_00.obj");
  std::ifstream in(test::data("sdk-cages/monsterfrog.dds"), std::ios::binary);
  const std::string dds{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  for (const std::size_t keep : {std::size_t(4096), std::size_t(128), std::size_t(60), dds.size() - 1}) {
    const fs::path cut = dir / ("cut-" + std::to_string(keep) + ".dds");
    std::ofstream(cut, std::ios::binary) << dds.substr(0, keep);
    const auto r = test::run_cli("render " + frog + " --displacement " + cut.string() +
                                 " --displacement-channel A --resolution 64x64 -o " + (dir / "x.png").string());
    INFO(keep << ": " << r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("truncated DDS") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  // A PNG cut in its pixel data: libpng's own line is not printed before ours.
  REQUIRE(test::run_cli("render " + frog + " --resolution 256x256 -o " + (dir / "whole.png").string()).exit_code == 0);
  std::ifstream png_in(dir / "whole.png", std::ios::binary);
  const std::string png{std::istreambuf_iterator<char>(png_in), std::istreambuf_iterator<char>()};
  std::ofstream(dir / "cut.png", std::ios::binary) << png.substr(0, png.size() / 2);
  const auto r = test::run_cli("render " + frog + " --displacement " + (dir / "cut.png").string() +
                               " --displacement-channel R --resolution 64x64 -o " + (dir / "x.png").string());
  CHECK(r.exit_code == 1);
  CHECK(r.err.rfind("tessera render: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find("libpng error") == std::string::npos);
  const auto d = test::run_cli("diff " + (dir / "cut.png").string() + " " + (dir / "whole.png").string());
  CHECK(d.exit_code != 0);
  CHECK(d.err.find("libpng error") == std::string::npos);
  CHECK(!fs::exists(dir / "x.png"));
  // An uncompressed TIFF whose header claims more pixels than the file holds (the maps fuzzer's find:
  // OpenImageIO spent seconds filling them), refused at once.
  {
    OIIO::ImageBuf big(OIIO::ImageSpec(512, 512, 1, OIIO::TypeDesc::UINT8));
    OIIO::ImageBufAlgo::fill(big, {0.5f});
    big.specmod().attribute("compression", "none");
    REQUIRE(big.write((dir / "whole.tif").string()));
    std::ifstream tif_in(dir / "whole.tif", std::ios::binary);
    const std::string tif{std::istreambuf_iterator<char>(tif_in), std::istreambuf_iterator<char>()};
    std::ofstream(dir / "cut.tif", std::ios::binary) << tif.substr(0, tif.size() / 3);
  }
  const auto t = test::run_cli("render " + frog + " --displacement " + (dir / "cut.tif").string() +
                               " --resolution 64x64 -o " + (dir / "x.png").string());
  INFO(t.err);
  CHECK(t.exit_code == 1);
  CHECK(t.err.find("cut.tif: truncated: its header (512x512, uncompressed) implies 262144 bytes") != std::string::npos);
  CHECK(std::count(t.err.begin(), t.err.end(), '\n') == 1);
  CHECK(!fs::exists(dir / "x.png"));
  // A compressed TIFF of 250 bytes whose header claims 20230x1029 RGB at 16 bits (the maps fuzzer's slow unit:
  // 1.8 s and 950 MB of decoding before): more than 4096 times its size, refused at once.
  {
    std::ifstream unit_in(fs::path(TESSERA_TEST_DATA_DIR).parent_path() /
                              "fuzz/regressions/maps/slow-unit-32bd9f5785fd50efecb88c948c12bc1bf50997e4",
                          std::ios::binary);
    const std::string unit{std::istreambuf_iterator<char>(unit_in), std::istreambuf_iterator<char>()};
    REQUIRE(unit.size() > 200);
    std::ofstream(dir / "claims.tif", std::ios::binary) << unit.substr(1);  // (byte 0 picks the fuzzer's decoder)
  }
  const auto c = test::run_cli("render " + frog + " --displacement " + (dir / "claims.tif").string() +
                               " --resolution 64x64 -o " + (dir / "x.png").string());
  INFO(c.err);
  CHECK(c.exit_code == 1);
  CHECK(c.err.find("claims.tif: 20230x1029 (124900020 bytes of pixels) cannot come from a") != std::string::npos);
  CHECK(std::count(c.err.begin(), c.err.end(), '\n') == 1);
  CHECK(!fs::exists(dir / "x.png"));
}

TEST_CASE("A 10 MB bad token is not echoed whole: errors stay one short line", "[cli][outputs]") {
  const fs::path dir = test::cli_temp_dir();
  {
    std::ofstream out(dir / "huge-token.obj");
    out << "v 1 2 " << std::string(10'000'000, 'x') << "\nf 1 2 3\n";
  }
  const auto r = test::run_cli("analyze " + (dir / "huge-token.obj").string());
  CHECK(r.exit_code == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.size() < 700);
  CHECK(r.err.find("huge-token.obj:1") != std::string::npos);  // the head: file and line
  CHECK(r.err.find("bytes ...]") != std::string::npos);        // the cut says so
}

}  // namespace tessera

namespace tessera {

TEST_CASE("The exact scheme draws a valence beyond 128 and says what it costs", "[cli][outputs]") {
  // A double cone over 200 segments: both apexes have valence 200 (OpenSubdiv's time around a vertex
  // grows as valence^2.4).
  const fs::path path = test::cli_temp_dir() / "valence-200.obj";
  {
    std::ofstream out(path);
    const int n = 200;
    out << "v 0 1 0\nv 0 -1 0\n";
    for (int i = 0; i < n; ++i)
      out << "v " << std::cos(6.283185307 * i / n) << " 0 " << -std::sin(6.283185307 * i / n) << "\n";
    for (int i = 0; i < n; ++i) {
      out << "f 1 " << 3 + i << " " << 3 + (i + 1) % n << "\n";
      out << "f 2 " << 3 + (i + 1) % n << " " << 3 + i << "\n";
    }
  }
  const auto r = test::run_cli("tessellate " + path.string() + " --scheme exact --factor 2 --check-watertight");
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("vertex 0 has valence 200; --scheme exact builds the surface around it in about 0.6 s") !=
        std::string::npos);
  CHECK(r.out.find("\nwatertight: ") != std::string::npos);
}

}  // namespace tessera
