// The bundled test data (tests/data; CMake passes its path as TESSERA_TEST_DATA_DIR).
#pragma once

#include <string>

namespace tessera::test {

// The path of a file under tests/data, e.g. data("osd-shapes/catmark_cube.obj").
inline std::string data(const std::string& name) { return std::string(TESSERA_TEST_DATA_DIR) + "/" + name; }

}  // namespace tessera::test
