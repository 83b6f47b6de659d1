#!/usr/bin/env bash
# The main job: install what is missing, build, denoise the default fixture into out/ with PNG
# previews and a report. Extra arguments go to `svgf denoise` (e.g. --backend cpu).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh svgf
sequence=${SVGF_DEMO_SEQUENCE:-fixtures/cornell-moving}
./build/app/svgf denoise "$sequence" out "$@"
echo "previews: out/preview/*.png (noisy | denoised | reference); all in one page: out/report.html"
