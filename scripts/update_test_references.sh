#!/usr/bin/env bash
# Traces the committed path-traced references anew (tests/references/, one file per recipe in
# tests/render/shared_references.cpp) on Vulkan, keeps the files that are current and removes those of no
# recipe. Run it when the test "committed references are current" fails, then commit tests/references/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/configure.sh" bricklight-render-tests
"$root/build/bin/bricklight-render-tests" "update the committed references"
