#!/usr/bin/env bash
# The GPU checks of docs/cuda.md, on a machine with a CUDA device, from the repository root:
# the full GPU test binary, compute-sanitizer memcheck and racecheck on its reduced mode, and
# the exact-vs-fast benchmark. Runs on a bundle made on the build machine with
#   ../shared/gpu/bundle .gpu build-cuda/tests/svgf_gpu_tests
# Usage: kernels_cuda/run_gpu_checks.sh [BUNDLE_DIR [LOG_DIR]]   (logs default to $OUT)
set -uo pipefail
bundle=${1:-.gpu}
logs=${2:-${OUT:-gpu-logs}}
mkdir -p "$logs"
sanitizer=$(command -v compute-sanitizer ||
  ls /usr/local/cuda*/bin/compute-sanitizer /usr/local/cuda*/compute-sanitizer/compute-sanitizer \
    2>/dev/null | head -1)

{ nvidia-smi; nvidia-smi --query-gpu=name,driver_version,memory.total,compute_cap --format=csv
  "$sanitizer" --version; } >"$logs/device.txt" 2>&1
cat "$logs/device.txt"

timeout 300 "$bundle/run" svgf_gpu_tests --durations yes >"$logs/gpu_tests.txt" 2>&1
rc_tests=$?
tail -n 25 "$logs/gpu_tests.txt"

# The bundle's libraries, unpacked by the run above, for the sanitizer to start the binary.
lib=/tmp/bundle-runtime-$(md5sum "$bundle/runtime.tar.xz" | cut -c1-12)
rc_memcheck=-1 rc_racecheck=-1
for tool in memcheck racecheck; do
  extra=()
  [ "$tool" = memcheck ] && extra=(--leak-check full)
  LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" timeout 200 \
    "$sanitizer" --tool "$tool" "${extra[@]}" --error-exitcode 99 \
    "$bundle/bin/svgf_gpu_tests" --reduced '~[cuda-errors]~[bench]' >"$logs/$tool.txt" 2>&1
  rc=$?
  [ "$tool" = memcheck ] && rc_memcheck=$rc || rc_racecheck=$rc
  grep -E "ERROR SUMMARY|RACECHECK SUMMARY|LEAK SUMMARY|test cases|summary:" "$logs/$tool.txt"
done

timeout 150 "$bundle/run" svgf_gpu_tests '[bench]' >"$logs/bench.txt" 2>&1
rc_bench=$?
grep -vE "^(~|=|-|$)" "$logs/bench.txt" | tail -n 20
echo "exit codes: tests $rc_tests, memcheck $rc_memcheck, racecheck $rc_racecheck, bench $rc_bench"
