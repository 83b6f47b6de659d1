#!/usr/bin/env bash
# The GPU checks of docs/cuda.md, on a machine with a CUDA device, from the repository root:
# the full GPU test binary, the CUDA variants (cuda, cuda-fast) of every test body of the stage,
# pipeline and OpenCV test binaries (tests/test_device.h), compute-sanitizer memcheck, racecheck
# and initcheck on the GPU tests' reduced mode, the stage tests and the bad-input pipeline
# tests, and (when svgf-bench bundles
# are given) the 1080p speed of this build against a baseline build, in one sitting.
# Bundles made on the build machine with
#   ../shared/gpu/bundle .gpu/tests build/tests/svgf_gpu_tests build/tests/svgf_stage_tests \
#     build/tests/svgf_pipeline_tests build/tests/svgf_opencv_tests
# (svgf_opencv_tests brings cv::ximgproc's libraries, about 50 MiB compressed: with the tree
# that passes the 64 MiB a call may carry, so bundle it alone or leave it out; a missing
# binary shows as exit 127 in the summary line)
#   ../shared/gpu/bundle .gpu/bench build-bench/bench/svgf-bench          (this build)
#   ../shared/gpu/bundle .gpu/base  OLD/build-bench/bench/svgf-bench      (optional baseline)
# Usage: kernels_cuda/run_gpu_checks.sh [LOG_DIR [tests|speed|all]]   (logs default to $OUT)
set -uo pipefail
logs=${1:-${OUT:-gpu-logs}}
what=${2:-all}
mkdir -p "$logs"
sanitizer=$(command -v compute-sanitizer ||
  ls /usr/local/cuda*/bin/compute-sanitizer /usr/local/cuda*/compute-sanitizer/compute-sanitizer \
    2>/dev/null | head -1)

{ nvidia-smi; nvidia-smi --query-gpu=name,driver_version,memory.total,compute_cap --format=csv
  "$sanitizer" --version; lscpu | grep -E "Model name|^CPU\(s\)"; } >"$logs/device.txt" 2>&1
grep -E "Model name|H100|H200" "$logs/device.txt" | head -3

if [ "$what" != speed ]; then
timeout 300 .gpu/tests/run svgf_gpu_tests --durations yes >"$logs/gpu_tests.txt" 2>&1
rc_tests=$?
tail -n 12 "$logs/gpu_tests.txt"
# Every test body's CUDA variants: cuda (exact: each stage run also compared bitwise with the
# CPU) and cuda-fast (within the fast tolerance).
rc_devices=0
for t in svgf_stage_tests svgf_pipeline_tests svgf_opencv_tests; do
  timeout 200 .gpu/tests/run $t "[cuda]" --durations yes >"$logs/${t}_cuda.txt" 2>&1
  rc=$?
  [ $rc -ne 0 ] && rc_devices=$rc
  echo "$t [cuda]: exit $rc"; tail -n 3 "$logs/${t}_cuda.txt"
done

# The bundle's libraries, unpacked by the runs above, for the sanitizer to start the binary.
lib=/tmp/bundle-runtime-$(md5sum .gpu/tests/runtime.tar.xz | cut -c1-12)
rc_memcheck=-1 rc_racecheck=-1 rc_initcheck=-1
for tool in memcheck racecheck initcheck; do
  extra=()
  [ "$tool" = memcheck ] && extra=(--leak-check full)
  LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" timeout 200 \
    "$sanitizer" --tool "$tool" "${extra[@]}" --error-exitcode 99 \
    .gpu/tests/bin/svgf_gpu_tests --reduced '~[cuda-errors]~[bench]~[timing]' \
    >"$logs/$tool.txt" 2>&1
  rc=$?
  LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" timeout 200 \
    "$sanitizer" --tool "$tool" "${extra[@]}" --error-exitcode 99 \
    .gpu/tests/bin/svgf_stage_tests "[cuda]" >"$logs/${tool}_stages.txt" 2>&1
  rc2=$?
  [ $rc -eq 0 ] && rc=$rc2
  LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" timeout 300 \
    "$sanitizer" --tool "$tool" "${extra[@]}" --error-exitcode 99 \
    .gpu/tests/bin/svgf_pipeline_tests "[cuda][bad-input]" >"$logs/${tool}_bad_input.txt" 2>&1
  rc3=$?
  [ $rc -eq 0 ] && rc=$rc3
  case $tool in
    memcheck) rc_memcheck=$rc ;;
    racecheck) rc_racecheck=$rc ;;
    initcheck) rc_initcheck=$rc ;;
  esac
  grep -E "ERROR SUMMARY|RACECHECK SUMMARY|LEAK SUMMARY|test cases|summary:" \
    "$logs/$tool.txt" "$logs/${tool}_stages.txt" "$logs/${tool}_bad_input.txt"
done
echo "exit codes: gpu tests $rc_tests, device variants $rc_devices, memcheck $rc_memcheck, racecheck $rc_racecheck, initcheck $rc_initcheck"
fi
[ "$what" = tests ] && exit 0

# Speed: 1080p, median of 200 frames after 20, default configuration; baseline and this build
# alternate so that both see the same card state. Frames are rendered once into a shared cache.
[ -x .gpu/bench/run ] || exit 0
builds=(bench)
[ -x .gpu/base/run ] && builds=(base bench)
cache=/tmp/svgf-frame-cache
for round in 1 2; do
  for scene in camera-pan cornell-moving; do
    for mode in fast exact; do
      for b in "${builds[@]}"; do
        json="$logs/speed_${b}_${scene}_${mode}_${round}.json"
        timeout 240 .gpu/$b/run svgf-bench --backend cuda --mode $mode --size 1080p \
          --scene $scene --frames 200 --warmup 20 --cache $cache --no-ceilings \
          --json "$json" >/dev/null 2>"$logs/speed_${b}.err"
        python3 - "$json" "$b $scene $mode round $round" <<'PY' || { echo "$b $scene $mode: failed"; tail -3 "$logs/speed_${b}.err"; }
import json, sys
t = json.load(open(sys.argv[1]))["timings"][0]
f = t["frame_ms"]["filter"]
stages = " ".join(f'{s["stage"]} {s["ms"]["median"]:.4f}' for s in t.get("stages", []))
print(f'{sys.argv[2]}: median {f["median"]:.4f} ms p95 {f["p95"]:.4f} ms | {stages}')
PY
      done
    done
  done
done | tee "$logs/speed.txt"
rm -f "$logs"/speed_*.json  # the table above is what is kept
