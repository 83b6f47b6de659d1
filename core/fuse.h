#pragma once
// Fusion: two pixel kernels as one, run per pixel one after the other by the same thread (the
// second may read what the first wrote at that pixel). A pipeline asks for fusion by composing
// kernels; the engines launch the result like any other kernel. The first kernel's result (a
// bool for counting kernels) is the fused kernel's.
#include <type_traits>

#include "core/hd.h"

namespace svgf {

template <class First, class Second>
struct Then {
  First first;
  Second second;
  SVGF_HD auto operator()(int x, int y) const {
    if constexpr (std::is_void_v<decltype(first(x, y))>) {
      first(x, y);
      second(x, y);
    } else {
      const auto r = first(x, y);
      second(x, y);
      return r;
    }
  }
};

template <class First, class Second>
Then<First, Second> then(const First& a, const Second& b) {
  return Then<First, Second>{a, b};
}

}  // namespace svgf
