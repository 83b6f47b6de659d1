#!/usr/bin/env bash
# Installs, from Debian 12's own packages, whatever the build, tests, fuzz targets, fixture tool
# and charts need and is not yet on this machine. Uses sudo when not root. Safe to run repeatedly.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libtbb-dev            # CPU kernels (oneTBB 2021)
  libopenexr-dev        # frame format (OpenEXR 3 / Imath)
  libpng-dev            # PNG previews
  libglm-dev            # camera math in gbuffer/ and io/
  nlohmann-json3-dev    # manifests, reports, benchmark JSON
  libssl-dev            # SHA-256 of frame files (OpenSSL's EVP digests)
  libcli11-dev          # the tools' command lines: subcommands, validators, help (CLI11 2.1)
  libembree-dev         # fixture path tracer (Embree 3)
  catch2                # tests (Catch2 2.13)
  libopencv-dev libopencv-contrib-dev   # independent checks (imgproc, ximgproc, quality)
  gnuplot-nox           # quality-vs-speed charts
  chromium              # the report page's browser test (tests/app_browser_test.cpp; ~30 s, 411 MB)
  clang libclang-rt-14-dev   # fuzz targets: libFuzzer and clang's sanitizer runtimes (scripts/fuzz.sh)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
