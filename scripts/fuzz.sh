#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (the frame reader, the manifest parser) with clang,
# ASan and UBSan into build-fuzz/ and runs each from its committed seed corpus for a fixed time,
# FUZZ_SECONDS (60) each, side by side (docs/sanitizers.md says why a time and not a number of inputs). A
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
# The targets run side by side, one per core (libFuzzer's run is single-threaded): each still
# gets its full time, in half the wall time on CI's 2 cores.
fuzz_one() {
  local target=$1 dict=()
  mkdir -p "$new_inputs/$target" "build-fuzz/artifacts/$target"
  if [ -f "tests/fuzz/$target.dict" ]; then dict=(-dict="tests/fuzz/$target.dict"); fi
  "build-fuzz/tests/fuzz/svgf_fuzz_$target" -max_total_time="$seconds" -timeout=10 \
    -print_funcs=0 -print_final_stats=1 -artifact_prefix="build-fuzz/artifacts/$target/" \
    "${dict[@]}" "$new_inputs/$target" "tests/fuzz/corpus/$target" >"build-fuzz/fuzz-$target.log" 2>&1
}
pids=()
for target in "${targets[@]}"; do
  echo "fuzz: $target for $seconds s (log: build-fuzz/fuzz-$target.log)"
  fuzz_one "$target" &
  pids+=($!)
done
failed=0
for i in "${!targets[@]}"; do
  target=${targets[$i]}
  log="build-fuzz/fuzz-$target.log"
  if ! wait "${pids[$i]}"; then
    tail -n 80 "$log"
    echo "fuzz: $target FAILED; the input is in build-fuzz/artifacts/$target/" >&2
    failed=1
    continue
  fi
  grep -a -E "DONE|stat::number_of_executed_units" "$log"
done
exit $failed
