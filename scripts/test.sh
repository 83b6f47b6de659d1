#!/usr/bin/env bash
# Install what is missing, build everything, run the whole test suite. GPU tests report
# "skipped" where there is no CUDA device.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build -j"$jobs" --output-on-failure --timeout 600
