#!/usr/bin/env bash
# Installs an already-built tree (default build/, as ./scripts/test.sh leaves it; nothing is
# rebuilt) into a temporary prefix, builds examples/denoise_sequence against the installed svgf
# package, and requires its output on a committed fixture to equal, file for file and bit for
# bit, what the installed `svgf denoise` writes with its defaults. Also checks that the
# installed CMake files name nothing in the source or build tree. docs/api.md.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=$(cd "${1:-build}" && pwd)
fixture=fixtures/cut  # 12 frames of 128x128 with a camera cut at frame 6
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >/dev/null
if grep -rl -e "$root" -e "$build" "$prefix/lib/cmake"; then
  echo "test-install: the installed CMake files above name the source or build tree" >&2
  exit 1
fi

cmake -S examples/denoise_sequence -B "$work/example" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/example" -j"$(nproc 2>/dev/null || echo 2)" >/dev/null

"$work/example/denoise_sequence" "$fixture" "$work/example-out" >"$work/example.log"
"$prefix/bin/svgf" denoise "$fixture" "$work/svgf-out" --no-preview >/dev/null 2>"$work/svgf.log" ||
  { cat "$work/svgf.log" >&2; exit 1; }

frames=0
for expected in "$work"/svgf-out/frame_*.exr; do
  name=$(basename "$expected")
  cmp -s "$expected" "$work/example-out/$name" || {
    echo "test-install: $name: the example's output differs from svgf denoise's" >&2
    exit 1
  }
  frames=$((frames + 1))
done
written=$(find "$work/example-out" -name 'frame_*.exr' | wc -l)
if [ "$frames" -ne 12 ] || [ "$written" -ne 12 ]; then
  echo "test-install: expected 12 frames from each, svgf denoise wrote $frames, the example $written" >&2
  exit 1
fi
echo "test-install: the example built against the installed package denoised $fixture:" \
     "$frames frames, bit for bit those of svgf denoise ($(tail -1 "$work/example.log"))"
