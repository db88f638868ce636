#!/usr/bin/env bash
# The Windows build, cross-compiled and run under Wine (ctest -L windows; docs/integration.md, "Windows"):
#   1. scripts/build_windows.sh: the MinGW-w64 cross build and its installed package;
#   2. bricklight-conformance-run.exe on Vulkan (Wine's vulkan-1.dll -> lavapipe) and GL (WGL through Wine's
#      opengl32.dll -> llvmpipe): every case passed on both, and their outputs agree;
#   3. hello_rhi.exe on each backend writes the same PNG, byte for byte, as the Linux build's hello_rhi;
#   4. bricklight-render.exe --scene cornell on each backend against the Linux build's image of the same run:
#      relMSE < 1e-4 (the cross-backend bound of tests/render), means within 1 % (the .hdr file's RGBE rounding);
#   5. examples/integration built against the installed Windows package and run on each backend (it checks
#      its own output).
# Every Vulkan run has the host's VK_LAYER_KHRONOS_validation inserted (Wine's vulkan-1.dll lists no layers, so
# the host loader is asked through VK_INSTANCE_LAYERS; the layer then reports to stdout) and fails on any message.
#   tests/windows/run.sh [HOST_BUILD_DIR [WINDOWS_BUILD_DIR]]   (defaults: build, build-windows)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
host="$(realpath "${1:-$root/build}")"
win="$(realpath -m "${2:-$root/build-windows}")"

if [ -z "${BRICKLIGHT_UNDER_XVFB:-}" ]; then
  # The Linux programs the images are compared with, and the shader compiler the cross build uses.
  cmake --build "$host" --target bricklight-render bricklight-compare hello_rhi bricklight-shaderc > /dev/null
  "$root/scripts/build_windows.sh" "$win" "$host/bin/bricklight-shaderc"
  # Wine's Vulkan and GL need its X11 driver: one virtual display of our own for every run below.
  exec env BRICKLIGHT_UNDER_XVFB=1 xvfb-run -a -s "-screen 0 64x64x24" "$0" "$host" "$win"
fi

work="$(mktemp -d)"
export WINEPREFIX="$win/wine-prefix" WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml="  # no Mono/Gecko prompts
cleanup() { wineserver -k 2> /dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
# Runs a Windows program; its output (stdout and stderr) is kept in $work/<name>.log and shown on failure.
run() {
  local name="$1"; shift
  if ! VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation \
       VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT \
       timeout 600 wine "$@" > "$work/$name.log" 2>&1; then
    cat "$work/$name.log" >&2
    fail "$name exited with an error"
  fi
  if grep -E "Validation (Error|Warning)|VUID-" "$work/$name.log" >&2; then fail "$name: Vulkan validation messages"; fi
}
bin="$win/bin"
cd "$work"
wineboot -i > /dev/null 2>&1 || true

# The validation layer really runs under Wine (else the silence below would mean nothing).
VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation VK_LOADER_DEBUG=layer timeout 600 wine "$bin/hello_rhi.exe" --backend vulkan \
  --out "$work/probe.png" > "$work/probe.log" 2>&1 || { cat "$work/probe.log" >&2; fail "hello_rhi (layer probe)"; }
grep -q 'Insert instance layer "VK_LAYER_KHRONOS_validation"' "$work/probe.log" ||
  fail "the host's validation layer was not inserted under Wine"
echo "windows: VK_LAYER_KHRONOS_validation inserted by the host loader under Wine"

run conformance "$bin/bricklight-conformance-run.exe" --backend both  # its exit code says every case passed
tail -n 1 "$work/conformance.log"

"$host/bin/hello_rhi" --backend vulkan --out "$work/hello_linux.png" > /dev/null
for backend in vulkan gl; do
  run "hello_$backend" "$bin/hello_rhi.exe" --backend "$backend" --out "hello_$backend.png"
  cmp "$work/hello_linux.png" "$work/hello_$backend.png" || fail "hello_rhi on $backend: not the Linux build's PNG"
  echo "windows: hello_rhi on $backend: the Linux build's PNG, byte for byte"
done

render=(--scene cornell --width 64 --height 64 --frames 16)
for backend in vulkan gl; do
  run "render_$backend" "$bin/bricklight-render.exe" "${render[@]}" --backend "$backend" --out "cornell_$backend.hdr"
  "$host/bin/bricklight-render" "${render[@]}" --backend "$backend" --out "$work/linux_$backend.exr" > /dev/null
  line="$("$host/bin/bricklight-compare" "$work/linux_$backend.exr" "$work/cornell_$backend.hdr")" ||
    fail "bricklight-compare on $backend"
  echo "windows: bricklight-render on $backend vs Linux: $line"
  relmse="$(echo "$line" | sed -n 's/^relMSE \([^ ]*\) .*/\1/p')"
  means="$(echo "$line" | sed -n 's/.* mean \([^ ]*\) vs \([^ ]*\) .*/\1 \2/p')"
  awk -v r="$relmse" 'BEGIN { exit !(r != "" && r + 0 < 1e-4) }' || fail "render on $backend: relMSE $relmse (bound 1e-4)"
  awk -v a="${means% *}" -v b="${means#* }" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a > 0 && d <= 0.01 * a) }' ||
    fail "render on $backend: means $means differ by more than 1 %"
done

# What the Windows build lacks is refused with a message that says so, and nothing is written.
refused() {
  local name="$1" expect="$2"; shift 2
  if timeout 600 wine "$@" > "$work/$name.log" 2>&1; then fail "$name: exited 0"; fi
  grep -qF "$expect" "$work/$name.log" || { cat "$work/$name.log" >&2; fail "$name: no message '$expect'"; }
  echo "windows: $name refused: $(grep -F "$expect" "$work/$name.log" | head -n 1)"
}
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$work/triangle.obj"
refused model "this build reads no model files" "$bin/bricklight-render.exe" --scene triangle.obj --out model.png
refused exr "unsupported output format (use .png or .hdr)" "$bin/bricklight-render.exe" --scene cornell --out cornell.exr
[ ! -e "$work/model.png" ] && [ ! -e "$work/cornell.exr" ] || fail "a refused run wrote a file"

cmake -S "$root/examples/integration" -B "$work/integration" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchains/windows-mingw64.cmake" -DCMAKE_FIND_ROOT_PATH="$win/prefix" \
  -DBRICKLIGHT_SHADERC="$host/bin/bricklight-shaderc" > "$work/integration-configure.log" 2>&1 ||
  { cat "$work/integration-configure.log" >&2; fail "examples/integration does not configure against the Windows package"; }
cmake --build "$work/integration" > "$work/integration-build.log" 2>&1 ||
  { cat "$work/integration-build.log" >&2; fail "examples/integration does not build against the Windows package"; }
for backend in vulkan gl; do
  run "integration_$backend" "$work/integration/bricklight_integration.exe" --backend "$backend"
  grep -q "^PASS" "$work/integration_$backend.log" || { cat "$work/integration_$backend.log" >&2; fail "integration on $backend"; }
  echo "windows: examples/integration (installed Windows package) on $backend: PASS"
done
echo "windows: all passed"
