// tessera: the executable. The commands that draw, or read images, cages or glTF, link OpenImageIO,
// OpenSubdiv, oneTBB and tinygltf: some 260 shared libraries whose loading cost every invocation
// 0.26 s and 133 MB before any work. They live in the commands module (tessera-commands.so, beside
// this binary in the build tree, or in LIBDIR/tessera/ when installed), loaded with dlopen only when a
// command needs it. `tessera --version` and `tessera pattern` (without --image, which draws through
// OpenImageIO) run here, with the tessellator alone. Results go to stdout or files, logs to stderr;
// exit codes 0 ok, 1 bad input or a failed check, 2 usage error.
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/cli/cli_app.h"
#include "tools/cli/pattern_image.h"

namespace {

namespace fs = std::filesystem;

// Whether this binary runs the command itself: `--version`, or `pattern` without --image (after
// the global -q/-v flags).
bool runs_here(int argc, char** argv) {
  int i = 1;
  auto is = [&](int k, const char* a) { return std::strcmp(argv[k], a) == 0; };
  while (i < argc && (is(i, "-q") || is(i, "--quiet") || is(i, "-v") || is(i, "--verbose"))) ++i;
  if (i >= argc) return false;
  if (is(i, "--version")) return i + 1 == argc;
  if (!is(i, "pattern")) return false;
  for (int k = i + 1; k < argc; ++k)
    if (std::strncmp(argv[k], "--image", 7) == 0) return false;
  return true;
}

std::vector<std::string> plain_arguments(int argc, char** argv) { return {argv, argv + argc}; }

int run_module(int argc, char** argv) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path dir = ec ? fs::path(".") : exe.parent_path();
  std::string tried;
  for (const fs::path& candidate : {dir / "tessera-commands.so", dir / TESSERA_MODULE_DIR / "tessera-commands.so"}) {
    if (!fs::exists(candidate, ec)) {
      tried += (tried.empty() ? "" : ", ") + candidate.string();
      continue;
    }
    void* module = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      std::fprintf(stderr, "tessera: cannot load its commands module %s (%s)\n", candidate.c_str(), dlerror());
      return 1;
    }
    using Main = int (*)(int, char**);
    const auto run = reinterpret_cast<Main>(dlsym(module, "tessera_cli_main"));
    if (!run) {
      std::fprintf(stderr, "tessera: %s has no tessera_cli_main (a mismatched install?)\n", candidate.c_str());
      return 1;
    }
    return run(argc, argv);
  }
  std::fprintf(stderr, "tessera: its commands module is missing (looked for %s)\n", tried.c_str());
  return 1;
}

}  // namespace

namespace tessera::cli {

// The pattern picture draws through OpenImageIO, in the module: runs_here() sends every --image there,
// so this stand-in is never reached.
void write_pattern_image(const PatternPicture&, const std::string&) {
  throw std::logic_error("tessera pattern --image reached the launcher; it belongs to the commands module");
}

}  // namespace tessera::cli

int main(int argc, char** argv) {
  if (!runs_here(argc, argv)) return run_module(argc, argv);
  static constexpr tessera::cli::CommandEntry kHere[] = {{"pattern", tessera::cli::add_pattern_command}};
  return tessera::cli::run_app(argc, argv, kHere, plain_arguments);
}
