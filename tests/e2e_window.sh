#!/usr/bin/env bash
# End-to-end: the real editor window under Xvfb, driven with real input (xdotool)
# and the console on standard input. Usage: e2e_window.sh OROGEN TESTS_DIR
set -u
orogen=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-window-XXXXXX")
failures=0
passes=0
check() { if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi; }

for tool in Xvfb xdotool; do
    command -v $tool >/dev/null || { echo "FAIL: $tool is not installed (scripts/install-deps.sh installs it)"; exit 1; }
done

# A private X server on a free display number.
exec 5>"$work/display"
Xvfb -displayfd 5 -screen 0 1400x900x24 -nolisten tcp >"$work/xvfb.log" 2>&1 &
xvfb=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.1; done
export DISPLAY=":$(head -n 1 "$work/display")"

# Under the sanitizers: Mesa's GL driver leaks a few allocations that LeakSanitizer
# cannot even name (the driver is unloaded at exit); leaks in Orogen's own code are
# caught by the other tests, which run the same code without a GL driver.
if [ -n "${ASAN_OPTIONS:-}" ]; then export ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"; fi

mkfifo "$work/stdin"
"$orogen" <"$work/stdin" >"$work/out" 2>"$work/err" &
app=$!
exec 3>"$work/stdin" # keep the console's input open

cleanup() {
    exec 3>&-
    kill $app 2>/dev/null
    kill $xvfb 2>/dev/null
    wait 2>/dev/null
    rm -rf "$work"
}
trap cleanup EXIT

wid=$(timeout 30 xdotool search --sync --name '^Orogen' | head -n 1)
[ -n "$wid" ]; check "the editor window opens" $?
[ -n "$wid" ] || { cat "$work/err"; echo "$passes passed, $failures failed"; exit 1; }

title() { xdotool getwindowname "$wid"; }
wait_title() { # pattern: waits up to 30 s for the title to match
    for _ in $(seq 300); do title | grep -q -- "$1" && return 0; sleep 0.1; done
    return 1
}
field() { title | sed -n "s/.*$1.*/\\1/p"; }

wait_title "pending 0$"; check "every tile of the first view arrives (title says pending 0)" $?
cx0=$(field 'centre (\([-0-9.]*\), .*')
mpp0=$(field ' - \([0-9.]*\) m\/px.*')
[ "$cx0" = "0.0" ] && [ "$mpp0" = "16.000" ]; check "default view: centre 0, 16 m/px ($cx0, $mpp0)" $?

# Drag 100 pixels left: the view moves 100 px * 16 m/px = 1600 m east.
xdotool mousemove --window "$wid" 600 400 mousedown 1 mousemove --window "$wid" 550 400 \
    mousemove --window "$wid" 500 400 mouseup 1
wait_title "centre (1600.0, 0.0)"; check "left-drag pans the map ($(title))" $?

# One wheel notch up zooms in by 0.8 about the cursor.
xdotool mousemove --window "$wid" 640 400 click 4
wait_title " - 12.800 m/px"; check "the wheel zooms" $?

# The console on standard input runs the command language and changes the world.
echo "seed 9; generate; params" >&3
for _ in $(seq 100); do grep -q '^seed = 9;$' "$work/out" && break; sleep 0.1; done
grep -q '^seed = 9;$' "$work/out"; check "console commands run while the window is open" $?
echo "frobnicate" >&3
for _ in $(seq 100); do grep -q "console:1: error: unknown command 'frobnicate'" "$work/err" && break; sleep 0.1; done
grep -q "console:1: error: unknown command 'frobnicate'" "$work/err"; check "console errors are reported and the window stays" $?
kill -0 $app 2>/dev/null; check "the editor survives a bad command" $?

echo "save $work/saved.world" >&3
for _ in $(seq 100); do [ -s "$work/saved.world" ] && break; sleep 0.1; done
[ -s "$work/saved.world" ]; check "save from the console" $?
echo "exit" >&3
status=1
for _ in $(seq 200); do kill -0 $app 2>/dev/null || break; sleep 0.1; done
if ! kill -0 $app 2>/dev/null; then wait $app; status=$?; fi
[ $status = 0 ]; check "exit closes the editor with status 0" $?
[ $status = 0 ] || tail -n 60 "$work/err"

echo "$passes passed, $failures failed"
[ $failures = 0 ]
