#pragma once
// The row drivers' tests compare every CPU kernel variant this build has and this CPU runs
// with the per-pixel kernels (kernels_cpu/cpu_variant.h).
#include <catch2/catch.hpp>

#include "kernels_cpu/cpu_variant.h"

namespace svgf::test {

// body(variant) on each runnable variant; at least one must run.
template <class Body>
void for_each_runnable_variant(const Body& body) {
  int variants = 0;
  for (const cpu::CpuVariant* v : cpu::built_variants()) {
    if (!cpu::runs_here(*v)) continue;
    body(*v);
    ++variants;
  }
  REQUIRE(variants > 0);
}

}  // namespace svgf::test
