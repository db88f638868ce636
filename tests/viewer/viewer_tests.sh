#!/usr/bin/env bash
# bricklight-viewer on one backend under its own Xvfb display (each ctest gets its own number, so parallel
# tests never share a display):
#   viewer_tests.sh VIEWER RENDER COMPARE BACKEND DISPLAY_NUMBER WORK_DIR
# 1. --frames 16 --screenshot matches bricklight-render's PNG of the same scene, camera, options and frame
#    count (relMSE < 1e-3; measured 3e-7: the same passes, the GPU's rounding of the display mapping), with
#    the Vulkan validation layer and our validation wrapper on (--validate) and silent (any message fails
#    the run).
# 2. GI off gives exactly the direct-light AOV of the same frame (relMSE < 1e-6).
# 3. Input through xdotool: a key switches the view, a click on the panel's GI checkbox turns GI off, the
#    screenshot key writes what is shown, a resize rebuilds the renderer and rendering goes on, Esc quits
#    with status 0. The screenshots change as they should: the direct view of one frame and the final
#    image with GI off of a later one differ only by the direct light's noise (relMSE < 0.02), GI on
#    brightens the final image (mean > 1.1x).
# 4. Frame time at 640x360 over 5 frames (printed, not asserted; a CPU driver's frame there takes about a second).
# 5. A refused camera: exit 1 and no screenshot; --screenshot-dir on a file or a missing folder refused.
# 6. Without a display: exit status 1 and the message, no crash.
set -uo pipefail
viewer=$1 render=$2 compare=$3 backend=$4 number=$5 work=$6
rm -rf "$work" && mkdir -p "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

Xvfb ":$number" -screen 0 1024x768x24 -nolisten tcp >"$work/xvfb.log" 2>&1 &
xvfb=$!
trap 'kill $viewer_pid 2>/dev/null; kill $xvfb 2>/dev/null; wait 2>/dev/null' EXIT
viewer_pid=""
for _ in $(seq 1 100); do [ -S "/tmp/.X11-unix/X$number" ] && break; sleep 0.1; done
[ -S "/tmp/.X11-unix/X$number" ] || fail "Xvfb :$number did not start: $(cat "$work/xvfb.log")"
export DISPLAY=":$number"

metric() {  # relMSE and the two means of A against B
  "$compare" "$1" "$2" | sed -E 's/^relMSE ([^ ]+).* mean ([^ ]+) vs ([^ ]+)( .*)?$/\1 \2 \3/'
}
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

# 1. The same image as bricklight-render.
common=(--backend "$backend" --width 96 --height 96 --frames 16)
"$viewer" "${common[@]}" --validate --screenshot "$work/viewer.png" --window 320x240 >"$work/viewer1.log" 2>&1 ||
  fail "viewer --frames 16 --screenshot: $(cat "$work/viewer1.log")"
"$render" "${common[@]}" --validate --out "$work/render.png" >"$work/render.log" 2>&1 || fail "bricklight-render: $(cat "$work/render.log")"
read -r relmse _ _ <<<"$(metric "$work/viewer.png" "$work/render.png")"
echo "viewer vs bricklight-render ($backend, 96x96, 16 frames): relMSE $relmse (bound 1e-3)"
below "$relmse" 1e-3 || fail "the viewer's screenshot differs from bricklight-render's image"

# Every panel section open for a few frames (their code runs; ImGui's checks and ours stay silent).
"$viewer" --backend "$backend" --width 64 --height 64 --frames 4 --open-panels --validate --scene dynamic >"$work/panels.log" 2>&1 ||
  fail "viewer --open-panels: $(cat "$work/panels.log")"

# 2. GI off is the direct light.
"$viewer" --backend "$backend" --width 96 --height 96 --frames 8 --gi none --screenshot "$work/gi-off.png" >"$work/v2.log" 2>&1 ||
  fail "viewer --gi none: $(cat "$work/v2.log")"
"$viewer" --backend "$backend" --width 96 --height 96 --frames 8 --view direct --screenshot "$work/direct.png" >"$work/v3.log" 2>&1 ||
  fail "viewer --view direct: $(cat "$work/v3.log")"
read -r relmse _ _ <<<"$(metric "$work/gi-off.png" "$work/direct.png")"
echo "GI off vs the direct AOV, same frame: relMSE $relmse (bound 1e-6)"
below "$relmse" 1e-6 || fail "GI off is not the direct light"

