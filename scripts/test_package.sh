#!/usr/bin/env bash
# Uses a Bricklight build the way an integrator does, from its INSTALLED package:
#   1. cmake --install <build-dir> into <work-dir>/prefix;
#   2. configures and builds examples/integration (its own CMake project, find_package(bricklight)) against
#      that prefix, and runs it on every backend the package has (it checks its own output and fails on
#      any message);
#   3. compiles examples/integration/hand_link.cpp with g++ and no CMake, linking the installed archives
#      through the installed bricklight.pc, and runs it (SDF + GI shaders must be inside the archives);
#   4. builds tests/package/subdirectory, a parent project that add_subdirectory()s the source tree and
#      compiles its own shader with the trace API through bricklight_add_shaders(), and runs it; checks that
#      our build left the parent's output folders alone.
# Exit status 0 only if every step passes. tests/package registers this as a ctest test.
#
#   scripts/test_package.sh <build-dir> <work-dir>
set -euo pipefail

if [ $# -ne 2 ]; then
  echo "usage: $0 <build-dir> <work-dir>" >&2
  exit 2
fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "$1" && pwd)"
mkdir -p "$2"
work="$(cd "$2" && pwd)"
prefix="$work/prefix"
start=$SECONDS
step() { echo "== [$((SECONDS - start)) s] $*"; }

# A clean prefix every time: a file left by an earlier install must not hide one this install misses.
rm -rf "$prefix" "$work/integration-build" "$work/hand_link" "$work"/*.ppm "$work/subdirectory-build"

step "install $build -> $prefix"
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
backends=()
for b in vulkan gl; do
  if compgen -G "$prefix/lib*/libbricklight_$b.*" > /dev/null || compgen -G "$prefix/lib/*/libbricklight_$b.*" > /dev/null; then
    backends+=("$b")
  fi
done
if [ ${#backends[@]} -eq 0 ]; then
  echo "test_package: the installed package has no backend library" >&2
  exit 1
fi
echo "   backends in the package: ${backends[*]}"

step "configure + build examples/integration against the package (find_package, Ninja)"
cmake -S "$root/examples/integration" -B "$work/integration-build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
  > "$work/integration-configure.log" || { cat "$work/integration-configure.log"; exit 1; }
cmake --build "$work/integration-build" > "$work/integration-build.log" || { cat "$work/integration-build.log"; exit 1; }

for b in "${backends[@]}"; do
  step "run bricklight_integration --backend $b"
  "$work/integration-build/bricklight_integration" --backend "$b" --out "$work/integration-$b.ppm"
done

step "hand link: g++ + pkg-config, no CMake"
pc="$(find "$prefix" -name bricklight.pc -print -quit)"
if [ -z "$pc" ]; then
  echo "test_package: no bricklight.pc under $prefix" >&2
  exit 1
fi
PKG_CONFIG_PATH="$(dirname "$pc")${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
export PKG_CONFIG_PATH
libdir="$(pkg-config --variable=libdir bricklight)"
defines=()
for b in "${backends[@]}"; do defines+=("-DHAND_LINK_${b^^}"); done
# The rpath only matters for a shared build (BRICKLIGHT_SHARED=ON); static archives ignore it.
# shellcheck disable=SC2046
g++ -std=c++20 -O1 "${defines[@]}" "$root/examples/integration/hand_link.cpp" -o "$work/hand_link" \
  $(pkg-config --cflags --libs bricklight) -Wl,-rpath,"$libdir"
for b in "${backends[@]}"; do
  "$work/hand_link" --backend "$b"
done

step "add_subdirectory: a parent project with its own trace-API shader (GL backend only, null device)"
# Unoptimized (-O0, no debug information): the check runs on a null device, and what this build is for, every
# library source compiled alone with the parent's flags, costs a fifth less time than at -O3.
cmake -S "$root/tests/package/subdirectory" -B "$work/subdirectory-build" -G Ninja -DBRICKLIGHT_SOURCE_DIR="$root" \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS_DEBUG=-O0 -DCMAKE_CXX_FLAGS_DEBUG=-O0 > "$work/subdirectory-configure.log" || { cat "$work/subdirectory-configure.log"; exit 1; }
cmake --build "$work/subdirectory-build" --target subdirectory_check > "$work/subdirectory-build.log" ||
  { cat "$work/subdirectory-build.log"; exit 1; }
if [ -e "$work/subdirectory-build/bin" ] || [ -e "$work/subdirectory-build/lib" ]; then
  echo "test_package: the subproject set the parent's output folders (bin/ or lib/ in the parent's build)" >&2
  exit 1
fi
"$work/subdirectory-build/subdirectory_check"

step "package test passed (backends: ${backends[*]})"
