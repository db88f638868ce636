#!/usr/bin/env bash
# bricklight-replay's command line and exit codes, on the null device (no GPU needed):
# 0 ok, 1 a call failed, 2 usage / unreadable file, 3 malformed recording, 5 over a budget; --help and --version
# exit 0.
#   replay_cli.sh <bricklight-replay> <regressions-dir> <work-dir>
set -uo pipefail
replay="$1" regressions="$2" work="$3"
mkdir -p "$work"
failures=0
expect() {  # expect <code> <what> <command...>
  local want="$1" what="$2"
  shift 2
  "$@" > "$work/out.txt" 2> "$work/err.txt"
  local got=$?
  if [ "$got" -ne "$want" ]; then
    echo "FAILED: $what: exit $got, expected $want"; cat "$work/out.txt" "$work/err.txt"
    failures=$((failures + 1))
  fi
}
printf '{"call":"endFrame"}\n{"call":"waitIdle"}\n' > "$work/ok.jsonl"
expect 0 "a valid recording" "$replay" "$work/ok.jsonl" --backend null --validate
grep -q "2 calls, 0 failed, 0 error(s) reported" "$work/out.txt" || { echo "FAILED: summary: $(cat "$work/out.txt")"; failures=$((failures + 1)); }
expect 0 "--help" "$replay" --help
expect 0 "--version" "$replay" --version
grep -q "^bricklight-replay [0-9]" "$work/out.txt" || { echo "FAILED: --version printed $(cat "$work/out.txt")"; failures=$((failures + 1)); }
expect 5 "a texture past the memory budget" "$replay" "$regressions/width_2pow31.jsonl" --backend null --validate
expect 1 "calls the wrapper refuses (no memory budget)" "$replay" "$regressions/width_2pow31.jsonl" --backend null --validate \
  --max-bytes 18446744073709551615
expect 2 "no file" "$replay" --backend null
expect 2 "a missing file" "$replay" "$work/missing.jsonl" --backend null
expect 2 "not a regular file" "$replay" /dev/zero --backend null
expect 2 "an unknown backend" "$replay" "$work/ok.jsonl" --backend metal
expect 2 "an unknown option" "$replay" "$work/ok.jsonl" --fast
printf '{"call":"endFrame"}\n{"call":"endFr\n' > "$work/truncated.jsonl"
expect 3 "a truncated line" "$replay" "$work/truncated.jsonl" --backend null
grep -q "recording line 2: not valid JSON" "$work/err.txt" || { echo "FAILED: no line in: $(cat "$work/err.txt")"; failures=$((failures + 1)); }
# The regression files name the replay fuzzer's stand-in shaders, which bricklight-replay does not embed.
expect 3 "a shader this program does not embed" "$replay" "$regressions/empty_groups.jsonl" --backend null
grep -q "recording line 1: createShader: blob: shader 'fuzz/probe.comp' is not embedded" "$work/err.txt" ||
  { echo "FAILED: $(cat "$work/err.txt")"; failures=$((failures + 1)); }
# Budgets: 100 open markers stop at the 33rd (exit 5, the line named); a raised budget still holds the devices' own
# kMaxMarkerDepth, and a budget that is not a positive number is a usage error.
for _ in $(seq 1 100); do printf '{"call":"beginMarker","label":"deep"}\n'; done > "$work/deep.jsonl"
expect 5 "markers past the budget" "$replay" "$work/deep.jsonl" --backend null --validate
grep -q "recording line 33: beginMarker: a marker opened inside 32 open ones, more than the budget of 32" "$work/err.txt" ||
  { echo "FAILED: $(cat "$work/err.txt")"; failures=$((failures + 1)); }
expect 5 "a lowered budget" "$replay" "$work/deep.jsonl" --backend null --max-marker-depth 4
grep -q "recording line 5: " "$work/err.txt" || { echo "FAILED: $(cat "$work/err.txt")"; failures=$((failures + 1)); }
expect 2 "a budget above kMaxMarkerDepth" "$replay" "$work/deep.jsonl" --backend null --max-marker-depth 100
expect 2 "a budget of 0" "$replay" "$work/ok.jsonl" --backend null --max-bytes 0
expect 2 "a negative budget" "$replay" "$work/ok.jsonl" --backend null --max-vertices -5
expect 2 "a budget that is not a number" "$replay" "$work/ok.jsonl" --backend null --max-invocations lots
expect 0 "raised budgets" "$replay" "$work/ok.jsonl" --backend null --max-invocations 99999999999 --max-bytes 99999999999
[ "$failures" -eq 0 ] && echo "bricklight-replay command line: all exit codes as documented"
exit $((failures > 0))
