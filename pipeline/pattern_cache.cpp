#include "pipeline/pattern_cache.h"

#include <chrono>

namespace tessera {

const ts::Pattern& PatternCache::get(const ts::ProcessedFactors& key, ts::OutputPrimitive output, bool& hit,
                                     double* miss_seconds) {
  const std::uint64_t h = ts::hash(key, output);
  for (const Entry& e : entries_) {
    if (e.hash == h && e.output == output && e.key == key) {
      ++hits_;
      hit = true;
      return e.pattern;
    }
  }
  ++misses_;
  hit = false;
  Entry* slot;
  if (entries_.size() < kEntries) {
    slot = &entries_.emplace_back();
  } else {
    slot = &entries_[next_victim_];
    next_victim_ = (next_victim_ + 1) % kEntries;
  }
  slot->hash = h;
  slot->key = key;
  slot->output = output;
  slot->shape.reset();
  const auto start = std::chrono::steady_clock::now();
  ts::generate(key, output, slot->pattern);
  if (miss_seconds != nullptr)
    *miss_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return slot->pattern;
}

const ts::PatternShape& PatternCache::shape(const ts::Pattern& pattern) {
  for (Entry& e : entries_) {
    if (&e.pattern != &pattern) continue;
    if (!e.shape) e.shape = ts::pattern_shape(e.pattern);
    return *e.shape;
  }
  // Not one of this cache's patterns: a programmer error, answered without a claim.
  static const ts::PatternShape none{};
  return none;
}

std::size_t PatternCache::bytes() const {
  std::size_t b = entries_.capacity() * sizeof(Entry);
  for (const Entry& e : entries_)
    b += e.pattern.points.capacity() * sizeof(ts::DomainPoint) + e.pattern.indices.capacity() * sizeof(std::uint32_t);
  return b;
}

}  // namespace tessera
