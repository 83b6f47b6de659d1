#pragma once
// Per-bit pixel counts of a kernel that returns a bit mask (uint32_t): what the engines'
// run_tallying adds up, e.g. the InputRepair bits of the sanitize stage (core/sanitize.h).
// Integer sums, so the same on every backend, thread count and block shape.
#include <cstdint>

namespace svgf {

inline constexpr int kTallyBits = 8;

struct Tallies {
  int64_t count[kTallyBits] = {};

  void add_mask(uint32_t mask) {
    for (int b = 0; b < kTallyBits; ++b) count[b] += (mask >> b) & 1u;
  }
  Tallies& operator+=(const Tallies& o) {
    for (int b = 0; b < kTallyBits; ++b) count[b] += o.count[b];
    return *this;
  }
  bool any() const {
    for (int64_t c : count)
      if (c != 0) return true;
    return false;
  }
};

}  // namespace svgf
