// libFuzzer harness: scene files (JSON) through read_scene and back through scene_json. Bad input
// must be a UsageError or InputError naming the field, never a crash.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "tools/scene/common.h"
#include "tools/scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // read_scene reads a file: one per process, in memory-backed /dev/shm when there is one.
  static const std::string path = (access("/dev/shm", W_OK) == 0 ? std::string("/dev/shm") : std::string("/tmp")) +
                                  "/tessera-fuzz-scene-" + std::to_string(getpid()) + ".json";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    const tessera::scene::RenderSettings s = tessera::scene::read_scene(path);
    (void)tessera::scene::scene_json(s, "");
  } catch (const tessera::scene::UsageError&) {
  } catch (const tessera::scene::InputError&) {
  }
  return 0;
}
