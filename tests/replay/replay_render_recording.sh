#!/usr/bin/env bash
# A real recording: bricklight-render --record of two frames of the Cornell box at 32x32 (rasterized,
# SDF GI), replayed by bricklight-replay on the null device, Vulkan (validation layer on) and GL, each
# bare and under the validation wrapper: every run must exit 0 (every line understood, every call
# accepted, no error reported).
#   replay_render_recording.sh <bricklight-render> <bricklight-replay> <work-dir>
set -euo pipefail
render="$1" replay="$2" work="$3"
mkdir -p "$work"
"$render" --scene cornell --width 32 --height 32 --frames 2 --record "$work/cornell.jsonl" --out "$work/cornell.png"
export BRICKLIGHT_VK_VALIDATION=1
for backend in null vulkan gl; do
  for validate in "" --validate; do
    "$replay" "$work/cornell.jsonl" --backend "$backend" $validate
  done
done
