// The bundled test data (tests/data; CMake passes its path as TESSERA_TEST_DATA_DIR).
#pragma once

#include <string>

namespace tessera::test {

// The path of a file under tests/data, e.g. data("osd-shapes/catmark_cube.obj").
inline std::string data(const std::string& name) { return std::string(TESSERA_TEST_DATA_DIR) + "/" + name; }

// A sanitizer build (ASan + UBSan, TSan): 5-20x slower, so the longest sweeps run a subset of their
// cases there (every case still runs in the normal build).
#ifdef TESSERA_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace tessera::test
