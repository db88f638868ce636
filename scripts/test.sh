#!/usr/bin/env bash
# Runs the whole test suite: the conformance kit on Vulkan (lavapipe, validation layer on) and on
# OpenGL 4.5 (llvmpipe through OSMesa), the cross-backend comparison, and the validation tests.
# Extra arguments go to ctest (e.g. scripts/test.sh -L vulkan).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/configure.sh"
cd "$root/build"
# The Windows cross build under Wine (label "windows") runs only when asked for: scripts/test.sh -L windows.
exclude=(-LE windows)
for a in "$@"; do
  case "$a" in *windows*) exclude=() ;; esac
done
ctest --output-on-failure --timeout 600 -j "$(nproc)" "${exclude[@]}" "$@"
