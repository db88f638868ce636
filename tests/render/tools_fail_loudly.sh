#!/usr/bin/env bash
# bricklight-compare and bricklight-bench on hostile input (issue 35): each case fails with the documented exit
# status and a message naming the problem, within a time bound, never by a signal; and no file is left where a
# run failed.
#   tools_fail_loudly.sh COMPARE BENCH WORK_DIR
set -u
compare="$1" bench="$2" work="$3"
rm -rf "$work" && mkdir -p "$work"
failures=0
expect() {  # expect <exit status> <message regex> <command...>
  local want="$1" pattern="$2"
  shift 2
  local log rc
  log=$(timeout 60 "$@" 2>&1); rc=$?
  if [ $rc -ne "$want" ] || ! grep -Eq -e "$pattern" <<<"$log"; then
    echo "FAIL: $* -> exit $rc (expected $want), output: $log (expected /$pattern/)"
    failures=$((failures + 1))
  else
    echo "ok: $* -> exit $rc"
  fi
}
python3 - "$work" <<'PY'
import struct, sys, zlib
work = sys.argv[1]
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
def png(path, w, h):
    ihdr = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"")) + chunk(b"IEND", b""))
# A whole PNG of 65 bytes (header, an empty image stream, the end) that claims 10^10 pixels.
png(work + "/huge_header.png", 100000, 100000)
def pfm(path, value, w=8, h=8):  # a float image: every channel of every pixel `value`
    open(path, "wb").write(b"PF\n%d %d\n-1.0\n" % (w, h) + struct.pack("<f", value) * (3 * w * h))
pfm(work + "/nan.pfm", float("nan"))
pfm(work + "/ones.pfm", 1.0)
pfm(work + "/ones_small.pfm", 1.0, 4, 4)
pfm(work + "/inf.pfm", float("inf"))
PY
# bricklight-compare: 0 within, 1 not (over --max-relmse, unreadable, sizes, not finite), 2 usage.
expect 0 "relMSE 0 " "$compare" "$work/ones.pfm" "$work/ones.pfm"
expect 1 "100000 x 100000 pixels, over the limit of 67108864" "$compare" "$work/huge_header.png" "$work/ones.pfm"
expect 1 "holds 192 values that are not finite .* of 192" "$compare" "$work/nan.pfm" "$work/ones.pfm"
expect 1 "holds 192 values that are not finite" "$compare" "$work/ones.pfm" "$work/inf.pfm" --max-relmse 1
expect 1 "sizes differ: 8x8 vs 4x4" "$compare" "$work/ones.pfm" "$work/ones_small.pfm"
expect 1 "not a regular file" "$compare" /dev/zero "$work/ones.pfm"
mkfifo "$work/fifo"
expect 1 "not a regular file" "$compare" "$work/fifo" "$work/ones.pfm"
expect 1 "missing\.png" "$compare" "$work/missing.png" "$work/ones.pfm"
expect 2 "usage" "$compare" "$work/ones.pfm"
expect 2 "--max-relmse expects a number >= 0" "$compare" "$work/ones.pfm" "$work/ones.pfm" --max-relmse nan
expect 2 "--max-relmse needs a value" "$compare" "$work/ones.pfm" "$work/ones.pfm" --max-relmse
expect 2 "unknown option '--fast'" "$compare" "$work/ones.pfm" "$work/ones.pfm" --fast
# bricklight-bench --json: checked before the run (a folder that is missing, a folder, a special file), exit 2.
expect 2 "--json: cannot write .*no/such/folder/r\.json" "$bench" sdf --scene cornell --frames 1 --width 16 --height 16 --json "$work/no/such/folder/r.json"
expect 2 "--json: cannot write .*it exists and is not a regular file" "$bench" sdf --scene cornell --frames 1 --width 16 --height 16 --json /dev/full
mkdir -p "$work/adir"
expect 2 "--json: cannot write .*adir" "$bench" sdf --scene cornell --frames 1 --width 16 --height 16 --json "$work/adir"
[ "$failures" -eq 0 ] && echo "tools fail loudly: every case as documented"
exit $((failures > 0))
