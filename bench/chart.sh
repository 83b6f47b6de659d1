#!/usr/bin/env bash
# Draws the benchmark charts (gnuplot) from suite results:
#   bench/chart.sh [RESULTS_DIR [OUT_DIR [QUALITY_FILE]]]   (both dirs default to docs/bench)
# RESULTS_DIR holds cpu.json and/or gpu.json (svgf-bench suite ...). QUALITY_FILE: the
# evaluation set's quality (svgf-bench quality), which replaces the suites' fixture quality on
# the quality axis and in the per-scene error charts. Writes OUT_DIR/data/*.dat
# and summary.md (svgf-bench chart-data), then OUT_DIR/*.png. Set SVGF_BENCH to the binary if it
# is not in build-bench/ or build/.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
results=${1:-$root/docs/bench}
out=${2:-$results}
quality=${3:-}
bench=${SVGF_BENCH:-}
if [ -z "$bench" ]; then
  for b in "$root/build-bench/bench/svgf-bench" "$root/build/bench/svgf-bench"; do
    if [ -x "$b" ]; then bench=$b; break; fi
  done
fi
[ -n "$bench" ] || { echo "chart.sh: build svgf-bench first, or set SVGF_BENCH" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "chart.sh: gnuplot is not installed (apt-get install gnuplot-nox)" >&2; exit 1; }

data=$out/data
if [ -n "$quality" ]; then
  "$bench" chart-data "$results" --out "$data" --quality "$quality"
else
  "$bench" chart-data "$results" --out "$data"
fi

# Where the chart's times come from, for the subtitle.
subtitle="CPU: $(jq -r '.host.cpu_model + ", " + (.host.hardware_threads|tostring) + " threads"' "$results/cpu.json" 2>/dev/null || echo '-')"
subtitle+="; GPU: $(jq -r '.device.name // "-"' "$results/gpu.json" 2>/dev/null || echo '-')"
cpu_size=$(jq -r '.chart_size // empty' "$results/cpu.json" 2>/dev/null || true)
gpu_size=$(jq -r '.chart_size // empty' "$results/gpu.json" 2>/dev/null || true)
if [ -n "$cpu_size" ] && [ -n "$gpu_size" ] && [ "$cpu_size" != "$gpu_size" ]; then
  subtitle+="; CPU times at $cpu_size, GPU times at $gpu_size"
elif [ -n "$cpu_size$gpu_size" ]; then
  subtitle+="; frames of ${cpu_size:-$gpu_size}"
fi
if [ -n "$quality" ]; then
  # The set's parameters, from its first scene (svgf-fixtures eval renders them all alike).
  set_desc=$(jq -r '.set.scenes | "\(.[0].width)x\(.[0].height), \(.[0].frames) frames, \(.[0].reference_spp)-spp references"' "$quality")
  clean=$(jq -r '.clean_scenes | length' "$quality")
  # The quality axis is the clean scenes' mean, PSNR with the references' noise taken out
  # (bench/eval_quality.h); a scene's error curves are its own, corrected where it is clean.
  quality_on="the $clean clean scenes of the evaluation set ($set_desc)"
  errors_on="the evaluation set ($set_desc; PSNR with the reference noise taken out on clean scenes)"
  subtitle+="; PSNR against the true image (reference noise taken out); CPU exact = CUDA exact"
else
  quality_on="the fixture scenes"
  errors_on=$quality_on
  subtitle+="; quality on the fixtures"
fi

for metric in psnr flip; do
  gnuplot -e "data='$data'; out='$out/quality_$metric.png'; metric='$metric'; subtitle='$subtitle'; quality_on='$quality_on'" \
    "$here/chart/quality.gp"
done
# Per-scene charts of scenes no longer in the results (a set without one) would be stale.
for png in "$out"/errors_*.png; do
  [ -e "$png" ] || continue
  scene=$(basename "$png" .png); scene=${scene#errors_}
  grep -qxF "$scene" "$data/scenes.txt" || rm -f "$png" "$data/errors_${scene}_"*.dat
done
while read -r scene; do
  [ -n "$scene" ] || continue
  gnuplot -e "data='$data'; scene='$scene'; out='$out/errors_$scene.png'; quality_on='$errors_on'" "$here/chart/errors.gp"
done < "$data/scenes.txt"
gnuplot -e "data='$data'; out_pixels='$out/scaling_pixels.png'; out_iterations='$out/scaling_iterations.png'" \
  "$here/chart/scaling.gp"
gnuplot -e "data='$data'; out='$out/kernel_sizes.png'; subtitle='$subtitle'" "$here/chart/kernel_sizes.gp"
# Nsight Compute reports of the GPU run (bench/gpu_run.sh), summarized, when present.
ncu_reports=$(ls "$results"/raw/ncu_*.csv 2>/dev/null || true)
if [ -n "$ncu_reports" ] && command -v python3 >/dev/null; then
  # shellcheck disable=SC2086
  python3 "$here/ncu_summary.py" $((1920 * 1080)) $ncu_reports > "$data/ncu_1080p.md"
fi
echo "chart.sh: charts in $out, tables in $data/summary.md"
