#pragma once
// Per-bit pixel counts of a kernel that returns a bit mask (uint32_t): what the engines'
// run_tallying adds up, e.g. the InputRepair bits of the sanitize stage (core/sanitize.h).
// Integer sums, so the same on every backend, thread count and block shape.
#include <cstdint>

namespace svgf {

inline constexpr int kTallyBits = 8;
// Who owns which bit: 0 .. 5 are the sanitize stage's InputRepair bits (core/sanitize.h); bit 6
// is a pixel whose filter could not give a result and fell back (each method says to what).
inline constexpr uint32_t kTallyFilterFallback = 1u << 6;

// The index of a one-bit mask's bit: its count in Tallies::count.
constexpr int tally_bit(uint32_t mask) {
  int b = 0;
  while ((mask >> b) != 1u) ++b;
  return b;
}

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
