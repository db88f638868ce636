#!/usr/bin/env bash
# The main job: build bricklight-render (and what it needs, not the tests), then render the Cornell box
# (256 x 256) to out/cornell.png with the fast default path (rasterized G-buffer, direct lighting and SDF GI
# over 64 frames). Extra arguments go to
# bricklight-render (e.g. --backend gl, --aov indirect-diffuse, --gi none, or --reference --spp 256 for the
# path tracer).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/configure.sh" bricklight-render
mkdir -p "$root/out"
"$root/build/bin/bricklight-render" --scene cornell --width 256 --height 256 \
  --out "$root/out/cornell.png" "$@"
