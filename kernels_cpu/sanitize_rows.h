#pragma once
// The sanitize stage's CPU driver (sanitize_rows.cpp): the stage every method runs first
// (core/sanitize.h) as a vector scan over spans of a row, the per-pixel kernel only on a span
// with a pixel to repair. Same planes and tallies as the kernel (tests/sanitize_rows_test.cpp).
// Declared here, included by the backend (cpu_backend.h), so every CPU instantiation of a
// method runs the same driver.
#include "core/sanitize.h"
#include "core/tallies.h"
#include "kernels_cpu/cpu_engine.h"

namespace svgf::cpu {

// Runs the kernel over the image (writing the repaired pixels when it has output planes) and
// returns the per-bit counts of its InputRepair masks, as tally_pixels would.
Tallies run_sanitize_rows(const SanitizeInputs& kernel, int width, int height);

template <>
struct PixelDriver<SanitizeInputs> {
  static void run(const SanitizeInputs& k, int w, int h) { run_sanitize_rows(k, w, h); }
  static Tallies tally(const SanitizeInputs& k, int w, int h) { return run_sanitize_rows(k, w, h); }
};

}  // namespace svgf::cpu
