#!/usr/bin/env bash
# The main job: build, then render the Cornell box (256 x 256) to out/cornell.png. Until the rasterized
# path lands, the image is the reference path tracer's (64 samples per pixel). Extra arguments go to
# bricklight-render (e.g. --backend gl, --spp 256, --aov indirect-diffuse).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/configure.sh"
mkdir -p "$root/out"
"$root/build/bin/bricklight-render" --scene cornell --width 256 --height 256 --reference --spp 64 \
  --out "$root/out/cornell.png" "$@"
