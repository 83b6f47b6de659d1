#!/usr/bin/env bash
# The GPU half of docs/benchmarks.md in one go, on a CUDA machine:
#   bench/gpu_run.sh OUT_DIR [SVGF_BENCH_COMMAND]
# SVGF_BENCH_COMMAND defaults to ".gpu/bench/run svgf-bench", the bundle made here by
#   ../shared/gpu/bundle .gpu/bench build-bench/bench/svgf-bench
# Writes OUT_DIR/gpu.json (svgf-bench suite gpu), its log, nvidia-smi's view of the device and
# Nsight Compute profiles of the 1080p default configuration in both modes (ncu_*.csv).
set -uo pipefail
out=${1:?usage: bench/gpu_run.sh OUT_DIR [SVGF_BENCH_COMMAND]}
bench=${2:-.gpu/bench/run svgf-bench}
mkdir -p "$out"

{ nvidia-smi --query-gpu=name,driver_version,pci.bus_id,clocks.max.sm,clocks.max.mem,memory.total,power.limit \
    --format=csv; nvidia-smi; } > "$out/nvidia-smi.txt" 2>&1

# The suite: sizes, iterations, chart configurations, the wavelet study, the JBF, quality on the
# fixtures.
# Frames are rendered in memory (--cache ""): writing 4K EXR files would cost more than rendering.
timeout 400 $bench suite gpu --out "$out" --cache "" > "$out/gpu-suite.log" 2>&1
echo "suite exit status $?"

# Profiles: one timed frame after three warm-up frames; --launch-skip passes the warm-up
# frames' kernels (6 a frame in fast mode, 9 in exact mode). --clock-control none: the card's
# clocks stay as they are.
ncu=$(command -v ncu || ls /opt/nvidia/nsight-compute/*/ncu /usr/local/cuda/bin/ncu 2>/dev/null | head -1)
for mode in fast exact; do
  if [ "$mode" = fast ]; then per_frame=6; else per_frame=9; fi
  timeout 60 "$ncu" --target-processes all --clock-control none --csv --page details \
    --section SpeedOfLight --section MemoryWorkloadAnalysis --section ComputeWorkloadAnalysis \
    --section Occupancy --section LaunchStats --section WarpStateStats \
    --metrics dram__bytes_read.sum,dram__bytes_write.sum,lts__t_bytes.sum,l1tex__t_bytes.sum \
    --launch-skip $((3 * per_frame)) --launch-count $per_frame --log-file "$out/ncu_$mode.csv" \
    $bench --backend cuda --mode $mode --size 1080p --frames 1 --warmup 3 --no-ceilings \
    --distinct-frames 4 --cache "" > "$out/ncu_${mode}_app.log" 2>&1
  echo "ncu $mode exit status $?"
done

# A short table for the caller's terminal.
python3 - "$out/gpu.json" <<'EOF' || true
import json, sys
d = json.load(open(sys.argv[1]))
dev = d.get("device", {})
print(dev.get("name"), "SMs", dev.get("sms"), "memcpy D2D GB/s", round(dev.get("memcpy_d2d_gbs", 0)),
      "FP32 Tops/s", round(dev.get("fp32_ops_per_s", 0) / 1e12, 1))
for c in d.get("checks", []):
    print("check:", c["name"], "differing", c["differing"], "of", c["values"])
for t in d.get("timings", []):
    if "error" in t:
        print("ERROR", t["label"], t["error"]); continue
    f = t["frame_ms"]["filter"]; i = t["input"]
    floor = t.get("floor", {}).get("floor_ms", float("nan"))  # SVGF only: other methods have no frame floor
    print(f'{t["group"]:10} {t["label"]:28} {i["width"]}x{i["height"]:<5} median {f["median"]:.4f} '
          f'p95 {f["p95"]:.4f} floor {floor:.4f} mem {t.get("peak_device_bytes", 0) / 2**20:.0f} MiB')
print("quality entries", len(d.get("quality", [])), "errors", sum("error" in q for q in d.get("quality", [])))
EOF
