#!/usr/bin/env bash
# Our own programs, run as a new user first runs them (their default scene and options, at a small size so that
# a CPU driver keeps up), print no warning: a false alarm in our own tools teaches integrators to ignore a true
# one. Each run must exit 0 with nothing on stderr that says "warning".
#   default_runs_are_quiet.sh RENDER BENCH OUT_DIR
set -u
render="$1"; bench="$2"; out="$3"
mkdir -p "$out"
failures=0
quiet() {  # label, command...
  local label="$1"; shift
  local rc
  "$@" > "$out/stdout.txt" 2> "$out/stderr.txt"; rc=$?
  if [ $rc -ne 0 ] || grep -qi "warning" "$out/stderr.txt" "$out/stdout.txt"; then
    echo "FAIL: $label -> exit $rc; stderr: $(cat "$out/stderr.txt")"
    failures=$((failures + 1))
  else
    echo "ok: $label"
  fi
}
for backend in vulkan gl; do
  quiet "bricklight-render ($backend)" "$render" --backend "$backend" --width 64 --height 64 --frames 16 --out "$out/render-$backend.png"
done
# The GI benchmark on its own scene (the atrium) and G-buffer: GI's camera self-check must find the benchmark's
# depth where the distance field's surfaces are (it warned on 92 of 245 positions before the G-buffer's rays
# stopped within a tenth of the hit epsilon).
quiet "bricklight-bench gi" "$bench" gi --width 128 --height 72 --frames 4
exit $failures
