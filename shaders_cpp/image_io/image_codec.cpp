#include "shaders_cpp/image_io/image_codec.h"

#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>

namespace {

const char* const kModuleName = "tessera-image-io.so";

// The directory of the shared object or executable that holds this code: for the commands module
// that is the build tree's bin/ or an installed tree's lib/tessera/, where the image module sits.
std::filesystem::path own_directory() {
  static const char anchor = 0;
  Dl_info info{};
  if (dladdr(&anchor, &info) == 0 || info.dli_fname == nullptr) return {};
  return std::filesystem::path(info.dli_fname).parent_path();
}

// Beside this code first, then the installed module directory (a program built against the installed
// libraries). dlopen's own errors are joined into the one line a failure throws.
void* open_module() {
  std::string tried;
  for (const std::filesystem::path& dir : {own_directory(), std::filesystem::path(TESSERA_IMAGE_MODULE_DIR)}) {
    const std::string path = (dir / kModuleName).string();
    if (void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) return module;
    const char* error = dlerror();
    tried += (tried.empty() ? "" : "; ") + (error ? std::string(error) : path);
  }
  throw std::runtime_error(std::string("cannot load the image module ") + kModuleName + " (" + tried + ")");
}

}  // namespace

// Defined (strongly) only where the codec is linked in.
extern "C" const void* tessera_image_codec_v1() __attribute__((weak));

namespace tessera {

const void* image_module_table(const char* symbol, const void* (*linked)()) {
  if (linked) return linked();
  static void* const module = open_module();  // once per process; never closed, as tables point into it
  using Entry = const void* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(module, symbol));
  if (!entry) throw std::runtime_error(std::string(kModuleName) + " has no " + symbol + " (a mismatched installation)");
  return entry();
}

const ImageCodec& image_codec() {
  static const auto* const codec =
      static_cast<const ImageCodec*>(image_module_table("tessera_image_codec_v1", tessera_image_codec_v1));
  return *codec;
}

}  // namespace tessera
