// `tessera diff` against OpenImageIO's own idiff (openimageio-tools, installed by scripts/setup.sh):
// the same exit code for every crafted pair and flag set, and what idiff does not have: --json,
// --exact with content hashes, -o/-od/-abs/-scale pictures, the heat map, file errors.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <tuple>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "tools/verify/image_diff.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

// An image with `channels` channels from f(x, y, c) in [0, 1] (or anything, for float files).
template <class F>
fs::path write_image(const fs::path& path, int w, int h, int channels, OIIO::TypeDesc type, F&& f) {
  OIIO::ImageBuf img(OIIO::ImageSpec(w, h, channels, OIIO::TypeFloat));
  std::vector<float> px(static_cast<std::size_t>(channels));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < channels; ++c) px[std::size_t(c)] = f(x, y, c);
      img.setpixel(x, y, px.data(), channels);
    }
  REQUIRE(img.write(path.string(), type));
  return path;
}

float base(int x, int y, int c) { return float((x * 7 + y * 3 + c * 50) % 256) / 255.0f; }

int exit_code_of(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool have_idiff() { return exit_code_of("command -v idiff >/dev/null 2>&1") == 0; }

}  // namespace

TEST_CASE("tessera diff and idiff give the same verdict on every crafted pair and flag set", "[diff][cli]") {
  REQUIRE(have_idiff());  // openimageio-tools: scripts/setup.sh installs it
  const fs::path dir = test::cli_temp_dir() / "diff-pairs";
  fs::create_directories(dir);
  const int w = 32, h = 24;
  const auto u8 = OIIO::TypeDesc::UINT8;
  std::mt19937 rng(7);
  auto noise = [&](double share, int steps) {
    std::vector<int> d(std::size_t(w * h), 0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int& v : d)
      if (u(rng) < share) v = (u(rng) < 0.5 ? -1 : 1) * steps;
    return d;
  };
  const auto n5 = noise(0.05, 2), n30 = noise(0.30, 2), n5big = noise(0.05, 40);
  auto plus = [&](const std::vector<int>& d) {
    return [&d](int x, int y, int c) {
      const float v = base(x, y, c) * 255.0f + float(c == 0 ? d[std::size_t(y * w + x)] : 0);
      return std::clamp(v, 0.0f, 255.0f) / 255.0f;
    };
  };
  const fs::path a = write_image(dir / "a.png", w, h, 3, u8, base);
  std::vector<fs::path> others = {
      write_image(dir / "same.png", w, h, 3, u8, base),
      write_image(dir / "same.tif", w, h, 3, u8, base),
      write_image(dir / "one-step.png", w, h, 3, u8,
                  [](int x, int y, int c) { return base(x, y, c) + (x == 5 && y == 6 && c == 1 ? 1.0f / 255 : 0.0f); }),
      write_image(dir / "one-big.png", w, h, 3, u8,
                  [](int x, int y, int c) { return x == 9 && y == 2 && c == 0 ? 1.0f : base(x, y, c); }),
      write_image(dir / "noise5.png", w, h, 3, u8, plus(n5)),
      write_image(dir / "noise30.png", w, h, 3, u8, plus(n30)),
      write_image(dir / "noise5big.png", w, h, 3, u8, plus(n5big)),
      write_image(dir / "wider.png", w + 1, h, 3, u8, base),
      write_image(dir / "rgba.png", w, h, 4, u8, [](int x, int y, int c) { return c == 3 ? 1.0f : base(x, y, c); }),
      write_image(dir / "black.png", w, h, 3, u8, [](int, int, int) { return 0.0f; }),
      dir / "missing.png"};
  // Float files: relative thresholds, values above 1, NaN on one side or both.
  const fs::path fa = write_image(dir / "fa.exr", 8, 8, 3, OIIO::TypeFloat,
                                  [](int x, int y, int c) { return 0.5f + float(x + y + c); });
  const std::vector<fs::path> float_others = {
      write_image(dir / "fb.exr", 8, 8, 3, OIIO::TypeFloat,
                  [](int x, int y, int c) { return (0.5f + float(x + y + c)) * 1.001f; }),
      write_image(dir / "fnan.exr", 8, 8, 3, OIIO::TypeFloat,
                  [](int x, int y, int c) { return x == 3 && y == 4 ? NAN : 0.5f + float(x + y + c); }),
      write_image(dir / "fbig.exr", 8, 8, 3, OIIO::TypeFloat,
                  [](int x, int y, int c) { return 40.0f + float(x * y + c); })};
  const std::vector<std::string> flag_sets = {"",
                                              "-fail 0.01",
                                              "-fail 0.004 -failpercent 10 -warn 0.001",
                                              "-warn 0.001 -fail 0.1",
                                              "-allowfailures 3",
                                              "-hardfail 0.1 -failpercent 50",
                                              "-failrelative 0.01 -warnrelative 0.0001 -failpercent 100",
                                              "-hardwarn 0.001 -failpercent 100"};
  std::vector<std::pair<fs::path, fs::path>> pairs;
  for (std::size_t i = 0; i < others.size(); ++i) pairs.emplace_back(i % 2 ? others[i] : a, i % 2 ? a : others[i]);
  for (const fs::path& b : float_others) pairs.emplace_back(fa, b);
  pairs.emplace_back(dir / "fnan.exr", dir / "fnan.exr");
  // idiff starts in about 0.3 s (its plugins): every case in one xargs run, two at a time.
  const fs::path list = dir / "cases.txt", codes = dir / "codes.txt";
  {
    std::ofstream out(list);
    for (const auto& [x, y] : pairs)
      for (const std::string& flags : flag_sets) out << flags << " " << x.string() << " " << y.string() << "\n";
  }
  REQUIRE(exit_code_of("xargs -P 2 -L 1 sh -c 'idiff \"$@\" >/dev/null 2>&1; echo \"$? $*\"' _ <" + list.string() +
                       " >" + codes.string()) == 0);
  std::map<std::string, int> theirs;
  {
    std::ifstream in(codes);
    std::string line;
    while (std::getline(in, line)) theirs[line.substr(line.find(' ') + 1)] = std::stoi(line.substr(0, line.find(' ')));
  }
  int cases = 0, disagreements = 0;
  std::map<int, int> verdicts;
  for (const auto& [x, y] : pairs)
    for (const std::string& flags : flag_sets) {
      // Ours through the library (the CLI's own path is checked below on a few of them).
      std::istringstream words(flags);
      verify::DiffThresholds t;
      for (std::string name, value; words >> name >> value;) {
        const float v = std::stof(value);
        if (name == "-fail") t.fail = v;
        if (name == "-failpercent") t.fail_percent = v;
        if (name == "-failrelative") t.fail_relative = v;
        if (name == "-hardfail") t.hard_fail = v;
        if (name == "-allowfailures") t.allow_failures = (long long)v;
        if (name == "-warn") t.warn = v;
        if (name == "-warnpercent") t.warn_percent = v;
        if (name == "-warnrelative") t.warn_relative = v;
        if (name == "-hardwarn") t.hard_warn = v;
      }
      const int ours = int(verify::diff_images(x.string(), y.string(), t, false).verdict);
      const std::string key = (flags.empty() ? "" : flags + " ") + x.string() + " " + y.string();
      REQUIRE(theirs.count(key) == 1);
      INFO("idiff " << key);
      CHECK(ours == theirs[key]);
      ++cases, ++verdicts[theirs[key]];
      disagreements += ours != theirs[key];
    }
  CHECK(disagreements == 0);
  CHECK(cases == int(flag_sets.size() * pairs.size()));
  // The pairs reach every verdict idiff gives: pass, warning, failure, file error.
  for (const int v : {0, 1, 2, 4}) CHECK(verdicts[v] > 0);
  // The command line, on cases of the matrix: idiff's spellings, its codes.
  for (const auto& [flags, x, y] :
       {std::tuple{std::string("-fail 0.004 -failpercent 10 -warn 0.001"), a, others[4]},
        std::tuple{std::string("-allowfailures 3"), others[3], a}, std::tuple{std::string(""), others[7], a},
        std::tuple{std::string(""), a, others.back()}}) {
    const std::string key = (flags.empty() ? "" : flags + " ") + x.string() + " " + y.string();
    REQUIRE(theirs.count(key) == 1);
    INFO("diff " << key);
    CHECK(test::run_cli("diff " + key).exit_code == theirs[key]);
  }
}

