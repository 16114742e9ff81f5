// A small per-thread cache of tessellation patterns keyed by processed factors (tessellator.h): the
// pattern is a pure function of (ProcessedFactors, OutputPrimitive), so patches with equal factors
// (the common case: uniform or screen-space factors in a region) tessellate once per thread.
//
// Bounded: at most kEntries patterns (each at most ~65x65 points), replaced round-robin. Results never
// depend on hits or misses, only speed does.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "tessellator/pattern_shape.h"
#include "tessellator/tessellator.h"

namespace tessera {

class PatternCache {
 public:
  static constexpr std::size_t kEntries = 16;

  // The pattern for `key`; valid until the next call. `hit` tells whether it was cached.
  // `miss_seconds`, when given, gets the time a miss spent tessellating added (hits read no clock).
  const ts::Pattern& get(const ts::ProcessedFactors& key, ts::OutputPrimitive output, bool& hit,
                         double* miss_seconds = nullptr);
  // The shape (pattern_shape.h) of a pattern get() returned last, computed once per entry when first
  // asked for: only the back-patch test needs it.
  const ts::PatternShape& shape(const ts::Pattern& pattern);

  // Hits and misses since construction or the last reset_counters(); the entries stay.
  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }
  void reset_counters() { hits_ = misses_ = 0; }
  std::size_t bytes() const;

 private:
  struct Entry {
    std::uint64_t hash = 0;
    ts::ProcessedFactors key;
    ts::OutputPrimitive output = ts::OutputPrimitive::triangle_cw;
    ts::Pattern pattern;
    std::optional<ts::PatternShape> shape;
  };
  std::vector<Entry> entries_;
  std::size_t next_victim_ = 0;
  std::uint64_t hits_ = 0, misses_ = 0;
};

}  // namespace tessera
