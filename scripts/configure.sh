#!/usr/bin/env bash
# Shared by run.sh and test.sh: bootstrap, configure and build into build/.
#   scripts/configure.sh [TARGET...]   # the given targets only (run.sh: bricklight-render); none: everything
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/bootstrap.sh"
# A unity build: the sources of each target compiled in batches, which shares the headers' parsing (Catch2's
# above all) and builds everything in a little over half the time. A build tree configured by hand is left as it
# is; the package test still builds the library file by file, as an integrator's add_subdirectory() does.
if [ ! -f "$root/build/build.ninja" ]; then
  cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_UNITY_BUILD=ON
fi
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$root/build" --parallel "$(nproc)" "${targets[@]}"
