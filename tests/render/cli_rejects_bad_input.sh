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
expect_failure "--gi must be sdf, vxgi or none" --gi voxels
expect_failure "--gi-scale must be 100, 75, 50 or 25" --gi-scale 60
expect_failure "--gi-debug must be radiance-cache" --gi-debug everything
expect_failure "--gi-debug needs the fast path" "${common[@]}" --gi-debug probes --out "$out/x.png"
expect_failure "--gi-debug probes needs the SDF GI" --gi vxgi --gi-debug probes --out "$out/x.png"
expect_failure "--gi-debug vct-opacity needs voxel cone tracing" --gi-debug vct-opacity --out "$out/x.png"
expect_failure "--aov ao needs --reference" --aov ao --out "$out/x.png"
expect_failure "--vct-occlusion must be voxels or sdf" --vct-occlusion rays
expect_failure "--vct-voxel expects the finest voxel's size" --vct-voxel 0
expect_failure "--vct-voxel expects the finest voxel's size" --vct-voxel 0.1x
expect_failure "--gi-unseen must be vxgi, path or none" --gi-unseen sdf
# Two outputs on one file (the recording would replace the image), also through another spelling of the path.
expect_failure "--out and --record name the same file" "${common[@]}" --out "$out/same.png" --record "$out/same.png"
expect_failure "--out and --record name the same file" "${common[@]}" --out "$out/same.png" --record "$out/./same.png"
expect_failure "--aov direct and --record name the same file" "${common[@]}" --aov direct --out "$out/y.png" --record "$out/y.direct.exr"
expect_failure "--spp sets the path tracer's samples: it needs --reference" --spp 16 --width 8 --height 8 --out "$out/x.png"
# Sun shadows: bvh, shadowmap or hybrid, and the shadow maps' parameters in range.
expect_failure "--shadows must be bvh, shadowmap or hybrid \(got 'rays'\)" --shadows rays
expect_failure "--shadows needs a value" --shadows
expect_failure "--shadow-resolution expects a whole number in 64\.\.4096" --shadow-resolution 32
expect_failure "--shadow-resolution expects a whole number in 64\.\.4096" --shadow-resolution 1e3
expect_failure "--shadow-lambda expects a number in 0\.\.1" --shadow-lambda 1.5
expect_failure "--shadow-lambda expects a number in 0\.\.1" --shadow-lambda nan
expect_failure "--shadow-pcf expects a whole number in 0\.\.3" --shadow-pcf 4
expect_failure "--shadows shadowmap and hybrid need the fast path" --shadows hybrid --reference --out "$out/x.png"
# Reflections: gi or hybrid; hybrid needs the SDF GI, and its debug views need hybrid reflections.
expect_failure "--reflections must be gi or hybrid \(got 'ssr'\)" --reflections ssr
expect_failure "--reflections hybrid needs --gi sdf" --reflections hybrid --gi none --out "$out/x.png"
expect_failure "--reflections hybrid needs --gi sdf" --reflections hybrid --gi vxgi --out "$out/x.png"
expect_failure "--gi-debug reflection-rays needs hybrid reflections" --gi-debug reflection-rays --out "$out/x.png"
expect_failure "cornell-mirror:2': the floor's roughness must be a number in \[0, 1\]" --width 8 --height 8 --frames 1 --scene cornell-mirror:2 --out "$out/x.png"
expect_failure "voxel AO with the SDF GI is not supported" --width 16 --height 16 --frames 1 --gi sdf --ao vxao --out "$out/x.png"
# Numbers are read as numbers: a negative one cannot wrap around to a valid size.
expect_failure "--width expects a whole number in 1\.\.8192 \(got '-18446744073709551615'\)" --width -18446744073709551615
expect_failure "--height expects a whole number" --height 99999999999999999999999
# Output paths are checked before any work (exit 2: nothing was done).
expect_failure "cannot write '$out/no-such-folder/x.png'" "${common[@]}" --out "$out/no-such-folder/x.png"
expect_failure "cannot write '$out/x.png.exr'.*not a regular file|unsupported output format" "${common[@]}" --out "$out"
expect_failure "unsupported output format" "${common[@]}" --aov normal --out "$out/x.tga"
# Work beyond a device limit is refused before rendering, naming the limit.
expect_failure "maxStorageBufferRange" --reference --spp 1 --width 1200 --height 1200 --out "$out/x.png"
# Triangles at the ends of the float range: no crash (the BVH), a clear refusal on both paths.
expect_failure "camera needs eye != at" "${common[@]}" --scene "$data/huge_coordinates.obj" --out "$out/x.png"
expect_failure "finestVoxelSize must be a positive finite number" --width 8 --height 8 --frames 1 --scene "$data/huge_coordinates.obj" --out "$out/x.png"
# Exit codes: usage errors 2, failed renders 1.
"$render" --width 0 > /dev/null 2>&1; rc=$?
if [ $rc -ne 2 ]; then echo "FAIL: a usage error exits $rc, not 2"; failures=$((failures + 1)); else echo "ok: usage error -> 2"; fi
"$render" "${common[@]}" --scene "$data/missing.obj" --out "$out/x.png" > /dev/null 2>&1; rc=$?
if [ $rc -ne 1 ]; then echo "FAIL: a failed render exits $rc, not 1"; failures=$((failures + 1)); else echo "ok: failed render -> 1"; fi
# --help and --version succeed.
if "$render" --help | grep -q "usage: bricklight-render" && "$render" --version | grep -Eq "^bricklight-render [0-9]+\.[0-9]+\.[0-9]+$"; then
  echo "ok: --help, --version"
else
  echo "FAIL: --help or --version"; failures=$((failures + 1))
fi
# A write that fails (a file-size limit stands in for a full disk) is an error and keeps the old image whole.
printf 'old image' > "$out/keep.exr"
log=$( (trap '' XFSZ; ulimit -f 1; "$render" --width 64 --height 64 --frames 1 --gi none --out "$out/keep.exr") 2>&1); rc=$?
if [ $rc -ne 1 ] || ! grep -q "cannot write '$out/keep.exr'" <<<"$log" || [ "$(cat "$out/keep.exr")" != "old image" ] ||
   ls -A "$out" | grep -q '\.tmp'; then
  echo "FAIL: a failed write: exit $rc, output: $log, old file: $(head -c 20 "$out/keep.exr")"; failures=$((failures + 1))
else
  echo "ok: a failed write exits 1 and leaves the old file: $log"
fi
log=$("$render" "${common[@]}" --scene "$data/non_manifold_degenerate.obj" --out "$out/ok.png" 2>&1); rc=$?
if [ $rc -ne 0 ]; then echo "FAIL: non-manifold/degenerate geometry: exit $rc: $log"; failures=$((failures + 1)); else echo "ok: non-manifold/degenerate geometry renders: $log"; fi
# --aov and --gi-debug take a list as the usage line shows them (or the flag repeated).
rm -f "$out"/list.*
log=$("$render" "${common[@]}" --aov direct indirect-diffuse --aov albedo --out "$out/list.png" 2>&1); rc=$?
if [ $rc -ne 0 ] || [ ! -f "$out/list.direct.exr" ] || [ ! -f "$out/list.indirect-diffuse.exr" ] || [ ! -f "$out/list.albedo.exr" ]; then
  echo "FAIL: --aov direct indirect-diffuse --aov albedo: exit $rc, files: $(ls "$out" | grep '^list' | tr '\n' ' '): $log"; failures=$((failures + 1))
else
  echo "ok: --aov takes a list"
fi
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
