#!/usr/bin/env bash
# Runs the whole test suite: the conformance kit on Vulkan (lavapipe, validation layer on) and on
# OpenGL 4.5 (llvmpipe through OSMesa), the cross-backend comparison, and the validation tests.
# Extra arguments go to ctest (e.g. scripts/test.sh -L vulkan).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/configure.sh"
cd "$root/build"
# The Windows cross build under Wine (label "windows") runs only when asked for: scripts/test.sh -L windows.
# ctest excludes only what matches every -LE given, so a caller's -LE X becomes -LE 'windows|X'.
args=()
exclude="windows"
while [ $# -gt 0 ]; do
  case "$1" in
    -LE|--label-exclude) exclude="windows|$2"; shift 2 ;;
    *windows*) exclude=""; args+=("$1"); shift ;;
    *) args+=("$1"); shift ;;
  esac
done
if [ -n "$exclude" ]; then args+=(-LE "$exclude"); fi
ctest --output-on-failure --timeout 600 -j "$(nproc)" "${args[@]}"
