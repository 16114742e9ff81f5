// Image files (shaders_cpp/image_io): an image encoded into memory is the bytes of the same image
// written to a file, for every format the viewer and the CLI write; failures are one line naming the
// file, and leave nothing behind.
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include "cli_runner.h"
#include "pipeline/framebuffer.h"
#include "shaders_cpp/image_io/image_file.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

Framebuffer gradient(ColorFormat format, int samples) {
  std::string error;
  auto fb = Framebuffer::create(37, 21, format, &error, samples);
  REQUIRE(fb);
  fb->clear(glm::vec4(0.2f, 0.4f, 0.6f, 1.0f), 1.0f);
  return std::move(*fb);
}

}  // namespace

TEST_CASE("an image encoded in memory is the bytes of the file", "[image_io]") {
  for (const char* ext : {".png", ".exr", ".tif", ".jpg"}) {
    for (const ColorFormat format : {ColorFormat::rgba8_unorm, ColorFormat::rgba32_float}) {
      const Framebuffer fb = gradient(format, format == ColorFormat::rgba8_unorm ? 4 : 1);
      const fs::path path = test::cli_temp_dir() / (std::string("image-io") + ext);
      REQUIRE(write_color(fb, {path.string()}).empty());
      std::string memory;
      REQUIRE(write_color(fb, {path.string(), &memory}).empty());
      INFO(ext << (format == ColorFormat::rgba8_unorm ? " rgba8, 4 samples" : " rgba32f"));
      CHECK(!memory.empty());
      CHECK(memory == test::slurp(path));
    }
  }
}

TEST_CASE("image writing fails in one line naming the file, and leaves no file", "[image_io]") {
  const Framebuffer fb = gradient(ColorFormat::rgba8_unorm, 1);
  const fs::path dir = test::cli_temp_dir();
  const std::string unknown = (dir / "frame.not-an-image").string();
  const std::string e = write_color(fb, {unknown});
  CHECK(e.rfind(unknown + ": ", 0) == 0);
  CHECK(e.find('\n') == std::string::npos);
  CHECK_FALSE(fs::exists(unknown));
  const std::string missing = (dir / "no-such-dir" / "frame.png").string();
  CHECK(write_color(fb, {missing}).rfind(missing, 0) == 0);
  CHECK_FALSE(fs::exists(missing));
  std::string memory;
  CHECK_FALSE(write_color(fb, {unknown, &memory}).empty());
  CHECK(memory.empty());
}

}  // namespace tessera
