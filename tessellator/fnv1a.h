// 64-bit FNV-1a, for hashing processed factors (pattern caches) and digests of outputs.
// Little-endian byte order of each value, so digests are the same on every host.
#pragma once

#include <cstdint>

namespace tessera::ts {

struct Fnv1a {
  std::uint64_t value = 0xcbf29ce484222325ull;
  // Adds the low `bytes` bytes of x, least significant first.
  void add(std::uint64_t x, int bytes = 8) {
    for (int i = 0; i < bytes; ++i) {
      value ^= (x >> (8 * i)) & 0xFF;
      value *= 0x100000001b3ull;
    }
  }
};

}  // namespace tessera::ts
