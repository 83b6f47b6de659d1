#pragma once
// How SVGF's functors are evaluated and stored: exact mode (ExactArith over separate float
// planes on the CPU, over packed Packed4 pixels on CUDA) or fast mode (FastArith over packed
// pixels, CUDA only). A flavor is a choice of arithmetic and storage over the same functors,
// never a second copy of a formula; it also says which stages the pipeline fuses into one
// launch (methods/svgf/pipeline.h): kFusedReprojection (demodulate + reproject + guide packing),
// kFusedOutputs (the feedback copy and the remodulation done by the a-trous iterations whose
// results they are), kFusedGradient (A-SVGF's three stages over tiles of strata).
#include "core/arith.h"
#include "core/views.h"
#include "methods/svgf/edge_stopping.h"

namespace svgf {

struct SvgfExact {
  using Arith = ExactArith;
  using Guides = GuideView;             // separate depth and normal planes
  using Signal = IllumVarView;          // color + variance, four planes
  using ConstSignal = ConstIllumVarView;
  // Every stage is its own pass (so each can be timed, read back and compared alone), but for
  // the outputs: the feedback copy and the remodulation ride on the a-trous iterations whose
  // results they are, as on CUDA (the CPU's rows remodulate a row as they finish it:
  // kernels_cpu/svgf_rows.h, AtrousRowOutputs). The remodulation's own pass read back the
  // filtered color and wrote the output: Zen 5 VM 720p camera-pan 2 threads, about 1 ms of a
  // 52 ms frame (docs/benchmarks.md).
  static constexpr bool kFusedReprojection = false;
  static constexpr bool kFusedOutputs = true;
  // A-SVGF's three stages as three passes (the CPU runs them as vectorized rows).
  static constexpr bool kFusedGradient = false;
  // The a-trous and spatial-variance taps as one loop with bounds tests (a second, test-free
  // copy for interior pixels made the exact kernels over planes larger and slower: the a-trous
  // on the H100, the variance on the H200).
  static constexpr bool kSplitInterior = false;
  static constexpr bool kSplitInteriorVariance = false;
  static constexpr bool kUnrollVariance = false;
  // No register cap on the a-trous (a CUDA launch hint; 0: the compiler's choice).
  static constexpr int kAtrousMaxRegisters = 0;
  template <class Body>
  static void with_normal_power(float phi_normal, const Body& body) {
    with_normal_power_of<Arith>(phi_normal, body);
  }
};

// Exact arithmetic over fast mode's packed storage: what the CUDA engine runs in exact mode.
// Storage is not arithmetic, so it gives SvgfExact's bits (tests/svgf_packed_exact_test.cpp runs
// both on the CPU, bitwise); on the GPU an a-trous tap loads its color + variance and its
// depth + normal as two 16-byte loads instead of eight 4-byte ones, and computes two addresses
// instead of eight (the exact a-trous is issue-bound: docs/benchmarks.md). The CPU keeps
// SvgfExact: its row drivers stream planes (kernels_cpu/svgf_rows.cpp).
struct SvgfExactPacked {
  using Arith = ExactArith;
  using Guides = PackedGuides;
  using Signal = PackedIllumVar<Packed4>;
  using ConstSignal = PackedIllumVar<const Packed4>;
  // Fused as in fast mode (the same stores of the same values: the same bits): demodulate +
  // reproject + guide packing in one launch, the feedback copy and the remodulation in the
  // a-trous iterations that produce them. H200, 1080p camera-pan: demodulate + reproject
  // 0.129 -> 0.118 ms; the remodulation's own pass took 0.031 ms, in the last iteration 0.018
  // (docs/benchmarks.md).
  static constexpr bool kFusedReprojection = true;
  static constexpr bool kFusedOutputs = true;
  // A-SVGF's three stages in one launch over tiles of strata (methods/svgf/gradient_tile.h)
  // where the filter is the default's size; the same lambdas.
  static constexpr bool kFusedGradient = true;
  // The a-trous's interior pixels skip the 24 bounds tests (same taps, same order). Packed, the
  // test-free copy pays: H200, 1080p exact a-trous 0.806 -> 0.800 ms at camera-pan, 0.497 ->
  // 0.469 at cornell-moving. The variance's did not (0.136 -> 0.148 ms at camera-pan); its
  // default 7x7 unrolled with the bounds tests did (0.120 -> 0.113 ms).
  static constexpr bool kSplitInterior = true;
  static constexpr bool kSplitInteriorVariance = false;
  static constexpr bool kUnrollVariance = true;
  // The a-trous capped at 64 registers (it took 72: 3 blocks of 256 threads an SM, 4 now, at
  // the price of 32 to 48 bytes spilled): 0.658 -> 0.629 ms at 1080p camera-pan on the H200;
  // capped at 56 or 48 it was slower (0.650, 0.658).
  static constexpr int kAtrousMaxRegisters = 64;
  template <class Body>
  static void with_normal_power(float phi_normal, const Body& body) {
    with_normal_power_of<Arith>(phi_normal, body);
  }
};

#if defined(__CUDACC__)
struct SvgfFast {
  using Arith = FastArith;
  using Guides = PackedGuides;          // depth + normal as one Packed4
  using Signal = PackedIllumVar<Packed4>;
  using ConstSignal = PackedIllumVar<const Packed4>;
  // Demodulate + reproject + guide packing in one launch; the feedback copy and the
  // remodulation ride on the a-trous iterations that produce them; A-SVGF's stages in one.
  static constexpr bool kFusedReprojection = true;
  static constexpr bool kFusedOutputs = true;
  static constexpr bool kFusedGradient = true;
  // Interior pixels (footprint inside the image) skip the bounds tests: the a-trous's 24
  // (kSplitInterior), the variance's 48 (its default 7x7 unrolled; kSplitInteriorVariance).
  static constexpr bool kSplitInterior = true;
  static constexpr bool kSplitInteriorVariance = true;
  static constexpr bool kUnrollVariance = true;  // implied: the split paths are unrolled
  static constexpr int kAtrousMaxRegisters = 0;
  template <class Body>
  static void with_normal_power(float phi_normal, const Body& body) {
    with_normal_power_of<Arith>(phi_normal, body);
  }
};
#endif

}  // namespace svgf
