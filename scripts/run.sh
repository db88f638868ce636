#!/usr/bin/env bash
# The main job. Until the renderer exists it runs hello_rhi: a compute pass and a draw on the chosen
# backend (vulkan or gl), written to out/hello_rhi_<backend>.png.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/configure.sh"
mkdir -p "$root/out"
backends=("$@")
if [ ${#backends[@]} -eq 0 ]; then backends=(vulkan gl); fi
for b in "${backends[@]}"; do
  "$root/build/bin/hello_rhi" --backend "$b" --out "$root/out/hello_rhi_$b.png"
done
