#!/usr/bin/env bash
# Golden images of the whole editor window (UI and viewport, above the status bar, whose
# frame time varies) at two UI scales, with an RMSE tolerance, and the images kept for a
# reviewer to look at. The window is driven
# under Xvfb; window_screenshot renders once every tile in view has arrived.
# Usage: e2e_window_golden.sh OROGEN TESTS_DIR   (OROGEN_UPDATE_GOLDEN=1 rewrites the goldens)
set -u
orogen=$1
tests=$2
golden="$tests/data/golden"
rmse_tool="$(dirname "$orogen")/image_rmse"
shots="${OROGEN_TEST_ARTIFACTS:-$(dirname "$orogen")/test-artifacts}"
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-wgolden-XXXXXX")
failures=0
passes=0
check() { if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi; }
. "$tests/support/window_session.sh"
require_tools Xvfb xdotool convert
mkdir -p "$shots"

start_xvfb 1600x1000 # larger than the window ever is: the pointer can wait off it
trap 'kill $xvfb 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT

# One window at a UI scale: a fixed camera, the pointer off the window, the picture.
shoot() { # scale, output png
    mkfifo "$work/in-$1"
    # The pointer is off the window before it opens: the window never sees it enter.
    xdotool mousemove --sync 1599 999
    OROGEN_UI_SCALE=$1 "$orogen" <"$work/in-$1" >"$work/out-$1" 2>"$work/err-$1" &
    local app=$!
    exec 3>"$work/in-$1"
    local wid
    wid=$(timeout 30 xdotool search --sync --name '^Orogen' | head -n 1)
    xdotool windowsize --sync "$wid" 1000 640
    echo "camera 400 -50 600 30 -25" >&3
    echo "window_screenshot $work/full-$1.png" >&3
    echo "ui_widgets Status/" >&3
    for _ in $(seq 600); do grep -q '^Status/ ' "$work/out-$1" && break; sleep 0.1; done
    # The status bar shows the last frame's time: the golden is the window above it.
    local top
    top=$(awk '/^Status\/ / { print $3; exit }' "$work/out-$1")
    convert "$work/full-$1.png" -crop "1000x${top}+0+0" +repage "$2"
    echo "exit" >&3
    exec 3>&-
    wait $app
}

for scale in 1 1.5; do
    name="window_${scale}x.png"
    shoot "$scale" "$work/$name"
    [ -s "$work/$name" ]; rc=$?; check "the window at UI scale $scale is captured ($(tail -n 2 "$work/err-$scale" | tr '\n' ' '))" $rc
    cp "$work/$name" "$shots/$name" 2>/dev/null
    if [ -n "${OROGEN_UPDATE_GOLDEN:-}" ]; then
        cp "$work/$name" "$golden/$name" && echo "updated $golden/$name"
    fi
    "$rmse_tool" "$golden/$name" "$work/$name" --max 2.0 --diff "$shots/diff_$name" >"$work/rmse" 2>&1
    rc=$?
    if [ $rc != 0 ]; then # where they differ, for a reviewer who has only the log
        convert "$golden/$name" "$work/$name" -compose difference -composite -threshold 4% \
            -format 'pixels differing by more than 4%: %[fx:mean*w*h] in the box %@' info: \
            >>"$work/rmse" 2>&1
    fi
    check "the window at UI scale $scale matches its golden ($(cat "$work/rmse"))" $rc
done
echo "e2e_window_golden: $passes passed, $failures failed (images in $shots)"
[ $failures = 0 ]
