#!/usr/bin/env bash
# The evaluation set's quality (issue 13 item 4) on a lent machine, in calls of bounded length:
#   bench/eval_on_device.sh OUT_DIR [SECONDS] [SCENE...]
# Each call starts what is not running yet and waits at most SECONDS (default 540) for it:
#   1. `svgf-fixtures eval` into /tmp/svgf-eval (resumable: a frame already rendered is kept);
#   2. once the set is complete, `svgf-bench quality --set /tmp/svgf-eval`;
# and copies the logs and, when done, eval_quality.json into OUT_DIR. Both run detached
# (setsid), so they go on between calls; call again until the summary line says "done".
# The machine is given back after 30 s without a call, and everything under /tmp with it: make
# the calls back to back (each ends before its time limit, with SECONDS below it).
# The bundle: ../shared/gpu/bundle .gpu/bench build-bench/bench/svgf-bench \
#               build-bench/gbuffer/svgf-fixtures
# It has no OpenCV, so the cv- baselines get no quality here.
set -uo pipefail
out=${1:?usage: bench/eval_on_device.sh OUT_DIR [SECONDS] [SCENE...]}
budget=${2:-540}
shift $(( $# >= 2 ? 2 : 1 ))
run=${SVGF_BUNDLE_RUN:-.gpu/bench/run}
set_dir=/tmp/svgf-eval
mkdir -p "$out" "$set_dir"
scene_args=()
for s in "$@"; do scene_args+=(--scene "$s"); done
start=$(date +%s)
left() { echo $(( budget - ($(date +%s) - start) )); }
# Each detached job's pid is kept in a file: a pid file names this script's own jobs only.
running() { [ -f "/tmp/svgf-eval-$1.pid" ] && kill -0 "$(cat "/tmp/svgf-eval-$1.pid")" 2>/dev/null; }

"$run" svgf-fixtures --help >/dev/null 2>&1  # unpacks the bundle's libraries once
if [ ! -f "$set_dir/.rendered" ] && ! running render; then
  setsid nohup bash -c "'$run' svgf-fixtures eval --out '$set_dir' ${scene_args[*]} && touch '$set_dir/.rendered'" \
    >>/tmp/svgf-eval-render.log 2>&1 </dev/null &
  echo $! >/tmp/svgf-eval-render.pid
  sleep 2
fi
while [ ! -f "$set_dir/.rendered" ] && running render && [ "$(left)" -gt 15 ]; do sleep 3; done
if [ -f "$set_dir/.rendered" ] && [ ! -f /tmp/svgf-eval-quality.json ] && ! running quality; then
  setsid nohup "$run" svgf-bench quality --set "$set_dir" --out /tmp/svgf-eval-quality.json \
    >>/tmp/svgf-eval-quality.log 2>&1 </dev/null &
  echo $! >/tmp/svgf-eval-quality.pid
  sleep 2
fi
while running quality && [ "$(left)" -gt 15 ]; do sleep 3; done
cp /tmp/svgf-eval-render.log "$out/eval-render.log" 2>/dev/null
cp /tmp/svgf-eval-quality.log "$out/eval-quality.log" 2>/dev/null
tail -c 200 /tmp/svgf-eval-render.log 2>/dev/null; echo
if [ -f /tmp/svgf-eval-quality.json ]; then
  cp /tmp/svgf-eval-quality.json "$out/eval_quality.json"
  echo "eval_on_device: done: $out/eval_quality.json"
elif running quality; then
  echo "eval_on_device: quality running ($(grep -o '\[[0-9]*/[0-9]*\]' /tmp/svgf-eval-quality.log | tail -1) pairs measured): call again"
elif running render; then
  echo "eval_on_device: rendering: call again"
else
  echo "eval_on_device: stopped without a result: see $out/eval-render.log and eval-quality.log"
  exit 1
fi