TEST_CASE("tessera diff --json, --exact and its pictures", "[diff][cli]") {
  const fs::path dir = test::cli_temp_dir() / "diff-extras";
  fs::create_directories(dir);
  const auto u8 = OIIO::TypeDesc::UINT8;
  const fs::path a = write_image(dir / "a.png", 16, 12, 3, u8, base);
  const fs::path same_tif = write_image(dir / "a.tif", 16, 12, 3, u8, base);
  const fs::path off = write_image(dir / "off.png", 16, 12, 3, u8, [](int x, int y, int c) {
    return x == 11 && y == 7 && c == 2 ? base(x, y, c) + 10.0f / 255.0f : base(x, y, c);
  });
  const fs::path wide = write_image(dir / "wide.png", 17, 12, 3, u8, base);

  const auto j = nlohmann::json::parse(test::run_cli("diff --json " + a.string() + " " + off.string()).out);
  CHECK(j["verdict"] == "failure");
  CHECK(j["exit_code"] == 2);
  CHECK(j["max_pixel"] == nlohmann::json::array({11, 7}));
  CHECK(j["max_channel"] == 2);
  CHECK(j["over_fail"] == 1);
  CHECK(j["max_error"].get<double>() == Approx(10.0 / 255.0).epsilon(1e-6));
  CHECK(j["identical"] == false);
  CHECK(j["pixels"] == 16 * 12);
  CHECK(j["max_channel_name"] == "B");
  CHECK(j["max_values"][1][2].get<double>() - j["max_values"][0][2].get<double>() ==
        Approx(10.0 / 255.0).epsilon(1e-5));
  // The text names the channel and both pixels as idiff does, to the character.
  const std::string pair = a.string() + " " + off.string();
  const std::string ours = test::run_cli("diff " + pair).out;
  const fs::path idiff_out = dir / "idiff.txt";
  exit_code_of("idiff " + pair + " >" + idiff_out.string() + " 2>&1");
  const std::string theirs = test::slurp(idiff_out);
  const auto max_line = [](const std::string& text) {
    const std::size_t at = text.find("  Max error");
    return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
  };
  CHECK(max_line(ours).find("@ (11, 7, B)  values are ") != std::string::npos);
  CHECK(max_line(ours) == max_line(theirs));

  // Exact: the same decoded pixels from PNG and TIFF are identical, with one hash.
  const auto e = test::run_cli("diff --exact --json " + a.string() + " " + same_tif.string());
  CHECK(e.exit_code == 0);
  const auto ej = nlohmann::json::parse(e.out);
  CHECK(ej["identical"] == true);
  CHECK(ej["hash_a"] == ej["hash_b"]);
  CHECK(ej["hash_a"].get<std::string>().size() == 40);
  CHECK(test::run_cli("diff --exact " + a.string() + " " + off.string()).exit_code == 2);
  CHECK(test::run_cli("diff --exact " + a.string() + " " + wide.string()).exit_code == 3);
  // Loose thresholds pass what exact refuses.
  CHECK(test::run_cli("diff -fail 0.05 " + a.string() + " " + off.string()).exit_code == 0);

  // -o: A - B scaled; -od writes nothing for equal images; the heat map has the union's size.
  const fs::path d = dir / "d.exr", none = dir / "none.exr", heat = dir / "heat.png";
  REQUIRE(test::run_cli("diff -o " + d.string() + " -scale 2 --heatmap " + heat.string() + " " + a.string() + " " +
                        off.string())
              .exit_code == 2);
  OIIO::ImageBuf dimg(d.string());
  REQUIRE(dimg.read(0, 0, true, OIIO::TypeFloat));
  CHECK(dimg.getchannel(11, 7, 0, 2) == Approx(-20.0f / 255.0f).epsilon(1e-5));
  CHECK(dimg.getchannel(3, 3, 0, 0) == 0.0f);
  CHECK(test::run_cli("diff -od -o " + none.string() + " " + a.string() + " " + same_tif.string()).exit_code == 0);
  CHECK_FALSE(fs::exists(none));
  OIIO::ImageBuf himg(heat.string());
  REQUIRE(himg.read(0, 0, true, OIIO::TypeFloat));
  CHECK(himg.spec().width == 16);
  CHECK(himg.spec().nchannels == 3);
  float hot[3], calm[3];
  himg.getpixel(11, 7, hot, 3);
  himg.getpixel(3, 3, calm, 3);
  CHECK(hot[0] > 0.5f);                               // the differing pixel glows
  CHECK((calm[0] == calm[1] && calm[1] == calm[2]));  // the rest is grey

  // Bad input: one line naming the file, exit 4; refused idiff options say so.
  const auto missing = test::run_cli("diff " + a.string() + " " + (dir / "nope.png").string());
  CHECK(missing.exit_code == 4);
  CHECK(missing.err.find("nope.png") != std::string::npos);
  CHECK(std::count(missing.err.begin(), missing.err.end(), '\n') == 1);
  {
    std::ofstream cut(dir / "cut.png", std::ios::binary);
    const std::string bytes = test::slurp(a);
    cut << bytes.substr(0, bytes.size() / 2);
  }
  const auto truncated = test::run_cli("diff " + a.string() + " " + (dir / "cut.png").string());
  CHECK(truncated.exit_code == 4);
  CHECK(truncated.err.find("cut.png") != std::string::npos);
  const auto perceptual = test::run_cli("diff -p " + a.string() + " " + off.string());
  CHECK(perceptual.exit_code == 2);
  CHECK(perceptual.err.find("not supported") != std::string::npos);
}

}  // namespace tessera
