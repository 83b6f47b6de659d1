#!/usr/bin/env bash
# Configures and builds the project into build/ (CUDA included when nvcc is on the PATH).
# Extra arguments are build targets; none builds everything.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
# SVGF_CUDA_ARCHITECTURES overrides CMakeLists.txt's "90-real;75-virtual" (.ci/run sets
# 90-virtual: CI cannot run CUDA, it only compiles it, so it skips ptxas's machine code and the
# PTX for other GPUs, which doubles the front end's work).
arch=()
if [ -n "${SVGF_CUDA_ARCHITECTURES:-}" ]; then
  arch=(-DCMAKE_CUDA_ARCHITECTURES="$SVGF_CUDA_ARCHITECTURES")
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${arch[@]}" >/dev/null
if [ $# -gt 0 ]; then
  cmake --build build -j"$jobs" --target "$@"
else
  cmake --build build -j"$jobs"
fi
