#!/usr/bin/env bash
# bricklight-render on bad input: each case must exit non-zero with a message that names the problem
# (and never crash); non-manifold and degenerate geometry must render. Usage: cli_rejects_bad_input.sh RENDER DATA_DIR OUT_DIR
set -u
render="$1"; data="$2"; out="$3"
mkdir -p "$out"
failures=0
expect_failure() {  # expected-message-regex, arguments...
  local pattern="$1"; shift
  local log rc
  log=$("$render" "$@" 2>&1); rc=$?
  if [ $rc -eq 0 ] || [ $rc -ge 128 ] || ! grep -Eq -e "$pattern" <<<"$log"; then
    echo "FAIL: bricklight-render $* -> exit $rc, output: $log (expected a failure matching /$pattern/)"
    failures=$((failures + 1))
  else
    echo "ok: $* -> exit $rc: $log"
  fi
}
common=(--reference --spp 1 --width 8 --height 8)
expect_failure "cannot load .*missing\.obj" "${common[@]}" --scene "$data/missing.obj" --out "$out/x.png"
expect_failure "cannot load .*unsupported\.xyz" "${common[@]}" --scene "$data/unsupported.xyz" --out "$out/x.png"
expect_failure "vertex 1 is not finite" "${common[@]}" --scene "$data/nan_vertex.obj" --out "$out/x.png"
expect_failure "out of range" "${common[@]}" --scene "$data/index_out_of_range.obj" --out "$out/x.png"
expect_failure "base colour texture .*nothere\.png' cannot be loaded" "${common[@]}" --scene "$data/missing_texture.obj" --out "$out/x.png"
expect_failure "unsupported output format" "${common[@]}" --scene cornell --out "$out/x.bmp"
expect_failure "--width expects a whole number in 1\.\.8192" "${common[@]}" --width 0
expect_failure "--spp expects" --reference --spp -3
expect_failure "unknown AOV 'shadows'" "${common[@]}" --aov shadows
expect_failure "--camera expects six numbers" "${common[@]}" --camera 1,2,3
expect_failure "--backend must be vulkan or gl" "${common[@]}" --backend metal
expect_failure "unknown option '--frobnicate'" --frobnicate
expect_failure "--gi must be sdf or none" --gi voxels
expect_failure "--gi-scale must be 100, 75, 50 or 25" --gi-scale 60
expect_failure "--gi-debug must be radiance-cache" --gi-debug everything
expect_failure "--gi-debug needs the fast path with GI" "${common[@]}" --gi-debug probes --out "$out/x.png"
log=$("$render" "${common[@]}" --scene "$data/non_manifold_degenerate.obj" --out "$out/ok.png" 2>&1); rc=$?
if [ $rc -ne 0 ]; then echo "FAIL: non-manifold/degenerate geometry: exit $rc: $log"; failures=$((failures + 1)); else echo "ok: non-manifold/degenerate geometry renders: $log"; fi
# Textures from a file and embedded in a binary glTF give the same albedo (Debian's assimp-testmodels).
models=/usr/share/assimp/models/glTF2
if [ -d "$models/BoxTextured-glTF" ]; then
  compare="$(dirname "$render")/bricklight-compare"
  "$render" --scene "$models/BoxTextured-glTF/BoxTextured.gltf" --width 32 --height 32 --out "$out/external.exr" --aov albedo >/dev/null &&
  "$render" --scene "$models/BoxTextured-glTF-Binary/BoxTextured.glb" --width 32 --height 32 --out "$out/embedded.exr" --aov albedo >/dev/null
  rc=$?
  if [ $rc -ne 0 ] || ! "$compare" "$out/embedded.albedo.exr" "$out/external.albedo.exr" --max-relmse 1e-9; then
    echo "FAIL: external and embedded textures differ (exit $rc)"; failures=$((failures + 1))
  else
    echo "ok: external and embedded textures give the same albedo"
  fi
fi
exit $failures
