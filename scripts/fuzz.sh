#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (the frame reader, the manifest parser) with clang,
# ASan and UBSan into build-fuzz/ and runs each from its committed seed corpus for a fixed time,
# FUZZ_SECONDS (60) each (docs/sanitizers.md says why a time and not a number of inputs). A
# failing input is kept under build-fuzz/artifacts/<target>/; rerun it with
#   build-fuzz/tests/fuzz/svgf_fuzz_<target> build-fuzz/artifacts/<target>/crash-...
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
seconds=${FUZZ_SECONDS:-60}
targets=(exr_frame manifest)
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
  -DSVGF_FUZZ=ON -DSVGF_BUILD_TESTS=OFF -DSVGF_BUILD_BENCH=OFF -DSVGF_BUILD_GBUFFER=OFF >/dev/null
cmake --build build-fuzz -j"$jobs" --target "${targets[@]/#/svgf_fuzz_}"
new_inputs=$(mktemp -d)  # what the runs add to the corpus; the committed seeds stay as they are
trap 'rm -rf "$new_inputs"' EXIT
for target in "${targets[@]}"; do
  mkdir -p "$new_inputs/$target" "build-fuzz/artifacts/$target"
  dict=()
  if [ -f "tests/fuzz/$target.dict" ]; then dict=(-dict="tests/fuzz/$target.dict"); fi
  log="build-fuzz/fuzz-$target.log"
  echo "fuzz: $target for $seconds s (log: $log)"
  if ! "build-fuzz/tests/fuzz/svgf_fuzz_$target" -max_total_time="$seconds" -timeout=10 \
      -print_funcs=0 -print_final_stats=1 -artifact_prefix="build-fuzz/artifacts/$target/" \
      "${dict[@]}" "$new_inputs/$target" "tests/fuzz/corpus/$target" >"$log" 2>&1; then
    tail -n 80 "$log"
    echo "fuzz: $target FAILED; the input is in build-fuzz/artifacts/$target/" >&2
    exit 1
  fi
  grep -a -E "DONE|stat::number_of_executed_units" "$log"
done
