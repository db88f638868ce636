#!/usr/bin/env bash
# Installs every Debian 12 package Bricklight needs to build, test and run. Idempotent: when all are
# present it only checks and returns.
#   scripts/bootstrap.sh             # the Linux build and its tests
#   scripts/bootstrap.sh --windows   # and the Windows cross build and its runs under Wine (scripts/build_windows.sh)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev vulkan-tools mesa-vulkan-drivers vulkan-validationlayers
  glslang-dev glslang-tools spirv-tools
  libosmesa6-dev libegl-dev libgl-dev libegl-mesa0
  libglfw3-dev libglm-dev libimgui-dev
  xvfb xauth xdotool  # bricklight-viewer's tests: a virtual X display, input events (tests/viewer)
  libopenimageio-dev
  catch2 nlohmann-json3-dev libassimp-dev assimp-testmodels
  libstb-dev  # hello_rhi's PNG; image files of builds without OpenImageIO (Windows)
  clang  # the ASan + UBSan build and libFuzzer (scripts/test_sanitizers.sh)
  time  # GNU time: peak memory in tests/loading/cli_rejects_hostile_files.sh
)

if [ "${1:-}" = "--windows" ]; then
  packages+=(
    g++-mingw-w64-x86-64-posix  # the cross compilers (POSIX threads: std::thread)
    wine wine64                 # running the Windows programs (vulkan-1.dll -> lavapipe, opengl32.dll -> llvmpipe)
    libwine-dev                 # vulkan-1.dll's import library for MinGW
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "bootstrap: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
