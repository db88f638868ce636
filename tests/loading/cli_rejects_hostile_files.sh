#!/usr/bin/env bash
# bricklight-render on the hostile files of issue 23 (written by bricklight-hostile-files): each run must
# exit non-zero below 128 (a refusal, not a crash or a kill) with the case's message, within 20 s, and
# stay under 1 GiB resident (GNU time, where installed). Valid models must still render.
#   cli_rejects_hostile_files.sh RENDER HOSTILE_FILES WORK_DIR
set -u
render="$1"; generate="$2"; work="$3"
mkdir -p "$work"
seconds_limit=20
memory_limit_kb=$((1024 * 1024))
gnu_time=""
if [ -x /usr/bin/time ] && /usr/bin/time -f %M true > /dev/null 2>&1; then gnu_time=/usr/bin/time; fi
failures=0
common=(--reference --spp 1 --width 8 --height 8 --out "$work/out.png")

# Runs bricklight-render with "$@"; sets rc, log, seconds and rss_kb (empty without GNU time).
run_render() {
  local start end
  start=$(date +%s.%N)
  if [ -n "$gnu_time" ]; then
    log=$(timeout -s KILL "$seconds_limit" "$gnu_time" -f "rss_kb=%M" -o "$work/time.txt" "$render" "$@" 2>&1); rc=$?
    rss_kb=$(sed -n 's/^rss_kb=//p' "$work/time.txt" 2>/dev/null)
  else
    log=$(timeout -s KILL "$seconds_limit" "$render" "$@" 2>&1); rc=$?
    rss_kb=""
  fi
  end=$(date +%s.%N)
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')
}

while IFS=$'\t' read -r name path pattern kind; do
  run_render "${common[@]}" --scene "$path"
  figures="exit $rc, ${seconds} s${rss_kb:+, ${rss_kb} KiB resident}"
  if [ $rc -eq 0 ] || [ $rc -ge 128 ] || ! grep -Eq -e "$pattern" <<<"$log"; then
    echo "FAIL: $name ($kind): $figures: $log (expected a refusal matching /$pattern/)"
    failures=$((failures + 1))
  elif [ -n "$rss_kb" ] && [ "$rss_kb" -gt "$memory_limit_kb" ]; then
    echo "FAIL: $name ($kind): $figures: over $memory_limit_kb KiB"
    failures=$((failures + 1))
  else
    echo "ok: $name ($kind): $figures: $log"
  fi
done < <("$generate" "$work/files")

# Valid models: Debian's assimp-testmodels (scripts/bootstrap.sh installs them).
models=/usr/share/assimp/models
for model in glTF2/BoxTextured-glTF/BoxTextured.gltf glTF2/BoxTextured-glTF-Binary/BoxTextured.glb OBJ/spider.obj PLY/Wuson.ply; do
  [ -f "$models/$model" ] || { echo "FAIL: $models/$model is missing (scripts/bootstrap.sh installs assimp-testmodels)"; failures=$((failures + 1)); continue; }
  run_render "${common[@]}" --scene "$models/$model"
  if [ $rc -ne 0 ]; then
    echo "FAIL: valid model $model: exit $rc: $log"; failures=$((failures + 1))
  else
    echo "ok: valid model $model renders (${seconds} s${rss_kb:+, ${rss_kb} KiB resident})"
  fi
done
echo "$failures failure(s)"
exit $((failures > 0))
