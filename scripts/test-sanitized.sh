#!/usr/bin/env bash
# Builds the CPU tests with AddressSanitizer and UndefinedBehaviorSanitizer (SVGF_SANITIZE: no
# CUDA, no benchmark) into build-asan/ and runs them; any finding fails its test. What is
# checked, and why some checks stop short of the kernels: docs/sanitizers.md.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DSVGF_SANITIZE=ON -DSVGF_BUILD_BENCH=OFF \
  >/dev/null
cmake --build build-asan -j"$jobs"
# ASan's defaults, leak checking included: TBB's worker threads leave nothing LeakSanitizer
# reports, so there is no suppression list. UBSan's report gets the stack that led there.
export UBSAN_OPTIONS="print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
ctest --test-dir build-asan -j"$jobs" --output-on-failure --timeout 900
