#!/usr/bin/env bash
# Cross-builds Bricklight for 64-bit Windows with MinGW-w64 (cmake/toolchains/windows-mingw64.cmake) into
# build-windows/, and installs its package into build-windows/prefix. Builds: the libraries, both backends,
# the conformance kit with its plain runner (bricklight-conformance-run), hello_rhi, bricklight-render (built-in
# scenes; PNG and Radiance HDR output), bricklight-bench, -replay and the forwarding-device example. Not built:
# the tests (Catch2), the viewer (GLFW), model and texture files (assimp, OpenImageIO): none is packaged for
# MinGW. Shaders are compiled by the host's bricklight-shaderc, built natively into build/ first.
#   scripts/build_windows.sh [BUILD_DIR [SHADERC]]   (defaults: build-windows; build/bin/bricklight-shaderc, built here)
# tests/windows/run.sh runs the result under Wine (ctest -L windows).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/build-windows}"
shaderc="${2:-}"
"$root/scripts/bootstrap.sh" --windows
if [ -z "$shaderc" ]; then
  "$root/scripts/configure.sh" bricklight-shaderc
  shaderc="$root/build/bin/bricklight-shaderc"
fi
if [ ! -f "$out/build.ninja" ]; then
  cmake -S "$root" -B "$out" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchains/windows-mingw64.cmake" \
    -DBRICKLIGHT_SHADERC="$shaderc" \
    -DBRICKLIGHT_TESTS=OFF -DBRICKLIGHT_OPENIMAGEIO=OFF
fi
cmake --build "$out" --parallel "$(nproc)"
rm -rf "$out/prefix"
cmake --install "$out" --prefix "$out/prefix" > /dev/null
echo "build_windows: Windows programs in $out/bin, the package in $out/prefix"