# 3. Keys, a click and a resize.
log="$work/interactive.log"
"$viewer" --backend "$backend" --window 200x150 --log --screenshot-dir "$work" >"$log" 2>&1 &
viewer_pid=$!
wait_for() {  # a line in the viewer's log, within 60 s
  for _ in $(seq 1 600); do grep -q -- "$1" "$log" && return 0; kill -0 $viewer_pid 2>/dev/null || break; sleep 0.1; done
  fail "no '$1' in the viewer's log: $(cat "$log")"
}
wait_for "first frame"
wid=$(xdotool search --sync --name "bricklight-viewer" | head -1)
[ -n "$wid" ] || fail "no viewer window"
xdotool windowfocus --sync "$wid"
xdotool key v && wait_for "view: direct"
xdotool key F12 && wait_for "bricklight-viewer-1.png (direct"
xdotool key b && wait_for "view: final"
# The panel sits at (8, 8); its first widget, the GI checkbox, is under the 19-pixel title bar.
xdotool mousemove --window "$wid" 25 44 click 1 && wait_for "gi: off"
wait_for "GI off"  # the renderer rebuilt without GI
xdotool key F12 && wait_for "bricklight-viewer-2.png (final"
xdotool key g && wait_for "gi: on"
sleep 3  # let GI gather some light
xdotool key F12 && wait_for "bricklight-viewer-3.png (final"
xdotool windowsize "$wid" 240 170 && wait_for "renderer 240x170"
xdotool key F12 && wait_for "bricklight-viewer-4.png (final"
xdotool key Escape
for _ in $(seq 1 100); do kill -0 $viewer_pid 2>/dev/null || break; sleep 0.1; done
wait $viewer_pid
status=$?
viewer_pid=""
[ $status -eq 0 ] || fail "the viewer exited with $status after Esc: $(cat "$log")"
read -r relmse direct_mean _ <<<"$(metric "$work/bricklight-viewer-2.png" "$work/bricklight-viewer-1.png")"
echo "final with GI off vs the direct view of an earlier frame: relMSE $relmse (bound 0.02)"
below "$relmse" 0.02 || fail "GI off does not show the direct light"
read -r _ gi_mean off_mean <<<"$(metric "$work/bricklight-viewer-3.png" "$work/bricklight-viewer-2.png")"
echo "final image mean with GI $gi_mean, without $off_mean"
below "$(awk -v a="$off_mean" 'BEGIN { print a * 1.1 }')" "$gi_mean" || fail "turning GI on did not brighten the image"
[ -s "$work/bricklight-viewer-4.png" ] || fail "no screenshot after the resize"

# 4. Frame time at 640x360 (lavapipe / llvmpipe; informative).
"$viewer" --backend "$backend" --window 640x360 --exit-after 5 --no-vsync --log >"$work/timing.log" 2>&1 ||
  fail "viewer at 640x360: $(cat "$work/timing.log")"
grep "frame time" "$work/timing.log" | sed "s/^/$backend 640x360: /"

# 5. Failures leave nothing behind: a camera the renderer refuses reports errors and writes no screenshot; a
# screenshot folder that is a file or missing is refused before the window opens.
"$viewer" --backend "$backend" --width 32 --height 32 --frames 2 --camera 1e38,1e38,1e38,0,0,0 --screenshot "$work/refused.png" \
  >"$work/refused.log" 2>&1
status=$?
[ $status -eq 1 ] || fail "a refused camera: exit status $status: $(cat "$work/refused.log")"
[ ! -e "$work/refused.png" ] || fail "a refused camera left a screenshot behind: $(cat "$work/refused.log")"
grep -q "no screenshot written" "$work/refused.log" || fail "a refused camera: $(cat "$work/refused.log")"
echo "refused camera: exit 1, no screenshot"
for dir in "$work/viewer.png" "$work/no/such/folder"; do
  "$viewer" --backend "$backend" --width 32 --height 32 --frames 1 --screenshot-dir "$dir" >"$work/dir.log" 2>&1
  status=$?
  [ $status -ne 0 ] && grep -q -- "--screenshot-dir '$dir'" "$work/dir.log" || fail "--screenshot-dir $dir: status $status: $(cat "$work/dir.log")"
done
echo "--screenshot-dir on a file or a missing folder: refused"

# 6. No display.
env -u DISPLAY "$viewer" --backend "$backend" --frames 1 >"$work/nodisplay.log" 2>&1
status=$?
[ $status -eq 1 ] || fail "without a display the exit status was $status: $(cat "$work/nodisplay.log")"
grep -q "no display" "$work/nodisplay.log" || fail "without a display: $(cat "$work/nodisplay.log")"
echo "no display: exit 1, '$(head -1 "$work/nodisplay.log")'"
echo "ok"
