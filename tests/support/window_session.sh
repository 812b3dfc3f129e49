# Sourced by the tests that drive the real editor window (e2e_window, e2e_gui,
# e2e_scenario, ...): their folders and counters (begin_window_test), the tools they
# need, a private X server, and the editor's environment.

# require_tools TOOL...: fails the test at once when one is missing.
require_tools() {
    for tool in "$@"; do
        command -v "$tool" >/dev/null ||
            { echo "FAIL: $tool is not installed (scripts/install-deps.sh installs it)"; exit 1; }
    done
}

# start_xvfb WxH: a private X server on a free display number ($xvfb is its pid).
start_xvfb() {
    exec 5>"$work/display"
    # -noreset: the server keeps its state (the pointer's place) when its last client goes,
    # so a pointer moved off the window before the editor starts stays there.
    Xvfb -displayfd 5 -screen 0 "$1x24" -nolisten tcp -noreset >"$work/xvfb.log" 2>&1 &
    xvfb=$!
    for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.1; done
    export DISPLAY=":$(head -n 1 "$work/display")"
}

# Under the sanitizers: Mesa's GL driver leaks a few allocations that LeakSanitizer
# cannot even name (the driver is unloaded at exit); leaks in Orogen's own code are
# caught by the other tests, which run the same code without a GL driver.
if [ -n "${ASAN_OPTIONS:-}" ]; then export ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"; fi
# The editor keeps its settings between runs, and user stamps in the data folder:
# keep both inside the test. Never-saved worlds' crash journals, and the offer to
# recover them at start, too.
keep_editor_state_in_work() {
    export XDG_CONFIG_HOME="$work/config"
    export XDG_DATA_HOME="$work/data"
    export XDG_STATE_HOME="$work/state"
    unset OROGEN_RECOVER_DIR
    unset OROGEN_STAMP_DIR
}
[ -n "${work:-}" ] && keep_editor_state_in_work

# check DESCRIPTION STATUS: counts a pass, or prints and counts a failure. Keep the status
# before a $(...) in DESCRIPTION, which sets $? itself: cond; ok=$?; check "... $(x)" $ok
check() { if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi; }

# begin_window_test NAME: the test's folder $work (removed at exit), the screenshots'
# folder $art, the counters, and a private HOME; the editor's state goes inside $work.
# Needs $orogen (the binary; $art sits beside it unless OROGEN_TEST_ARTIFACTS says).
begin_window_test() {
    work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-$1-XXXXXX")
    art=${OROGEN_TEST_ARTIFACTS:-$(dirname "$orogen")/test-artifacts}
    mkdir -p "$art"
    failures=0
    passes=0
    export HOME="$work/home"
    mkdir -p "$HOME"
    keep_editor_state_in_work
}

# end_window_test: the counts, and the test's status.
end_window_test() {
    echo "$passes passed, $failures failed"
    [ "$failures" = 0 ]
}

# open_editor COMMAND...: runs the editor with its console on $work/stdin (held open on
# fd 3) and its output in $work/out and $work/err ($app is its pid); the editor and the X
# server go at exit. $wid is its window; the test ends here if none shows.
open_editor() {
    [ -p "$work/stdin" ] || mkfifo "$work/stdin" # a restarted editor reuses it
    "$@" <"$work/stdin" >"$work/out" 2>"$work/err" &
    app=$!
    exec 3>"$work/stdin"
    trap '' PIPE # should the editor die, writes to its console fail instead of ending the test
    trap cleanup EXIT
    wid=$(timeout 30 xdotool search --sync --name '^Orogen' | head -n 1)
    [ -n "$wid" ]
    check "the editor window opens" $?
    [ -n "$wid" ] || { cat "$work/err"; echo "$passes passed, $failures failed"; exit 1; }
}

cleanup() {
    exec 3>&-
    kill $app 2>/dev/null
    kill $xvfb 2>/dev/null
    wait 2>/dev/null
    rm -rf "$work"
}
