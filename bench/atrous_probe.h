#pragma once
// The CPU's exact a-trous iteration on a frame small enough to stay in the cores' caches: the
// rate its taps reach when memory does not limit them. Beside a run's a-trous (its in-frame
// rate, bench/runner.cpp), it tells whether the stage waits on memory or on the cores
// (docs/benchmarks.md: "CPU: what limits it").
namespace svgf::bench {

// Nanoseconds a tap (those inside the frame) of the exact a-trous rows of the CPU kernel variant
// that runs, on `threads` workers over a 1280x64 synthetic frame (a 720p frame's rows) with a
// surface at every pixel, iterations of steps 1 and 2 alternating: 14 planes, 4.6 MB, in the L3
// cache. The fastest of 7 runs. (A 256x128 frame, in two cores' L2, measured the rows' per-row
// and per-iteration costs instead: 0.55 ns against the 720p frame's 0.44 on the Zen 5 VM.)
double resident_atrous_ns_per_tap(int threads);

}  // namespace svgf::bench
