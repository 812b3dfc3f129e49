#!/usr/bin/env bash
# End-to-end in the real window (Xvfb, xdotool): what the world warns about while opening
# a file is shown in the window, not only on the terminal that started it. A parameter
# file with a line that does not read opens read-only: opened at start or through
# File > Open, the line's error and the read-only stay over the viewport (ui_messages
# lists them) until dismissed; a file only edited by hand (its seal no longer matches,
# every line reads) opens with a warning that passes.
# Usage: e2e_window_damaged_file.sh OROGEN TESTS_DIR
set -u
orogen=$1
. "$2/support/window_session.sh"
begin_window_test damaged-file
require_tools Xvfb xdotool
"$orogen" -c "new planet preset=moon; save $work/moon.planet" >/dev/null 2>&1
sed 's/^radius = .*/radius = nan;/' "$work/moon.planet" >"$work/nan.planet"
sed 's/^seed = .*/seed = 7;/' "$work/moon.planet" >"$work/edited.planet"
grep -q '^radius = nan;' "$work/nan.planet" && grep -q '^seed = 7;' "$work/edited.planet"
check "the damaged and the hand-edited files are made" $?
start_xvfb 1200x800
open_editor "$orogen" "$work/nan.planet"
. "$2/support/gui_helpers.sh"
# Waits up to 10 s for ui_messages to list a line matching pattern.
shown() {
    for _ in $(seq 40); do messages | grep -q -- "$1" && return 0; sleep 0.25; done
    return 1
}

dismiss_all() {
    for _ in 1 2 3 4 5 6; do widget "Notices/Dismiss" 4 >/dev/null || break; click "Notices/Dismiss"; done
}

# 1. Opened at start: the line's error and why it is read-only are shown.
shown "^Notices: .*nan.planet:[0-9]*: error: radius: .*got 'nan'"
ok=$?
check "opened at start, the bad line is shown in the window ($(messages | tr '\n' '|'))" $ok
shown "^Notices: .*nan.planet: error: the file is damaged: .*read-only"
check "and that it opened read-only, naming the file once" $?
widget "Notices/Dismiss" >/dev/null; check "with a Dismiss button" $?

# 2. Dismissed, then opened again through File > Open: shown again.
dismiss_all
messages | grep -q '^Notices: '; [ $? = 1 ]; ok=$?
check "Dismiss takes them away ($(messages | tr '\n' '|'))" $ok
click "Menu/File" && click "Menu/File/Open..." && fill "Open/Path" "$work/nan.planet" &&
    click "Open/Open"
shown "^Notices: .*nan.planet:[0-9]*: error: radius: "
check "opened through File > Open, the bad line is shown again" $?
dismiss_all

# 3. Edited by hand: every line reads; the warning is shown and passes by itself.
click "Menu/File" && click "Menu/File/Open..." && fill "Open/Path" "$work/edited.planet" &&
    click "Open/Open"
shown "^Notices: .*edited.planet: warning: it was changed after Orogen saved it"
ok=$?
check "a hand-edited file's warning is shown ($(messages | tr '\n' '|'))" $ok
title | grep -q "read-only"; [ $? = 1 ]; ok=$?
check "and it is not read-only ($(title))" $ok
gone=1
for _ in $(seq 60); do messages | grep -q '^Notices: '; [ $? = 1 ] && { gone=0; break; }; sleep 0.5; done
check "the warning passes without a click ($(messages | tr '\n' '|'))" $gone

end_window_test
